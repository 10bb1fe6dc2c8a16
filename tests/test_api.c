/* The public API (include/neuv/neuv.h) used as an application would: meshes
 * from arrays, the atlas's stages one by one and at once, outputs per mesh,
 * callbacks and cancellation, models, packing and metrics of existing UVs,
 * and two atlases on two threads. Only the public header is included. */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "neuv/neuv.h"
#include "check.h"

/* A cylinder without caps around the z axis: rings of `around` vertices,
 * `rows` rows of quads, each split into two triangles (a disk topology
 * once cut, unwrapped in well under a second with LSCM). */
typedef struct grid {
    float pos[64 * 64 * 3];
    uint32_t idx[64 * 64 * 6];
    int nv, ni;
} grid;

static void make_cylinder(grid *g, int around, int rows, float radius, float z0)
{
    g->nv = 0;
    g->ni = 0;
    for (int r = 0; r <= rows; r++)
        for (int a = 0; a < around; a++) {
            double t = 2 * 3.14159265358979323846 * a / around;
            g->pos[3 * g->nv] = (float)(radius * cos(t));
            g->pos[3 * g->nv + 1] = (float)(radius * sin(t));
            g->pos[3 * g->nv + 2] = z0 + (float)r / rows;
            g->nv++;
        }
    for (int r = 0; r < rows; r++)
        for (int a = 0; a < around; a++) {
            uint32_t v00 = (uint32_t)(r * around + a), v01 = (uint32_t)(r * around + (a + 1) % around);
            uint32_t v10 = v00 + (uint32_t)around, v11 = v01 + (uint32_t)around;
            uint32_t q[6] = {v00, v01, v11, v00, v11, v10};
            memcpy(g->idx + g->ni, q, sizeof q);
            g->ni += 6;
        }
}

static void decl_of(const grid *g, neuv_mesh_decl *d)
{
    neuv_mesh_decl_init(d);
    d->positions = g->pos;
    d->vertex_count = g->nv;
    d->indices = g->idx;
    d->index_count = g->ni;
}

/* Options for a short run: two charts, 30 training steps, no cache. */
static neuv_unwrap_options quick_options(neuv_method method)
{
    neuv_unwrap_options uo;
    neuv_unwrap_options_init(&uo);
    uo.method = method;
    uo.use_cache = 0;
    uo.charts = 2;
    uo.iters = 30;
    uo.refine = 0;
    uo.threads = 1;
    return uo;
}

static void test_mesh_from_arrays(void)
{
    /* Interleaved double positions with a stride, uint16 indices. */
    struct { double p[3]; double pad; } v[4] = {{{0, 0, 0}, 9}, {{1, 0, 0}, 9}, {{1, 1, 0}, 9}, {{0, 1, 0}, 9}};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    neuv_mesh_decl d;
    neuv_mesh_decl_init(&d);
    d.positions = v;
    d.position_type = NEUV_FLOAT64;
    d.position_stride = sizeof v[0];
    d.vertex_count = 4;
    d.indices = idx;
    d.index_type = NEUV_UINT16;
    d.index_count = 6;
    neuv_mesh *m = NULL;
    CHECK(neuv_mesh_create(&d, &m) == NEUV_OK);
    CHECK_INT(neuv_mesh_vertex_count(m), 4);
    CHECK_INT(neuv_mesh_face_count(m), 2);
    double p[12];
    int t[6];
    neuv_mesh_get_positions(m, p);
    neuv_mesh_get_indices(m, t);
    CHECK(p[3 * 2] == 1 && p[3 * 2 + 1] == 1 && p[3 * 2 + 2] == 0);
    CHECK(t[4] == 2 && t[5] == 3);
    CHECK_INT(neuv_mesh_has_uv(m), 0);
    neuv_mesh_free(m);

    /* Bad arrays: an error with a message, nothing allocated. */
    idx[4] = 7;
    m = (neuv_mesh *)&d;
    CHECK(neuv_mesh_create(&d, &m) == NEUV_ERR_INPUT && m == NULL);
    CHECK(strstr(neuv_last_error(), "index 4 is 7") != NULL);
    idx[4] = 2;
    d.index_count = 5;
    CHECK(neuv_mesh_create(&d, &m) == NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "multiple of 3") != NULL);
    d.index_count = 6;
    v[1].p[2] = NAN;
    CHECK(neuv_mesh_create(&d, &m) == NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "vertex 1") != NULL);
    v[1].p[2] = 0;
    d.position_stride = 8;
    CHECK(neuv_mesh_create(&d, &m) == NEUV_ERR_INPUT);
    CHECK(neuv_mesh_create(NULL, &m) == NEUV_ERR_INPUT);

    /* Per-vertex UVs become per-corner UVs. */
    float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    d.position_stride = sizeof v[0];
    d.uvs = uv;
    CHECK(neuv_mesh_create(&d, &m) == NEUV_OK);
    double cu[12];
    CHECK_INT(neuv_mesh_get_corner_uvs(m, cu), 1);
    CHECK(cu[2 * 4] == 1 && cu[2 * 4 + 1] == 1 && cu[2 * 5] == 0 && cu[2 * 5 + 1] == 1);
    neuv_metrics mt;
    CHECK(neuv_evaluate(m, NULL, &mt) == NEUV_OK);
    CHECK_NEAR(mt.qce_mean, 1.0, 1e-12);
    CHECK_INT(mt.flipped, 0);
    CHECK_NEAR(mt.packing_efficiency, 1.0, 1e-12);
    neuv_mesh_free(m);
}

