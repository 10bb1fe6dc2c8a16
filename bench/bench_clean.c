/* Cleaning speed: mesh_clean on a face soup (every face with its own three
 * vertices, faces shuffled, a third flipped) of an icosphere, against a
 * reference measured in the same run: qsort of the 3F corner vertex ids
 * (an O(F log F) pass over the same data). Prints medians of several runs.
 * usage: bench_clean [icosphere level, default 8 = 1.3M faces] [runs, default 3]
 *                    [shuffle faces: 1 (default, worst case for caches) or 0] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/timer.h"
#include "mesh/clean.h"
#include "mesh/shapes.h"

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static neuv_mesh *soup_of(const neuv_mesh *s, rng *r, int shuffle)
{
    neuv_mesh *m = mesh_create(3 * s->nf, s->nf, 0);
    if (!m) return NULL;
    int *order = malloc(sizeof(int) * (size_t)s->nf);
    if (!order) { mesh_free(m); return NULL; }
    for (int f = 0; f < s->nf; f++) order[f] = f;
    for (int f = s->nf - 1; f > 0 && shuffle; f--) { int j = rng_below(r, f + 1), t = order[f]; order[f] = order[j]; order[j] = t; }
    for (int f = 0; f < s->nf; f++) {
        int g = order[f], flip = rng_uniform(r) < 0.33;
        for (int k = 0; k < 3; k++) {
            int src = s->tri[3 * g + (flip && k ? 3 - k : k)];
            memcpy(m->pos + 3 * (3 * f + k), s->pos + 3 * src, sizeof(double) * 3);
            m->tri[3 * f + k] = 3 * f + k;
        }
    }
    free(order);
    return m;
}

int main(int argc, char **argv)
{
    int level = argc > 1 ? atoi(argv[1]) : 8, runs = argc > 2 ? atoi(argv[2]) : 3;
    if (runs < 1 || runs > 50) runs = 3;
    neuv_mesh *s = shape_icosphere(level, 1.0);
    if (!s) { fprintf(stderr, "bench_clean: cannot build icosphere level %d\n", level); return 1; }
    rng r;
    rng_seed(&r, 1);
    int shuffle = argc > 3 ? atoi(argv[3]) : 1;
    neuv_mesh *soup = soup_of(s, &r, shuffle);
    if (!soup) return 1;
    double *t_clean = malloc(sizeof(double) * (size_t)runs), *t_sort = malloc(sizeof(double) * (size_t)runs);
    int *keys = malloc(sizeof(int) * 3 * (size_t)s->nf);
    mesh_clean_report rep;
    for (int i = 0; i < runs; i++) {
        neuv_mesh *m = mesh_clone(soup);
        double t0 = now_seconds();
        if (mesh_clean(m, NULL, &rep) != NEUV_OK) { fprintf(stderr, "clean failed\n"); return 1; }
        t_clean[i] = now_seconds() - t0;
        if (m->nv != s->nv || m->nf != s->nf) { fprintf(stderr, "wrong result\n"); return 1; }
        mesh_free(m);
        for (int c = 0; c < 3 * s->nf; c++) keys[c] = s->tri[(c * 7919LL) % (3LL * s->nf)];
        t0 = now_seconds();
        qsort(keys, 3 * (size_t)s->nf, sizeof(int), cmp_int);
        t_sort[i] = now_seconds() - t0;
    }
    qsort(t_clean, (size_t)runs, sizeof(double), cmp_double);
    qsort(t_sort, (size_t)runs, sizeof(double), cmp_double);
    double c = t_clean[runs / 2], q = t_sort[runs / 2];
    printf("bench_clean: %d faces soup (%d vertices, %s) -> %d vertices; welded %d, flipped %d\n",
           soup->nf, soup->nv, shuffle ? "faces shuffled" : "faces in order", s->nv,
           rep.welded_vertices, rep.flipped_faces);
    printf("  mesh_clean        %8.3f s  (median of %d)\n", c, runs);
    printf("  qsort 3F ints     %8.3f s  (reference)\n", q);
    printf("  ratio             %8.2f x the reference\n", c / q);
    free(t_clean); free(t_sort); free(keys);
    mesh_free(soup); mesh_free(s);
    return 0;
}
