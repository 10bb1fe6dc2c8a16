/* The packing's split trials (atlas/pack_split.h) on the charts of UV files:
 * for each file, its charts (connected UV islands) go through
 * pack_split_charts with the unwrap's defaults (1024 px, padding 2), and the
 * table gives the trials, the cuts kept, the quick packing before and after,
 * and the seconds (median of RUNS); then one full packing of the charts as
 * cut, for scale: issue 16 asks that the trials cost no more than the
 * packing they improve. OMP_NUM_THREADS sets the threads.
 * Usage: bench_pack_split [RUNS] FILE.obj... */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/pack.h"
#include "atlas/pack_split.h"
#include "atlas/uv_charts.h"
#include "core/timer.h"
#include "mesh/clean.h"
#include "mesh/mesh.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    int runs = argc > 1 ? atoi(argv[1]) : 0;
    if (runs < 1 || argc < 3) {
        fprintf(stderr, "usage: bench_pack_split RUNS FILE.obj...\n");
        return 2;
    }
    printf("| file | faces | charts | trials | cuts kept | quick packing before -> after | trials s (median of %d) | "
           "full packing s | trials / packing |\n|---|---:|---:|---:|---:|---|---:|---:|---:|\n", runs);
    for (int i = 2; i < argc; i++) {
        neuv_mesh *m = NULL;
        if (neuv_mesh_load(argv[i], NULL, &m) != NEUV_OK || m->nuv == 0 || mesh_weld_positions(m) < 0) {
            printf("| %s | load failed: %s |\n", argv[i], neuv_last_error());
            mesh_free(m);
            continue;
        }
        int *chart = malloc(sizeof(int) * (size_t)m->nf), *fc = malloc(sizeof(int) * (size_t)m->nf);
        int nc0 = uv_charts(m, chart), nc = nc0;
        double *secs = malloc(sizeof(double) * (size_t)runs);
        pack_split_options so;
        pack_split_default_options(&so);
        pack_split_report rep = {0};
        int ok = chart && fc && secs && nc0 > 0;
        for (int r = 0; ok && r < runs; r++) {
            memcpy(fc, chart, sizeof(int) * (size_t)m->nf);
            nc = nc0;
            int *parent = NULL;
            double t = now_seconds();
            ok = pack_split_charts(m, fc, &nc, &so, &parent, &rep) == NEUV_OK;
            secs[r] = now_seconds() - t;
            free(parent);
        }
        double full = 0;
        if (ok) {
            neuv_mesh *c = mesh_clone(m);
            atlas_pack_options po;
            atlas_pack_options_default(&po);
            double t = now_seconds();
            ok = c && atlas_pack(c, fc, nc, &po, NULL, NULL) == NEUV_OK;
            full = now_seconds() - t;
            mesh_free(c);
        }
        if (!ok) {
            printf("| %s | failed: %s |\n", argv[i], neuv_last_error());
        } else {
            qsort(secs, (size_t)runs, sizeof *secs, cmp_double);
            double med = secs[runs / 2];
            const char *name = strrchr(argv[i], '/');
            printf("| %s | %d | %d | %d | %d | %.4f -> %.4f | %.3f | %.3f | %.2f |\n", name ? name + 1 : argv[i], m->nf,
                   nc0, rep.trials, rep.splits, rep.efficiency_before, rep.efficiency_after, med, full,
                   full > 0 ? med / full : 0);
        }
        fflush(stdout);
        free(chart); free(fc); free(secs);
        mesh_free(m);
    }
    return 0;
}
