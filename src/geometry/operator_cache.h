/* On-disk cache of the geometry operators, keyed by the mesh content and the
 * parameters, so a mesh seen before skips the eigen solve.
 *
 * Folder: $XDG_CACHE_HOME/neuv, else $HOME/.cache/neuv (created on demand).
 * File ops-<key as 16 hex digits>.bin: magic "NEUVOPS\0", format version,
 * byte-order mark, key, sizes, the arrays of `operators`, then a CRC-32 of
 * everything before it. Written atomically (temp file + rename). A file
 * whose magic, version, byte order, key, sizes, length, CRC or sparse
 * structure is wrong is never trusted: it is ignored (logged at debug level)
 * and rebuilt. */
#ifndef NEUV_GEOMETRY_OPERATOR_CACHE_H
#define NEUV_GEOMETRY_OPERATOR_CACHE_H

#include <stdint.h>

#include "geometry/operators.h"

#define OPERATOR_CACHE_VERSION 1

/* FNV-1a 64 of #V, #F, positions, faces, k, n_hks and the format version. */
uint64_t operator_cache_key(const neuv_mesh *m, const operators_params *p);

/* The cache folder, created if missing. Outputs: *dir (caller frees).
 * Fails (NEUV_ERR_IO) when no folder can be named or created. */
neuv_status operator_cache_dir(char **dir);

/* Writes ops to path atomically. */
neuv_status operator_cache_save(const char *path, uint64_t key, const operators *ops);

/* Reads path into ops (zeroed first), checking everything listed above
 * against key and the expected sizes (nv, k, n_hks).
 * Fails with NEUV_ERR_IO, message saying what was wrong, on any mismatch. */
neuv_status operator_cache_load(const char *path, uint64_t key, int nv, int k, int n_hks, operators *ops);

/* The operators of m: from the cache when a valid file exists, else computed
 * (and saved when use_cache is set). A cache that cannot be read or written
 * is never an error, only a debug message.
 * Inputs:  m, params (NULL for defaults), use_cache (0: compute, touch no file)
 * Outputs: ops; cache_path (may be NULL; set to the file path or NULL when
 *          use_cache is 0, caller frees); cache_hit (may be NULL) */
neuv_status operators_get(const neuv_mesh *m, const operators_params *params, int use_cache,
                          operators *ops, char **cache_path, int *cache_hit);

#endif
