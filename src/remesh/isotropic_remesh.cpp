/* Isotropic remeshing through CGAL (see isotropic_remesh.h). The only C++
 * in neuv: every exception stops here and becomes a neuv_status. neuv's C
 * headers carry no extern "C" of their own, hence the block. */
extern "C" {
#include "core/error.h"
#include "mesh/mesh.h"
#include "spatial/bvh.h"
}
#include "remesh/isotropic_remesh.h"
#include "remesh/cgal_guard.hpp"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

typedef neuv_cgal::Kernel Kernel;
typedef CGAL::Surface_mesh<Kernel::Point_3> Surface;
typedef Surface::Vertex_index Vertex;
typedef Surface::Edge_index Edge;
typedef std::vector<Kernel::Segment_3>::const_iterator Segment_iterator;
typedef CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_segment_primitive<Kernel, Segment_iterator>>>
    Segment_tree;
namespace PMP = CGAL::Polygon_mesh_processing;

/* A larger target is refused: it would take minutes and gigabytes. */
const double ISOTROPIC_MAX_FACES = 2e7;
const double ISOTROPIC_FACE_TOLERANCE = 0.10;
const int ISOTROPIC_MAX_CORRECTIONS = 2;
const double ISOTROPIC_PI = 3.14159265358979323846;

/* Faces of equilateral triangles with side L tiling area A. */
double equilateral_faces(double area, double L) { return 4.0 * area / (std::sqrt(3.0) * L * L); }

struct remesh_result {
    std::vector<double> pos;
    std::vector<int> tri;
    int feature_edges_in = 0, feature_edges_out = 0, corners = 0;
    void swap(remesh_result &o)
    {
        pos.swap(o.pos);
        tri.swap(o.tri);
        std::swap(feature_edges_in, o.feature_edges_in);
        std::swap(feature_edges_out, o.feature_edges_out);
        std::swap(corners, o.corners);
    }
};

