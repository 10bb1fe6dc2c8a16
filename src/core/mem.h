/* Every allocation neuv makes goes through these, so that an application's
 * allocator (and a test's failing one) sees all of them. Same contracts as
 * malloc, calloc, realloc, free and strdup. */
#ifndef NEUV_CORE_MEM_H
#define NEUV_CORE_MEM_H

#include <stddef.h>

void *mem_alloc(size_t size);
void *mem_calloc(size_t count, size_t size);
void *mem_realloc(void *ptr, size_t size);
void mem_free(void *ptr);
char *mem_strdup(const char *s);

#endif
