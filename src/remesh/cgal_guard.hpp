/* What neuv's CGAL files (isotropic_remesh.cpp, edge_collapse.cpp) share:
 * a neuv mesh as a checked polygon soup, and a guard that turns every
 * exception into a neuv_status with a one-line message. C++ only. */
#ifndef NEUV_REMESH_CGAL_GUARD_HPP
#define NEUV_REMESH_CGAL_GUARD_HPP

extern "C" {
#include "core/error.h"
#include "mesh/mesh.h"
}

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <array>
#include <cmath>
#include <exception>
#include <new>
#include <string>
#include <vector>

namespace neuv_cgal {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;

/* CGAL's messages span lines; neuv's errors are one line. */
inline std::string one_line(std::string s)
{
    for (char &c : s)
        if (c == '\n' || c == '\r') c = ' ';
    return s;
}

inline void silent_warning(const char *, const char *, const char *, int, const char *) {}

/* m's positions and triangles as a polygon soup, refused (NEUV_ERR_INPUT,
 * messages starting with `what`) for a non-finite coordinate, a corner out
 * of range, or a soup that is not a manifold oriented mesh (`not_manifold`
 * is then the whole message). */
inline neuv_status soup_from_mesh(const neuv_mesh *m, const char *what, const char *not_manifold,
                                  std::vector<Kernel::Point_3> &points, std::vector<std::array<int, 3>> &faces)
{
    points.clear();
    points.reserve((size_t)m->nv);
    faces.assign((size_t)m->nf, std::array<int, 3>());
    for (int v = 0; v < m->nv; v++) {
        const double *p = m->pos + 3 * (size_t)v;
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            return error_set(NEUV_ERR_INPUT, "%s: vertex %d has a non-finite coordinate", what, v);
        points.emplace_back(p[0], p[1], p[2]);
    }
    for (int f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++) {
            int v = m->tri[3 * (size_t)f + k];
            if (v < 0 || v >= m->nv) return error_set(NEUV_ERR_INPUT, "%s: face %d uses vertex %d of %d", what, f, v, m->nv);
            faces[(size_t)f][k] = v;
        }
    if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(faces))
        return error_set(NEUV_ERR_INPUT, "%s", not_manifold);
    return NEUV_OK;
}

/* Runs body() (returning a neuv_status, filling *out) with CGAL's warnings
 * silenced and every exception caught as "<what> failed ..."; on failure
 * *out is freed and NULL. */
template <class Body> neuv_status guarded(const char *what, neuv_mesh **out, Body body)
{
    CGAL::Failure_function old_warning = CGAL::set_warning_handler(silent_warning);
    neuv_status st;
    try {
        st = body();
    } catch (const std::bad_alloc &) {
        st = error_nomem(what);
    } catch (const CGAL::Failure_exception &e) {
        st = error_set(NEUV_ERR_INTERNAL, "%s failed in CGAL: %s%s%s (%s:%d)", what, one_line(e.expression()).c_str(),
                       e.message().empty() ? "" : ": ", one_line(e.message()).c_str(), e.filename().c_str(),
                       e.line_number());
    } catch (const std::exception &e) {
        st = error_set(NEUV_ERR_INTERNAL, "%s failed: %s", what, one_line(e.what()).c_str());
    } catch (...) {
        st = error_set(NEUV_ERR_INTERNAL, "%s failed with an unknown exception", what);
    }
    CGAL::set_warning_handler(old_warning);
    if (st != NEUV_OK && *out) {
        mesh_free(*out);
        *out = NULL;
    }
    return st;
}

} // namespace neuv_cgal

#endif
