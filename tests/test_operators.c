/* Geometry operators: Laplacian, mass, eigenbasis, frames, gradients, HKS. */
#include "check.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#include "core/rng.h"
#include "geometry/cholesky.h"
#include "geometry/cotan_laplacian.h"
#include "geometry/eigenbasis.h"
#include "geometry/lumped_mass.h"
#include "geometry/operators.h"
#include "geometry/spatial_gradient.h"
#include "geometry/tangent_frames.h"
#include "mesh/shapes.h"

/* Level 5: 10242 vertices, the acceptance test of issue 3. */
#ifndef SPHERE_LEVEL
#define SPHERE_LEVEL 5
#endif

static double max_m_orth_error(const operators *o)
{
    double err = 0.0;
    for (int a = 0; a < o->k; a++)
        for (int b = a; b < o->k; b++) {
            double g = 0.0;
            for (int i = 0; i < o->nv; i++) g += o->mass[i] * o->evecs[(size_t)i * o->k + a] * o->evecs[(size_t)i * o->k + b];
            err = fmax(err, fabs(g - (a == b)));
        }
    return err;
}

/* max_a ||L φ_a − λ_a M φ_a||_∞ / (1 + |λ_a|) max M */
static double max_eigen_residual(const operators *o)
{
    double *phi = malloc((size_t)o->nv * sizeof *phi), *y = malloc((size_t)o->nv * sizeof *y);
    double mmax = 0.0, res = 0.0;
    for (int i = 0; i < o->nv; i++) mmax = fmax(mmax, o->mass[i]);
    for (int a = 0; a < o->k; a++) {
        for (int i = 0; i < o->nv; i++) phi[i] = o->evecs[(size_t)i * o->k + a];
        sparse_matvec(&o->L, phi, y);
        for (int i = 0; i < o->nv; i++)
            res = fmax(res, fabs(y[i] - o->evals[a] * o->mass[i] * phi[i]) / ((1 + fabs(o->evals[a])) * mmax));
    }
    free(phi);
    free(y);
    return res;
}

static void check_laplacian_and_mass(const neuv_mesh *m, const operators *o)
{
    const sparse_matrix *L = &o->L;
    double asym = 0.0, rowsum = 0.0, scale = 0.0;
    int diag_ok = 1;
    for (int r = 0; r < L->rows; r++) {
        double s = 0.0;
        for (int p = L->row_start[r]; p < L->row_start[r + 1]; p++) {
            int c = L->col[p];
            s += L->val[p];
            scale = fmax(scale, fabs(L->val[p]));
            /* find (c, r) */
            double t = 0.0;
            for (int q = L->row_start[c]; q < L->row_start[c + 1]; q++)
                if (L->col[q] == r) t = L->val[q];
            asym = fmax(asym, fabs(t - L->val[p]));
            if (c == r && !(L->val[p] > 0)) diag_ok = 0;
        }
        rowsum = fmax(rowsum, fabs(s));
    }
    CHECK(asym <= 1e-14 * scale);
    CHECK(rowsum <= 1e-12 * scale);
    double msum = 0.0;
    int all_positive = 1;
    for (int i = 0; i < o->nv; i++) { msum += o->mass[i]; if (!(o->mass[i] > 0)) all_positive = 0; }
    CHECK(all_positive);
    CHECK_NEAR(msum, mesh_total_area(m), 1e-12 * msum);
    CHECK(diag_ok);
}