/* Checks an atlas output against the mesh it came from: xref positions,
 * UVs in the unit square, no triangle turned over. */
static void check_output(const neuv_atlas_output *o, const grid *g, int faces)
{
    CHECK_INT(o->index_count, 3 * faces);
    int bad_xref = 0, outside = 0, flipped = 0;
    for (int i = 0; i < o->vertex_count; i++) {
        if (o->xref[i] < 0 || o->xref[i] >= g->nv) bad_xref++;
        if (o->uvs[2 * i] < 0 || o->uvs[2 * i] > 1 || o->uvs[2 * i + 1] < 0 || o->uvs[2 * i + 1] > 1) outside++;
    }
    for (int f = 0; f < o->index_count / 3; f++) {
        const double *a = o->uvs + 2 * o->indices[3 * f], *b = o->uvs + 2 * o->indices[3 * f + 1],
                     *c = o->uvs + 2 * o->indices[3 * f + 2];
        double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if (!(area > 0)) flipped++;
    }
    CHECK_INT(bad_xref, 0);
    CHECK_INT(outside, 0);
    CHECK_INT(flipped, 0);
    /* Each output triangle's corners are the input triangle's vertices. */
    int mismatched = 0;
    for (int f = 0; f < o->index_count / 3; f++) {
        uint32_t in[3], out[3];
        for (int k = 0; k < 3; k++) { in[k] = g->idx[3 * f + k]; out[k] = (uint32_t)o->xref[o->indices[3 * f + k]]; }
        int same = 0;
        for (int s = 0; s < 3; s++) same |= in[0] == out[s] && in[1] == out[(s + 1) % 3] && in[2] == out[(s + 2) % 3];
        mismatched += !same;
    }
    CHECK_INT(mismatched, 0);
}

static void test_stages_and_generate(void)
{
    static grid g;
    make_cylinder(&g, 24, 8, 0.5f, 0);
    neuv_mesh_decl d;
    decl_of(&g, &d);

    /* All at once. */
    neuv_unwrap_options uo = quick_options(NEUV_METHOD_LSCM);
    neuv_atlas *one = NULL;
    CHECK(neuv_atlas_create(&one) == NEUV_OK);
    CHECK(neuv_atlas_add_mesh(one, &d) == NEUV_OK);
    CHECK(neuv_atlas_generate(one, &uo) == NEUV_OK);
    CHECK_INT(neuv_atlas_stage(one), 3);
    neuv_atlas_output o1;
    CHECK(neuv_atlas_get_output(one, 0, &o1) == NEUV_OK);
    check_output(&o1, &g, g.ni / 3);
    neuv_report rep;
    CHECK(neuv_atlas_get_report(one, &rep) == NEUV_OK);
    CHECK_INT(rep.input_faces, g.ni / 3);
    CHECK_INT(rep.charts_by_source[NEUV_SOURCE_LSCM], rep.charts);
    CHECK_INT(rep.metrics.flipped, 0);
    CHECK(rep.metrics.overlap_fraction == 0);
    neuv_chart_info ci;
    CHECK(neuv_atlas_get_chart(one, 0, &ci) == NEUV_OK);
    CHECK(ci.source == NEUV_SOURCE_LSCM && isnan(ci.network_qce) && ci.qce >= 1 && ci.faces > 0);
    CHECK(neuv_atlas_get_chart(one, rep.charts, &ci) == NEUV_ERR_INPUT);
    neuv_metrics again;
    CHECK(neuv_evaluate(neuv_atlas_mesh(one), NULL, &again) == NEUV_OK);
    CHECK(again.qce_mean == rep.metrics.qce_mean && again.packing_efficiency == rep.metrics.packing_efficiency);
    char *json = neuv_atlas_report_json(one, "cylinder", 0, 0);
    CHECK(json && strstr(json, "\"lscm\"") && strstr(json, "\"input\":\"cylinder\""));
    neuv_free(json);

    /* Stage by stage with the same options: the same bytes. */
    neuv_atlas *staged = NULL;
    CHECK(neuv_atlas_create(&staged) == NEUV_OK);
    CHECK(neuv_atlas_add_mesh(staged, &d) == NEUV_OK);
    CHECK(neuv_atlas_parameterize(staged, NULL) == NEUV_ERR_INPUT); /* charts first */
    neuv_chart_options co;
    neuv_chart_options_init(&co);
    co.charts = 2;
    co.use_cache = 0;
    co.iters = 30;
    neuv_param_options po;
    neuv_param_options_init(&po);
    po.method = NEUV_METHOD_LSCM;
    po.iters = 30;
    neuv_pack_options ko;
    neuv_pack_options_init(&ko);
    CHECK(neuv_atlas_compute_charts(staged, &co) == NEUV_OK);
    CHECK_INT(neuv_atlas_stage(staged), 1);
    CHECK(neuv_atlas_chart_count(staged) >= 2);
    CHECK(neuv_atlas_get_output(staged, 0, &o1) == NEUV_ERR_INPUT); /* not packed yet */
    CHECK(neuv_atlas_parameterize(staged, &po) == NEUV_OK);
    CHECK(neuv_atlas_pack(staged, &ko) == NEUV_OK);
    neuv_atlas_output o2;
    CHECK(neuv_atlas_get_output(staged, 0, &o2) == NEUV_OK);
    CHECK(neuv_atlas_get_output(one, 0, &o1) == NEUV_OK);
    CHECK_INT(o2.vertex_count, o1.vertex_count);
    CHECK(o2.vertex_count == o1.vertex_count && !memcmp(o1.uvs, o2.uvs, sizeof(double) * 2 * (size_t)o1.vertex_count));

    /* Packing again at another size changes the layout; at the first size
     * it is the same again (packing runs from the parameterized charts). */
    ko.resolution = 256;
    ko.padding = 8;
    CHECK(neuv_atlas_pack(staged, &ko) == NEUV_OK);
    CHECK(neuv_atlas_get_output(staged, 0, &o2) == NEUV_OK);
    CHECK(memcmp(o1.uvs, o2.uvs, sizeof(double) * 2 * (size_t)o1.vertex_count) != 0);
    neuv_pack_options_init(&ko);
    CHECK(neuv_atlas_pack(staged, &ko) == NEUV_OK);
    CHECK(neuv_atlas_get_output(staged, 0, &o2) == NEUV_OK);
    CHECK(!memcmp(o1.uvs, o2.uvs, sizeof(double) * 2 * (size_t)o1.vertex_count));
    ko.padding = -1;
    CHECK(neuv_atlas_pack(staged, &ko) == NEUV_ERR_INPUT);
    CHECK_INT(neuv_atlas_stage(staged), 3); /* a refused call keeps the atlas */
    neuv_atlas_destroy(staged);
    neuv_atlas_destroy(one);
}

