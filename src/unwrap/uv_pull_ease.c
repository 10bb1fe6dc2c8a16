#include "unwrap/uv_pull_ease.h"

double uv_face_area2(const double *uv, const int *t)
{
    const double *a = uv + 2 * t[0], *b = uv + 2 * t[1], *c = uv + 2 * t[2];
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

int uv_pull_ease(const neuv_mesh *sub, const double *uv0, double *uv)
{
    int eased_total = 0;
    for (int round = 0; round < UV_PULL_EASE_ROUNDS; round++) {
        int eased = 0;
        for (int f = 0; f < sub->nf; f++) {
            const int *t = sub->tri + 3 * f;
            double before = uv_face_area2(uv0, t);
            if (!(before > 0) || uv_face_area2(uv, t) >= UV_PULL_KEEP_AREA * before) continue;
            for (int k = 0; k < 3; k++) {
                double *q = uv + 2 * t[k];
                const double *q0 = uv0 + 2 * t[k];
                if (q[0] == q0[0] && q[1] == q0[1]) continue;
                q[0] = q0[0] + 0.5 * (q[0] - q0[0]);
                q[1] = q0[1] + 0.5 * (q[1] - q0[1]);
                eased++;
            }
        }
        if (!eased) break;
        eased_total += eased;
    }
    return eased_total;
}
