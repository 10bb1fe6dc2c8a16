/* Remeshing: midpoint and Loop subdivision, meshoptimizer simplification,
 * and jitter (vertices stay on the input surface, connectivity changes,
 * same seed same result). */
#include "check.h"
#include "mesh/clean.h"
#include "mesh/shapes.h"
#include "mesh/topology.h"
#include "remesh/jitter.h"
#include "remesh/simplify.h"
#include "remesh/subdivide.h"
#include "spatial/bvh.h"
#include "surface_distance.h"

static component_topology topo(const neuv_mesh *m)
{
    component_topology t;
    memset(&t, 0, sizeof t);
    CHECK_INT(mesh_subset_topology(m, NULL, 0, &t), NEUV_OK);
    return t;
}


static void test_midpoint(void)
{
    neuv_mesh *g = shape_grid(5, 4, 2.0, 1.5, 1);
    /* Make it non-planar so "area unchanged" is not trivially true. */
    for (int v = 0; v < g->nv; v++) g->pos[3 * v + 2] = 0.3 * sin(3 * g->pos[3 * v]) * g->pos[3 * v + 1];
    neuv_mesh *s = NULL;
    CHECK_INT(mesh_subdivide(g, 2, SUBDIVIDE_MIDPOINT, &s), NEUV_OK);
    CHECK_INT(s->nf, g->nf * 16);
    CHECK_NEAR(mesh_total_area(s), mesh_total_area(g), 1e-12 * mesh_total_area(g));
    int moved = 0;
    for (int i = 0; i < 3 * g->nv; i++) moved += s->pos[i] != g->pos[i];
    CHECK_INT(moved, 0);
    /* Every new vertex lies on the input surface. */
    CHECK(max_deviation(g, s) < 1e-12);
    /* UVs interpolated: the grid's UVs equal (x, y), so they still do at every corner. */
    CHECK(s->nuv > 0 && s->tri_uv);
    double uv_err = 0;
    for (int c = 0; c < 3 * s->nf; c++) {
        const double *p = s->pos + 3 * s->tri[c], *uv = s->uv + 2 * s->tri_uv[c];
        uv_err = fmax(uv_err, fmax(fabs(uv[0] - p[0]), fabs(uv[1] - p[1])));
    }
    CHECK(uv_err < 1e-14);
    component_topology t = topo(s);
    CHECK_INT(t.boundary_loops, 1);
    CHECK_INT(t.euler, 1);
    mesh_free(s);

    /* Seams stay seams: a per-face UV copy (every face its own island). */
    neuv_mesh *h = mesh_clone(g);
    double *uv = malloc(sizeof(double) * 6 * h->nf);
    int *tuv = malloc(sizeof(int) * 3 * h->nf);
    for (int c = 0; c < 3 * h->nf; c++) {
        tuv[c] = c;
        uv[2 * c] = g->uv[2 * g->tri_uv[c]] + (c / 3);
        uv[2 * c + 1] = g->uv[2 * g->tri_uv[c] + 1];
    }
    CHECK_INT(mesh_set_uv(h, 3 * h->nf, uv, tuv), NEUV_OK);
    CHECK_INT(mesh_subdivide(h, 1, SUBDIVIDE_MIDPOINT, &s), NEUV_OK);
    CHECK_INT(s->nuv, h->nf * 6); /* 3 corners + 3 edge midpoints per island */
    mesh_free(s); mesh_free(h); free(uv); free(tuv);
    mesh_free(g);
}

