/* PatchNet: loss values on hand-checkable cases, their gradients by finite
 * differences, the re-seeding of an emptied patch on a hand-made case, the
 * cube's six sides as six charts for ten seeds, disk charts covering
 * every face on a sphere, a torus and fertility.off, one network trained on
 * several shapes, and determinism. */
#include <math.h>

#include "check.h"
#include "charts/charts.h"
#include "core/rng.h"
#include "geometry/operators.h"
#include "losses/patch_losses.h"
#include "mesh/clean.h"
#include "mesh/shape_family.h"
#include "mesh/shapes.h"
#include "models/patchnet.h"
#include "models/patchnet_split.h"
#include "segment/patchnet_segment.h"

#ifdef __SANITIZE_ADDRESS__
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

/* Two unit-area faces with normals z and x. */
static void test_cos_values(void)
{
    nn_ctx *ctx = nn_ctx_create(0);
    float area[2] = {1, 1}, normal[6] = {0, 0, 1, 1, 0, 0};
    nn_tensor *a = nn_from(ctx, 2, 1, area), *n = nn_from(ctx, 2, 3, normal);
    float one[2] = {1, 1};
    nn_tensor *l = patch_loss_cos(ctx, nn_from(ctx, 2, 1, one), a, n);
    CHECK_NEAR(l->data[0], 1 - 1 / sqrt(2.0), 1e-6);      /* m = (1,0,1)/√2 */
    float eye[4] = {1, 0, 0, 1};
    l = patch_loss_cos(ctx, nn_from(ctx, 2, 2, eye), a, n);
    CHECK_NEAR(l->data[0], 0, 1e-6);                      /* each face its own patch */
    float half[4] = {0.5f, 0.5f, 0.5f, 0.5f};
    l = patch_loss_cos(ctx, nn_from(ctx, 2, 2, half), a, n);
    CHECK_NEAR(l->data[0], 1 - 1 / sqrt(2.0), 1e-6);
    /* Unequal areas 3 and 1 in one patch: m ∝ (1,0,3), n·m = 3/√10 and 1/√10. */
    float area2[2] = {3, 1};
    l = patch_loss_cos(ctx, nn_from(ctx, 2, 1, one), nn_from(ctx, 2, 1, area2), n);
    CHECK_NEAR(l->data[0], (3 * (1 - 3 / sqrt(10.0)) + (1 - 1 / sqrt(10.0))) / 4, 1e-6);
    nn_ctx_free(ctx);
}

/* Full-sum L_geo in double, for comparison. */
static double geo_reference(int nf, int k, const float *P, const float *a, const float *D)
{
    double num = 0, den = 0;
    for (int c = 0; c < k; c++) {
        double s = 0;
        for (int f = 0; f < nf; f++) {
            s += a[f] * P[f * k + c];
            for (int g = 0; g < nf; g++) num += (double)a[f] * a[g] * P[f * k + c] * P[g * k + c] * D[f * nf + g];
        }
        den += s * s;
    }
    return num / den;
}

