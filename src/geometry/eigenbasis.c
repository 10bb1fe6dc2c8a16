/* Generalized Laplacian eigenpairs: ARPACK shift-invert on CHOLMOD, or dense
 * LAPACK for small meshes. See eigenbasis.h. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <arpack/arpack.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/rng.h"
#include "core/timer.h"
#include "core/union_find.h"
#include "geometry/cholesky.h"
#include "geometry/eigenbasis.h"

/* LAPACK (OpenBLAS exports it). */
void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda, double *w,
            double *work, const int *lwork, int *info);

enum { DENSE_MAX_VERTICES = 400, ARPACK_MAX_RESTARTS = 1000 };
static const uint64_t START_VECTOR_SEED = 0x6e65757665696773ULL;

/* Column-major n by k Z -> M-Gram matrix error max |Zᵀ M Z − I|. */
static double m_orth_error(int n, int k, const double *mass, const double *z)
{
    double err = 0.0;
    for (int a = 0; a < k; a++)
        for (int b = a; b < k; b++) {
            const double *za = z + (size_t)a * n, *zb = z + (size_t)b * n;
            double g = 0.0;
            for (int i = 0; i < n; i++) g += mass[i] * za[i] * zb[i];
            double e = fabs(g - (a == b ? 1.0 : 0.0));
            if (e > err) err = e;
        }
    return err;
}

/* Modified Gram-Schmidt in the M inner product, twice ("twice is enough"),
 * in eigenvalue order so each vector moves by the size of its error only. */
static void m_orthonormalize(int n, int k, const double *mass, double *z)
{
    for (int pass = 0; pass < 2; pass++)
        for (int a = 0; a < k; a++) {
            double *za = z + (size_t)a * n;
            for (int b = 0; b < a; b++) {
                const double *zb = z + (size_t)b * n;
                double g = 0.0;
                for (int i = 0; i < n; i++) g += mass[i] * za[i] * zb[i];
                for (int i = 0; i < n; i++) za[i] -= g * zb[i];
            }
            double nn = 0.0;
            for (int i = 0; i < n; i++) nn += mass[i] * za[i] * za[i];
            nn = sqrt(nn);
            if (nn > 0)
                for (int i = 0; i < n; i++) za[i] /= nn;
        }
}

/* Dense path: symmetric S = M^-1/2 L M^-1/2, S ψ = λ ψ, φ = M^-1/2 ψ. */
static neuv_status eigen_dense(const sparse_matrix *L, const double *mass, int k, double *evals, double *z)
{
    int n = L->rows;
    double *s = mem_calloc((size_t)n * n, sizeof *s);
    double *w = mem_alloc((size_t)n * sizeof *w);
    double *isq = mem_alloc((size_t)n * sizeof *isq);
    if (!s || !w || !isq) { mem_free(s); mem_free(w); mem_free(isq); return error_nomem("dense eigen problem"); }
    for (int i = 0; i < n; i++) isq[i] = 1.0 / sqrt(mass[i]);
    for (int r = 0; r < n; r++)
        for (int p = L->row_start[r]; p < L->row_start[r + 1]; p++)
            s[(size_t)L->col[p] * n + r] = isq[r] * L->val[p] * isq[L->col[p]];
    int lwork = -1, info = 0;
    double wq;
    dsyev_("V", "U", &n, s, &n, w, &wq, &lwork, &info);
    lwork = info == 0 ? (int)wq : 3 * n;
    double *work = mem_alloc((size_t)lwork * sizeof *work);
    if (!work) { mem_free(s); mem_free(w); mem_free(isq); return error_nomem("dense eigen workspace"); }
    dsyev_("V", "U", &n, s, &n, w, work, &lwork, &info);
    mem_free(work);
    if (info != 0) {
        mem_free(s); mem_free(w); mem_free(isq);
        return error_set(NEUV_ERR_INTERNAL, "dense eigen solver failed (LAPACK dsyev info %d)", info);
    }
    /* dsyev returns ascending eigenvalues with orthonormal eigenvector columns. */
    for (int a = 0; a < k; a++) {
        evals[a] = w[a];
        for (int i = 0; i < n; i++) z[(size_t)a * n + i] = isq[i] * s[(size_t)a * n + i];
    }
    mem_free(s); mem_free(w); mem_free(isq);
    return NEUV_OK;
}