/* One remeshing of the input soup at target length L. */
void remesh_once(const std::vector<Kernel::Point_3> &points, const std::vector<std::array<int, 3>> &soup,
                 const isotropic_options &o, double L, remesh_result &r)
{
    Surface sm;
    PMP::polygon_soup_to_polygon_mesh(points, soup, sm);
    Surface::Property_map<Edge, bool> feature = sm.add_property_map<Edge, bool>("e:neuv_feature", false).first;
    Surface::Property_map<Vertex, bool> fixed = sm.add_property_map<Vertex, bool>("v:neuv_fixed", false).first;
    if (o.feature_degrees < 180) PMP::detect_sharp_edges(sm, o.feature_degrees, feature);
    r.feature_edges_in = 0;
    for (Edge e : sm.edges()) r.feature_edges_in += feature[e] && !sm.is_border(e);
    /* Vertices on feature and boundary polylines may be collapsed away
     * along them. Where polylines meet or end (a cube's corner), or where
     * one turns by more than the feature angle (a square's corner), that
     * would cut the shape: those stay. The polylines' vertices are not
     * relaxed (relax_constraints): CGAL's 1D smoothing moves them to their
     * neighbours' midpoint without projecting, which left cow.obj's curved
     * ridges 0.07 off the surface and made zero-area faces; in 5.5 it also
     * ignores vertex_is_constrained_map. */
    const double cos_turn = std::cos(std::fmin(o.feature_degrees, 180.0) * ISOTROPIC_PI / 180.0);
    r.corners = 0;
    for (Vertex v : sm.vertices()) {
        if (sm.is_isolated(v)) continue;
        int n = 0;
        Vertex ends[2];
        for (auto h : CGAL::halfedges_around_target(v, sm))
            if (feature[sm.edge(h)] || sm.is_border(sm.edge(h))) {
                if (n < 2) ends[n] = sm.source(h);
                n++;
            }
        int corner = n == 1 || n > 2;
        if (n == 2) {
            /* The turn is the angle between (v - a) and (b - v). */
            Kernel::Vector_3 in = sm.point(v) - sm.point(ends[0]), out = sm.point(ends[1]) - sm.point(v);
            double len = std::sqrt(in.squared_length() * out.squared_length());
            corner = len > 0 && in * out < cos_turn * len;
        }
        if (corner) { fixed[v] = true; r.corners++; }
    }
    std::vector<Kernel::Segment_3> polylines;
    for (Edge e : sm.edges())
        if (feature[e] || sm.is_border(e)) polylines.emplace_back(sm.point(sm.vertex(e, 0)), sm.point(sm.vertex(e, 1)));
    PMP::isotropic_remeshing(sm.faces(), L, sm,
                             CGAL::parameters::number_of_iterations((unsigned)o.iterations)
                                 .edge_is_constrained_map(feature)
                                 .vertex_is_constrained_map(fixed)
                                 .protect_constraints(false)
                                 .relax_constraints(false)
                                 .do_project(true));
    /* CGAL projects only vertices off the polylines; a split of a chord
     * left where a collapse cut a polyline's bend puts a vertex off the
     * surface. Put such vertices back on the input's polylines. */
    if (!polylines.empty()) {
        Segment_tree tree(polylines.begin(), polylines.end());
        tree.accelerate_distance_queries();
        for (Vertex v : sm.vertices()) {
            if (fixed[v] || sm.is_isolated(v)) continue;
            int on_polyline = 0;
            for (auto h : CGAL::halfedges_around_target(v, sm))
                on_polyline |= feature[sm.edge(h)] || sm.is_border(sm.edge(h));
            if (on_polyline) sm.point(v) = tree.closest_point(sm.point(v));
        }
    }
    r.feature_edges_out = 0;
    for (Edge e : sm.edges()) r.feature_edges_out += feature[e] && !sm.is_border(e);
    std::vector<int> index(sm.num_vertices(), -1);
    r.pos.clear();
    r.tri.clear();
    int nv = 0;
    for (Vertex v : sm.vertices()) {
        if (sm.is_isolated(v)) continue;
        index[(size_t)v] = nv++;
        const Kernel::Point_3 &p = sm.point(v);
        r.pos.insert(r.pos.end(), {p.x(), p.y(), p.z()});
    }
    for (auto f : sm.faces()) {
        int k = 0, t[3] = {-1, -1, -1};
        for (Vertex v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
            if (k == 3) throw std::runtime_error("CGAL returned a face with more than 3 vertices");
            t[k++] = index[(size_t)v];
        }
        if (k != 3) throw std::runtime_error("CGAL returned a face with fewer than 3 vertices");
        r.tri.insert(r.tri.end(), {t[0], t[1], t[2]});
    }
}

/* Largest distance from the points to the surface of m (the repo's BVH). */
neuv_status max_distance_to(const neuv_mesh *m, const std::vector<double> &pos, double *out)
{
    bvh b;
    neuv_status st = bvh_build(&b, m);
    if (st) return st;
    int n = (int)(pos.size() / 3);
    std::vector<double> d2((size_t)n);
    bvh_closest_points(&b, n, pos.data(), NULL, NULL, d2.data());
    bvh_free(&b);
    double worst = 0;
    for (double d : d2) worst = std::fmax(worst, d);
    *out = std::sqrt(worst);
    return NEUV_OK;
}

