/* Exact output-layer solves of the parameterization networks (param_output_solve.h). */
#include "models/param_output_solve.h"

#include <cblas.h>
#include <lapacke.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "losses/param_losses.h"

int param_head_size(const param_mlp *f)
{
    return 2 * (param_mlp_head_width(f) + 1);
}

/* Features of `m` at nv inputs (in: nv by in_dim), as the network computes
 * them (float): the last hidden layer (width), or with heads every hidden
 * layer (param_mlp_head_width). Computed HIDDEN_ROWS inputs at a time, so
 * that the network's intermediate tensors stay a fixed size whatever nv is
 * (each row is a function of its own input only: the same values). */
enum { HIDDEN_ROWS = 4096 };
static neuv_status hidden_at(const param_mlp *m, const param_solve_data *d, const float *in, int in_dim, int heads,
                             float *phi)
{
    nn_ctx *ctx = nn_ctx_create(0);
    if (!ctx) return error_nomem("output-layer solve");
    neuv_status s = NEUV_OK;
    for (int r0 = 0; r0 < d->nv && s == NEUV_OK; r0 += HIDDEN_ROWS) {
        int n = d->nv - r0 < HIDDEN_ROWS ? d->nv - r0 : HIDDEN_ROWS;
        nn_ctx_reset(ctx);
        nn_tensor *x = nn_view(ctx, n, in_dim, (float *)in + (size_t)r0 * in_dim);
        nn_tensor *psi = NULL;
        const int *row = NULL;
        if (d->psi_dim > 0 && d->psi_per_vertex) {
            psi = nn_view(ctx, n, d->psi_dim, (float *)d->psi + (size_t)r0 * d->psi_dim);
        } else if (d->psi_dim > 0) {
            psi = nn_view(ctx, d->n_charts, d->psi_dim, (float *)d->psi);
            row = d->vchart + r0;
        }
        nn_tensor *h = heads ? param_mlp_head_features(ctx, m, x, psi, row) : param_mlp_hidden(ctx, m, x, psi, row);
        if (!h) { s = nn_ctx_status(ctx); break; }
        memcpy(phi + (size_t)r0 * h->cols, h->data, sizeof(float) * (size_t)n * h->cols);
    }
    nn_ctx_free(ctx);
    return s;
}

/* Normal equations of a least-squares problem built block by block:
 * rows r (n wide) with constants c, minimizing Σ (r·θ + c)²; g = −Σ r c. */
typedef struct normal_eq {
    int n, cap, used;
    double *a, *g;     /* n by n (upper triangle), n */
    double *rows, *c;  /* cap by n, cap */
    /* Filled by vertex_eq_flush (cap 0): its scratch, VERTEX_EQ_CHUNK rows
     * of K = n / 2 features and their three products, the chunk's h values
     * and vertices. Each system has its own, so that blocks can be solved
     * side by side. */
    double *scratch, *hc;
    int *chunk;
} normal_eq;

enum { VERTEX_EQ_CHUNK = 128 };

static void normal_eq_free(normal_eq *q)
{
    mem_free(q->a); mem_free(q->g); mem_free(q->rows); mem_free(q->c);
    mem_free(q->scratch); mem_free(q->hc); mem_free(q->chunk);
    memset(q, 0, sizeof *q);
}

/* cap: rows buffered before they are added to A (0: A and g are filled
 * otherwise, by vertex_eq_flush, for n = 2 K). */
static neuv_status normal_eq_init(normal_eq *q, int n, int cap)
{
    memset(q, 0, sizeof *q);
    q->n = n;
    q->cap = cap;
    q->a = mem_calloc((size_t)n * n, sizeof(double));
    q->g = mem_calloc((size_t)n, sizeof(double));
    int ok = q->a && q->g;
    if (cap > 0) {
        q->rows = mem_calloc((size_t)q->cap * n, sizeof(double));
        q->c = mem_calloc((size_t)q->cap, sizeof(double));
        ok = ok && q->rows && q->c;
    } else {
        q->scratch = mem_alloc(sizeof(double) * VERTEX_EQ_CHUNK * (size_t)(n / 2) * 4);
        q->hc = mem_alloc(sizeof(double) * 2 * VERTEX_EQ_CHUNK);
        q->chunk = mem_alloc(sizeof(int) * VERTEX_EQ_CHUNK);
        ok = ok && q->scratch && q->hc && q->chunk;
    }
    if (!ok) { normal_eq_free(q); return error_nomem("output-layer solve"); }
    return NEUV_OK;
}

static void normal_eq_flush(normal_eq *q)
{
    if (q->used == 0) return;
    cblas_dsyrk(CblasRowMajor, CblasUpper, CblasTrans, q->n, q->used, 1.0, q->rows, q->n, 1.0, q->a, q->n);
    cblas_dgemv(CblasRowMajor, CblasTrans, q->used, q->n, -1.0, q->rows, q->n, q->c, 1, 1.0, q->g, 1);
    q->used = 0;
}

/* The next row to fill (zeroed); its constant goes to *c. */
static double *normal_eq_row(normal_eq *q, double **c)
{
    if (q->used == q->cap) normal_eq_flush(q);
    double *r = q->rows + (size_t)q->used * q->n;
    memset(r, 0, sizeof(double) * (size_t)q->n);
    *c = q->c + q->used;
    **c = 0;
    q->used++;
    return r;
}

/* Solves (A + ridge) X = B for nrhs right-hand sides b (n by nrhs,
 * row-major; NULL: q->g), in place; ridge = 1e-9 of the mean diagonal.
 * Returns 0, or -1 when the system is not positive definite. */
static int normal_eq_solve(normal_eq *q, int nrhs, double *b)
{
    normal_eq_flush(q);
    double tr = 0;
    for (int i = 0; i < q->n; i++) tr += q->a[(size_t)i * q->n + i];
    double ridge = 1e-9 * (tr > 0 ? tr / q->n : 1) + 1e-300;
    for (int i = 0; i < q->n; i++) q->a[(size_t)i * q->n + i] += ridge;
    if (!b) { b = q->g; nrhs = 1; }
    return LAPACKE_dposv(LAPACK_ROW_MAJOR, 'U', q->n, nrhs, q->a, q->n, b, nrhs) == 0 ? 0 : -1;
}

/* Faces and vertices of one block (all charts, or one). */
typedef struct block {
    const int *faces, *verts;
    int nf, nv;
} block;

/* The Gauss-Newton systems of the output-layer solves, kept in vertex space.
 * Every residual row is linear in the uv of at most three vertices: r·θ + c
 * with r = (Σ_v a_v φ̂_v, Σ_v b_v φ̂_v) (u weights, then v weights), φ̂_v =
 * (φ_v, 1). So Σ r rᵀ = [Φ̂ᵀ Muu Φ̂, Φ̂ᵀ Muv Φ̂; ·, Φ̂ᵀ Mvv Φ̂] with Muu =
 * Σ a aᵀ, Muv = Σ a bᵀ, Mvv = Σ b bᵀ sparse over the mesh's vertex pairs,
 * and −Σ r c = −(Φ̂ᵀ hu, Φ̂ᵀ hv), hu = Σ a c, hv = Σ b c. The rows' weights go
 * into these sparse sums (a few numbers per row); the dense products cost
 * about 6 V K² for a block of V vertices instead of the rows' 4 R K² (R ≈ 6 V
 * rows: two per face, two per vertex, the barrier's), K = H + 1 the features. */

typedef struct vertex_eq {
    int *start, *col;        /* CSR over vertices: each vertex's neighbours in its faces, itself included */
    int *face_pos;           /* nf by 9: the entry of (t[i], t[j]) */
    int *diag;               /* nv: the entry of (v, v) */
    double *muu, *muv, *mvv; /* per entry */
    double *hu, *hv;         /* nv */
    int K;
} vertex_eq;

static void vertex_eq_free(vertex_eq *e)
{
    mem_free(e->start); mem_free(e->col); mem_free(e->face_pos); mem_free(e->diag);
    mem_free(e->muu); mem_free(e->muv); mem_free(e->mvv); mem_free(e->hu); mem_free(e->hv);
    memset(e, 0, sizeof *e);
}

static int int_cmp(const void *p, const void *q)
{
    int a = *(const int *)p, b = *(const int *)q;
    return (a > b) - (a < b);
}

/* The vertex pairs that share a face, from nf faces `tri` over nv vertices,
 * for features of H numbers (φ̂ has K = H + 1). */
static neuv_status vertex_eq_init(vertex_eq *e, int nv, int nf, const int *tri, int H)
{
    memset(e, 0, sizeof *e);
    e->K = H + 1;
    int *fstart = mem_calloc((size_t)nv + 1, sizeof(int)), *flist = mem_alloc(sizeof(int) * (3 * (size_t)nf + 1));
    e->start = mem_calloc((size_t)nv + 1, sizeof(int));
    e->face_pos = mem_alloc(sizeof(int) * (9 * (size_t)nf + 1));
    e->diag = mem_alloc(sizeof(int) * ((size_t)nv + 1));
    e->hu = mem_calloc((size_t)nv + 1, sizeof(double));
    e->hv = mem_calloc((size_t)nv + 1, sizeof(double));
    neuv_status s = NEUV_OK;
    if (!fstart || !flist || !e->start || !e->face_pos || !e->diag || !e->hu || !e->hv)
        { s = error_nomem("output-layer solve"); goto done; }
    /* faces of each vertex */
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++) fstart[tri[3 * f + k] + 1]++;
    for (int v = 0; v < nv; v++) fstart[v + 1] += fstart[v];
    {
        int *fill = mem_alloc(sizeof(int) * ((size_t)nv + 1));
        if (!fill) { s = error_nomem("output-layer solve"); goto done; }
        memcpy(fill, fstart, sizeof(int) * (size_t)nv);
        for (int f = 0; f < nf; f++)
            for (int k = 0; k < 3; k++) flist[fill[tri[3 * f + k]]++] = f;
        mem_free(fill);
    }
    /* neighbours: at most 3 per incident face, sorted and unique */
    size_t cap = 0;
    for (int v = 0; v < nv; v++) cap += 3 * (size_t)(fstart[v + 1] - fstart[v]) + 1;
    e->col = mem_alloc(sizeof(int) * (cap + 1));
    if (!e->col) { s = error_nomem("output-layer solve"); goto done; }
    size_t nnz = 0;
    for (int v = 0; v < nv; v++) {
        size_t r0 = nnz;
        e->col[nnz++] = v;
        for (int k = fstart[v]; k < fstart[v + 1]; k++)
            for (int j = 0; j < 3; j++) e->col[nnz++] = tri[3 * flist[k] + j];
        qsort(e->col + r0, nnz - r0, sizeof(int), int_cmp);
        size_t w = r0;
        for (size_t k = r0; k < nnz; k++)
            if (k == r0 || e->col[k] != e->col[w - 1]) e->col[w++] = e->col[k];
        nnz = w;
        if (nnz > INT_MAX) { s = error_nomem("output-layer solve"); goto done; }
        e->start[v + 1] = (int)nnz;
    }
    e->muu = mem_calloc(nnz + 1, sizeof(double));
    e->muv = mem_calloc(nnz + 1, sizeof(double));
    e->mvv = mem_calloc(nnz + 1, sizeof(double));
    if (!e->muu || !e->muv || !e->mvv) { s = error_nomem("output-layer solve"); goto done; }
    for (int v = 0; v < nv; v++) {
        const int *c = e->col + e->start[v];
        e->diag[v] = e->start[v] + (int)((const int *)bsearch(&v, c, (size_t)(e->start[v + 1] - e->start[v]), sizeof(int), int_cmp) - c);
    }
    for (int f = 0; f < nf; f++)
        for (int i = 0; i < 3; i++) {
            int a = tri[3 * f + i];
            const int *c = e->col + e->start[a];
            size_t len = (size_t)(e->start[a + 1] - e->start[a]);
            for (int j = 0; j < 3; j++) {
                const int *hit = bsearch(&tri[3 * f + j], c, len, sizeof(int), int_cmp);
                e->face_pos[9 * (size_t)f + 3 * i + j] = e->start[a] + (int)(hit - c);
            }
        }
