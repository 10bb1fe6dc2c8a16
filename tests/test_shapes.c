/* Procedural shapes: counts, topology, orientation and analytic areas. */
#include "check.h"

#include "mesh/edge_map.h"
#include "mesh/blob_family.h"
#include "mesh/shape_family.h"
#include "mesh/shapes.h"
#include "mesh/signed_volume.h"
#include "mesh/topology.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* 1 when every directed edge occurs once (manifold, consistently oriented)
 * and, for a closed shape, its reverse occurs too (watertight). */
static int oriented_manifold(const neuv_mesh *m, int closed)
{
    edge_map e;
    if (edge_map_init(&e, (size_t)m->nf * 3) != 0) return 0;
    int ok = 1;
    for (int f = 0; f < m->nf && ok; f++)
        for (int k = 0; k < 3; k++) {
            int a = m->tri[3 * f + k], b = m->tri[3 * f + (k + 1) % 3], ins;
            if (a == b || !edge_map_slot(&e, a, b, f, &ins) || !ins) ok = 0;
        }
    for (int f = 0; f < m->nf && ok && closed; f++)
        for (int k = 0; k < 3; k++)
            if (edge_map_get(&e, m->tri[3 * f + (k + 1) % 3], m->tri[3 * f + k]) < 0) ok = 0;
    edge_map_free(&e);
    return ok;
}

static int min_area_positive(const neuv_mesh *m)
{
    for (int f = 0; f < m->nf; f++)
        if (!(mesh_face_area(m, f) > 1e-12)) return 0;
    return 1;
}

/* Checks topology of the whole mesh and returns it. */
static component_topology topo(const neuv_mesh *m)
{
    component_topology t;
    memset(&t, 0, sizeof t);
    CHECK(mesh_subset_topology(m, NULL, 0, &t) == NEUV_OK);
    int *comp = malloc(sizeof(int) * (size_t)m->nf);
    CHECK_INT(mesh_face_components(m, comp), 1);
    free(comp);
    return t;
}

