/* io/gltf_read: a .gltf with an external, percent-encoded buffer file, a
 * node tree (translation, matrix, quaternion), strips and fans, byte indices
 * and normalized UVs, checked vertex by vertex against the transforms; the
 * same geometry as a .glb; the scene choice; and each refused construct with
 * its message. */
#include "check.h"
#include "load_checked.h"

#include <math.h>
#include <stdint.h>

#include "io/mesh_io.h"
#include "mesh/mesh.h"

/* The buffer: 4 positions (float VEC3, 48 bytes), 4 UVs (normalized
 * unsigned short VEC2, 16 bytes), 4 strip indices (unsigned byte, 4 bytes). */
static const float P[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5f}};
static const unsigned short UV[4][2] = {{0, 0}, {65535, 0}, {0, 65535}, {32768, 16384}};
static const unsigned char IDX[4] = {0, 1, 2, 3};

static size_t make_buffer(unsigned char *b)
{
    size_t n = 0;
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) { memcpy(b + n, &P[i][k], 4); n += 4; } /* the test host is little-endian */
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 2; k++) { b[n++] = (unsigned char)(UV[i][k] & 255); b[n++] = (unsigned char)(UV[i][k] >> 8); }
    memcpy(b + n, IDX, 4);
    return n + 4;
}

/* Accessors 0-2 and their views over buffer 0, then `rest` (nodes, scenes). */
static char *gltf_json(const char *buffer_entry, const char *mesh_extra, const char *rest)
{
    static char text[4096];
    snprintf(text, sizeof text,
             "{\"asset\":{\"version\":\"2.0\"},%s"
             "\"buffers\":[%s],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
             "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":16},{\"buffer\":0,\"byteOffset\":64,\"byteLength\":4}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
             "{\"bufferView\":1,\"componentType\":5123,\"normalized\":true,\"count\":4,\"type\":\"VEC2\"},"
             "{\"bufferView\":2,\"componentType\":5121,\"count\":4,\"type\":\"SCALAR\"}%s],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},\"indices\":2,\"mode\":5}%s]}]}",
             rest, buffer_entry, "", mesh_extra);
    return text;
}

/* Vertex `base + i` is A * P[i] + t, with A = a * (rotation by `turn` quarter
 * turns about z). */
static void check_instance(const neuv_mesh *m, int base, double a, int turn, const double t[3])
{
    for (int i = 0; i < 4; i++) {
        double x = P[i][0], y = P[i][1];
        for (int q = 0; q < turn; q++) { double x2 = -y; y = x; x = x2; }
        const double *p = m->pos + 3 * (base + i);
        CHECK_NEAR(p[0], a * x + t[0], 1e-6);
        CHECK_NEAR(p[1], a * y + t[1], 1e-6);
        CHECK_NEAR(p[2], a * P[i][2] + t[2], 1e-6);
    }
}