done:
    mem_free(fstart); mem_free(flist);
    if (s != NEUV_OK) vertex_eq_free(e);
    return s;
}

/* Empties the sums of the block's vertices (verts). */
static void vertex_eq_reset(vertex_eq *e, const int *verts, int n)
{
    for (int k = 0; k < n; k++) {
        int v = verts[k];
        size_t a = (size_t)e->start[v], len = (size_t)(e->start[v + 1] - e->start[v]);
        memset(e->muu + a, 0, len * sizeof(double));
        memset(e->muv + a, 0, len * sizeof(double));
        memset(e->mvv + a, 0, len * sizeof(double));
        e->hu[v] = e->hv[v] = 0;
    }
}

/* A residual row over face f's vertices t: u weights a, v weights b, constant c. */
static void vertex_eq_face_row(vertex_eq *e, int f, const int *t, const double a[3], const double b[3], double c)
{
    const int *pos = e->face_pos + 9 * (size_t)f;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            int p = pos[3 * i + j];
            e->muu[p] += a[i] * a[j];
            e->muv[p] += a[i] * b[j];
            e->mvv[p] += b[i] * b[j];
        }
        e->hu[t[i]] += a[i] * c;
        e->hv[t[i]] += b[i] * c;
    }
}

/* A residual row on one vertex's u (comp 0) or v (comp 1): weight a, constant c. */
static void vertex_eq_vertex_row(vertex_eq *e, int v, int comp, double a, double c)
{
    int p = e->diag[v];
    if (comp == 0) { e->muu[p] += a * a; e->hu[v] += a * c; }
    else { e->mvv[p] += a * a; e->hv[v] += a * c; }
}

/* The features a system is built over: each vertex's row of `phi` (H
 * numbers; the row of local[v] when `local` is set), with a constant 1
 * appended when `one`, so K = H + one numbers. */
typedef struct feature_rows {
    const float *phi;
    int H, one;
    const int *local;
} feature_rows;

static const float *feature_row(const feature_rows *fr, int v)
{
    return fr->phi + (size_t)(fr->local ? fr->local[v] : v) * fr->H;
}

/* The normal equations (A upper triangle, g) of the block from the sums over
 * its vertices, VERTEX_EQ_CHUNK vertices at a time, over the features fr.
 * hz (NULL, or 2 numbers per block vertex, in the order of verts) replaces
 * the sums' hu, hv. */
static void vertex_eq_flush(const vertex_eq *e, const feature_rows *fr, const double *hz, const int *verts, int n,
                            normal_eq *q)
{
    int H = fr->H, K = H + fr->one, N = q->n;
    memset(q->a, 0, sizeof(double) * (size_t)N * N);
    memset(q->g, 0, sizeof(double) * (size_t)N);
    double *C = q->scratch, *hc = q->hc;
    int *chunk = q->chunk;
    double *Puu = C + VERTEX_EQ_CHUNK * (size_t)K, *Puv = Puu + VERTEX_EQ_CHUNK * (size_t)K, *Pvv = Puv + VERTEX_EQ_CHUNK * (size_t)K;
    /* Vertices no row touches add nothing (on the faces split in four, the
     * edge midpoints carry rows only where the fold barrier is active). */
    for (int k = 0; k < n;) {
        int m = 0;
        for (; k < n && m < VERTEX_EQ_CHUNK; k++) {
            int v = verts[k], used = hz ? hz[2 * k] != 0 || hz[2 * k + 1] != 0 : e->hu[v] != 0 || e->hv[v] != 0;
            for (int p = e->start[v]; p < e->start[v + 1] && !used; p++)
                used = e->muu[p] != 0 || e->muv[p] != 0 || e->mvv[p] != 0;
            if (used) chunk[m++] = k;
        }
        if (m == 0) break;
        for (int r = 0; r < m; r++) {
            int v = verts[chunk[r]];
            double *c = C + (size_t)r * K, *pu = Puu + (size_t)r * K, *pm = Puv + (size_t)r * K, *pv = Pvv + (size_t)r * K;
            const float *fv = feature_row(fr, v);
            for (int i = 0; i < H; i++) c[i] = fv[i];
            if (fr->one) c[H] = 1;
            memset(pu, 0, sizeof(double) * (size_t)K);
            memset(pm, 0, sizeof(double) * (size_t)K);
            memset(pv, 0, sizeof(double) * (size_t)K);
            for (int p = e->start[v]; p < e->start[v + 1]; p++) {
                const float *fw = feature_row(fr, e->col[p]);
                double wu = e->muu[p], wm = e->muv[p], wv = e->mvv[p];
                for (int i = 0; i < H; i++) { pu[i] += wu * fw[i]; pm[i] += wm * fw[i]; pv[i] += wv * fw[i]; }
                if (fr->one) { pu[H] += wu; pm[H] += wm; pv[H] += wv; }
            }
            hc[r] = hz ? hz[2 * chunk[r]] : e->hu[v];
            hc[VERTEX_EQ_CHUNK + r] = hz ? hz[2 * chunk[r] + 1] : e->hv[v];
        }
        /* The three blocks of A are three independent products, each the
         * same single-threaded call on whichever thread runs it (the same
         * bits on any thread count); outside the heads' side-by-side solves
         * they share the threads. */
#pragma omp parallel for schedule(dynamic, 1) if (!omp_in_parallel() && omp_get_max_threads() > 1)
        for (int b = 0; b < 3; b++) {
            const double *P = b == 0 ? Puu : b == 1 ? Puv : Pvv;
            double *out = b == 0 ? q->a : b == 1 ? q->a + K : q->a + (size_t)K * N + K;
            cblas_dgemm(CblasRowMajor, CblasTrans, CblasNoTrans, K, K, m, 1.0, C, K, P, K, 1.0, out, N);
            if (b == 1) { /* this block's thread also takes g */
                cblas_dgemv(CblasRowMajor, CblasTrans, m, K, -1.0, C, K, hc, 1, 1.0, q->g, 1);
                cblas_dgemv(CblasRowMajor, CblasTrans, m, K, -1.0, C, K, hc + VERTEX_EQ_CHUNK, 1, 1.0, q->g + K, 1);
            }
        }
    }
}

/* z = φ̂ θ and uv = tanh(z) at the block's vertices (arrays indexed by vertex). */
static void map_block(const float *phi, int H, const double *theta, const block *b, double *z, double *uv)
{
    int K = H + 1;
    for (int k = 0; k < b->nv; k++) {
        int v = b->verts[k];
        const float *p = phi + (size_t)v * H;
        for (int j = 0; j < 2; j++) {
            const double *t = theta + (size_t)j * K;
            double acc = t[H];
            for (int i = 0; i < H; i++) acc += p[i] * t[i];
            z[2 * v + j] = acc;
            uv[2 * v + j] = tanh(acc);
        }
    }
}

/* Per vertex of a face: the weights of u_v in ∂u/∂x (wx) and ∂u/∂y (wy) in
 * the face's frame (J = [u1 − u0, u2 − u0] B). */
static void face_weights(const float *B, double wx[3], double wy[3])
{
    wx[0] = -(double)B[0] - B[2]; wx[1] = B[0]; wx[2] = B[2];
    wy[0] = -(double)B[1] - B[3]; wy[1] = B[1]; wy[2] = B[3];
}

/* The face's Jacobian in its frame from the vertices' uv. */
static void face_jacobian(const param_solve_data *d, int f, const double *uv, double wx[3], double wy[3], double J[4])
{
    const int *t = d->tri + 3 * f;
    face_weights(d->frame_inv + 4 * (size_t)f, wx, wy);
    J[0] = J[1] = J[2] = J[3] = 0;
    for (int q = 0; q < 3; q++) {
        J[0] += wx[q] * uv[2 * t[q]]; J[1] += wy[q] * uv[2 * t[q]];
        J[2] += wx[q] * uv[2 * t[q] + 1]; J[3] += wy[q] * uv[2 * t[q] + 1];
    }
}

/* The fold barrier's weight on face f. */
static double fold_weight_of(const param_solve_data *d, int f)
{
    return d->fold_w ? d->fold_w[f] : d->face_w[f];
}

/* Conformal energy of the block's faces and the count of faces whose UV
 * orientation disagrees with their chart's σ. */
static double block_energy(const param_solve_data *d, const block *b, const double *uv, const int *sigma,
                           const double *fold_s2, int *flips)
{
    double e = 0;
    int fl = 0;
    for (int k = 0; k < b->nf; k++) {
        int f = b->faces[k];
        double wx[3], wy[3], J[4];
        face_jacobian(d, f, uv, wx, wy, J);
        double sg = sigma[d->fchart[f]], r1 = J[0] - sg * J[3], r2 = J[1] + sg * J[2];
        e += d->face_w[f] * (r1 * r1 + r2 * r2);
        double det = sg * (J[0] * J[3] - J[1] * J[2]), fw = fold_weight_of(d, f);
        if (fold_s2 && d->fold_weight > 0) {
            double s2 = fold_s2[d->fchart[f]], gap = d->fold_eps * s2 - det;
            if (gap > 0 && s2 > 0) e += d->fold_weight * fw * gap * gap / s2;
        }
        if ((d->face_w[f] > 0 || fw > 0) && det <= 0) fl++;
    }
    if (flips) *flips = fl;
    return e;
}

static double block_anchor(const block *b, const double *uv, const double *uv0, const double *mv)
{
    double e = 0;
    for (int k = 0; k < b->nv; k++) {
        int v = b->verts[k];
        double du = uv[2 * v] - uv0[2 * v], dv = uv[2 * v + 1] - uv0[2 * v + 1];
        e += mv[v] * (du * du + dv * dv);
    }
    return e;
}

/* Gauss-Newton system at (z, uv): per face the two Cauchy-Riemann rows, per
 * vertex the two anchor rows, each linearized through tanh:
 * u_v ≈ s_v φ̂_v·θ_u + κ_v with s = 1 − uv², κ = uv − s z. */
/* The fold barrier's row for face f when it is active (σ det J < ε s̄²):
 * r = k (ε s̄² − σ det J) with k = sqrt(fold_weight w_f / s̄²), det J
 * linearized in the vertices' u, v and those through tanh as above. */
static void fold_row(const param_solve_data *d, int f, const double *z, const double *uv, double sg, double s2,
                     vertex_eq *q)
{
    const int *t = d->tri + 3 * f;
    double wx[3], wy[3], J[4];
    face_jacobian(d, f, uv, wx, wy, J);
    double det = sg * (J[0] * J[3] - J[1] * J[2]), gap = d->fold_eps * s2 - det;
    double fw = fold_weight_of(d, f);
    if (!(gap > 0) || !(s2 > 0) || !(fw > 0)) return;
    double k = sqrt(d->fold_weight * fw / s2), a[3], b[3];
    /* r(θ) ≈ gap − k σ ∇det·(θ − θ0): row −k σ ∇det, constant gap + k σ ∇det·θ0. */
    double cst = k * gap;
    for (int j = 0; j < 3; j++) {
        int v = t[j];
        double su = 1 - uv[2 * v] * uv[2 * v], sv = 1 - uv[2 * v + 1] * uv[2 * v + 1];
        double du = sg * (J[3] * wx[j] - J[2] * wy[j]) * su, dv = sg * (J[0] * wy[j] - J[1] * wx[j]) * sv;
        a[j] = -k * du;
        b[j] = -k * dv;
        cst += k * (du * z[2 * v] + dv * z[2 * v + 1]);
    }
    vertex_eq_face_row(q, f, t, a, b, cst);
}

