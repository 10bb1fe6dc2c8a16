#include "flatten/uv_refine.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "losses/param_losses.h"
#include "nn/adam.h"
#include "nn/nn.h"

void uv_refine_default_options(uv_refine_options *o)
{
    *o = (uv_refine_options){0};
    o->iters = 400;
    o->lr = 0.02;
    o->lambda_iso = 0;
    o->lambda_angle = 0;
    o->lambda_conformal = 0.1;
    o->lambda_area = 0.01;
    o->lambda_fold = 100;
    o->fold_eps = 0.05;
}

/* All charts concatenated, each vertex once per chart holding it, positions
 * scaled per chart to a mean edge length of 1 (UVs by the same factor). */
typedef struct refine_data {
    int nv, nf, ne;
    int *tri;          /* nf by 3 chart-vertex indices */
    int *fmesh;        /* nf mesh face */
    int *fchart;       /* nf */
    int *ei, *ej;      /* ne: the three edges of every face */
    float *elen;       /* ne: 3D length, normalized */
    param_corners corners;
    float *cos3d, *area3d, *orient;
    float *frame_inv, *weight;  /* L_conf targets: #F by 4, #F */
    float *uv0;        /* nv by 2: starting map, normalized */
    double *scale;     /* n_charts */
    int *vfirst, *ffirst; /* n_charts + 1: chart c owns vertices and faces [first[c], first[c+1]) */
    int nb;            /* boundary edges, grouped by chart */
    int *bi, *bj;
    int *bfirst;       /* n_charts + 1 */
    unsigned char *vbound; /* nv: 1 on the chart's boundary */
} refine_data;

static void refine_data_free(refine_data *d)
{
    mem_free(d->tri); mem_free(d->fmesh); mem_free(d->fchart); mem_free(d->ei); mem_free(d->ej); mem_free(d->elen);
    param_corners_free(&d->corners);
    mem_free(d->cos3d); mem_free(d->area3d); mem_free(d->frame_inv); mem_free(d->weight); mem_free(d->orient); mem_free(d->uv0); mem_free(d->scale); mem_free(d->vfirst); mem_free(d->ffirst); mem_free(d->vbound);
    mem_free(d->bi); mem_free(d->bj); mem_free(d->bfirst);
    memset(d, 0, sizeof *d);
}

static double dist3(const double *a, const double *b)
{
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return sqrt(x * x + y * y + z * z);
}

static int cmp_edge_key(const void *a, const void *b)
{
    unsigned long long x = *(const unsigned long long *)a, y = *(const unsigned long long *)b;
    return x < y ? -1 : x > y;
}

/* Boundary edges and vertices: an edge one face of the chart holds. Chart
 * vertices are numbered chart by chart, so sorted keys come grouped by chart
 * and a key never joins two charts. */
static neuv_status mark_boundary(refine_data *d, int n_charts)
{
    unsigned long long *key = mem_alloc(sizeof *key * (size_t)(d->ne > 0 ? d->ne : 1));
    d->vbound = mem_calloc((size_t)(d->nv > 0 ? d->nv : 1), 1);
    d->bi = mem_alloc(sizeof(int) * (size_t)(d->ne > 0 ? d->ne : 1));
    d->bj = mem_alloc(sizeof(int) * (size_t)(d->ne > 0 ? d->ne : 1));
    d->bfirst = mem_calloc((size_t)n_charts + 1, sizeof(int));
    if (!key || !d->vbound || !d->bi || !d->bj || !d->bfirst) { mem_free(key); return error_nomem("UV refinement"); }
    for (int e = 0; e < d->ne; e++) {
        unsigned long long a = (unsigned)d->ei[e], b = (unsigned)d->ej[e];
        key[e] = a < b ? a << 32 | b : b << 32 | a;
    }
    qsort(key, (size_t)d->ne, sizeof *key, cmp_edge_key);
    d->nb = 0;
    int c = 0;
    for (int e = 0; e < d->ne;) {
        int n = 1;
        while (e + n < d->ne && key[e + n] == key[e]) n++;
        if (n == 1) {
            int a = (int)(key[e] >> 32), b = (int)(key[e] & 0xffffffffu);
            while (c < n_charts && a >= d->vfirst[c + 1]) d->bfirst[++c] = d->nb;
            d->vbound[a] = d->vbound[b] = 1;
            d->bi[d->nb] = a;
            d->bj[d->nb] = b;
            d->nb++;
        }
        e += n;
    }
    while (c < n_charts) d->bfirst[++c] = d->nb;
    mem_free(key);
    return NEUV_OK;
}