static void test_loop(void)
{
    neuv_mesh *ico = shape_icosphere(2, 1.0);
    neuv_mesh *s = NULL;
    CHECK_INT(mesh_subdivide(ico, 1, SUBDIVIDE_LOOP, &s), NEUV_OK);
    CHECK_INT(s->nf, ico->nf * 4);
    double rmin = INFINITY, rmax = 0;
    for (int v = 0; v < s->nv; v++) {
        double r = sqrt(s->pos[3 * v] * s->pos[3 * v] + s->pos[3 * v + 1] * s->pos[3 * v + 1] + s->pos[3 * v + 2] * s->pos[3 * v + 2]);
        rmin = fmin(rmin, r); rmax = fmax(rmax, r);
    }
    /* Loop averages with the neighbours: the convex mesh shrinks a little, not much. */
    CHECK(rmax < 1.0);
    CHECK(rmin > 0.95);
    component_topology t = topo(s);
    CHECK(t.closed);
    CHECK_INT(t.genus, 0);
    CHECK_INT(t.euler, 2);
    /* An old vertex of valence 6 follows the formula exactly: beta = 1/16. */
    int v6 = -1;
    int *val = calloc((size_t)ico->nv, sizeof(int));
    for (int c = 0; c < 3 * ico->nf; c++) val[ico->tri[c]]++;
    for (int v = 0; v < ico->nv && v6 < 0; v++) if (val[v] == 6) v6 = v;
    CHECK(v6 >= 0);
    double sum[3] = {0, 0, 0};
    int seen[64], ns = 0;
    for (int f = 0; f < ico->nf; f++)
        for (int k = 0; k < 3; k++)
            if (ico->tri[3 * f + k] == v6) {
                int w = ico->tri[3 * f + (k + 1) % 3], dup = 0;
                for (int i = 0; i < ns; i++) dup |= seen[i] == w;
                if (!dup) { seen[ns++] = w; for (int i = 0; i < 3; i++) sum[i] += ico->pos[3 * w + i]; }
            }
    CHECK_INT(ns, 6);
    for (int i = 0; i < 3; i++) CHECK_NEAR(s->pos[3 * v6 + i], 0.625 * ico->pos[3 * v6 + i] + sum[i] / 16, 1e-14);
    free(val);
    mesh_free(s);
    /* Boundary rule on a flat grid: everything stays in the plane, the border straight. */
    neuv_mesh *g = shape_grid(4, 4, 1, 1, 0);
    CHECK_INT(mesh_subdivide(g, 2, SUBDIVIDE_LOOP, &s), NEUV_OK);
    double zmax = 0, outside = 0;
    for (int v = 0; v < s->nv; v++) {
        zmax = fmax(zmax, fabs(s->pos[3 * v + 2]));
        outside = fmax(outside, fmax(-s->pos[3 * v], s->pos[3 * v] - 1));
    }
    CHECK(zmax == 0);
    CHECK(outside <= 1e-15);
    mesh_free(s); mesh_free(g); mesh_free(ico);
}

/* Whether every vertex of s is bit-identical to some vertex of m. */
static int positions_subset(const neuv_mesh *m, const neuv_mesh *s)
{
    for (int v = 0; v < s->nv; v++) {
        int found = 0;
        for (int w = 0; w < m->nv && !found; w++) found = !memcmp(s->pos + 3 * v, m->pos + 3 * w, sizeof(double) * 3);
        if (!found) return 0;
    }
    return 1;
}

static void test_simplify(void)
{
    neuv_mesh *shapes[2] = {shape_icosphere(4, 1.0), shape_torus(1.0, 0.35, 64, 32)};
    int genus[2] = {0, 1};
    double ratios[2] = {0.5, 0.2};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            neuv_mesh *s = NULL;
            CHECK_INT(mesh_simplify(shapes[i], ratios[j], &s), NEUV_OK);
            if (!s) continue;
            double want = ratios[j] * shapes[i]->nf;
            CHECK(fabs(s->nf - want) <= 0.1 * want);
            component_topology t = topo(s);
            CHECK(t.closed);
            CHECK_INT(t.genus, genus[i]);
            CHECK(positions_subset(shapes[i], s));
            int unreferenced = 0;
            char *used = calloc((size_t)(s->nv > 0 ? s->nv : 1), 1);
            for (int c = 0; c < 3 * s->nf; c++) used[s->tri[c]] = 1;
            for (int v = 0; v < s->nv; v++) unreferenced += !used[v];
            CHECK_INT(unreferenced, 0);
            free(used);
            mesh_free(s);
        }
    /* UVs survive: a grid with identity UVs keeps them at every kept corner. */
    neuv_mesh *g = shape_grid(20, 20, 1, 1, 1), *s = NULL;
    CHECK_INT(mesh_simplify(g, 0.5, &s), NEUV_OK);
    CHECK(s && s->nuv > 0);
    double uv_err = 0;
    for (int c = 0; s && c < 3 * s->nf; c++) {
        const double *p = s->pos + 3 * s->tri[c], *uv = s->uv + 2 * s->tri_uv[c];
        uv_err = fmax(uv_err, fmax(fabs(uv[0] - p[0]), fabs(uv[1] - p[1])));
    }
    CHECK(uv_err == 0);
    CHECK(s && s->nf < g->nf);
    mesh_free(s);
    CHECK_INT(mesh_simplify(g, 0, &s), NEUV_ERR_INPUT);
    CHECK_INT(mesh_simplify(g, 1.5, &s), NEUV_ERR_INPUT);
    mesh_free(g);
    mesh_free(shapes[0]); mesh_free(shapes[1]);
}

