/* The heat method for geodesic distance (Crane, Weischedel, Wardetzky 2013,
 * "Geodesics in Heat: A New Approach to Computing Distance Based on Heat
 * Flow", Algorithm 1), on systems factored once with CHOLMOD. */
#include "geometry/heat_geodesics.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/union_find.h"
#include "geometry/cholesky.h"
#include "geometry/cotan_laplacian.h"
#include "geometry/lumped_mass.h"
#include "geometry/sparse_matrix.h"

struct heat_geodesics {
    int nv, nf;
    int *tri;              /* #F by 3, copied from the mesh */
    /* Per face: grad[9] holds (N × e_c) / (2A) for each corner c, so that
     * ∇u = Σ_c u_c grad_c on the face; div[9] holds, for each corner c,
     * ½ (cot θ_k (p_j - p_c) + cot θ_j (p_k - p_c)), so that the integrated
     * divergence at c gains div_c · X (the paper's eq. for ∇·X). */
    double *grad, *div;
    int *component;        /* #V connected component per vertex */
    int ncomponents;
    int *interior;         /* #V index into the Dirichlet system, or -1 on the boundary */
    int ninterior;
    int has_boundary;
    double t;
    cholesky *heat;        /* M + tL */
    cholesky *heat_dirichlet; /* (M + tL) restricted to interior vertices, NULL if closed */
    cholesky *poisson;     /* L with one vertex per component pinned */
    /* Workspace for one block of HEAT_GEODESICS_BLOCK right-hand sides. */
    double *w_src, *w_heat, *w_int, *w_int2;
    unsigned char *w_reached; /* #components */
};

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Marks vertices on boundary edges (edges with exactly one incident face). */
static neuv_status mark_boundary(const neuv_mesh *m, unsigned char *on_boundary)
{
    size_t ne = (size_t)m->nf * 3;
    uint64_t *keys = mem_alloc(sizeof *keys * (ne ? ne : 1));
    if (!keys) return error_nomem("edge list");
    for (int f = 0; f < m->nf; f++)
        for (int c = 0; c < 3; c++) {
            uint64_t a = (uint32_t)m->tri[3 * f + c], b = (uint32_t)m->tri[3 * f + (c + 1) % 3];
            keys[3 * (size_t)f + c] = a < b ? (a << 32 | b) : (b << 32 | a);
        }
    qsort(keys, ne, sizeof *keys, cmp_u64);
    for (size_t k = 0; k < ne;) {
        size_t e = k;
        while (e < ne && keys[e] == keys[k]) e++;
        if (e - k == 1) {
            on_boundary[keys[k] >> 32] = 1;
            on_boundary[keys[k] & 0xffffffffu] = 1;
        }
        k = e;
    }
    mem_free(keys);
    return NEUV_OK;
}

