#include "metrics/uv_metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/uv_charts.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "metrics/uv_overlap.h"

/* Faces below this share of the mean 3D area are left out of everything;
 * UV triangles below this share of the mean UV area count as degenerate. */
#define UV_METRICS_RASTER 2048

double uv_jacobian_singular_values(const double p[3][3], const double q[3][2], double s[2])
{
    double e1[3], e2[3], x[3];
    for (int d = 0; d < 3; d++) { e1[d] = p[1][d] - p[0][d]; e2[d] = p[2][d] - p[0][d]; }
    x[0] = e1[1] * e2[2] - e1[2] * e2[1];
    x[1] = e1[2] * e2[0] - e1[0] * e2[2];
    x[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double area2 = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    double len1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    s[0] = s[1] = 0;
    if (!(area2 > 0) || !(len1 > 0)) return 0;
    /* The triangle in the frame x = e1/|e1| of its plane: P = [[p11, p12], [0, p22]]. */
    double p11 = len1, p12 = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / len1;
    double p22 = area2 / len1;
    double du1 = q[1][0] - q[0][0], dv1 = q[1][1] - q[0][1];
    double du2 = q[2][0] - q[0][0], dv2 = q[2][1] - q[0][1];
    /* J = Q P^-1. */
    double a = du1 / p11, c = dv1 / p11;
    double b = (du2 - du1 * p12 / p11) / p22, d = (dv2 - dv1 * p12 / p11) / p22;
    /* Closed-form 2x2 SVD: J splits into a similarity (E, H) and an
     * anti-similarity (F, G) part; s1 is the sum of their scales. The smaller
     * value comes from the determinant, which keeps it accurate when s1 >> s2. */
    double E = (a + d) / 2, F = (a - d) / 2, G = (c + b) / 2, H = (c - b) / 2;
    double det = (du1 * dv2 - du2 * dv1) / area2;
    s[0] = sqrt(E * E + H * H) + sqrt(F * F + G * G);
    s[1] = s[0] > 0 ? fabs(det) / s[0] : 0;
    return det;
}

/* Per-face values the metrics share. */
typedef struct face_measure {
    double area3;   /* 3D area */
    double area_uv; /* signed UV area */
    double s1, s2;
} face_measure;

static void face_corners(const neuv_mesh *m, int f, double p[3][3], double q[3][2])
{
    for (int k = 0; k < 3; k++) {
        const double *v = m->pos + 3 * (size_t)m->tri[3 * (size_t)f + k];
        const double *t = m->uv + 2 * (size_t)m->tri_uv[3 * (size_t)f + k];
        p[k][0] = v[0]; p[k][1] = v[1]; p[k][2] = v[2];
        q[k][0] = t[0]; q[k][1] = t[1];
    }
}

static double face_area3(const double p[3][3])
{
    double e1[3], e2[3];
    for (int d = 0; d < 3; d++) { e1[d] = p[1][d] - p[0][d]; e2[d] = p[2][d] - p[0][d]; }
    double x = e1[1] * e2[2] - e1[2] * e2[1];
    double y = e1[2] * e2[0] - e1[0] * e2[2];
    double z = e1[0] * e2[1] - e1[1] * e2[0];
    return sqrt(x * x + y * y + z * z) / 2;
}

static double face_area_uv(const double q[3][2])
{
    return ((q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[2][0] - q[0][0]) * (q[1][1] - q[0][1])) / 2;
}

/* The p95 sort key: (qce, face) ascending. */
typedef struct qce_entry { double qce, weight; int face; } qce_entry;

static int cmp_qce(const void *a, const void *b)
{
    const qce_entry *x = a, *y = b;
    if (x->qce != y->qce) return x->qce < y->qce ? -1 : 1;
    return (x->face > y->face) - (x->face < y->face);
}

typedef struct edge_side { int lo, hi, face; } edge_side;

static int cmp_edge_side(const void *a, const void *b)
{
    const edge_side *x = a, *y = b;
    if (x->lo != y->lo) return x->lo < y->lo ? -1 : 1;
    if (x->hi != y->hi) return x->hi < y->hi ? -1 : 1;
    return (x->face > y->face) - (x->face < y->face);
}

/* UV of vertex v in face f of m. */
static const double *uv_at(const neuv_mesh *m, int f, int v)
{
    for (int k = 0; k < 3; k++)
        if (m->tri[3 * (size_t)f + k] == v) return m->uv + 2 * (size_t)m->tri_uv[3 * (size_t)f + k];
    return NULL;
}

static int uv_equal(const double *a, const double *b)
{
    return a && b && a[0] == b[0] && a[1] == b[1];
}

/* 3D length of the cut edges of m (edges of two or more faces whose sides
 * disagree on an endpoint UV), each edge once. Negative on allocation failure. */
static double cut_length(const neuv_mesh *m)
{
    size_t n = (size_t)m->nf * 3;
    edge_side *es = mem_alloc(sizeof *es * (n ? n : 1));
    if (!es) return -1;
    for (int f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++) {
            int a = m->tri[3 * (size_t)f + k], b = m->tri[3 * (size_t)f + (k + 1) % 3];
            edge_side *e = &es[3 * (size_t)f + k];
            e->lo = a < b ? a : b;
            e->hi = a < b ? b : a;
            e->face = f;
        }
    qsort(es, n, sizeof *es, cmp_edge_side);
    double total = 0;
    for (size_t i = 0; i < n;) {
        size_t j = i + 1;
        while (j < n && es[j].lo == es[i].lo && es[j].hi == es[i].hi) j++;
        int cut = 0;
        for (size_t a = i; a < j && !cut; a++)
            for (size_t b = a + 1; b < j && !cut; b++) {
                int f = es[a].face, g = es[b].face;
                cut = !uv_equal(uv_at(m, f, es[i].lo), uv_at(m, g, es[i].lo)) ||
                      !uv_equal(uv_at(m, f, es[i].hi), uv_at(m, g, es[i].hi));
            }
        if (cut) {
            const double *pa = m->pos + 3 * (size_t)es[i].lo, *pb = m->pos + 3 * (size_t)es[i].hi;
            double dx = pa[0] - pb[0], dy = pa[1] - pb[1], dz = pa[2] - pb[2];
            total += sqrt(dx * dx + dy * dy + dz * dz);
        }
        i = j;
    }
    mem_free(es);
    return total;
}

static void metrics_set_nan(uv_metrics *out)
{
    double nan = NAN;
    out->qce_mean = out->qce_p95 = out->qce_max = nan;
    out->ase_mean = out->ase_abs_mean = out->ase_abs_mean_chart = nan;
    out->l2_stretch = out->linf_stretch = out->sym_dirichlet_mean = nan;
    out->packing_efficiency = nan;
    out->overlap_fraction = 0;
    out->seam_length = nan;
    out->charts = out->flipped = out->degenerate_uv = 0;
}

/* The measured faces' sums (docs/metrics.md "Metrics"): qce, ase, stretch,
 * symmetric Dirichlet. fm and chart are indexed by valid face. */
static neuv_status distortion_metrics(int nf, const face_measure *fm, const unsigned char *measured,
                                      const int *chart, int nchart, uv_metrics *out)
{
    double sum3 = 0, sumuv = 0;
    int nm = 0;
    for (int f = 0; f < nf; f++)
        if (measured[f]) { sum3 += fm[f].area3; sumuv += fabs(fm[f].area_uv); nm++; }
    if (nm == 0) return NEUV_OK;

    double *chart3 = mem_calloc((size_t)nchart * 2, sizeof *chart3);
    qce_entry *qe = mem_alloc(sizeof *qe * (size_t)nm);
    if (!chart3 || !qe) { mem_free(chart3); mem_free(qe); return error_nomem("UV metrics"); }
    double *chartuv = chart3 + nchart;
    for (int f = 0; f < nf; f++)
        if (measured[f]) { chart3[chart[f]] += fm[f].area3; chartuv[chart[f]] += fabs(fm[f].area_uv); }

    /* Sander et al. 2001 measure stretch after a global scale that makes the
     * UV area equal the surface area, so only the shape of the map counts. */
    double sigma = sqrt(sum3 / sumuv);
    double log_global = log(sumuv / sum3);
    double qce_sum = 0, qce_max = 0, ase_sum = 0, ase_abs = 0, ase_chart = 0;
    double l2_sum = 0, linf = 0, sd_sum = 0;
    int k = 0;
    for (int f = 0; f < nf; f++) {
        if (!measured[f]) continue;
        double w = fm[f].area3, s1 = fm[f].s1, s2 = fm[f].s2;
        double qce = s1 / s2;
        qce_sum += w * qce;
        if (qce > qce_max) qce_max = qce;
        qe[k].qce = qce; qe[k].weight = w; qe[k].face = f; k++;
        double log_ratio = log(fabs(fm[f].area_uv) / w);
        double ase = log_ratio - log_global;
        ase_sum += w * ase;
        ase_abs += w * fabs(ase);
        ase_chart += w * fabs(log_ratio - log(chartuv[chart[f]] / chart3[chart[f]]));
        double t1 = sigma * s1, t2 = sigma * s2;
        double big = 1 / t2, small = 1 / t1; /* Γ and γ of the inverse map UV -> 3D */
        l2_sum += w * (big * big + small * small) / 2;
        if (big > linf) linf = big;
        sd_sum += w * (t1 * t1 + t2 * t2 + 1 / (t1 * t1) + 1 / (t2 * t2));
    }
    out->qce_mean = qce_sum / sum3;
    out->qce_max = qce_max;
    out->ase_mean = ase_sum / sum3;
    out->ase_abs_mean = ase_abs / sum3;
    out->ase_abs_mean_chart = ase_chart / sum3;
    out->l2_stretch = sqrt(l2_sum / sum3);
    out->linf_stretch = linf;
    out->sym_dirichlet_mean = sd_sum / sum3;

    /* Lower weighted percentile; the running sum's own total decides, so the
     * comparison does not depend on how the total was summed elsewhere. */
    qsort(qe, (size_t)nm, sizeof *qe, cmp_qce);
    double run = 0;
    for (int i = 0; i < nm; i++) { run += qe[i].weight; qe[i].weight = run; }
    double target = 0.95 * run;
    out->qce_p95 = qe[nm - 1].qce;
    for (int i = 0; i < nm; i++)
        if (qe[i].weight >= target) { out->qce_p95 = qe[i].qce; break; }
    mem_free(chart3);
    mem_free(qe);
    return NEUV_OK;
}

/* with_overlap 0: overlap_fraction is left NaN (no raster drawn). */
static neuv_status metrics_compute(const neuv_mesh *m, int with_overlap, uv_metrics *out)
{
    memset(out, 0, sizeof *out);
    metrics_set_nan(out);
    if (!with_overlap) out->overlap_fraction = NAN;
    if (!m || m->nuv <= 0 || !m->uv || !m->tri_uv)
        return error_set(NEUV_ERR_INPUT, "the mesh carries no texture coordinates");
    if (m->nf == 0) return NEUV_OK;

    /* Valid faces: 3D area at least 1e-12 x the mean. */
    double mean3 = 0;
    for (int f = 0; f < m->nf; f++) {
        double p[3][3], q[3][2];
        face_corners(m, f, p, q);
        mean3 += face_area3(p);
    }
    mean3 /= m->nf;
    neuv_mesh sub = *m; /* the valid faces, sharing positions and UVs with m */
    sub.tri = mem_alloc(sizeof *sub.tri * 3 * (size_t)m->nf);
    sub.tri_uv = mem_alloc(sizeof *sub.tri_uv * 3 * (size_t)m->nf);
    face_measure *fm = mem_alloc(sizeof *fm * (size_t)m->nf);
    unsigned char *measured = mem_alloc((size_t)m->nf);
    int *chart = mem_alloc(sizeof *chart * (size_t)m->nf);
    neuv_status st = NEUV_OK;
    if (!sub.tri || !sub.tri_uv || !fm || !measured || !chart) { st = error_nomem("UV metrics"); goto done; }
    int nvalid = 0;
    for (int f = 0; f < m->nf; f++) {
        double p[3][3], q[3][2], s[2];
        face_corners(m, f, p, q);
        double a3 = face_area3(p);
        if (!(a3 >= UV_METRICS_AREA_EPS * mean3)) continue;
        memcpy(sub.tri + 3 * (size_t)nvalid, m->tri + 3 * (size_t)f, sizeof *sub.tri * 3);
        memcpy(sub.tri_uv + 3 * (size_t)nvalid, m->tri_uv + 3 * (size_t)f, sizeof *sub.tri_uv * 3);
        uv_jacobian_singular_values(p, q, s);
        fm[nvalid].area3 = a3;
        fm[nvalid].area_uv = face_area_uv(q);
        fm[nvalid].s1 = s[0];
        fm[nvalid].s2 = s[1];
        nvalid++;
    }
    sub.nf = nvalid;
    out->excluded_faces = m->nf - nvalid;
    if (nvalid == 0) goto done;

    /* Degenerate UV faces: |a| at most 1e-12 x the mean over valid faces. */
    double meanuv = 0, sum3 = 0, sumuv_all = 0;
    for (int f = 0; f < nvalid; f++) { meanuv += fabs(fm[f].area_uv); sum3 += fm[f].area3; }
    sumuv_all = meanuv;
    meanuv /= nvalid;
    for (int f = 0; f < nvalid; f++) {
        measured[f] = fabs(fm[f].area_uv) > UV_METRICS_AREA_EPS * meanuv;
        out->degenerate_uv += !measured[f];
    }

    int nchart = uv_charts(&sub, chart);
    if (nchart < 0) { st = error_nomem("UV charts"); goto done; }
    out->charts = nchart;

    st = distortion_metrics(nvalid, fm, measured, chart, nchart, out);
    if (st != NEUV_OK) goto done;

    /* Flips against each chart's 3D-area-weighted majority orientation. */
    double *vote = mem_calloc(nchart > 0 ? (size_t)nchart : 1, sizeof *vote);
    if (!vote) { st = error_nomem("UV metrics"); goto done; }
    for (int f = 0; f < nvalid; f++)
        if (measured[f]) vote[chart[f]] += fm[f].area_uv > 0 ? fm[f].area3 : -fm[f].area3;
    for (int f = 0; f < nvalid; f++)
        if (measured[f]) out->flipped += (fm[f].area_uv > 0) != (vote[chart[f]] >= 0);
    mem_free(vote);

    if (with_overlap) {
        uv_coverage cov;
        double t0 = now_seconds();
        st = uv_coverage_count(sub.uv, nvalid, sub.tri_uv, measured, UV_METRICS_RASTER, &cov);
        if (st != NEUV_OK) goto done;
        log_message(NEUV_LOG_DEBUG, "overlap raster: %d faces, %lld pixels covered, %lld twice, %.3f s",
                    nvalid - out->degenerate_uv, cov.covered, cov.overlapped, now_seconds() - t0);
        out->overlap_fraction = uv_coverage_overlap_fraction(&cov);
    }

    int inside = 1;
    for (size_t c = 0; c < 3 * (size_t)nvalid && inside; c++) {
        const double *t = sub.uv + 2 * (size_t)sub.tri_uv[c];
        inside = t[0] >= -UV_METRICS_UNIT_TOL && t[0] <= 1 + UV_METRICS_UNIT_TOL &&
                 t[1] >= -UV_METRICS_UNIT_TOL && t[1] <= 1 + UV_METRICS_UNIT_TOL;
    }
    out->packing_efficiency = inside ? sumuv_all : NAN;

    double cut = cut_length(&sub);
    if (cut < 0) { st = error_nomem("UV seams"); goto done; }
    out->seam_length = cut / sqrt(sum3);

done:
    mem_free(sub.tri);
    mem_free(sub.tri_uv);
    mem_free(fm);
    mem_free(measured);
    mem_free(chart);
    return st;
}

neuv_status uv_metrics_compute(const neuv_mesh *m, uv_metrics *out) { return metrics_compute(m, 1, out); }

neuv_status uv_metrics_compute_no_overlap(const neuv_mesh *m, uv_metrics *out) { return metrics_compute(m, 0, out); }

void uv_metrics_write_json(const uv_metrics *mt, json_writer *w)
{
    json_key(w, "charts"); json_int(w, mt->charts);
    json_key(w, "qce_mean"); json_number(w, mt->qce_mean);
    json_key(w, "qce_p95"); json_number(w, mt->qce_p95);
    json_key(w, "qce_max"); json_number(w, mt->qce_max);
    json_key(w, "ase_mean"); json_number(w, mt->ase_mean);
    json_key(w, "ase_abs_mean"); json_number(w, mt->ase_abs_mean);
    json_key(w, "ase_abs_mean_chart"); json_number(w, mt->ase_abs_mean_chart);
    json_key(w, "l2_stretch"); json_number(w, mt->l2_stretch);
    json_key(w, "linf_stretch"); json_number(w, mt->linf_stretch);
    json_key(w, "sym_dirichlet_mean"); json_number(w, mt->sym_dirichlet_mean);
    json_key(w, "flipped"); json_int(w, mt->flipped);
    json_key(w, "degenerate_uv"); json_int(w, mt->degenerate_uv);
    json_key(w, "overlap_fraction"); json_number(w, mt->overlap_fraction);
    json_key(w, "packing_efficiency"); json_number(w, mt->packing_efficiency);
    json_key(w, "seam_length"); json_number(w, mt->seam_length);
    json_key(w, "excluded_faces"); json_int(w, mt->excluded_faces);
}
