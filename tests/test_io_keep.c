/* io/ PLY and glTF keep what comes in (issue 19, item 1): a glTF with two
 * primitives of two named materials, per-vertex normals, colours and a node
 * name read and written back (.gltf and .glb) keeps each face's material
 * (the file's index), the materials array, the normals per corner, the
 * colours and the name; a PLY with a quad, colours and other vertex and face
 * properties keeps them and the quad; with a first UV set kept
 * (attr->nuv0), glTF TEXCOORD_0 and the PLY first pair are that set bit for
 * bit and TEXCOORD_1 / the second pair the atlas. */
#include "check.h"
#include "load_checked.h"

#include <stdint.h>

#include "core/json_reader.h"
#include "core/mem.h"
#include "io/mesh_io.h"
#include "mesh/mesh.h"
#include "mesh/mesh_attributes.h"

static char *slurp(const char *path, size_t *len)
{
    FILE *fp = fopen(path, "rb");
    if (!fp) return NULL;
    char *data = NULL;
    if (io_read_all(fp, &data, len) != NEUV_OK) data = NULL;
    fclose(fp);
    return data;
}

/* ---- glTF ------------------------------------------------------------ */

static const float GP[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
static const float GN[4][3] = {{0, 0, 1}, {0.6f, 0, 0.8f}, {0, 0.6f, 0.8f}, {0.8f, 0, 0.6f}};
static const unsigned char GC[4][4] = {{255, 0, 0, 255}, {0, 255, 0, 128}, {0, 0, 255, 0}, {51, 102, 153, 204}};
/* Primitive 0 (material 1, "blue"): 0 1 2; primitive 1 (material 0, "red"): 2 1 3. */
static const unsigned char GI[8] = {0, 1, 2, 2, 1, 3, 0, 0};

static int vertex_at(const double *p)
{
    for (int i = 0; i < 4; i++)
        if (fabs(p[0] - GP[i][0]) < 1e-9 && fabs(p[1] - GP[i][1]) < 1e-9 && fabs(p[2] - GP[i][2]) < 1e-9) return i;
    return -1;
}

/* m is the two-material file (as read, or written and read back): each face
 * has the material of its source primitive, each corner its vertex's normal
 * and colour, the node its name. */
static void check_gltf_kept(const neuv_mesh *m)
{
    CHECK_INT(m->nf, 2);
    CHECK(m->face_material && m->attr && m->tri_normal);
    if (!m->face_material || !m->attr || !m->tri_normal || m->nf != 2) return;
    const mesh_attributes *a = m->attr;
    CHECK(a->node_name && !strcmp(a->node_name, "Thing"));
    CHECK_INT(a->n_materials, 2);
    CHECK(a->gltf_materials && strstr(a->gltf_materials, "baseColorFactor") && strstr(a->gltf_materials, "\"blue\""));
    CHECK(a->gltf_material != NULL);
    CHECK_INT(a->color_channels, 4);
    /* What the materials refer to: the image (in a bufferView) as a data
     * URI, the material extensions and not the geometry ones. */
    CHECK(a->gltf_textures && strstr(a->gltf_textures, "\"textures\":[{\"source\":0}]") &&
          strstr(a->gltf_textures, "\"uri\":\"data:image/png;base64,AAECAgEDAAA=\"") &&
          strstr(a->gltf_textures, "KHR_materials_unlit") && !strstr(a->gltf_textures, "draco") &&
          !strstr(a->gltf_textures, "bufferView"));
    for (int f = 0; f < 2; f++) {
        int v[3];
        for (int k = 0; k < 3; k++) v[k] = vertex_at(m->pos + 3 * (size_t)m->tri[3 * f + k]);
        /* The face with vertex 0 came from primitive 0, material 1 ("blue"). */
        int from0 = v[0] == 0 || v[1] == 0 || v[2] == 0;
        int mat = m->face_material[f];
        CHECK(mat >= 0 && mat < a->n_materials);
        if (mat < 0 || mat >= a->n_materials) continue;
        CHECK(a->material_name[mat] && !strcmp(a->material_name[mat], from0 ? "blue" : "red"));
        if (a->gltf_material) CHECK_INT(a->gltf_material[mat], from0 ? 1 : 0);
        for (int k = 0; k < 3; k++) {
            CHECK(v[k] >= 0);
            if (v[k] < 0) continue;
            const double *n = m->normal + 3 * (size_t)m->tri_normal[3 * f + k];
            for (int e = 0; e < 3; e++) CHECK_NEAR(n[e], GN[v[k]][e], 1e-6);
            const float *c = a->color + 4 * (size_t)m->tri[3 * f + k];
            for (int e = 0; e < 4; e++) CHECK_NEAR(c[e], GC[v[k]][e] / 255.0, 1e-6);
        }
    }
}

static void test_gltf_materials_normals(void)
{
    unsigned char buf[160];
    size_t n = 0;
    memcpy(buf + n, GP, 48); n += 48; /* the test host is little-endian */
    memcpy(buf + n, GN, 48); n += 48;
    memcpy(buf + n, GC, 16); n += 16;
    memcpy(buf + n, GI, 8); n += 8;
    write_tmp_file("keep.bin", buf, n);
    char text[4096];
    snprintf(text, sizeof text,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
             "\"nodes\":[{\"name\":\"Thing\",\"mesh\":0}],"
             "\"textures\":[{\"source\":0}],\"images\":[{\"bufferView\":3,\"mimeType\":\"image/png\"}],"
             "\"extensionsUsed\":[\"KHR_materials_unlit\",\"KHR_draco_mesh_compression\"],"
             "\"materials\":[{\"name\":\"red\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0,0,1]}},"
             "{\"name\":\"blue\",\"doubleSided\":true}],"
             "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"keep.bin\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48},"
             "{\"buffer\":0,\"byteOffset\":96,\"byteLength\":16},{\"buffer\":0,\"byteOffset\":112,\"byteLength\":8}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
             "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
             "{\"bufferView\":2,\"componentType\":5121,\"normalized\":true,\"count\":4,\"type\":\"VEC4\"},"
             "{\"bufferView\":3,\"componentType\":5121,\"count\":3,\"type\":\"SCALAR\"},"
             "{\"bufferView\":3,\"byteOffset\":3,\"componentType\":5121,\"count\":3,\"type\":\"SCALAR\"}],"
             "\"meshes\":[{\"primitives\":["
             "{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"COLOR_0\":2},\"indices\":3,\"material\":1},"
             "{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"COLOR_0\":2},\"indices\":4,\"material\":0}]}]}",
             n);
    /* A primitive without a material: finish puts an unnamed material
     * first, and the file's index is still known for the other. */
    {
        char text2[4096];
        snprintf(text2, sizeof text2, "%s", text);
        char *at = strstr(text2, ",\"material\":1}");
        CHECK(at != NULL);
        if (at) memmove(at, at + 13, strlen(at + 13) + 1);
        neuv_mesh *u = load(write_tmp_file("keep_unnamed.gltf", text2, strlen(text2)));
        for (int round = 0; u && round < 2; round++) {
            CHECK(u->attr && u->face_material && u->attr->gltf_material && u->attr->n_materials == 3);
            if (!(u->attr && u->face_material && u->attr->gltf_material && u->attr->n_materials == 3)) break;
            for (int f = 0; f < u->nf; f++) {
                int from0 = vertex_at(u->pos + 3 * (size_t)u->tri[3 * f]) == 0 || vertex_at(u->pos + 3 * (size_t)u->tri[3 * f + 1]) == 0 ||
                            vertex_at(u->pos + 3 * (size_t)u->tri[3 * f + 2]) == 0;
                CHECK_INT(u->attr->gltf_material[u->face_material[f]], from0 ? -1 : 0);
            }
            const char *path = tmp_path("keep_unnamed_out.glb");
            CHECK(neuv_mesh_save(u, path) == NEUV_OK);
            mesh_free(u);
            u = load(path);
        }
        mesh_free(u);
    }
    neuv_mesh *m = load(write_tmp_file("keep.gltf", text, strlen(text)));
    if (!m) return;
    check_gltf_kept(m);
    static const char *outs[] = {"keep_out.gltf", "keep_out.glb"};
    for (int i = 0; i < 2; i++) {
        const char *path = tmp_path(outs[i]);
        CHECK(neuv_mesh_save(m, path) == NEUV_OK);
        neuv_mesh *r = load(path);
        if (!r) continue;
        check_gltf_kept(r);
        /* The materials array comes back as it was read. */
        CHECK(r->attr && m->attr && r->attr->gltf_materials && !strcmp(r->attr->gltf_materials, m->attr->gltf_materials));
        mesh_free(r);
    }
    mesh_free(m);
}