static void test_geo_values(void)
{
    nn_ctx *ctx = nn_ctx_create(0);
    /* Two faces, areas 2 and 1, distance 0.5, one patch:
     * 2 · 2 · 1 · 0.5 / (3)² = 2/9. */
    float area[2] = {2, 1}, D[4] = {0, 0.5f, 0.5f, 0}, one[2] = {1, 1};
    int all[2] = {0, 1};
    nn_tensor *l = patch_loss_geo(ctx, nn_from(ctx, 2, 1, one), nn_from(ctx, 2, 1, area), all, 2,
                                  nn_from(ctx, 2, 2, D));
    CHECK_NEAR(l->data[0], 2.0 / 9.0, 1e-6);
    /* Each face its own patch: no pair shares a patch, L_geo = 0. */
    float eye[4] = {1, 0, 0, 1};
    l = patch_loss_geo(ctx, nn_from(ctx, 2, 2, eye), nn_from(ctx, 2, 1, area), all, 2, nn_from(ctx, 2, 2, D));
    CHECK_NEAR(l->data[0], 0, 1e-7);
    /* Random case: all faces as sources equals the double reference; a
     * half sample is (F/S) times the partial sum over its rows. */
    enum { F = 12, K = 3 };
    rng r;
    rng_seed(&r, 5);
    float P[F * K], a[F], Dm[F * F];
    for (int f = 0; f < F; f++) {
        a[f] = (float)(0.5 + rng_uniform(&r));
        double s = 0, e[K];
        for (int c = 0; c < K; c++) s += e[c] = exp(2 * rng_normal(&r));
        for (int c = 0; c < K; c++) P[f * K + c] = (float)(e[c] / s);
    }
    for (int f = 0; f < F; f++)
        for (int g = 0; g <= f; g++) Dm[f * F + g] = Dm[g * F + f] = f == g ? 0 : (float)rng_uniform(&r);
    int src[F];
    for (int f = 0; f < F; f++) src[f] = f;
    l = patch_loss_geo(ctx, nn_from(ctx, F, K, P), nn_from(ctx, F, 1, a), src, F, nn_from(ctx, F, F, Dm));
    CHECK_NEAR(l->data[0], geo_reference(F, K, P, a, Dm), 1e-5);
    int half[6] = {1, 2, 5, 7, 8, 11};
    float Dh[6 * F];
    for (int s = 0; s < 6; s++) memcpy(Dh + s * F, Dm + half[s] * F, sizeof(float) * F);
    l = patch_loss_geo(ctx, nn_from(ctx, F, K, P), nn_from(ctx, F, 1, a), half, 6, nn_from(ctx, 6, F, Dh));
    double num = 0, den = 0;
    for (int c = 0; c < K; c++) {
        double sc = 0;
        for (int f = 0; f < F; f++) sc += a[f] * P[f * K + c];
        den += sc * sc;
        for (int s = 0; s < 6; s++)
            for (int g = 0; g < F; g++)
                num += (double)a[half[s]] * a[g] * P[half[s] * K + c] * P[g * K + c] * Dm[half[s] * F + g];
    }
    CHECK_NEAR(l->data[0], (F / 6.0) * num / den, 1e-5);
    nn_ctx_free(ctx);
}

/* Gradients of both losses with respect to logits Z (P = softmax(Z)). */
static double loss_of(nn_ctx *ctx, nn_tensor *Z, int which, int F, const float *a, const float *n, const int *src,
                      int S, const float *D)
{
    nn_ctx_reset(ctx);
    nn_tensor *P = nn_softmax_rows(ctx, Z);
    nn_tensor *l = which == 0 ? patch_loss_cos(ctx, P, nn_from(ctx, F, 1, a), nn_from(ctx, F, 3, n))
                              : patch_loss_geo(ctx, P, nn_from(ctx, F, 1, a), src, S, nn_from(ctx, S, F, D));
    return l->data[0];
}

static void test_loss_gradients(void)
{
    enum { F = 10, K = 4, S = 5 };
    rng r;
    rng_seed(&r, 17);
    float a[F], n[F * 3], D[S * F];
    int src[S] = {0, 3, 4, 6, 9};
    for (int f = 0; f < F; f++) {
        a[f] = (float)(0.3 + rng_uniform(&r));
        double v[3], s = 0;
        for (int d = 0; d < 3; d++) { v[d] = rng_normal(&r); s += v[d] * v[d]; }
        for (int d = 0; d < 3; d++) n[3 * f + d] = (float)(v[d] / sqrt(s));
    }
    for (int i = 0; i < S * F; i++) D[i] = (float)rng_uniform(&r);
    nn_tensor *Z = nn_param_create(F, K, "z");
    for (int i = 0; i < F * K; i++) Z->data[i] = (float)rng_normal(&r);
    nn_ctx *ctx = nn_ctx_create(0);
    for (int which = 0; which < 2; which++) {
        loss_of(ctx, Z, which, F, a, n, src, S, D);
        nn_ctx_reset(ctx);
        nn_tensor *P = nn_softmax_rows(ctx, Z);
        nn_tensor *l = which == 0 ? patch_loss_cos(ctx, P, nn_from(ctx, F, 1, a), nn_from(ctx, F, 3, n))
                                  : patch_loss_geo(ctx, P, nn_from(ctx, F, 1, a), src, S, nn_from(ctx, S, F, D));
        memset(Z->grad, 0, sizeof(float) * F * K);
        CHECK(nn_backward(ctx, l) == NEUV_OK);
        float g[F * K];
        memcpy(g, Z->grad, sizeof g);
        double worst = 0, gmax = 0;
        for (int i = 0; i < F * K; i++) {
            float s = Z->data[i];
            double h = 1e-2;
            Z->data[i] = (float)(s + h);
            double lp = loss_of(ctx, Z, which, F, a, n, src, S, D);
            Z->data[i] = (float)(s - h);
            double lm = loss_of(ctx, Z, which, F, a, n, src, S, D);
            Z->data[i] = s;
            worst = fmax(worst, fabs((lp - lm) / (2 * h) - g[i]));
            gmax = fmax(gmax, fabs(g[i]));
        }
        CHECK(gmax > 1e-3);
        CHECK(worst < 2e-3 * fmax(gmax, 1e-2) + 2e-4);
        if (!(worst < 2e-3 * fmax(gmax, 1e-2) + 2e-4))
            fprintf(stderr, "%s: worst gradient error %g (max gradient %g)\n", which ? "L_geo" : "L_cos", worst, gmax);
    }
    nn_ctx_free(ctx);
    nn_param_free(Z);
}