static void test_two_meshes(void)
{
    static grid a, b;
    make_cylinder(&a, 16, 6, 0.5f, 0);
    make_cylinder(&b, 12, 4, 0.3f, 3);
    neuv_mesh_decl da, db;
    decl_of(&a, &da);
    decl_of(&b, &db);
    neuv_atlas *atlas = NULL;
    CHECK(neuv_atlas_create(&atlas) == NEUV_OK);
    CHECK(neuv_atlas_add_mesh(atlas, &da) == NEUV_OK);
    CHECK(neuv_atlas_add_mesh(atlas, &db) == NEUV_OK);
    CHECK_INT(neuv_atlas_mesh_count(atlas), 2);
    neuv_unwrap_options uo = quick_options(NEUV_METHOD_LSCM);
    CHECK(neuv_atlas_generate(atlas, &uo) == NEUV_OK);
    neuv_atlas_output oa, ob;
    CHECK(neuv_atlas_get_output(atlas, 0, &oa) == NEUV_OK);
    CHECK(neuv_atlas_get_output(atlas, 1, &ob) == NEUV_OK);
    check_output(&oa, &a, a.ni / 3);
    check_output(&ob, &b, b.ni / 3);
    CHECK(neuv_atlas_get_output(atlas, 2, &oa) == NEUV_ERR_INPUT);
    neuv_atlas_destroy(atlas);
}

typedef struct counter {
    int progress, logs, cancel_after;
} counter;

static int count_progress(void *user, const char *stage, double fraction, const char *detail)
{
    (void)stage; (void)fraction; (void)detail;
    counter *c = user;
    c->progress++;
    return c->cancel_after <= 0 || c->progress < c->cancel_after;
}

static void count_log(void *user, neuv_log_level level, const char *message)
{
    (void)level; (void)message;
    ((counter *)user)->logs++;
}

