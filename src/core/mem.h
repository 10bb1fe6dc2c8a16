/* Every allocation neuv makes goes through these, so that an application's
 * allocator (neuv_set_allocator) and a test's failing one see all of them.
 * Same contracts as malloc, calloc, realloc, free and strdup, except that a
 * size of 0 allocates 1 byte (never NULL on success). Memory that another
 * library or the C library hands out (getline, CHOLMOD's cholmod_free'd
 * objects, Assimp's scenes) is released with that library's own function,
 * never mem_free. */
#ifndef NEUV_CORE_MEM_H
#define NEUV_CORE_MEM_H

#include <stddef.h>

void *mem_alloc(size_t size);
void *mem_calloc(size_t count, size_t size);
void *mem_realloc(void *ptr, size_t size);
void mem_free(void *ptr);
char *mem_strdup(const char *s);
/* How many allocations have failed on this thread so far. A library that
 * works around a failed allocation by itself (CHOLMOD's analysis tries
 * another ordering) is caught by comparing it before and after the call:
 * neuv reports every failure as NEUV_ERR_NOMEM rather than give a result
 * that differs from the one with enough memory. */
unsigned long mem_failures(void);

#endif
