#include "mesh/shapes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/mem.h"
#include "mesh/edge_map.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void set_pos(neuv_mesh *m, int v, double x, double y, double z)
{
    m->pos[3 * v] = x; m->pos[3 * v + 1] = y; m->pos[3 * v + 2] = z;
}

static void set_tri(neuv_mesh *m, int f, int a, int b, int c)
{
    m->tri[3 * f] = a; m->tri[3 * f + 1] = b; m->tri[3 * f + 2] = c;
}

/* Splits the quad a b c d (counter-clockwise) into two triangles at f, f+1. */
static void set_quad(neuv_mesh *m, int f, int a, int b, int c, int d)
{
    set_tri(m, f, a, b, c);
    set_tri(m, f + 1, a, c, d);
}

/* ---- icosphere ------------------------------------------------------- */

/* Index of the midpoint of edge (a, b), created on first request and
 * pushed onto the unit sphere. -1 on allocation failure. */
static int midpoint(neuv_mesh *m, edge_map *mid, int *nv, int a, int b)
{
    int lo = a < b ? a : b, hi = a < b ? b : a, inserted;
    int *slot = edge_map_slot(mid, lo, hi, *nv, &inserted);
    if (!slot) return -1;
    if (inserted) {
        const double *p = m->pos + 3 * a, *q = m->pos + 3 * b;
        double x = p[0] + q[0], y = p[1] + q[1], z = p[2] + q[2];
        double l = sqrt(x * x + y * y + z * z);
        set_pos(m, *nv, x / l, y / l, z / l);
        (*nv)++;
    }
    return *slot;
}

