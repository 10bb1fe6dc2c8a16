/* Heat-method geodesics: set-up (three factorizations) and one single-source
 * query on stanford-bunny.obj and armadillo.obj, medians of 3, against a
 * reference measured in the same run: Dijkstra on the edge graph from the
 * same source (the cheap, less accurate alternative). Peak memory from getrusage.
 * Usage: bench_heat [MESH...]   (default: the two meshes in ../shared/meshes) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "core/timer.h"
#include "geometry/heat_geodesics.h"
#include "mesh/clean.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median3(double *t) { qsort(t, 3, sizeof *t, cmp_double); return t[1]; }

/* Dijkstra over mesh edges with a binary heap (lazy deletion). */
static void dijkstra(const neuv_mesh *m, int src, double *d)
{
    int nv = m->nv;
    int *deg = calloc((size_t)nv + 1, sizeof(int)), *adj = malloc(sizeof(int) * 6 * (size_t)m->nf);
    for (int f = 0; f < m->nf; f++) for (int c = 0; c < 3; c++) deg[m->tri[3 * f + c] + 1] += 2;
    for (int v = 0; v < nv; v++) deg[v + 1] += deg[v];
    int *fill = calloc((size_t)nv, sizeof(int));
    for (int f = 0; f < m->nf; f++)
        for (int c = 0; c < 3; c++) {
            int a = m->tri[3 * f + c], b = m->tri[3 * f + (c + 1) % 3];
            adj[deg[a] + fill[a]++] = b;
            adj[deg[b] + fill[b]++] = a;
        }
    size_t cap = 6 * (size_t)m->nf + 1, n = 0;
    double *hk = malloc(sizeof(double) * cap);
    int *hv = malloc(sizeof(int) * cap);
    for (int v = 0; v < nv; v++) d[v] = INFINITY;
    d[src] = 0; hk[0] = 0; hv[0] = src; n = 1;
    while (n) {
        double k = hk[0]; int v = hv[0];
        n--; hk[0] = hk[n]; hv[0] = hv[n];
        for (size_t i = 0;;) {
            size_t l = 2 * i + 1, r = l + 1, s = i;
            if (l < n && hk[l] < hk[s]) s = l;
            if (r < n && hk[r] < hk[s]) s = r;
            if (s == i) break;
            double tk = hk[i]; hk[i] = hk[s]; hk[s] = tk;
            int tv = hv[i]; hv[i] = hv[s]; hv[s] = tv;
            i = s;
        }
        if (k > d[v]) continue;
        for (int p = deg[v]; p < deg[v + 1]; p++) {
            int w = adj[p];
            const double *a = m->pos + 3 * v, *b = m->pos + 3 * w;
            double nd = k + sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
            if (nd < d[w] && n < cap) {
                d[w] = nd;
                size_t i = n++;
                hk[i] = nd; hv[i] = w;
                while (i > 0 && hk[(i - 1) / 2] > hk[i]) {
                    size_t pa = (i - 1) / 2;
                    double tk = hk[i]; hk[i] = hk[pa]; hk[pa] = tk;
                    int tv = hv[i]; hv[i] = hv[pa]; hv[pa] = tv;
                    i = pa;
                }
            }
        }
    }
    free(deg); free(adj); free(fill); free(hk); free(hv);
}

static long peak_rss_mib(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss / 1024;
}

static int bench(const char *path)
{
    neuv_mesh *m = NULL;
    mesh_clean_report rep;
    if (neuv_mesh_load(path, NULL, &m) != NEUV_OK || mesh_clean(m, NULL, &rep) != NEUV_OK) {
        fprintf(stderr, "bench_heat: %s: %s\n", path, neuv_last_error());
        mesh_free(m);
        return 1;
    }
    double t_setup[3], t_solve[3], t_dijk[3];
    double *d = malloc(sizeof(double) * m->nv), *ref = malloc(sizeof(double) * m->nv);
    heat_geodesics *g = NULL;
    for (int r = 0; r < 3; r++) {
        heat_geodesics_free(g);
        g = NULL;
        double t0 = now_seconds();
        if (heat_geodesics_create(m, 1.0, &g) != NEUV_OK) {
            fprintf(stderr, "bench_heat: %s: %s\n", path, neuv_last_error());
            return 1;
        }
        t_setup[r] = now_seconds() - t0;
    }
    for (int r = 0; r < 3; r++) {
        double t0 = now_seconds();
        heat_geodesics_from_vertex(g, 0, d);
        t_solve[r] = now_seconds() - t0;
        t0 = now_seconds();
        dijkstra(m, 0, ref);
        t_dijk[r] = now_seconds() - t0;
    }
    /* Block of 64 sources: the per-source cost when batched. */
    int src[64];
    for (int k = 0; k < 64; k++) src[k] = (int)(((long)k * 7919) % m->nv);
    double *blk = malloc(sizeof(double) * (size_t)m->nv * 64);
    double t0 = now_seconds();
    heat_geodesics_batch(g, src, 64, blk);
    double t_block = now_seconds() - t0;
    double diff = 0; int n = 0;
    for (int v = 0; v < m->nv; v++)
        if (isfinite(ref[v]) && ref[v] > 0) { diff += (ref[v] - d[v]) / ref[v]; n++; }
    double s = median3(t_setup), q = median3(t_solve), dj = median3(t_dijk);
    printf("%-20s %7d V  setup %.3f s  solve %.4f s  (64-source block %.3f s = %.4f s/source)  "
           "dijkstra %.4f s  solve/dijkstra %.2f  dijkstra longer by %.1f%% on average  peak RSS %ld MiB\n",
           path, m->nv, s, q, t_block, t_block / 64, dj, q / dj, 100 * diff / n, peak_rss_mib());
    free(d); free(ref); free(blk);
    heat_geodesics_free(g);
    mesh_free(m);
    return 0;
}

int main(int argc, char **argv)
{
    const char *defaults[] = {"../shared/meshes/stanford-bunny.obj", "../shared/meshes/armadillo.obj"};
    char buf[2][4096];
    const char *root = getenv("NEUV_SHARED");
    if (root) {
        snprintf(buf[0], sizeof buf[0], "%s/meshes/stanford-bunny.obj", root);
        snprintf(buf[1], sizeof buf[1], "%s/meshes/armadillo.obj", root);
        defaults[0] = buf[0]; defaults[1] = buf[1];
    }
    int rc = 0;
    if (argc > 1) for (int i = 1; i < argc; i++) rc |= bench(argv[i]);
    else for (int i = 0; i < 2; i++) rc |= bench(defaults[i]);
    return rc;
}
