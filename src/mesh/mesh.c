#include "mesh/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "mesh/mesh_attributes.h"

neuv_mesh *mesh_create(int nv, int nf, int nuv)
{
    neuv_mesh *m = mem_calloc(1, sizeof *m);
    if (!m) return NULL;
    m->nv = nv;
    m->nf = nf;
    m->pos = mem_calloc((size_t)(nv > 0 ? nv : 1) * 3, sizeof(double));
    m->tri = mem_calloc((size_t)(nf > 0 ? nf : 1) * 3, sizeof(int));
    if (!m->pos || !m->tri) { mesh_free(m); return NULL; }
    if (nuv > 0) {
        m->nuv = nuv;
        m->uv = mem_calloc((size_t)nuv * 2, sizeof(double));
        m->tri_uv = mem_calloc((size_t)(nf > 0 ? nf : 1) * 3, sizeof(int));
        if (!m->uv || !m->tri_uv) { mesh_free(m); return NULL; }
    }
    return m;
}

neuv_mesh *mesh_clone(const neuv_mesh *m)
{
    neuv_mesh *c = mesh_create(m->nv, m->nf, m->nuv);
    if (!c) return NULL;
    memcpy(c->pos, m->pos, sizeof(double) * 3 * (size_t)m->nv);
    memcpy(c->tri, m->tri, sizeof(int) * 3 * (size_t)m->nf);
    if (m->nuv > 0) {
        memcpy(c->uv, m->uv, sizeof(double) * 2 * (size_t)m->nuv);
        memcpy(c->tri_uv, m->tri_uv, sizeof(int) * 3 * (size_t)m->nf);
    }
    if (mesh_set_normals(c, m->nn, m->normal, m->tri_normal) != NEUV_OK ||
        mesh_set_face_material(c, m->face_material) != NEUV_OK) {
        mesh_free(c);
        return NULL;
    }
    return c;
}

neuv_status mesh_set_normals(neuv_mesh *m, int nn, const double *normal, const int *tri_normal)
{
    mem_free(m->normal); mem_free(m->tri_normal);
    m->normal = NULL; m->tri_normal = NULL; m->nn = 0;
    if (nn <= 0 || !normal || !tri_normal) return NEUV_OK;
    m->normal = mem_alloc(sizeof(double) * 3 * (size_t)nn);
    m->tri_normal = mem_alloc(sizeof(int) * 3 * (size_t)(m->nf > 0 ? m->nf : 1));
    if (!m->normal || !m->tri_normal) {
        mem_free(m->normal); mem_free(m->tri_normal); m->normal = NULL; m->tri_normal = NULL;
        return error_nomem("normals");
    }
    m->nn = nn;
    memcpy(m->normal, normal, sizeof(double) * 3 * (size_t)nn);
    memcpy(m->tri_normal, tri_normal, sizeof(int) * 3 * (size_t)m->nf);
    return NEUV_OK;
}

neuv_status mesh_set_face_material(neuv_mesh *m, const int *face_material)
{
    mem_free(m->face_material);
    m->face_material = NULL;
    if (!face_material) return NEUV_OK;
    m->face_material = mem_alloc(sizeof(int) * (size_t)(m->nf > 0 ? m->nf : 1));
    if (!m->face_material) return error_nomem("face materials");
    memcpy(m->face_material, face_material, sizeof(int) * (size_t)m->nf);
    return NEUV_OK;
}

void mesh_drop_polygons(neuv_mesh *m)
{
    mem_free(m->face_polygon); mem_free(m->poly_start); mem_free(m->poly_corner);
    m->face_polygon = m->poly_start = m->poly_corner = NULL;
    m->np = 0;
}

void mesh_drop_file_structure(neuv_mesh *m)
{
    mesh_drop_polygons(m);
    mesh_attributes_free(m->attr);
    m->attr = NULL;
}

neuv_status mesh_copy_file_structure(neuv_mesh *m, const neuv_mesh *src)
{
    mesh_drop_file_structure(m);
    if (src->np > 0) {
        size_t nc = (size_t)src->poly_start[src->np];
        m->face_polygon = mem_alloc(sizeof(int) * (size_t)(src->nf > 0 ? src->nf : 1));
        m->poly_start = mem_alloc(sizeof(int) * ((size_t)src->np + 1));
        m->poly_corner = mem_alloc(sizeof(int) * (nc > 0 ? nc : 1));
        if (!m->face_polygon || !m->poly_start || !m->poly_corner) {
            mesh_drop_file_structure(m);
            return error_nomem("polygons");
        }
        memcpy(m->face_polygon, src->face_polygon, sizeof(int) * (size_t)src->nf);
        memcpy(m->poly_start, src->poly_start, sizeof(int) * ((size_t)src->np + 1));
        memcpy(m->poly_corner, src->poly_corner, sizeof(int) * nc);
        m->np = src->np;
    }
    if (src->attr && !(m->attr = mesh_attributes_clone(src->attr, src->nv, src->nf))) {
        mesh_drop_file_structure(m);
        return error_nomem("the file's attributes");
    }
    return NEUV_OK;
}

