/* The public calls behind the CLI's commands other than unwrap (include/
 * neuv/neuv.h, from "cleaning and topology" to "checkpoint files"), used
 * as an application would: meshes from arrays or the built-in shapes, the
 * structs and JSON documents they give, their errors. Only the public
 * header is included. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "neuv/neuv.h"
#include "check.h"

/* A flat n by n grid of quads on [0,1]^2, each split in two: one disk. */
typedef struct grid {
    double pos[33 * 33 * 3 + 3];
    int idx[32 * 32 * 6];
    int nv, ni;
} grid;

static void make_grid(grid *g, int n)
{
    g->nv = 0;
    g->ni = 0;
    for (int y = 0; y <= n; y++)
        for (int x = 0; x <= n; x++) {
            g->pos[3 * g->nv] = (double)x / n;
            g->pos[3 * g->nv + 1] = (double)y / n;
            g->pos[3 * g->nv + 2] = 0;
            g->nv++;
        }
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            int v00 = y * (n + 1) + x, v10 = v00 + 1, v01 = v00 + n + 1, v11 = v01 + 1;
            int q[6] = {v00, v10, v11, v00, v11, v01};
            memcpy(g->idx + g->ni, q, sizeof q);
            g->ni += 6;
        }
}

static neuv_mesh *mesh_of(const double *pos, int nv, const int *idx, int ni, const double *uvs)
{
    neuv_mesh_decl d;
    neuv_mesh_decl_init(&d);
    d.positions = pos;
    d.position_type = NEUV_FLOAT64;
    d.vertex_count = nv;
    d.indices = idx;
    d.index_type = NEUV_INT32;
    d.index_count = ni;
    d.uvs = uvs;
    d.uv_type = NEUV_FLOAT64;
    neuv_mesh *m = NULL;
    CHECK(neuv_mesh_create(&d, &m) == NEUV_OK);
    return m;
}

static neuv_mesh *grid_mesh(int n, int with_uv)
{
    static grid g;
    make_grid(&g, n);
    double *uv = malloc(sizeof(double) * 2 * (size_t)g.nv);
    for (int v = 0; v < g.nv; v++) { uv[2 * v] = g.pos[3 * v]; uv[2 * v + 1] = g.pos[3 * v + 1]; }
    neuv_mesh *m = mesh_of(g.pos, g.nv, g.idx, g.ni, with_uv ? uv : NULL);
    free(uv);
    return m;
}

/* A Moebius strip of 2 * n triangles: one non-orientable component. */
static neuv_mesh *moebius(int n)
{
    double pos[2 * 64 * 3];
    int idx[2 * 64 * 3], ni = 0;
    for (int i = 0; i < n; i++) {
        double t = 2 * 3.14159265358979323846 * i / n;
        for (int s = -1; s <= 1; s += 2) {
            double r = 1 + 0.3 * s * cos(t / 2);
            double *p = pos + 3 * (2 * i + (s > 0));
            p[0] = r * cos(t);
            p[1] = r * sin(t);
            p[2] = 0.3 * s * sin(t / 2);
        }
    }
    for (int i = 0; i < n; i++) {
        int a0 = 2 * i, a1 = 2 * i + 1, b0 = i + 1 < n ? 2 * i + 2 : 1, b1 = i + 1 < n ? 2 * i + 3 : 0;
        int f[6] = {a0, b0, b1, a0, b1, a1};
        memcpy(idx + ni, f, sizeof f);
        ni += 6;
    }
    return mesh_of(pos, 2 * n, idx, ni, NULL);
}

static int warnings;
static void count_warnings(void *user, neuv_log_level level, const char *message)
{
    (void)user;
    (void)message;
    if (level == NEUV_LOG_WARN) warnings++;
}