/* ---- PLY ------------------------------------------------------------- */

static const char *PLY_TEXT =
    "ply\nformat ascii 1.0\nelement vertex 5\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property float u\nproperty float v\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float quality\n"
    "element face 2\nproperty list uchar int vertex_indices\nproperty ushort flags\nend_header\n"
    "0 0 0 0 0 255 0 0 0.5\n"
    "1 0 0 1 0 0 255 0 1.5\n"
    "1 1 0 1 1 0 0 255 2.5\n"
    "0 1 0 0 1 10 20 30 3.5\n"
    "2 0 0 0.75 0.25 40 50 60 4.5\n"
    "4 0 1 2 3 7\n"
    "3 1 4 2 65535\n";

static void check_ply_kept(const neuv_mesh *m)
{
    CHECK_INT(m->nv, 5);
    CHECK_INT(m->np, 2);
    CHECK(m->attr != NULL);
    if (!m->attr || m->np != 2) return;
    CHECK_INT(m->poly_start[1] - m->poly_start[0], 4); /* the quad is still a quad */
    CHECK_INT(m->poly_start[2] - m->poly_start[1], 3);
    const mesh_attributes *a = m->attr;
    CHECK_INT(a->color_channels, 3);
    CHECK_INT(a->color_type, PLY_U8);
    CHECK(a->ply_uv_name[0] && !strcmp(a->ply_uv_name[0], "u") && a->ply_uv_name[1] && !strcmp(a->ply_uv_name[1], "v"));
    CHECK_INT(a->ply_vertex.count, 1);
    CHECK_INT(a->ply_face.count, 1);
    if (a->ply_vertex.count != 1 || a->ply_face.count != 1 || !a->color) return;
    CHECK(!strcmp(a->ply_vertex.name[0], "quality") && a->ply_vertex.type[0] == PLY_F32);
    CHECK(!strcmp(a->ply_face.name[0], "flags") && a->ply_face.type[0] == PLY_U16);
    CHECK_INT(a->ply_face.elements, 2);
    if (a->ply_face.elements == 2) {
        CHECK(a->ply_face.value[0] == 7);
        CHECK(a->ply_face.value[1] == 65535);
    }
    static const int rgb[5][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {10, 20, 30}, {40, 50, 60}};
    for (int v = 0; v < 5; v++) {
        int i = (int)lround(m->pos[3 * v] + 3 * m->pos[3 * v + 1]); /* x + 3y names the vertex */
        int src = i == 0 ? 0 : i == 1 ? 1 : i == 4 ? 2 : i == 3 ? 3 : 4;
        CHECK(a->ply_vertex.value[v] == src + 0.5);
        for (int c = 0; c < 3; c++) CHECK_NEAR(a->color[3 * v + c], rgb[src][c] / 255.0, 1e-7);
    }
}

