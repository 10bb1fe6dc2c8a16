/* Topology-preserving edge collapse through CGAL (see edge_collapse.h).
 * Every exception stops here and becomes a neuv_status. */
extern "C" {
#include "core/error.h"
#include "mesh/mesh.h"
}
#include "remesh/edge_collapse.h"
#include "remesh/cgal_guard.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_ratio_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <new>
#include <string>
#include <vector>

namespace {

typedef neuv_cgal::Kernel Kernel;
typedef CGAL::Surface_mesh<Kernel::Point_3> Surface;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace SMS = CGAL::Surface_mesh_simplification;

neuv_status collapse_checked(const neuv_mesh *m, int target_faces, neuv_mesh **out)
{
    std::vector<Kernel::Point_3> points;
    std::vector<std::array<int, 3>> faces;
    neuv_status st = neuv_cgal::soup_from_mesh(
        m, "edge collapse",
        "edge collapse needs a manifold, oriented triangle mesh: found an edge with more than two faces, a pinched "
        "vertex, a repeated vertex in a face, or two faces of opposite orientation across an edge",
        points, faces);
    if (st) return st;
    Surface sm;
    PMP::polygon_soup_to_polygon_mesh(points, faces, sm);
    std::vector<Kernel::Point_3>().swap(points);
    std::vector<std::array<int, 3>>().swap(faces);
    /* The stop counts edges; on a manifold mesh E = 3F/2 + B/2, so the
     * edge ratio is the face ratio but for the boundary's share. */
    SMS::Count_ratio_stop_predicate<Surface> stop((double)target_faces / m->nf);
    SMS::edge_collapse(sm, stop);

    std::vector<int> index(sm.number_of_vertices() + sm.number_of_removed_vertices(), -1);
    int nv = 0;
    for (Surface::Vertex_index v : sm.vertices()) index[(size_t)v] = nv++;
    neuv_mesh *o = mesh_create(nv, (int)sm.number_of_faces(), 0);
    if (!o) return error_nomem("the simplified mesh");
    for (Surface::Vertex_index v : sm.vertices()) {
        const Kernel::Point_3 &p = sm.point(v);
        double *q = o->pos + 3 * (size_t)index[(size_t)v];
        q[0] = p.x(); q[1] = p.y(); q[2] = p.z();
    }
    size_t c = 0;
    for (Surface::Face_index f : sm.faces()) {
        int k = 0;
        for (Surface::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
            if (k < 3) o->tri[c + (size_t)k] = index[(size_t)v];
            k++;
        }
        if (k != 3) {
            mesh_free(o);
            return error_set(NEUV_ERR_INTERNAL, "edge collapse left a face with %d corners", k);
        }
        c += 3;
    }
    *out = o;
    return NEUV_OK;
}

} // namespace

extern "C" neuv_status mesh_edge_collapse(const neuv_mesh *m, int target_faces, neuv_mesh **out)
{
    *out = NULL;
    if (m->nf <= 0) return error_set(NEUV_ERR_INPUT, "cannot simplify a mesh without faces");
    if (target_faces < 1) return error_set(NEUV_ERR_INPUT, "edge collapse needs a target of at least 1 face, got %d", target_faces);
    return neuv_cgal::guarded("edge collapse", out, [&] { return collapse_checked(m, target_faces, out); });
}