/* Per-face gradient and divergence coefficients (see struct comment). */
static void face_operators(const neuv_mesh *m, int f, double area_floor, double *grad, double *div)
{
    const int *v = m->tri + 3 * f;
    const double *p[3] = {m->pos + 3 * v[0], m->pos + 3 * v[1], m->pos + 3 * v[2]};
    double e[3][3]; /* e[c]: edge opposite corner c, counter-clockwise: p[c+2] - p[c+1] */
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 3; k++) e[c][k] = p[(c + 2) % 3][k] - p[(c + 1) % 3][k];
    /* n = e[2] × (-e[1]) = (p1 - p0) × (p2 - p0) */
    double n[3] = {e[1][1] * e[2][2] - e[1][2] * e[2][1],
                   e[1][2] * e[2][0] - e[1][0] * e[2][2],
                   e[1][0] * e[2][1] - e[1][1] * e[2][0]};
    double twice_area = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(twice_area > area_floor)) {
        /* A degenerate face carries no gradient; leaving it out keeps the
         * divergence finite and still summing to zero. */
        memset(grad, 0, 9 * sizeof *grad);
        memset(div, 0, 9 * sizeof *div);
        return;
    }
    for (int k = 0; k < 3; k++) n[k] /= twice_area;
    for (int c = 0; c < 3; c++) {
        double *g = grad + 3 * c;
        g[0] = (n[1] * e[c][2] - n[2] * e[c][1]) / twice_area;
        g[1] = (n[2] * e[c][0] - n[0] * e[c][2]) / twice_area;
        g[2] = (n[0] * e[c][1] - n[1] * e[c][0]) / twice_area;
    }
    /* The edges leaving corner c are e[c+2] and -e[c+1], so the cotangent of
     * the angle at c is -(e[c+2]·e[c+1]) / (2A). */
    double cot[3];
    for (int c = 0; c < 3; c++) {
        const double *a = e[(c + 2) % 3], *b = e[(c + 1) % 3];
        cot[c] = -(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / twice_area;
    }
    for (int c = 0; c < 3; c++) {
        int j = (c + 1) % 3, k = (c + 2) % 3;
        for (int d = 0; d < 3; d++)
            div[3 * c + d] = 0.5 * (cot[k] * (p[j][d] - p[c][d]) + cot[j] * (p[k][d] - p[c][d]));
    }
}

/* Copies the entries of a whose row and column both map (map[] >= 0) into a
 * new matrix over the mapped indices, adding diag_add[i] to the diagonal. */
static neuv_status build_system(const sparse_matrix *a, double scale, const double *diag_add,
                                const int *map, int n, sparse_matrix *out)
{
    triplet_list t;
    neuv_status s = triplets_init(&t, n, n, sparse_nnz(a) + (size_t)a->rows);
    if (s) return s;
    for (int r = 0; r < a->rows && !s; r++) {
        int mr = map ? map[r] : r;
        if (mr < 0) continue;
        for (int p = a->row_start[r]; p < a->row_start[r + 1] && !s; p++) {
            int mc = map ? map[a->col[p]] : a->col[p];
            if (mc >= 0) s = triplets_add(&t, mr, mc, scale * a->val[p]);
        }
        if (!s && diag_add[r] != 0.0) s = triplets_add(&t, mr, mr, diag_add[r]);
    }
    if (!s) s = sparse_from_triplets(&t, out);
    triplets_free(&t);
    return s;
}

/* Factors one of the method's systems; they are definite by construction, so
 * a failure here is an internal (numerical) one, not bad input. */
static neuv_status factor(const sparse_matrix *a, const char *what, cholesky **out)
{
    neuv_status s = cholesky_factor(a, out);
    if (s == NEUV_ERR_INPUT) {
        char why[256];
        snprintf(why, sizeof why, "%s", neuv_last_error());
        return error_set(NEUV_ERR_INTERNAL, "geodesics: %s system: %s", what, why);
    }
    return s;
}