static void test_topology(void)
{
    /* A tetrahedron, a square of two triangles, a degenerate face and an unused vertex. */
    const double pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1,  5, 0, 0, 6, 0, 0, 6, 1, 0, 5, 1, 0,  9, 9, 9};
    const int idx[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3,  4, 5, 6, 4, 6, 7,  4, 5, 5};
    neuv_mesh *m = mesh_of(pos, 9, idx, 21, NULL);
    neuv_topology t;
    CHECK(neuv_mesh_topology(m, NULL, &t) == NEUV_OK);
    CHECK_INT(t.input_vertices, 9);
    CHECK_INT(t.input_faces, 7);
    CHECK_INT(t.vertices, 8);
    CHECK_INT(t.faces, 6);
    CHECK_INT(t.has_uv, 0);
    CHECK_INT(t.repairs.degenerate_faces, 1);
    CHECK_INT(t.repairs.unreferenced_vertices, 1);
    CHECK_INT(t.component_count, 2);
    CHECK(t.components && t.components[0].closed && t.components[0].genus == 0 && t.components[0].euler == 2);
    CHECK(t.components && !t.components[1].closed && t.components[1].boundary_loops == 1 &&
          t.components[1].faces == 2 && t.components[1].edges == 5);
    CHECK_INT(neuv_mesh_face_count(m), 7); /* the caller's mesh is not cleaned */
    char *json = neuv_topology_json(&t, "two.obj");
    CHECK(json && strstr(json, "\"input\":\"two.obj\"") && strstr(json, "\"degenerate_faces\":1") &&
          strstr(json, "\"components\":[{\"faces\":4,"));
    neuv_free(json);
    neuv_free(t.components);
    neuv_mesh_free(m);

    /* Every face dropped: no error, no components. */
    const double flat[] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    const int line[] = {0, 1, 2};
    m = mesh_of(flat, 3, line, 3, NULL);
    CHECK(neuv_mesh_topology(m, NULL, &t) == NEUV_OK);
    CHECK_INT(t.faces, 0);
    CHECK_INT(t.component_count, 0);
    neuv_free(t.components);
    neuv_clean_report rep;
    CHECK(neuv_mesh_clean(m, NULL, &rep) == NEUV_ERR_INPUT); /* as neuv_mesh_clean */
    neuv_mesh_free(m);

    /* The warning about a non-orientable component reaches the callbacks. */
    neuv_callbacks cb = {count_warnings, NULL, NULL};
    m = moebius(24);
    warnings = 0;
    CHECK(neuv_mesh_topology(m, &cb, &t) == NEUV_OK);
    CHECK_INT(warnings, 1);
    CHECK_INT(t.repairs.nonorientable_components, 1);
    neuv_free(t.components);
    warnings = 0;
    CHECK(neuv_mesh_clean(m, &cb, &rep) == NEUV_OK);
    CHECK_INT(warnings, 1);
    CHECK_INT(rep.nonorientable_components, 1);
    neuv_mesh_free(m);

    CHECK(neuv_mesh_topology(NULL, NULL, &t) == NEUV_ERR_INPUT && t.components == NULL);
}

static void test_flatten(void)
{
    for (int method = NEUV_METHOD_LSCM; method <= NEUV_METHOD_HARMONIC; method++) {
        neuv_mesh *m = grid_mesh(8, 0);
        neuv_flatten_report r;
        CHECK(neuv_flatten(m, (neuv_method)method, NULL, &r) == NEUV_OK);
        CHECK(neuv_mesh_has_uv(m));
        CHECK_INT(r.metrics.flipped, 0);
        if (method == NEUV_METHOD_LSCM) CHECK_NEAR(r.metrics.qce_mean, 1, 1e-6); /* a flat square: conformal */
        int nf = neuv_mesh_face_count(m);
        double *uv = malloc(sizeof(double) * 6 * (size_t)nf), lo = 1, hi = 0;
        CHECK(neuv_mesh_get_corner_uvs(m, uv) == 1);
        for (int i = 0; i < 6 * nf; i++) { lo = fmin(lo, uv[i]); hi = fmax(hi, uv[i]); }
        CHECK(lo >= 0 && hi <= 1 && hi - lo > 0.999); /* scaled into the unit square */
        free(uv);
        neuv_mesh_free(m);
    }
    /* Not a disk, or not a classic method: refused, the mesh unchanged. */
    neuv_mesh *s = NULL;
    CHECK(neuv_shape("sphere", -1, &s) == NEUV_OK);
    int nv = neuv_mesh_vertex_count(s);
    CHECK(neuv_flatten(s, NEUV_METHOD_LSCM, NULL, NULL) == NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "not a disk") != NULL);
    CHECK(!neuv_mesh_has_uv(s) && neuv_mesh_vertex_count(s) == nv);
    CHECK(neuv_flatten(s, NEUV_METHOD_NEURAL, NULL, NULL) == NEUV_ERR_INPUT);
    neuv_mesh_free(s);
}