static void anchor_rows(const block *b, const double *z, const double *uv, const double *uv0, const double *mv,
                        double anchor, vertex_eq *q);

static void gauss_newton_rows(const param_solve_data *d, const block *b, const double *z, const double *uv,
                              const double *uv0, const double *mv, const int *sigma, const double *fold_s2,
                              double anchor, vertex_eq *q)
{
    for (int k = 0; k < b->nf; k++) {
        int f = b->faces[k];
        double w = sqrt(d->face_w[f]), sg = sigma[d->fchart[f]];
        if (fold_s2 && d->fold_weight > 0) fold_row(d, f, z, uv, sg, fold_s2[d->fchart[f]], q);
        if (!(w > 0)) continue;
        const int *t = d->tri + 3 * f;
        double wx[3], wy[3], a1[3], a2[3], b1[3], b2[3], c1 = 0, c2 = 0;
        face_weights(d->frame_inv + 4 * (size_t)f, wx, wy);
        /* r1 = ∂u/∂x − σ ∂v/∂y, r2 = ∂u/∂y + σ ∂v/∂x */
        for (int j = 0; j < 3; j++) {
            int v = t[j];
            double su = 1 - uv[2 * v] * uv[2 * v], sv = 1 - uv[2 * v + 1] * uv[2 * v + 1];
            double ku = uv[2 * v] - su * z[2 * v], kv = uv[2 * v + 1] - sv * z[2 * v + 1];
            a1[j] = w * wx[j] * su; a2[j] = w * wy[j] * su; b1[j] = -sg * w * wy[j] * sv; b2[j] = sg * w * wx[j] * sv;
            c1 += w * wx[j] * ku - sg * w * wy[j] * kv;
            c2 += w * wy[j] * ku + sg * w * wx[j] * kv;
        }
        vertex_eq_face_row(q, f, t, a1, b1, c1);
        vertex_eq_face_row(q, f, t, a2, b2, c2);
    }
    anchor_rows(b, z, uv, uv0, mv, anchor, q);
}

/* The anchor's two rows per vertex, linearized through tanh. */
static void anchor_rows(const block *b, const double *z, const double *uv, const double *uv0, const double *mv,
                        double anchor, vertex_eq *q)
{
    for (int k = 0; k < b->nv; k++) {
        int v = b->verts[k];
        double w = sqrt(anchor * mv[v]);
        if (!(w > 0)) continue;
        for (int j = 0; j < 2; j++) {
            double s = 1 - uv[2 * v + j] * uv[2 * v + j], kap = uv[2 * v + j] - s * z[2 * v + j];
            vertex_eq_vertex_row(q, v, j, w * s, w * (kap - uv0[2 * v + j]));
        }
    }
}

/* Scale-free conformal energy Σ_f w_f [(J11 − σ J22)² + (J12 + σ J21)²] / (σ det J)
 * = 2 Σ_f w_f (MIPS_f − 1), MIPS = (s1/s2 + s2/s1)/2: the qce of each face
 * whatever its size. Infinite when a face folds (a barrier). */
static double block_energy_mips(const param_solve_data *d, const block *b, const double *uv, const int *sigma)
{
    double e = 0;
    for (int k = 0; k < b->nf; k++) {
        int f = b->faces[k];
        if (!(d->face_w[f] > 0) && !(fold_weight_of(d, f) > 0)) continue;
        double wx[3], wy[3], J[4];
        face_jacobian(d, f, uv, wx, wy, J);
        double sg = sigma[d->fchart[f]], r1 = J[0] - sg * J[3], r2 = J[1] + sg * J[2];
        double D = sg * (J[0] * J[3] - J[1] * J[2]);
        if (!(D > 0)) return INFINITY;
        if (!(d->face_w[f] > 0)) continue; /* a barrier-only face */
        e += d->face_w[f] * (r1 * r1 + r2 * r2) / D;
    }
    return e;
}

/* Gauss-Newton rows of block_energy_mips (residuals r/sqrt(D), r the
 * Cauchy-Riemann pair, D = σ det J), linearized through tanh, and the
 * anchor's rows. Every face must be unfolded. */
static void mips_rows(const param_solve_data *d, const block *b, const double *z, const double *uv, const double *uv0,
                      const double *mv, const int *sigma, double anchor, vertex_eq *q)
{
    for (int k = 0; k < b->nf; k++) {
        int f = b->faces[k];
        if (!(d->face_w[f] > 0)) continue;
        const int *t = d->tri + 3 * f;
        double wx[3], wy[3], J[4];
        face_jacobian(d, f, uv, wx, wy, J);
        double sg = sigma[d->fchart[f]], w = sqrt(d->face_w[f]);
        double D = sg * (J[0] * J[3] - J[1] * J[2]), rs = 1 / sqrt(D);
        double r[2] = {J[0] - sg * J[3], J[1] + sg * J[2]};
        for (int e = 0; e < 2; e++) {
            double ga[3], gb[3], cst = w * r[e] * rs;
            for (int j = 0; j < 3; j++) {
                int v = t[j];
                double su = 1 - uv[2 * v] * uv[2 * v], sv = 1 - uv[2 * v + 1] * uv[2 * v + 1];
                /* ∂r/∂u_v, ∂r/∂v_v and ∂D/∂u_v, ∂D/∂v_v */
                double ru = e == 0 ? wx[j] : wy[j], rv = e == 0 ? -sg * wy[j] : sg * wx[j];
                double Du = sg * (J[3] * wx[j] - J[2] * wy[j]), Dv = sg * (J[0] * wy[j] - J[1] * wx[j]);
                double gu = w * (ru * rs - 0.5 * r[e] * rs / D * Du) * su;
                double gv = w * (rv * rs - 0.5 * r[e] * rs / D * Dv) * sv;
                ga[j] = gu;
                gb[j] = gv;
                cst -= gu * z[2 * v] + gv * z[2 * v + 1];
            }
            vertex_eq_face_row(q, f, t, ga, gb, cst);
        }
    }
    anchor_rows(b, z, uv, uv0, mv, anchor, q);
}

/* Working state shared by the shared and per-chart solves. */
typedef struct solve_state {
    const param_solve_data *d;
    int H;
    float *phi;              /* nv by H: the network's features */
    double *z, *uv, *uv0;    /* nv by 2 */
    double *tz, *tuv;        /* nv by 2, trial */
    double *mv;              /* nv anchor weights (pins included) */
    int *sigma;              /* n_charts */
    double *fold_s2;         /* n_charts: mean |det J| of uv0 (the fold barrier's scale) */
    int *face_start, *face_list, *vert_start, *vert_list; /* per-chart CSR */
    int *all_faces, *all_verts;
    vertex_eq eq;            /* the Gauss-Newton sums */
    double *fit_mass;        /* nv, zero between uses: fit_head's vertex weights (only with d->fit_uv) */
    int *local;              /* nv, -1 between uses: a vertex's index in the block dual_eq solves */
} solve_state;

static void solve_state_free(solve_state *st)
{
    mem_free(st->phi); mem_free(st->z); mem_free(st->uv); mem_free(st->uv0); mem_free(st->tz); mem_free(st->tuv); mem_free(st->mv);
    mem_free(st->sigma); mem_free(st->fold_s2); mem_free(st->face_start); mem_free(st->face_list); mem_free(st->vert_start); mem_free(st->vert_list);
    mem_free(st->all_faces); mem_free(st->all_verts); mem_free(st->fit_mass); mem_free(st->local);
    vertex_eq_free(&st->eq);
}

/* Each chart holds two far-apart vertices of uv0 (see the header). */
static void add_pins(solve_state *st, double anchor)
{
    const param_solve_data *d = st->d;
    for (int c = 0; c < d->n_charts; c++) {
        const int *vl = st->vert_list + st->vert_start[c];
        int n = st->vert_start[c + 1] - st->vert_start[c];
        if (n == 0) continue;
        double share = 0, cu = 0, cv = 0, best = -1;
        for (int k = st->face_start[c]; k < st->face_start[c + 1]; k++) share += d->face_w[st->face_list[k]];
        for (int k = 0; k < n; k++) { cu += st->uv0[2 * vl[k]] / n; cv += st->uv0[2 * vl[k] + 1] / n; }
        int p1 = vl[0], p2 = vl[0];
        for (int k = 0; k < n; k++) {
            double du = st->uv0[2 * vl[k]] - cu, dv = st->uv0[2 * vl[k] + 1] - cv;
            if (du * du + dv * dv > best) { best = du * du + dv * dv; p1 = vl[k]; }
        }
        best = -1;
        for (int k = 0; k < n; k++) {
            double du = st->uv0[2 * vl[k]] - st->uv0[2 * p1], dv = st->uv0[2 * vl[k] + 1] - st->uv0[2 * p1 + 1];
            if (du * du + dv * dv > best) { best = du * du + dv * dv; p2 = vl[k]; }
        }
        st->mv[p1] += 10 * share / anchor;
        if (p2 != p1) st->mv[p2] += 10 * share / anchor;
    }
}

/* Hidden features, the map of the shared layer (uv0), chart orientations,
 * anchor weights and per-chart lists. */
