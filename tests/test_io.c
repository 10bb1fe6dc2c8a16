/* Mesh input/output: every reader on small hand-written files, round trips
 * through every writer, seam splitting, each bad input's message, and the
 * vertex/triangle counts of every mesh in ../shared/meshes. */
#include "check.h"

#include <dirent.h>
#include <stdint.h>
#include <unistd.h>

#include "core/error.h"
#include "io/mesh_io.h"
#include "io/polygon_triangulate.h"
#include "io/seam_split.h"
#include "mesh/mesh.h"

/* Assimp 5.2 leaks the partial mesh when an STL import throws (the bad.stl
 * case below); that leak is inside the library, not ours. Read by
 * LeakSanitizer in the sanitizer build, unused otherwise. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) { return "leak:libassimp.so\n"; }

/* ---- helpers ---------------------------------------------------------- */

static const char *write_text(const char *name, const char *text) { return write_tmp_file(name, text, strlen(text)); }

/* Callbacks the loads report their warnings to (count_warnings, or none). */
static const neuv_callbacks *load_callbacks;

static neuv_mesh *load_ok(const char *path)
{
    neuv_mesh *m = NULL;
    neuv_status s = neuv_mesh_load(path, load_callbacks, &m);
    if (s != NEUV_OK) fprintf(stderr, "load %s failed: %s\n", path, neuv_last_error());
    CHECK(s == NEUV_OK && m != NULL);
    return m;
}

/* Loading must fail with `code` and a message containing `msg`. */
static void expect_load_error(const char *path, neuv_status code, const char *msg)
{
    neuv_mesh *m = (neuv_mesh *)1;
    neuv_status s = neuv_mesh_load(path, NULL, &m);
    CHECK_INT(s, code);
    CHECK(m == NULL);
    if (!strstr(neuv_last_error(), msg)) {
        check_failures++;
        fprintf(stderr, "%s: message '%s' lacks '%s'\n", path, neuv_last_error(), msg);
    }
    check_count++;
    CHECK(strchr(neuv_last_error(), '\n') == NULL);
}

static int warnings;
static char last_warning[512];
static void count_warnings(void *user, neuv_log_level level, const char *message)
{
    (void)user;
    if (level == NEUV_LOG_WARN) { warnings++; snprintf(last_warning, sizeof last_warning, "%s", message); }
}

static double signed_area_along(const neuv_mesh *m, int f, const double n[3])
{
    const double *a = m->pos + 3 * m->tri[3 * f], *b = m->pos + 3 * m->tri[3 * f + 1], *c = m->pos + 3 * m->tri[3 * f + 2];
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double x[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    return 0.5 * (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]);
}

static int tri_is(const neuv_mesh *m, int f, int a, int b, int c)
{
    const int *t = m->tri + 3 * f;
    return t[0] == a && t[1] == b && t[2] == c;
}

/* UV of corner k of face f. */
static const double *corner_uv(const neuv_mesh *m, int f, int k) { return m->uv + 2 * m->tri_uv[3 * f + k]; }

/* ---- readers ---------------------------------------------------------- */