neuv_status heat_geodesics_create(const neuv_mesh *m, double t_factor, heat_geodesics **out)
{
    *out = NULL;
    if (!m || m->nv <= 0 || m->nf <= 0)
        return error_set(NEUV_ERR_INPUT, "geodesics need a mesh with faces");
    if (!(t_factor > 0)) t_factor = 1.0;
    for (int k = 0; k < 3 * m->nf; k++)
        if (m->tri[k] < 0 || m->tri[k] >= m->nv)
            return error_set(NEUV_ERR_INPUT, "face %d has vertex index %d out of range", k / 3, m->tri[k]);

    heat_geodesics *g = mem_calloc(1, sizeof *g);
    if (!g) return error_nomem("heat geodesics");
    g->nv = m->nv;
    g->nf = m->nf;
    neuv_status s = NEUV_OK;
    sparse_matrix lap = {0}, sys = {0};
    double *mass = NULL, *diag = NULL;
    unsigned char *on_boundary = NULL;
    union_find uf = {0};
    int uf_ok = 0;

    g->tri = mem_alloc(sizeof(int) * 3 * (size_t)m->nf);
    g->grad = mem_alloc(sizeof(double) * 9 * (size_t)m->nf);
    g->div = mem_alloc(sizeof(double) * 9 * (size_t)m->nf);
    g->component = mem_alloc(sizeof(int) * (size_t)m->nv);
    g->interior = mem_alloc(sizeof(int) * (size_t)m->nv);
    mass = mem_alloc(sizeof(double) * (size_t)m->nv);
    diag = mem_calloc((size_t)m->nv, sizeof(double));
    on_boundary = mem_calloc((size_t)m->nv, 1);
    size_t block = (size_t)m->nv * HEAT_GEODESICS_BLOCK;
    g->w_src = mem_alloc(sizeof(double) * block);
    g->w_heat = mem_alloc(sizeof(double) * block);
    if (!g->tri || !g->grad || !g->div || !g->component || !g->interior || !mass || !diag ||
        !on_boundary || !g->w_src || !g->w_heat) {
        s = error_nomem("heat geodesics");
        goto done;
    }
    memcpy(g->tri, m->tri, sizeof(int) * 3 * (size_t)m->nf);

    /* t = h², h the mean edge length (paper section 3.2.4, m = 1). */
    double sum_len = 0.0, sum_len2 = 0.0;
    for (int f = 0; f < m->nf; f++)
        for (int c = 0; c < 3; c++) {
            const double *a = m->pos + 3 * m->tri[3 * f + c], *b = m->pos + 3 * m->tri[3 * f + (c + 1) % 3];
            double l2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
            sum_len += sqrt(l2);
            sum_len2 += l2;
        }
    double h = sum_len / (3.0 * m->nf);
    if (!(h > 0) || !isfinite(h)) {
        s = error_set(NEUV_ERR_INPUT, "geodesics: mean edge length is %g", h);
        goto done;
    }
    g->t = t_factor * h * h;
    double area_floor = 1e-12 * sum_len2 / (3.0 * m->nf);
    for (int f = 0; f < m->nf; f++)
        face_operators(m, f, area_floor, g->grad + 9 * (size_t)f, g->div + 9 * (size_t)f);

    if (uf_init(&uf, m->nv)) { s = error_nomem("vertex components"); goto done; }
    uf_ok = 1;
    for (int f = 0; f < m->nf; f++) {
        uf_union(&uf, m->tri[3 * f], m->tri[3 * f + 1]);
        uf_union(&uf, m->tri[3 * f], m->tri[3 * f + 2]);
    }
    g->ncomponents = uf_labels(&uf, g->component);
    if (g->ncomponents < 0) { g->ncomponents = 0; s = error_nomem("vertex components"); goto done; }
    g->w_reached = mem_calloc((size_t)g->ncomponents, 1);
    if (!g->w_reached) { s = error_nomem("heat geodesics"); goto done; }

    if ((s = cotan_laplacian(m, &lap))) goto done;
    lumped_mass(m, mass);

    /* Heat flow, Neumann: M + tL. A vertex used by no face has an empty row;
     * a unit diagonal keeps it decoupled and the system definite. */
    for (int i = 0; i < m->nv; i++) diag[i] = mass[i] > 0 ? mass[i] : 1.0;
    if ((s = build_system(&lap, g->t, diag, NULL, m->nv, &sys))) goto done;
    s = factor(&sys, "heat", &g->heat);
    sparse_free(&sys);
    if (s) goto done;

    /* Heat flow, Dirichlet: the same operator on interior vertices only. */
    if ((s = mark_boundary(m, on_boundary))) goto done;
    for (int i = 0; i < m->nv; i++) {
        g->has_boundary |= on_boundary[i];
        g->interior[i] = on_boundary[i] ? -1 : g->ninterior++;
    }
    if (g->has_boundary && g->ninterior > 0) {
        if ((s = build_system(&lap, g->t, diag, g->interior, g->ninterior, &sys))) goto done;
        s = factor(&sys, "Dirichlet heat", &g->heat_dirichlet);
        sparse_free(&sys);
        if (s) goto done;
        g->w_int = mem_alloc(sizeof(double) * (size_t)g->ninterior * HEAT_GEODESICS_BLOCK);
        g->w_int2 = mem_alloc(sizeof(double) * (size_t)g->ninterior * HEAT_GEODESICS_BLOCK);
        if (!g->w_int || !g->w_int2) { s = error_nomem("heat geodesics"); goto done; }
    }

    /* Poisson: L is singular (constants on each component). Doubling the
     * diagonal of each component's first vertex p adds L_pp e_p e_pᵀ, which
     * makes the system definite; since the right-hand side sums to zero on
     * every component, the solution has φ_p = 0 — the pinned solution. */
    memset(diag, 0, sizeof(double) * (size_t)m->nv);
    {
        unsigned char *pinned = g->w_reached;
        for (int i = 0; i < m->nv; i++) {
            int c = g->component[i];
            if (pinned[c]) continue;
            pinned[c] = 1;
            double lii = 0.0;
            for (int p = lap.row_start[i]; p < lap.row_start[i + 1]; p++)
                if (lap.col[p] == i) lii = lap.val[p];
            diag[i] = lii > 0 ? lii : 1.0;
        }
        memset(pinned, 0, (size_t)g->ncomponents);
    }
    if ((s = build_system(&lap, 1.0, diag, NULL, m->nv, &sys))) goto done;
    s = factor(&sys, "Poisson", &g->poisson);
    sparse_free(&sys);

done:
    sparse_free(&lap);
    mem_free(mass);
    mem_free(diag);
    mem_free(on_boundary);
    if (uf_ok) uf_free(&uf);
    if (s) { heat_geodesics_free(g); return s; }
    *out = g;
    return NEUV_OK;
}

