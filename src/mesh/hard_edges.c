#include "mesh/hard_edges.h"

#include <math.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "mesh/clean.h"
#include "mesh/edge_faces.h"

/* 1 - cos of the largest angle between two normals that count as the same
 * (about 0.1 degree: files round normals to 4-6 digits). */
#define SAME_NORMAL 2e-6

static double unit_dot(const double *a, const double *b)
{
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    if (!(la > 0) || !(lb > 0)) return 1; /* a zero normal says nothing */
    return (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
}

/* The normal of face f's corner at vertex v (NULL if f has no such corner). */
static const double *corner_normal(const neuv_mesh *m, int f, int v)
{
    for (int k = 0; k < 3; k++)
        if (m->tri[3 * (size_t)f + k] == v) return m->normal + 3 * (size_t)m->tri_normal[3 * (size_t)f + k];
    return NULL;
}

/* Whether every corner's normal is its face's own (faces of zero area aside). */
static int is_flat_shaded(const neuv_mesh *m)
{
    for (int f = 0; f < m->nf; f++) {
        double fn[3];
        mesh_face_normal(m, f, fn);
        if (fn[0] == 0 && fn[1] == 0 && fn[2] == 0) continue;
        for (int k = 0; k < 3; k++)
            if (1 - unit_dot(fn, m->normal + 3 * (size_t)m->tri_normal[3 * (size_t)f + k]) > 1e-4) return 0;
    }
    return 1;
}

neuv_status mesh_hard_edges(const neuv_mesh *m, double **ends, int *n, hard_edge_report *rep)
{
    *ends = NULL;
    *n = 0;
    memset(rep, 0, sizeof *rep);
    int normals = m->nn > 0 && m->tri_normal, materials = m->face_material != NULL;
    if (!normals && !materials) return NEUV_OK;
    if (normals && is_flat_shaded(m)) { rep->flat_shaded = 1; normals = 0; }
    if (!normals && !materials) return NEUV_OK;
    neuv_mesh *w = mesh_clone(m);
    if (!w || mesh_weld_positions(w) < 0) { mesh_free(w); return error_nomem("the hard edges"); }
    edge_faces ef;
    if (edge_faces_build(&ef, w) != 0) { mesh_free(w); return error_nomem("the hard edges"); }
    double *out = mem_alloc(sizeof(double) * 6 * (size_t)(ef.ne > 0 ? ef.ne : 1));
    if (!out) { edge_faces_free(&ef); mesh_free(w); return error_nomem("the hard edges"); }
    int count = 0;
    for (int e = 0; e < ef.ne; e++) {
        if (edge_faces_count(&ef, e) != 2) continue;
        int f = ef.side[ef.start[e]] / 3, g = ef.side[ef.start[e] + 1] / 3;
        int hard = 0;
        for (int i = 0; normals && i < 2 && !hard; i++) {
            int v = ef.edge_v[2 * e + i];
            const double *a = corner_normal(w, f, v), *b = corner_normal(w, g, v);
            hard = a && b && 1 - unit_dot(a, b) > SAME_NORMAL;
        }
        if (hard) rep->from_normals++;
        else if (materials && w->face_material[f] != w->face_material[g]) { hard = 1; rep->from_materials++; }
        if (!hard) continue;
        memcpy(out + 6 * (size_t)count, w->pos + 3 * (size_t)ef.edge_v[2 * e], sizeof(double) * 3);
        memcpy(out + 6 * (size_t)count + 3, w->pos + 3 * (size_t)ef.edge_v[2 * e + 1], sizeof(double) * 3);
        count++;
    }
    edge_faces_free(&ef);
    mesh_free(w);
    if (count == 0) { mem_free(out); out = NULL; }
    *ends = out;
    *n = count;
    return NEUV_OK;
}