static void test_obj_reader(void)
{
    const char *path = write_text("quad.obj",
        "# a quad and a triangle, CRLF, every corner syntax\r\n"
        "mtllib x.mtl\r\no thing\r\ng group\r\ns off\r\nusemtl red\r\n"
        "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0 1.0\r\nv 0.1 0.2 0.30000000000000004\r\n"
        "vn 0 0 1\r\nvt 0 0\r\nvt 1 0\r\nvt 1 1\r\nvt 0 1\r\nvt 0.5 0.25 0\r\n"
        "f 1/1/1 2/2/1 3/3/1 4/4/1\r\n"
        "l 1 2\r\np 1\r\n"
        "f -5/-5 -3/3 -1/-1 # trailing comment\r\n");
    neuv_mesh *m = load_ok(path);
    if (!m) return;
    CHECK_INT(m->nv, 5);
    CHECK_INT(m->nf, 3);
    CHECK(tri_is(m, 0, 0, 1, 2) && tri_is(m, 1, 0, 2, 3)); /* convex quad: the usual fan */
    CHECK(tri_is(m, 2, 0, 2, 4));                          /* relative indices */
    CHECK(m->pos[3 * 4 + 2] == 0.30000000000000004);      /* read exactly, not via float */
    CHECK(m->pos[3 * 3 + 1] == 1.0);
    CHECK_INT(m->nuv, 5);
    CHECK(m->tri_uv[3 * 1 + 2] == 3 && m->tri_uv[3 * 2 + 1] == 2 && m->tri_uv[3 * 2 + 2] == 4);
    CHECK(corner_uv(m, 2, 2)[0] == 0.5 && corner_uv(m, 2, 2)[1] == 0.25);
    /* The quad's corners name normal 1, the triangle none: normals only when every face has them. */
    CHECK_INT(m->nn, 0);
    CHECK(m->face_material && m->face_material[0] == 0 && m->face_material[2] == 0);
    mesh_free(m);

    /* Normals per corner and materials per face, in order of first use; a
     * face before any usemtl gets material 0 and the named ones follow. */
    m = load_ok(write_text("marks.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0.6 0.8\n"
        "f 1//1 2//1 3//2\nusemtl steel \nf 2//2 4//2 3//2\nusemtl wood\nf 1//1 3//1 4//1\nusemtl steel\nf 1//-1 2//-2 4//1\n"));
    if (m) {
        CHECK_INT(m->nn, 2);
        CHECK(m->normal[3 * 1 + 1] == 0.6 && m->normal[3 * 1 + 2] == 0.8);
        CHECK(m->tri_normal[2] == 1 && m->tri_normal[3] == 1 && m->tri_normal[9] == 1 && m->tri_normal[10] == 0);
        CHECK(m->face_material[0] == 0 && m->face_material[1] == 1 && m->face_material[2] == 2 &&
              m->face_material[3] == 1);
        mesh_free(m);
    }
    /* PLY vertex normals name each corner's normal by its vertex. */
    m = load_ok(write_text("normals.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n"
        "0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0.6 0.8\n0 1 0 0 0 1\n4 0 1 2 3\n"));
    if (m) {
        CHECK_INT(m->nn, 4);
        CHECK_NEAR(m->normal[3 * 2 + 1], 0.6, 1e-7);
        CHECK_NEAR(m->normal[3 * 2 + 2], 0.8, 1e-7);
        CHECK(m->tri_normal && m->tri_normal[0] == m->tri[0] && m->tri_normal[5] == m->tri[5]);
        CHECK(m->face_material == NULL);
        mesh_free(m);
    }
    /* A normal index out of range drops the normals, not the mesh. */
    m = load_ok(write_text("badvn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//7\n"));
    if (m) { CHECK_INT(m->nf, 1); CHECK_INT(m->nn, 0); CHECK(m->tri_normal == NULL); mesh_free(m); }

    /* v//vn corners and no vt at all: no UVs, no warning. */
    warnings = 0;
    const neuv_callbacks counting = {count_warnings, NULL, NULL};
    load_callbacks = &counting;
    m = load_ok(write_text("vn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n"));
    if (m) { CHECK_INT(m->nf, 1); CHECK_INT(m->nuv, 0); CHECK(m->tri_uv == NULL); mesh_free(m); }
    CHECK_INT(warnings, 0);

    /* UVs on some faces only: dropped, with a warning. */
    m = load_ok(write_text("partial.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 2 4 3\n"));
    if (m) { CHECK_INT(m->nf, 2); CHECK_INT(m->nuv, 0); mesh_free(m); }
    CHECK_INT(warnings, 1);
    CHECK(strstr(last_warning, "1 of 2 faces") != NULL);
    load_callbacks = NULL;
}

/* An L-shaped hexagon whose first corner is next to the reflex corner, on a
 * tilted plane: a fan from corner 0 would make a flipped triangle. */