static void test_sphere(void)
{
    neuv_mesh *m = shape_icosphere(SPHERE_LEVEL, 1.0);
    CHECK(m != NULL);
    if (!m) return;
    operators o;
    operators_params p = operators_default_params();
    neuv_status s = operators_compute(m, &p, &o);
    CHECK_INT(s, NEUV_OK);
    if (s) { fprintf(stderr, "%s\n", neuv_last_error()); mesh_free(m); return; }
    printf("sphere %d vertices: laplacian %.3fs factor %.3fs eigen %.3fs gradients %.3fs hks %.3fs\n", o.nv,
           o.seconds.laplacian, o.seconds.factor, o.seconds.eigen, o.seconds.gradients, o.seconds.hks);
    CHECK_INT(o.k, 64);
    check_laplacian_and_mass(m, &o);
    /* Area of the inscribed polyhedron approaches 4π from below. */
    double area = 0.0;
    for (int i = 0; i < o.nv; i++) area += o.mass[i];
    CHECK(area < 4 * M_PI && area > 0.99 * 4 * M_PI);

    /* Spherical harmonics: λ = l(l+1) with multiplicity 2l+1. */
    CHECK(fabs(o.evals[0]) < 1e-8);
    int idx = 1;
    for (int l = 1; idx <= 16; l++)
        for (int mlt = 0; mlt < 2 * l + 1 && idx <= 16; mlt++, idx++) {
            double want = l * (l + 1.0);
            CHECK(fabs(o.evals[idx] - want) <= 0.01 * want);
            if (fabs(o.evals[idx] - want) > 0.01 * want)
                fprintf(stderr, "eigenvalue %d = %.6f, expected %.0f\n", idx, o.evals[idx], want);
        }
    for (int a = 1; a < o.k; a++) CHECK(o.evals[a] >= o.evals[a - 1]);
    double orth = max_m_orth_error(&o);
    printf("M-orthonormality error %.3g, residual %.3g\n", orth, max_eigen_residual(&o));
    CHECK(orth <= 1e-8);
    CHECK(max_eigen_residual(&o) <= 1e-8);
    /* Constant eigenvector: φ_0 = 1/sqrt(area) everywhere. */
    CHECK_NEAR(o.evecs[0], 1.0 / sqrt(area), 1e-8);
    CHECK_NEAR(o.evecs[(size_t)(o.nv - 1) * o.k], 1.0 / sqrt(area), 1e-8);

    /* Frames: orthonormal, right-handed, normal = radial direction. */
    double ferr = 0.0, nerr = 0.0;
    for (int i = 0; i < o.nv; i++) {
        const double *f = o.frames + 9 * (size_t)i;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                double d = f[3 * a] * f[3 * b] + f[3 * a + 1] * f[3 * b + 1] + f[3 * a + 2] * f[3 * b + 2];
                ferr = fmax(ferr, fabs(d - (a == b)));
            }
        double c[3] = {f[1] * f[5] - f[2] * f[4], f[2] * f[3] - f[0] * f[5], f[0] * f[4] - f[1] * f[3]};
        for (int d = 0; d < 3; d++) {
            ferr = fmax(ferr, fabs(c[d] - f[6 + d]));
            nerr = fmax(nerr, fabs(f[6 + d] - m->pos[3 * i + d]));
        }
    }
    CHECK(ferr < 1e-12);
    printf("max normal deviation from radial %.3g\n", nerr);
    CHECK(nerr < 1e-2);

    /* HKS: positive, strictly decreasing in t at every vertex (the l > 0
     * terms decay), times ascending per the 4 ln10 / λ rule. */
    CHECK_INT(o.n_hks, 16);
    CHECK_NEAR(o.hks_times[0], 4 * log(10.0) / o.evals[o.k - 1], 1e-12 * o.hks_times[0]);
    CHECK_NEAR(o.hks_times[15], 4 * log(10.0) / o.evals[1], 1e-12 * o.hks_times[15]);
    int pos = 1, dec = 1;
    for (int i = 0; i < o.nv; i++)
        for (int j = 0; j < 16; j++) {
            double h = o.hks[(size_t)i * 16 + j];
            if (!(h > 0)) pos = 0;
            if (j > 0 && !(h < o.hks[(size_t)i * 16 + j - 1])) dec = 0;
        }
    CHECK(pos);
    CHECK(dec);
    /* Large t: only φ_0 survives, area · φ_0² = 1; the sphere is homogeneous,
     * so every vertex is near the same value at every time. */
    CHECK(fabs(o.hks[15] - 1.0) < 0.2);

    /* Tangent gradient of f = z on the unit sphere: (e_z − z n) projected. */
    double *f = malloc((size_t)o.nv * sizeof *f), *gx = malloc((size_t)o.nv * sizeof *gx), *gy = malloc((size_t)o.nv * sizeof *gy);
    for (int i = 0; i < o.nv; i++) f[i] = m->pos[3 * i + 2];
    sparse_matvec(&o.grad_x, f, gx);
    sparse_matvec(&o.grad_y, f, gy);
    double gerr = 0.0;
    for (int i = 0; i < o.nv; i++) {
        const double *fr = o.frames + 9 * (size_t)i;
        gerr = fmax(gerr, fabs(gx[i] - fr[2]));
        gerr = fmax(gerr, fabs(gy[i] - fr[5]));
    }
    CHECK(gerr < 0.05);
    free(f); free(gx); free(gy);
    operators_free(&o);
    mesh_free(m);
}