static int same_mesh(const neuv_mesh *a, const neuv_mesh *b)
{
    return a->nv == b->nv && a->nf == b->nf && !memcmp(a->pos, b->pos, sizeof(double) * 3 * a->nv) &&
           !memcmp(a->tri, b->tri, sizeof(int) * 3 * a->nf);
}

/* Issue 20, item 6: meshoptimizer's simplifier tears a fine regular bumpy
 * grid (this one, 99k faces at 0.05, came out with Euler characteristic
 * 3, 2 non-manifold edges and a duplicate face; the hostile test's 200k
 * grid with 9 components), and ARPACK then failed on the torn copy. The copy must
 * keep the input's topology: one component, one boundary loop, a disk's
 * Euler characteristic, manifold and consistently oriented. */
static void test_simplify_keeps_topology(void)
{
    const int k = 223;
    neuv_mesh *g = shape_grid(k, k, 1.0, 1.0, 0), *s = NULL;
    for (int v = 0; v < g->nv; v++)
        g->pos[3 * v + 2] = 0.1 * sin(3 * g->pos[3 * v]) * cos(2 * g->pos[3 * v + 1]);
    CHECK_INT(mesh_simplify(g, 0.05, &s), NEUV_OK);
    if (s) {
        double want = 0.05 * g->nf;
        CHECK(fabs(s->nf - want) <= 0.1 * want);
        int *comp = malloc(sizeof(int) * (size_t)s->nf);
        CHECK_INT(mesh_face_components(s, comp), 1);
        free(comp);
        component_topology t = topo(s);
        CHECK_INT(t.boundary_loops, 1);
        CHECK_INT(t.euler, 1);
        neuv_mesh *c = mesh_clone(s);
        mesh_clean_report rep;
        memset(&rep, 0, sizeof rep);
        CHECK_INT(mesh_clean(c, NULL, &rep), NEUV_OK);
        CHECK_INT(rep.nonmanifold_edges, 0);
        CHECK_INT(rep.nonmanifold_vertices, 0);
        CHECK_INT(rep.duplicate_faces, 0);
        CHECK_INT(rep.degenerate_faces, 0);
        CHECK_INT(rep.flipped_faces, 0);
        /* The copy still spans the unit square. */
        double lo[3], hi[3];
        mesh_bounding_box(s, lo, hi);
        CHECK(lo[0] < 1e-9 && lo[1] < 1e-9 && hi[0] > 1 - 1e-9 && hi[1] > 1 - 1e-9);
        mesh_free(c);
        /* Same input, same copy. */
        neuv_mesh *s2 = NULL;
        CHECK_INT(mesh_simplify(g, 0.05, &s2), NEUV_OK);
        CHECK(s2 && same_mesh(s, s2));
        mesh_free(s2);
    }
    mesh_free(s);
    mesh_free(g);
}

