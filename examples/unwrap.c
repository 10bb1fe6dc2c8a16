/* Unwraps a procedural box with libneuv and prints its charts and report.
 *
 * Build against an installed neuv (make install PREFIX=DIR):
 *
 *     export PKG_CONFIG_PATH=DIR/lib/pkgconfig
 *     cc unwrap.c $(pkg-config --cflags --libs neuv) -o unwrap
 *     LD_LIBRARY_PATH=DIR/lib ./unwrap
 *
 * Uses only the public header. The API reads meshes from files, so the
 * box goes through an OBJ in a temporary directory.
 */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */

#include <neuv/neuv.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { N = 6 }; /* quads along each edge of the box */
enum {
    N_VERTICES = (N + 1) * (N + 1) * (N + 1) - (N - 1) * (N - 1) * (N - 1),
    N_FACES = 6 * N * N * 2
};

/* A unit box whose sides are N by N grids of quads, each split in two, as
 * plain arrays: positions is #V by 3, triangles is #F by 3 (0-based,
 * counter-clockwise seen from outside). The vertices are the points of an
 * (N+1)^3 lattice that lie on its surface, so the sides share their edges. */
static void make_box(float positions[N_VERTICES][3], int triangles[N_FACES][3])
{
    int index[N + 1][N + 1][N + 1];
    int v = 0;
    for (int i = 0; i <= N; i++)
        for (int j = 0; j <= N; j++)
            for (int k = 0; k <= N; k++) {
                int surface = i == 0 || i == N || j == 0 || j == N || k == 0 || k == N;
                index[i][j][k] = surface ? v : -1;
                if (!surface) continue;
                positions[v][0] = (float)i / N - 0.5f;
                positions[v][1] = (float)j / N - 0.5f;
                positions[v][2] = (float)k / N - 0.5f;
                v++;
            }

    /* A side holds axis a at 0 or N; axes b and c, in that order, span it
     * and b x c = a points outwards on the side at N. */
    int f = 0;
    for (int a = 0; a < 3; a++) {
        int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int side = 0; side <= N; side += N)
            for (int s = 0; s < N; s++)
                for (int t = 0; t < N; t++) {
                    int q[4]; /* the quad's corners (s,t) (s+1,t) (s+1,t+1) (s,t+1) */
                    for (int m = 0; m < 4; m++) {
                        int p[3];
                        p[a] = side;
                        p[b] = s + (m == 1 || m == 2);
                        p[c] = t + (m >= 2);
                        q[m] = index[p[0]][p[1]][p[2]];
                    }
                    int outwards = side == N;
                    int t0[3] = {q[0], outwards ? q[1] : q[2], outwards ? q[2] : q[1]};
                    int t1[3] = {q[0], outwards ? q[2] : q[3], outwards ? q[3] : q[2]};
                    memcpy(triangles[f++], t0, sizeof t0);
                    memcpy(triangles[f++], t1, sizeof t1);
                }
    }
}

static int fail(neuv_atlas *atlas)
{
    fprintf(stderr, "unwrap: error: %s\n", neuv_last_error());
    neuv_atlas_destroy(atlas);
    return 2;
}

int main(void)
{
    static float positions[N_VERTICES][3];
    static int triangles[N_FACES][3];
    make_box(positions, triangles);
    printf("neuv %s: box with %d vertices, %d faces\n", neuv_version(), N_VERTICES, N_FACES);

    neuv_mesh_decl box;
    neuv_mesh_decl_init(&box);
    box.positions = positions;
    box.vertex_count = N_VERTICES;
    box.indices = triangles;
    box.index_type = NEUV_INT32;
    box.index_count = 3 * N_FACES;

    /* Quick settings, a second or two: least squares conformal maps on the
     * charts (the default, NEUV_METHOD_NEURAL, trains the parameterization
     * networks), a short training of the network that finds the charts,
     * and a small atlas, which packs faster. */
    neuv_unwrap_options o;
    neuv_unwrap_options_init(&o);
    o.method = NEUV_METHOD_LSCM;
    o.iters = 50;
    o.resolution = 256;
    o.use_cache = 0; /* no operator cache on disk */

    neuv_atlas *atlas = NULL;
    if (neuv_atlas_create(&atlas) != NEUV_OK) return fail(atlas);
    if (neuv_atlas_add_mesh(atlas, &box) != NEUV_OK) return fail(atlas);
    if (neuv_atlas_generate(atlas, &o) != NEUV_OK) return fail(atlas);

    neuv_atlas_output out;
    if (neuv_atlas_get_output(atlas, 0, &out) != NEUV_OK) return fail(atlas);
    printf("charts: %d\n", neuv_atlas_chart_count(atlas));
    printf("output: %d vertices (split along seams), %d triangles\n", out.vertex_count, out.index_count / 3);
    printf("vertex 0: input vertex %d, uv %.4f %.4f\n", out.xref[0], out.uvs[0], out.uvs[1]);

    char *report = neuv_atlas_report_json(atlas, "box", 0, 0);
    if (!report) return fail(atlas);
    printf("%s\n", report);
    neuv_free(report);
    neuv_atlas_destroy(atlas);
    return 0;
}
