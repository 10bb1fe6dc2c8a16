#include "remesh/jitter.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "core/rng.h"
#include "mesh/edge_faces.h"
#include "mesh/edge_map.h"
#include "spatial/bvh.h"

#define JITTER_PI 3.14159265358979323846

void jitter_default_options(jitter_options *o)
{
    o->max_offset = 0.3;
    o->flip_probability = 0.5;
    o->flip_max_degrees = 1.0;
    o->feature_degrees = 20.0;
}

static void sub3(const double *a, const double *b, double *r) { r[0] = a[0] - b[0]; r[1] = a[1] - b[1]; r[2] = a[2] - b[2]; }
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double *a, const double *b, double *r)
{
    r[0] = a[1] * b[2] - a[2] * b[1]; r[1] = a[2] * b[0] - a[0] * b[2]; r[2] = a[0] * b[1] - a[1] * b[0];
}

/* Twice-area vector of triangle (a, b, c). */
static void tri_cross(const double *a, const double *b, const double *c, double *n)
{
    double u[3], v[3];
    sub3(b, a, u); sub3(c, a, v);
    cross3(u, v, n);
}

typedef struct jitter_ctx {
    neuv_mesh *m;
    const neuv_mesh *orig;
    int *vf_start, *vf; /* vertex -> incident faces (CSR) */
    double *orig_cross; /* #F by 3 face cross products of the input */
} jitter_ctx;

/* Whether placing v at p keeps each incident face facing the same way
 * (within 60 degrees) with at least a tenth of its input area. */
static int placement_ok(const jitter_ctx *cx, int v, const double *p)
{
    const neuv_mesh *m = cx->m;
    for (int j = cx->vf_start[v]; j < cx->vf_start[v + 1]; j++) {
        int f = cx->vf[j];
        const double *q[3];
        for (int k = 0; k < 3; k++) q[k] = m->tri[3 * f + k] == v ? p : m->pos + 3 * (size_t)m->tri[3 * f + k];
        double n[3];
        tri_cross(q[0], q[1], q[2], n);
        const double *n0 = cx->orig_cross + 3 * (size_t)f;
        double l0 = sqrt(dot3(n0, n0)), l1 = sqrt(dot3(n, n));
        if (!(l1 >= 0.1 * l0) || dot3(n, n0) < 0.5 * l0 * l1) return 0;
    }
    return 1;
}

/* The UV index of vertex v in face f. */
static int corner_uv(const neuv_mesh *m, int f, int v)
{
    for (int k = 0; k < 3; k++) if (m->tri[3 * f + k] == v) return m->tri_uv[3 * f + k];
    return -1;
}

static neuv_status flip_edges(neuv_mesh *m, const edge_faces *ef, rng *r, const jitter_options *o, int *flipped);