static void test_geodesics(void)
{
    static grid g;
    make_grid(&g, 16);
    /* One more vertex, used by no face. */
    g.pos[3 * g.nv] = 5;
    g.pos[3 * g.nv + 1] = 5;
    g.pos[3 * g.nv + 2] = 5;
    neuv_mesh *m = mesh_of(g.pos, g.nv + 1, g.idx, g.ni, NULL);
    int nv = neuv_mesh_vertex_count(m);
    double *d = malloc(sizeof(double) * (size_t)nv), t = 0;
    CHECK(neuv_geodesic_distances(m, 0, NULL, d, &t) == NEUV_OK);
    CHECK(d[0] == 0);
    /* Within the heat method's smoothing on a 16 by 16 grid (0.948 and 1.424). */
    CHECK_NEAR(d[16], 1, 0.1);             /* along the edge y = 0 */
    CHECK_NEAR(d[g.nv - 1], sqrt(2), 0.1); /* the opposite corner */
    CHECK(isinf(d[g.nv]));                 /* the unused vertex */
    CHECK(t > 0);
    char *json = neuv_geodesics_json("grid", 0, d, nv, 0.5);
    CHECK(json && strstr(json, "\"distances\":[0,") && strstr(json, ",null],\"seconds\":0.5}"));
    neuv_free(json);
    CHECK(neuv_geodesic_distances(m, g.nv, NULL, d, NULL) == NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "used by no face") != NULL);
    CHECK(neuv_geodesic_distances(m, nv, NULL, d, NULL) == NEUV_ERR_INPUT);
    CHECK(neuv_geodesic_distances(m, -1, NULL, d, NULL) == NEUV_ERR_INPUT);
    free(d);
    neuv_mesh_free(m);
}

static void test_operators(void)
{
    neuv_mesh *s = NULL;
    CHECK(neuv_shape("sphere", -1, &s) == NEUV_OK);
    neuv_operator_options o;
    neuv_operator_options_init(&o);
    CHECK_INT(o.k, 64);
    CHECK_INT(o.use_cache, 1);
    o.k = 8;
    o.hks = 4;
    o.use_cache = 0;
    neuv_operators *ops = NULL;
    CHECK(neuv_operators_compute(s, &o, NULL, &ops) == NEUV_OK && ops);
    neuv_operators_info info;
    neuv_operators_get_info(ops, &info);
    CHECK_INT(info.vertices, neuv_mesh_vertex_count(s));
    CHECK_INT(info.faces, neuv_mesh_face_count(s));
    CHECK_INT(info.k, 8);
    CHECK_INT(info.hks_count, 4);
    CHECK(fabs(info.eigenvalues[0]) < 1e-8);
    /* The unit sphere's Laplacian: l(l+1), 2 three times after 0. */
    CHECK_NEAR(info.eigenvalues[1], 2, 0.05);
    CHECK_NEAR(info.eigenvalues[3], 2, 0.05);
    for (int a = 1; a < info.k; a++) CHECK(info.eigenvalues[a] >= info.eigenvalues[a - 1]);
    CHECK(info.cache_path == NULL && !info.cache_hit);
    char *json = neuv_operators_json(ops, "sphere", 0.25);
    CHECK(json && strstr(json, "\"k\":8,") && strstr(json, "\"load\":0.25,") && strstr(json, "\"path\":null"));
    neuv_free(json);
    neuv_operators_free(ops);
    o.k = 0;
    ops = (neuv_operators *)&o; /* must be reset to NULL */
    CHECK(neuv_operators_compute(s, &o, NULL, &ops) == NEUV_ERR_INPUT && ops == NULL);
    neuv_mesh_free(s);
}

