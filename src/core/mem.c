#include "core/mem.h"

#include <stdlib.h>
#include <string.h>

void *mem_alloc(size_t size) { return malloc(size ? size : 1); }
void *mem_calloc(size_t count, size_t size) { return calloc(count ? count : 1, size ? size : 1); }
void *mem_realloc(void *ptr, size_t size) { return realloc(ptr, size ? size : 1); }
void mem_free(void *ptr) { free(ptr); }

char *mem_strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = mem_alloc(n);
    if (d) memcpy(d, s, n);
    return d;
}
