#include "io/mesh_builder.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "io/polygon_triangulate.h"
#include "mesh/mesh_attributes.h"

/* nv and nf are ints everywhere in neuv, and index arithmetic uses 3*nf. */
#define MAX_ITEMS ((size_t)INT_MAX / 4)

void mesh_builder_init(mesh_builder *b)
{
    memset(b, 0, sizeof *b);
    b->material = -1;
    b->group = -1;
}

struct mesh_attributes *mesh_builder_attributes(mesh_builder *b)
{
    if (!b->attr) b->attr = mesh_attributes_new();
    return b->attr;
}

void mesh_builder_free(mesh_builder *b)
{
    mem_free(b->pos); mem_free(b->uv); mem_free(b->tri); mem_free(b->tri_uv); mem_free(b->origin);
    mem_free(b->normal); mem_free(b->tri_normal); mem_free(b->face_material);
    mem_free(b->face_polygon); mem_free(b->face_group); mem_free(b->poly_start); mem_free(b->poly_corner);
    mesh_attributes_free(b->attr);
    mem_free(b->scratch_pos); mem_free(b->scratch_xy); mem_free(b->scratch_idx); mem_free(b->scratch_tri);
    mesh_builder_init(b);
}

static int grow(void **p, size_t *cap, size_t need, size_t item)
{
    if (need <= *cap) return 1;
    size_t c = *cap ? *cap : 256;
    while (c < need) c *= 2;
    void *q = mem_realloc(*p, c * item);
    if (!q) return 0;
    *p = q;
    *cap = c;
    return 1;
}

static neuv_status grow_vertices(mesh_builder *b, size_t need)
{
    if (need > MAX_ITEMS) return error_set(NEUV_ERR_INPUT, "more than %zu vertices; too large for neuv", MAX_ITEMS);
    return grow((void **)&b->pos, &b->cap_v, need, 3 * sizeof(double)) ? NEUV_OK : error_nomem("vertices");
}

static neuv_status grow_uvs(mesh_builder *b, size_t need)
{
    if (need > MAX_ITEMS) return error_set(NEUV_ERR_INPUT, "more than %zu texture coordinates; too large for neuv", MAX_ITEMS);
    return grow((void **)&b->uv, &b->cap_uv, need, 2 * sizeof(double)) ? NEUV_OK : error_nomem("texture coordinates");
}

static neuv_status grow_faces(mesh_builder *b, size_t need)
{
    if (need > MAX_ITEMS) return error_set(NEUV_ERR_INPUT, "more than %zu triangles; too large for neuv", MAX_ITEMS);
    if (need <= b->cap_f) return NEUV_OK;
    size_t c1 = b->cap_f, c2 = b->cap_f, c3 = b->cap_f, c4 = b->cap_f, c5 = b->cap_f, c6 = b->cap_f, c7 = b->cap_f;
    if (!grow((void **)&b->tri, &c1, need, 3 * sizeof(int)) ||
        !grow((void **)&b->tri_uv, &c2, need, 3 * sizeof(int)) ||
        !grow((void **)&b->origin, &c3, need, sizeof(int)) ||
        !grow((void **)&b->tri_normal, &c4, need, 3 * sizeof(int)) ||
        !grow((void **)&b->face_material, &c5, need, sizeof(int)) ||
        !grow((void **)&b->face_polygon, &c6, need, sizeof(int)) ||
        !grow((void **)&b->face_group, &c7, need, sizeof(int)))
        return error_nomem("faces");
    b->cap_f = c1;
    return NEUV_OK;
}

neuv_status mesh_builder_reserve(mesh_builder *b, long long nv, long long nf)
{
    neuv_status s;
    if (nv > 0 && (s = grow_vertices(b, (size_t)nv)) != NEUV_OK) return s;
    if (nf > 0 && (s = grow_faces(b, (size_t)nf)) != NEUV_OK) return s;
    return NEUV_OK;
}

neuv_status mesh_builder_add_vertex(mesh_builder *b, double x, double y, double z)
{
    if ((size_t)b->nv >= b->cap_v) {
        neuv_status s = grow_vertices(b, (size_t)b->nv + 1);
        if (s != NEUV_OK) return s;
    }
    double *p = b->pos + 3 * (size_t)b->nv++;
    p[0] = x; p[1] = y; p[2] = z;
    return NEUV_OK;
}