static neuv_status solve_state_init(solve_state *st, const param_mlp *f, const param_solve_data *d, double anchor,
                                    int heads, const double *theta)
{
    memset(st, 0, sizeof *st);
    st->d = d;
    int H = st->H = heads ? param_mlp_head_width(f) : f->width, nv = d->nv, nc = d->n_charts > 0 ? d->n_charts : 1;
    size_t v2 = sizeof(double) * 2 * (size_t)(nv > 0 ? nv : 1);
    st->phi = mem_alloc(sizeof(float) * (size_t)(nv > 0 ? nv : 1) * H);
    st->z = mem_alloc(v2); st->uv = mem_alloc(v2); st->uv0 = mem_alloc(v2); st->tz = mem_alloc(v2); st->tuv = mem_alloc(v2);
    st->mv = mem_calloc((size_t)(nv > 0 ? nv : 1), sizeof(double));
    st->sigma = mem_alloc(sizeof(int) * (size_t)nc);
    st->fold_s2 = mem_calloc((size_t)nc, sizeof(double));
    st->face_start = mem_calloc((size_t)nc + 1, sizeof(int));
    st->vert_start = mem_calloc((size_t)nc + 1, sizeof(int));
    st->face_list = mem_alloc(sizeof(int) * (size_t)(d->nf > 0 ? d->nf : 1));
    st->vert_list = mem_alloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
    st->all_faces = mem_alloc(sizeof(int) * (size_t)(d->nf > 0 ? d->nf : 1));
    st->all_verts = mem_alloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
    st->local = mem_alloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
    double *csum = mem_calloc((size_t)nc, sizeof(double));
    if (d->fit_uv) st->fit_mass = mem_calloc((size_t)(nv > 0 ? nv : 1), sizeof(double));
    if ((d->fit_uv && !st->fit_mass) || !st->local || !st->phi || !st->z || !st->uv || !st->uv0 || !st->tz || !st->tuv || !st->mv || !st->sigma || !st->fold_s2 || !st->face_start ||
        !st->vert_start || !st->face_list || !st->vert_list || !st->all_faces || !st->all_verts || !csum) {
        mem_free(csum);
        return error_nomem("output-layer solve");
    }
    for (int f0 = 0; f0 < d->nf; f0++) { st->face_start[d->fchart[f0] + 1]++; st->all_faces[f0] = f0; }
    for (int v = 0; v < nv; v++) { st->vert_start[d->vchart[v] + 1]++; st->all_verts[v] = v; st->local[v] = -1; }
    for (int c = 0; c < nc; c++) { st->face_start[c + 1] += st->face_start[c]; st->vert_start[c + 1] += st->vert_start[c]; }
    int *fp = mem_alloc(sizeof(int) * (size_t)nc), *vp = mem_alloc(sizeof(int) * (size_t)nc);
    if (!fp || !vp) { mem_free(fp); mem_free(vp); mem_free(csum); return error_nomem("output-layer solve"); }
    memcpy(fp, st->face_start, sizeof(int) * (size_t)nc);
    memcpy(vp, st->vert_start, sizeof(int) * (size_t)nc);
    for (int f0 = 0; f0 < d->nf; f0++) st->face_list[fp[d->fchart[f0]]++] = f0;
    for (int v = 0; v < nv; v++) st->vert_list[vp[d->vchart[v]]++] = v;
    mem_free(fp); mem_free(vp);
    neuv_status s = hidden_at(f, d, d->f_in, d->f_in_dim, heads, st->phi);
    if (s == NEUV_OK) s = vertex_eq_init(&st->eq, nv, d->nf, d->tri, H);
    if (s != NEUV_OK) { mem_free(csum); return s; }
    block all = {st->all_faces, st->all_verts, d->nf, nv};
    map_block(st->phi, H, theta, &all, st->z, st->uv);
    memcpy(st->uv0, st->uv, v2);
    /* Each chart keeps the orientation it has (a network may map a chart mirrored). */
    for (int f0 = 0; f0 < d->nf; f0++) {
        const int *t = d->tri + 3 * f0;
        const double *a = st->uv + 2 * t[0], *b = st->uv + 2 * t[1], *c = st->uv + 2 * t[2];
        csum[d->fchart[f0]] += (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        for (int k = 0; k < 3; k++) st->mv[t[k]] += d->face_w[f0] / 3;
    }
    for (int c = 0; c < nc; c++) st->sigma[c] = csum[c] < 0 ? -1 : 1;
    /* The fold barrier's scale: each chart's area-weighted mean |det J| in uv0. */
    memset(csum, 0, sizeof(double) * (size_t)nc);
    for (int f0 = 0; f0 < d->nf; f0++) {
        double wx[3], wy[3], J[4];
        face_jacobian(d, f0, st->uv, wx, wy, J);
        st->fold_s2[d->fchart[f0]] += d->face_w[f0] * fabs(J[0] * J[3] - J[1] * J[2]);
        csum[d->fchart[f0]] += d->face_w[f0];
    }
    for (int c = 0; c < nc; c++) st->fold_s2[c] = csum[c] > 0 ? st->fold_s2[c] / csum[c] : 0;
    mem_free(csum);
    add_pins(st, anchor);
    return NEUV_OK;
}

/* The objective of a descent: 0, the conformal energy (with the fold
 * barrier when d->fold_weight > 0); 1, the scale-free one (block_energy_mips);
 * both plus the anchor. *flips: the faces folded against their chart. */
static double block_objective(const solve_state *st, const block *b, const double *uv, int mips, double anchor,
                              int *flips)
{
    const param_solve_data *d = st->d;
    double e;
    if (mips) { /* infinite exactly when a face the barrier counts folds */
        e = block_energy_mips(d, b, uv, st->sigma);
        if (flips) *flips = isfinite(e) ? 0 : 1;
    } else {
        e = block_energy(d, b, uv, st->sigma, st->fold_s2, flips);
    }
    return e + anchor * block_anchor(b, uv, st->uv0, st->mv);
}

/* The Gauss-Newton step of a block with fewer vertices than features, solved
 * in vertex space. The step solves (Pᵀ M P + λ I) θ = −Pᵀ h, P = I₂ ⊗ Φ̂
 * (V by K each), M the 2V by 2V sums of vertex_eq (u block, then v) and h =
 * (hu, hv). With θ = Pᵀ y that is Pᵀ [(M G₂ + λ I) y + h] = 0, G₂ = P Pᵀ =
 * I₂ ⊗ Φ̂ Φ̂ᵀ, so y solving the 2V by 2V system (M G₂ + λ I) y = −h gives the
 * same θ (the push-through identity; unique since λ > 0) at (2V)³ instead of
 * (2K)³ and without the 2K by 2K matrix: a chart's step costs what its
 * vertices cost, not what the features cost. λ is normal_eq_solve's ridge,
 * tr(Pᵀ M P) = tr(M G₂). Vertices no row touches get y = 0. */
typedef struct dual_eq {
    int V, K;
    int *local;        /* the state's nv entries: a block vertex's index, else -1 (owned by the state) */
    double *phi;       /* V by K: φ̂ at the block's vertices */
    double *gram;      /* V by V: Φ̂ Φ̂ᵀ */
    double *m, *s, *y; /* 2V by 2V, 2V by 2V, 2V */
    int *ipiv;         /* 2V */
} dual_eq;

static void dual_eq_free(dual_eq *q, const block *b)
{
    if (q->local && b)
        for (int k = 0; k < b->nv; k++) q->local[b->verts[k]] = -1;
    mem_free(q->phi); mem_free(q->gram); mem_free(q->m); mem_free(q->s); mem_free(q->y); mem_free(q->ipiv);
    memset(q, 0, sizeof *q);
}

static neuv_status dual_eq_init(dual_eq *q, int *local, const float *phi, int H, const block *b)
{
    memset(q, 0, sizeof *q);
    int V = q->V = b->nv, K = q->K = H + 1;
    size_t v2 = 2 * (size_t)V;
    q->phi = mem_alloc(sizeof(double) * (size_t)V * K);
    q->gram = mem_alloc(sizeof(double) * (size_t)V * V);
    q->m = mem_alloc(sizeof(double) * v2 * v2);
    q->s = mem_alloc(sizeof(double) * v2 * v2);
    q->y = mem_alloc(sizeof(double) * v2);
    q->ipiv = mem_alloc(sizeof(int) * v2);
    if (!q->phi || !q->gram || !q->m || !q->s || !q->y || !q->ipiv) { dual_eq_free(q, NULL); return error_nomem("output-layer solve"); }
    q->local = local;
    for (int k = 0; k < V; k++) {
        int v = b->verts[k];
        local[v] = k;
        double *r = q->phi + (size_t)k * K;
        const float *p = phi + (size_t)v * H;
        for (int i = 0; i < H; i++) r[i] = p[i];
        r[H] = 1;
    }
    cblas_dgemm(CblasRowMajor, CblasNoTrans, CblasTrans, V, V, K, 1.0, q->phi, K, q->phi, K, 0.0, q->gram, V);
    return NEUV_OK;
}

/* The step's θ (n = 2K numbers) from the block's sums; 0, or -1 when the
 * system is singular. */
static int dual_eq_solve(dual_eq *q, const vertex_eq *e, const block *b, double *theta)
{
    int V = q->V, K = q->K, W = 2 * V;
    double *M = q->m, *S = q->s, *G = q->gram, *y = q->y;
    memset(M, 0, sizeof(double) * (size_t)W * W);
    for (int k = 0; k < V; k++) {
        int v = b->verts[k];
        for (int p = e->start[v]; p < e->start[v + 1]; p++) {
            int l = q->local[e->col[p]];
            if (l < 0) continue; /* not the block's (a block is whole charts) */
            M[(size_t)k * W + l] = e->muu[p];
            M[(size_t)k * W + V + l] = e->muv[p];
            M[(size_t)(V + l) * W + k] = e->muv[p];
            M[(size_t)(V + k) * W + V + l] = e->mvv[p];
        }
        y[k] = -e->hu[v];
        y[V + k] = -e->hv[v];
    }
    double tr = 0;
    for (int i = 0; i < V; i++)
        for (int j = 0; j < V; j++)
            tr += (M[(size_t)i * W + j] + M[(size_t)(V + i) * W + V + j]) * G[(size_t)j * V + i];
    double ridge = 1e-9 * (tr > 0 ? tr / (2 * K) : 1) + 1e-300;
    cblas_dgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, W, V, V, 1.0, M, W, G, V, 0.0, S, W);
    cblas_dgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, W, V, V, 1.0, M + V, W, G, V, 0.0, S + V, W);
    for (int i = 0; i < W; i++) S[(size_t)i * W + i] += ridge;
    if (LAPACKE_dgesv(LAPACK_ROW_MAJOR, W, 1, S, W, q->ipiv, y, 1) != 0) return -1;
    cblas_dgemv(CblasRowMajor, CblasTrans, V, K, 1.0, q->phi, K, y, 1, 0.0, theta, 1);
    cblas_dgemv(CblasRowMajor, CblasTrans, V, K, 1.0, q->phi, K, y + V, 1, 0.0, theta + K, 1);
    return 0;
}

/* The Gauss-Newton step of a block with more vertices than features, in the
 * span its features have. A chart's K features are far from independent on
 * its vertices (the hidden layers' units and the Fourier terms repeat one
 * another: on spot's charts Φ̂ has 145-250 singular values above 1e-7 of
 * the largest, of K = 420), and the feature-space system costs 6 V K² per
 * step to build. With G = Φ̂ᵀ Φ̂ = W Λ Wᵀ, B = W_r Λ_r^(-1/2) over the r
 * eigenvalues above rank_tol² of the largest and Ψ = Φ̂ B (V by r,
 * orthonormal columns), each step takes θ = θ_b + B y (θ_b the descent's
 * start; per component u, v) and solves the quadratic the feature-space
 * step minimizes, ½ θᵀAθ + θᵀΦ̂ᵀh + ½ λ|θ|², A = Φ̂ᵀ M Φ̂, for y:
 * (Ψᵀ M Ψ + λ Λ_r⁻¹) y = −Ψᵀ (h + M z_b) − λ Bᵀ θ_b, z_b = Φ̂ θ_b, at
 * 6 V r² for the products. λ is normal_eq_solve's ridge, 1e-9 tr(A) / 2K,
 * with tr(A) = Σ M_vw φ̂_v·φ̂_w. The directions left out (σ below rank_tol
 * of the largest) keep θ_b's weights; in the feature-space step their
 * curvature is below the ridge's. */
typedef struct reduced_eq {
    int V, K, r;
    int *local;        /* the state's nv entries: a block vertex's index, else -1 (owned by the state) */
    float *psi;        /* V by r: Ψ */
    double *basis;     /* K by r: B */
    double *lam_inv;   /* r: Λ_r⁻¹ = diag(BᵀB) */
    double *dots;      /* φ̂_v·φ̂_w for the block's entries of the sums, vertex by vertex */
    int *dstart;       /* V + 1: each block vertex's first entry in dots */
    double *zb, *hz;   /* V by 2: z_b; h + M z_b */
    double *thb, *bt;  /* 2K: θ_b; 2r: Bᵀ θ_b per component */
    normal_eq q;       /* 2r */
} reduced_eq;

static void reduced_eq_free(reduced_eq *q, const block *b)
{
    if (q->local && b)
        for (int k = 0; k < b->nv; k++) q->local[b->verts[k]] = -1;
    mem_free(q->psi); mem_free(q->basis); mem_free(q->lam_inv); mem_free(q->dots); mem_free(q->dstart);
    mem_free(q->zb); mem_free(q->hz); mem_free(q->thb); mem_free(q->bt);
    normal_eq_free(&q->q);
    memset(q, 0, sizeof *q);
}

enum { REDUCED_CHUNK = 256 };

/* φ̂ (K = H + 1 numbers) of the block's vertices from k0, up to
 * REDUCED_CHUNK of them, as the rows of C; returns how many. */