/* A flat grid, rotated and shifted so the plane is not z = 0. */
static void test_gradient_linear(void)
{
    neuv_mesh *m = shape_grid(12, 9, 1.2, 0.7, 0);
    CHECK(m != NULL);
    if (!m) return;
    /* Jitter interior vertices so the one-rings are irregular. */
    rng r;
    rng_seed(&r, 7);
    for (int j = 1; j < 9; j++)
        for (int i = 1; i < 12; i++) {
            int v = j * 13 + i;
            m->pos[3 * v] += 0.02 * (rng_uniform(&r) - 0.5);
            m->pos[3 * v + 1] += 0.02 * (rng_uniform(&r) - 0.5);
        }
    double R[3][3] = {{0.36, 0.48, -0.8}, {-0.8, 0.6, 0.0}, {0.48, 0.64, 0.6}};
    for (int v = 0; v < m->nv; v++) {
        double x[3] = {m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]};
        for (int d = 0; d < 3; d++) m->pos[3 * v + d] = R[d][0] * x[0] + R[d][1] * x[1] + R[d][2] * x[2] + 0.3 * d;
    }
    double *frames = malloc((size_t)m->nv * 9 * sizeof *frames);
    tangent_frames(m, frames);
    sparse_matrix gx, gy;
    CHECK_INT(spatial_gradient(m, frames, &gx, &gy), NEUV_OK);
    /* f = a · x: its gradient is a projected onto the plane (a has a normal part too). */
    double a[3] = {3.0, -2.0, 0.5};
    double *f = malloc((size_t)m->nv * sizeof *f), *ux = malloc((size_t)m->nv * sizeof *ux), *uy = malloc((size_t)m->nv * sizeof *uy);
    for (int v = 0; v < m->nv; v++) f[v] = a[0] * m->pos[3 * v] + a[1] * m->pos[3 * v + 1] + a[2] * m->pos[3 * v + 2] + 4.0;
    sparse_matvec(&gx, f, ux);
    sparse_matvec(&gy, f, uy);
    double err = 0.0, nrm = 0.0;
    int interior = 0;
    for (int j = 1; j < 9; j++)
        for (int i = 1; i < 12; i++) {
            int v = j * 13 + i;
            const double *fr = frames + 9 * (size_t)v;
            for (int d = 0; d < 3; d++) nrm = fmax(nrm, fabs(fr[6 + d] - R[d][2]));
            /* Reconstruct the 3D gradient and compare with the tangential part of a. */
            double an = a[0] * fr[6] + a[1] * fr[7] + a[2] * fr[8];
            for (int d = 0; d < 3; d++) {
                double g = ux[v] * fr[d] + uy[v] * fr[3 + d];
                err = fmax(err, fabs(g - (a[d] - an * fr[6 + d])));
            }
            interior++;
        }
    CHECK_INT(interior, 88);
    CHECK(nrm < 1e-12);
    CHECK(err < 1e-9);
    printf("linear gradient error %.3g\n", err);
    /* A constant has zero gradient everywhere, boundary included. */
    for (int v = 0; v < m->nv; v++) f[v] = 2.5;
    sparse_matvec(&gx, f, ux);
    sparse_matvec(&gy, f, uy);
    double cerr = 0.0;
    for (int v = 0; v < m->nv; v++) cerr = fmax(cerr, fabs(ux[v]) + fabs(uy[v]));
    CHECK(cerr < 1e-9);
    free(f); free(ux); free(uy); free(frames);
    sparse_free(&gx);
    sparse_free(&gy);
    mesh_free(m);
}

/* Two disjoint spheres: two zero eigenvalues, each eigenvector of the
 * null space constant on each component. Large enough for the ARPACK path. */