neuv_status mesh_builder_add_uv(mesh_builder *b, double u, double v)
{
    if ((size_t)b->nuv >= b->cap_uv) {
        neuv_status s = grow_uvs(b, (size_t)b->nuv + 1);
        if (s != NEUV_OK) return s;
    }
    double *p = b->uv + 2 * (size_t)b->nuv++;
    p[0] = u; p[1] = v;
    return NEUV_OK;
}

neuv_status mesh_builder_add_normal(mesh_builder *b, double x, double y, double z)
{
    if ((size_t)b->nn >= b->cap_n) {
        if ((size_t)b->nn + 1 > MAX_ITEMS) return error_set(NEUV_ERR_INPUT, "more than %zu normals; too large for neuv", MAX_ITEMS);
        if (!grow((void **)&b->normal, &b->cap_n, (size_t)b->nn + 1, 3 * sizeof(double))) return error_nomem("normals");
    }
    double *p = b->normal + 3 * (size_t)b->nn++;
    p[0] = x; p[1] = y; p[2] = z;
    return NEUV_OK;
}

/* A triangle of polygon corners i, j, k; corner_of[c] is set to the
 * triangle corner of polygon corner c when it has none yet. */
static void put_triangle(mesh_builder *b, const int *v, const int *uv, const int *vn, int i, int j, int k, int origin,
                         int *corner_of)
{
    int ijk[3] = {i, j, k};
    for (int q = 0; q < 3; q++)
        if (corner_of[ijk[q]] < 0) corner_of[ijk[q]] = 3 * b->nf + q;
    b->face_polygon[b->nf] = b->np;
    b->face_group[b->nf] = b->group;
    int *t = b->tri + 3 * (size_t)b->nf, *tu = b->tri_uv + 3 * (size_t)b->nf, *tn = b->tri_normal + 3 * (size_t)b->nf;
    t[0] = v[i]; t[1] = v[j]; t[2] = v[k];
    if (uv) { tu[0] = uv[i]; tu[1] = uv[j]; tu[2] = uv[k]; }
    else tu[0] = tu[1] = tu[2] = -1;
    if (vn) { tn[0] = vn[i]; tn[1] = vn[j]; tn[2] = vn[k]; }
    else tn[0] = tn[1] = tn[2] = -1;
    b->face_material[b->nf] = b->material;
    b->origin[b->nf++] = origin;
}

static neuv_status triangulate(mesh_builder *b, int n, const int *v, const int *uv, const int *vn, int origin,
                               int *corner_of);

neuv_status mesh_builder_add_polygon(mesh_builder *b, int n, const int *v, const int *uv, int origin)
{
    return mesh_builder_add_polygon_normals(b, n, v, uv, NULL, origin);
}

neuv_status mesh_builder_add_polygon_normals(mesh_builder *b, int n, const int *v, const int *uv, const int *vn,
                                             int origin)
{
    neuv_status s = grow_faces(b, (size_t)b->nf + (size_t)(n - 2));
    if (s != NEUV_OK) return s;
    if (uv) b->faces_with_uv++;
    else b->faces_without_uv++;
    if (vn) b->faces_with_normal++;
    else b->faces_without_normal++;
    if (!grow((void **)&b->poly_start, &b->cap_p, (size_t)b->np + 2, sizeof(int))) return error_nomem("polygons");
    if (b->np == 0) b->poly_start[0] = 0;
    if (!grow((void **)&b->poly_corner, &b->cap_pc, (size_t)b->poly_start[b->np] + (size_t)n, sizeof(int)))
        return error_nomem("polygons");
    int *corner_of = b->poly_corner + b->poly_start[b->np];
    for (int i = 0; i < n; i++) corner_of[i] = -1;
    if (n > 3) b->any_polygon = 1;
    if (n == 3) {
        put_triangle(b, v, uv, vn, 0, 1, 2, origin, corner_of);
    } else {
        if ((s = triangulate(b, n, v, uv, vn, origin, corner_of)) != NEUV_OK) return s;
    }
    b->poly_start[b->np + 1] = b->poly_start[b->np] + n;
    b->np++;
    return NEUV_OK;
}

