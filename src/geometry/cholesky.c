/* Sparse Cholesky through CHOLMOD (supernodal, fill-reducing ordering chosen
 * by CHOLMOD). One cholmod_common per factor keeps factors independent;
 * solves reuse per-factor workspace, so one factor must not be solved from
 * two threads at once. */
#include <stdlib.h>
#include <string.h>
#include <cholmod.h>

#include "core/error.h"
#include "core/mem.h"
#include "geometry/cholesky.h"

struct cholesky {
    cholmod_common common;
    cholmod_factor *factor;
    cholmod_dense *x, *y, *e; /* cholmod_solve2 workspace, reused across solves */
    int n;
};

/* The lower triangle of a (CSR with both triangles) as a CHOLMOD matrix with
 * stype = -1. Row r of a symmetric CSR is column r, so the CSC arrays are the
 * CSR arrays restricted to entries with col >= row. */
static cholmod_sparse *lower_triangle(const sparse_matrix *a, cholmod_common *cc)
{
    size_t nnz = 0;
    for (int r = 0; r < a->rows; r++)
        for (int p = a->row_start[r]; p < a->row_start[r + 1]; p++)
            if (a->col[p] >= r) nnz++;
    cholmod_sparse *s = cholmod_allocate_sparse((size_t)a->rows, (size_t)a->cols, nnz, 1, 1, -1, CHOLMOD_REAL, cc);
    if (!s) return NULL;
    int *cp = s->p, *ri = s->i;
    double *vx = s->x;
    size_t k = 0;
    for (int c = 0; c < a->rows; c++) {
        cp[c] = (int)k;
        for (int p = a->row_start[c]; p < a->row_start[c + 1]; p++)
            if (a->col[p] >= c) {
                ri[k] = a->col[p];
                vx[k] = a->val[p];
                k++;
            }
    }
    cp[a->rows] = (int)k;
    return s;
}

neuv_status cholesky_factor(const sparse_matrix *a, cholesky **out)
{
    *out = NULL;
    if (a->rows != a->cols || a->rows <= 0)
        return error_set(NEUV_ERR_INTERNAL, "cholesky: matrix is %d by %d, expected square and non-empty", a->rows, a->cols);
    cholesky *c = mem_calloc(1, sizeof *c);
    if (!c) return error_nomem("Cholesky factor");
    c->n = a->rows;
    cholmod_start(&c->common);
    c->common.supernodal = CHOLMOD_SUPERNODAL;
    c->common.print = 0;
    /* CHOLMOD's default error handler prints to stderr; the library reports through error_set instead. */
    c->common.error_handler = NULL;

    /* CHOLMOD's analysis tries another ordering when one runs out of memory,
     * and would give a different factor: any failed allocation (CHOLMOD's go
     * through core/mem) is reported instead. */
    unsigned long failures = mem_failures();
    cholmod_sparse *s = lower_triangle(a, &c->common);
    if (!s) { cholesky_free(c); return error_nomem("Cholesky input matrix"); }
    c->factor = cholmod_analyze(s, &c->common);
    if (c->factor && mem_failures() != failures) {
        cholmod_free_sparse(&s, &c->common);
        cholesky_free(c);
        return error_nomem("Cholesky analysis");
    }
    if (!c->factor) {
        cholmod_free_sparse(&s, &c->common);
        int st = c->common.status;
        cholesky_free(c);
        return st == CHOLMOD_OUT_OF_MEMORY ? error_nomem("Cholesky analysis")
                                           : error_set(NEUV_ERR_INTERNAL, "cholesky: analysis failed (CHOLMOD status %d)", st);
    }
    int ok = cholmod_factorize(s, c->factor, &c->common);
    cholmod_free_sparse(&s, &c->common);
    int st = c->common.status;
    if (mem_failures() != failures) st = CHOLMOD_OUT_OF_MEMORY;
    if (!ok || st == CHOLMOD_OUT_OF_MEMORY) {
        cholesky_free(c);
        return st == CHOLMOD_OUT_OF_MEMORY ? error_nomem("Cholesky factorization")
                                           : error_set(NEUV_ERR_INTERNAL, "cholesky: factorization failed (CHOLMOD status %d)", st);
    }
    if (st == CHOLMOD_NOT_POSDEF || c->factor->minor < (size_t)c->n) {
        size_t minor = c->factor->minor;
        cholesky_free(c);
        return error_set(NEUV_ERR_INPUT, "matrix is not positive definite (pivot %zu of %d)", minor, a->rows);
    }
    *out = c;
    return NEUV_OK;
}

neuv_status cholesky_solve(cholesky *c, const double *b, double *x, int nrhs)
{
    if (nrhs <= 0) return NEUV_OK;
    /* Wrap b without copying; CHOLMOD only reads it. */
    cholmod_dense bd;
    memset(&bd, 0, sizeof bd);
    bd.nrow = (size_t)c->n;
    bd.ncol = (size_t)nrhs;
    bd.nzmax = (size_t)c->n * (size_t)nrhs;
    bd.d = (size_t)c->n;
    bd.x = (void *)b;
    bd.xtype = CHOLMOD_REAL;
    bd.dtype = CHOLMOD_DOUBLE;
    /* CHOLMOD 3's supernodal solve allocates its workspace Y, then E, and only
     * then looks at the status, which E's allocation has reset: a failed Y
     * went on as a NULL pointer. Y is allocated here first (same shape, so the
     * solve reuses it) and its failure seen. */
    if (c->factor->is_super
        && !cholmod_ensure_dense(&c->y, (size_t)c->n, (size_t)nrhs, (size_t)c->n, c->factor->xtype, &c->common))
        return error_nomem("Cholesky solve");
    unsigned long failures = mem_failures();
    if (!cholmod_solve2(CHOLMOD_A, c->factor, &bd, NULL, &c->x, NULL, &c->y, &c->e, &c->common)
        || mem_failures() != failures)
        return c->common.status == CHOLMOD_OUT_OF_MEMORY || mem_failures() != failures ? error_nomem("Cholesky solve")
                                                         : error_set(NEUV_ERR_INTERNAL, "cholesky: solve failed (CHOLMOD status %d)", c->common.status);
    memcpy(x, c->x->x, (size_t)c->n * (size_t)nrhs * sizeof *x);
    return NEUV_OK;
}

void cholesky_free(cholesky *c)
{
    if (!c) return;
    cholmod_free_factor(&c->factor, &c->common);
    cholmod_free_dense(&c->x, &c->common);
    cholmod_free_dense(&c->y, &c->common);
    cholmod_free_dense(&c->e, &c->common);
    cholmod_finish(&c->common);
    mem_free(c);
}