static void test_concave_polygon(void)
{
    const double xy[6][2] = {{2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}, {2, 0}};
    char text[1024] = "", line[128];
    for (int i = 0; i < 6; i++) {
        snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", xy[i][0], 0.6 * xy[i][1], 0.8 * xy[i][1]);
        strcat(text, line);
    }
    strcat(text, "f 1 2 3 4 5 6\n");
    neuv_mesh *m = load_ok(write_text("lshape.obj", text));
    if (!m) return;
    CHECK_INT(m->nf, 4);
    const double n[3] = {0, -0.8, 0.6}; /* the plane's normal for counter-clockwise corners */
    double total = 0;
    for (int f = 0; f < m->nf; f++) {
        double a = signed_area_along(m, f, n);
        CHECK(a > 1e-9);
        total += a;
    }
    CHECK_NEAR(total, 3.0, 1e-12); /* the L covers 3 unit squares, nothing twice */
    mesh_free(m);

    /* Direct call: a convex pentagon is the fan (0,1,2), (0,2,3), (0,3,4). */
    double P[15], work[10];
    int idx[5], tri[9];
    for (int i = 0; i < 5; i++) {
        P[3 * i] = cos(2 * 3.14159265358979323846 * i / 5); P[3 * i + 1] = sin(2 * 3.14159265358979323846 * i / 5); P[3 * i + 2] = 0;
    }
    polygon_triangulate(5, P, tri, work, idx);
    const int fan[9] = {0, 1, 2, 0, 2, 3, 0, 3, 4};
    CHECK(memcmp(tri, fan, sizeof fan) == 0);
}