static void test_remesh(void)
{
    neuv_mesh *m = grid_mesh(8, 1), *out = NULL;
    CHECK(neuv_mesh_subdivide(m, 2, NEUV_SUBDIVIDE_LOOP, &out) == NEUV_OK);
    CHECK_INT(neuv_mesh_face_count(out), 16 * neuv_mesh_face_count(m));
    CHECK(neuv_mesh_has_uv(out));
    neuv_mesh_free(out);
    CHECK(neuv_mesh_subdivide(m, -1, NEUV_SUBDIVIDE_MIDPOINT, &out) == NEUV_ERR_INPUT && !out);
    CHECK(neuv_mesh_simplify(m, 0.5, NULL, &out) == NEUV_OK);
    CHECK(neuv_mesh_face_count(out) < neuv_mesh_face_count(m));
    neuv_mesh_free(out);
    CHECK(neuv_mesh_simplify(m, 0, NULL, &out) == NEUV_ERR_INPUT && !out);

    neuv_isotropic_options io;
    neuv_isotropic_options_init(&io);
    CHECK(neuv_mesh_remesh_isotropic(m, &io, NULL, &out, NULL) == NEUV_ERR_INPUT); /* no target */
    io.faces = 200;
    neuv_isotropic_report ir;
    CHECK(neuv_mesh_remesh_isotropic(m, &io, NULL, &out, &ir) == NEUV_OK && out);
    CHECK_INT(ir.faces_in, 128);
    CHECK_INT(ir.faces_out, neuv_mesh_face_count(out));
    CHECK(ir.faces_out > 150 && ir.faces_out < 250);
    CHECK_NEAR(ir.diagonal, sqrt(2), 1e-12);
    CHECK(ir.max_distance < 1e-9); /* every vertex on the plane */
    CHECK(!neuv_mesh_has_uv(out));

    /* Jitter: the same vertices, moved within the plane, deterministic. */
    neuv_mesh *again = NULL;
    CHECK(neuv_mesh_subdivide(out, 0, NEUV_SUBDIVIDE_MIDPOINT, &again) == NEUV_OK); /* a copy */
    neuv_jitter_report jr, jr2;
    CHECK(neuv_mesh_jitter(out, 7, &jr) == NEUV_OK && neuv_mesh_jitter(again, 7, &jr2) == NEUV_OK);
    CHECK(jr.moved_vertices > 0 && jr.moved_vertices == jr2.moved_vertices);
    int nv = neuv_mesh_vertex_count(out);
    double *p = malloc(sizeof(double) * 3 * (size_t)nv), *q = malloc(sizeof(double) * 3 * (size_t)nv);
    neuv_mesh_get_positions(out, p);
    neuv_mesh_get_positions(again, q);
    CHECK(memcmp(p, q, sizeof(double) * 3 * (size_t)nv) == 0);
    double zmax = 0;
    for (int v = 0; v < nv; v++) zmax = fmax(zmax, fabs(p[3 * v + 2]));
    CHECK(zmax < 1e-12);
    free(p);
    free(q);
    neuv_mesh_free(again);
    neuv_mesh_free(out);
    neuv_mesh_free(m);
}