static int chunk_features(const solve_state *st, const block *b, int k0, double *C)
{
    int H = st->H, K = H + 1, m = b->nv - k0 < REDUCED_CHUNK ? b->nv - k0 : REDUCED_CHUNK;
    for (int r = 0; r < m; r++) {
        const float *p = st->phi + (size_t)b->verts[k0 + r] * H;
        for (int i = 0; i < H; i++) C[(size_t)r * K + i] = p[i];
        C[(size_t)r * K + H] = 1;
    }
    return m;
}

/* The block's reduced basis. Returns 1 when it has fewer directions than
 * features (the system is then this one), 0 when not (q is empty), -1 on
 * allocation failure. */
static int reduced_eq_init(reduced_eq *q, const solve_state *st, const block *b, double rank_tol)
{
    memset(q, 0, sizeof *q);
    int H = st->H, K = H + 1, V = b->nv, ret = -1;
    double *G = mem_calloc((size_t)K * K, sizeof(double)), *w = mem_alloc(sizeof(double) * (size_t)K);
    double *C = mem_alloc(sizeof(double) * REDUCED_CHUNK * (size_t)K), *Y = NULL;
    if (!G || !w || !C) goto out;
    for (int k0 = 0; k0 < V; k0 += REDUCED_CHUNK) {
        int m = chunk_features(st, b, k0, C);
        cblas_dsyrk(CblasRowMajor, CblasUpper, CblasTrans, K, m, 1.0, C, K, 1.0, G, K);
    }
    if (LAPACKE_dsyevd(LAPACK_ROW_MAJOR, 'V', 'U', K, G, K, w) != 0) { ret = 0; goto out; }
    /* eigenvalues ascending, eigenvector j in column j */
    double cut = rank_tol * rank_tol * w[K - 1];
    int r = 0;
    for (int j = 0; j < K; j++) r += w[j] > cut && w[j] > 0;
    if (r == 0 || r >= K) { ret = 0; goto out; }
    q->V = V; q->K = K; q->r = r;
    q->local = st->local;
    q->psi = mem_alloc(sizeof(float) * (size_t)V * r);
    q->basis = mem_alloc(sizeof(double) * (size_t)K * r);
    q->lam_inv = mem_alloc(sizeof(double) * (size_t)r);
    q->dstart = mem_alloc(sizeof(int) * ((size_t)V + 1));
    q->zb = mem_alloc(sizeof(double) * 2 * (size_t)V);
    q->hz = mem_alloc(sizeof(double) * 2 * (size_t)V);
    q->thb = mem_alloc(sizeof(double) * 2 * (size_t)K);
    q->bt = mem_alloc(sizeof(double) * 2 * (size_t)r);
    Y = mem_alloc(sizeof(double) * REDUCED_CHUNK * (size_t)r);
    if (!q->psi || !q->basis || !q->lam_inv || !q->dstart || !q->zb || !q->hz || !q->thb || !q->bt || !Y ||
        normal_eq_init(&q->q, 2 * r, 0) != NEUV_OK)
        goto out;
    for (int j = K - r, c = 0; j < K; j++, c++) {
        q->lam_inv[c] = 1 / w[j];
        double s = 1 / sqrt(w[j]);
        for (int i = 0; i < K; i++) q->basis[(size_t)i * r + c] = G[(size_t)i * K + j] * s;
    }
    for (int k0 = 0; k0 < V; k0 += REDUCED_CHUNK) {
        int m = chunk_features(st, b, k0, C);
        cblas_dgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, m, r, K, 1.0, C, K, q->basis, r, 0.0, Y, r);
        for (size_t i = 0; i < (size_t)m * r; i++) q->psi[(size_t)k0 * r + i] = (float)Y[i];
    }
    for (int k = 0; k < V; k++) q->local[b->verts[k]] = k;
    const vertex_eq *e = &st->eq;
    q->dstart[0] = 0;
    for (int k = 0; k < V; k++) {
        int v = b->verts[k];
        q->dstart[k + 1] = q->dstart[k] + (e->start[v + 1] - e->start[v]);
    }
    q->dots = mem_alloc(sizeof(double) * ((size_t)q->dstart[V] + 1));
    if (!q->dots) goto out;
    for (int k = 0; k < V; k++) {
        int v = b->verts[k];
        const float *pv = st->phi + (size_t)v * H;
        for (int p = e->start[v]; p < e->start[v + 1]; p++) {
            const float *pw = st->phi + (size_t)e->col[p] * H;
            double dot = 1;
            for (int i = 0; i < H; i++) dot += (double)pv[i] * pw[i];
            q->dots[q->dstart[k] + p - e->start[v]] = dot;
        }
    }
    ret = 1;
out:
    mem_free(G); mem_free(w); mem_free(C); mem_free(Y);
    if (ret != 1) reduced_eq_free(q, ret < 0 ? b : NULL);
    return ret;
}

/* The descent's start θ_b, with z at it (the state's z on the block). */
static void reduced_eq_start(reduced_eq *q, const block *b, const double *theta, const double *z)
{
    int K = q->K, r = q->r;
    memcpy(q->thb, theta, sizeof(double) * 2 * (size_t)K);
    for (int k = 0; k < b->nv; k++) {
        q->zb[2 * k] = z[2 * b->verts[k]];
        q->zb[2 * k + 1] = z[2 * b->verts[k] + 1];
    }
    for (int j = 0; j < 2; j++)
        cblas_dgemv(CblasRowMajor, CblasTrans, K, r, 1.0, q->basis, r, theta + (size_t)j * K, 1, 0.0, q->bt + (size_t)j * r, 1);
}

/* The step's θ (2K numbers) from the block's sums; 0, or -1 when the system is not positive definite. */
static int reduced_eq_solve(reduced_eq *q, const vertex_eq *e, const block *b, double *theta)
{
    int V = q->V, K = q->K, r = q->r, n = 2 * r;
    double tr = 0;
    for (int k = 0; k < V; k++) {
        int v = b->verts[k];
        q->hz[2 * k] = e->hu[v];
        q->hz[2 * k + 1] = e->hv[v];
    }
    for (int k = 0; k < V; k++) {
        int v = b->verts[k];
        const double *dot = q->dots + q->dstart[k] - e->start[v];
        for (int p = e->start[v]; p < e->start[v + 1]; p++) {
            int l = q->local[e->col[p]];
            if (l < 0) continue; /* not the block's (a block is whole charts) */
            tr += (e->muu[p] + e->mvv[p]) * dot[p];
            q->hz[2 * k] += e->muu[p] * q->zb[2 * l] + e->muv[p] * q->zb[2 * l + 1];
            q->hz[2 * k + 1] += e->mvv[p] * q->zb[2 * l + 1];
            q->hz[2 * l + 1] += e->muv[p] * q->zb[2 * k];
        }
    }
    double ridge = 1e-9 * (tr > 0 ? tr / (2 * K) : 1) + 1e-300;
    vertex_eq_flush(e, &(feature_rows){q->psi, r, 0, q->local}, q->hz, b->verts, V, &q->q);
    for (int j = 0; j < 2; j++)
        for (int c = 0; c < r; c++) {
            q->q.a[(size_t)(j * r + c) * n + j * r + c] += ridge * q->lam_inv[c];
            q->q.g[j * r + c] -= ridge * q->bt[j * r + c];
        }
    if (LAPACKE_dposv(LAPACK_ROW_MAJOR, 'U', n, 1, q->q.a, n, q->q.g, 1) != 0) return -1;
    for (int j = 0; j < 2; j++) {
        memcpy(theta + (size_t)j * K, q->thb + (size_t)j * K, sizeof(double) * (size_t)K);
        cblas_dgemv(CblasRowMajor, CblasNoTrans, K, r, 1.0, q->basis, r, q->q.g + (size_t)j * r, 1, 1.0, theta + (size_t)j * K, 1);
    }
    return 0;
}

/* Gauss-Newton on theta for one block and objective, from the state's z/uv
 * at theta. A step is halved until the objective falls. The result is the
 * iterate chosen by `keep` among the start and the steps: without the fold
 * barrier the lowest objective with no more flips than the start; with it,
 * the fewest flips, then the lowest objective (the scale-free objective
 * never flips a face). rq: the block's reduced system (NULL: the feature-space
 * one). Returns the steps up to that iterate, or -1 on allocation failure;
 * *flips_out: that iterate's folded faces. */
static int descend(solve_state *st, const block *b, reduced_eq *rq, int mips, double anchor, int steps, double *theta,
                   int *flips_out)
{
    const param_solve_data *d = st->d;
    int H = st->H, n = 2 * (H + 1), flips0, taken = 0, best_step = 0;
    double *trial = mem_alloc(sizeof(double) * (size_t)n), *best = mem_alloc(sizeof(double) * (size_t)n);
    if (!trial || !best) { mem_free(trial); mem_free(best); return -1; }
    memcpy(best, theta, sizeof(double) * (size_t)n);
    double e = block_objective(st, b, st->uv, mips, anchor, &flips0);
    int flips_start = flips0, fewest = !mips && d->fold_weight > 0;
    /* One system's buffers for every step (a fresh n² matrix per step costs
     * more than the solve on a small chart: page faults). A block with fewer
     * vertices than features is solved in vertex space (dual_eq), one with
     * more in its features' span when rq is given (reduced_eq). */
    normal_eq q;
    dual_eq dq;
    memset(&q, 0, sizeof q);
    memset(&dq, 0, sizeof dq);
    int dual = b->nv < H + 1, reduced = !dual && rq;
    if (reduced) reduced_eq_start(rq, b, theta, st->z);
    double *sol = dual || reduced ? mem_alloc(sizeof(double) * (size_t)n) : NULL;
    if (dual ? !sol || dual_eq_init(&dq, st->local, st->phi, H, b) != NEUV_OK
             : reduced ? !sol : normal_eq_init(&q, n, 0) != NEUV_OK) {
        mem_free(sol); mem_free(trial); mem_free(best);
        return -1;
    }
    if (!dual && !reduced) sol = q.g;
    for (int step = 0; step < steps; step++) {
        vertex_eq_reset(&st->eq, b->verts, b->nv);
        if (mips) mips_rows(d, b, st->z, st->uv, st->uv0, st->mv, st->sigma, anchor, &st->eq);
        else gauss_newton_rows(d, b, st->z, st->uv, st->uv0, st->mv, st->sigma, st->fold_s2, anchor, &st->eq);
        if (dual) {
            if (dual_eq_solve(&dq, &st->eq, b, sol) != 0) break;
        } else if (reduced) {
            if (reduced_eq_solve(rq, &st->eq, b, sol) != 0) break;
        } else {
            vertex_eq_flush(&st->eq, &(feature_rows){st->phi, H, 1, NULL}, NULL, b->verts, b->nv, &q);
            if (normal_eq_solve(&q, 0, NULL) != 0) break;
        }
        int kept = 0, fl = 0;
        for (double alpha = 1; alpha > (mips ? 1e-4 : 1.0 / 64) && !kept; alpha *= 0.5) {
            for (int i = 0; i < n; i++) trial[i] = theta[i] + alpha * (sol[i] - theta[i]);
            map_block(st->phi, H, trial, b, st->tz, st->tuv);
            double et = block_objective(st, b, st->tuv, mips, anchor, &fl);
            if (isfinite(et) && et < e) {
                memcpy(theta, trial, sizeof(double) * (size_t)n);
                for (int k = 0; k < b->nv; k++) {
                    int v = b->verts[k];
                    for (int j = 0; j < 2; j++) { st->z[2 * v + j] = st->tz[2 * v + j]; st->uv[2 * v + j] = st->tuv[2 * v + j]; }
                }
                e = et;
                kept = 1;
            }
        }
        if (!kept) break;
        taken++;
        if (fewest ? fl <= flips0 : fl <= flips_start) {
            memcpy(best, theta, sizeof(double) * (size_t)n);
            best_step = taken;
            flips0 = fl;
        }
    }
    normal_eq_free(&q);
    if (dual) dual_eq_free(&dq, b);
    if (dual || reduced) mem_free(sol);
    if (best_step != taken) { /* back to the best valid iterate */
        memcpy(theta, best, sizeof(double) * (size_t)n);
        map_block(st->phi, H, theta, b, st->z, st->uv);
    }
    if (flips_out) *flips_out = best_step > 0 ? flips0 : flips_start;
    mem_free(trial); mem_free(best);
    return best_step;
}