typedef struct segmented {
    int *chart;
    int n;
    patchnet_report rep;
} segmented;

static int segment(const neuv_mesh *m, const patchnet_options *o, segmented *s)
{
    operators ops;
    operators_params p = operators_default_params();
    if (operators_compute(m, &p, &ops) != NEUV_OK) return 0;
    s->chart = malloc(sizeof(int) * m->nf);
    neuv_status st = patchnet_segment(m, &ops, o, s->chart, &s->n, NULL, NULL, &s->rep);
    operators_free(&ops);
    if (st) fprintf(stderr, "patchnet_segment: %s\n", neuv_last_error());
    return st == NEUV_OK;
}

/* Every face in exactly one chart id in 0..n-1, every chart non-empty and a disk. */
static void check_disk_cover(const neuv_mesh *m, const segmented *s, const char *what)
{
    int *count = calloc(s->n, sizeof(int)), bad = 0;
    for (int f = 0; f < m->nf; f++) {
        if (s->chart[f] < 0 || s->chart[f] >= s->n) bad++;
        else count[s->chart[f]]++;
    }
    CHECK_INT(bad, 0);
    int empty = 0, nondisk = 0;
    for (int c = 0; c < s->n; c++) {
        if (!count[c]) empty++;
        if (chart_is_disk(m, s->chart, c) != 1) nondisk++;
    }
    CHECK_INT(empty, 0);
    CHECK_INT(nondisk, 0);
    printf("%s: %d faces, %d charts, worst LSCM qce %.4f, %d iterations\n", what, m->nf, s->n, s->rep.worst_qce,
           s->rep.iterations);
    free(count);
}

/* Re-seeding: four faces, all won by patch 0, two facing +z (hidden
 * features (1, 0)) and two facing +x (hidden (0, 1)); patches 1 and 2 are
 * empty. The move splits patch 0 by its normals into patch 1 (the emptier
 * by index): afterwards the two pairs have their argmax on patches 0 and 1,
 * logit_1 - logit_0 = ±gap on them exactly, and patch 2's column is untouched. */