static void test_external_tree(void)
{
    unsigned char buf[128];
    size_t n = make_buffer(buf);
    write_tmp_file("geo.bin", buf, n);
    /* No scenes: node 0 is the only root; node 1 is its child (scale 2 by
     * matrix), node 2 a child of 1 (a quarter turn about z); a fan of the
     * same four vertices as a second primitive on mesh 0. */
    char entry[64];
    snprintf(entry, sizeof entry, "{\"byteLength\":%zu,\"uri\":\"ge%%6F.bin\"}", n);
    const char *nodes = "\"nodes\":[{\"translation\":[10,0,0],\"mesh\":0,\"children\":[1]},"
                        "{\"matrix\":[2,0,0,0, 0,2,0,0, 0,0,2,0, 0,0,0,1],\"mesh\":0,\"children\":[2]},"
                        "{\"rotation\":[0,0,0.70710678118654752,0.70710678118654752],\"mesh\":0}],";
    const char *json = gltf_json(entry, ",{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},\"indices\":2,\"mode\":6}", nodes);
    const char *path = write_tmp_file("tree.gltf", json, strlen(json));
    neuv_mesh *m = load(path);
    if (!m) return;
    /* 3 nodes x 2 primitives x 4 vertices; strip and fan give 2 triangles each. */
    CHECK_INT(m->nv, 24);
    CHECK_INT(m->nf, 12);
    const double t10[3] = {10, 0, 0};
    check_instance(m, 0, 1, 0, t10);   /* node 0, strip */
    check_instance(m, 4, 1, 0, t10);   /* node 0, fan */
    check_instance(m, 8, 2, 0, t10);   /* node 1: T(10) * S(2) */
    check_instance(m, 16, 2, 1, t10);  /* node 2: T(10) * S(2) * Rz(90) */
    /* Strip (0,1,2), (2,1,3): every other triangle swapped to keep winding;
     * fan (0,1,2), (0,2,3). */
    CHECK(m->tri[0] == 0 && m->tri[1] == 1 && m->tri[2] == 2);
    CHECK(m->tri[3] == 2 && m->tri[4] == 1 && m->tri[5] == 3);
    CHECK(m->tri[6] == 4 && m->tri[7] == 5 && m->tri[8] == 6);
    CHECK(m->tri[9] == 4 && m->tri[10] == 6 && m->tri[11] == 7);
    /* Normalized unsigned short UVs, v flipped (glTF's origin is top-left). */
    CHECK(m->nuv == 24 && m->tri_uv);
    if (m->nuv == 24) {
        for (int i = 0; i < 4; i++) {
            CHECK_NEAR(m->uv[2 * i], UV[i][0] / 65535.0, 1e-12);
            CHECK_NEAR(m->uv[2 * i + 1], 1 - UV[i][1] / 65535.0, 1e-12);
        }
    }
    mesh_free(m);
}

static void test_glb_and_scene(void)
{
    unsigned char bin[128];
    size_t n = make_buffer(bin);
    /* Two scenes; "scene": 1 picks the second, whose node is translated. */
    char entry[32];
    snprintf(entry, sizeof entry, "{\"byteLength\":%zu}", n);
    const char *json = gltf_json(entry, "", "\"scene\":1,\"scenes\":[{\"nodes\":[0]},{\"nodes\":[1]}],"
                                            "\"nodes\":[{\"mesh\":0},{\"mesh\":0,\"translation\":[0,0,-3]}],");
    size_t jl = strlen(json), jp = (jl + 3) & ~(size_t)3, bp = (n + 3) & ~(size_t)3;
    size_t total = 12 + 8 + jp + 8 + bp;
    unsigned char *g = calloc(1, total);
    memcpy(g, "glTF", 4);
    uint32_t w[3] = {2, (uint32_t)total, (uint32_t)jp};
    memcpy(g + 4, w, 8);
    memcpy(g + 12, &w[2], 4);
    memcpy(g + 16, "JSON", 4);
    memset(g + 20, ' ', jp);
    memcpy(g + 20, json, jl);
    uint32_t bl = (uint32_t)bp;
    memcpy(g + 20 + jp, &bl, 4);
    memcpy(g + 24 + jp, "BIN", 4); /* "BIN\0" */
    memcpy(g + 28 + jp, bin, n);
    neuv_mesh *m = load(write_tmp_file("scene.glb", g, total));
    if (m) {
        CHECK_INT(m->nv, 4);
        CHECK_INT(m->nf, 2);
        const double t[3] = {0, 0, -3};
        check_instance(m, 0, 1, 0, t);
        mesh_free(m);
    }
    /* The same file cut short: its header's length is longer than the file. */
    neuv_mesh *bad = (neuv_mesh *)1;
    CHECK_INT(neuv_mesh_load(write_tmp_file("cut.glb", g, total - 8), NULL, &bad), NEUV_ERR_INPUT);
    CHECK(bad == NULL && strstr(neuv_last_error(), "GLB header gives"));
    /* Found by fuzzing: a header total below the header's own size made the
     * chunk bound (total - 20) wrap around. */
    uint32_t zero = 0;
    memcpy(g + 8, &zero, 4);
    bad = (neuv_mesh *)1;
    CHECK_INT(neuv_mesh_load(write_tmp_file("total0.glb", g, total), NULL, &bad), NEUV_ERR_INPUT);
    CHECK(bad == NULL && strstr(neuv_last_error(), "less than a header and a chunk"));
    free(g);
}