/* y = M x */
static void apply_mass(int n, const double *mass, const double *x, double *y)
{
    for (int i = 0; i < n; i++) y[i] = mass[i] * x[i];
}

static neuv_status eigen_arpack(const sparse_matrix *L, const double *mass, int k, double *evals, double *z,
                                eigenbasis_info *info)
{
    int n = L->rows;
    /* Scale-aware shift: L_ii / M_i has units of 1/length², like λ. */
    double ratio = 0.0;
    for (int r = 0; r < n; r++) {
        double d = 0.0;
        for (int p = L->row_start[r]; p < L->row_start[r + 1]; p++)
            if (L->col[p] == r) d = L->val[p];
        ratio += fabs(d) / mass[r];
    }
    ratio /= n;
    double sigma = -1e-6 * (ratio > 0 ? ratio : 1.0);
    info->sigma = sigma;

    double t0 = now_seconds();
    sparse_matrix shifted;
    neuv_status s = sparse_add_diagonal(L, mass, -sigma, &shifted);
    if (s) return s;
    cholesky *chol = NULL;
    s = cholesky_factor(&shifted, &chol);
    sparse_free(&shifted);
    if (s) return s == NEUV_ERR_INPUT ? error_set(NEUV_ERR_INPUT, "Laplacian shifted by %g M is not positive definite", sigma) : s;
    info->factor_seconds = now_seconds() - t0;
    t0 = now_seconds();

    int ncv = 2 * k + 1 > 20 ? 2 * k + 1 : 20;
    if (ncv > n) ncv = n;
    int lworkl = ncv * (ncv + 8);
    double *resid = mem_alloc((size_t)n * sizeof *resid);
    double *v = mem_alloc((size_t)n * ncv * sizeof *v);
    double *workd = mem_alloc((size_t)3 * n * sizeof *workd);
    double *workl = mem_alloc((size_t)lworkl * sizeof *workl);
    double *tmp = mem_alloc((size_t)n * sizeof *tmp);
    int *select = mem_calloc((size_t)ncv, sizeof *select);
    double *d = mem_alloc((size_t)ncv * sizeof *d);
    if (!resid || !v || !workd || !workl || !tmp || !select || !d) {
        s = error_nomem("eigen solver workspace");
        goto done;
    }
    /* Deterministic start vector (info = 1 tells ARPACK to use resid). */
    rng g;
    rng_seed(&g, START_VECTOR_SEED);
    for (int i = 0; i < n; i++) resid[i] = rng_uniform(&g) - 0.5;

    int iparam[11] = {0}, ipntr[14] = {0};
    iparam[0] = 1;                    /* exact shifts */
    iparam[2] = ARPACK_MAX_RESTARTS;
    iparam[6] = 3;                    /* shift-invert mode */
    int ido = 0, ainfo = 1;
    /* Unit roundoff, what SciPy's eigsh passes for its default tol = 0. Debian's
     * ARPACK given 0 substitutes a smaller value and needs twice the restarts
     * for no accuracy that matters (residuals are ~1e-13 either way). */
    double tol = DBL_EPSILON / 2;
    for (;;) {
        dsaupd_c(&ido, "G", n, "LM", k, tol, resid, ncv, v, n, iparam, ipntr, workd, workl, lworkl, &ainfo);
        double top = now_seconds();
        if (ido == -1) {
            /* y = (L − σM)⁻¹ M x */
            apply_mass(n, mass, workd + ipntr[0] - 1, tmp);
            if ((s = cholesky_solve(chol, tmp, workd + ipntr[1] - 1, 1))) goto done;
            info->op_applies++;
        } else if (ido == 1) {
            /* M x is already at ipntr[2]. */
            if ((s = cholesky_solve(chol, workd + ipntr[2] - 1, workd + ipntr[1] - 1, 1))) goto done;
            info->op_applies++;
        } else if (ido == 2) {
            apply_mass(n, mass, workd + ipntr[0] - 1, workd + ipntr[1] - 1);
        } else {
            break;
        }
        info->op_seconds += now_seconds() - top;
    }
    info->restarts = iparam[2];
    if (ainfo < 0) {
        s = error_set(NEUV_ERR_INTERNAL, "eigen solver failed (ARPACK dsaupd info %d)", ainfo);
        goto done;
    }
    if (iparam[4] < k) {
        s = error_set(NEUV_ERR_INPUT, "eigen solver converged for %d of %d eigenpairs after %d restarts",
                      iparam[4], k, iparam[2]);
        goto done;
    }
    int einfo = 0;
    dseupd_c(1, "A", select, d, z, n, sigma, "G", n, "LM", k, tol, resid, ncv, v, n, iparam, ipntr, workd,
             workl, lworkl, &einfo);
    if (einfo != 0) {
        s = error_set(NEUV_ERR_INTERNAL, "eigen solver failed (ARPACK dseupd info %d)", einfo);
        goto done;
    }
    memcpy(evals, d, (size_t)k * sizeof *evals);
done:
    info->solve_seconds = now_seconds() - t0;
    cholesky_free(chol);
    mem_free(resid); mem_free(v); mem_free(workd); mem_free(workl); mem_free(tmp); mem_free(select); mem_free(d);
    return s;
}