static neuv_status refine_data_build(const neuv_mesh *m, const int *face_chart, int n_charts,
                                     const double *corner_uv, refine_data *d)
{
    memset(d, 0, sizeof *d);
    int nf = m->nf;
    d->nf = nf;
    d->ne = 3 * nf;
    int *order = mem_alloc(sizeof(int) * (size_t)nf), *first = mem_calloc((size_t)n_charts + 1, sizeof(int));
    int *stamp = mem_alloc(sizeof(int) * (size_t)m->nv), *local = mem_alloc(sizeof(int) * (size_t)m->nv);
    double *pos = mem_alloc(sizeof(double) * 3 * 3 * (size_t)nf);   /* chart-vertex positions, at most 3 nf */
    double *edge_sum = mem_calloc((size_t)n_charts, sizeof(double));
    d->tri = mem_alloc(sizeof(int) * 3 * (size_t)nf);
    d->fmesh = mem_alloc(sizeof(int) * (size_t)nf);
    d->fchart = mem_alloc(sizeof(int) * (size_t)nf);
    d->ei = mem_alloc(sizeof(int) * (size_t)d->ne);
    d->ej = mem_alloc(sizeof(int) * (size_t)d->ne);
    d->elen = mem_alloc(sizeof(float) * (size_t)d->ne);
    d->cos3d = mem_alloc(sizeof(float) * 3 * (size_t)nf);
    d->area3d = mem_alloc(sizeof(float) * (size_t)nf);
    d->frame_inv = mem_alloc(sizeof(float) * 4 * (size_t)nf);
    d->weight = mem_alloc(sizeof(float) * (size_t)nf);
    d->orient = mem_alloc(sizeof(float) * (size_t)nf);
    d->uv0 = mem_alloc(sizeof(float) * 2 * 3 * (size_t)nf);
    d->scale = mem_alloc(sizeof(double) * (size_t)n_charts);
    d->vfirst = mem_alloc(sizeof(int) * ((size_t)n_charts + 1));
    neuv_status s = NEUV_OK;
    if (!order || !first || !stamp || !local || !pos || !edge_sum || !d->tri || !d->fmesh || !d->fchart ||
        !d->ei || !d->ej || !d->elen || !d->cos3d || !d->area3d || !d->frame_inv || !d->weight || !d->orient || !d->uv0 || !d->scale || !d->vfirst) {
        s = error_nomem("UV refinement");
        goto done;
    }
    /* Faces grouped by chart (counting sort keeps mesh order inside a chart). */
    for (int f = 0; f < nf; f++) first[face_chart[f] + 1]++;
    for (int c = 0; c < n_charts; c++) first[c + 1] += first[c];
    {
        int *fill = mem_alloc(sizeof(int) * (size_t)n_charts);
        if (!fill) { s = error_nomem("UV refinement"); goto done; }
        memcpy(fill, first, sizeof(int) * (size_t)n_charts);
        for (int f = 0; f < nf; f++) order[fill[face_chart[f]]++] = f;
        mem_free(fill);
    }
    for (int v = 0; v < m->nv; v++) stamp[v] = -1;
    int nv = 0;
    for (int c = 0; c < n_charts; c++) {
        d->vfirst[c] = nv;
        for (int k = first[c]; k < first[c + 1]; k++) {
            int f = order[k];
            d->fmesh[k] = f;
            d->fchart[k] = c;
            for (int q = 0; q < 3; q++) {
                int v = m->tri[3 * f + q];
                if (stamp[v] != c) {
                    stamp[v] = c;
                    local[v] = nv;
                    memcpy(pos + 3 * (size_t)nv, m->pos + 3 * (size_t)v, 3 * sizeof(double));
                    d->uv0[2 * nv] = (float)corner_uv[6 * (size_t)f + 2 * q];
                    d->uv0[2 * nv + 1] = (float)corner_uv[6 * (size_t)f + 2 * q + 1];
                    nv++;
                }
                d->tri[3 * k + q] = local[v];
            }
            for (int q = 0; q < 3; q++) {
                int a = d->tri[3 * k + q], b = d->tri[3 * k + (q + 1) % 3];
                d->ei[3 * k + q] = a;
                d->ej[3 * k + q] = b;
                edge_sum[c] += dist3(pos + 3 * (size_t)a, pos + 3 * (size_t)b);
            }
        }
    }
    d->nv = nv;
    d->vfirst[n_charts] = nv;
    d->ffirst = first;
    first = NULL;
    for (int c = 0; c < n_charts; c++) {
        int ne = 3 * (d->ffirst[c + 1] - d->ffirst[c]);
        d->scale[c] = ne > 0 && edge_sum[c] > 0 ? ne / edge_sum[c] : 1;
    }
    /* Scale positions and UVs per chart vertex (every vertex's chart is its faces' chart). */
    {
        int *vchart = mem_alloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
        if (!vchart) { s = error_nomem("UV refinement"); goto done; }
        for (int k = 0; k < nf; k++)
            for (int q = 0; q < 3; q++) vchart[d->tri[3 * k + q]] = d->fchart[k];
        for (int i = 0; i < nv; i++) {
            double sc = d->scale[vchart[i]];
            for (int q = 0; q < 3; q++) pos[3 * (size_t)i + q] *= sc;
            d->uv0[2 * i] = (float)(d->uv0[2 * i] * sc);
            d->uv0[2 * i + 1] = (float)(d->uv0[2 * i + 1] * sc);
        }
        mem_free(vchart);
    }
    for (int e = 0; e < d->ne; e++)
        d->elen[e] = (float)dist3(pos + 3 * (size_t)d->ei[e], pos + 3 * (size_t)d->ej[e]);
    s = mark_boundary(d, n_charts);
    if (s == NEUV_OK) s = param_corners_build(d->tri, nf, &d->corners);
    if (s != NEUV_OK) goto done;
    param_corner_targets(pos, &d->corners, d->cos3d, d->area3d);
    param_conformal_targets(pos, &d->corners, d->frame_inv, d->weight);
    /* A near-degenerate 3D face would make the scale-free barrier infinite. */
    for (int f = 0; f < nf; f++)
        if (d->area3d[f] < 1e-6f) d->area3d[f] = 1e-6f;
done:
    mem_free(order); mem_free(first); mem_free(stamp); mem_free(local); mem_free(pos); mem_free(edge_sum);
    if (s != NEUV_OK) refine_data_free(d);
    return s;
}