static void test_two_components(void)
{
    neuv_mesh *a = shape_icosphere(3, 1.0), *b = shape_icosphere(3, 0.5);
    CHECK(a && b);
    if (!a || !b) { mesh_free(a); mesh_free(b); return; }
    neuv_mesh *m = mesh_create(a->nv + b->nv, a->nf + b->nf, 0);
    memcpy(m->pos, a->pos, sizeof(double) * 3 * a->nv);
    for (int v = 0; v < b->nv; v++) {
        m->pos[3 * (a->nv + v)] = b->pos[3 * v] + 3.0;
        m->pos[3 * (a->nv + v) + 1] = b->pos[3 * v + 1];
        m->pos[3 * (a->nv + v) + 2] = b->pos[3 * v + 2];
    }
    memcpy(m->tri, a->tri, sizeof(int) * 3 * a->nf);
    for (int i = 0; i < 3 * b->nf; i++) m->tri[3 * a->nf + i] = b->tri[i] + a->nv;
    operators o;
    operators_params p = {20, 4};
    CHECK_INT(operators_compute(m, &p, &o), NEUV_OK);
    CHECK_INT(o.k, 20);
    CHECK(fabs(o.evals[0]) < 1e-8 && fabs(o.evals[1]) < 1e-8);
    /* Next: l = 1 on the unit sphere (≈2, ×3), then the small sphere's
     * l = 1 (≈ 2 / 0.5² = 8, ×3). */
    for (int i = 2; i < 5; i++) CHECK(fabs(o.evals[i] - 2.0) < 0.05);
    CHECK(o.evals[5] > 5.5);
    for (int i = 5; i < 8; i++) CHECK(fabs(o.evals[i] - 6.0) < 0.15); /* l = 2 on the unit sphere */
    CHECK(max_m_orth_error(&o) <= 1e-8);
    CHECK(max_eigen_residual(&o) <= 1e-8);
    /* Null-space vectors are piecewise constant. */
    for (int z = 0; z < 2; z++) {
        double spread_a = 0.0, spread_b = 0.0;
        for (int v = 1; v < a->nv; v++) spread_a = fmax(spread_a, fabs(o.evecs[(size_t)v * o.k + z] - o.evecs[z]));
        for (int v = a->nv + 1; v < m->nv; v++)
            spread_b = fmax(spread_b, fabs(o.evecs[(size_t)v * o.k + z] - o.evecs[(size_t)a->nv * o.k + z]));
        CHECK(spread_a < 1e-6 && spread_b < 1e-6);
    }
    operators_free(&o);
    mesh_free(a); mesh_free(b); mesh_free(m);
}

/* Six disjoint spheres of different radii (one large enough for ARPACK):
 * six zero eigenvalues, then l = 1 of the largest sphere. */
static void test_many_components(void)
{
    const double radius[6] = {1.0, 0.5, 0.4, 0.3, 0.25, 0.2};
    neuv_mesh *part[6];
    int nv = 0, nf = 0;
    for (int c = 0; c < 6; c++) {
        part[c] = shape_icosphere(c == 0 ? 3 : 1, radius[c]);
        nv += part[c]->nv;
        nf += part[c]->nf;
    }
    neuv_mesh *m = mesh_create(nv, nf, 0);
    int v0 = 0, f0 = 0;
    for (int c = 0; c < 6; c++) {
        for (int v = 0; v < part[c]->nv; v++)
            for (int d = 0; d < 3; d++) m->pos[3 * (v0 + v) + d] = part[c]->pos[3 * v + d] + (d == 0 ? 3.0 * c : 0.0);
        for (int i = 0; i < 3 * part[c]->nf; i++) m->tri[3 * f0 + i] = part[c]->tri[i] + v0;
        v0 += part[c]->nv;
        f0 += part[c]->nf;
    }
    operators o;
    operators_params p = {16, 4};
    CHECK_INT(operators_compute(m, &p, &o), NEUV_OK);
    for (int i = 0; i < 6; i++) CHECK(fabs(o.evals[i]) < 1e-8);
    for (int i = 6; i < 9; i++) CHECK(fabs(o.evals[i] - 2.0) < 0.05);
    CHECK(o.evals[9] > 5.0);
    CHECK(max_m_orth_error(&o) <= 1e-8);
    CHECK(max_eigen_residual(&o) <= 1e-8);
    /* Each null vector is constant on one sphere and zero elsewhere. */
    for (int a = 0; a < 6; a++) {
        int nonzero_parts = 0;
        v0 = 0;
        for (int c = 0; c < 6; c++) {
            double lo = INFINITY, hi = -INFINITY;
            for (int v = v0; v < v0 + part[c]->nv; v++) {
                lo = fmin(lo, o.evecs[(size_t)v * o.k + a]);
                hi = fmax(hi, o.evecs[(size_t)v * o.k + a]);
            }
            CHECK(hi - lo < 1e-8);
            if (fabs(hi) > 1e-8) nonzero_parts++;
            v0 += part[c]->nv;
        }
        CHECK_INT(nonzero_parts, 1);
    }
    operators_free(&o);
    for (int c = 0; c < 6; c++) mesh_free(part[c]);
    mesh_free(m);
}

