/* The geometry operators every later stage needs, computed once per mesh
 * (DiffusionNet, Sharp et al. 2022, section 3): cotangent Laplacian, lumped
 * mass, the k smallest Laplacian eigenpairs, tangent frames, spatial
 * gradients, and heat kernel signature features.
 *
 * Lifetime: operators_compute (or operators_get, which goes through the disk
 * cache, operator_cache.h) fills a zeroed `operators`; operators_free
 * releases everything it owns. */
#ifndef NEUV_GEOMETRY_OPERATORS_H
#define NEUV_GEOMETRY_OPERATORS_H

#include "geometry/sparse_matrix.h"
#include "mesh/mesh.h"

#define OPERATORS_DEFAULT_K 64
#define OPERATORS_DEFAULT_HKS 16

/* Every field is part of the operator cache key (operator_cache.c, which
 * fails to compile when this struct grows until the key covers the new
 * field). */
typedef struct operators_params {
    int k;     /* eigenpairs wanted (clamped to #V) */
    int n_hks; /* heat kernel signature times */
} operators_params;

/* Wall-clock seconds per part; zero for parts not computed (cache hit). */
typedef struct operators_timings {
    double laplacian, factor, eigen, gradients, hks, cache_load, total;
} operators_timings;

typedef struct operators {
    int nv;
    int k;              /* eigenpairs actually computed: min(params k, #V) */
    int n_hks;
    sparse_matrix L;    /* #V by #V cotangent Laplacian (weak form, PSD) */
    double *mass;       /* #V lumped vertex areas */
    double *evals;      /* k, ascending */
    double *evecs;      /* #V by k, row-major, M-orthonormal columns */
    double *frames;     /* #V by 3 by 3: e1, e2, n per vertex */
    sparse_matrix grad_x, grad_y; /* #V by #V, gradient components along e1, e2 */
    double *hks;        /* #V by n_hks, area-normalized (heat_kernel_signature.h) */
    double *hks_times;  /* n_hks */
    double sigma;       /* eigen shift used (0 for the dense path; a cache hit restores it) */
    operators_timings seconds;
} operators;

/* Defaults: k = 64, n_hks = 16. */
operators_params operators_default_params(void);

/* Computes every operator for mesh m (reports progress, stage "operators").
 * Inputs:  m      cleaned mesh (every vertex used by a face of nonzero area)
 *          params NULL for defaults
 * Outputs: ops    filled (caller frees with operators_free)
 * Fails with NEUV_ERR_INPUT for an empty mesh, a vertex with zero area or
 * non-finite positions. */
neuv_status operators_compute(const neuv_mesh *m, const operators_params *params, operators *ops);
void operators_free(operators *ops);

#endif