static double signed_area(const float *uv, const int *t)
{
    const float *a = uv + 2 * t[0], *b = uv + 2 * t[1], *c = uv + 2 * t[2];
    return 0.5 * ((double)(b[0] - a[0]) * (c[1] - a[1]) - (double)(b[1] - a[1]) * (c[0] - a[0]));
}

/* Orientation of each chart from the sign of its total UV area. */
static void chart_orientation(const refine_data *d, const float *uv, int n_charts, double *sum)
{
    for (int c = 0; c < n_charts; c++) sum[c] = 0;
    for (int f = 0; f < d->nf; f++) sum[d->fchart[f]] += signed_area(uv, d->tri + 3 * f);
}

/* Faces of each chart that are flipped or degenerate against orientation `orient`. */
static void count_bad(const refine_data *d, const float *uv, int n_charts, int *bad)
{
    for (int c = 0; c < n_charts; c++) bad[c] = 0;
    for (int f = 0; f < d->nf; f++)
        if (signed_area(uv, d->tri + 3 * f) * d->orient[f] <= 0) bad[d->fchart[f]]++;
}

typedef struct lr_decay { int iters; } lr_decay;

static float lr_decay_at(void *user, long step, float base_lr)
{
    const lr_decay *c = user;
    double t = c->iters > 1 ? (double)(step - 1) / (c->iters - 1) : 1;
    if (t > 1) t = 1;
    return (float)(base_lr * 0.5 * (1 + cos(3.14159265358979323846 * t)));
}

/* Writes chart c of the normalized map `uv` into corner_uv (mesh units). */
static void write_chart(const refine_data *d, const float *uv, int c, double *corner_uv)
{
    for (int k = d->ffirst[c]; k < d->ffirst[c + 1]; k++) {
        int mf = d->fmesh[k];
        for (int q = 0; q < 3; q++) {
            const float *p = uv + 2 * d->tri[3 * k + q];
            corner_uv[6 * (size_t)mf + 2 * q] = p[0] / d->scale[c];
            corner_uv[6 * (size_t)mf + 2 * q + 1] = p[1] / d->scale[c];
        }
    }
}