/* Tiny meshes: k is clamped to #V and the dense path gives all eigenpairs. */
static void test_tiny(void)
{
    neuv_mesh *m = mesh_create(4, 4, 0);
    double P[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
    int T[12] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
    memcpy(m->pos, P, sizeof P);
    memcpy(m->tri, T, sizeof T);
    operators o;
    CHECK_INT(operators_compute(m, NULL, &o), NEUV_OK);
    CHECK_INT(o.k, 4);
    CHECK(fabs(o.evals[0]) < 1e-12);
    /* Regular tetrahedron: L is symmetric under all vertex permutations, so the
     * three nonzero eigenvalues coincide. */
    CHECK_NEAR(o.evals[1], o.evals[3], 1e-9 * o.evals[3]);
    CHECK(o.evals[1] > 0);
    CHECK(max_m_orth_error(&o) <= 1e-10);
    CHECK(max_eigen_residual(&o) <= 1e-10);
    operators_free(&o);

    /* k larger than the ARPACK path allows for 162 vertices: dense, all 64 computed. */
    neuv_mesh *s = shape_icosphere(2, 1.0);
    operators_params p = {64, 8};
    CHECK_INT(operators_compute(s, &p, &o), NEUV_OK);
    CHECK_INT(o.k, 64);
    for (int i = 1; i < 4; i++) CHECK(fabs(o.evals[i] - 2.0) < 0.05);
    CHECK(max_m_orth_error(&o) <= 1e-10);
    CHECK(max_eigen_residual(&o) <= 1e-10);
    operators_free(&o);
    mesh_free(s);
    mesh_free(m);
}

static void test_bad_input(void)
{
    neuv_mesh *m = shape_icosphere(1, 1.0);
    operators o;
    /* An unreferenced vertex has zero mass: refused, not a crash. */
    neuv_mesh *u = mesh_create(m->nv + 1, m->nf, 0);
    memcpy(u->pos, m->pos, sizeof(double) * 3 * m->nv);
    memcpy(u->tri, m->tri, sizeof(int) * 3 * m->nf);
    CHECK_INT(operators_compute(u, NULL, &o), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "zero area") != NULL);
    u->pos[0] = NAN;
    CHECK_INT(operators_compute(u, NULL, &o), NEUV_ERR_INPUT);
    u->tri[4] = 999;
    u->pos[0] = 0;
    CHECK_INT(operators_compute(u, NULL, &o), NEUV_ERR_INPUT);
    neuv_mesh *e = mesh_create(0, 0, 0);
    CHECK_INT(operators_compute(e, NULL, &o), NEUV_ERR_INPUT);
    operators_params bad = {0, 16};
    CHECK_INT(operators_compute(m, &bad, &o), NEUV_ERR_INPUT);
    mesh_free(e);
    mesh_free(u);
    mesh_free(m);
}

/* The Cholesky wrapper: solves, and refuses an indefinite matrix. */
static void test_cholesky(void)
{
    neuv_mesh *m = shape_icosphere(2, 1.0);
    sparse_matrix L, A;
    double *mass = malloc((size_t)m->nv * sizeof *mass);
    CHECK_INT(cotan_laplacian(m, &L), NEUV_OK);
    lumped_mass(m, mass);
    CHECK_INT(sparse_add_diagonal(&L, mass, 1.0, &A), NEUV_OK);
    cholesky *c = NULL;
    CHECK_INT(cholesky_factor(&A, &c), NEUV_OK);
    int n = m->nv;
    double *b = malloc(2 * (size_t)n * sizeof *b), *x = malloc(2 * (size_t)n * sizeof *x), *y = malloc((size_t)n * sizeof *y);
    rng r;
    rng_seed(&r, 3);
    for (int i = 0; i < 2 * n; i++) b[i] = rng_normal(&r);
    CHECK_INT(cholesky_solve(c, b, x, 2), NEUV_OK);
    double err = 0.0;
    for (int q = 0; q < 2; q++) {
        sparse_matvec(&A, x + (size_t)q * n, y);
        for (int i = 0; i < n; i++) err = fmax(err, fabs(y[i] - b[(size_t)q * n + i]));
    }
    CHECK(err < 1e-10);
    cholesky_free(c);
    sparse_free(&A);
    /* L − M is indefinite (λ_1 ≈ 2 > 1 > 0 = λ_0). */
    CHECK_INT(sparse_add_diagonal(&L, mass, -1.0, &A), NEUV_OK);
    c = NULL;
    CHECK_INT(cholesky_factor(&A, &c), NEUV_ERR_INPUT);
    CHECK(c == NULL);
    sparse_free(&A);
    sparse_free(&L);
    free(mass); free(b); free(x); free(y);
    mesh_free(m);
}

int main(void)
{
    test_cholesky();
    test_bad_input();
    test_tiny();
    test_gradient_linear();
    test_two_components();
    test_many_components();
    test_sphere();
    return check_report("test_operators");
}