neuv_status mesh_set_uv(neuv_mesh *m, int nuv, const double *uv, const int *tri_uv)
{
    mem_free(m->uv); mem_free(m->tri_uv);
    m->uv = NULL; m->tri_uv = NULL; m->nuv = 0;
    if (nuv <= 0) return NEUV_OK;
    m->uv = mem_alloc(sizeof(double) * 2 * (size_t)nuv);
    m->tri_uv = mem_alloc(sizeof(int) * 3 * (size_t)(m->nf > 0 ? m->nf : 1));
    if (!m->uv || !m->tri_uv) {
        mem_free(m->uv); mem_free(m->tri_uv); m->uv = NULL; m->tri_uv = NULL;
        return error_nomem("UVs");
    }
    m->nuv = nuv;
    memcpy(m->uv, uv, sizeof(double) * 2 * (size_t)nuv);
    memcpy(m->tri_uv, tri_uv, sizeof(int) * 3 * (size_t)m->nf);
    return NEUV_OK;
}

/* Materials used by m: the largest id + 1, or 1 when it has none. */
static int material_count(const neuv_mesh *m)
{
    int n = 1;
    for (int f = 0; m->face_material && f < m->nf; f++)
        if (m->face_material[f] + 1 > n) n = m->face_material[f] + 1;
    return n;
}

/* Appends the polygons of m (faces from face f0 of joined, polygons from
 * p0, corners from c0); a mesh without polygons gives one per triangle. */
static void append_polygons(neuv_mesh *joined, const neuv_mesh *m, int f0, int p0, int c0)
{
    if (m->np > 0) {
        for (int f = 0; f < m->nf; f++) joined->face_polygon[f0 + f] = p0 + m->face_polygon[f];
        for (int p = 0; p <= m->np; p++) joined->poly_start[p0 + p] = c0 + m->poly_start[p];
        for (int c = 0; c < m->poly_start[m->np]; c++)
            joined->poly_corner[c0 + c] = m->poly_corner[c] < 0 ? -1 : 3 * f0 + m->poly_corner[c];
        return;
    }
    for (int f = 0; f <= m->nf; f++) {
        if (f < m->nf) joined->face_polygon[f0 + f] = p0 + f;
        joined->poly_start[p0 + f] = c0 + 3 * f;
    }
    for (int c = 0; c < 3 * m->nf; c++) joined->poly_corner[c0 + c] = 3 * f0 + c;
}

/* The polygons of joined (faces of a, then of b), when either has some. */
static neuv_status join_polygons(neuv_mesh *joined, const neuv_mesh *a, const neuv_mesh *b)
{
    mesh_drop_polygons(joined);
    if (!(a && a->np > 0) && b->np == 0) return NEUV_OK;
    int npa = !a ? 0 : a->np > 0 ? a->np : a->nf, npb = b->np > 0 ? b->np : b->nf;
    int nca = !a ? 0 : a->np > 0 ? a->poly_start[a->np] : 3 * a->nf;
    int ncb = b->np > 0 ? b->poly_start[b->np] : 3 * b->nf;
    joined->face_polygon = mem_alloc(sizeof(int) * (size_t)(joined->nf > 0 ? joined->nf : 1));
    joined->poly_start = mem_alloc(sizeof(int) * ((size_t)npa + (size_t)npb + 1));
    joined->poly_corner = mem_alloc(sizeof(int) * ((size_t)nca + (size_t)ncb + 1));
    if (!joined->face_polygon || !joined->poly_start || !joined->poly_corner) {
        mesh_drop_polygons(joined);
        return error_nomem("polygons");
    }
    if (a) append_polygons(joined, a, 0, 0, 0);
    append_polygons(joined, b, a ? a->nf : 0, npa, nca);
    joined->np = npa + npb;
    return NEUV_OK;
}