int main(void)
{
    /* Icosphere: V = 10*4^L + 2, F = 20*4^L, closed genus 0, area -> 4 pi r^2. */
    neuv_mesh *m = shape_icosphere(4, 1.0);
    CHECK(m != NULL);
    CHECK_INT(m->nv, 2562);
    CHECK_INT(m->nf, 5120);
    component_topology t = topo(m);
    CHECK_INT(t.genus, 0); CHECK_INT(t.euler, 2); CHECK(t.closed); CHECK_INT(t.boundary_loops, 0);
    CHECK(oriented_manifold(m, 1));
    CHECK(fabs(mesh_total_area(m) - 4 * M_PI) < 0.01 * 4 * M_PI);
    CHECK(mesh_signed_volume(m, NULL, 0) > 0);
    for (int v = 0; v < m->nv; v++) {
        double *p = m->pos + 3 * v;
        if (fabs(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1) > 1e-12) { CHECK(0); break; }
    }
    mesh_free(m);
    m = shape_icosphere(5, 2.0);
    CHECK_INT(m->nv, 10242); CHECK_INT(m->nf, 20480);
    CHECK(fabs(mesh_total_area(m) - 16 * M_PI) < 0.003 * 16 * M_PI);
    CHECK_NEAR(mesh_signed_volume(m, NULL, 0), 4.0 / 3 * M_PI * 8, 0.01 * 4.0 / 3 * M_PI * 8);
    mesh_free(m);

    /* UV sphere: 2 poles + (stacks-1) rings. */
    m = shape_uv_sphere(32, 16, 1.0);
    CHECK_INT(m->nv, 2 + 15 * 32);
    CHECK_INT(m->nf, 2 * 32 * 16 - 2 * 32);
    t = topo(m);
    CHECK_INT(t.genus, 0); CHECK(t.closed);
    CHECK(oriented_manifold(m, 1)); CHECK(min_area_positive(m));
    CHECK(mesh_signed_volume(m, NULL, 0) > 0);
    CHECK(fabs(mesh_total_area(m) - 4 * M_PI) < 0.02 * 4 * M_PI);
    mesh_free(m);

    /* Torus: area 4 pi^2 R r, volume 2 pi^2 R r^2, genus 1, Euler 0. */
    m = shape_torus(2.0, 0.5, 96, 48);
    CHECK_INT(m->nv, 96 * 48); CHECK_INT(m->nf, 2 * 96 * 48);
    t = topo(m);
    CHECK_INT(t.genus, 1); CHECK_INT(t.euler, 0); CHECK(t.closed);
    CHECK(oriented_manifold(m, 1));
    CHECK(fabs(mesh_total_area(m) - 4 * M_PI * M_PI * 2.0 * 0.5) < 0.01 * 4 * M_PI * M_PI);
    CHECK_NEAR(mesh_signed_volume(m, NULL, 0), 2 * M_PI * M_PI * 2.0 * 0.25, 0.01 * M_PI * M_PI);
    mesh_free(m);

    /* Bumpy torus (the demo shape): genus 1, outward; volume 2 pi^2 R r^2 (1 + b^2/4)
     * since the bumps' odd harmonics cancel against cos w in the volume integral. */
    m = shape_bumpy_torus(1.0, 0.4, 0.25, 96, 40);
    t = topo(m);
    CHECK_INT(t.genus, 1); CHECK(t.closed);
    CHECK(oriented_manifold(m, 1)); CHECK(min_area_positive(m));
    CHECK_NEAR(mesh_signed_volume(m, NULL, 0), 2 * M_PI * M_PI * 0.16 * (1 + 0.25 * 0.25 / 4),
               0.02 * 2 * M_PI * M_PI * 0.16);
    mesh_free(m);

    /* Grid: disk, one loop of 2(nx+ny) edges, area w h, identity UVs. */
    m = shape_grid(8, 5, 2.0, 1.0, 1);
    CHECK_INT(m->nv, 9 * 6); CHECK_INT(m->nf, 80);
    t = topo(m);
    CHECK_INT(t.boundary_loops, 1); CHECK_INT(t.genus, 0); CHECK_INT(t.euler, 1); CHECK(!t.closed);
    CHECK(oriented_manifold(m, 0));
    CHECK_NEAR(mesh_total_area(m), 2.0, 1e-12);
    CHECK_INT(m->nuv, m->nv);
    int uv_ok = 1;
    for (int c = 0; c < 3 * m->nf; c++) {
        const double *p = m->pos + 3 * m->tri[c], *uv = m->uv + 2 * m->tri_uv[c];
        if (p[0] != uv[0] || p[1] != uv[1]) uv_ok = 0;
    }
    CHECK(uv_ok);
    double n[3];
    mesh_face_normal(m, 0, n);
    CHECK_NEAR(n[2], 1.0, 1e-12); /* counter-clockwise seen from +z */
    mesh_free(m);
    m = shape_grid(3, 3, 1, 1, 0);
    CHECK(m->uv == NULL && m->tri_uv == NULL && m->nuv == 0);
    mesh_free(m);

    /* Open cylinder: annulus, 2 loops, genus 0, area 2 pi r h (inscribed polygon). */
    m = shape_cylinder(1.0, 2.0, 64, 10);
    CHECK_INT(m->nv, 64 * 11); CHECK_INT(m->nf, 2 * 64 * 10);
    t = topo(m);
    CHECK_INT(t.boundary_loops, 2); CHECK_INT(t.genus, 0); CHECK_INT(t.euler, 0);
    CHECK(oriented_manifold(m, 0));
    CHECK(fabs(mesh_total_area(m) - 4 * M_PI) < 0.01 * 4 * M_PI);
    mesh_face_normal(m, 0, n);
    const double *p0 = m->pos + 3 * m->tri[0];
    CHECK(n[0] * p0[0] + n[1] * p0[1] > 0); /* outward */
    mesh_free(m);

    /* Capsule: closed genus 0, area 4 pi r^2 + 2 pi r h. */
    m = shape_capsule(0.5, 1.0, 64, 16);
    t = topo(m);
    CHECK_INT(t.genus, 0); CHECK(t.closed);
    CHECK(oriented_manifold(m, 1)); CHECK(min_area_positive(m));
    CHECK(fabs(mesh_total_area(m) - (M_PI + M_PI)) < 0.01 * 2 * M_PI);
    CHECK(mesh_signed_volume(m, NULL, 0) > 0);
    mesh_free(m);

    /* Cube: 6 n^2 quads, V = 6n^2 + 2, area 24, volume 8. */
    m = shape_cube(4);
    CHECK_INT(m->nf, 6 * 16 * 2); CHECK_INT(m->nv, 6 * 16 + 2);
    t = topo(m);
    CHECK_INT(t.genus, 0); CHECK(t.closed);
    CHECK(oriented_manifold(m, 1));
    CHECK_NEAR(mesh_total_area(m), 24.0, 1e-9);
    CHECK_NEAR(mesh_signed_volume(m, NULL, 0), 8.0, 1e-9);
    mesh_free(m);

    /* Genus 2 plate: Euler -2, volume 15 - 2. */
    for (int res = 1; res <= 3; res++) {
        m = shape_genus2(res);
        CHECK(m != NULL);
        t = topo(m);
        CHECK_INT(t.genus, 2); CHECK_INT(t.euler, -2); CHECK(t.closed);
        CHECK(oriented_manifold(m, 1)); CHECK(min_area_positive(m));
        CHECK_NEAR(mesh_signed_volume(m, NULL, 0), 13.0, 1e-9);
        /* outer 2(15 + 5 + 3) + hole walls 2 * 4 */
        CHECK_NEAR(mesh_total_area(m), 2 * (15 - 2) + 2 * (5 + 3) + 8, 1e-9);
        mesh_free(m);
    }

    /* The bent-capsule family: every member a closed, outward-oriented
     * genus-0 manifold; bending about a circle keeps area and volume (the
     * stretch (R - x) / R averages to 1 over a cross-section symmetric in x),
     * up to the straight triangles; no bend, bulge or scale is the capsule. */
    {
        capsule_params p = {0.5, 1.0, 0, 0, 1, 48, 12};
        neuv_mesh *straight = shape_bent_capsule(&p), *plain = shape_capsule(0.5, 1.0, 48, 12);
        CHECK(straight && plain && straight->nv == plain->nv);
        CHECK(memcmp(straight->pos, plain->pos, sizeof(double) * 3 * (size_t)plain->nv) == 0);
        p.bend = 1.2;
        neuv_mesh *bent = shape_bent_capsule(&p);
        double a0 = mesh_total_area(straight), v0 = mesh_signed_volume(straight, NULL, 0);
        printf("bent capsule: area %.5f vs %.5f, volume %.5f vs %.5f\n", mesh_total_area(bent), a0,
               mesh_signed_volume(bent, NULL, 0), v0);
        CHECK_NEAR(mesh_total_area(bent), a0, 0.005 * a0);
        CHECK_NEAR(mesh_signed_volume(bent, NULL, 0), v0, 0.005 * v0);
        /* The top pole (arc length 1 from the middle) lands on the bend
         * circle of radius 2 / 1.2 at angle 1 / R. */
        int top = 0;
        for (int v = 0; v < straight->nv; v++)
            if (straight->pos[3 * v + 2] > straight->pos[3 * top + 2]) top = v;
        double R = 2.0 / 1.2;
        CHECK_NEAR(bent->pos[3 * top], R - R * cos(1.0 / R), 1e-12);
        CHECK_NEAR(bent->pos[3 * top + 2], R * sin(1.0 / R), 1e-12);
        mesh_free(straight); mesh_free(plain); mesh_free(bent);
        for (int i = 0; i < 25; i++) {
            capsule_family_params((uint64_t)i, &p);
            CHECK(p.radius >= 0.3 && p.radius <= 0.55 && p.length >= 0.8 && p.length <= 2.5);
            CHECK(p.bend >= 0 && p.bend <= 1.5 && p.size >= 0.5 && p.size <= 2 && p.slices >= 20 && p.slices <= 32);
            m = shape_capsule_family((uint64_t)i);
            CHECK(m != NULL);
            if (!m) continue;
            t = topo(m);
            CHECK_INT(t.genus, 0); CHECK(t.closed);
            CHECK(oriented_manifold(m, 1)); CHECK(min_area_positive(m));
            CHECK(mesh_signed_volume(m, NULL, 0) > 0);
            mesh_free(m);
        }
        p.radius = -1;
        CHECK(shape_bent_capsule(&p) == NULL);
    }

    /* Blobs: without bumps and stretch, the unit icosphere; a single bump of
     * height h raises its centre to 1 + h exactly; members are closed genus-0
     * surfaces, each one reproducible and different from the next. */
    {
        blob_params p = {0};
        p.level = 2;
        for (int q = 0; q < 3; q++) { p.stretch[q] = 1; p.turn[q] = 0.3 * (q + 1); }
        neuv_mesh *b = shape_blob(&p);
        CHECK(b != NULL);
        double worst = 0;
        for (int v = 0; b && v < b->nv; v++)
            worst = fmax(worst, fabs(sqrt(b->pos[3 * v] * b->pos[3 * v] + b->pos[3 * v + 1] * b->pos[3 * v + 1] +
                                          b->pos[3 * v + 2] * b->pos[3 * v + 2]) - 1));
        CHECK(worst < 1e-12);
        mesh_free(b);
        /* one bump at the icosphere's vertex (0, 0, 1)·(normalized) direction of vertex 0 */
        b = shape_icosphere(2, 1.0);
        p.bumps = 1;
        for (int q = 0; q < 3; q++) p.dir[0][q] = b->pos[q];
        p.height[0] = 0.4;
        p.width[0] = 0.5;
        mesh_free(b);
        b = shape_blob(&p);
        CHECK(b != NULL);
        if (b) CHECK_NEAR(sqrt(b->pos[0] * b->pos[0] + b->pos[1] * b->pos[1] + b->pos[2] * b->pos[2]), 1.4, 1e-12);
        mesh_free(b);
        p.width[0] = 0;
        CHECK(shape_blob(&p) == NULL);
        for (int i = 0; i < 12; i++) {
            blob_family_params((uint64_t)i, &p);
            CHECK(p.bumps >= 3 && p.bumps <= BLOB_MAX_BUMPS && (p.level == 3 || p.level == 4));
            for (int q = 0; q < 3; q++) CHECK(p.stretch[q] >= 0.6 && p.stretch[q] <= 1.5);
            m = shape_blob_family((uint64_t)i);
            neuv_mesh *again = shape_blob_family((uint64_t)i), *next = shape_blob_family((uint64_t)i + 1);
            CHECK(m && again && next);
            if (!m || !again || !next) { mesh_free(m); mesh_free(again); mesh_free(next); continue; }
            CHECK(m->nv == again->nv && !memcmp(m->pos, again->pos, sizeof(double) * 3 * (size_t)m->nv));
            CHECK(m->nv != next->nv || memcmp(m->pos, next->pos, sizeof(double) * 3 * (size_t)m->nv) != 0);
            t = topo(m);
            CHECK_INT(t.genus, 0); CHECK(t.closed);
            CHECK(oriented_manifold(m, 1)); CHECK(min_area_positive(m));
            CHECK(mesh_signed_volume(m, NULL, 0) > 0);
            mesh_free(m); mesh_free(again); mesh_free(next);
        }
    }

    CHECK(shape_icosphere(-1, 1) == NULL);
    CHECK(shape_torus(1, 0.5, 2, 3) == NULL);
    CHECK(shape_grid(0, 3, 1, 1, 0) == NULL);
    return check_report("test_shapes");
}