static void test_split_empty(void)
{
    enum { F = 4, K = 3, C = 2 };
    int fv[3 * F];
    for (int c = 0; c < 3; c++)
        for (int f = 0; f < F; f++) fv[c * F + f] = f; /* face f's corners all at vertex f */
    diffusion_net_geometry g = {.nv = F, .nf = F, .face_vertex = fv};
    float hidden[F * C] = {1, 0, 1, 0, 0, 1, 0, 1};
    float normal[3 * F] = {0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0};
    float area[F] = {1, 1, 1, 1};
    float P[F * K];
    for (int f = 0; f < F; f++) { P[f * K] = 0.8f; P[f * K + 1] = 0.1f; P[f * K + 2] = 0.1f; }
    float w[C * K] = {0.5f, -0.25f, 0.125f, 0.25f, 0.5f, -0.375f}, b[K] = {0.1f, 0.2f, 0.3f};
    float w0[C * K], b0[K];
    memcpy(w0, w, sizeof w);
    memcpy(b0, b, sizeof b);
    patchnet_split mv;
    patchnet_split_empty(P, hidden, &g, area, normal, K, C, 0.05, 4.0, w, b, &mv);
    CHECK_INT(mv.empty, 1);
    CHECK_INT(mv.split, 0);
    CHECK_NEAR(mv.moved_share, 0.5, 1e-12);
    double diff[F];
    for (int f = 0; f < F; f++) {
        double z[K];
        for (int k = 0; k < K; k++) z[k] = b[k] + hidden[f * C] * w[k] + hidden[f * C + 1] * w[K + k];
        diff[f] = z[1] - z[0];
        CHECK_NEAR(fabs(diff[f]), 4.0, 1e-5);
    }
    CHECK_NEAR(diff[0], diff[1], 1e-6);   /* each pair on one patch */
    CHECK_NEAR(diff[2], diff[3], 1e-6);
    CHECK_NEAR(diff[0], -diff[2], 1e-5);  /* and the pairs on different patches */
    CHECK(w[2] == w0[2] && w[K + 2] == w0[K + 2] && b[2] == b0[2]);
    /* No patch under the share: nothing moves. */
    for (int f = 0; f < F; f++)
        for (int k = 0; k < K; k++) P[f * K + k] = k == (f < 2 ? f : 2) ? 0.8f : 0.1f; /* faces 0, 1, {2, 3} */
    memcpy(w, w0, sizeof w);
    patchnet_split_empty(P, hidden, &g, area, normal, K, C, 0.05, 4.0, w, b, &mv);
    CHECK_INT(mv.empty, -1);
    CHECK(!memcmp(w, w0, sizeof w));
    /* Hidden features that cannot tell the halves apart (a cube's sides under
     * HKS input): no move either. */
    for (int f = 0; f < F; f++) { P[f * K] = 0.8f; P[f * K + 1] = 0.1f; P[f * K + 2] = 0.1f; }
    float same[F * C] = {1, 1, 1, 1, 1, 1, 1, 1};
    patchnet_split_empty(P, same, &g, area, normal, K, C, 0.05, 4.0, w, b, &mv);
    CHECK_INT(mv.empty, -1);
    CHECK(!memcmp(w, w0, sizeof w));
}

/* Cube with K = 6, default input (HKS and normals), seeds 1..10 (issue 20,
 * item 5): each chart is one whole side (all faces of a chart share the
 * normal, and there are six charts of equal size). Before the re-seeding of
 * emptied patches, xyz input found the sides for 6 of these 10 seeds and HKS
 * alone for none. NEUV_TEST_SEED runs one seed. */
static void test_cube_sides(void)
{
    neuv_mesh *m = shape_cube(6);
    int first_seed = 1, last_seed = 10, found = 0;
    if (getenv("NEUV_TEST_SEED")) first_seed = last_seed = atoi(getenv("NEUV_TEST_SEED"));
    for (int seed = first_seed; seed <= last_seed; seed++) {
        patchnet_options o;
        patchnet_default_options(&o);
        o.charts = 6;
        o.seed = (uint64_t)seed;
        segmented s;
        CHECK(segment(m, &o, &s));
        int mixed = 0, uneven = 0;
        for (int c = 0; c < s.n; c++) {
            double n0[3] = {0, 0, 0};
            int first = 1, count = 0;
            for (int f = 0; f < m->nf; f++) {
                if (s.chart[f] != c) continue;
                double n[3];
                mesh_face_normal(m, f, n);
                if (first) { memcpy(n0, n, sizeof n); first = 0; }
                else if (n[0] * n0[0] + n[1] * n0[1] + n[2] * n0[2] < 0.99) mixed++;
                count++;
            }
            uneven += count != m->nf / 6;
        }
        int ok = s.n == 6 && !mixed && !uneven;
        found += ok;
        printf("cube seed %d: %d faces, %d charts%s, loss_cos %.4f after %d iterations, %d re-seeded\n", seed, m->nf,
               s.n, ok ? " (the six sides)" : "", s.rep.loss_cos, s.rep.iterations, s.rep.reseeds);
        free(s.chart);
    }
    CHECK_INT(found, last_seed - first_seed + 1);
    mesh_free(m);
}