static void test_ply_properties(void)
{
    neuv_mesh *m = load(write_tmp_file("keep.ply", PLY_TEXT, strlen(PLY_TEXT)));
    if (!m) return;
    check_ply_kept(m);
    const char *path = tmp_path("keep_out.ply");
    CHECK(neuv_mesh_save(m, path) == NEUV_OK);
    size_t len = 0;
    char *data = slurp(path, &len);
    CHECK(data && strstr(data, "property float quality\n") && strstr(data, "property ushort flags\n") &&
          strstr(data, "property uchar red\n") && strstr(data, "property float u\n"));
    mem_free(data);
    neuv_mesh *r = load(path);
    if (r) check_ply_kept(r);
    mesh_free(r);
    mesh_free(m);
}

/* ---- a kept first UV set --------------------------------------------- */

/* Gives m (read from PLY_TEXT) its UVs as the first set and a different
 * atlas with a seam: face f's UVs shifted by f. */
static void make_second_set(neuv_mesh *m)
{
    mesh_attributes *a = m->attr;
    a->nuv0 = m->nuv;
    a->uv0 = mem_alloc(sizeof(double) * 2 * (size_t)m->nuv);
    a->tri_uv0 = mem_alloc(sizeof(int) * 3 * (size_t)m->nf);
    memcpy(a->uv0, m->uv, sizeof(double) * 2 * (size_t)m->nuv);
    memcpy(a->tri_uv0, m->tri_uv, sizeof(int) * 3 * (size_t)m->nf);
    double *uv = mem_alloc(sizeof(double) * 6 * (size_t)m->nf);
    int *tri_uv = mem_alloc(sizeof(int) * 3 * (size_t)m->nf);
    for (int c = 0; c < 3 * m->nf; c++) {
        const double *t = m->uv + 2 * (size_t)m->tri_uv[c];
        uv[2 * c] = 0.1 + 0.25 * t[0] + 0.3 * (c / 3);
        uv[2 * c + 1] = 0.2 + 0.25 * t[1] + 0.01 * (c / 3);
        tri_uv[c] = c;
    }
    CHECK(mesh_set_uv(m, 3 * m->nf, uv, tri_uv) == NEUV_OK);
    mem_free(uv);
    mem_free(tri_uv);
}