static void expect_refused(const char *json, const char *msg)
{
    neuv_mesh *m = (neuv_mesh *)1;
    neuv_status s = io_read_gltf(json, strlen(json), NULL, &m);
    CHECK_INT(s, NEUV_ERR_INPUT);
    CHECK(m == NULL);
    if (!strstr(neuv_last_error(), msg)) {
        check_failures++;
        fprintf(stderr, "message '%s' lacks '%s'\n", neuv_last_error(), msg);
    }
    check_count++;
    CHECK(strchr(neuv_last_error(), '\n') == NULL);
}

static void test_refused(void)
{
    /* Base64 of make_buffer's 68 bytes, so that the files below stand alone. */
    unsigned char buf[128];
    size_t n = make_buffer(buf);
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char entry[256];
    int k = snprintf(entry, sizeof entry, "{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,", n);
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)buf[i] << 16 | (i + 1 < n ? (uint32_t)buf[i + 1] << 8 : 0) | (i + 2 < n ? buf[i + 2] : 0);
        entry[k++] = digits[v >> 18]; entry[k++] = digits[(v >> 12) & 63];
        entry[k++] = i + 1 < n ? digits[(v >> 6) & 63] : '=';
        entry[k++] = i + 2 < n ? digits[v & 63] : '=';
    }
    snprintf(entry + k, sizeof entry - (size_t)k, "\"}");
    const char *one = "\"nodes\":[{\"mesh\":0}],";
    /* A well-formed file first, so that each case below fails for its own reason. */
    const char *good = gltf_json(entry, "", one);
    neuv_mesh *m = NULL;
    CHECK_INT(io_read_gltf(good, strlen(good), NULL, &m), NEUV_OK);
    mesh_free(m);

    char text[4096];
    expect_refused("{\"asset\":{\"version\":\"1.0\"}}", "only 2.x");
    expect_refused("[1,2]", "not a glTF file");
    expect_refused("{\"asset\":{\"version\":\"2.0\"}", "JSON: line 1");
    expect_refused(gltf_json(entry, "", "\"nodes\":[{\"mesh\":0,\"children\":[0]}],"), "do not form a tree");
    expect_refused(gltf_json(entry, "", "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"children\":[0]}],"), "reached twice");
    expect_refused(gltf_json(entry, "", "\"nodes\":[{\"children\":[2]},{\"children\":[2]},{\"mesh\":0}],"), "reached twice");
    expect_refused(gltf_json(entry, "", "\"nodes\":[{\"mesh\":3}],"), "missing mesh");
    expect_refused(gltf_json(entry, "", "\"nodes\":[{\"mesh\":0,\"matrix\":[1,2]}],"), "matrix is not 16 numbers");
    expect_refused(gltf_json(entry, "", "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],\"nodes\":[{\"mesh\":0}],"), "requires KHR_draco_mesh_compression");
    expect_refused(gltf_json(entry, ",{\"attributes\":{\"POSITION\":0},\"extensions\":{\"KHR_draco_mesh_compression\":{}}}", one), "Draco");
    expect_refused(gltf_json("{\"byteLength\":68,\"uri\":\"geo.bin\"}", "", one), "cannot be read from memory");
    expect_refused(gltf_json("{\"byteLength\":68,\"uri\":\"data:text/plain,abc\"}", "", one), "only base64");
    expect_refused(gltf_json("{\"byteLength\":999,\"uri\":\"data:application/octet-stream;base64,AAAA\"}", "", one), "shorter than its byteLength");
    expect_refused(gltf_json("{\"byteLength\":68}", "", one), "no GLB binary chunk");
    /* Accessors beyond their views, sparse ones, bad indices. */
    snprintf(text, sizeof text, "%s", gltf_json(entry, "", one));
    char *c = strstr(text, "\"count\":4,\"type\":\"VEC3\"");
    memcpy(c, "\"count\":5", 9);
    expect_refused(text, "accessor 0 leaves its bufferView");
    expect_refused(gltf_json(entry, ",{\"attributes\":{\"POSITION\":3}}", one), "missing accessor");
    snprintf(text, sizeof text, "%s", gltf_json(entry, "", one));
    c = strstr(text, "{\"bufferView\":2,");
    const char *sparse = "{\"sparse\":{},\"bufferView\":2,";
    memmove(c + strlen(sparse), c + strlen("{\"bufferView\":2,"), strlen(c) - strlen("{\"bufferView\":2,") + 1);
    memcpy(c, sparse, strlen(sparse));
    expect_refused(text, "accessor 2 is sparse");
    /* Positions cut to 3 (and no UVs): index 3 is past them. */
    snprintf(text, sizeof text, "%s", gltf_json(entry, "", one));
    c = strstr(text, "\"count\":4,\"type\":\"VEC3\"");
    memcpy(c, "\"count\":3", 9);
    c = strstr(text, ",\"TEXCOORD_0\":1");
    memmove(c, c + 15, strlen(c + 15) + 1);
    expect_refused(text, "past the vertex count");
    /* POSITION must be float VEC3. */
    expect_refused(gltf_json(entry, ",{\"attributes\":{\"POSITION\":1}}", one), "POSITION is not float VEC3");
    /* Only lines: no surface. */
    snprintf(text, sizeof text, "%s", gltf_json(entry, "", one));
    c = strstr(text, "\"mode\":5");
    c[7] = '1';
    expect_refused(text, "no triangles");
}