void heat_geodesics_free(heat_geodesics *g)
{
    if (!g) return;
    cholesky_free(g->heat);
    cholesky_free(g->heat_dirichlet);
    cholesky_free(g->poisson);
    mem_free(g->tri); mem_free(g->grad); mem_free(g->div);
    mem_free(g->component); mem_free(g->interior);
    mem_free(g->w_src); mem_free(g->w_heat); mem_free(g->w_int); mem_free(g->w_int2);
    mem_free(g->w_reached);
    mem_free(g);
}

int heat_geodesics_vertex_count(const heat_geodesics *g) { return g->nv; }
double heat_geodesics_time(const heat_geodesics *g) { return g->t; }

/* Steps I-III of Algorithm 1 for k columns: the heat sources are in g->w_src
 * (#V by k); the raw Poisson solution φ (up to a constant per component) is
 * left in g->w_heat. g->w_src is overwritten. */
static neuv_status solve_block(heat_geodesics *g, int k)
{
    const int nv = g->nv;
    double *src = g->w_src, *u = g->w_heat;
    neuv_status s;

    /* I. Heat flow: backward Euler step (M + tL) u = u0. */
    if (g->heat_dirichlet) {
        const int ni = g->ninterior;
        for (int col = 0; col < k; col++)
            for (int i = 0; i < nv; i++)
                if (g->interior[i] >= 0) g->w_int[(size_t)col * ni + g->interior[i]] = src[(size_t)col * nv + i];
        if ((s = cholesky_solve(g->heat_dirichlet, g->w_int, g->w_int2, k))) return s;
    }
    if ((s = cholesky_solve(g->heat, src, u, k))) return s;
    if (g->heat_dirichlet) {
        /* Average the Neumann and Dirichlet solutions (section 3.2.2); a
         * column whose sources all lie on the boundary has no Dirichlet part. */
        const int ni = g->ninterior;
        for (int col = 0; col < k; col++) {
            double interior_mass = 0.0;
            for (int i = 0; i < ni; i++) interior_mass += fabs(g->w_int[(size_t)col * ni + i]);
            if (interior_mass == 0.0) continue;
            double *uc = u + (size_t)col * nv;
            const double *ud = g->w_int2 + (size_t)col * ni;
            for (int i = 0; i < nv; i++)
                uc[i] = 0.5 * (uc[i] + (g->interior[i] >= 0 ? ud[g->interior[i]] : 0.0));
        }
    }

    /* II. X = -∇u/|∇u| per face, and III. its integrated divergence,
     * accumulated straight into the right-hand side (X is never stored). */
    memset(src, 0, sizeof(double) * (size_t)nv * (size_t)k);
    for (int f = 0; f < g->nf; f++) {
        const int *v = g->tri + 3 * f;
        const double *gr = g->grad + 9 * (size_t)f, *dv = g->div + 9 * (size_t)f;
        for (int col = 0; col < k; col++) {
            const double *uc = u + (size_t)col * nv;
            double gx = 0, gy = 0, gz = 0;
            for (int c = 0; c < 3; c++) {
                gx += uc[v[c]] * gr[3 * c];
                gy += uc[v[c]] * gr[3 * c + 1];
                gz += uc[v[c]] * gr[3 * c + 2];
            }
            double len = sqrt(gx * gx + gy * gy + gz * gz);
            if (!(len > 0) || !isfinite(len)) continue; /* no heat here: no direction */
            double x = -gx / len, y = -gy / len, z = -gz / len;
            double *bc = src + (size_t)col * nv;
            for (int c = 0; c < 3; c++)
                bc[v[c]] += dv[3 * c] * x + dv[3 * c + 1] * y + dv[3 * c + 2] * z;
        }
    }

    /* IV. Poisson: Δφ = ∇·X, i.e. L φ = -b with L positive semi-definite. */
    for (size_t i = 0; i < (size_t)nv * (size_t)k; i++) src[i] = -src[i];
    return cholesky_solve(g->poisson, src, u, k);
}

