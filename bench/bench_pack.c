/* Packing benchmark (issue 5): for every UV sample in ../shared/uv-samples,
 * the file's own packing efficiency (UV area in [0,1]^2) against `neuv pack`
 * (resolution 1024, padding 2) on the same charts, and the packing time
 * (median of 3 runs). Prints a Markdown table.
 * Usage: bench_pack [SHARED_DIR] */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/pack.h"
#include "atlas/uv_charts.h"
#include "core/timer.h"
#include "mesh/clean.h"
#include "mesh/mesh.h"
#include "mesh/shapes.h"

static double uv_area_in_unit_square(const neuv_mesh *m)
{
    double a = 0;
    for (int u = 0; u < 2 * m->nuv; u++)
        if (m->uv[u] < 0 || m->uv[u] > 1) return NAN;
    for (int f = 0; f < m->nf; f++) {
        const double *p = m->uv + 2 * m->tri_uv[3 * f], *q = m->uv + 2 * m->tri_uv[3 * f + 1],
                     *r = m->uv + 2 * m->tri_uv[3 * f + 2];
        a += fabs(0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])));
    }
    return a;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static int cmp_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Many charts: every triangle of an icosphere its own chart (flattened
 * isometrically), the worst case for the number of placements. */
static neuv_mesh *one_chart_per_face(int level)
{
    neuv_mesh *s = shape_icosphere(level, 1.0);
    if (!s) return NULL;
    neuv_mesh *m = mesh_create(s->nv, s->nf, 3 * s->nf);
    if (!m) { mesh_free(s); return NULL; }
    memcpy(m->pos, s->pos, sizeof(double) * 3 * (size_t)s->nv);
    memcpy(m->tri, s->tri, sizeof(int) * 3 * (size_t)s->nf);
    for (int f = 0; f < s->nf; f++) {
        const double *a = s->pos + 3 * s->tri[3 * f], *b = s->pos + 3 * s->tri[3 * f + 1], *c = s->pos + 3 * s->tri[3 * f + 2];
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) { e1[k] = b[k] - a[k]; e2[k] = c[k] - a[k]; }
        double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        double x2 = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1;
        double y2 = sqrt(fmax(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2] - x2 * x2, 0));
        double uv[6] = {0, 0, l1, 0, x2, y2};
        memcpy(m->uv + 6 * (size_t)f, uv, sizeof uv);
        for (int k = 0; k < 3; k++) m->tri_uv[3 * f + k] = 3 * f + k;
    }
    mesh_free(s);
    return m;
}

static void bench_many_charts(int level)
{
    neuv_mesh *m = one_chart_per_face(level);
    if (!m) return;
    int *chart = malloc(sizeof(int) * (size_t)m->nf);
    int nc = uv_charts(m, chart);
    double t[3], eff = 0;
    for (int r = 0; r < 3; r++) {
        neuv_mesh *c = mesh_clone(m);
        atlas_pack_result res;
        double t0 = now_seconds();
        if (atlas_pack(c, chart, nc, NULL, NULL, &res) != NEUV_OK) res.efficiency = NAN;
        t[r] = now_seconds() - t0;
        eff = res.efficiency;
        mesh_free(c);
    }
    qsort(t, 3, sizeof *t, cmp_double);
    printf("| icosphere(%d), one chart per face | %d | %d | - | %.3f | - | %.2f |\n", level, m->nf, nc, eff, t[1]);
    free(chart);
    mesh_free(m);
}

int main(int argc, char **argv)
{
    const char *shared = argc > 1 ? argv[1] : (getenv("NEUV_SHARED") ? getenv("NEUV_SHARED") : "../shared");
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/uv-samples", shared);
    DIR *d = opendir(dir);
    if (!d) fprintf(stderr, "bench_pack: cannot open %s (UV samples left out)\n", dir);
    char *names[256];
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)) && n < 256) {
        size_t l = strlen(e->d_name);
        if (l > 4 && !strcmp(e->d_name + l - 4, ".obj")) names[n++] = strdup(e->d_name);
    }
    if (d) closedir(d);
    qsort(names, (size_t)n, sizeof *names, cmp_name);
    printf("| file | faces | charts | file's own | neuv pack | ratio | pack time (s, median of 3) |\n");
    printf("|---|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < n; i++) {
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        neuv_mesh *m = NULL;
        if (neuv_mesh_load(path, NULL, &m) != NEUV_OK || m->nuv == 0 || mesh_weld_positions(m) < 0) {
            printf("| %s | load failed: %s |\n", names[i], neuv_last_error());
            mesh_free(m);
            continue;
        }
        int *chart = malloc(sizeof(int) * (size_t)m->nf);
        int nc = uv_charts(m, chart);
        double own = uv_area_in_unit_square(m), t[3], eff = 0;
        for (int r = 0; r < 3; r++) {
            neuv_mesh *c = mesh_clone(m);
            atlas_pack_result res;
            double t0 = now_seconds();
            neuv_status st = atlas_pack(c, chart, nc, NULL, NULL, &res);
            t[r] = now_seconds() - t0;
            if (st != NEUV_OK) { fprintf(stderr, "%s: %s\n", names[i], neuv_last_error()); res.efficiency = NAN; }
            eff = res.efficiency;
            mesh_free(c);
        }
        qsort(t, 3, sizeof *t, cmp_double);
        printf("| %s | %d | %d | %.3f | %.3f | %.2f | %.2f |\n", names[i], m->nf, nc, own, eff, eff / own, t[1]);
        fflush(stdout);
        free(chart);
        mesh_free(m);
        free(names[i]);
    }
    bench_many_charts(3);
    bench_many_charts(4);
    return 0;
}