static void test_callbacks_and_cancel(void)
{
    static grid g;
    make_cylinder(&g, 16, 5, 0.5f, 0);
    neuv_mesh_decl d;
    decl_of(&g, &d);
    neuv_unwrap_options uo = quick_options(NEUV_METHOD_NEURAL);

    /* Each atlas reports to its own callbacks. */
    counter c1 = {0, 0, 0}, c2 = {0, 0, 0};
    neuv_callbacks cb1 = {count_log, count_progress, &c1}, cb2 = {count_log, count_progress, &c2};
    neuv_atlas *a1 = NULL, *a2 = NULL;
    CHECK(neuv_atlas_create(&a1) == NEUV_OK && neuv_atlas_create(&a2) == NEUV_OK);
    neuv_atlas_set_callbacks(a1, &cb1);
    neuv_atlas_set_callbacks(a2, &cb2);
    CHECK(neuv_atlas_add_mesh(a1, &d) == NEUV_OK && neuv_atlas_add_mesh(a2, &d) == NEUV_OK);
    CHECK(neuv_atlas_generate(a1, &uo) == NEUV_OK);
    CHECK(c1.progress > 10);
    CHECK_INT(c2.progress, 0);

    /* A progress callback that returns 0 cancels: the call stops with
     * NEUV_ERR_CANCELLED and the atlas keeps no stage. */
    c2.cancel_after = 5;
    CHECK(neuv_atlas_generate(a2, &uo) == NEUV_ERR_CANCELLED);
    CHECK_INT(c2.progress, 5);
    CHECK_INT(neuv_atlas_stage(a2), 0);
    CHECK(strstr(neuv_last_error(), "cancelled") != NULL);
    CHECK(neuv_atlas_mesh(a2) == NULL);
    c2.cancel_after = 0;
    CHECK(neuv_atlas_generate(a2, &uo) == NEUV_OK); /* and runs again */
    neuv_atlas_output o1, o2;
    CHECK(neuv_atlas_get_output(a1, 0, &o1) == NEUV_OK && neuv_atlas_get_output(a2, 0, &o2) == NEUV_OK);
    CHECK(o1.vertex_count == o2.vertex_count && !memcmp(o1.uvs, o2.uvs, sizeof(double) * 2 * (size_t)o1.vertex_count));
    neuv_atlas_destroy(a1);
    neuv_atlas_destroy(a2);
}

/* Cancels at the first progress report of the heads solved on the full mesh
 * (a mesh trained on a simplified copy), which run side by side. */
typedef struct heads_cancel {
    int seen, after;
} heads_cancel;

static int cancel_at_heads(void *user, const char *stage, double fraction, const char *detail)
{
    (void)stage; (void)fraction;
    heads_cancel *h = user;
    if (h->seen) h->after++;
    if (detail && strstr(detail, "heads solved on this mesh")) h->seen = 1;
    return !h->seen;
}

static void test_cancel_heads_on_mesh(void)
{
    static grid g;
    make_cylinder(&g, 32, 12, 0.5f, 0);
    neuv_mesh_decl d;
    decl_of(&g, &d);
    neuv_unwrap_options uo = quick_options(NEUV_METHOD_NEURAL);
    uo.train_faces = 300;
    uo.threads = 2;
    heads_cancel h = {0, 0};
    neuv_callbacks cb = {NULL, cancel_at_heads, &h};
    neuv_atlas *a = NULL;
    CHECK(neuv_atlas_create(&a) == NEUV_OK);
    neuv_atlas_set_callbacks(a, &cb);
    CHECK(neuv_atlas_add_mesh(a, &d) == NEUV_OK);
    CHECK(neuv_atlas_generate(a, &uo) == NEUV_ERR_CANCELLED);
    CHECK_INT(h.seen, 1);
    CHECK_INT(h.after, 0);
    CHECK_INT(neuv_atlas_stage(a), 0);
    neuv_atlas_destroy(a);
}

/* Two unwraps with the neural method on two threads at once give the bytes
 * of one after the other. */
typedef struct job {
    const neuv_mesh_decl *mesh;
    neuv_unwrap_options opts;
    neuv_status status;
    double *uvs;
    int n;
} job;

static void *run_job(void *arg)
{
    job *j = arg;
    neuv_atlas *a = NULL;
    j->status = neuv_atlas_create(&a);
    if (j->status == NEUV_OK) j->status = neuv_atlas_add_mesh(a, j->mesh);
    if (j->status == NEUV_OK) j->status = neuv_atlas_generate(a, &j->opts);
    neuv_atlas_output o;
    if (j->status == NEUV_OK) j->status = neuv_atlas_get_output(a, 0, &o);
    if (j->status == NEUV_OK) {
        j->n = 2 * o.vertex_count;
        j->uvs = malloc(sizeof(double) * (size_t)j->n);
        if (j->uvs) memcpy(j->uvs, o.uvs, sizeof(double) * (size_t)j->n);
    }
    neuv_atlas_destroy(a);
    return NULL;
}

static void test_two_threads(void)
{
    static grid g1, g2;
    make_cylinder(&g1, 16, 5, 0.5f, 0);
    make_cylinder(&g2, 14, 6, 0.4f, 0);
    neuv_mesh_decl d1, d2;
    decl_of(&g1, &d1);
    decl_of(&g2, &d2);
    neuv_unwrap_options uo = quick_options(NEUV_METHOD_NEURAL);
    uo.refine = 20;
    job seq[2] = {{&d1, uo, NEUV_OK, NULL, 0}, {&d2, uo, NEUV_OK, NULL, 0}};
    job par[2] = {{&d1, uo, NEUV_OK, NULL, 0}, {&d2, uo, NEUV_OK, NULL, 0}};
    run_job(&seq[0]);
    run_job(&seq[1]);
    pthread_t t[2];
    for (int i = 0; i < 2; i++) CHECK(pthread_create(&t[i], NULL, run_job, &par[i]) == 0);
    for (int i = 0; i < 2; i++) pthread_join(t[i], NULL);
    for (int i = 0; i < 2; i++) {
        CHECK(seq[i].status == NEUV_OK && par[i].status == NEUV_OK);
        CHECK(seq[i].n > 0 && seq[i].n == par[i].n);
        CHECK(seq[i].uvs && par[i].uvs && !memcmp(seq[i].uvs, par[i].uvs, sizeof(double) * (size_t)seq[i].n));
        free(seq[i].uvs);
        free(par[i].uvs);
    }
}