/* Shifts column phi so the smallest value over its sources in each component
 * is 0; components without a source get INFINITY; negatives clamp to 0. */
static void shift_to_sources(heat_geodesics *g, double *phi, const int *sources, int n)
{
    double *lo = g->w_src; /* one value per component; w_src is free after solve_block */
    unsigned char *reached = g->w_reached;
    memset(reached, 0, (size_t)g->ncomponents);
    for (int k = 0; k < n; k++) {
        int c = g->component[sources[k]];
        double v = phi[sources[k]];
        if (!reached[c] || v < lo[c]) lo[c] = v;
        reached[c] = 1;
    }
    for (int i = 0; i < g->nv; i++) {
        int c = g->component[i];
        if (!reached[c]) { phi[i] = INFINITY; continue; }
        double d = phi[i] - lo[c];
        phi[i] = d > 0 ? d : 0.0;
    }
}

static neuv_status check_vertices(const heat_geodesics *g, const int *v, int n)
{
    if (n <= 0) return error_set(NEUV_ERR_INPUT, "geodesics need at least one source");
    for (int k = 0; k < n; k++)
        if (v[k] < 0 || v[k] >= g->nv)
            return error_set(NEUV_ERR_INPUT, "source vertex %d is out of range (the mesh has %d vertices)", v[k], g->nv);
    return NEUV_OK;
}

neuv_status heat_geodesics_nearest(heat_geodesics *g, const int *sources, int nsources, double *dist)
{
    neuv_status s = check_vertices(g, sources, nsources);
    if (s) return s;
    memset(g->w_src, 0, sizeof(double) * (size_t)g->nv);
    for (int k = 0; k < nsources; k++) g->w_src[sources[k]] = 1.0;
    if ((s = solve_block(g, 1))) return s;
    memcpy(dist, g->w_heat, sizeof(double) * (size_t)g->nv);
    shift_to_sources(g, dist, sources, nsources);
    return NEUV_OK;
}