/* Index sort of evals (insertion sort: k is small). */
static void sort_ascending(int k, const double *evals, int *order)
{
    for (int a = 0; a < k; a++) order[a] = a;
    for (int a = 1; a < k; a++) {
        int x = order[a], b = a - 1;
        while (b >= 0 && evals[order[b]] > evals[x]) { order[b + 1] = order[b]; b--; }
        order[b + 1] = x;
    }
}

/* Eigenpairs of one connected problem, unsorted: evals k, z #N by k column-major. */
static neuv_status eigen_connected(const sparse_matrix *L, const double *mass, int k, double *evals, double *z,
                                   eigenbasis_info *info)
{
    int n = L->rows;
    if (n <= DENSE_MAX_VERTICES || k >= n - 1) {
        double t0 = now_seconds();
        neuv_status s = eigen_dense(L, mass, k, evals, z);
        info->solve_seconds += now_seconds() - t0;
        return s;
    }
    info->dense = 0;
    eigenbasis_info one;
    memset(&one, 0, sizeof one);
    neuv_status s = eigen_arpack(L, mass, k, evals, z, &one);
    /* The shift reported is the one of the largest component (solved first). */
    if (info->sigma == 0) info->sigma = one.sigma;
    info->restarts += one.restarts;
    info->op_applies += one.op_applies;
    info->factor_seconds += one.factor_seconds;
    info->solve_seconds += one.solve_seconds;
    info->op_seconds += one.op_seconds;
    return s;
}

/* One candidate eigenpair of one component, for the global selection. */
typedef struct candidate {
    double lambda;
    int comp, index;
} candidate;

static int candidate_cmp(const void *a, const void *b)
{
    const candidate *x = a, *y = b;
    if (x->lambda != y->lambda) return x->lambda < y->lambda ? -1 : 1;
    if (x->comp != y->comp) return x->comp < y->comp ? -1 : 1;
    return (x->index > y->index) - (x->index < y->index);
}

/* Several components: L is block diagonal, so its eigenpairs are the union
 * of each block's. Solving each block separately is exact, where a single
 * Lanczos run on the whole would have to find a zero eigenvalue of
 * multiplicity #components from one start vector (in exact arithmetic it
 * finds one). Outputs evals k ascending and z #V by k column-major. */