static void test_jitter(void)
{
    /* Flat grid with identity UVs: every vertex stays in the plane and in
     * the square, the UVs keep following the positions. */
    neuv_mesh *g = shape_grid(12, 10, 1.2, 1.0, 1);
    neuv_mesh *j = mesh_clone(g), *j2 = mesh_clone(g), *j3 = mesh_clone(g);
    jitter_report rep;
    CHECK_INT(mesh_jitter(j, 7, NULL, &rep), NEUV_OK);
    CHECK(max_deviation(g, j) < 1e-9);
    CHECK(rep.moved_vertices > 0.8 * (11 * 9));
    CHECK(rep.slid_vertices > 0);
    CHECK(rep.flipped_edges > 0);
    CHECK(!same_mesh(g, j));
    int tri_changed = memcmp(g->tri, j->tri, sizeof(int) * 3 * g->nf) != 0;
    CHECK(tri_changed);
    CHECK_NEAR(mesh_total_area(j), mesh_total_area(g), 1e-12);
    double uv_err = 0;
    for (int c = 0; c < 3 * j->nf; c++) {
        const double *p = j->pos + 3 * j->tri[c], *uv = j->uv + 2 * j->tri_uv[c];
        uv_err = fmax(uv_err, fmax(fabs(uv[0] - p[0]), fabs(uv[1] - p[1])));
    }
    CHECK(uv_err < 1e-12);
    /* The four corners stay. */
    double lo[3], hi[3];
    mesh_bounding_box(j, lo, hi);
    CHECK(lo[0] == 0 && lo[1] == 0 && hi[0] == 1.2 && hi[1] == 1.0);
    /* No face flipped: all normals still +z. */
    int flipped = 0;
    for (int f = 0; f < j->nf; f++) { double n[3]; mesh_face_normal(j, f, n); flipped += !(n[2] > 0.99); }
    CHECK_INT(flipped, 0);
    component_topology t = topo(j);
    CHECK_INT(t.euler, 1); CHECK_INT(t.boundary_loops, 1);
    /* Deterministic for a seed, different for another. */
    CHECK_INT(mesh_jitter(j2, 7, NULL, NULL), NEUV_OK);
    CHECK(same_mesh(j, j2));
    CHECK_INT(mesh_jitter(j3, 8, NULL, NULL), NEUV_OK);
    CHECK(!same_mesh(j, j3));
    mesh_free(j); mesh_free(j2); mesh_free(j3); mesh_free(g);

    /* Sphere-like mesh: vertices stay on the input polyhedron. */
    neuv_mesh *ico = shape_icosphere(3, 1.0), *ji = mesh_clone(ico);
    CHECK_INT(mesh_jitter(ji, 11, NULL, &rep), NEUV_OK);
    double dev = max_deviation(ico, ji);
    CHECK(dev < 1e-12);
    CHECK(rep.moved_vertices > ico->nv / 2);
    double moved = 0;
    for (int v = 0; v < ico->nv; v++)
        moved = fmax(moved, fabs(ji->pos[3 * v] - ico->pos[3 * v]) + fabs(ji->pos[3 * v + 1] - ico->pos[3 * v + 1]));
    CHECK(moved > 1e-3);
    t = topo(ji);
    CHECK(t.closed); CHECK_INT(t.genus, 0);
    printf("jitter: icosphere %d moved, %d fixed, %d flips, max deviation %.3g\n", rep.moved_vertices,
           rep.fixed_vertices, rep.flipped_edges, dev);
    mesh_free(ji); mesh_free(ico);

    /* A cube: vertices on its edges and corners stay, the faces' interiors move. */
    neuv_mesh *cube = shape_cube(4), *jc = mesh_clone(cube);
    CHECK_INT(mesh_jitter(jc, 3, NULL, &rep), NEUV_OK);
    CHECK(max_deviation(cube, jc) < 1e-12);
    mesh_bounding_box(jc, lo, hi);
    CHECK(lo[0] == -1 && hi[2] == 1);
    CHECK_INT(rep.moved_vertices, 6 * 9);
    mesh_free(jc); mesh_free(cube);
}

int main(void)
{
    test_midpoint();
    test_loop();
    test_simplify();
    test_simplify_keeps_topology();
    test_jitter();
    return check_report("test_remesh");
}
