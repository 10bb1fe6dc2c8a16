/* Chart provenance names and the per-chart qce (chart_source.h). */
#include "unwrap/chart_source.h"

#include <math.h>

#include "metrics/uv_metrics.h"

const char *chart_source_name(chart_source s)
{
    switch (s) {
    case CHART_SOURCE_NETWORK: return "network";
    case CHART_SOURCE_NETWORK_REFINED: return "network+refined";
    case CHART_SOURCE_NETWORK_FOLDED: return "network_folded";
    case CHART_SOURCE_LSCM_AFTER_FOLD: return "lscm_after_fold";
    case CHART_SOURCE_LSCM_AFTER_SPLIT: return "lscm_after_split";
    case CHART_SOURCE_LSCM: return "lscm";
    case CHART_SOURCE_HARMONIC: return "harmonic";
    case CHART_SOURCE_HARMONIC_AFTER_SPLIT: return "harmonic_after_split";
    case CHART_SOURCE_TRANSFERRED: return "transferred";
    default: return "unknown";
    }
}

int chart_source_is_network(chart_source s)
{
    return s == CHART_SOURCE_NETWORK || s == CHART_SOURCE_NETWORK_REFINED;
}

/* Face f's corners: 3D positions and UVs. */
static void face_corners(const neuv_mesh *sub, const double *uv, int f, double p[3][3], double q[3][2])
{
    for (int k = 0; k < 3; k++) {
        int v = sub->tri[3 * f + k];
        for (int c = 0; c < 3; c++) p[k][c] = sub->pos[3 * v + c];
        q[k][0] = uv[2 * v];
        q[k][1] = uv[2 * v + 1];
    }
}

double chart_qce_mean(const neuv_mesh *sub, const double *uv, double *area)
{
    double num = 0, den = 0, total = 0;
    for (int f = 0; f < sub->nf; f++) {
        double p[3][3], q[3][2], s[2];
        face_corners(sub, uv, f, p, q);
        double a = mesh_face_area(sub, f);
        total += a;
        uv_jacobian_singular_values(p, q, s);
        if (!(a > 0) || !(s[1] > 0) || !isfinite(s[0] / s[1])) continue;
        num += a * s[0] / s[1];
        den += a;
    }
    if (area) *area = total;
    return den > 0 ? num / den : NAN;
}

double chart_l2_stretch(const neuv_mesh *sub, const double *uv)
{
    double a3 = 0, auv = 0, sum = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int f = 0; f < sub->nf; f++) {
            double p[3][3], q[3][2], s[2];
            face_corners(sub, uv, f, p, q);
            double a = mesh_face_area(sub, f);
            double b = 0.5 * fabs((q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0]));
            if (!(a > 0) || !(b > 0)) continue;
            if (pass == 0) { a3 += a; auv += b; continue; }
            uv_jacobian_singular_values(p, q, s);
            double sigma = sqrt(a3 / auv), big = 1 / (sigma * s[1]), small = 1 / (sigma * s[0]);
            if (isfinite(big)) sum += a * (big * big + small * small) / 2;
        }
    return a3 > 0 ? sqrt(sum / a3) : NAN;
}