/* The conformal descent, then, when d->mips_steps > 0 and the map is
 * injective on the block, the scale-free one, both over one reduced system
 * when the block's features span fewer directions than they number (unless
 * d->rank_tol < 0). Returns the steps kept or -1. */
static int solve_block(solve_state *st, const block *b, double anchor, int steps, double *theta)
{
    const param_solve_data *d = st->d;
    reduced_eq rq;
    int reduced = 0;
    memset(&rq, 0, sizeof rq);
    if (b->nv >= st->H + 1 && !(d->rank_tol < 0) && steps > 0) {
        reduced = reduced_eq_init(&rq, st, b, d->rank_tol > 0 ? d->rank_tol : PARAM_SOLVE_RANK_TOL);
        if (reduced < 0) return -1;
    }
    reduced_eq *r = reduced ? &rq : NULL;
    int flips, taken = descend(st, b, r, 0, anchor, steps, theta, &flips);
    if (taken >= 0 && d->mips_steps > 0 && flips == 0) {
        int more = descend(st, b, r, 1, anchor, d->mips_steps, theta, NULL);
        taken = more < 0 ? -1 : taken + more;
    }
    if (reduced) reduced_eq_free(&rq, b);
    return taken;
}

static void theta_from_layer(const nn_linear *l, int H, double *theta)
{
    for (int j = 0; j < 2; j++) {
        for (int i = 0; i < H; i++) theta[(size_t)j * (H + 1) + i] = l->w->data[(size_t)i * 2 + j];
        theta[(size_t)j * (H + 1) + H] = l->b->data[j];
    }
}

/* A head that is the shared output layer: zero weight on all but the last
 * hidden layer, which comes last in a head's features (theta: 2(H + 1)
 * numbers, zeroed, H the head width). */
static void head_from_shared_layer(const param_mlp *f, double *theta)
{
    const nn_linear *l = &f->rest[f->depth - 2];
    int W = f->width, H = param_mlp_head_width(f), off = H - W;
    for (int j = 0; j < 2; j++) {
        for (int i = 0; i < W; i++) theta[(size_t)j * (H + 1) + off + i] = l->w->data[(size_t)i * 2 + j];
        theta[(size_t)j * (H + 1) + H] = l->b->data[j];
    }
}

static neuv_status check_f(const param_mlp *f, double anchor)
{
    if (f->depth < 2 || f->out != 2 || !(anchor > 0))
        return error_set(NEUV_ERR_INPUT, "output-layer solve needs a hidden layer, 2 outputs and an anchor > 0");
    return NEUV_OK;
}

neuv_status param_output_solve_conformal(param_mlp *f, const param_solve_data *d, double anchor, int steps,
                                         param_solve_report *rep)
{
    param_solve_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    neuv_status s = check_f(f, anchor);
    if (s != NEUV_OK) return s;
    int H = f->width, n = 2 * (H + 1);
    nn_linear *out = &f->rest[f->depth - 2];
    double *theta = mem_alloc(sizeof(double) * (size_t)n);
    solve_state st;
    if (!theta) return error_nomem("output-layer solve");
    theta_from_layer(out, H, theta);
    s = solve_state_init(&st, f, d, anchor, 0, theta);
    if (s == NEUV_OK) {
        block all = {st.all_faces, st.all_verts, d->nf, d->nv};
        rep->energy_before = block_energy(d, &all, st.uv, st.sigma, NULL, NULL);
        int taken = solve_block(&st, &all, anchor, steps, theta);
        if (taken < 0) s = error_nomem("output-layer solve");
        else {
            rep->steps = taken;
            rep->energy_after = block_energy(d, &all, st.uv, st.sigma, NULL, NULL);
            for (int j = 0; j < 2; j++) {
                for (int i = 0; i < H; i++) out->w->data[(size_t)i * 2 + j] = (float)theta[(size_t)j * (H + 1) + i];
                out->b->data[j] = (float)theta[(size_t)j * (H + 1) + H];
            }
        }
    }
    solve_state_free(&st);
    mem_free(theta);
    return s;
}

/* The block's map at theta becomes its start: z, uv and uv0 (the anchor's
 * reference), the chart's orientation σ and the barrier's scale s̄². */
static void restart_block(solve_state *st, const block *b, int chart, const double *theta)
{
    const param_solve_data *d = st->d;
    map_block(st->phi, st->H, theta, b, st->z, st->uv);
    for (int k = 0; k < b->nv; k++) {
        int v = b->verts[k];
        st->uv0[2 * v] = st->uv[2 * v];
        st->uv0[2 * v + 1] = st->uv[2 * v + 1];
    }
    double orient = 0, s2 = 0, w = 0;
    for (int k = 0; k < b->nf; k++) {
        int f = b->faces[k];
        double wx[3], wy[3], J[4];
        face_jacobian(d, f, st->uv, wx, wy, J);
        double det = J[0] * J[3] - J[1] * J[2];
        orient += fold_weight_of(d, f) * det;
        s2 += d->face_w[f] * fabs(det);
        w += d->face_w[f];
    }
    st->sigma[chart] = orient < 0 ? -1 : 1;
    st->fold_s2[chart] = w > 0 ? s2 / w : 0;
}

/* Relative ridge of the least-squares fit of a head to target uvs (see
 * fit_head): measured on the charts the networks fold (bench/RESULTS.md,
 * "A second start for folded charts"). */
#define FIT_RIDGE 1e-6

/* theta = the head whose pre-tanh outputs fit atanh of the targets (d->fit_uv)
 * at the block's vertices below d->fit_nv, each weighted by its share of the
 * chart's area, by least squares with a ridge of FIT_RIDGE of the mean
 * diagonal. Returns 1 when fitted, 0 when the block has no target or the
 * system is singular, -1 on allocation failure. */
static int fit_head(const solve_state *st, const block *b, double *theta)
{
    const param_solve_data *d = st->d;
    int H = st->H, K = H + 1, n = 0;
    double *mass = st->fit_mass;
    for (int k = 0; k < b->nf; k++) {
        const int *t = d->tri + 3 * b->faces[k];
        for (int j = 0; j < 3; j++) mass[t[j]] += d->face_w[b->faces[k]] / 3;
    }
    normal_eq q;
    double *rhs = mem_calloc(2 * (size_t)K, sizeof(double));
    if (!rhs || normal_eq_init(&q, K, VERTEX_EQ_CHUNK) != NEUV_OK) { mem_free(rhs); n = -1; }
    for (int k = 0; n >= 0 && k < b->nv; k++) {
        int v = b->verts[k];
        if (v >= d->fit_nv || !(mass[v] > 0)) continue;
        double sw = sqrt(mass[v]), y[2];
        for (int j = 0; j < 2; j++) {
            double t = d->fit_uv[2 * v + j];
            t = t > 0.995 ? 0.995 : t < -0.995 ? -0.995 : t;
            y[j] = atanh(t);
        }
        double *c, *r = normal_eq_row(&q, &c);
        const float *p = st->phi + (size_t)v * H;
        for (int i = 0; i < H; i++) r[i] = sw * p[i];
        r[H] = sw;
        for (int i = 0; i < K; i++) { rhs[2 * i] += r[i] * sw * y[0]; rhs[2 * i + 1] += r[i] * sw * y[1]; }
        n++;
    }
    int ok = 0;
    if (n > 0) {
        normal_eq_flush(&q);
        double tr = 0;
        for (int i = 0; i < K; i++) tr += q.a[(size_t)i * K + i];
        for (int i = 0; i < K; i++) q.a[(size_t)i * K + i] += FIT_RIDGE * tr / K;
        ok = normal_eq_solve(&q, 2, rhs) == 0;
        if (ok)
            for (int j = 0; j < 2; j++)
                for (int i = 0; i < K; i++) theta[(size_t)j * K + i] = rhs[2 * i + j];
    }
    for (int k = 0; k < b->nv; k++) mass[b->verts[k]] = 0; /* zero again for the next chart */
    if (n < 0) return -1;
    normal_eq_free(&q);
    mem_free(rhs);
    return ok;
}

/* The faces of the block folded against its chart's orientation at the state's uv. */
static int block_flips(const solve_state *st, const block *b)
{
    int fl;
    block_energy(st->d, b, st->uv, st->sigma, NULL, &fl);
    return fl;
}

/* A chart whose head folds after its solve from the shared layer: solved
 * again from the head fitted to d->fit_uv; theta and the state keep that
 * solve when it folds fewer faces. Returns 1 when kept, 0 when not, -1 on
 * allocation failure. */
static int solve_from_fit(solve_state *st, const block *b, int chart, double anchor, int steps, double *theta)
{
    int H = st->H, n = 2 * (H + 1), flips = block_flips(st, b);
    double *fit = mem_alloc(sizeof(double) * (size_t)n), *keep = mem_alloc(sizeof(double) * 2 * (size_t)b->nv);
    int sigma = st->sigma[chart];
    double s2 = st->fold_s2[chart];
    if (!fit || !keep) { mem_free(fit); mem_free(keep); return -1; }
    int got = fit_head(st, b, fit), kept = 0;
    if (got > 0) {
        for (int k = 0; k < b->nv; k++) {
            int v = b->verts[k];
            for (int j = 0; j < 2; j++) keep[2 * k + j] = st->uv0[2 * v + j];
        }
        restart_block(st, b, chart, fit);
        if (solve_block(st, b, anchor, steps, fit) < 0) got = -1;
        else if (block_flips(st, b) < flips) {
            memcpy(theta, fit, sizeof(double) * (size_t)n);
            kept = 1;
        } else { /* back to the first solve's map and references */
            st->sigma[chart] = sigma;
            st->fold_s2[chart] = s2;
            for (int k = 0; k < b->nv; k++) {
                int v = b->verts[k];
                for (int j = 0; j < 2; j++) st->uv0[2 * v + j] = keep[2 * k + j];
            }
            map_block(st->phi, H, theta, b, st->z, st->uv);
        }
    }
    mem_free(fit); mem_free(keep);
    return got < 0 ? -1 : kept;
}

/* order (n charts) sorted by vertex count (CSR vstart), largest first,
 * ties by chart index: an insertion sort, the charts are few. */
static void chart_order_by_size(int *order, int n, const int *vstart)
{
    for (int i = 1; i < n; i++) {
        int c = order[i], size = vstart[c + 1] - vstart[c], j = i;
        for (; j > 0; j--) {
            int p = order[j - 1], ps = vstart[p + 1] - vstart[p];
            if (ps > size || (ps == size && p < c)) break;
            order[j] = p;
        }
        order[j] = c;
    }
}