static void test_models(void)
{
    static grid g;
    make_cylinder(&g, 16, 5, 0.5f, 0);
    neuv_mesh_decl d;
    decl_of(&g, &d);
    neuv_unwrap_options uo = quick_options(NEUV_METHOD_NEURAL);
    neuv_atlas *a = NULL;
    CHECK(neuv_atlas_create(&a) == NEUV_OK && neuv_atlas_add_mesh(a, &d) == NEUV_OK);
    neuv_model *model = NULL, *model2 = NULL;
    CHECK(neuv_atlas_generate(a, &uo) == NEUV_OK);
    CHECK(neuv_atlas_take_model(a, &model) == NEUV_ERR_INPUT && model == NULL); /* not kept */
    uo.keep_model = 1;
    CHECK(neuv_atlas_generate(a, &uo) == NEUV_OK);
    CHECK(neuv_atlas_take_model(a, &model) == NEUV_OK && model);
    CHECK(!neuv_model_is_category(model));
    const char *file = tmp_path("test_api_model.neuv");
    CHECK(neuv_model_save(model, file) == NEUV_OK);
    neuv_model_free(model);
    model = NULL;
    CHECK(neuv_model_load(file, &model) == NEUV_OK);

    /* Applied to the same triangulation: the same atlas. */
    neuv_atlas *b = NULL;
    CHECK(neuv_atlas_create(&b) == NEUV_OK && neuv_atlas_add_mesh(b, &d) == NEUV_OK);
    neuv_apply_options ao;
    neuv_apply_options_init(&ao);
    ao.finetune = 5;
    CHECK(neuv_atlas_apply_model(b, model, &ao) == NEUV_ERR_INPUT); /* category models only */
    CHECK(strstr(neuv_last_error(), "finetune") != NULL);
    /* Every field a surface model cannot honour is refused by name, none ignored. */
    const char *refused[] = {"resolution", "padding", "refine", "allow_overlaps", "shared_layer", "keep_model"};
    for (int k = 0; k < 6; k++) {
        neuv_apply_options_init(&ao);
        if (k == 0) ao.resolution = 512;
        if (k == 1) ao.padding = 4;
        if (k == 2) ao.refine = 0;
        if (k == 3) ao.allow_overlaps = 1;
        if (k == 4) ao.shared_layer = 1;
        if (k == 5) ao.keep_model = 1;
        CHECK(neuv_atlas_apply_model(b, model, &ao) == NEUV_ERR_INPUT);
        CHECK(strncmp(neuv_last_error(), refused[k], strlen(refused[k])) == 0);
        CHECK_INT(neuv_atlas_stage(b), 0); /* refused before any work */
    }
    neuv_apply_options_init(&ao);
    CHECK(neuv_atlas_apply_model(b, model, &ao) == NEUV_OK);
    CHECK(neuv_atlas_take_model(b, &model2) == NEUV_ERR_INPUT && model2 == NULL); /* nothing kept */
    neuv_report ra, rb;
    CHECK(neuv_atlas_get_report(a, &ra) == NEUV_OK && neuv_atlas_get_report(b, &rb) == NEUV_OK);
    CHECK_INT(rb.from_model, 1);
    CHECK_INT(rb.metrics.flipped, 0);
    /* The float32 networks evaluated chart by chart here, over every vertex at
     * once in training: OpenBLAS may round a row's last bit differently in
     * another batch (2.2e-9 of qce_mean measured with OPENBLAS_CORETYPE=Haswell,
     * 0 with the default kernel). */
    CHECK_NEAR(rb.metrics.qce_mean, ra.metrics.qce_mean, 1e-7);
    neuv_model_free(model);
    remove(file);
    neuv_atlas_destroy(a);
    neuv_atlas_destroy(b);
}