/* NORMAL turned with the node (a quarter turn about z) and each primitive's
 * material: the first primitive names material 3, the second none (it
 * becomes material 0 and 3 becomes 4). Accessor 0 serves as the normals. */
static void test_normals_and_materials(void)
{
    unsigned char buf[128];
    size_t n = make_buffer(buf);
    write_tmp_file("geo.bin", buf, n);
    char entry[64];
    snprintf(entry, sizeof entry, "{\"byteLength\":%zu,\"uri\":\"geo.bin\"}", n);
    const char *nodes = "\"nodes\":[{\"rotation\":[0,0,0.70710678118654752,0.70710678118654752],\"mesh\":0}],";
    char text[4096];
    snprintf(text, sizeof text, "%s", gltf_json(entry, ",{\"attributes\":{\"POSITION\":0,\"NORMAL\":0},\"indices\":2,\"mode\":6}", nodes));
    const char *from = "\"TEXCOORD_0\":1},\"indices\":2,\"mode\":5}";
    char *at = strstr(text, from);
    CHECK(at != NULL);
    if (!at) return;
    char tail[4096];
    snprintf(tail, sizeof tail, "\"TEXCOORD_0\":1,\"NORMAL\":0},\"indices\":2,\"mode\":5,\"material\":3}%s", at + strlen(from));
    strcpy(at, tail);
    neuv_mesh *m = load(write_tmp_file("marks.gltf", text, strlen(text)));
    if (!m) return;
    CHECK_INT(m->nn, 8);
    CHECK(m->tri_normal && m->face_material);
    if (m->nn == 8 && m->tri_normal && m->face_material) {
        CHECK_NEAR(m->normal[3 * 1 + 0], 0, 1e-6); /* P[1] = (1, 0, 0) turned to (0, 1, 0) */
        CHECK_NEAR(m->normal[3 * 1 + 1], 1, 1e-6);
        CHECK_NEAR(m->normal[3 * 3 + 2], 0.5, 1e-6);
        CHECK(m->tri_normal[0] == 0 && m->tri_normal[1] == 1 && m->tri_normal[2] == 2 && m->tri_normal[6] == 4);
        CHECK(m->face_material[0] == 4 && m->face_material[1] == 4 && m->face_material[2] == 0 && m->face_material[3] == 0);
    }
    mesh_free(m);
}

int main(void)
{
    test_external_tree();
    test_glb_and_scene();
    test_refused();
    test_normals_and_materials();
    return check_report("test_gltf_read");
}