static neuv_status eigen_components(const sparse_matrix *L, const double *mass, int k, int ncomp, const int *label,
                                    double *evals, double *z, eigenbasis_info *info)
{
    int n = L->rows;
    neuv_status s = NEUV_OK;
    int *count = mem_calloc((size_t)ncomp, sizeof *count), *local = mem_alloc((size_t)n * sizeof *local);
    int *order = mem_alloc((size_t)ncomp * sizeof *order), *kc = mem_calloc((size_t)ncomp, sizeof *kc);
    int **verts = mem_calloc((size_t)ncomp, sizeof *verts);
    double **cev = mem_calloc((size_t)ncomp, sizeof *cev), **cz = mem_calloc((size_t)ncomp, sizeof *cz);
    candidate *cand = NULL;
    if (!count || !local || !order || !kc || !verts || !cev || !cz) { s = error_nomem("eigen components"); goto done; }
    for (int i = 0; i < n; i++) local[i] = count[label[i]]++;
    for (int c = 0; c < ncomp; c++) {
        verts[c] = mem_alloc((size_t)count[c] * sizeof **verts);
        if (!verts[c]) { s = error_nomem("eigen components"); goto done; }
    }
    for (int i = 0; i < n; i++) verts[label[i]][local[i]] = i;
    /* Largest component first (ties by label), so the reported shift is its own. */
    for (int c = 0; c < ncomp; c++) order[c] = c;
    for (int a = 1; a < ncomp; a++) {
        int x = order[a], b = a - 1;
        while (b >= 0 && count[order[b]] < count[x]) { order[b + 1] = order[b]; b--; }
        order[b + 1] = x;
    }
    size_t ncand = 0;
    for (int q = 0; q < ncomp && !s; q++) {
        int c = order[q], nc = count[c];
        kc[c] = k < nc ? k : nc;
        triplet_list t;
        if ((s = triplets_init(&t, nc, nc, (size_t)nc * 7))) break;
        for (int a = 0; a < nc && !s; a++) {
            int r = verts[c][a];
            for (int p = L->row_start[r]; p < L->row_start[r + 1] && !s; p++)
                s = triplets_add(&t, a, local[L->col[p]], L->val[p]);
        }
        sparse_matrix sub;
        memset(&sub, 0, sizeof sub);
        double *smass = mem_alloc((size_t)nc * sizeof *smass);
        cev[c] = mem_alloc((size_t)kc[c] * sizeof **cev);
        cz[c] = mem_alloc((size_t)nc * kc[c] * sizeof **cz);
        if (!s && (!smass || !cev[c] || !cz[c])) s = error_nomem("eigen components");
        if (!s) s = sparse_from_triplets(&t, &sub);
        triplets_free(&t);
        if (!s) {
            for (int a = 0; a < nc; a++) smass[a] = mass[verts[c][a]];
            s = eigen_connected(&sub, smass, kc[c], cev[c], cz[c], info);
        }
        sparse_free(&sub);
        mem_free(smass);
        ncand += (size_t)kc[c];
    }
    if (s) goto done;
    cand = mem_alloc(ncand * sizeof *cand);
    if (!cand) { s = error_nomem("eigen components"); goto done; }
    size_t e = 0;
    for (int c = 0; c < ncomp; c++)
        for (int j = 0; j < kc[c]; j++) cand[e++] = (candidate){cev[c][j], c, j};
    qsort(cand, ncand, sizeof *cand, candidate_cmp);
    memset(z, 0, (size_t)n * k * sizeof *z);
    for (int a = 0; a < k; a++) {
        int c = cand[a].comp, j = cand[a].index;
        evals[a] = cand[a].lambda;
        for (int v = 0; v < count[c]; v++) z[(size_t)a * n + verts[c][v]] = cz[c][(size_t)j * count[c] + v];
    }
done:
    if (verts)
        for (int c = 0; c < ncomp; c++) mem_free(verts[c]);
    if (cev)
        for (int c = 0; c < ncomp; c++) mem_free(cev[c]);
    if (cz)
        for (int c = 0; c < ncomp; c++) mem_free(cz[c]);
    mem_free(count); mem_free(local); mem_free(order); mem_free(kc); mem_free(verts); mem_free(cev); mem_free(cz); mem_free(cand);
    return s;
}