neuv_status mesh_jitter(neuv_mesh *m, uint64_t seed, const jitter_options *opts, jitter_report *report)
{
    jitter_options o;
    if (opts) o = *opts; else jitter_default_options(&o);
    jitter_report rep;
    memset(&rep, 0, sizeof rep);
    if (m->nf <= 0) return error_set(NEUV_ERR_INPUT, "cannot jitter a mesh without faces");
    int has_uv = m->nuv > 0 && m->tri_uv;
    int nv = m->nv, nf = m->nf;
    neuv_status st = NEUV_OK;
    jitter_ctx cx = {m, NULL, NULL, NULL, NULL};
    bvh tree;
    memset(&tree, 0, sizeof tree);
    edge_faces ef;
    memset(&ef, 0, sizeof ef);
    double *emin = mem_alloc(sizeof(double) * (size_t)nv), *normal = mem_calloc((size_t)nv * 3, sizeof(double));
    int *nb = mem_calloc((size_t)nv, sizeof(int)), *bnbr = mem_alloc(sizeof(int) * 2 * (size_t)nv);
    int *vuv = mem_alloc(sizeof(int) * (size_t)nv);
    char *fixed = mem_calloc((size_t)nv, 1);
    cx.vf_start = mem_calloc((size_t)nv + 1, sizeof(int));
    cx.vf = mem_alloc(sizeof(int) * 3 * (size_t)nf);
    cx.orig_cross = mem_alloc(sizeof(double) * 3 * (size_t)nf);
    neuv_mesh *orig = mesh_clone(m);
    cx.orig = orig;
    if (!emin || !normal || !nb || !bnbr || !vuv || !fixed || !cx.vf_start || !cx.vf || !cx.orig_cross || !orig)
        goto nomem;
    if (edge_faces_build(&ef, m)) goto nomem;
    if ((st = bvh_build(&tree, orig))) goto done;

    for (int f = 0; f < nf; f++) {
        const int *t = m->tri + 3 * (size_t)f;
        tri_cross(m->pos + 3 * (size_t)t[0], m->pos + 3 * (size_t)t[1], m->pos + 3 * (size_t)t[2], cx.orig_cross + 3 * (size_t)f);
        for (int k = 0; k < 3; k++) {
            cx.vf_start[t[k] + 1]++;
            for (int i = 0; i < 3; i++) normal[3 * (size_t)t[k] + i] += cx.orig_cross[3 * (size_t)f + i];
        }
    }
    for (int v = 0; v < nv; v++) cx.vf_start[v + 1] += cx.vf_start[v];
    {
        int *fill = mem_alloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
        if (!fill) goto nomem;
        memcpy(fill, cx.vf_start, sizeof(int) * (size_t)nv);
        for (int f = 0; f < nf; f++)
            for (int k = 0; k < 3; k++) cx.vf[fill[m->tri[3 * f + k]]++] = f;
        mem_free(fill);
    }
    for (int v = 0; v < nv; v++) { emin[v] = INFINITY; vuv[v] = -1; }
    for (size_t c = 0; c < (size_t)nf * 3; c++) {
        int v = m->tri[c];
        if (ef.face_edge[c] < 0) fixed[v] = 1;
        if (!has_uv) continue;
        if (vuv[v] < 0) vuv[v] = m->tri_uv[c];
        else if (vuv[v] != m->tri_uv[c]) fixed[v] = 1; /* UV seam */
    }
    double cos_feature = cos(o.feature_degrees * JITTER_PI / 180);
    for (int e = 0; e < ef.ne; e++) {
        int a = ef.edge_v[2 * e], b = ef.edge_v[2 * e + 1], k = edge_faces_count(&ef, e);
        double d[3];
        sub3(m->pos + 3 * (size_t)a, m->pos + 3 * (size_t)b, d);
        double len = sqrt(dot3(d, d));
        emin[a] = fmin(emin[a], len); emin[b] = fmin(emin[b], len);
        if (k == 1) {
            if (nb[a] < 2) bnbr[2 * a + nb[a]] = b;
            if (nb[b] < 2) bnbr[2 * b + nb[b]] = a;
            nb[a]++; nb[b]++;
        } else if (k == 2) {
            const double *n0 = cx.orig_cross + 3 * (size_t)(ef.side[ef.start[e]] / 3);
            const double *n1 = cx.orig_cross + 3 * (size_t)(ef.side[ef.start[e] + 1] / 3);
            double l = sqrt(dot3(n0, n0) * dot3(n1, n1));
            if (!(dot3(n0, n1) >= cos_feature * l)) fixed[a] = fixed[b] = 1;
        } else {
            fixed[a] = fixed[b] = 1;
        }
    }

    rng r;
    rng_seed(&r, seed);
    double cos_line = cos(1.0 * JITTER_PI / 180);
    for (int v = 0; v < nv; v++) {
        /* Two draws per vertex whatever happens, so one vertex's fate does
         * not shift the random stream of the next. */
        double u1 = rng_uniform(&r), u2 = rng_uniform(&r);
        if (fixed[v] || nb[v] == 1 || nb[v] > 2 || !isfinite(emin[v]) || cx.vf_start[v] == cx.vf_start[v + 1]) {
            rep.fixed_vertices++;
            continue;
        }
        const double *p = orig->pos + 3 * (size_t)v;
        double step = o.max_offset * emin[v] * u2;
        if (nb[v] == 2) {
            int w = bnbr[2 * v + (u1 < 0.5 ? 0 : 1)], w2 = bnbr[2 * v + (u1 < 0.5 ? 1 : 0)];
            double d1[3], d2[3];
            sub3(orig->pos + 3 * (size_t)w, p, d1); sub3(orig->pos + 3 * (size_t)w2, p, d2);
            double l1 = sqrt(dot3(d1, d1)), l2 = sqrt(dot3(d2, d2));
            if (!(dot3(d1, d2) <= -cos_line * l1 * l2)) { rep.fixed_vertices++; continue; }
            /* The face holding the boundary edge (v, w) gives the UVs. */
            int fe = -1;
            for (int j = cx.vf_start[v]; j < cx.vf_start[v + 1] && fe < 0; j++)
                for (int k = 0; k < 3; k++) if (m->tri[3 * cx.vf[j] + k] == w) fe = cx.vf[j];
            int done = 0;
            for (int tries = 0; tries < 5 && !done && fe >= 0; tries++, step *= 0.5) {
                double t = step / l1, q[3];
                for (int i = 0; i < 3; i++) q[i] = p[i] + t * d1[i];
                if (!placement_ok(&cx, v, q)) continue;
                memcpy(m->pos + 3 * (size_t)v, q, sizeof q);
                if (has_uv) {
                    int ua = vuv[v], ub = corner_uv(orig, fe, w);
                    for (int i = 0; i < 2; i++)
                        m->uv[2 * (size_t)ua + i] = (1 - t) * orig->uv[2 * (size_t)ua + i] + t * orig->uv[2 * (size_t)ub + i];
                }
                done = 1;
            }
            if (done) rep.slid_vertices++; else rep.fixed_vertices++;
            continue;
        }
        /* Interior: a random direction in the tangent plane of the normal. */
        double *n = normal + 3 * (size_t)v, ln = sqrt(dot3(n, n));
        if (!(ln > 0)) { rep.fixed_vertices++; continue; }
        double nn[3] = {n[0] / ln, n[1] / ln, n[2] / ln}, t1[3], t2[3];
        double axis[3] = {0, 0, 0};
        axis[fabs(nn[0]) < 0.6 ? 0 : fabs(nn[1]) < 0.6 ? 1 : 2] = 1;
        cross3(nn, axis, t1);
        double lt = sqrt(dot3(t1, t1));
        for (int i = 0; i < 3; i++) t1[i] /= lt;
        cross3(nn, t1, t2);
        double ang = 2 * JITTER_PI * u1, dir[3];
        for (int i = 0; i < 3; i++) dir[i] = cos(ang) * t1[i] + sin(ang) * t2[i];
        int done = 0;
        for (int tries = 0; tries < 5 && !done; tries++, step *= 0.5) {
            double q[3], bary[3], d2;
            int f;
            for (int i = 0; i < 3; i++) q[i] = p[i] + step * dir[i];
            bvh_closest_point(&tree, q, &f, bary, &d2);
            int own = 0;
            for (int j = cx.vf_start[v]; j < cx.vf_start[v + 1]; j++) own |= cx.vf[j] == f;
            if (!own) continue;
            const int *t = orig->tri + 3 * (size_t)f;
            for (int i = 0; i < 3; i++)
                q[i] = bary[0] * orig->pos[3 * (size_t)t[0] + i] + bary[1] * orig->pos[3 * (size_t)t[1] + i] +
                       bary[2] * orig->pos[3 * (size_t)t[2] + i];
            if (!placement_ok(&cx, v, q)) continue;
            memcpy(m->pos + 3 * (size_t)v, q, sizeof q);
            if (has_uv) {
                const int *tu = orig->tri_uv + 3 * (size_t)f;
                for (int i = 0; i < 2; i++)
                    m->uv[2 * (size_t)vuv[v] + i] = bary[0] * orig->uv[2 * (size_t)tu[0] + i] +
                                                     bary[1] * orig->uv[2 * (size_t)tu[1] + i] +
                                                     bary[2] * orig->uv[2 * (size_t)tu[2] + i];
            }
            done = 1;
        }
        if (done) rep.moved_vertices++; else rep.fixed_vertices++;
    }
    for (int v = 0; v < nv; v++) {
        double d2;
        bvh_closest_point(&tree, m->pos + 3 * (size_t)v, NULL, NULL, &d2);
        rep.max_deviation = fmax(rep.max_deviation, sqrt(d2));
    }
    if ((st = flip_edges(m, &ef, &r, &o, &rep.flipped_edges))) goto done;
    if (report) *report = rep;
    goto done;
nomem:
    st = error_set(NEUV_ERR_NOMEM, "out of memory jittering %d faces", nf);
done:
    mem_free(emin); mem_free(normal); mem_free(nb); mem_free(bnbr); mem_free(vuv); mem_free(fixed);
    mem_free(cx.vf_start); mem_free(cx.vf); mem_free(cx.orig_cross);
    mesh_free(orig);
    bvh_free(&tree);
    edge_faces_free(&ef);
    return st;
}