static void test_segment(void)
{
    neuv_mesh *m = grid_mesh(12, 0);
    int nf = neuv_mesh_face_count(m), n = 0;
    int *chart = malloc(sizeof(int) * (size_t)nf);
    neuv_segment_options o;
    neuv_segment_options_init(&o);
    CHECK(o.charts == 0 && o.max_distortion > 1 && o.seed == 1 && o.use_cache == 1 && o.features == NEUV_FEATURES_HKS_NORMALS);
    o.charts = 3;
    o.iters = 20;
    o.threads = 1;
    o.use_cache = 0;
    neuv_segment_report r;
    CHECK(neuv_segment(m, &o, NULL, chart, &n, &r) == NEUV_OK);
    CHECK(n >= 1 && r.charts == n && r.patches == 3 && r.iterations == 20 && r.faces == nf);
    int in_range = 1;
    for (int f = 0; f < nf; f++) in_range &= chart[f] >= 0 && chart[f] < n;
    CHECK(in_range);
    char *json = neuv_segment_report_json(&r, "grid", "grid.ply", 0, 1);
    CHECK(json && strstr(json, "\"features\":\"hks+normals\"") && strstr(json, "\"patches\":3,"));
    neuv_free(json);

    const char *ply = tmp_path("test_api_commands-charts.ply");
    const char *obj = tmp_path("test_api_commands-charts.obj");
    const char *png = tmp_path("test_api_commands-charts.png");
    CHECK(neuv_save_face_labels(m, chart, ply) == NEUV_OK);
    CHECK(neuv_save_face_labels(m, chart, obj) == NEUV_OK);
    CHECK(neuv_save_face_labels(m, chart, tmp_path("test_api_commands-charts.txt")) == NEUV_ERR_INPUT);
    CHECK(neuv_write_label_preview(m, chart, png) == NEUV_OK);
    struct stat st;
    CHECK(stat(ply, &st) == 0 && st.st_size > 0 && stat(png, &st) == 0 && st.st_size > 0);
    remove(ply);
    remove(obj);
    remove(png);

    o.max_distortion = 1;
    CHECK(neuv_segment(m, &o, NULL, chart, &n, NULL) == NEUV_ERR_INPUT);
    neuv_segment_options_init(&o);
    o.charts = -1;
    CHECK(neuv_segment(m, &o, NULL, chart, &n, NULL) == NEUV_ERR_INPUT);
    free(chart);
    neuv_mesh_free(m);
}

static void test_compare(void)
{
    neuv_mesh *a = grid_mesh(8, 1), *b = NULL, *bare = grid_mesh(8, 0);
    CHECK(neuv_mesh_subdivide(a, 1, NEUV_SUBDIVIDE_MIDPOINT, &b) == NEUV_OK);
    neuv_uv_comparison c;
    CHECK(neuv_compare_uvs(a, b, NULL, &c) == NEUV_OK);
    CHECK(c.uv_max < 1e-12 && c.chart_agreement == 1);
    CHECK_INT(c.faces_a, 128);
    CHECK_INT(c.faces_b, 512);
    CHECK_INT(c.charts_b, 1);
    CHECK(c.worst_count >= 0 && c.worst_count <= NEUV_WORST_CHARTS);
    CHECK_INT(c.b_metrics.flipped, 0);
    CHECK_NEAR(c.b_metrics.qce_mean, 1, 1e-9);
    char *json = neuv_uv_comparison_json(&c, "a.obj", "b.obj");
    CHECK(json && !strncmp(json, "{\"a\":\"a.obj\",\"b\":\"b.obj\",\"uv_distance\":{", 40) &&
          strstr(json, "\"faces_b\":512"));
    neuv_free(json);
    CHECK(neuv_compare_uvs(a, bare, NULL, &c) == NEUV_ERR_INPUT); /* no UVs */
    neuv_mesh_free(a);
    neuv_mesh_free(b);
    neuv_mesh_free(bare);
}

/* CRC-32 (IEEE, as zlib) for the hand-written checkpoint. */
static uint32_t crc32_of(uint32_t crc, const void *data, size_t n)
{
    const unsigned char *p = data;
    crc = ~crc;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int k = 0; k < 8; k++) crc = crc & 1 ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
    }
    return ~crc;
}

static void put_u32(FILE *fp, uint32_t x)
{
    unsigned char b[4] = {(unsigned char)x, (unsigned char)(x >> 8), (unsigned char)(x >> 16), (unsigned char)(x >> 24)};
    fwrite(b, 1, 4, fp);
}