static void test_auto_disks(void)
{
    patchnet_options o;
    patchnet_default_options(&o);
    if (SANITIZED) o.iters = 40;
    neuv_mesh *sphere = shape_icosphere(SANITIZED ? 2 : 3, 1.0);
    segmented s;
    CHECK(segment(sphere, &o, &s));
    check_disk_cover(sphere, &s, "sphere");
    CHECK(s.rep.worst_qce < o.max_distortion);
    /* Same seed, same threads: identical charts. */
    segmented s2;
    CHECK(segment(sphere, &o, &s2));
    CHECK_INT(s2.n, s.n);
    CHECK(!memcmp(s.chart, s2.chart, sizeof(int) * sphere->nf));
    free(s.chart);
    free(s2.chart);
    mesh_free(sphere);

    neuv_mesh *torus = shape_torus(1.0, 0.35, SANITIZED ? 24 : 48, SANITIZED ? 12 : 20);
    CHECK(segment(torus, &o, &s));
    check_disk_cover(torus, &s, "torus");
    CHECK(s.rep.worst_qce < o.max_distortion);
    free(s.chart);
    mesh_free(torus);

    const char *path = shared_path("meshes/fertility.off");
    if (!path || SANITIZED) return;
    neuv_mesh *m = NULL;
    if (neuv_mesh_load(path, NULL, &m) != NEUV_OK) { printf("fertility.off not readable: skipped\n"); return; }
    CHECK(mesh_clean(m, NULL, NULL) == NEUV_OK);
    CHECK(segment(m, &o, &s));
    check_disk_cover(m, &s, "fertility");
    CHECK(s.rep.worst_qce < o.max_distortion || s.n >= o.max_charts);
    free(s.chart);
    mesh_free(m);
}

/* One network trained on two members of the bent-capsule family (a category
 * model's PatchNet): labels on both and on an unseen member cut into disk
 * charts covering every face, several patches used on each, and the same
 * bytes twice. */
static void test_several_shapes(void)
{
    neuv_mesh *m[3];
    operators ops[3];
    operators_params p = operators_default_params();
    for (int i = 0; i < 3; i++) {
        m[i] = shape_capsule_family((uint64_t)i);
        CHECK(m[i] && operators_compute(m[i], &p, &ops[i]) == NEUV_OK);
    }
    patchnet_options o;
    patchnet_default_options(&o);
    o.charts = 4;
    o.iters = SANITIZED ? 10 : 80;
    const neuv_mesh *ms[2] = {m[0], m[1]};
    const operators *os[2] = {&ops[0], &ops[1]};
    float *x = NULL;
    int dim = 0;
    CHECK(diffusion_net_input_features(m[0], &ops[0], o.features, &x, &dim) == NEUV_OK);
    free(x);
    patchnet_model a, b;
    CHECK(patchnet_model_create(&a, &o, dim, 4) == NEUV_OK);
    CHECK(patchnet_model_create(&b, &o, dim, 4) == NEUV_OK);
    patchnet_report rep;
    CHECK(patchnet_train_shapes(&a, ms, os, 2, &o, &rep) == NEUV_OK);
    CHECK(rep.iterations > 0 && rep.iterations <= o.iters && isfinite(rep.loss));
    CHECK(patchnet_train_shapes(&b, ms, os, 2, &o, NULL) == NEUV_OK);
    CHECK_INT(patchnet_train_shapes(&b, ms, os, 0, &o, NULL), NEUV_ERR_INPUT);
    const char *names[3] = {"family member 0 (trained)", "family member 1 (trained)", "family member 2 (unseen)"};
    for (int i = 0; i < 3; i++) {
        int *la = malloc(sizeof(int) * m[i]->nf), *lb = malloc(sizeof(int) * m[i]->nf), used[4] = {0};
        CHECK(patchnet_infer(&a, m[i], &ops[i], la) == NEUV_OK);
        CHECK(patchnet_infer(&b, m[i], &ops[i], lb) == NEUV_OK);
        CHECK(!memcmp(la, lb, sizeof(int) * m[i]->nf));
        for (int f = 0; f < m[i]->nf; f++) used[la[f]] = 1;
        CHECK(used[0] + used[1] + used[2] + used[3] >= 2);
        segmented sg;
        memset(&sg, 0, sizeof sg);
        sg.chart = malloc(sizeof(int) * m[i]->nf);
        CHECK(patchnet_charts_from_model(&a, m[i], &ops[i], &o, sg.chart, &sg.n, NULL, NULL, &sg.rep) == NEUV_OK);
        sg.rep.iterations = rep.iterations;
        check_disk_cover(m[i], &sg, names[i]);
        free(sg.chart); free(la); free(lb);
    }
    patchnet_model_free(&a);
    patchnet_model_free(&b);
    for (int i = 0; i < 3; i++) { operators_free(&ops[i]); mesh_free(m[i]); }
}

int main(void)
{
    nn_set_threads(1);
    test_cos_values();
    test_geo_values();
    test_loss_gradients();
    test_split_empty();
    test_cube_sides();
    test_auto_disks();
    test_several_shapes();
    return check_report("test_patchnet");
}
