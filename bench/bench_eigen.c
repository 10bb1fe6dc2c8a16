/* Eigenpair benchmark: k = 64 smallest generalized eigenpairs L φ = λ M φ of
 * a mesh, as operators_compute does them (CHOLMOD factor + ARPACK
 * shift-invert), median of several runs.
 *
 * usage: bench_eigen MESH [--runs N] [--k K] [--out DIR]
 * With --out, writes DIR/L.mtx and DIR/M.mtx (Matrix Market, full digits)
 * and DIR/evals.txt so bench/eigen_vs_scipy.py can run SciPy on the very
 * same matrices. Prints one line "RESULT key=value ..." for scripts. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "core/timer.h"
#include "geometry/cotan_laplacian.h"
#include "geometry/eigenbasis.h"
#include "geometry/lumped_mass.h"
#include "mesh/clean.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int write_mtx(const char *path, const sparse_matrix *a, const double *diag, int n)
{
    FILE *fp = fopen(path, "w");
    if (!fp) return -1;
    fprintf(fp, "%%%%MatrixMarket matrix coordinate real general\n");
    if (a) {
        fprintf(fp, "%d %d %zu\n", a->rows, a->cols, sparse_nnz(a));
        for (int r = 0; r < a->rows; r++)
            for (int p = a->row_start[r]; p < a->row_start[r + 1]; p++)
                fprintf(fp, "%d %d %.17g\n", r + 1, a->col[p] + 1, a->val[p]);
    } else {
        fprintf(fp, "%d %d %d\n", n, n, n);
        for (int i = 0; i < n; i++) fprintf(fp, "%d %d %.17g\n", i + 1, i + 1, diag[i]);
    }
    return fclose(fp);
}

int main(int argc, char **argv)
{
    const char *mesh_path = NULL, *out = NULL;
    int runs = 3, k = 64;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--runs") && i + 1 < argc) runs = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--k") && i + 1 < argc) k = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--out") && i + 1 < argc) out = argv[++i];
        else mesh_path = argv[i];
    }
    if (!mesh_path || runs < 1 || k < 1) {
        fprintf(stderr, "usage: bench_eigen MESH [--runs N] [--k K] [--out DIR]\n");
        return 2;
    }
    neuv_mesh *m = NULL;
    if (neuv_mesh_load(mesh_path, NULL, &m) != NEUV_OK || mesh_clean(m, NULL, NULL) != NEUV_OK) {
        fprintf(stderr, "bench_eigen: %s: %s\n", mesh_path, neuv_last_error());
        return 2;
    }
    sparse_matrix L;
    double *mass = malloc((size_t)m->nv * sizeof *mass);
    double *evals = malloc((size_t)k * sizeof *evals);
    double *evecs = malloc((size_t)m->nv * k * sizeof *evecs);
    double *secs = malloc((size_t)runs * sizeof *secs);
    if (!mass || !evals || !evecs || !secs || cotan_laplacian(m, &L) != NEUV_OK) {
        fprintf(stderr, "bench_eigen: out of memory\n");
        return 1;
    }
    lumped_mass(m, mass);
    eigenbasis_info info;
    for (int r = 0; r < runs; r++) {
        double t0 = now_seconds();
        if (eigenbasis(&L, mass, k, evals, evecs, &info) != NEUV_OK) {
            fprintf(stderr, "bench_eigen: %s\n", neuv_last_error());
            return 1;
        }
        secs[r] = now_seconds() - t0;
        fprintf(stderr, "run %d: %.3f s (factor %.3f, eigen %.3f of which solves %.3f, %d restarts, %d solves)\n", r,
                secs[r], info.factor_seconds, info.solve_seconds, info.op_seconds, info.restarts, info.op_applies);
    }
    qsort(secs, (size_t)runs, sizeof *secs, cmp_double);
    double median = runs % 2 ? secs[runs / 2] : 0.5 * (secs[runs / 2 - 1] + secs[runs / 2]);
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    if (out) {
        char p[4096];
        snprintf(p, sizeof p, "%s/L.mtx", out);
        int bad = write_mtx(p, &L, NULL, 0);
        snprintf(p, sizeof p, "%s/M.mtx", out);
        bad |= write_mtx(p, NULL, mass, m->nv);
        snprintf(p, sizeof p, "%s/evals.txt", out);
        FILE *fp = fopen(p, "w");
        if (fp) {
            for (int a = 0; a < k; a++) fprintf(fp, "%.17g\n", evals[a]);
            bad |= fclose(fp);
        }
        if (bad || !fp) { fprintf(stderr, "bench_eigen: cannot write to %s\n", out); return 1; }
    }
    printf("RESULT vertices=%d k=%d runs=%d median_s=%.4f min_s=%.4f sigma=%.17g maxrss_kb=%ld orth=%.3g\n", m->nv, k,
           runs, median, secs[0], info.sigma, ru.ru_maxrss, info.orth_error);
    sparse_free(&L);
    free(mass); free(evals); free(evecs); free(secs);
    mesh_free(m);
    return 0;
}