neuv_status heat_geodesics_from_vertex(heat_geodesics *g, int source, double *dist)
{
    return heat_geodesics_nearest(g, &source, 1, dist);
}

neuv_status heat_geodesics_batch(heat_geodesics *g, const int *sources, int nsources, double *dist)
{
    neuv_status s = check_vertices(g, sources, nsources);
    if (s) return s;
    const size_t nv = (size_t)g->nv;
    for (int b0 = 0; b0 < nsources; b0 += HEAT_GEODESICS_BLOCK) {
        int k = nsources - b0 < HEAT_GEODESICS_BLOCK ? nsources - b0 : HEAT_GEODESICS_BLOCK;
        memset(g->w_src, 0, sizeof(double) * nv * (size_t)k);
        for (int c = 0; c < k; c++) g->w_src[(size_t)c * nv + sources[b0 + c]] = 1.0;
        if ((s = solve_block(g, k))) return s;
        for (int c = 0; c < k; c++) {
            double *col = dist + (size_t)(b0 + c) * nv;
            memcpy(col, g->w_heat + (size_t)c * nv, sizeof(double) * nv);
            shift_to_sources(g, col, &sources[b0 + c], 1);
        }
    }
    return NEUV_OK;
}

void geodesic_pairs_free(geodesic_pairs *p)
{
    if (!p) return;
    mem_free(p->i); mem_free(p->j); mem_free(p->d);
    memset(p, 0, sizeof *p);
}

static neuv_status pairs_push(geodesic_pairs *p, int i, int j, double d)
{
    if (p->n == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 1024;
        int *ni = mem_realloc(p->i, sizeof(int) * cap);
        if (ni) p->i = ni;
        int *nj = mem_realloc(p->j, sizeof(int) * cap);
        if (nj) p->j = nj;
        double *nd = mem_realloc(p->d, sizeof(double) * cap);
        if (nd) p->d = nd;
        if (!ni || !nj || !nd) return error_nomem("geodesic pair list");
        p->cap = cap;
    }
    p->i[p->n] = i;
    p->j[p->n] = j;
    p->d[p->n] = d;
    p->n++;
    return NEUV_OK;
}

neuv_status heat_geodesics_pairs_within(heat_geodesics *g, double radius, const int *subset,
                                        int nsubset, geodesic_pairs *out)
{
    neuv_status s;
    int n = subset ? nsubset : g->nv;
    if (subset && (s = check_vertices(g, subset, nsubset))) return s;
    if (!(radius > 0)) return NEUV_OK;
    /* Targets in ascending order so each pair is found once, from its smaller index. */
    int *targets = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    if (!targets) return error_nomem("geodesic pair targets");
    for (int k = 0; k < n; k++) targets[k] = subset ? subset[k] : k;
    if (subset) {
        /* Ascending order and no duplicates, through a mark array (O(V)). */
        unsigned char *mark = mem_calloc((size_t)g->nv, 1);
        if (!mark) { mem_free(targets); return error_nomem("geodesic pair targets"); }
        for (int k = 0; k < n; k++) mark[subset[k]] = 1;
        n = 0;
        for (int v = 0; v < g->nv; v++) if (mark[v]) targets[n++] = v;
        mem_free(mark);
    }
    const size_t nv = (size_t)g->nv;
    s = NEUV_OK;
    for (int b0 = 0; b0 < n && !s; b0 += HEAT_GEODESICS_BLOCK) {
        int k = n - b0 < HEAT_GEODESICS_BLOCK ? n - b0 : HEAT_GEODESICS_BLOCK;
        memset(g->w_src, 0, sizeof(double) * nv * (size_t)k);
        for (int c = 0; c < k; c++) g->w_src[(size_t)c * nv + targets[b0 + c]] = 1.0;
        if ((s = solve_block(g, k))) break;
        for (int c = 0; c < k && !s; c++) {
            int src = targets[b0 + c];
            double *col = g->w_heat + (size_t)c * nv;
            shift_to_sources(g, col, &src, 1);
            for (int q = b0 + c + 1; q < n && !s; q++)
                if (col[targets[q]] < radius) s = pairs_push(out, src, targets[q], col[targets[q]]);
        }
        log_progress("geodesic pairs", (double)(b0 + k) / n, "%zu pairs", out->n);
    }
    mem_free(targets);
    return s;
}