static neuv_status triangulate(mesh_builder *b, int n, const int *v, const int *uv, const int *vn, int origin,
                               int *corner_of)
{
    if ((size_t)n > b->cap_scratch) {
        size_t c = (size_t)n * 2;
        double *sp = mem_realloc(b->scratch_pos, c * 3 * sizeof(double));
        if (sp) b->scratch_pos = sp;
        double *sx = mem_realloc(b->scratch_xy, c * 2 * sizeof(double));
        if (sx) b->scratch_xy = sx;
        int *si = mem_realloc(b->scratch_idx, c * sizeof(int));
        if (si) b->scratch_idx = si;
        int *st = mem_realloc(b->scratch_tri, c * 3 * sizeof(int));
        if (st) b->scratch_tri = st;
        if (!sp || !sx || !si || !st) return error_nomem("a polygon");
        b->cap_scratch = c;
    }
    /* A corner outside the vertices seen so far is reported by finish; the
     * polygon is then fanned, as its shape is unknown. */
    int known = 1;
    for (int i = 0; i < n; i++) {
        if (v[i] < 0 || v[i] >= b->nv) { known = 0; break; }
        memcpy(b->scratch_pos + 3 * i, b->pos + 3 * (size_t)v[i], 3 * sizeof(double));
    }
    if (!known) memset(b->scratch_pos, 0, (size_t)n * 3 * sizeof(double));
    polygon_triangulate(n, b->scratch_pos, b->scratch_tri, b->scratch_xy, b->scratch_idx);
    for (int t = 0; t < n - 2; t++) {
        const int *c = b->scratch_tri + 3 * t;
        put_triangle(b, v, uv, vn, c[0], c[1], c[2], origin, corner_of);
    }
    return NEUV_OK;
}

static neuv_status bad_index(mesh_builder_style st, int origin, const char *what, const char *whats,
                             int index, int count)
{
    if (st.origin_is_line)
        return error_set(NEUV_ERR_INPUT, "line %d: face references %s %d, but there are %d %s",
                         origin, what, index + st.index_base, count, whats);
    return error_set(NEUV_ERR_INPUT, "face %d references %s %d, but there are %d %s",
                     origin, what, index + st.index_base, count, whats);
}