neuv_status mesh_join_marks(neuv_mesh *joined, const neuv_mesh *a, const neuv_mesh *b)
{
    int nfa = a ? a->nf : 0;
    mesh_set_normals(joined, 0, NULL, NULL);
    mesh_set_face_material(joined, NULL);
    if ((!a || a->nn > 0) && b->nn > 0) {
        int nna = a ? a->nn : 0;
        joined->normal = mem_alloc(sizeof(double) * 3 * (size_t)(nna + b->nn));
        joined->tri_normal = mem_alloc(sizeof(int) * 3 * (size_t)(joined->nf > 0 ? joined->nf : 1));
        if (!joined->normal || !joined->tri_normal) { mesh_set_normals(joined, 0, NULL, NULL); return error_nomem("normals"); }
        joined->nn = nna + b->nn;
        if (a) memcpy(joined->normal, a->normal, sizeof(double) * 3 * (size_t)nna);
        memcpy(joined->normal + 3 * (size_t)nna, b->normal, sizeof(double) * 3 * (size_t)b->nn);
        if (a) memcpy(joined->tri_normal, a->tri_normal, sizeof(int) * 3 * (size_t)nfa);
        for (size_t c = 0; c < 3 * (size_t)b->nf; c++) joined->tri_normal[3 * (size_t)nfa + c] = b->tri_normal[c] + nna;
    }
    if ((a && a->face_material) || b->face_material) {
        joined->face_material = mem_alloc(sizeof(int) * (size_t)(joined->nf > 0 ? joined->nf : 1));
        if (!joined->face_material) return error_nomem("face materials");
        for (int f = 0; f < nfa; f++) joined->face_material[f] = a->face_material ? a->face_material[f] : 0;
        int first = a ? material_count(a) : 0;
        for (int f = 0; f < b->nf; f++) joined->face_material[nfa + f] = first + (b->face_material ? b->face_material[f] : 0);
    }
    return join_polygons(joined, a, b);
}

void mesh_free(neuv_mesh *m)
{
    if (!m) return;
    mem_free(m->pos); mem_free(m->tri); mem_free(m->uv); mem_free(m->tri_uv);
    mem_free(m->normal); mem_free(m->tri_normal); mem_free(m->face_material);
    mesh_drop_file_structure(m);
    mem_free(m);
}

void neuv_mesh_free(neuv_mesh *m) { mesh_free(m); }
int neuv_mesh_vertex_count(const neuv_mesh *m) { return m ? m->nv : 0; }
int neuv_mesh_face_count(const neuv_mesh *m) { return m ? m->nf : 0; }
int neuv_mesh_has_uv(const neuv_mesh *m) { return m && m->nuv > 0; }

static void face_cross(const neuv_mesh *m, int f, double c[3])
{
    const double *a = m->pos + 3 * m->tri[3 * f], *b = m->pos + 3 * m->tri[3 * f + 1],
                 *d = m->pos + 3 * m->tri[3 * f + 2];
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    c[0] = e1[1] * e2[2] - e1[2] * e2[1];
    c[1] = e1[2] * e2[0] - e1[0] * e2[2];
    c[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

double mesh_face_area(const neuv_mesh *m, int f)
{
    double c[3];
    face_cross(m, f, c);
    return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

void mesh_face_normal(const neuv_mesh *m, int f, double n[3])
{
    face_cross(m, f, n);
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0) { n[0] /= l; n[1] /= l; n[2] /= l; }
}

void mesh_vertex_normals(const neuv_mesh *m, double *n)
{
    for (size_t i = 0; i < 3 * (size_t)m->nv; i++) n[i] = 0;
    for (int f = 0; f < m->nf; f++) {
        double fn[3], a = mesh_face_area(m, f);
        mesh_face_normal(m, f, fn);
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < 3; c++) n[3 * (size_t)m->tri[3 * f + k] + c] += a * fn[c];
    }
    for (int v = 0; v < m->nv; v++) {
        double *p = n + 3 * (size_t)v, l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        if (l > 0)
            for (int c = 0; c < 3; c++) p[c] /= l;
    }
}

double mesh_total_area(const neuv_mesh *m)
{
    double a = 0;
    for (int f = 0; f < m->nf; f++) a += mesh_face_area(m, f);
    return a;
}

void mesh_bounding_box(const neuv_mesh *m, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) { lo[k] = m->nv ? m->pos[k] : 0; hi[k] = lo[k]; }
    for (int v = 0; v < m->nv; v++)
        for (int k = 0; k < 3; k++) {
            double x = m->pos[3 * v + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
}
