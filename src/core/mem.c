/* The allocator behind every allocation neuv makes: process-wide state, like
 * the callbacks of neuv_set_callbacks, and the one place the library calls the
 * C library's allocator. neuv_set_allocator changes it before any other neuv
 * call and never while one runs (its contract), so it is read without a lock,
 * from any thread. With no application allocator the C library's is called
 * directly, so calloc keeps its lazily zeroed pages. */
#include "core/mem.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <SuiteSparse_config.h>

#include "neuv/neuv.h"

static neuv_allocator hook; /* hook.alloc == NULL: the C library's */
static _Thread_local unsigned long failures;

static void *counted(void *p)
{
    if (!p) failures++;
    return p;
}

void *mem_alloc(size_t size)
{
    if (!size) size = 1;
    return counted(hook.alloc ? hook.alloc(hook.user, size) : malloc(size));
}

void *mem_calloc(size_t count, size_t size)
{
    if (!count) count = 1;
    if (!size) size = 1;
    if (!hook.alloc) return counted(calloc(count, size));
    if (size > SIZE_MAX / count) return counted(NULL);
    void *p = counted(hook.alloc(hook.user, count * size));
    if (p) memset(p, 0, count * size);
    return p;
}

void *mem_realloc(void *ptr, size_t size)
{
    if (!ptr) return mem_alloc(size);
    if (!size) size = 1;
    return counted(hook.alloc ? hook.realloc(hook.user, ptr, size) : realloc(ptr, size));
}

unsigned long mem_failures(void) { return failures; }

void mem_free(void *ptr)
{
    if (!ptr) return;
    if (hook.alloc) hook.free(hook.user, ptr);
    else free(ptr);
}

char *mem_strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = mem_alloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

void neuv_free(void *ptr) { mem_free(ptr); }

/* CHOLMOD allocates through SuiteSparse's process-wide functions; while an
 * application allocator is set they lead to it too, so that it sees the
 * factorizations' memory and a failure there is an ordinary CHOLMOD
 * out-of-memory status. SuiteSparse's own functions are kept to be put back. */
static void *suitesparse_malloc(size_t size) { return mem_alloc(size); }
static void *suitesparse_calloc(size_t count, size_t size) { return mem_calloc(count, size); }
static void *suitesparse_realloc(void *ptr, size_t size) { return mem_realloc(ptr, size); }
static void suitesparse_free(void *ptr) { mem_free(ptr); }

typedef struct suitesparse_functions {
    void *(*malloc_func)(size_t);
    void *(*calloc_func)(size_t, size_t);
    void *(*realloc_func)(void *, size_t);
    void (*free_func)(void *);
} suitesparse_functions;

static suitesparse_functions suitesparse_saved;
static int suitesparse_routed;

/* SuiteSparse 7 hides SuiteSparse_config behind get and set functions. */
#if SUITESPARSE_MAIN_VERSION >= 7
static suitesparse_functions suitesparse_get(void)
{
    suitesparse_functions f = {SuiteSparse_config_malloc_func_get(), SuiteSparse_config_calloc_func_get(),
                               SuiteSparse_config_realloc_func_get(), SuiteSparse_config_free_func_get()};
    return f;
}
static void suitesparse_set(suitesparse_functions f)
{
    SuiteSparse_config_malloc_func_set(f.malloc_func);
    SuiteSparse_config_calloc_func_set(f.calloc_func);
    SuiteSparse_config_realloc_func_set(f.realloc_func);
    SuiteSparse_config_free_func_set(f.free_func);
}
#else
static suitesparse_functions suitesparse_get(void)
{
    suitesparse_functions f = {SuiteSparse_config.malloc_func, SuiteSparse_config.calloc_func,
                               SuiteSparse_config.realloc_func, SuiteSparse_config.free_func};
    return f;
}
static void suitesparse_set(suitesparse_functions f)
{
    SuiteSparse_config.malloc_func = f.malloc_func;
    SuiteSparse_config.calloc_func = f.calloc_func;
    SuiteSparse_config.realloc_func = f.realloc_func;
    SuiteSparse_config.free_func = f.free_func;
}
#endif

void neuv_set_allocator(const neuv_allocator *a)
{
    if (a && a->alloc && a->realloc && a->free) {
        hook = *a;
        if (!suitesparse_routed) {
            suitesparse_saved = suitesparse_get();
            suitesparse_functions ours = {suitesparse_malloc, suitesparse_calloc, suitesparse_realloc, suitesparse_free};
            suitesparse_set(ours);
            suitesparse_routed = 1;
        }
    } else {
        memset(&hook, 0, sizeof hook);
        if (suitesparse_routed) {
            suitesparse_set(suitesparse_saved);
            suitesparse_routed = 0;
        }
    }
}