neuv_status param_output_solve_heads(const param_mlp *f, const param_solve_data *d, double anchor, int steps,
                                     float *heads, param_solve_report *rep)
{
    param_solve_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    neuv_status s = check_f(f, anchor);
    if (s != NEUV_OK) return s;
    /* A head reads every hidden layer; it starts as the shared output layer. */
    int H = param_mlp_head_width(f), n = 2 * (H + 1);
    double *shared = mem_calloc((size_t)n, sizeof(double));
    solve_state st;
    if (!shared) return error_nomem("output-layer solve");
    head_from_shared_layer(f, shared);
    s = solve_state_init(&st, f, d, anchor, 1, shared);
    if (s == NEUV_OK) {
        block all = {st.all_faces, st.all_verts, d->nf, d->nv};
        rep->energy_before = block_energy(d, &all, st.uv, st.sigma, NULL, NULL);
    }
    /* Each chart's head on its own: the charts are solved side by side, the
     * largest first (each solve touches only its chart's vertices and faces,
     * so the heads are the same on any thread count and in any order). */
    int nc = d->n_charts > 0 ? d->n_charts : 0;
    int *order = mem_alloc(sizeof(int) * (size_t)(nc + 1)), *taken_of = mem_calloc((size_t)nc + 1, sizeof(int));
    int *refit_of = mem_calloc((size_t)nc + 1, sizeof(int));
    if (s == NEUV_OK && (!order || !taken_of || !refit_of)) s = error_nomem("output-layer solve");
    if (s == NEUV_OK) {
        for (int c = 0; c < nc; c++) order[c] = c;
        chart_order_by_size(order, nc, st.vert_start);
#pragma omp parallel
        {
            double *th = mem_alloc(sizeof(double) * (size_t)n);
#pragma omp for schedule(dynamic, 1)
            for (int k = 0; k < nc; k++) {
                int c = order[k];
                block b = {st.face_list + st.face_start[c], st.vert_list + st.vert_start[c],
                           st.face_start[c + 1] - st.face_start[c], st.vert_start[c + 1] - st.vert_start[c]};
                if (!th) { taken_of[c] = -1; continue; }
                memcpy(th, shared, sizeof(double) * (size_t)n);
                int taken = b.nf > 0 ? solve_block(&st, &b, anchor, steps, th) : 0;
                if (taken >= 0 && b.nf > 0 && d->fit_uv && block_flips(&st, &b) > 0) {
                    int refit = solve_from_fit(&st, &b, c, anchor, steps, th);
                    if (refit < 0) taken = -1;
                    else if (refit) { refit_of[c] = 1; taken = taken > 0 ? taken : 1; }
                }
                taken_of[c] = taken;
                if (taken >= 0)
                    for (int i = 0; i < n; i++) heads[(size_t)c * n + i] = (float)th[i];
            }
            mem_free(th);
        }
        for (int c = 0; c < nc && s == NEUV_OK; c++) {
            if (taken_of[c] < 0) { s = error_nomem("output-layer solve"); break; }
            rep->heads_refit += refit_of[c];
            rep->heads_improved += taken_of[c] > 0;
            rep->steps += taken_of[c];
        }
    }
    mem_free(order); mem_free(taken_of); mem_free(refit_of);
    if (s == NEUV_OK) {
        block all = {st.all_faces, st.all_verts, d->nf, d->nv};
        rep->energy_after = block_energy(d, &all, st.uv, st.sigma, NULL, NULL);
    }
    solve_state_free(&st);
    mem_free(shared);
    return s;
}

neuv_status param_output_solve_head_from(const param_mlp *f, const param_solve_data *d, double anchor, int steps,
                                         const float *start, float *head, param_solve_report *rep)
{
    param_solve_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    neuv_status s = check_f(f, anchor);
    if (s != NEUV_OK) return s;
    if (d->n_charts != 1) return error_set(NEUV_ERR_INPUT, "a head is solved from a start on one chart at a time");
    int n = 2 * (param_mlp_head_width(f) + 1);
    double *theta = mem_alloc(sizeof(double) * (size_t)n);
    if (!theta) return error_nomem("output-layer solve");
    for (int i = 0; i < n; i++) theta[i] = start[i];
    solve_state st;
    s = solve_state_init(&st, f, d, anchor, 1, theta);
    block all = {st.all_faces, st.all_verts, d->nf, d->nv};
    if (s == NEUV_OK) rep->energy_before = block_energy(d, &all, st.uv, st.sigma, NULL, NULL);
    int taken = s == NEUV_OK && d->nf > 0 ? solve_block(&st, &all, anchor, steps, theta) : 0;
    if (taken < 0) s = error_nomem("output-layer solve");
    if (s == NEUV_OK) {
        rep->steps = taken;
        rep->heads_improved = taken > 0;
        rep->energy_after = block_energy(d, &all, st.uv, st.sigma, NULL, NULL);
        for (int i = 0; i < n; i++) head[i] = (float)theta[i];
    }
    solve_state_free(&st);
    mem_free(theta);
    return s;
}

void param_heads_apply(const param_mlp *f, const float *hidden, int n, const int *head_of, const float *heads,
                       float *uv)
{
    int H = param_mlp_head_width(f), K = H + 1, hs = 2 * K;
    for (int i = 0; i < n; i++) {
        const float *p = hidden + (size_t)i * H, *t = heads + (size_t)head_of[i] * hs;
        for (int j = 0; j < 2; j++) {
            double acc = t[j * K + H];
            for (int k = 0; k < H; k++) acc += (double)p[k] * t[j * K + k];
            uv[2 * i + j] = (float)tanh(acc);
        }
    }
}

neuv_status param_output_solve_inverse(param_mlp *g, const param_mlp *f, const float *heads,
                                       const param_solve_data *d)
{
    if (g->depth < 2 || g->out != 3 || f->depth < 2)
        return error_set(NEUV_ERR_INPUT, "output-layer solve needs hidden layers (inverse: 3 outputs)");
    int H = g->width, K = H + 1, nv = d->nv, F = heads ? param_mlp_head_width(f) : f->width;
    nn_linear *out = &g->rest[g->depth - 2];
    float *uvf = mem_alloc(sizeof(float) * 2 * (size_t)nv), *hf = mem_alloc(sizeof(float) * (size_t)nv * F);
    float *phi = mem_alloc(sizeof(float) * (size_t)nv * H);
    double *rhs = mem_calloc((size_t)K * 3, sizeof(double));
    normal_eq q = {0};
    neuv_status s = NEUV_OK;
    if (!uvf || !hf || !phi || !rhs) { s = error_nomem("output-layer solve"); goto done; }
    /* MLP_f's outputs at the vertices, then MLP_f⁻¹'s hidden layer there. */
    if ((s = hidden_at(f, d, d->f_in, d->f_in_dim, heads != NULL, hf)) != NEUV_OK) goto done;
    if (heads) {
        param_heads_apply(f, hf, nv, d->vchart, heads, uvf);
    } else {
        const nn_linear *fo = &f->rest[f->depth - 2];
        for (int v = 0; v < nv; v++)
            for (int j = 0; j < 2; j++) {
                double acc = fo->b->data[j];
                for (int i = 0; i < F; i++) acc += (double)hf[(size_t)v * F + i] * fo->w->data[(size_t)i * 2 + j];
                uvf[2 * v + j] = (float)tanh(acc);
            }
    }
    if ((s = hidden_at(g, d, uvf, 2, 0, phi)) != NEUV_OK) goto done;
    /* Least squares in tanh's pre-image, each row weighted by the smallest
     * tanh' of its targets (a first-order match of the error after tanh). */
    if ((s = normal_eq_init(&q, K, 1024)) != NEUV_OK) goto done;
    for (int v = 0; v < nv; v++) {
        double *c, *r = normal_eq_row(&q, &c), w = 1;
        for (int j = 0; j < 3; j++) {
            double x = d->x[3 * v + j];
            if (1 - x * x < w) w = 1 - x * x;
        }
        if (!(w > 1e-6)) w = 1e-6;
        for (int i = 0; i < H; i++) r[i] = w * (double)phi[(size_t)v * H + i];
        r[H] = w;
        for (int j = 0; j < 3; j++) {
            double x = d->x[3 * v + j];
            if (x > 0.999999) x = 0.999999;
            if (x < -0.999999) x = -0.999999;
            double zt = atanh(x);
            for (int i = 0; i < K; i++) rhs[(size_t)i * 3 + j] += r[i] * w * zt;
        }
    }
    if (normal_eq_solve(&q, 3, rhs) != 0) goto done; /* keep the weights Adam left */
    for (int j = 0; j < 3; j++) {
        for (int i = 0; i < H; i++) out->w->data[(size_t)i * 3 + j] = (float)rhs[(size_t)i * 3 + j];
        out->b->data[j] = (float)rhs[(size_t)H * 3 + j];
    }
done:
    normal_eq_free(&q);
    mem_free(uvf); mem_free(hf); mem_free(phi); mem_free(rhs);
    return s;
}

double param_output_solve_gradient_error(const param_mlp *f, const param_solve_data *d, double anchor, int n_probe)
{
    if (check_f(f, anchor) != NEUV_OK) return INFINITY;
    int H = f->width, n = 2 * (H + 1);
    double *theta = mem_alloc(sizeof(double) * (size_t)n), *grad = mem_alloc(sizeof(double) * (size_t)n);
    solve_state st;
    normal_eq q = {0};
    double worst = INFINITY;
    if (!theta || !grad) goto out;
    theta_from_layer(&f->rest[f->depth - 2], H, theta);
    if (solve_state_init(&st, f, d, anchor, 0, theta) != NEUV_OK) { solve_state_free(&st); goto out; }
    block all = {st.all_faces, st.all_verts, d->nf, d->nv};
    if (normal_eq_init(&q, n, 0) != NEUV_OK) { solve_state_free(&st); goto out; }
    int mips = d->mips_steps > 0;
    vertex_eq_reset(&st.eq, all.verts, all.nv);
    if (mips) mips_rows(d, &all, st.z, st.uv, st.uv0, st.mv, st.sigma, anchor, &st.eq);
    else gauss_newton_rows(d, &all, st.z, st.uv, st.uv0, st.mv, st.sigma, st.fold_s2, anchor, &st.eq);
    vertex_eq_flush(&st.eq, &(feature_rows){st.phi, H, 1, NULL}, NULL, all.verts, all.nv, &q);
    /* The linearization is exact at θ: ∇E = 2 (A θ − g), A symmetric (upper triangle stored). */
    cblas_dsymv(CblasRowMajor, CblasUpper, n, 2.0, q.a, n, theta, 1, 0.0, grad, 1);
    for (int i = 0; i < n; i++) grad[i] -= 2 * q.g[i];
    double scale = 0;
    for (int i = 0; i < n; i++) scale = fmax(scale, fabs(grad[i]));
    worst = 0;
    for (int k = 0; k < n_probe && k < n; k++) {
        int i = (int)(((long)k * 7919) % n);
        double h = 1e-6, keep = theta[i], e[2];
        for (int sgn = 0; sgn < 2; sgn++) {
            theta[i] = keep + (sgn ? -h : h);
            map_block(st.phi, H, theta, &all, st.tz, st.tuv);
            e[sgn] = block_objective(&st, &all, st.tuv, mips, anchor, NULL);
        }
        theta[i] = keep;
        double fd = (e[0] - e[1]) / (2 * h);
        worst = fmax(worst, fabs(fd - grad[i]) / (scale > 0 ? scale : 1));
    }
    solve_state_free(&st);
out:
    normal_eq_free(&q);
    mem_free(theta); mem_free(grad);
    return worst;
}

