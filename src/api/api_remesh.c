/* Public remeshing (`neuv remesh`): other triangulations of the same
 * surface by simplification, subdivision, isotropic remeshing and jitter. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "neuv/neuv.h"
#include "core/error.h"
#include "core/log.h"
#include "remesh/isotropic_remesh.h"
#include "remesh/jitter.h"
#include "remesh/simplify.h"
#include "remesh/subdivide.h"

/* Subdivision rounds accepted: 8 rounds already make 65536 faces of one. */
#define MAX_SUBDIVISION_ROUNDS 8

neuv_status neuv_mesh_simplify(const neuv_mesh *mesh, double ratio, const neuv_callbacks *cb, neuv_mesh **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_mesh_simplify: no output pointer");
    *out = NULL;
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_mesh_simplify: no mesh");
    if (!(ratio > 0 && ratio <= 1)) return error_set(NEUV_ERR_INPUT, "simplify ratio must be in (0, 1], got %g", ratio);
    log_scope scope;
    log_scope_open(&scope, cb);
    neuv_status s = mesh_simplify(mesh, ratio, out);
    log_scope_close(&scope);
    return s;
}

neuv_status neuv_mesh_subdivide(const neuv_mesh *mesh, int rounds, neuv_subdivision scheme, neuv_mesh **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_mesh_subdivide: no output pointer");
    *out = NULL;
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_mesh_subdivide: no mesh");
    if (rounds < 0 || rounds > MAX_SUBDIVISION_ROUNDS)
        return error_set(NEUV_ERR_INPUT, "subdivision rounds must be 0 to %d, got %d", MAX_SUBDIVISION_ROUNDS, rounds);
    if (scheme != NEUV_SUBDIVIDE_MIDPOINT && scheme != NEUV_SUBDIVIDE_LOOP)
        return error_set(NEUV_ERR_INPUT, "unknown subdivision scheme %d", (int)scheme);
    return mesh_subdivide(mesh, rounds, scheme == NEUV_SUBDIVIDE_LOOP ? SUBDIVIDE_LOOP : SUBDIVIDE_MIDPOINT, out);
}

void neuv_isotropic_options_init(neuv_isotropic_options *o)
{
    isotropic_options d;
    isotropic_default_options(&d);
    memset(o, 0, sizeof *o);
    o->edge_length = d.target_edge_length;
    o->faces = d.target_faces;
    o->iterations = d.iterations;
    o->feature_degrees = d.feature_degrees;
}

static double diagonal(const neuv_mesh *m)
{
    double lo[3], hi[3];
    mesh_bounding_box(m, lo, hi);
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

neuv_status neuv_mesh_remesh_isotropic(const neuv_mesh *mesh, const neuv_isotropic_options *o,
                                       const neuv_callbacks *cb, neuv_mesh **out, neuv_isotropic_report *report)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_mesh_remesh_isotropic: no output pointer");
    *out = NULL;
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_mesh_remesh_isotropic: no mesh");
    if (!o) return error_set(NEUV_ERR_INPUT, "isotropic remeshing needs options with an edge length or a face count");
    isotropic_options io;
    isotropic_default_options(&io);
    io.target_edge_length = o->edge_length;
    io.target_faces = o->faces;
    io.iterations = o->iterations;
    io.feature_degrees = o->feature_degrees;
    isotropic_report ir;
    log_scope scope;
    log_scope_open(&scope, cb);
    neuv_status s = mesh_remesh_isotropic(mesh, &io, out, &ir);
    log_scope_close(&scope);
    if (s != NEUV_OK || !report) return s;
    memset(report, 0, sizeof *report);
    report->faces_in = ir.faces_in;
    report->faces_out = ir.faces_out;
    report->edge_length = ir.edge_length;
    report->feature_edges_in = ir.feature_edges_in;
    report->feature_edges_out = ir.feature_edges_out;
    report->rounds = ir.rounds;
    report->max_distance = ir.max_distance;
    report->diagonal = diagonal(mesh);
    return NEUV_OK;
}

neuv_status neuv_mesh_jitter(neuv_mesh *mesh, unsigned long long seed, neuv_jitter_report *report)
{
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_mesh_jitter: no mesh");
    /* On a copy that replaces the mesh once it succeeded: a failure leaves
     * the mesh as it was. */
    neuv_mesh *c = mesh_clone(mesh);
    if (!c) return error_nomem("the mesh");
    jitter_report jr;
    neuv_status s = mesh_jitter(c, (uint64_t)seed, NULL, &jr);
    if (s != NEUV_OK) { mesh_free(c); return s; }
    neuv_mesh old = *mesh;
    *mesh = *c;
    *c = old;
    mesh_free(c);
    if (report) {
        memset(report, 0, sizeof *report);
        report->moved_vertices = jr.moved_vertices;
        report->slid_vertices = jr.slid_vertices;
        report->fixed_vertices = jr.fixed_vertices;
        report->flipped_edges = jr.flipped_edges;
        report->max_deviation = jr.max_deviation;
    }
    return NEUV_OK;
}