neuv_status heat_geodesics_pairs_from(heat_geodesics *g, double radius, const int *sources, int nsources,
                                      geodesic_pairs *out)
{
    neuv_status s = check_vertices(g, sources, nsources);
    if (s) return s;
    if (!(radius > 0) || nsources <= 0) return NEUV_OK;
    const size_t nv = (size_t)g->nv;
    unsigned char *is_source = mem_calloc(nv, 1);
    if (!is_source) return error_nomem("geodesic pair sources");
    for (int k = 0; k < nsources; k++) {
        if (is_source[sources[k]]) { mem_free(is_source); return error_set(NEUV_ERR_INPUT, "geodesic pairs: source vertex %d given twice", sources[k]); }
        is_source[sources[k]] = 1;
    }
    for (int b0 = 0; b0 < nsources && !s; b0 += HEAT_GEODESICS_BLOCK) {
        int k = nsources - b0 < HEAT_GEODESICS_BLOCK ? nsources - b0 : HEAT_GEODESICS_BLOCK;
        memset(g->w_src, 0, sizeof(double) * nv * (size_t)k);
        for (int c = 0; c < k; c++) g->w_src[(size_t)c * nv + sources[b0 + c]] = 1.0;
        if ((s = solve_block(g, k))) break;
        for (int c = 0; c < k && !s; c++) {
            int src = sources[b0 + c];
            double *col = g->w_heat + (size_t)c * nv;
            shift_to_sources(g, col, &src, 1);
            for (int q = 0; q < (int)nv && !s; q++) {
                if (q == src || !(col[q] < radius) || (is_source[q] && q < src)) continue;
                s = src < q ? pairs_push(out, src, q, col[q]) : pairs_push(out, q, src, col[q]);
            }
        }
        log_progress("geodesic pairs", (double)(b0 + k) / nsources, "%zu pairs", out->n);
    }
    mem_free(is_source);
    return s;
}

