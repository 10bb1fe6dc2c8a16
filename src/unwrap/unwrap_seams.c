#include "unwrap/unwrap_seams.h"

#include <math.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "mesh/edge_faces.h"
#include "mesh/edge_map.h"
#include "mesh/seam_cut.h"

/* The user's pairs as positions of `in` (n by 6 doubles). */
static neuv_status user_seam_points(const neuv_unwrap_options *o, const neuv_mesh *in, double **out)
{
    *out = NULL;
    if (o->seam_edge_count <= 0) return NEUV_OK;
    if (!o->seam_edges) return error_set(NEUV_ERR_INPUT, "seam_edge_count is %d but seam_edges is NULL",
                                         o->seam_edge_count);
    double *p = mem_alloc(sizeof(double) * 6 * (size_t)o->seam_edge_count);
    if (!p) return error_nomem("the seams");
    for (int i = 0; i < o->seam_edge_count; i++)
        for (int j = 0; j < 2; j++) {
            int v = o->seam_edges[2 * i + j];
            if (v < 0 || v >= in->nv) {
                mem_free(p);
                return error_set(NEUV_ERR_INPUT, "seam edge %d: vertex %d is not a vertex of the mesh (0..%d)", i,
                                 v, in->nv - 1);
            }
            memcpy(p + 6 * (size_t)i + 3 * j, in->pos + 3 * (size_t)v, sizeof(double) * 3);
        }
    *out = p;
    return NEUV_OK;
}

neuv_status unwrap_seams_cut(struct neuv_unwrap_result *r, const neuv_mesh *in, int keep_model, int apply)
{
    const neuv_unwrap_options *o = &r->opts;
    if (!(o->seam_angle >= 0 && o->seam_angle < 180))
        return error_set(NEUV_ERR_INPUT, "seam angle (--seam-angle) %g: expected degrees in 0..180", o->seam_angle);
    if (o->seam_edge_count < 0) return error_set(NEUV_ERR_INPUT, "seam_edge_count %d is negative", o->seam_edge_count);
    double *hard = NULL;
    int n_hard = 0;
    if (o->hard_edges) {
        neuv_status s = mesh_hard_edges(in, &hard, &n_hard, &r->hard);
        if (s != NEUV_OK) return s;
    }
    int asked = o->seam_angle > 0 || o->seam_edge_count > 0;
    if (!asked && n_hard == 0) return NEUV_OK;
    if (keep_model) {
        mem_free(hard);
        if (asked)
            return error_set(NEUV_ERR_INPUT, "required seams (--seam-angle) cannot be used with a model to save "
                                             "(--save-model): a model does not record them yet");
        return error_set(NEUV_ERR_INPUT, "the mesh's normals or materials mark %d hard edges, which a saved model "
                                         "does not record yet: --no-hard-edges saves a model without them", n_hard);
    }
    if (apply) {
        mem_free(hard);
        if (asked)
            return error_set(NEUV_ERR_INPUT, "required seams (--seam-angle) cannot be used with --model: the charts "
                                             "come from the model, which does not record seams yet");
        r->hard_edges_not_kept = n_hard;
        return NEUV_OK;
    }
    double *points = NULL;
    neuv_status s = user_seam_points(o, in, &points);
    r->opts.seam_edges = NULL; /* the caller's array: read here only */
    if (s != NEUV_OK) { mem_free(hard); return s; }
    neuv_mesh *m = r->mesh;
    edge_faces ef;
    if (edge_faces_build(&ef, m) != 0) { mem_free(points); mem_free(hard); return error_nomem("the seams"); }
    unsigned char *seam = mem_calloc((size_t)ef.ne + 1, 1);
    if (!seam) { edge_faces_free(&ef); mem_free(points); mem_free(hard); return error_nomem("the seams"); }
    if (o->seam_angle > 0) r->seam_edges_angle = seam_mark_angle(m, &ef, o->seam_angle, seam);
    int user = seam_mark_positions(m, &ef, points, o->seam_edge_count, seam, &r->seam_unmatched);
    int unmatched_hard = 0;
    int from_file = user < 0 ? 0 : seam_mark_positions(m, &ef, hard, n_hard, seam, &unmatched_hard);
    mem_free(points);
    mem_free(hard);
    if (user < 0 || from_file < 0) s = error_nomem("the seams");
    int n = 0;
    for (int e = 0; e < ef.ne; e++) n += seam[e];
    r->seam_edges = n;
    r->seam_nv = m->nv;
    if (s == NEUV_OK && n > 0) {
        r->seam_pair = mem_alloc(sizeof(int) * 2 * (size_t)n);
        if (!r->seam_pair) s = error_nomem("the seams");
        for (int e = 0, i = 0; s == NEUV_OK && e < ef.ne; e++)
            if (seam[e]) { r->seam_pair[2 * i] = ef.edge_v[2 * e]; r->seam_pair[2 * i + 1] = ef.edge_v[2 * e + 1]; i++; }
        neuv_mesh *cut = NULL;
        if (s == NEUV_OK) s = mesh_cut_seams(m, &ef, seam, &cut, &r->seam_origin);
        if (s == NEUV_OK) { mesh_free(r->mesh); r->mesh = cut; }
    }
    mem_free(seam);
    edge_faces_free(&ef);
    return s;
}

/* Whether the corners of faces f and g at vertex v carry the same UV. */
static int same_uv_at(const neuv_mesh *m, int f, int g, int v)
{
    const double *a = NULL, *b = NULL;
    for (int k = 0; k < 3; k++) {
        if (m->tri[3 * (size_t)f + k] == v) a = m->uv + 2 * (size_t)m->tri_uv[3 * (size_t)f + k];
        if (m->tri[3 * (size_t)g + k] == v) b = m->uv + 2 * (size_t)m->tri_uv[3 * (size_t)g + k];
    }
    return a && b && a[0] == b[0] && a[1] == b[1];
}

neuv_status unwrap_seams_join(struct neuv_unwrap_result *r)
{
    if (!r->seam_origin) return NEUV_OK;
    neuv_mesh *m = r->mesh;
    mesh_join_seams(m, r->seam_origin, r->seam_nv);
    mem_free(r->seam_origin);
    r->seam_origin = NULL;
    r->seam_crossed = 0;
    if (!m->tri_uv) return NEUV_OK;
    edge_faces ef;
    edge_map map;
    if (edge_faces_build(&ef, m) != 0) return error_nomem("the seams");
    if (edge_faces_index(&ef, &map) != 0) { edge_faces_free(&ef); return error_nomem("the seams"); }
    for (int i = 0; i < r->seam_edges; i++) {
        int e = edge_map_get(&map, r->seam_pair[2 * i], r->seam_pair[2 * i + 1]);
        if (e < 0 || edge_faces_count(&ef, e) != 2) continue;
        int f = ef.side[ef.start[e]] / 3, g = ef.side[ef.start[e] + 1] / 3;
        if (same_uv_at(m, f, g, ef.edge_v[2 * e]) && same_uv_at(m, f, g, ef.edge_v[2 * e + 1])) r->seam_crossed++;
    }
    edge_map_free(&map);
    edge_faces_free(&ef);
    return NEUV_OK;
}