static void copy_chart(const refine_data *d, int c, float *dst, const float *src)
{
    memcpy(dst + 2 * (size_t)d->vfirst[c], src + 2 * (size_t)d->vfirst[c],
           sizeof(float) * 2 * (size_t)(d->vfirst[c + 1] - d->vfirst[c]));
}

static double orient2(const float *a, const float *b, const float *c)
{
    return ((double)b[0] - a[0]) * ((double)c[1] - a[1]) - ((double)b[1] - a[1]) * ((double)c[0] - a[0]);
}

/* Whether segments ab and cd touch or cross (collinear overlaps included). */
static int segments_meet(const float *a, const float *b, const float *c, const float *d)
{
    double o1 = orient2(a, b, c), o2 = orient2(a, b, d), o3 = orient2(c, d, a), o4 = orient2(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return 1;
    if (o1 == 0 || o2 == 0 || o3 == 0 || o4 == 0) {
        /* degenerate cases: some endpoint on the other segment's line; test by boxes */
        for (int k = 0; k < 2; k++) {
            double lo1 = fmin(a[k], b[k]), hi1 = fmax(a[k], b[k]), lo2 = fmin(c[k], d[k]), hi2 = fmax(c[k], d[k]);
            if (hi1 < lo2 || hi2 < lo1) return 0;
        }
        return 1;
    }
    return 0;
}

/* Marks (in `mark`, chart vertices) the endpoints of chart c's boundary edges
 * that meet a non-adjacent boundary edge in the map uv. Returns how many
 * pairs meet; -1 when the boundary is too long to test (quadratic test). */
static int boundary_meetings(const refine_data *d, int c, const float *uv, unsigned char *mark)
{
    int b0 = d->bfirst[c], b1 = d->bfirst[c + 1], n = 0;
    if ((long)(b1 - b0) * (b1 - b0) > 64L * 1000 * 1000) return -1;
    for (int e = b0; e < b1; e++) {
        const float *p = uv + 2 * d->bi[e], *q = uv + 2 * d->bj[e];
        for (int f = e + 1; f < b1; f++) {
            if (d->bi[f] == d->bi[e] || d->bi[f] == d->bj[e] || d->bj[f] == d->bi[e] || d->bj[f] == d->bj[e]) continue;
            if (!segments_meet(p, q, uv + 2 * d->bi[f], uv + 2 * d->bj[f])) continue;
            mark[d->bi[e]] = mark[d->bj[e]] = mark[d->bi[f]] = mark[d->bj[f]] = 1;
            n++;
        }
    }
    return n;
}

/* Holds the boundary vertices of chart c within `radius` (edge lengths, in
 * the map uv) of a marked vertex; clears the marks. */
static void pin_near_marks(const refine_data *d, int c, const float *uv, unsigned char *mark, unsigned char *pinned,
                           double radius)
{
    for (int i = d->vfirst[c]; i < d->vfirst[c + 1]; i++) {
        if (!mark[i]) continue;
        for (int j = d->vfirst[c]; j < d->vfirst[c + 1]; j++) {
            if (!d->vbound[j] || pinned[j] == 1) continue;
            double x = (double)uv[2 * j] - uv[2 * i], y = (double)uv[2 * j + 1] - uv[2 * i + 1];
            if (x * x + y * y <= radius * radius) pinned[j] = 2; /* 2: set in this pass */
        }
    }
    for (int i = d->vfirst[c]; i < d->vfirst[c + 1]; i++) {
        if (pinned[i]) pinned[i] = 1;
        mark[i] = 0;
    }
}

static nn_tensor *refine_loss(nn_ctx *ctx, const refine_data *d, const uv_refine_options *o, nn_tensor *uv)
{
    nn_tensor *area3d = nn_view(ctx, d->nf, 1, d->area3d), *orient = nn_view(ctx, d->nf, 1, d->orient);
    nn_tensor *loss = nn_fill(ctx, 1, 1, 0);
    if (o->lambda_angle > 0)
        loss = nn_add(ctx, loss, nn_scale(ctx, param_loss_angle(ctx, uv, &d->corners, nn_view(ctx, 3 * d->nf, 1, d->cos3d)),
                                          (float)o->lambda_angle));
    if (o->lambda_conformal > 0)
        loss = nn_add(ctx, loss, nn_scale(ctx, param_loss_conformal(ctx, uv, &d->corners, nn_view(ctx, d->nf, 4, d->frame_inv),
                                                                    nn_view(ctx, d->nf, 1, d->weight), orient),
                                          (float)o->lambda_conformal));
    if (o->lambda_iso > 0)
        loss = nn_add(ctx, loss, nn_scale(ctx, param_loss_iso(ctx, uv, d->ei, d->ej, nn_view(ctx, d->ne, 1, d->elen), d->ne),
                                          (float)o->lambda_iso));
    if (o->lambda_area > 0)
        loss = nn_add(ctx, loss, nn_scale(ctx, param_loss_area(ctx, uv, &d->corners, area3d, orient),
                                          (float)o->lambda_area));
    if (o->lambda_fold > 0)
        loss = nn_add(ctx, loss, nn_scale(ctx, param_loss_fold_barrier(ctx, uv, &d->corners, area3d, orient,
                                                                       (float)o->fold_eps),
                                          (float)o->lambda_fold));
    return loss;
}

/* Boundary vertices held around a place where the boundary met itself
 * (mean edge lengths), and how many such places a chart may have before it stops. */
#define PIN_RADIUS 3.0
#define MAX_PINNINGS 16
#define FROZEN (-1)

neuv_status uv_refine(const neuv_mesh *m, const int *face_chart, int n_charts, const uv_refine_options *o,
                      double *corner_uv, uv_refine_report *rep)
{
    uv_refine_report local_rep;
    if (!rep) rep = &local_rep;
    memset(rep, 0, sizeof *rep);
    if (!m || !face_chart || !corner_uv || !o || n_charts < 1)
        return error_set(NEUV_ERR_INPUT, "UV refinement needs a mesh, charts, UVs and options");
    if (o->iters <= 0) return NEUV_OK;
    if (!(o->lr > 0) || !(o->fold_eps >= 0) || (o->accept && o->check_every < 1))
        return error_set(NEUV_ERR_INPUT, "bad UV refinement options (rate %g, check every %d)", o->lr, o->check_every);
    for (int f = 0; f < m->nf; f++)
        if (face_chart[f] < 0 || face_chart[f] >= n_charts)
            return error_set(NEUV_ERR_INPUT, "face %d has chart %d outside 0..%d", f, face_chart[f], n_charts - 1);
    double t0 = now_seconds();
    refine_data d;
    neuv_status s = refine_data_build(m, face_chart, n_charts, corner_uv, &d);
    if (s != NEUV_OK) return s;

    nn_params params;
    nn_params_init(&params);
    nn_adam adam = {0};
    nn_ctx *ctx = NULL;
    double *sum = mem_alloc(sizeof(double) * (size_t)n_charts);
    int *bad0 = mem_alloc(sizeof(int) * (size_t)n_charts), *bad1 = mem_alloc(sizeof(int) * (size_t)n_charts);
    int *fails = mem_calloc((size_t)n_charts, sizeof(int));   /* failed accept tests; FROZEN: stopped */
    unsigned char *pinned = mem_calloc((size_t)(d.nv > 0 ? d.nv : 1), 1), *mark = mem_calloc((size_t)(d.nv > 0 ? d.nv : 1), 1);
    float *snap = mem_alloc(sizeof(float) * 2 * (size_t)(d.nv > 0 ? d.nv : 1));
    nn_tensor *uv = nn_params_add(&params, d.nv, 2, "uv");
    if (!sum || !bad0 || !bad1 || !fails || !pinned || !mark || !snap || !uv) { s = error_nomem("UV refinement"); goto done; }
    memcpy(uv->data, d.uv0, sizeof(float) * 2 * (size_t)d.nv);
    memcpy(snap, d.uv0, sizeof(float) * 2 * (size_t)d.nv);
    chart_orientation(&d, d.uv0, n_charts, sum);
    for (int f = 0; f < d.nf; f++) d.orient[f] = sum[d.fchart[f]] < 0 ? -1.0f : 1.0f;
    count_bad(&d, d.uv0, n_charts, bad0);

    nn_adam_config ac = nn_adam_defaults();
    ac.lr = (float)o->lr;
    lr_decay sched = {o->iters};
    ac.schedule = lr_decay_at;
    ac.schedule_user = &sched;
    s = nn_adam_init(&adam, &params, &ac);
    if (s != NEUV_OK) goto done;
    ctx = nn_ctx_create(0);
    if (!ctx) { s = error_nomem("UV refinement"); goto done; }
    int n_frozen = 0;
    for (int it = 0; it < o->iters && n_frozen < n_charts; it++) {
        nn_ctx_reset(ctx);
        nn_tensor *loss = refine_loss(ctx, &d, o, uv);
        nn_params_zero_grad(&params);
        s = nn_backward(ctx, loss);
        if (s != NEUV_OK) goto done;
        if (!isfinite(loss->data[0])) {
            s = error_set(NEUV_ERR_INTERNAL, "UV refinement loss is not finite at step %d", it);
            goto done;
        }
        if (it == 0) rep->loss_start = loss->data[0];
        rep->loss_end = loss->data[0];
        nn_adam_step(&adam);
        for (int i = 0; i < d.nv; i++)
            if (pinned[i]) { uv->data[2 * i] = snap[2 * i]; uv->data[2 * i + 1] = snap[2 * i + 1]; }
        rep->iters = it + 1;
        if ((it % 50 == 0 || it == o->iters - 1) &&
            log_progress("refine", (double)(it + 1) / o->iters, "step %d loss %.5f", it + 1, rep->loss_end))
            { s = error_cancelled(); goto done; }
        if (!o->accept || ((it + 1) % o->check_every != 0 && it != o->iters - 1)) continue;
        for (int c = 0; c < n_charts; c++) {
            if (fails[c] == FROZEN) continue;
            write_chart(&d, uv->data, c, corner_uv);
            int ok = o->accept(o->accept_user, c, corner_uv);
            if (ok < 0) { s = error_nomem("UV refinement check"); goto done; }
            if (ok) { copy_chart(&d, c, snap, uv->data); continue; }
            /* Back to the last accepted map, with the boundary vertices near
             * where the boundary met itself held there from now on; a chart
             * that keeps failing, or fails for another reason, stops there. */
            int met = boundary_meetings(&d, c, uv->data, mark);
            copy_chart(&d, c, uv->data, snap);
            if (met > 0 && ++fails[c] <= MAX_PINNINGS) {
                if (fails[c] == 1) rep->charts_pinned++;
                pin_near_marks(&d, c, snap, mark, pinned, PIN_RADIUS);
                continue;
            }
            for (int i = d.vfirst[c]; i < d.vfirst[c + 1]; i++) { pinned[i] = 1; mark[i] = 0; }
            fails[c] = FROZEN;
            n_frozen++;
            rep->charts_stopped++;
        }
    }
    /* A chart the refinement made worse keeps its starting map. */
    count_bad(&d, uv->data, n_charts, bad1);
    for (int c = 0; c < n_charts; c++) {
        int revert = bad1[c] > bad0[c];
        rep->charts_reverted += revert;
        write_chart(&d, revert ? d.uv0 : uv->data, c, corner_uv);
    }
    s = NEUV_OK;
done:
    nn_ctx_free(ctx);
    nn_adam_free(&adam);
    nn_params_free(&params);
    mem_free(sum); mem_free(bad0); mem_free(bad1); mem_free(fails); mem_free(pinned); mem_free(mark); mem_free(snap);
    refine_data_free(&d);
    rep->seconds = now_seconds() - t0;
    return s;
}

neuv_status uv_refine_chart(const neuv_mesh *sub, const uv_refine_options *o, double *uv, uv_refine_report *rep)
{
    if (!sub || !uv) return error_set(NEUV_ERR_INPUT, "UV refinement needs a chart and its UVs");
    int *zero = mem_calloc((size_t)(sub->nf > 0 ? sub->nf : 1), sizeof(int));
    double *corner = mem_alloc(sizeof(double) * 6 * (size_t)(sub->nf > 0 ? sub->nf : 1));
    if (!zero || !corner) { mem_free(zero); mem_free(corner); return error_nomem("UV refinement"); }
    for (int f = 0; f < sub->nf; f++)
        for (int q = 0; q < 3; q++) {
            int v = sub->tri[3 * f + q];
            corner[6 * (size_t)f + 2 * q] = uv[2 * v];
            corner[6 * (size_t)f + 2 * q + 1] = uv[2 * v + 1];
        }
    neuv_status s = uv_refine(sub, zero, 1, o, corner, rep);
    if (s == NEUV_OK)
        for (int f = 0; f < sub->nf; f++)
            for (int q = 0; q < 3; q++) {
                int v = sub->tri[3 * f + q];
                uv[2 * v] = corner[6 * (size_t)f + 2 * q];
                uv[2 * v + 1] = corner[6 * (size_t)f + 2 * q + 1];
            }
    mem_free(zero);
    mem_free(corner);
    return s;
}