neuv_status heat_geodesics_face_distances(heat_geodesics *g, const neuv_mesh *m,
                                          const int *source_faces, int nsources, double *dist)
{
    if (m->nf != g->nf || m->nv != g->nv)
        return error_set(NEUV_ERR_INPUT, "face distances: mesh has %d vertices and %d faces, geodesics were built for %d and %d",
                         m->nv, m->nf, g->nv, g->nf);
    if (nsources <= 0) return error_set(NEUV_ERR_INPUT, "face distances need at least one source face");
    for (int k = 0; k < nsources; k++)
        if (source_faces[k] < 0 || source_faces[k] >= g->nf)
            return error_set(NEUV_ERR_INPUT, "source face %d is out of range (the mesh has %d faces)", source_faces[k], g->nf);
    const size_t nv = (size_t)g->nv, nf = (size_t)g->nf;
    for (int b0 = 0; b0 < nsources; b0 += HEAT_GEODESICS_BLOCK) {
        int k = nsources - b0 < HEAT_GEODESICS_BLOCK ? nsources - b0 : HEAT_GEODESICS_BLOCK;
        memset(g->w_src, 0, sizeof(double) * nv * (size_t)k);
        for (int c = 0; c < k; c++)
            for (int q = 0; q < 3; q++) g->w_src[(size_t)c * nv + g->tri[3 * source_faces[b0 + c] + q]] += 1.0 / 3.0;
        neuv_status s = solve_block(g, k);
        if (s) return s;
        for (int c = 0; c < k; c++) {
            const double *phi = g->w_heat + (size_t)c * nv;
            double *col = dist + (size_t)(b0 + c) * nf;
            const int *sv = g->tri + 3 * source_faces[b0 + c];
            /* The source is the centroid, so its vertices sit at their
             * distance from it, not at 0: anchor their mean there. */
            double cen[3] = {0, 0, 0}, spread = 0;
            for (int q = 0; q < 3; q++)
                for (int d = 0; d < 3; d++) cen[d] += m->pos[3 * sv[q] + d] / 3.0;
            for (int q = 0; q < 3; q++) {
                const double *pq = m->pos + 3 * sv[q];
                spread += sqrt((pq[0] - cen[0]) * (pq[0] - cen[0]) + (pq[1] - cen[1]) * (pq[1] - cen[1]) +
                               (pq[2] - cen[2]) * (pq[2] - cen[2])) / 3.0;
            }
            double zero = (phi[sv[0]] + phi[sv[1]] + phi[sv[2]]) / 3.0 - spread;
            int comp = g->component[sv[0]];
            for (size_t f = 0; f < nf; f++) {
                const int *v = g->tri + 3 * f;
                if (g->component[v[0]] != comp) { col[f] = INFINITY; continue; }
                double d = (phi[v[0]] + phi[v[1]] + phi[v[2]]) / 3.0 - zero;
                col[f] = d > 0 ? d : 0.0;
            }
            col[source_faces[b0 + c]] = 0.0;
        }
    }
    return NEUV_OK;
}

neuv_status heat_geodesics_diameter(heat_geodesics *g, double *diameter)
{
    *diameter = 0.0;
    /* One start per component that has faces; both sweeps of all components
     * go through in blocks of independent right-hand sides. */
    int *start = mem_alloc(sizeof(int) * (size_t)g->ncomponents);
    int *far = mem_alloc(sizeof(int) * (size_t)g->ncomponents);
    double *col = mem_alloc(sizeof(double) * (size_t)g->nv);
    if (!start || !far || !col) { mem_free(start); mem_free(far); mem_free(col); return error_nomem("diameter"); }
    for (int c = 0; c < g->ncomponents; c++) start[c] = -1;
    for (int f = 0; f < g->nf; f++) {
        int v = g->tri[3 * f], c = g->component[v];
        if (start[c] < 0) start[c] = v;
    }
    int n = 0;
    for (int c = 0; c < g->ncomponents; c++) if (start[c] >= 0) start[n++] = start[c];
    neuv_status s = NEUV_OK;
    for (int sweep = 0; sweep < 2 && !s; sweep++) {
        for (int b0 = 0; b0 < n && !s; b0 += HEAT_GEODESICS_BLOCK) {
            int k = n - b0 < HEAT_GEODESICS_BLOCK ? n - b0 : HEAT_GEODESICS_BLOCK;
            const size_t nv = (size_t)g->nv;
            memset(g->w_src, 0, sizeof(double) * nv * (size_t)k);
            for (int c = 0; c < k; c++) g->w_src[(size_t)c * nv + start[b0 + c]] = 1.0;
            if ((s = solve_block(g, k))) break;
            for (int c = 0; c < k; c++) {
                memcpy(col, g->w_heat + (size_t)c * nv, sizeof(double) * nv);
                shift_to_sources(g, col, &start[b0 + c], 1);
                int best = start[b0 + c];
                for (size_t i = 0; i < nv; i++)
                    if (isfinite(col[i]) && col[i] > col[best]) best = (int)i;
                far[b0 + c] = best;
                if (sweep == 1 && col[best] > *diameter) *diameter = col[best];
            }
        }
        memcpy(start, far, sizeof(int) * (size_t)n);
    }
    mem_free(start); mem_free(far); mem_free(col);
    return s;
}