/* CGAL writes warnings to std::cerr by default; the library prints nothing. */
neuv_status remesh_checked(const neuv_mesh *m, const isotropic_options &o, neuv_mesh **out, isotropic_report *rep)
{
    std::vector<Kernel::Point_3> points;
    std::vector<std::array<int, 3>> faces;
    neuv_status st0 = neuv_cgal::soup_from_mesh(
        m, "isotropic remeshing",
        "isotropic remeshing needs a manifold, oriented triangle mesh: found an edge with more than two faces, a "
        "pinched vertex, a face with a repeated vertex, or two faces of opposite orientation across an edge (a "
        "non-orientable surface such as a Moebius strip, or an uncleaned mesh)",
        points, faces);
    if (st0) return st0;
    double area = mesh_total_area(m);
    if (!(area > 0)) return error_set(NEUV_ERR_INPUT, "isotropic remeshing: the mesh has zero area");
    double L = o.target_edge_length;
    if (!(L > 0)) L = std::sqrt(4.0 * area / (std::sqrt(3.0) * o.target_faces));

    /* With a face target the round closest to it is kept: the count is a
     * step function of L (edges within [4/5 L, 4/3 L] are left alone), so
     * a correction can overshoot. */
    remesh_result r, best;
    double best_L = L, best_miss = INFINITY;
    int rounds = 0;
    for (;;) {
        double expected = equilateral_faces(area, L);
        if (expected > ISOTROPIC_MAX_FACES)
            return error_set(NEUV_ERR_INPUT, "isotropic remeshing: edge length %g would give about %.3g faces "
                                             "(over %.0g)", L, expected, ISOTROPIC_MAX_FACES);
        remesh_once(points, faces, o, L, r);
        rounds++;
        if (o.target_edge_length > 0) { best.swap(r); best_L = L; break; }
        double got = (double)(r.tri.size() / 3), want = o.target_faces;
        double miss = std::fabs(got - want) / want;
        if (miss < best_miss) { best.swap(r); best_L = L; best_miss = miss; }
        if (miss <= ISOTROPIC_FACE_TOLERANCE || rounds > ISOTROPIC_MAX_CORRECTIONS || got == 0) break;
        /* Faces go as 1 / L^2, so this L would have hit N had this round's ratio held. */
        L *= std::sqrt(got / want);
    }
    L = best_L;
    if (best.tri.empty()) return error_set(NEUV_ERR_INTERNAL, "isotropic remeshing at edge length %g left no face", L);
    if (best.pos.size() / 3 > (size_t)INT32_MAX / 3 || best.tri.size() / 3 > (size_t)INT32_MAX / 3)
        return error_set(NEUV_ERR_INPUT, "isotropic remeshing: the output is too large");
    double dist = 0;
    neuv_status st = max_distance_to(m, best.pos, &dist);
    if (st) return st;
    neuv_mesh *o_mesh = mesh_create((int)(best.pos.size() / 3), (int)(best.tri.size() / 3), 0);
    if (!o_mesh) return error_nomem("the remeshed mesh");
    std::copy(best.pos.begin(), best.pos.end(), o_mesh->pos);
    std::copy(best.tri.begin(), best.tri.end(), o_mesh->tri);
    *out = o_mesh;
    if (rep) {
        rep->faces_in = m->nf;
        rep->faces_out = o_mesh->nf;
        rep->edge_length = L;
        rep->feature_edges_in = best.feature_edges_in;
        rep->feature_edges_out = best.feature_edges_out;
        rep->corners = best.corners;
        rep->rounds = rounds;
        rep->max_distance = dist;
    }
    return NEUV_OK;
}

} // namespace

extern "C" void isotropic_default_options(isotropic_options *o)
{
    o->target_edge_length = 0;
    o->target_faces = 0;
    o->iterations = 5;
    o->feature_degrees = 60;
}

extern "C" neuv_status mesh_remesh_isotropic(const neuv_mesh *m, const isotropic_options *opts, neuv_mesh **out,
                                             isotropic_report *report)
{
    *out = NULL;
    if (report) *report = isotropic_report();
    if (!opts) return error_set(NEUV_ERR_INPUT, "isotropic remeshing needs a target edge length or face count");
    if (!(opts->target_edge_length > 0) && !(opts->target_edge_length == 0 && opts->target_faces >= 4))
        return error_set(NEUV_ERR_INPUT, "isotropic remeshing needs an edge length > 0 or at least 4 faces "
                                         "(got %g and %d)", opts->target_edge_length, opts->target_faces);
    if (opts->iterations < 1 || opts->iterations > 100)
        return error_set(NEUV_ERR_INPUT, "isotropic remeshing: iterations must be in 1..100, got %d", opts->iterations);
    if (!(opts->feature_degrees > 0))
        return error_set(NEUV_ERR_INPUT, "isotropic remeshing: feature angle must be > 0, got %g", opts->feature_degrees);
    if (m->nf <= 0) return error_set(NEUV_ERR_INPUT, "cannot remesh a mesh without faces");
    return neuv_cgal::guarded("isotropic remeshing", out, [&] { return remesh_checked(m, *opts, out, report); });
}