static void test_pack_existing(void)
{
    neuv_mesh *m = NULL;
    CHECK(neuv_shape("capsule", -1, &m) == NEUV_OK);
    neuv_mesh_free(m);
    CHECK(neuv_shape("capsule", 3, &m) == NEUV_ERR_INPUT);
    CHECK(neuv_shape("teapot", -1, &m) == NEUV_ERR_INPUT);
    neuv_atlas *a = NULL;
    CHECK(neuv_shape("capsule", -1, &m) == NEUV_OK);
    CHECK(neuv_atlas_create(&a) == NEUV_OK && neuv_atlas_add_loaded_mesh(a, m) == NEUV_OK);
    neuv_mesh_free(m);
    neuv_unwrap_options uo;
    neuv_unwrap_options_init(&uo);
    uo.method = NEUV_METHOD_LSCM;
    uo.use_cache = 0;
    uo.iters = 30;
    CHECK(neuv_atlas_generate(a, &uo) == NEUV_OK);
    /* The atlas's mesh, its charts repacked at another size. */
    int nf = neuv_mesh_face_count(neuv_atlas_mesh(a));
    double *uv = malloc(sizeof(double) * 6 * (size_t)nf);
    CHECK(uv && neuv_mesh_get_corner_uvs(neuv_atlas_mesh(a), uv) == 1);
    neuv_mesh *copy = NULL;
    {
        /* Rebuilt from arrays: one vertex per corner, so charts are found by welding. */
        int nv = neuv_mesh_vertex_count(neuv_atlas_mesh(a));
        double *pos = malloc(sizeof(double) * 3 * (size_t)nv), *cpos = malloc(sizeof(double) * 9 * (size_t)nf);
        int *tri = malloc(sizeof(int) * 3 * (size_t)nf);
        neuv_mesh_get_positions(neuv_atlas_mesh(a), pos);
        neuv_mesh_get_indices(neuv_atlas_mesh(a), tri);
        for (int c = 0; c < 3 * nf; c++) memcpy(cpos + 3 * c, pos + 3 * tri[c], sizeof(double) * 3);
        neuv_mesh_decl d;
        neuv_mesh_decl_init(&d);
        d.positions = cpos;
        d.position_type = NEUV_FLOAT64;
        d.vertex_count = 3 * nf;
        d.uvs = uv;
        d.uv_type = NEUV_FLOAT64;
        CHECK(neuv_mesh_create(&d, &copy) == NEUV_OK);
        free(pos);
        free(cpos);
        free(tri);
    }
    neuv_metrics before, after;
    CHECK(neuv_evaluate(copy, NULL, &before) == NEUV_OK);
    neuv_pack_options ko;
    neuv_pack_options_init(&ko);
    ko.resolution = 512;
    ko.padding = 4;
    neuv_pack_report pr;
    CHECK(neuv_pack_uvs(copy, &ko, NULL, &pr) == NEUV_OK);
    CHECK(neuv_evaluate(copy, NULL, &after) == NEUV_OK);
    CHECK_INT(pr.charts, before.charts);
    CHECK_NEAR(after.qce_mean, before.qce_mean, 1e-9); /* packing only moves, turns and scales charts */
    CHECK_INT(after.flipped, 0);
    CHECK(after.overlap_fraction == 0);
    CHECK(after.packing_efficiency > 0.4);
    neuv_mesh_free(copy);
    free(uv);
    neuv_atlas_destroy(a);
}

/* Whether the two faces of `atlas`'s mesh on edge (a, b) carry different
 * UVs at a or at b (the edge is a seam of the atlas); -1 when the edge does
 * not have two faces. */
static int uv_split_at(const neuv_mesh *m, int a, int b)
{
    int nf = neuv_mesh_face_count(m);
    int *tri = malloc(sizeof(int) * 3 * (size_t)nf);
    double *uv = malloc(sizeof(double) * 6 * (size_t)nf);
    neuv_mesh_get_indices(m, tri);
    neuv_mesh_get_corner_uvs(m, uv);
    int face[2], n = 0;
    for (int f = 0; f < nf && n < 3; f++) {
        int has_a = 0, has_b = 0;
        for (int k = 0; k < 3; k++) { has_a |= tri[3 * f + k] == a; has_b |= tri[3 * f + k] == b; }
        if (has_a && has_b) { if (n < 2) face[n] = f; n++; }
    }
    int split = -1;
    if (n == 2) {
        split = 0;
        for (int v = 0; v < 2; v++) {
            int w = v ? b : a;
            const double *p = NULL, *q = NULL;
            for (int k = 0; k < 3; k++) {
                if (tri[3 * face[0] + k] == w) p = uv + 6 * face[0] + 2 * k;
                if (tri[3 * face[1] + k] == w) q = uv + 6 * face[1] + 2 * k;
            }
            if (p[0] != q[0] || p[1] != q[1]) split = 1;
        }
    }
    free(tri);
    free(uv);
    return split;
}

/* Seams given as vertex pairs: a ring around the cylinder's middle and the
 * first column of its lower half. No chart crosses them (the two faces of
 * every seam edge have different UVs at an end), the report counts them,
 * and a pair that is no edge is counted as unmatched, not guessed. */