double param_output_solve_dual_error(const param_mlp *f, const param_solve_data *d, double anchor)
{
    if (check_f(f, anchor) != NEUV_OK) return INFINITY;
    int H = f->width, n = 2 * (H + 1);
    double *theta = mem_alloc(sizeof(double) * (size_t)n), *dual = mem_alloc(sizeof(double) * (size_t)n);
    solve_state st;
    normal_eq q = {0};
    dual_eq dq = {0};
    double worst = INFINITY;
    block all = {0};
    if (!theta || !dual) goto out;
    theta_from_layer(&f->rest[f->depth - 2], H, theta);
    if (solve_state_init(&st, f, d, anchor, 0, theta) != NEUV_OK) { solve_state_free(&st); goto out; }
    all = (block){st.all_faces, st.all_verts, d->nf, d->nv};
    if (normal_eq_init(&q, n, 0) != NEUV_OK || dual_eq_init(&dq, st.local, st.phi, H, &all) != NEUV_OK) {
        solve_state_free(&st);
        goto out;
    }
    vertex_eq_reset(&st.eq, all.verts, all.nv);
    if (d->mips_steps > 0) mips_rows(d, &all, st.z, st.uv, st.uv0, st.mv, st.sigma, anchor, &st.eq);
    else gauss_newton_rows(d, &all, st.z, st.uv, st.uv0, st.mv, st.sigma, st.fold_s2, anchor, &st.eq);
    if (dual_eq_solve(&dq, &st.eq, &all, dual) == 0) {
        vertex_eq_flush(&st.eq, &(feature_rows){st.phi, H, 1, NULL}, NULL, all.verts, all.nv, &q);
        if (normal_eq_solve(&q, 0, NULL) == 0) {
            double scale = 0, diff = 0;
            for (int i = 0; i < n; i++) {
                scale = fmax(scale, fabs(q.g[i]));
                diff = fmax(diff, fabs(q.g[i] - dual[i]));
            }
            worst = diff / (scale > 0 ? scale : 1);
        }
    }
    dual_eq_free(&dq, &all);
    solve_state_free(&st);
out:
    normal_eq_free(&q);
    mem_free(theta); mem_free(dual);
    return worst;
}

double param_output_solve_reduced_error(const param_mlp *f, const param_solve_data *d, double anchor, double rank_tol,
                                       int *rank)
{
    if (rank) *rank = 0;
    if (check_f(f, anchor) != NEUV_OK || param_mlp_head_width(f) <= 0) return INFINITY;
    int H = param_mlp_head_width(f), n = 2 * (H + 1);
    double *theta = mem_calloc((size_t)n, sizeof(double)), *red = mem_alloc(sizeof(double) * (size_t)n);
    solve_state st;
    normal_eq q = {0};
    reduced_eq rq = {0};
    double worst = INFINITY;
    block all = {0};
    int got = 0;
    if (!theta || !red) goto out;
    head_from_shared_layer(f, theta); /* the heads' start */
    if (solve_state_init(&st, f, d, anchor, 1, theta) != NEUV_OK) { solve_state_free(&st); goto out; }
    all = (block){st.all_faces, st.all_verts, d->nf, d->nv};
    got = normal_eq_init(&q, n, 0) == NEUV_OK ? reduced_eq_init(&rq, &st, &all, rank_tol) : -1;
    if (got == 1) {
        if (rank) *rank = rq.r;
        reduced_eq_start(&rq, &all, theta, st.z);
        vertex_eq_reset(&st.eq, all.verts, all.nv);
        if (d->mips_steps > 0) mips_rows(d, &all, st.z, st.uv, st.uv0, st.mv, st.sigma, anchor, &st.eq);
        else gauss_newton_rows(d, &all, st.z, st.uv, st.uv0, st.mv, st.sigma, st.fold_s2, anchor, &st.eq);
        vertex_eq_flush(&st.eq, &(feature_rows){st.phi, H, 1, NULL}, NULL, all.verts, all.nv, &q);
        if (normal_eq_solve(&q, 0, NULL) == 0 && reduced_eq_solve(&rq, &st.eq, &all, red) == 0) {
            /* Both steps' maps (pre-tanh) at the vertices, against the
             * start's: the full step's (q.g) in the trial buffers, the
             * reduced one's over the start's once it is kept. */
            double *z0 = mem_alloc(sizeof(double) * 2 * (size_t)d->nv), step = 0, diff = 0;
            if (z0) {
                memcpy(z0, st.z, sizeof(double) * 2 * (size_t)d->nv);
                map_block(st.phi, H, q.g, &all, st.tz, st.tuv);
                map_block(st.phi, H, red, &all, st.z, st.uv);
                for (int i = 0; i < 2 * d->nv; i++) {
                    step = fmax(step, fabs(st.tz[i] - z0[i]));
                    diff = fmax(diff, fabs(st.tz[i] - st.z[i]));
                }
                worst = diff / (step > 0 ? step : 1);
                mem_free(z0);
            }
        }
    }
    if (got == 1) reduced_eq_free(&rq, &all);
    solve_state_free(&st);
out:
    normal_eq_free(&q);
    mem_free(theta); mem_free(red);
    return worst;
}

typedef struct edge_key { int a, b, id; } edge_key;

static int edge_key_cmp(const void *p, const void *q)
{
    const edge_key *x = p, *y = q;
    if (x->a != y->a) return x->a < y->a ? -1 : 1;
    if (x->b != y->b) return x->b < y->b ? -1 : 1;
    return (x->id > y->id) - (x->id < y->id);
}

/* The share of a face's conformal energy its sub-faces carry, in a chart of
 * nv vertices (param_solve_subdivide). */
static double chart_energy_share(int nv, double energy_share, int dense_vertices)
{
    return dense_vertices > 0 && nv >= dense_vertices ? 0 : energy_share;
}

void param_solve_subdivided_free(param_solve_subdivided *sd)
{
    mem_free(sd->x); mem_free(sd->f_in); mem_free(sd->vchart); mem_free(sd->tri); mem_free(sd->fchart);
    mem_free(sd->frame_inv); mem_free(sd->face_w); mem_free(sd->fold_w);
    memset(sd, 0, sizeof *sd);
}

neuv_status param_solve_subdivide(const param_solve_data *d, double energy_share, int dense_vertices,
                                  param_solve_subdivided *out)
{
    memset(out, 0, sizeof *out);
    if (d->psi_per_vertex) return error_set(NEUV_ERR_INPUT, "subdivided solve data needs a pooled ψ");
    int nv = d->nv, nf = d->nf, dim = d->f_in_dim;
    edge_key *e = mem_alloc(sizeof *e * 3 * (size_t)(nf > 0 ? nf : 1));
    int *mid = mem_alloc(sizeof(int) * 3 * (size_t)(nf > 0 ? nf : 1));
    if (!e || !mid) { mem_free(e); mem_free(mid); return error_nomem("subdivided solve data"); }
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++) {
            int a = d->tri[3 * f + k], b = d->tri[3 * f + (k + 1) % 3];
            e[3 * f + k] = (edge_key){a < b ? a : b, a < b ? b : a, 3 * f + k};
        }
    qsort(e, 3 * (size_t)nf, sizeof *e, edge_key_cmp);
    int ne = 0;
    for (int i = 0; i < 3 * nf; i++) {
        if (i > 0 && (e[i].a != e[i - 1].a || e[i].b != e[i - 1].b)) ne++;
        mid[e[i].id] = nv + ne; /* the midpoint of face id/3's edge id%3 */
    }
    if (nf > 0) ne++;
    int NV = nv + ne, NF = 5 * nf;
    out->x = mem_alloc(sizeof(float) * 3 * (size_t)NV);
    out->f_in = d->f_in == d->x ? NULL : mem_alloc(sizeof(float) * (size_t)dim * NV);
    out->vchart = mem_alloc(sizeof(int) * (size_t)NV);
    out->tri = mem_alloc(sizeof(int) * 3 * (size_t)NF);
    out->fchart = mem_alloc(sizeof(int) * (size_t)NF);
    out->frame_inv = mem_alloc(sizeof(float) * 4 * (size_t)NF);
    out->face_w = mem_alloc(sizeof(float) * (size_t)NF);
    out->fold_w = mem_alloc(sizeof(float) * (size_t)NF);
    double *pos = mem_alloc(sizeof(double) * 3 * (size_t)NV);
    int *chart_nv = mem_calloc((size_t)d->n_charts + 1, sizeof(int));
    neuv_status s = NEUV_OK;
    if (!chart_nv || !out->x || (d->f_in != d->x && !out->f_in) || !out->vchart || !out->tri || !out->fchart || !out->frame_inv ||
        !out->face_w || !out->fold_w || !pos) {
        s = error_nomem("subdivided solve data");
        goto done;
    }
    memcpy(out->x, d->x, sizeof(float) * 3 * (size_t)nv);
    if (out->f_in) memcpy(out->f_in, d->f_in, sizeof(float) * (size_t)dim * nv);
    memcpy(out->vchart, d->vchart, sizeof(int) * (size_t)nv);
    for (int i = 0; i < 3 * nf; i++) {
        int m = mid[i], f = i / 3, a = d->tri[i], b = d->tri[3 * f + (i % 3 + 1) % 3];
        for (int q = 0; q < 3; q++) out->x[3 * m + q] = 0.5f * (d->x[3 * a + q] + d->x[3 * b + q]);
        if (out->f_in)
            for (int q = 0; q < dim; q++)
                out->f_in[(size_t)m * dim + q] = 0.5f * (d->f_in[(size_t)a * dim + q] + d->f_in[(size_t)b * dim + q]);
        out->vchart[m] = d->vchart[a];
    }
    for (int v = 0; v < NV; v++)
        for (int q = 0; q < 3; q++) pos[3 * v + q] = out->x[3 * v + q];
    memcpy(out->tri, d->tri, sizeof(int) * 3 * (size_t)nf);
    memcpy(out->fchart, d->fchart, sizeof(int) * (size_t)nf);
    memcpy(out->frame_inv, d->frame_inv, sizeof(float) * 4 * (size_t)nf);
    for (int v = 0; v < nv; v++)
        if (d->vchart[v] >= 0 && d->vchart[v] < d->n_charts) chart_nv[d->vchart[v]]++;
    for (int f = 0; f < nf; f++) {
        double share = chart_energy_share(chart_nv[d->fchart[f]], energy_share, dense_vertices);
        out->face_w[f] = (float)((1 - share) * d->face_w[f]);
    }
    memcpy(out->fold_w, d->fold_w ? d->fold_w : d->face_w, sizeof(float) * (size_t)nf);
    for (int f = 0; f < nf; f++) {
        const int *t = d->tri + 3 * f;
        int m01 = mid[3 * f], m12 = mid[3 * f + 1], m20 = mid[3 * f + 2];
        int sub[4][3] = {{t[0], m01, m20}, {m01, t[1], m12}, {m20, m12, t[2]}, {m01, m12, m20}};
        for (int k = 0; k < 4; k++) {
            int g = nf + 4 * f + k;
            memcpy(out->tri + 3 * g, sub[k], sizeof sub[k]);
            out->fchart[g] = d->fchart[f];
            double share = chart_energy_share(chart_nv[d->fchart[f]], energy_share, dense_vertices);
            out->face_w[g] = (float)(0.25 * share * d->face_w[f]);
            out->fold_w[g] = 0.25f * (d->fold_w ? d->fold_w[f] : d->face_w[f]);
        }
    }
    {
        param_corners c;
        float *w = mem_alloc(sizeof(float) * 4 * (size_t)(nf > 0 ? nf : 1));
        if (!w || param_corners_build(out->tri + 3 * (size_t)nf, 4 * nf, &c) != NEUV_OK) {
            mem_free(w);
            s = error_nomem("subdivided solve data");
            goto done;
        }
        param_conformal_targets(pos, &c, out->frame_inv + 4 * (size_t)nf, w);
        param_corners_free(&c);
        mem_free(w);
    }
    out->d = *d;
    out->d.nv = NV;
    out->d.nf = NF;
    out->d.x = out->x;
    out->d.f_in = out->f_in ? out->f_in : out->x;
    out->d.vchart = out->vchart;
    out->d.tri = out->tri;
    out->d.fchart = out->fchart;
    out->d.frame_inv = out->frame_inv;
    out->d.face_w = out->face_w;
    out->d.fold_w = out->fold_w;
done:
    mem_free(e); mem_free(mid); mem_free(pos); mem_free(chart_nv);
    if (s != NEUV_OK) param_solve_subdivided_free(out);
    return s;
}