neuv_status eigenbasis(const sparse_matrix *L, const double *mass, int k,
                       double *evals, double *evecs, eigenbasis_info *info)
{
    eigenbasis_info local;
    if (!info) info = &local;
    memset(info, 0, sizeof *info);
    info->dense = 1;
    int n = L->rows;
    if (n <= 0 || L->cols != n) return error_set(NEUV_ERR_INPUT, "eigenbasis: Laplacian is %d by %d", L->rows, L->cols);
    if (k < 1 || k > n) return error_set(NEUV_ERR_INPUT, "eigenbasis: asked for %d eigenpairs of a %d-vertex mesh", k, n);
    for (int i = 0; i < n; i++)
        if (!(mass[i] > 0) || !isfinite(mass[i]))
            return error_set(NEUV_ERR_INPUT, "vertex %d has zero area (no non-degenerate face uses it)", i);

    /* Connected components of L's sparsity pattern. */
    union_find uf;
    int *label = mem_alloc((size_t)n * sizeof *label);
    if (!label || uf_init(&uf, n) != 0) { mem_free(label); return error_nomem("eigen components"); }
    for (int r = 0; r < n; r++)
        for (int p = L->row_start[r]; p < L->row_start[r + 1]; p++) uf_union(&uf, r, L->col[p]);
    info->components = uf_labels(&uf, label);
    uf_free(&uf);
    if (info->components < 0) { mem_free(label); return error_nomem("eigen components"); }

    double *z = mem_alloc((size_t)n * k * sizeof *z);
    double *ev = mem_alloc((size_t)k * sizeof *ev);
    int *order = mem_alloc((size_t)k * sizeof *order);
    if (!z || !ev || !order) { mem_free(label); mem_free(z); mem_free(ev); mem_free(order); return error_nomem("eigenvectors"); }

    neuv_status s = info->components == 1 ? eigen_connected(L, mass, k, ev, z, info)
                                          : eigen_components(L, mass, k, info->components, label, ev, z, info);
    mem_free(label);
    if (s) { mem_free(z); mem_free(ev); mem_free(order); return s; }

    sort_ascending(k, ev, order);
    /* Reorder columns, then check M-orthonormality in the sorted order. */
    double *zs = mem_alloc((size_t)n * k * sizeof *zs);
    if (!zs) { mem_free(z); mem_free(ev); mem_free(order); return error_nomem("eigenvectors"); }
    for (int a = 0; a < k; a++) {
        evals[a] = ev[order[a]];
        memcpy(zs + (size_t)a * n, z + (size_t)order[a] * n, (size_t)n * sizeof *zs);
    }
    mem_free(z); mem_free(ev); mem_free(order);

    info->orth_error = m_orth_error(n, k, mass, zs);
    if (info->orth_error > 1e-10) {
        log_message(NEUV_LOG_DEBUG, "eigenbasis: M-orthonormality error %.3g, re-orthonormalizing", info->orth_error);
        m_orthonormalize(n, k, mass, zs);
        info->orth_error = m_orth_error(n, k, mass, zs);
    }
    /* Sign convention: the entry of largest magnitude is positive (first on ties). */
    for (int a = 0; a < k; a++) {
        double *za = zs + (size_t)a * n;
        int best = 0;
        for (int i = 1; i < n; i++)
            if (fabs(za[i]) > fabs(za[best])) best = i;
        if (za[best] < 0)
            for (int i = 0; i < n; i++) za[i] = -za[i];
    }
    for (int i = 0; i < n; i++)
        for (int a = 0; a < k; a++) evecs[(size_t)i * k + a] = zs[(size_t)a * n + i];
    mem_free(zs);
    return NEUV_OK;
}