static void test_user_seams(void)
{
    static grid g;
    int around = 16, rows = 6;
    make_cylinder(&g, around, rows, 0.5f, 0);
    neuv_mesh_decl d;
    decl_of(&g, &d);
    int pairs[2 * 64], n = 0;
    for (int a = 0; a < around; a++) { /* the ring of vertices at mid height */
        pairs[2 * n] = 3 * around + a;
        pairs[2 * n + 1] = 3 * around + (a + 1) % around;
        n++;
    }
    for (int r = 0; r < 3; r++) { pairs[2 * n] = r * around; pairs[2 * n + 1] = (r + 1) * around; n++; }
    pairs[2 * n] = 0; pairs[2 * n + 1] = 5 * around + 7; n++; /* no edge */
    neuv_unwrap_options uo = quick_options(NEUV_METHOD_LSCM);
    uo.charts = 1;
    uo.seam_edges = pairs;
    uo.seam_edge_count = n;
    neuv_atlas *at = NULL;
    CHECK(neuv_atlas_create(&at) == NEUV_OK);
    CHECK(neuv_atlas_add_mesh(at, &d) == NEUV_OK);
    CHECK(neuv_atlas_generate(at, &uo) == NEUV_OK);
    const neuv_mesh *m = neuv_atlas_mesh(at);
    CHECK_INT(neuv_mesh_vertex_count(m), g.nv); /* the copies along the seams are joined again */
    for (int i = 0; i < n - 1; i++) CHECK_INT(uv_split_at(m, pairs[2 * i], pairs[2 * i + 1]), 1);
    neuv_report rep;
    CHECK(neuv_atlas_get_report(at, &rep) == NEUV_OK);
    CHECK(rep.charts >= 2); /* the ring cuts the cylinder in two */
    CHECK_INT(rep.metrics.flipped, 0);
    CHECK(rep.metrics.overlap_fraction == 0);
    char *json = neuv_atlas_report_json(at, "cylinder", 0, 0);
    char want[160];
    snprintf(want, sizeof want, "\"required_edges\":%d,\"above_angle\":0,\"user_pairs\":%d,"
             "\"user_pairs_unmatched\":1,", n - 1, n);
    CHECK(json && strstr(json, want) && strstr(json, "\"from_normals\":0,\"from_materials\":0,") &&
          strstr(json, "\"crossed\":0}"));
    if (json && !strstr(json, want)) fprintf(stderr, "  want %s in %s\n", want, strstr(json, "\"seams\""));
    neuv_free(json);
    neuv_atlas_destroy(at);

    /* Without the seams the middle ring is crossed somewhere. */
    uo.seam_edges = NULL;
    uo.seam_edge_count = 0;
    CHECK(neuv_atlas_create(&at) == NEUV_OK);
    CHECK(neuv_atlas_add_mesh(at, &d) == NEUV_OK);
    CHECK(neuv_atlas_generate(at, &uo) == NEUV_OK);
    int crossed = 0;
    for (int a = 0; a < around; a++) crossed += uv_split_at(neuv_atlas_mesh(at), pairs[2 * a], pairs[2 * a + 1]) == 0;
    CHECK(crossed > 0);
    neuv_atlas_destroy(at);

    /* Refused: an index out of range; seams with a model to keep. */
    uo.seam_edges = pairs;
    uo.seam_edge_count = n;
    pairs[1] = g.nv;
    CHECK(neuv_atlas_create(&at) == NEUV_OK);
    CHECK(neuv_atlas_add_mesh(at, &d) == NEUV_OK);
    CHECK(neuv_atlas_generate(at, &uo) == NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "seam edge 0") != NULL);
    pairs[1] = 3 * around + 1;
    uo.keep_model = 1;
    CHECK(neuv_atlas_generate(at, &uo) == NEUV_ERR_INPUT);
    neuv_atlas_destroy(at);
}

/* neuv_atlas_output_mesh: the mesh as read (quads, materials, its own
 * UVs) with the atlas as its UVs, written back with its quads and
 * materials; the refusals. */