neuv_status mesh_builder_finish(mesh_builder *b, mesh_builder_style st, neuv_mesh **out)
{
    *out = NULL;
    neuv_status s = NEUV_OK;
    if (b->nf == 0) {
        s = error_set(NEUV_ERR_INPUT, "no faces (a point cloud?); neuv needs a triangle mesh");
        goto done;
    }
    for (int i = 0; i < b->nv; i++) {
        const double *p = b->pos + 3 * (size_t)i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            s = error_set(NEUV_ERR_INPUT, "vertex %d has a non-finite coordinate", i + st.index_base);
            goto done;
        }
    }
    for (size_t k = 0; k < 3 * (size_t)b->nf; k++)
        if (b->tri[k] < 0 || b->tri[k] >= b->nv) {
            s = bad_index(st, b->origin[k / 3], "vertex", "vertices", b->tri[k], b->nv);
            goto done;
        }
    int keep_uv = b->faces_with_uv > 0 && b->faces_without_uv == 0;
    if (b->faces_with_uv > 0 && b->faces_without_uv > 0)
        log_message(NEUV_LOG_WARN, "%d of %d faces have no texture coordinates; UVs dropped",
                 b->faces_without_uv, b->faces_with_uv + b->faces_without_uv);
    if (keep_uv) {
        for (size_t k = 0; k < 3 * (size_t)b->nf; k++)
            if (b->tri_uv[k] < 0 || b->tri_uv[k] >= b->nuv) {
                s = bad_index(st, b->origin[k / 3], "texture coordinate", "texture coordinates", b->tri_uv[k], b->nuv);
                goto done;
            }
        for (int i = 0; i < b->nuv; i++)
            if (!isfinite(b->uv[2 * (size_t)i]) || !isfinite(b->uv[2 * (size_t)i + 1])) {
                s = error_set(NEUV_ERR_INPUT, "texture coordinate %d is not finite", i + st.index_base);
                goto done;
            }
    }

    int keep_normals = b->nn > 0 && b->faces_with_normal > 0 && b->faces_without_normal == 0;
    for (size_t k = 0; keep_normals && k < 3 * (size_t)b->nf; k++)
        if (b->tri_normal[k] < 0 || b->tri_normal[k] >= b->nn) {
            log_message(NEUV_LOG_WARN, "%s%d: a face references normal %d, but there are %d; normals dropped",
                        st.origin_is_line ? "line " : "face ", b->origin[k / 3], b->tri_normal[k] + st.index_base,
                        b->nn);
            keep_normals = 0;
        }
    for (int i = 0; keep_normals && i < b->nn; i++) {
        const double *p = b->normal + 3 * (size_t)i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            log_message(NEUV_LOG_WARN, "normal %d has a non-finite coordinate; normals dropped", i + st.index_base);
            keep_normals = 0;
        }
    }
    int any_material = 0;
    for (int f = 0; f < b->nf && !any_material; f++) any_material = b->face_material[f] >= 0;

    neuv_mesh *m = mem_calloc(1, sizeof *m);
    if (!m) { s = error_nomem("a mesh"); goto done; }
    /* Hand the arrays over, shrunk to size (a failed shrink keeps the block). */
    m->nv = b->nv;
    m->nf = b->nf;
    m->pos = b->pos; b->pos = NULL;
    m->tri = b->tri; b->tri = NULL;
    double *pp = mem_realloc(m->pos, 3 * sizeof(double) * (size_t)(m->nv > 0 ? m->nv : 1));
    if (pp) m->pos = pp;
    int *tp = mem_realloc(m->tri, 3 * sizeof(int) * (size_t)m->nf);
    if (tp) m->tri = tp;
    if (keep_uv && b->nuv > 0) {
        m->nuv = b->nuv;
        m->uv = b->uv; b->uv = NULL;
        m->tri_uv = b->tri_uv; b->tri_uv = NULL;
        double *up = mem_realloc(m->uv, 2 * sizeof(double) * (size_t)m->nuv);
        if (up) m->uv = up;
        int *tup = mem_realloc(m->tri_uv, 3 * sizeof(int) * (size_t)m->nf);
        if (tup) m->tri_uv = tup;
    }
    if (keep_normals) {
        m->nn = b->nn;
        m->normal = b->normal; b->normal = NULL;
        m->tri_normal = b->tri_normal; b->tri_normal = NULL;
    }
    if (any_material) { /* faces before the first material: material 0, the others after it */
        int first_unnamed = 0;
        for (int f = 0; f < b->nf; f++) first_unnamed |= b->face_material[f] < 0;
        if (first_unnamed)
            for (int f = 0; f < b->nf; f++) b->face_material[f]++;
        m->face_material = b->face_material; b->face_material = NULL;
        mesh_attributes *a = b->attr;
        if (first_unnamed && a && a->n_materials > 0) { /* the unnamed material comes first */
            char **names = mem_realloc(a->material_name, sizeof(char *) * ((size_t)a->n_materials + 1));
            if (!names) { mesh_free(m); s = error_nomem("material names"); goto done; }
            memmove(names + 1, names, sizeof(char *) * (size_t)a->n_materials);
            names[0] = NULL;
            a->material_name = names;
            a->n_materials++;
        }
    }
    int any_group = 0;
    for (int f = 0; f < b->nf && !any_group; f++) any_group = b->face_group[f] >= 0;
    if (any_group && b->attr) {
        b->attr->face_group = b->face_group;
        b->face_group = NULL;
    }
    if (b->any_polygon || (b->attr && b->attr->ply_face.count > 0)) {
        m->np = b->np;
        m->poly_start = b->poly_start; b->poly_start = NULL;
        m->poly_corner = b->poly_corner; b->poly_corner = NULL;
        m->face_polygon = b->face_polygon; b->face_polygon = NULL;
    }
    m->attr = b->attr;
    b->attr = NULL;
    *out = m;
done:
    mesh_builder_free(b);
    return s;
}
