/* 64-bit FNV-1a content hash (cache keys, not security). */
#ifndef NEUV_CORE_HASH_H
#define NEUV_CORE_HASH_H

#include <stddef.h>
#include <stdint.h>

#define HASH_INIT 0xcbf29ce484222325ULL
uint64_t hash_bytes(uint64_t h, const void *data, size_t n);
uint32_t crc32_bytes(uint32_t crc, const void *data, size_t n); /* start with crc = 0 */

#endif
