/* Easing back pulls that collapse faces (unwrap/uv_pull_ease.h): a pull that
 * lays a corner on the line through its face's other two is halved until the
 * face keeps a tenth of its area; a pull that collapses nothing is kept. */
#include <string.h>

#include "check.h"
#include "unwrap/uv_pull_ease.h"

static double area2(const double *uv, int a, int b, int c)
{
    return (uv[2 * b] - uv[2 * a]) * (uv[2 * c + 1] - uv[2 * a + 1]) -
           (uv[2 * b + 1] - uv[2 * a + 1]) * (uv[2 * c] - uv[2 * a]);
}

int main(void)
{
    /* Two faces sharing the edge 0-1 (the island's border at v = 0 runs
     * through 0 and 1); vertex 2 lies past it at v = -1, vertex 3 inside. */
    neuv_mesh *m = mesh_create(4, 2, 0);
    const int tri[6] = {0, 2, 1, 0, 1, 3};
    memcpy(m->tri, tri, sizeof tri);
    const double uv0[8] = {0, 0, 1, 0, 0.5, -1, 0.5, 1};
    double uv[8];

    /* Vertex 2 pulled onto the border (v = 0): face 0 collapses; its pull is
     * halved once (v = -0.5, half the area), and only vertex 2 moves. */
    memcpy(uv, uv0, sizeof uv);
    uv[5] = 0;
    CHECK_NEAR(area2(uv, 0, 2, 1), 0, 0);
    CHECK_INT(uv_pull_ease(m, uv0, uv), 1);
    CHECK_NEAR(uv[5], -0.5, 1e-15);
    CHECK_NEAR(uv[4], 0.5, 0);
    CHECK(uv[0] == 0 && uv[1] == 0 && uv[2] == 1 && uv[3] == 0 && uv[6] == 0.5 && uv[7] == 1);

    /* Pulled past the border to v = 0.9 (folded): halved to v = -0.05 (a
     * twentieth of the area, still collapsed), then to v = -0.525. */
    memcpy(uv, uv0, sizeof uv);
    uv[5] = 0.9;
    CHECK_INT(uv_pull_ease(m, uv0, uv), 2);
    CHECK_NEAR(uv[5], -0.525, 1e-15);
    CHECK(area2(uv, 0, 2, 1) >= UV_PULL_KEEP_AREA * area2(uv0, 0, 2, 1));

    /* A pull to v = -0.5 keeps half the area: nothing eased. */
    memcpy(uv, uv0, sizeof uv);
    uv[5] = -0.5;
    CHECK_INT(uv_pull_ease(m, uv0, uv), 0);
    CHECK_NEAR(uv[5], -0.5, 0);

    /* A face already folded before the pull is left to the fold checks. */
    double folded0[8] = {0, 0, 1, 0, 0.5, 1, 0.5, 2};
    memcpy(uv, folded0, sizeof uv);
    uv[5] = 0;
    CHECK_INT(uv_pull_ease(m, folded0, uv), 0);
    CHECK_NEAR(uv[5], 0, 0);

    mesh_free(m);
    return check_report("test_uv_pull_ease");
}