static void put_tensor(FILE *fp, const char *name, uint32_t rows, uint32_t cols, const float *data)
{
    unsigned char shape[8], *bytes = malloc(4 * (size_t)rows * cols);
    for (int k = 0; k < 4; k++) {
        shape[k] = (unsigned char)(rows >> (8 * k));
        shape[4 + k] = (unsigned char)(cols >> (8 * k));
    }
    for (size_t i = 0; i < (size_t)rows * cols; i++) {
        uint32_t u;
        memcpy(&u, &data[i], 4);
        for (int k = 0; k < 4; k++) bytes[4 * i + k] = (unsigned char)(u >> (8 * k));
    }
    uint32_t crc = crc32_of(crc32_of(crc32_of(0, name, strlen(name)), shape, 8), bytes, 4 * (size_t)rows * cols);
    put_u32(fp, (uint32_t)strlen(name));
    fwrite(name, 1, strlen(name), fp);
    put_u32(fp, rows);
    put_u32(fp, cols);
    put_u32(fp, crc);
    fwrite(bytes, 1, 4 * (size_t)rows * cols, fp);
    free(bytes);
}

static void test_checkpoint(void)
{
    const char *path = tmp_path("test_api_commands.neuv");
    const char *config = "{\"model\":\"test\"}";
    const float w[6] = {-2, 0, 1, 3, NAN, INFINITY}, b[2] = {0.5f, 0.5f};
    FILE *fp = fopen(path, "wb");
    CHECK(fp != NULL);
    if (!fp) return;
    fwrite("NEUVMODL", 1, 8, fp);
    put_u32(fp, 1);
    put_u32(fp, (uint32_t)strlen(config));
    fwrite(config, 1, strlen(config), fp);
    put_u32(fp, crc32_of(0, config, strlen(config)));
    put_u32(fp, 2);
    put_tensor(fp, "layer.w", 2, 3, w);
    put_tensor(fp, "layer.b", 1, 2, b);
    fclose(fp);

    neuv_checkpoint *c = NULL;
    CHECK(neuv_checkpoint_load(path, &c) == NEUV_OK && c);
    CHECK_INT(neuv_checkpoint_version(c), 1);
    CHECK(!strcmp(neuv_checkpoint_config(c), config));
    CHECK_INT(neuv_checkpoint_tensor_count(c), 2);
    CHECK_INT(neuv_checkpoint_parameter_count(c), 8);
    neuv_tensor_info t;
    CHECK(neuv_checkpoint_get_tensor(c, 0, &t) == NEUV_OK);
    CHECK(!strcmp(t.name, "layer.w") && t.rows == 2 && t.cols == 3);
    CHECK(t.min == -2 && t.max == 3 && t.nonfinite == 2);
    CHECK_NEAR(t.rms, sqrt(14.0 / 4), 1e-12);
    CHECK(neuv_checkpoint_get_tensor(c, 2, &t) == NEUV_ERR_INPUT);
    char *json = neuv_checkpoint_json(c, "m.neuv");
    CHECK(json && strstr(json, "\"parameters\":8,") && strstr(json, "\"name\":\"layer.b\",\"rows\":1,\"cols\":2,"
                                                                    "\"min\":0.5,\"max\":0.5,\"rms\":0.5"));
    neuv_free(json);
    neuv_checkpoint_free(c);

    /* One byte of data damaged: refused with one line naming the tensor. */
    fp = fopen(path, "r+b");
    if (fp) {
        fseek(fp, -1, SEEK_END);
        fputc(0x55, fp);
        fclose(fp);
    }
    c = (neuv_checkpoint *)path; /* must be reset to NULL */
    CHECK(neuv_checkpoint_load(path, &c) == NEUV_ERR_INPUT && c == NULL);
    CHECK(strstr(neuv_last_error(), "CRC mismatch in tensor 'layer.b'") != NULL);
    remove(path);
    CHECK(neuv_checkpoint_load(path, &c) == NEUV_ERR_IO);
}

int main(void)
{
    test_topology();
    test_flatten();
    test_geodesics();
    test_operators();
    test_remesh();
    test_segment();
    test_compare();
    test_checkpoint();
    return check_report("test_api_commands");
}