/* Local corner of vertex v in face f (-1 if absent). */
static int corner_of(const neuv_mesh *m, int f, int v)
{
    for (int k = 0; k < 3; k++) if (m->tri[3 * f + k] == v) return k;
    return -1;
}

/* One pass over the input's edges in a random order; each face takes part
 * in at most one flip, so the edge table of the input stays valid for the
 * faces not yet touched. */
static neuv_status flip_edges(neuv_mesh *m, const edge_faces *ef, rng *r, const jitter_options *o, int *flipped)
{
    int ne = ef->ne;
    int *order = mem_alloc(sizeof(int) * (size_t)(ne > 0 ? ne : 1));
    char *touched = mem_calloc((size_t)m->nf, 1);
    edge_map present;
    int map_ok = edge_map_init(&present, (size_t)ne + 16) == 0;
    if (!order || !touched || !map_ok) {
        mem_free(order); mem_free(touched);
        if (map_ok) edge_map_free(&present);
        return error_set(NEUV_ERR_NOMEM, "out of memory flipping edges");
    }
    for (int e = 0; e < ne; e++) {
        order[e] = e;
        if (!edge_map_slot(&present, ef->edge_v[2 * e], ef->edge_v[2 * e + 1], 1, NULL)) goto nomem;
    }
    for (int i = ne - 1; i > 0; i--) { /* Fisher-Yates */
        int j = rng_below(r, i + 1), t = order[i];
        order[i] = order[j]; order[j] = t;
    }
    double cos_flat = cos(o->flip_max_degrees * JITTER_PI / 180);
    int has_uv = m->nuv > 0 && m->tri_uv;
    for (int i = 0; i < ne; i++) {
        int e = order[i];
        if (rng_uniform(r) >= o->flip_probability || edge_faces_count(ef, e) != 2) continue;
        int s0 = ef->side[ef->start[e]], s1 = ef->side[ef->start[e] + 1];
        int f = s0 / 3, g = s1 / 3;
        if (f == g || touched[f] || touched[g]) continue;
        /* f runs a -> b -> c; g must run b -> a -> d for a consistent pair. */
        int a = m->tri[s0], b = m->tri[3 * f + (s0 % 3 + 1) % 3], c = m->tri[3 * f + (s0 % 3 + 2) % 3];
        int kb = corner_of(m, g, b);
        if (kb < 0 || m->tri[3 * g + (kb + 1) % 3] != a) continue;
        int d = m->tri[3 * g + (kb + 2) % 3];
        if (c == d) continue;
        int lo = c < d ? c : d, hi = c < d ? d : c;
        if (edge_map_get(&present, lo, hi) >= 0) continue;
        const double *pa = m->pos + 3 * (size_t)a, *pb = m->pos + 3 * (size_t)b, *pc = m->pos + 3 * (size_t)c,
                     *pd = m->pos + 3 * (size_t)d;
        double nf_[3], ng[3], n1[3], n2[3];
        tri_cross(pa, pb, pc, nf_); tri_cross(pb, pa, pd, ng);
        double lf = sqrt(dot3(nf_, nf_)), lg = sqrt(dot3(ng, ng));
        if (!(dot3(nf_, ng) >= cos_flat * lf * lg)) continue;
        /* The quad runs a, d, b, c; the new diagonal c-d gives (a, d, c) and (d, b, c). */
        tri_cross(pa, pd, pc, n1); tri_cross(pd, pb, pc, n2);
        double l1 = sqrt(dot3(n1, n1)), l2 = sqrt(dot3(n2, n2)), lq = lf + lg;
        if (!(l1 > 0.05 * lq && l2 > 0.05 * lq)) continue;
        if (dot3(n1, nf_) < cos_flat * l1 * lf || dot3(n2, nf_) < cos_flat * l2 * lf) continue;
        int ua = 0, ub = 0, uc = 0, ud = 0;
        if (has_uv) {
            ua = m->tri_uv[s0]; ub = m->tri_uv[3 * f + (s0 % 3 + 1) % 3]; uc = m->tri_uv[3 * f + (s0 % 3 + 2) % 3];
            if (m->tri_uv[3 * g + (kb + 1) % 3] != ua || m->tri_uv[3 * g + kb] != ub) continue; /* seam */
            ud = m->tri_uv[3 * g + (kb + 2) % 3];
        }
        int *tf = m->tri + 3 * (size_t)f, *tg = m->tri + 3 * (size_t)g;
        tf[0] = a; tf[1] = d; tf[2] = c;
        tg[0] = d; tg[1] = b; tg[2] = c;
        if (has_uv) {
            int *uf = m->tri_uv + 3 * (size_t)f, *ug = m->tri_uv + 3 * (size_t)g;
            uf[0] = ua; uf[1] = ud; uf[2] = uc;
            ug[0] = ud; ug[1] = ub; ug[2] = uc;
        }
        touched[f] = touched[g] = 1;
        if (!edge_map_slot(&present, lo, hi, 1, NULL)) goto nomem;
        (*flipped)++;
    }
    mem_free(order); mem_free(touched); edge_map_free(&present);
    return NEUV_OK;
nomem:
    mem_free(order); mem_free(touched); edge_map_free(&present);
    return error_set(NEUV_ERR_NOMEM, "out of memory flipping edges");
}