static void test_off_reader(void)
{
    neuv_mesh *m = load_ok(write_text("c.off",
        "# leading comment\nCOFF\n# counts next\n5 2 0\n"
        "0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 9 9 9 255\n"
        "# a comment between vertices\n2.5 -1e-3 7 1 1 1 1\n"
        "4 0 1 2 3 255 0 0\n3 1 4 2   # with a comment\n"));
    if (!m) return;
    CHECK_INT(m->nv, 5);
    CHECK_INT(m->nf, 3);
    CHECK(tri_is(m, 0, 0, 1, 2) && tri_is(m, 1, 0, 2, 3) && tri_is(m, 2, 1, 4, 2));
    CHECK(m->pos[12] == 2.5 && m->pos[13] == -1e-3 && m->pos[14] == 7);
    CHECK_INT(m->nuv, 0);
    mesh_free(m);
    /* STOFF: s t after the coordinates, one UV per vertex. */
    m = load_ok(write_text("st.off", "STOFF\n3 1 0\n0 0 0 0.1 0.2\n1 0 0 0.3 0.4\n0 1 0 0.5 0.6\n3 0 1 2\n"));
    if (m) {
        CHECK_INT(m->nuv, 3);
        CHECK(corner_uv(m, 0, 2)[0] == 0.5 && corner_uv(m, 0, 2)[1] == 0.6);
        mesh_free(m);
    }
    /* Counts on the OFF line itself. */
    m = load_ok(write_text("inline.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    if (m) { CHECK_INT(m->nf, 1); mesh_free(m); }
}

static void test_ply_ascii(void)
{
    neuv_mesh *m = load_ok(write_text("a.ply",
        "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info nothing\r\n"
        "element vertex 4\r\nproperty float x\r\nproperty float y\r\nproperty double z\r\n"
        "property uchar red\r\nproperty float s\r\nproperty float t\r\n"
        "element face 1\r\nproperty list uchar int vertex_indices\r\nproperty list uchar float weights\r\n"
        "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n"
        "0 0 0.1 255 0 0\r\n1 0 0 3 1 0\r\n1 1 0 4 1 1\r\n0 1 0 5 0 1\r\n"
        "4 0 1 2 3 2 0.5 0.5\r\n0 1\r\n"));
    if (!m) return;
    CHECK_INT(m->nv, 4);
    CHECK_INT(m->nf, 2);
    CHECK(m->pos[2] == 0.1); /* a double property keeps all its digits */
    CHECK_INT(m->nuv, 4);    /* per-vertex UVs */
    CHECK(corner_uv(m, 1, 1)[0] == 1 && corner_uv(m, 1, 1)[1] == 1);
    CHECK(corner_uv(m, 1, 2)[0] == 0 && corner_uv(m, 1, 2)[1] == 1);
    mesh_free(m);
}

/* Big-endian bytes for the binary PLY fixture. */
static unsigned char *be(unsigned char *p, const void *x, size_t n)
{
    uint64_t u = 0;
    memcpy(&u, x, n);
    for (size_t i = 0; i < n; i++) p[i] = (unsigned char)(u >> (8 * (n - 1 - i)));
    return p + n;
}

static size_t binary_ply_be(unsigned char *buf, int faces_written)
{
    const char *head =
        "ply\nformat binary_big_endian 1.0\n"
        "element vertex 4\nproperty double x\nproperty double y\nproperty double z\nproperty short flags\n"
        "element material 1\nproperty list ushort uint junk\nproperty float shine\n"
        "element face 2\nproperty list uchar uint vertex_indices\nproperty list uchar float texcoord\n"
        "property int label\nend_header\n";
    size_t n = strlen(head);
    memcpy(buf, head, n);
    unsigned char *p = buf + n;
    const double V[4][3] = {{0, 0, 0}, {1.0 / 3.0, 0, 0}, {1.0 / 3.0, 1e-300, 0}, {0, 1, -2.5e10}};
    for (int v = 0; v < 4; v++) {
        for (int k = 0; k < 3; k++) p = be(p, &V[v][k], 8);
        int16_t fl = (int16_t)-v;
        p = be(p, &fl, 2);
    }
    uint16_t nj = 2;
    uint32_t junk[2] = {7, 8};
    float shine = 0.5f;
    p = be(p, &nj, 2); p = be(p, &junk[0], 4); p = be(p, &junk[1], 4); p = be(p, &shine, 4);
    const uint32_t F[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int f = 0; f < faces_written; f++) {
        *p++ = 3;
        for (int k = 0; k < 3; k++) p = be(p, &F[f][k], 4);
        *p++ = 6;
        for (int k = 0; k < 3; k++) {
            float u = (float)(0.25 * F[f][k] + f), w = (float)(0.125 * F[f][k]);
            p = be(p, &u, 4); p = be(p, &w, 4);
        }
        int32_t label = f;
        p = be(p, &label, 4);
    }
    return (size_t)(p - buf);
}

static void test_ply_binary(void)
{
    unsigned char buf[2048];
    size_t n = binary_ply_be(buf, 2);
    neuv_mesh *m = load_ok(write_tmp_file("be.ply", buf, n));
    if (m) {
        CHECK_INT(m->nv, 4);
        CHECK_INT(m->nf, 2);
        CHECK(m->pos[3] == 1.0 / 3.0 && m->pos[7] == 1e-300 && m->pos[11] == -2.5e10);
        CHECK(tri_is(m, 1, 0, 2, 3));
        CHECK_INT(m->nuv, 6); /* per-corner texcoords: one UV per corner */
        CHECK(corner_uv(m, 1, 2)[0] == 1.75 && corner_uv(m, 1, 2)[1] == 0.375);
        CHECK(corner_uv(m, 0, 0)[0] == 0 && corner_uv(m, 1, 0)[0] == 1);
        mesh_free(m);
    }
    /* Cut inside the second face: truncated, with the counts. */
    size_t cut = binary_ply_be(buf, 1) + 5;
    binary_ply_be(buf, 2);
    expect_load_error(write_tmp_file("trunc.ply", buf, cut), NEUV_ERR_INPUT,
                      "truncated: header declares 2 faces, data ends after 1");
    size_t head_len = (size_t)(strstr((const char *)buf, "end_header\n") - (const char *)buf) + 11;
    expect_load_error(write_tmp_file("trunc_v.ply", buf, head_len + 2 * 26 + 7), NEUV_ERR_INPUT,
                      "truncated: header declares 4 vertices, data ends after 2");

    /* Little endian, float positions, ushort indices, uppercase extension. */
    unsigned char le[512];
    const char *head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                       "property float y\nproperty float z\nelement face 1\n"
                       "property list int ushort vertex_index\nend_header\n";
    size_t h = strlen(head);
    memcpy(le, head, h);
    const float P[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0.5f};
    memcpy(le + h, P, sizeof P); /* the test machine is little endian, like every target */
    const int32_t cnt = 3;
    const uint16_t idx[3] = {2, 0, 1};
    memcpy(le + h + 36, &cnt, 4);
    memcpy(le + h + 40, idx, 6);
    m = load_ok(write_tmp_file("LE.PLY", le, h + 46));
    if (m) { CHECK(tri_is(m, 0, 2, 0, 1)); CHECK(m->pos[8] == 0.5); mesh_free(m); }
}

static void test_stl_via_assimp(void)
{
    neuv_mesh *m = load_ok(write_text("two.stl",
        "solid two\n"
        " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 1 1 0\n  endloop\n endfacet\n"
        " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 1 0\n   vertex 0 1 0.5\n  endloop\n endfacet\n"
        "endsolid two\n"));
    if (!m) return;
    CHECK_INT(m->nf, 2);
    CHECK_INT(m->nv, 6); /* STL is a triangle soup; the loader does not weld */
    const int *t = m->tri + 3;
    CHECK(m->pos[3 * t[2] + 2] == 0.5 && m->pos[3 * t[1]] == 1 && m->pos[3 * t[1] + 1] == 1);
    mesh_free(m);
}

/* ---- writers and round trips ------------------------------------------ */

/* Two triangles sharing edge 1-2 with a seam along it: vertices 1 and 2
 * carry different UVs on each side, vertices 0 and 3 one each. */
static neuv_mesh *seam_mesh(void)
{
    neuv_mesh *m = mesh_create(5, 2, 6);
    const double P[15] = {0.1, 1.0 / 3.0, -0.0, 1e-300, 2.0 / 7.0, 1, 1, 1, 1.2345678901234567e8,
                          0, 1, 0.7, 9, 9, 9 /* unreferenced */};
    memcpy(m->pos, P, sizeof P);
    const int T[6] = {0, 1, 2, 1, 3, 2};
    memcpy(m->tri, T, sizeof T);
    const double UV[12] = {0, 0, 0.5, 0, 0.5, 0.5, 0.75, 0.1, 0.9, 0.3, 0.75, 0.6};
    const int TU[6] = {0, 1, 2, 3, 4, 5};
    memcpy(m->uv, UV, sizeof UV);
    memcpy(m->tri_uv, TU, sizeof TU);
    return m;
}

static void test_seam_split(void)
{
    neuv_mesh *m = seam_mesh();
    seam_split sp;
    CHECK(seam_split_vertices(m, &sp) == NEUV_OK);
    CHECK_INT(sp.nv, 7); /* 0, 1 twice, 2 twice, 3, and the unused 4 */
    const int src[7] = {0, 1, 1, 2, 2, 3, 4};
    CHECK(memcmp(sp.src, src, sizeof src) == 0);
    for (int c = 0; c < 6; c++) {
        CHECK_INT(sp.src[sp.tri[c]], m->tri[c]);
        CHECK(sp.uv[2 * sp.tri[c]] == m->uv[2 * m->tri_uv[c]] && sp.uv[2 * sp.tri[c] + 1] == m->uv[2 * m->tri_uv[c] + 1]);
    }
    seam_split_free(&sp);
    /* Equal UV values under different UV indices are no seam. */
    m->uv[6] = 0.5; m->uv[7] = 0; m->uv[10] = 0.5; m->uv[11] = 0.5;
    CHECK(seam_split_vertices(m, &sp) == NEUV_OK);
    CHECK_INT(sp.nv, 5);
    seam_split_free(&sp);
    mesh_free(m);
}

static void check_same_corners(const neuv_mesh *a, const neuv_mesh *b, double uv_tol)
{
    CHECK_INT(b->nf, a->nf);
    if (b->nf != a->nf || !b->nuv) { CHECK(b->nuv > 0); return; }
    int pos_ok = 1, uv_ok = 1;
    for (int c = 0; c < 3 * a->nf; c++) {
        for (int k = 0; k < 3; k++) {
            double x = a->pos[3 * a->tri[c] + k], y = b->pos[3 * b->tri[c] + k];
            if (!(fabs(x - y) <= 1e-6 * fabs(x) + 1e-30)) pos_ok = 0;
        }
        for (int k = 0; k < 2; k++)
            if (!(fabs(a->uv[2 * a->tri_uv[c] + k] - b->uv[2 * b->tri_uv[c] + k]) <= uv_tol)) uv_ok = 0;
    }
    CHECK(pos_ok);
    CHECK(uv_ok);
}

static void test_round_trips(void)
{
    neuv_mesh *m = seam_mesh();

    /* OBJ: everything bit for bit, vertex for vertex, UV for UV. */
    /* tmp_path reuses 4 buffers: keep copies of the names used throughout. */
    char obj[4096], ply[4096];
    snprintf(obj, sizeof obj, "%s", tmp_path("rt.obj"));
    snprintf(ply, sizeof ply, "%s", tmp_path("rt.ply"));
    CHECK(neuv_mesh_save(m, obj) == NEUV_OK);
    neuv_mesh *r = load_ok(obj);
    if (r) {
        CHECK_INT(r->nv, m->nv);
        CHECK(memcmp(r->pos, m->pos, sizeof(double) * 15) == 0);
        CHECK(memcmp(r->tri, m->tri, sizeof(int) * 6) == 0);
        CHECK_INT(r->nuv, m->nuv);
        CHECK(memcmp(r->uv, m->uv, sizeof(double) * 12) == 0);
        CHECK(memcmp(r->tri_uv, m->tri_uv, sizeof(int) * 6) == 0);
        mesh_free(r);
    }

    /* PLY: seam vertices split, positions exact (double), UVs as float. */
    CHECK(neuv_mesh_save(m, ply) == NEUV_OK);
    r = load_ok(ply);
    if (r) {
        CHECK_INT(r->nv, 7);
        const int src[7] = {0, 1, 1, 2, 2, 3, 4};
        int exact = 1;
        for (int v = 0; v < 7; v++)
            if (memcmp(r->pos + 3 * v, m->pos + 3 * src[v], 3 * sizeof(double))) exact = 0;
        CHECK(exact);
        check_same_corners(m, r, 1e-7);
        mesh_free(r);
    }

    /* GLB and .gltf (base64 buffer), read back through Assimp: float32, split
     * seams, and v flipped on the way out and back. */
    const char *names[2] = {"rt.glb", "rt.gltf"};
    for (int i = 0; i < 2; i++) {
        const char *g = tmp_path(names[i]);
        CHECK(neuv_mesh_save(m, g) == NEUV_OK);
        r = load_ok(g);
        if (r) {
            CHECK_INT(r->nv, 7);
            check_same_corners(m, r, 1e-7);
            mesh_free(r);
        }
    }

    /* A glTF scene with the mesh instanced twice, the second node moved: both
     * instances come back, the second with its node's translation applied. */
    {
        const char *g = tmp_path("rt.gltf");
        FILE *fp = fopen(g, "rb");
        char *text = calloc(1, 1 << 16);
        size_t n = fp && text ? fread(text, 1, (1 << 16) - 1, fp) : 0;
        if (fp) fclose(fp);
        char *nodes = text ? strstr(text, "\"nodes\":[{\"mesh\":0}]") : NULL;
        char *scene_nodes = text ? strstr(text, "\"nodes\":[0]") : NULL;
        CHECK(n > 0 && nodes && scene_nodes && scene_nodes < nodes);
        if (n > 0 && nodes && scene_nodes && scene_nodes < nodes) {
            char *edited = malloc(n + 256);
            size_t a = (size_t)(scene_nodes - text), b = (size_t)(nodes - text);
            size_t nodes_len = strlen("\"nodes\":[{\"mesh\":0}]");
            sprintf(edited, "%.*s\"nodes\":[0,1]%.*s\"nodes\":[{\"mesh\":0},{\"mesh\":0,\"translation\":[10,0,0]}]%s",
                    (int)a, text, (int)(b - a - strlen("\"nodes\":[0]")), scene_nodes + strlen("\"nodes\":[0]"),
                    nodes + nodes_len);
            r = load_ok(write_text("twice.gltf", edited));
            if (r) {
                CHECK_INT(r->nf, 4);
                CHECK_INT(r->nv, 14);
                int moved = 1;
                for (int c = 0; c < 6; c++)
                    for (int k = 0; k < 3; k++) {
                        double x = r->pos[3 * r->tri[c] + k] + (k == 0 ? 10 : 0), y = r->pos[3 * r->tri[6 + c] + k];
                        if (!(fabs(x - y) <= 1e-5 * fabs(x))) moved = 0;
                    }
                CHECK(moved);
                mesh_free(r);
            }
            free(edited);
        }
        free(text);
    }

    /* Without UVs: OBJ has f v, PLY no s t, and both still read back. */
    CHECK(mesh_set_uv(m, 0, NULL, NULL) == NEUV_OK);
    CHECK(neuv_mesh_save(m, obj) == NEUV_OK);
    r = load_ok(obj);
    if (r) { CHECK_INT(r->nuv, 0); CHECK(memcmp(r->pos, m->pos, sizeof(double) * 15) == 0); mesh_free(r); }
    CHECK(neuv_mesh_save(m, ply) == NEUV_OK);
    r = load_ok(ply);
    if (r) { CHECK_INT(r->nv, 5); CHECK(memcmp(r->tri, m->tri, sizeof(int) * 6) == 0); mesh_free(r); }
    mesh_free(m);
}

/* ---- bad input -------------------------------------------------------- */

/* 1 when `dir` holds a name starting with `prefix` (a left-over temporary). */
static int has_file_starting(const char *dir, const char *prefix)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int found = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (!strncmp(e->d_name, prefix, strlen(prefix))) found = 1;
    closedir(d);
    return found;
}

static void test_bad_input(void)
{
    expect_load_error(tmp_path("does-not-exist.obj"), NEUV_ERR_IO, "cannot open: No such file or directory");
    const char *dir = tmp_path("a-folder.obj");
    mkdir(dir, 0755);
    expect_load_error(dir, NEUV_ERR_IO, "is a directory, not a mesh file");
    expect_load_error(write_text("empty.obj", ""), NEUV_ERR_INPUT, "empty file");
    expect_load_error(write_text("empty.ply", ""), NEUV_ERR_INPUT, "empty file");
    expect_load_error(write_text("empty.stl", ""), NEUV_ERR_INPUT, "empty file");
    expect_load_error(write_text("points.xyz", "0 0 0\n"), NEUV_ERR_INPUT,
                      "unknown format '.xyz' (expected .obj, .off, .ply, .stl, .gltf, .glb)");
    expect_load_error(write_text("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n"), NEUV_ERR_INPUT,
                      "line 3: vertex 3 has a non-finite coordinate");
    expect_load_error(write_text("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n"), NEUV_ERR_INPUT,
                      "vertex 2 has a non-finite coordinate");
    expect_load_error(write_text("huge.obj", "v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), NEUV_ERR_INPUT,
                      "vertex 1 has a non-finite coordinate");
    expect_load_error(write_text("range.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 900\n"),
                      NEUV_ERR_INPUT, "face 1 references vertex 900, but there are 3 vertices");
    expect_load_error(write_text("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 3\nf 1 2 900\n"),
                      NEUV_ERR_INPUT, "line 6: face references vertex 900, but there are 3 vertices");
    expect_load_error(write_text("rel.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n"), NEUV_ERR_INPUT,
                      "line 3: relative vertex index -3 reaches before the first one");
    /* Found by fuzzing: strtoll's LLONG_MIN, whose negation overflowed. */
    expect_load_error(write_text("rel-huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -99999999999999999999999\n"),
                      NEUV_ERR_INPUT, "line 4: relative vertex index -9223372036854775808 reaches before the first one");
    expect_load_error(write_text("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), NEUV_ERR_INPUT,
                      "line 4: vertex index 0 is not valid");
    expect_load_error(write_text("cloud.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), NEUV_ERR_INPUT,
                      "no faces (a point cloud?); neuv needs a triangle mesh");
    expect_load_error(write_text("cloud.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                 "property float y\nproperty float z\nend_header\n0 0 0\n"),
                      NEUV_ERR_INPUT, "no faces (a point cloud?)");
    expect_load_error(write_text("bad.obj", "v 0 0 0\nv 1 0x 0\n"), NEUV_ERR_INPUT,
                      "line 2: malformed number '0x' in 'v'");
    expect_load_error(write_text("short.obj", "v 0 0 0\nv 1 0\n"), NEUV_ERR_INPUT, "line 2: 'v' needs 3 coordinates");
    expect_load_error(write_text("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n"), NEUV_ERR_INPUT,
                      "line 5: malformed number 'zero'");
    expect_load_error(write_text("bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                 "property float y\nproperty float z\nelement face 1\n"
                                 "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n"),
                      NEUV_ERR_INPUT, "line 12: malformed number 'one'");
    expect_load_error(write_text("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), NEUV_ERR_INPUT, "line 3: face has 2 corners");
    expect_load_error(write_text("trunc.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n"), NEUV_ERR_INPUT,
                      "truncated: header declares 2 faces, data ends after 1");
    expect_load_error(write_text("notply.ply", "PLY?\n"), NEUV_ERR_INPUT, "not a PLY file");
    expect_load_error(write_tmp_file("bin2.obj", "v 0 0 0\n\0\1\2", 11), NEUV_ERR_INPUT, "binary data");
    expect_load_error(write_text("bad.stl", "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0\n"), NEUV_ERR_INPUT,
                      "");

    /* Writing: unknown extension, missing folder, and a writer that fails
     * after the temporary was opened: no file, no temporary left. */
    neuv_mesh *m = seam_mesh();
    CHECK_INT(neuv_mesh_save(m, tmp_path("out.xyz")), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "unknown output format '.xyz'") != NULL);
    char missing[4200];
    snprintf(missing, sizeof missing, "%s/out.obj", tmp_path("no-such-folder"));
    CHECK_INT(neuv_mesh_save(m, missing), NEUV_ERR_IO);
    CHECK(strstr(neuv_last_error(), "no-such-folder does not exist") != NULL);
    mesh_free(m);
    neuv_mesh *empty = mesh_create(0, 0, 0);
    const char *glb = tmp_path("empty-out.glb");
    unlink(glb);
    CHECK_INT(neuv_mesh_save(empty, glb), NEUV_ERR_INPUT);
    CHECK(access(glb, F_OK) != 0);
    CHECK(!has_file_starting(getenv("NEUV_TEST_TMP") ? getenv("NEUV_TEST_TMP") : "/tmp", "empty-out.glb"));
    mesh_free(empty);
}

/* ---- shared meshes ---------------------------------------------------- */

static void test_shared_meshes(void)
{
    /* Vertices as in the file; triangles counted independently (each
     * n-gon of the file gives n-2). spot.obj carries 3225 UVs. */
    static const struct { const char *file; int nv, ntri; } expected[] = {
        {"spot.obj", 2930, 5856},       {"cow.obj", 2903, 5804},          {"beetle.obj", 1148, 2053},
        {"woody.obj", 694, 1267},       {"alligator.obj", 3208, 5981},    {"homer.obj", 6002, 12000},
        {"fandisk.obj", 6475, 12946},   {"suzanne.obj", 507, 968},        {"teapot.obj", 3644, 6320},
        {"stanford-bunny.obj", 35947, 69451}, {"armadillo.obj", 43243, 86482}, {"camelhead.off", 11381, 22704},
        {"face.obj", 25905, 51712},     {"bumpy.off", 1250, 2496},        {"3holes.off", 3596, 7200},
        {"fertility.off", 4494, 9000},  {"decimated-knight.off", 502, 1000}, {"horse_quad.obj", 2400, 4796},
        {"grid.off", 145, 256},         {"halftunnel.off", 831, 1568},
        {"category/cactus/cactus0.ply", 5261, 10518}, {"category/cactus/cactus13.ply", 5261, 10518},
    };
    if (!shared_path("meshes")) { printf("shared meshes absent: that part skipped\n"); return; }
    int seen = 0;
    for (size_t i = 0; i < sizeof expected / sizeof expected[0]; i++) {
        char rel[256];
        snprintf(rel, sizeof rel, "meshes/%s", expected[i].file);
        const char *path = shared_path(rel);
        if (access(path, R_OK) != 0) continue;
        neuv_mesh *m = load_ok(path);
        if (!m) continue;
        seen++;
        if (m->nv != expected[i].nv || m->nf != expected[i].ntri)
            fprintf(stderr, "%s: %d vertices, %d triangles; expected %d, %d\n", expected[i].file, m->nv, m->nf,
                    expected[i].nv, expected[i].ntri);
        CHECK_INT(m->nv, expected[i].nv);
        CHECK_INT(m->nf, expected[i].ntri);
        if (!strcmp(expected[i].file, "spot.obj")) CHECK_INT(m->nuv, 3225);
        mesh_free(m);
    }
    CHECK(seen > 0);
}

int main(void)
{
    test_obj_reader();
    test_concave_polygon();
    test_off_reader();
    test_ply_ascii();
    test_ply_binary();
    test_stl_via_assimp();
    test_seam_split();
    test_round_trips();
    test_bad_input();
    test_shared_meshes();
    return check_report("test_io");
}