static int same_float(double a, float b) { float x = (float)a; return !memcmp(&x, &b, 4); }

/* The floats of accessor `ai` of a GLB (which neuv writes tightly packed). */
static const float *glb_floats(const json_value *root, const unsigned char *bin, long long ai)
{
    const json_value *acc = json_at(json_get(root, "accessors"), (int)ai);
    long long vi = 0, off = 0;
    if (!json_int_in(json_get(acc, "bufferView"), 0, 100, &vi)) return NULL;
    const json_value *view = json_at(json_get(root, "bufferViews"), (int)vi);
    if (!json_int_in(json_get(view, "byteOffset"), 0, 1 << 30, &off)) return NULL;
    return (const float *)(const void *)(bin + off);
}

static void test_second_uv_set(void)
{
    neuv_mesh *m = load(write_tmp_file("keep2.ply", PLY_TEXT, strlen(PLY_TEXT)));
    if (!m || !m->attr || m->nuv == 0) { mesh_free(m); CHECK(0); return; }
    make_second_set(m);
    const mesh_attributes *a = m->attr;

    /* PLY: u v is the first set, u1 v1 the atlas; reading takes the first. */
    const char *ply = tmp_path("keep2_out.ply");
    CHECK(neuv_mesh_save(m, ply) == NEUV_OK);
    size_t len = 0;
    char *data = slurp(ply, &len);
    CHECK(data && strstr(data, "property float u\nproperty float v\nproperty float u1\nproperty float v1\n"));
    mem_free(data);
    neuv_mesh *r = load(ply);
    if (r && r->attr && r->nf == m->nf && r->nuv > 0) {
        const ply_extra *x = &r->attr->ply_vertex;
        int iu = -1, iv = -1;
        for (int i = 0; i < x->count; i++) {
            if (!strcmp(x->name[i], "u1")) iu = i;
            if (!strcmp(x->name[i], "v1")) iv = i;
        }
        CHECK(iu >= 0 && iv >= 0);
        CHECK(r->nv > m->nv); /* the atlas's seams split vertices */
        for (int c = 0; c < 3 * m->nf && iu >= 0 && iv >= 0; c++) {
            const double *first = a->uv0 + 2 * (size_t)a->tri_uv0[c], *atlas = m->uv + 2 * (size_t)m->tri_uv[c];
            const double *got = r->uv + 2 * (size_t)r->tri_uv[c];
            CHECK(same_float(first[0], (float)got[0]) && same_float(first[1], (float)got[1]));
            int v = r->tri[c];
            CHECK(same_float(atlas[0], (float)x->value[(size_t)v * (size_t)x->count + (size_t)iu]));
            CHECK(same_float(atlas[1], (float)x->value[(size_t)v * (size_t)x->count + (size_t)iv]));
        }
    } else {
        CHECK(0);
    }
    /* Written again with the atlas as the second set, u1 v1 are the new
     * atlas, not a copy of the old one beside it. */
    if (r && r->attr) {
        make_second_set(r);
        const char *again = tmp_path("keep3_out.ply");
        CHECK(neuv_mesh_save(r, again) == NEUV_OK);
        data = slurp(again, &len);
        CHECK(data && strstr(data, "property float u1\n") && strstr(strstr(data, "property float u1\n") + 18, "u1\n") == NULL);
        mem_free(data);
    }
    mesh_free(r);

    /* glTF: TEXCOORD_0 the first set, TEXCOORD_1 the atlas (both v flipped). */
    const char *glb = tmp_path("keep2_out.glb");
    CHECK(neuv_mesh_save(m, glb) == NEUV_OK);
    data = slurp(glb, &len);
    json_value root = {0};
    uint32_t jl = 0;
    if (data && len > 20) memcpy(&jl, data + 12, 4);
    CHECK(data && len > 28 + jl && json_parse(data + 20, jl, &root) == NEUV_OK);
    if (data && len > 28 + jl && root.type == JSON_OBJECT) {
        const unsigned char *bin = (const unsigned char *)data + 20 + jl + 8;
        const json_value *prim = json_at(json_get(json_at(json_get(&root, "meshes"), 0), "primitives"), 0);
        const json_value *at = json_get(prim, "attributes");
        long long t0, t1, ii;
        CHECK(json_int_in(json_get(at, "TEXCOORD_0"), 0, 100, &t0) && json_int_in(json_get(at, "TEXCOORD_1"), 0, 100, &t1) &&
              json_int_in(json_get(prim, "indices"), 0, 100, &ii));
        const float *uv0 = glb_floats(&root, bin, t0), *uv1 = glb_floats(&root, bin, t1);
        const uint32_t *idx = (const uint32_t *)(const void *)glb_floats(&root, bin, ii);
        CHECK(uv0 && uv1 && idx);
        for (int c = 0; uv0 && uv1 && idx && c < 3 * m->nf; c++) {
            const double *first = a->uv0 + 2 * (size_t)a->tri_uv0[c], *atlas = m->uv + 2 * (size_t)m->tri_uv[c];
            uint32_t v = idx[c];
            CHECK(same_float(first[0], uv0[2 * v]) && same_float(1.0 - first[1], uv0[2 * v + 1]));
            CHECK(same_float(atlas[0], uv1[2 * v]) && same_float(1.0 - atlas[1], uv1[2 * v + 1]));
        }
    }
    json_value_free(&root);
    mem_free(data);
    /* Read back, the first set is the mesh's UVs. */
    r = load(glb);
    if (r && r->nf == m->nf && r->nuv > 0)
        for (int c = 0; c < 3 * m->nf; c++) {
            const double *first = a->uv0 + 2 * (size_t)a->tri_uv0[c], *got = r->uv + 2 * (size_t)r->tri_uv[c];
            CHECK_NEAR(got[0], first[0], 1e-7);
            CHECK_NEAR(got[1], first[1], 1e-7);
        }
    mesh_free(r);
    mesh_free(m);
}

int main(void)
{
    test_gltf_materials_normals();
    test_ply_properties();
    test_second_uv_set();
    return check_report("test_io_keep");
}
