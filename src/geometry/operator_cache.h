/* On-disk cache of the geometry operators, keyed by the mesh content, the
 * parameters and the code that computes them, so a mesh seen before skips
 * the eigen solve.
 *
 * Folder: $XDG_CACHE_HOME/neuv, else $HOME/.cache/neuv (created on demand).
 * File ops-<key as 16 hex digits>.bin: magic "NEUVOPS\0", format version,
 * byte-order mark, key, sizes, the arrays of `operators`, then a CRC-32 of
 * everything before it. Written atomically (temp file + rename), so a
 * reader sees the old file or the new one, never half of one.
 *
 * Key (operator_cache_key): FNV-1a 64 over #V, #F, every field of
 * operators_params (k, n_hks), the format version, the digest of the
 * operators' code (operator_cache_code_hash), the positions and the
 * triangles, all as their bytes. Everything else the operators depend on
 * (the HKS times, derived from the eigenvalues; the eigen shift sigma, from
 * L and M; the solver tolerances, seeds and restarts, constants in
 * eigenbasis.c) is a function of these.
 *
 * Reading never trusts a file: one whose magic, version, byte order, key,
 * sizes, length, CRC or sparse structure is wrong, an empty one, a folder
 * in its place, one that cannot be opened, are all a miss: logged (info),
 * recomputed and rewritten. Only running out of memory is an error. */
#ifndef NEUV_GEOMETRY_OPERATOR_CACHE_H
#define NEUV_GEOMETRY_OPERATOR_CACHE_H

#include <stdint.h>

#include "geometry/operators.h"

#define OPERATOR_CACHE_VERSION 1

/* The digest of the code that computes the operators: 64 hex digits, a
 * SHA-256 that CMake computes at configure time (CMakeLists.txt,
 * NEUV_OPERATORS_CODE_FILES). */
const char *operator_cache_code_hash(void);

/* The key of m's operators under params p (NULL: defaults), as computed by
 * the code whose digest is code_hash. */
uint64_t operator_cache_key_for(const neuv_mesh *m, const operators_params *p, const char *code_hash);
/* operator_cache_key_for(m, p, operator_cache_code_hash()). */
uint64_t operator_cache_key(const neuv_mesh *m, const operators_params *p);

/* The cache folder, created if missing. Outputs: *dir (caller frees).
 * Fails (NEUV_ERR_IO) when no folder can be named or created. */
neuv_status operator_cache_dir(char **dir);

/* Writes ops to path atomically. */
neuv_status operator_cache_save(const char *path, uint64_t key, const operators *ops);

/* Reads path into ops (zeroed first), checking everything listed above
 * against key and the expected sizes (nv, k, n_hks).
 * Fails with NEUV_ERR_IO, message saying what was wrong, on any mismatch or
 * read failure; NEUV_ERR_NOMEM when out of memory. ops is left zeroed on
 * failure. */
neuv_status operator_cache_load(const char *path, uint64_t key, int nv, int k, int n_hks, operators *ops);

/* The operators of m: from the cache when a valid file exists, else computed
 * (and saved when use_cache is set). A cache file that cannot be used is
 * never an error, only an info message, and is replaced; a cache folder that
 * cannot be made or written, a debug message. Fails with what
 * operators_compute fails with, or NEUV_ERR_NOMEM when out of memory
 * anywhere, the cache included.
 * Inputs:  m, params (NULL for defaults), use_cache (0: compute, touch no file)
 * Outputs: ops; cache_path (may be NULL; set to the file path or NULL when
 *          use_cache is 0, caller frees); cache_hit (may be NULL) */
neuv_status operators_get(const neuv_mesh *m, const operators_params *params, int use_cache,
                          operators *ops, char **cache_path, int *cache_hit);

#endif