static void test_output_mesh(void)
{
    /* A strip of 6 quads in two materials, with UVs of its own. */
    char obj[2048];
    int n = snprintf(obj, sizeof obj, "mtllib strip.mtl\n");
    for (int i = 0; i <= 6; i++)
        n += snprintf(obj + n, sizeof obj - (size_t)n, "v %d 0 0\nv %d 1 0.%d\n", i, i, i);
    for (int i = 0; i <= 6; i++) n += snprintf(obj + n, sizeof obj - (size_t)n, "vt 0.%d 0\nvt 0.%d 1\n", i, i);
    for (int i = 0; i < 6; i++) {
        if (i % 3 == 0) n += snprintf(obj + n, sizeof obj - (size_t)n, "usemtl m%d\n", i / 3);
        int a = 2 * i + 1;
        n += snprintf(obj + n, sizeof obj - (size_t)n, "f %d/%d %d/%d %d/%d %d/%d\n", a, a, a + 2, a + 2, a + 3,
                      a + 3, a + 1, a + 1);
    }
    const char *in_path = write_tmp_file("test_api_strip.obj", obj, (size_t)n);
    neuv_mesh *in = NULL, *other = NULL, *out = NULL;
    CHECK_INT(neuv_mesh_load(in_path, NULL, &in), NEUV_OK);
    if (!in) return;
    CHECK_INT(neuv_mesh_face_count(in), 12);
    neuv_atlas *atlas = NULL;
    CHECK_INT(neuv_atlas_create(&atlas), NEUV_OK);
    CHECK_INT(neuv_atlas_add_loaded_mesh(atlas, in), NEUV_OK);
    CHECK_INT(neuv_atlas_output_mesh(atlas, 0, in, 0, &out), NEUV_ERR_INPUT); /* not packed yet */
    CHECK(out == NULL);
    neuv_unwrap_options uo = quick_options(NEUV_METHOD_LSCM);
    uo.charts = 1;
    CHECK_INT(neuv_atlas_generate(atlas, &uo), NEUV_OK);
    CHECK_INT(neuv_atlas_output_mesh(atlas, 0, in, 0, &out), NEUV_OK);
    CHECK_INT(neuv_mesh_vertex_count(out), neuv_mesh_vertex_count(in));
    CHECK_INT(neuv_mesh_face_count(out), 12);
    const char *out_path = tmp_path("test_api_strip_uv.obj");
    CHECK_INT(neuv_mesh_save(out, out_path), NEUV_OK);
    neuv_mesh_free(out);
    out = NULL;
    /* Six quads of four corners, each under its material, and new UVs. */
    FILE *fp = fopen(out_path, "r");
    char line[256];
    int quads = 0, materials = 0, vt = 0, other_faces = 0;
    while (fp && fgets(line, sizeof line, fp)) {
        if (!strncmp(line, "usemtl m", 8)) materials++;
        if (!strncmp(line, "vt ", 3)) vt++;
        if (!strncmp(line, "f ", 2)) {
            int corners = 0;
            for (char *t = strtok(line + 2, " \n"); t; t = strtok(NULL, " \n")) corners++;
            if (corners == 4) quads++;
            else other_faces++;
        }
    }
    if (fp) fclose(fp);
    CHECK_INT(quads, 6);
    CHECK_INT(other_faces, 0);
    CHECK_INT(materials, 2);
    CHECK_INT(vt, 16); /* two charts (the material border is a seam): its 2 vertices twice */
    /* The first UV set kept: a mesh without UVs is refused, as is a
     * second set in OBJ. */
    CHECK_INT(neuv_atlas_output_mesh(atlas, 0, in, 1, &out), NEUV_OK);
    CHECK_INT(neuv_mesh_save(out, tmp_path("test_api_strip_uv1.obj")), NEUV_ERR_INPUT);
    neuv_mesh_free(out);
    out = NULL;
    CHECK_INT(neuv_atlas_output_mesh(atlas, 0, in, 2, &out), NEUV_ERR_INPUT);
    CHECK_INT(neuv_atlas_output_mesh(atlas, 1, in, 0, &out), NEUV_ERR_INPUT);
    /* Another mesh of the same size is not the one added. */
    float pos[14 * 3];
    uint32_t idx[12 * 3];
    for (int v = 0; v < 14; v++) { pos[3 * v] = (float)(v / 2); pos[3 * v + 1] = (float)(v % 2); pos[3 * v + 2] = 0; }
    for (int i = 0; i < 6; i++) {
        uint32_t a = (uint32_t)(2 * i), q[6] = {a, a + 2, a + 3, a, a + 3, a + 1};
        memcpy(idx + 6 * i, q, sizeof q);
    }
    neuv_mesh_decl d;
    neuv_mesh_decl_init(&d);
    d.positions = pos;
    d.vertex_count = 14;
    d.indices = idx;
    d.index_count = 36;
    CHECK_INT(neuv_mesh_create(&d, &other), NEUV_OK);
    CHECK_INT(neuv_atlas_output_mesh(atlas, 0, other, 0, &out), NEUV_ERR_INPUT);
    CHECK_INT(neuv_atlas_output_mesh(atlas, 0, other, 1, &out), NEUV_ERR_INPUT); /* and it has no UVs */
    CHECK(out == NULL);
    neuv_mesh_free(other);
    neuv_atlas_destroy(atlas);
    neuv_mesh_free(in);
}

/* neuv_set_threads sets the calling thread's OpenMP threads; below 1 it changes nothing. */
static void test_set_threads(void)
{
    int before = omp_get_max_threads();
    neuv_set_threads(1);
    CHECK_INT(omp_get_max_threads(), 1);
    neuv_set_threads(0);
    neuv_set_threads(-3);
    CHECK_INT(omp_get_max_threads(), 1);
    neuv_set_threads(3);
    CHECK_INT(omp_get_max_threads(), 3);
    neuv_set_threads(before);
}

int main(void)
{
    test_set_threads();
    test_mesh_from_arrays();
    test_stages_and_generate();
    test_two_meshes();
    test_user_seams();
    test_output_mesh();
    test_callbacks_and_cancel();
    test_cancel_heads_on_mesh();
    test_models();
    test_pack_existing();
    test_two_threads();
    return check_report("test_api");
}
