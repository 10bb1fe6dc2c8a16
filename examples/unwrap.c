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

/* Writes the arrays as an OBJ (1-based indices). 0 on success, else -1
 * with errno set. */
static int write_obj(const char *path, float positions[][3], int n_vertices,
                     int triangles[][3], int n_faces)
{
    FILE *fp = fopen(path, "w");
    if (!fp) return -1;
    for (int v = 0; v < n_vertices; v++)
        fprintf(fp, "v %.9g %.9g %.9g\n", (double)positions[v][0], (double)positions[v][1],
                (double)positions[v][2]);
    for (int f = 0; f < n_faces; f++)
        fprintf(fp, "f %d %d %d\n", triangles[f][0] + 1, triangles[f][1] + 1, triangles[f][2] + 1);
    int failed = ferror(fp);
    if (fclose(fp) != 0 || failed) return -1;
    return 0;
}

/* The box as a neuv_mesh, read back from a temporary OBJ. NULL, with one
 * line on stderr, on failure. */
static neuv_mesh *load_box(void)
{
    float positions[N_VERTICES][3];
    int triangles[N_FACES][3];
    make_box(positions, triangles);

    char dir[] = "/tmp/neuv-example-XXXXXX", path[sizeof dir + 16];
    if (!mkdtemp(dir)) {
        fprintf(stderr, "unwrap: error: %s: %s\n", dir, strerror(errno));
        return NULL;
    }
    snprintf(path, sizeof path, "%s/box.obj", dir);
    neuv_mesh *mesh = NULL;
    if (write_obj(path, positions, N_VERTICES, triangles, N_FACES) != 0)
        fprintf(stderr, "unwrap: error: %s: %s\n", path, strerror(errno));
    else if (neuv_mesh_load(path, &mesh) != NEUV_OK)
        fprintf(stderr, "unwrap: error: %s\n", neuv_last_error());
    remove(path);
    rmdir(dir);
    return mesh;
}

int main(void)
{
    neuv_mesh *mesh = load_box();
    if (!mesh) return 2;
    printf("neuv %s: box with %d vertices, %d faces\n", neuv_version(),
           neuv_mesh_vertex_count(mesh), neuv_mesh_face_count(mesh));

    /* Quick settings, a second or two: least squares conformal maps on the
     * charts (the default, NEUV_METHOD_NEURAL, trains the paper's
     * parameterization networks), a short training of the network that
     * finds the charts, and a small atlas, which packs faster. */
    neuv_unwrap_options o;
    neuv_unwrap_options_default(&o);
    o.method = NEUV_METHOD_LSCM;
    o.iters = 50;
    o.resolution = 256;
    o.use_cache = 0; /* no operator cache on disk */

    neuv_unwrap_result *result = NULL;
    neuv_status s = neuv_unwrap(mesh, &o, &result);
    neuv_mesh_free(mesh);
    if (s != NEUV_OK) {
        fprintf(stderr, "unwrap: error: %s\n", neuv_last_error());
        return 2;
    }
    printf("charts: %d\n", neuv_unwrap_chart_count(result));
    char *report = neuv_unwrap_report_json(result, "box", 0, 0);
    if (!report) {
        fprintf(stderr, "unwrap: error: %s\n", neuv_last_error());
        neuv_unwrap_result_free(result);
        return 2;
    }
    printf("%s\n", report);
    free(report);
    neuv_unwrap_result_free(result);
    return 0;
}
