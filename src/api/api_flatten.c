/* Public classic flattening of one disk (`neuv flatten`): LSCM or the
 * harmonic map, scaled into the unit square. */
#include <math.h>
#include <string.h>

#include "neuv/neuv.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "flatten/disk_topology.h"
#include "flatten/harmonic.h"
#include "flatten/lscm.h"
#include "mesh/mesh.h"
#include "metrics/uv_metrics.h"

_Static_assert(sizeof(neuv_metrics) == sizeof(uv_metrics), "public and internal metrics differ");

/* Uniform scale and shift of uv (#V by 2) into [0,1]², keeping the aspect. */
static void fit_unit_square(int nv, double *uv)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int v = 0; v < nv; v++)
        for (int c = 0; c < 2; c++) {
            lo[c] = fmin(lo[c], uv[2 * v + c]);
            hi[c] = fmax(hi[c], uv[2 * v + c]);
        }
    double size = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    double s = size > 0 ? 1.0 / size : 1.0;
    for (int v = 0; v < nv; v++)
        for (int c = 0; c < 2; c++) {
            double x = (uv[2 * v + c] - lo[c]) * s;
            uv[2 * v + c] = x < 0 ? 0 : x > 1 ? 1 : x; /* clamp rounding only */
        }
}

/* The map on a copy of m, which replaces m only once everything succeeded,
 * so that a failure leaves m as it was. */
static neuv_status flatten_copy(const neuv_mesh *m, neuv_method method, neuv_mesh **out, neuv_flatten_report *report)
{
    neuv_status s = flatten_require_disk(m, NULL, NULL);
    if (s != NEUV_OK) return s;
    double *uv = mem_alloc(sizeof(double) * 2 * (size_t)m->nv);
    if (!uv) return error_set(NEUV_ERR_NOMEM, "out of memory");
    double t0 = now_seconds();
    s = method == NEUV_METHOD_LSCM ? lscm(m, uv) : harmonic(m, uv);
    double seconds = now_seconds() - t0;
    neuv_mesh *c = NULL;
    if (s == NEUV_OK) {
        fit_unit_square(m->nv, uv);
        c = mesh_clone(m);
        if (!c) s = error_nomem("the mesh");
    }
    if (s == NEUV_OK) s = mesh_set_uv(c, c->nv, uv, c->tri);
    mem_free(uv);
    uv_metrics mt;
    if (s == NEUV_OK && report) s = uv_metrics_compute(c, &mt);
    if (s != NEUV_OK) { mesh_free(c); return s; }
    if (report) {
        report->seconds = seconds;
        memcpy(&report->metrics, &mt, sizeof report->metrics);
    }
    *out = c;
    return NEUV_OK;
}

neuv_status neuv_flatten(neuv_mesh *mesh, neuv_method method, const neuv_callbacks *cb, neuv_flatten_report *report)
{
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_flatten: no mesh");
    if (method != NEUV_METHOD_LSCM && method != NEUV_METHOD_HARMONIC)
        return error_set(NEUV_ERR_INPUT, "flattening is by NEUV_METHOD_LSCM or NEUV_METHOD_HARMONIC, not method %d",
                         (int)method);
    log_scope scope;
    log_scope_open(&scope, cb);
    neuv_mesh *c = NULL;
    neuv_status s = flatten_copy(mesh, method, &c, report);
    log_scope_close(&scope);
    if (s != NEUV_OK) return s;
    neuv_mesh old = *mesh;
    *mesh = *c;
    *c = old;
    mesh_free(c);
    return NEUV_OK;
}