neuv_mesh *shape_icosphere(int level, double radius)
{
    if (level < 0 || level > 10) return NULL;
    int nf_final = 20, nv_final = 12;
    for (int l = 0; l < level; l++) { nv_final += 3 * nf_final / 2; nf_final *= 4; }
    neuv_mesh *m = mesh_create(nv_final, nf_final, 0);
    int *next = mem_alloc(sizeof(int) * 3 * (size_t)nf_final);
    if (!m || !next) { mesh_free(m); mem_free(next); return NULL; }

    /* Icosahedron: the 12 cyclic permutations of (0, ±1, ±t). */
    const double t = (1.0 + sqrt(5.0)) / 2.0;
    const double ico[12][3] = {
        {-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
        {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
        {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    const int faces[20][3] = {
        {0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
        {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
        {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
        {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    double l0 = sqrt(1 + t * t);
    for (int v = 0; v < 12; v++) set_pos(m, v, ico[v][0] / l0, ico[v][1] / l0, ico[v][2] / l0);
    for (int f = 0; f < 20; f++) set_tri(m, f, faces[f][0], faces[f][1], faces[f][2]);

    int nv = 12, nf = 20;
    for (int l = 0; l < level; l++) {
        edge_map mid;
        if (edge_map_init(&mid, (size_t)nf * 3 / 2) != 0) { mesh_free(m); mem_free(next); return NULL; }
        for (int f = 0; f < nf; f++) {
            int a = m->tri[3 * f], b = m->tri[3 * f + 1], c = m->tri[3 * f + 2];
            int ab = midpoint(m, &mid, &nv, a, b), bc = midpoint(m, &mid, &nv, b, c),
                ca = midpoint(m, &mid, &nv, c, a);
            if (ab < 0 || bc < 0 || ca < 0) { edge_map_free(&mid); mesh_free(m); mem_free(next); return NULL; }
            int *t4 = next + 12 * f;
            int quad[12] = {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca};
            memcpy(t4, quad, sizeof quad);
        }
        edge_map_free(&mid);
        nf *= 4;
        memcpy(m->tri, next, sizeof(int) * 3 * (size_t)nf);
    }
    mem_free(next);
    for (int i = 0; i < 3 * nv; i++) m->pos[i] *= radius;
    return m;
}

/* ---- surfaces of revolution around z -------------------------------- */

/* Revolves the profile (rho[i], z[i]), i = 0..n-1, listed from top to
 * bottom, around the z axis with `slices` vertices per ring. A profile
 * point with rho == 0 at either end becomes a single pole vertex. Quads
 * (ring i, ring i+1) are ordered so normals point away from the axis for a
 * profile that goes downwards. */
static neuv_mesh *revolve(const double *rho, const double *z, int n, int slices)
{
    if (n < 2 || slices < 3) return NULL;
    int top_pole = rho[0] == 0.0, bottom_pole = rho[n - 1] == 0.0;
    int rings = n - top_pole - bottom_pole;
    int nv = rings * slices + top_pole + bottom_pole;
    int nf = 2 * slices * (n - 1) - slices * (top_pole + bottom_pole);
    neuv_mesh *m = mesh_create(nv, nf, 0);
    if (!m) return NULL;
    /* Vertex index of profile point i at slice j. */
    int first_ring = top_pole ? 1 : 0;
    #define RING(i, j) (top_pole + ((i) - first_ring) * slices + ((j) % slices))
    int v = 0;
    if (top_pole) set_pos(m, v++, 0, 0, z[0]);
    for (int i = first_ring; i < first_ring + rings; i++)
        for (int j = 0; j < slices; j++) {
            double phi = 2.0 * M_PI * j / slices;
            set_pos(m, v++, rho[i] * cos(phi), rho[i] * sin(phi), z[i]);
        }
    int south = v;
    if (bottom_pole) set_pos(m, v++, 0, 0, z[n - 1]);

    int f = 0;
    for (int i = 0; i + 1 < n; i++)
        for (int j = 0; j < slices; j++) {
            if (i == 0 && top_pole) {
                set_tri(m, f++, 0, RING(1, j), RING(1, j + 1));
            } else if (i + 1 == n - 1 && bottom_pole) {
                set_tri(m, f++, south, RING(i, j + 1), RING(i, j));
            } else {
                set_quad(m, f, RING(i, j), RING(i + 1, j), RING(i + 1, j + 1), RING(i, j + 1));
                f += 2;
            }
        }
    #undef RING
    return m;
}

neuv_mesh *shape_uv_sphere(int slices, int stacks, double radius)
{
    if (slices < 3 || stacks < 2) return NULL;
    double *rho = mem_alloc(sizeof(double) * (size_t)(stacks + 1));
    double *z = mem_alloc(sizeof(double) * (size_t)(stacks + 1));
    if (!rho || !z) { mem_free(rho); mem_free(z); return NULL; }
    for (int i = 0; i <= stacks; i++) {
        double theta = M_PI * i / stacks;
        rho[i] = (i == 0 || i == stacks) ? 0.0 : radius * sin(theta);
        z[i] = radius * cos(theta);
    }
    neuv_mesh *m = revolve(rho, z, stacks + 1, slices);
    mem_free(rho); mem_free(z);
    return m;
}

neuv_mesh *shape_cylinder(double r, double h, int slices, int stacks)
{
    if (slices < 3 || stacks < 1 || !(r > 0)) return NULL;
    double *rho = mem_alloc(sizeof(double) * (size_t)(stacks + 1));
    double *z = mem_alloc(sizeof(double) * (size_t)(stacks + 1));
    if (!rho || !z) { mem_free(rho); mem_free(z); return NULL; }
    for (int i = 0; i <= stacks; i++) { rho[i] = r; z[i] = h / 2 - h * i / stacks; }
    neuv_mesh *m = revolve(rho, z, stacks + 1, slices);
    mem_free(rho); mem_free(z);
    return m;
}

neuv_mesh *shape_capsule(double r, double h, int slices, int stacks)
{
    if (slices < 3 || stacks < 1 || !(r > 0) || h < 0) return NULL;
    /* Bands on the cylinder chosen so quads there are about as tall as on the caps. */
    int bands = (int)ceil(h / (r * M_PI / 2 / stacks));
    if (bands < 1) bands = 1;
    int n = 2 * (stacks + 1) + bands - 1;
    double *rho = mem_alloc(sizeof(double) * (size_t)n), *z = mem_alloc(sizeof(double) * (size_t)n);
    if (!rho || !z) { mem_free(rho); mem_free(z); return NULL; }
    int k = 0;
    for (int i = 0; i <= stacks; i++) { /* top hemisphere, pole to equator */
        double theta = M_PI / 2 * i / stacks;
        rho[k] = i == 0 ? 0.0 : r * sin(theta);
        z[k++] = h / 2 + r * cos(theta);
    }
    for (int b = 1; b < bands; b++) { rho[k] = r; z[k++] = h / 2 - h * b / bands; }
    for (int i = stacks; i >= 0; i--) { /* bottom hemisphere, equator to pole */
        double theta = M_PI / 2 * i / stacks;
        rho[k] = i == 0 ? 0.0 : r * sin(theta);
        z[k++] = -h / 2 - r * cos(theta);
    }
    neuv_mesh *m = revolve(rho, z, n, slices);
    mem_free(rho); mem_free(z);
    return m;
}

/* ---- torus and grid -------------------------------------------------- */

neuv_mesh *shape_torus(double R, double r, int nu, int nv)
{
    if (nu < 3 || nv < 3) return NULL;
    neuv_mesh *m = mesh_create(nu * nv, 2 * nu * nv, 0);
    if (!m) return NULL;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double u = 2.0 * M_PI * i / nu, w = 2.0 * M_PI * j / nv;
            double rho = R + r * cos(w);
            set_pos(m, i * nv + j, rho * cos(u), rho * sin(u), r * sin(w));
        }
    /* d/du x d/dv points outward, so (i,j) (i+1,j) (i+1,j+1) is counter-clockwise. */
    int f = 0;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            int i1 = (i + 1) % nu, j1 = (j + 1) % nv;
            set_quad(m, f, i * nv + j, i1 * nv + j, i1 * nv + j1, i * nv + j1);
            f += 2;
        }
    return m;
}

neuv_mesh *shape_bumpy_torus(double R, double r, double bump, int nu, int nv)
{
    neuv_mesh *m = shape_torus(R, r, nu, nv);
    if (!m) return NULL;
    /* Move each vertex along the tube's normal by a smooth product of
     * sines: 5 bumps around the ring, 3 around the tube. */
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double u = 2.0 * M_PI * i / nu, w = 2.0 * M_PI * j / nv;
            double rr = r * (1.0 + bump * sin(5.0 * u) * sin(3.0 * w));
            double rho = R + rr * cos(w);
            set_pos(m, i * nv + j, rho * cos(u), rho * sin(u), rr * sin(w));
        }
    return m;
}

neuv_mesh *shape_grid(int nx, int ny, double w, double h, int with_uv)
{
    if (nx < 1 || ny < 1) return NULL;
    int nv = (nx + 1) * (ny + 1);
    neuv_mesh *m = mesh_create(nv, 2 * nx * ny, with_uv ? nv : 0);
    if (!m) return NULL;
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            int v = j * (nx + 1) + i;
            double x = w * i / nx, y = h * j / ny;
            set_pos(m, v, x, y, 0);
            if (with_uv) { m->uv[2 * v] = x; m->uv[2 * v + 1] = y; }
        }
    int f = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            int a = j * (nx + 1) + i;
            set_quad(m, f, a, a + 1, a + nx + 2, a + nx + 1);
            f += 2;
        }
    if (with_uv) memcpy(m->tri_uv, m->tri, sizeof(int) * 3 * (size_t)m->nf);
    return m;
}

/* ---- voxel solids: cube and genus-2 plate ---------------------------- */

/* The boundary of a union of unit voxels in an X by Y by Z grid (solid[x +
 * X*(y + Y*z)] != 0), one quad per solid/empty voxel face, oriented
 * outward. Lattice points are shared, so the result is watertight; it is
 * manifold as long as no two voxels touch only along an edge or corner.
 * Positions are lattice coordinates times `scale` plus `offset`. */
static neuv_mesh *voxel_boundary(const unsigned char *solid, const int dim[3], double scale,
                                 const double offset[3])
{
    const int X = dim[0], Y = dim[1], Z = dim[2];
    #define SOLID(x, y, z) ((x) >= 0 && (y) >= 0 && (z) >= 0 && (x) < X && (y) < Y && (z) < Z && \
                            solid[(x) + X * ((y) + Y * (z))])
    size_t nlat = (size_t)(X + 1) * (Y + 1) * (Z + 1);
    int *lattice = mem_alloc(sizeof(int) * nlat);
    if (!lattice) return NULL;
    for (size_t i = 0; i < nlat; i++) lattice[i] = -1;

    /* Two passes: count the faces and number the lattice points, then fill. */
    neuv_mesh *m = NULL;
    int nv = 0, nf = 0;
    for (int pass = 0; pass < 2; pass++) {
        nf = 0;
        for (int z = 0; z < Z; z++)
            for (int y = 0; y < Y; y++)
                for (int x = 0; x < X; x++) {
                    if (!SOLID(x, y, z)) continue;
                    int c[3] = {x, y, z};
                    for (int a = 0; a < 3; a++)
                        for (int s = -1; s <= 1; s += 2) {
                            int n[3] = {x, y, z};
                            n[a] += s;
                            if (SOLID(n[0], n[1], n[2])) continue;
                            /* Corners in the plane of the face, counter-clockwise
                             * around +a (u = a+1, v = a+2 is right-handed). */
                            int u = (a + 1) % 3, v = (a + 2) % 3, q[4];
                            const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
                            for (int k = 0; k < 4; k++) {
                                int p[3] = {c[0], c[1], c[2]};
                                p[a] += s > 0 ? 1 : 0;
                                p[u] += du[k];
                                p[v] += dv[k];
                                size_t li = (size_t)p[0] + (size_t)(X + 1) * ((size_t)p[1] + (size_t)(Y + 1) * (size_t)p[2]);
                                if (pass == 0 && lattice[li] < 0) lattice[li] = nv++;
                                q[k] = lattice[li];
                            }
                            if (pass == 1) {
                                if (s > 0) set_quad(m, nf, q[0], q[1], q[2], q[3]);
                                else set_quad(m, nf, q[0], q[3], q[2], q[1]);
                            }
                            nf += 2;
                        }
                }
        if (pass == 0) {
            m = mesh_create(nv, nf, 0);
            if (!m) { mem_free(lattice); return NULL; }
            for (int z = 0; z <= Z; z++)
                for (int y = 0; y <= Y; y++)
                    for (int x = 0; x <= X; x++) {
                        int v = lattice[(size_t)x + (size_t)(X + 1) * ((size_t)y + (size_t)(Y + 1) * (size_t)z)];
                        if (v >= 0) set_pos(m, v, x * scale + offset[0], y * scale + offset[1], z * scale + offset[2]);
                    }
        }
    }
    #undef SOLID
    mem_free(lattice);
    return m;
}

neuv_mesh *shape_cube(int n)
{
    if (n < 1 || n > 400) return NULL;
    /* Only the outer layer of voxels matters for the boundary, but a full
     * block keeps this simple and n stays small in practice. */
    size_t count = (size_t)n * n * n;
    unsigned char *solid = mem_alloc(count);
    if (!solid) return NULL;
    memset(solid, 1, count);
    int dim[3] = {n, n, n};
    double offset[3] = {-1, -1, -1};
    neuv_mesh *m = voxel_boundary(solid, dim, 2.0 / n, offset);
    mem_free(solid);
    return m;
}

neuv_mesh *shape_genus2(int n)
{
    if (n < 1 || n > 200) return NULL;
    /* In units of n voxels: a 5 by 3 by 1 plate with unit square holes at
     * x in [1,2] and [3,4], y in [1,2]. */
    int dim[3] = {5 * n, 3 * n, n};
    size_t count = (size_t)dim[0] * dim[1] * dim[2];
    unsigned char *solid = mem_alloc(count);
    if (!solid) return NULL;
    for (int z = 0; z < dim[2]; z++)
        for (int y = 0; y < dim[1]; y++)
            for (int x = 0; x < dim[0]; x++) {
                int ux = x / n, uy = y / n;
                int hole = uy == 1 && (ux == 1 || ux == 3);
                solid[x + dim[0] * (y + dim[1] * z)] = !hole;
            }
    double scale = 1.0 / n, offset[3] = {-2.5, -1.5, -0.5};
    neuv_mesh *m = voxel_boundary(solid, dim, scale, offset);
    mem_free(solid);
    return m;
}
