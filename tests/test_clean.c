/* Mesh cleaning: exact repair counts on a hand-made soup, the result
 * manifold and consistently oriented, UVs following their corners. */
#include "check.h"

#include "core/rng.h"
#include "mesh/clean.h"
#include "mesh/edge_map.h"
#include "mesh/shapes.h"
#include "mesh/signed_volume.h"
#include "mesh/topology.h"
#include "neuv/neuv.h"

/* 1 when every directed edge occurs at most once (manifold edges,
 * consistent orientation) and no vertex has two fans (checked via the
 * number of boundary edges leaving each vertex being at most one). */
static int oriented_manifold(const neuv_mesh *m)
{
    edge_map e;
    if (edge_map_init(&e, (size_t)m->nf * 3) != 0) return 0;
    int ok = 1;
    for (int f = 0; f < m->nf && ok; f++)
        for (int k = 0; k < 3; k++) {
            int a = m->tri[3 * f + k], b = m->tri[3 * f + (k + 1) % 3], ins;
            if (a == b || !edge_map_slot(&e, a, b, f, &ins) || !ins) ok = 0;
        }
    int *out = calloc((size_t)m->nv + 1, sizeof(int));
    for (int f = 0; f < m->nf && ok; f++)
        for (int k = 0; k < 3; k++) {
            int a = m->tri[3 * f + k], b = m->tri[3 * f + (k + 1) % 3];
            if (edge_map_get(&e, b, a) < 0 && ++out[a] > 1) ok = 0;
        }
    free(out);
    edge_map_free(&e);
    return ok;
}

/* Soup builder: positions and faces appended one by one. */
typedef struct soup { double pos[300]; int tri[300]; int nv, nf; } soup;
static int add_v(soup *s, double x, double y, double z)
{
    s->pos[3 * s->nv] = x; s->pos[3 * s->nv + 1] = y; s->pos[3 * s->nv + 2] = z;
    return s->nv++;
}
static void add_f(soup *s, int a, int b, int c)
{
    s->tri[3 * s->nf] = a; s->tri[3 * s->nf + 1] = b; s->tri[3 * s->nf + 2] = c; s->nf++;
}
/* A face with its own three vertices (so welding has work to do). */
static void add_soup_face(soup *s, const double *a, const double *b, const double *c)
{
    int i = add_v(s, a[0], a[1], a[2]), j = add_v(s, b[0], b[1], b[2]), k = add_v(s, c[0], c[1], c[2]);
    add_f(s, i, j, k);
}

static neuv_mesh *soup_mesh(const soup *s)
{
    neuv_mesh *m = mesh_create(s->nv, s->nf, 3 * s->nf);
    memcpy(m->pos, s->pos, sizeof(double) * 3 * (size_t)s->nv);
    memcpy(m->tri, s->tri, sizeof(int) * 3 * (size_t)s->nf);
    /* Corner c carries UV (c, 0.5): it names the input corner it belongs to. */
    for (int c = 0; c < 3 * s->nf; c++) { m->tri_uv[c] = c; m->uv[2 * c] = c; m->uv[2 * c + 1] = 0.5; }
    return m;
}

/* The soup: an octahedron as separate triangles with one face flipped, one
 * duplicate (reversed) face, two degenerate faces, an unreferenced vertex;
 * three triangles on one edge; two triangles touching at one vertex. */
static soup make_soup(void)
{
    soup s = {.nv = 0};
    const double P[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    /* Outward faces of the octahedron. */
    const int O[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                         {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (int f = 0; f < 8; f++) {
        if (f == 5) add_soup_face(&s, P[O[f][0]], P[O[f][2]], P[O[f][1]]); /* flipped */
        else add_soup_face(&s, P[O[f][0]], P[O[f][1]], P[O[f][2]]);
    }
    add_soup_face(&s, P[4], P[2], P[0]);                 /* duplicate of face 0, reversed */
    int a = add_v(&s, 1, 0, 0), b = add_v(&s, 0, 1, 0);
    add_f(&s, a, a, b);                                  /* repeated index */
    int mid = add_v(&s, 0.5, 0.5, 0);
    add_f(&s, a, mid, b);                                /* collinear: zero area */
    add_v(&s, 7, 7, 7);                                  /* used by no face */
    /* Fin: three triangles on edge PQ. */
    int p = add_v(&s, 5, 0, 0), q = add_v(&s, 5, 1, 0);
    add_f(&s, p, q, add_v(&s, 6, 0.5, 0));
    add_f(&s, q, p, add_v(&s, 4, 0.5, 0));
    add_f(&s, p, q, add_v(&s, 5, 0.5, 1));
    /* Bow-tie at B. */
    int B = add_v(&s, 10, 0, 0);
    add_f(&s, B, add_v(&s, 11, 0, 0), add_v(&s, 11, 1, 0));
    add_f(&s, B, add_v(&s, 9, 0, 0), add_v(&s, 9, -1, 0));
    return s;
}

static void test_soup(void)
{
    soup s = make_soup();
    neuv_mesh *in = soup_mesh(&s);
    neuv_mesh *m = mesh_clone(in);
    mesh_clean_report r;
    CHECK(mesh_clean(m, NULL, &r) == NEUV_OK);
    /* 27 soup vertices of the octahedron (24 + duplicate face 3) weld to 6;
     * a, b of the degenerate faces weld onto +x, +y. */
    CHECK_INT(r.welded_vertices, 21 + 2);
    CHECK_INT(r.degenerate_faces, 2);
    CHECK_INT(r.duplicate_faces, 1);
    CHECK_INT(r.unreferenced_vertices, 2); /* the midpoint and (7,7,7) */
    CHECK_INT(r.flipped_faces, 1);
    CHECK_INT(r.nonmanifold_edges, 1);
    CHECK_INT(r.nonmanifold_vertices, 1);
    CHECK_INT(r.split_vertices, 3);        /* P, Q for the third fin face; B */
    CHECK_INT(r.nonorientable_components, 0);
    CHECK_INT(m->nf, 8 + 3 + 2);
    CHECK_INT(m->nv, 6 + 7 + 6);
    CHECK(oriented_manifold(m));

    int *comp = malloc(sizeof(int) * (size_t)m->nf);
    CHECK_INT(mesh_face_components(m, comp), 5);
    component_topology t;
    CHECK(mesh_subset_topology(m, comp, comp[0], &t) == NEUV_OK);
    CHECK(t.closed); CHECK_INT(t.genus, 0); CHECK_INT(t.faces, 8);
    int octa[8], n = 0;
    for (int f = 0; f < m->nf; f++) if (comp[f] == comp[0]) octa[n++] = f;
    CHECK_NEAR(mesh_signed_volume(m, octa, n), 4.0 / 3.0, 1e-12); /* outward */
    free(comp);

    /* Each output corner's UV names an input corner at the same position,
     * and the UV corners of a face run in the face's order. */
    int uv_ok = 1;
    for (int c = 0; c < 3 * m->nf; c++) {
        int ic = (int)m->uv[2 * m->tri_uv[c]];
        const double *p = m->pos + 3 * m->tri[c], *q = in->pos + 3 * in->tri[ic];
        if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) uv_ok = 0;
        if (ic / 3 != (int)m->uv[2 * m->tri_uv[3 * (c / 3)]] / 3) uv_ok = 0;
    }
    CHECK(uv_ok);
    /* The flipped octahedron face (input face 5) came back with two corners swapped. */
    int found = 0;
    for (int f = 0; f < m->nf; f++)
        if ((int)m->uv[2 * m->tri_uv[3 * f]] / 3 == 5) {
            found = 1;
            CHECK_INT((int)m->uv[2 * m->tri_uv[3 * f + 1]], 17);
            CHECK_INT((int)m->uv[2 * m->tri_uv[3 * f + 2]], 16);
        }
    CHECK(found);

    /* Cleaning again gives the same mesh: the split copies weld back onto
     * their originals (same position) and are split off again. */
    neuv_mesh *again = mesh_clone(m);
    CHECK(mesh_clean(again, NULL, &r) == NEUV_OK);
    CHECK_INT(r.welded_vertices, 3); CHECK_INT(r.split_vertices, 3);
    CHECK_INT(r.degenerate_faces + r.duplicate_faces + r.unreferenced_vertices + r.flipped_faces, 0);
    CHECK(again->nf == m->nf && again->nv == m->nv);
    CHECK(!memcmp(again->tri, m->tri, sizeof(int) * 3 * (size_t)m->nf));
    mesh_free(again);

    /* Refusing non-manifold input: one-line error naming the edge (input
     * vertex numbers), mesh unchanged. */
    neuv_mesh *strict = mesh_clone(in);
    mesh_clean_options opts = {.split_nonmanifold = 0};
    CHECK(mesh_clean(strict, &opts, &r) == NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "non-manifold edge between vertices 31 and 32 (3 faces)") != NULL);
    CHECK_INT(strict->nv, in->nv);
    CHECK(!memcmp(strict->tri, in->tri, sizeof(int) * 3 * (size_t)in->nf));
    mesh_free(strict);
    mesh_free(m);
    mesh_free(in);

    /* The bow-tie alone is refused too. */
    soup b = {.nv = 0};
    int B = add_v(&b, 0, 0, 0);
    add_f(&b, B, add_v(&b, 1, 0, 0), add_v(&b, 1, 1, 0));
    add_f(&b, B, add_v(&b, -1, 0, 0), add_v(&b, -1, -1, 0));
    m = soup_mesh(&b);
    CHECK(mesh_clean(m, &opts, &r) == NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "non-manifold vertex 0") != NULL);
    mesh_free(m);
}

static void test_weld(void)
{
    neuv_mesh *m = mesh_create(5, 2, 0);
    const double p[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, -0.0, 0, 0, 1, 0, 0};
    const int t[6] = {0, 1, 2, 3, 2, 4};
    memcpy(m->pos, p, sizeof p);
    memcpy(m->tri, t, sizeof t);
    CHECK_INT(mesh_weld_positions(m), 2);
    CHECK_INT(m->nv, 3);
    CHECK_INT(m->tri[3], 0); CHECK_INT(m->tri[4], 2); CHECK_INT(m->tri[5], 1);
    CHECK_NEAR(m->pos[3], 1.0, 0); CHECK_NEAR(m->pos[7], 1.0, 0);
    mesh_free(m);
}

static void test_orientation(void)
{
    rng r;
    rng_seed(&r, 7);
    /* Random flips on a closed torus: all undone, closed => outward. */
    neuv_mesh *m = shape_torus(2, 0.5, 24, 12);
    neuv_mesh *ref = mesh_clone(m);
    int flipped = 0;
    for (int f = 0; f < m->nf; f++)
        if (rng_uniform(&r) < 0.3) {
            int x = m->tri[3 * f + 1]; m->tri[3 * f + 1] = m->tri[3 * f + 2]; m->tri[3 * f + 2] = x;
            flipped++;
        }
    mesh_clean_report rep;
    CHECK(mesh_clean(m, NULL, &rep) == NEUV_OK);
    CHECK_INT(rep.flipped_faces, flipped);
    CHECK(!memcmp(m->tri, ref->tri, sizeof(int) * 3 * (size_t)m->nf));
    mesh_free(m);

    /* An inside-out sphere is turned outward. */
    m = shape_icosphere(2, 1);
    for (int f = 0; f < m->nf; f++) { int x = m->tri[3 * f]; m->tri[3 * f] = m->tri[3 * f + 1]; m->tri[3 * f + 1] = x; }
    CHECK(mesh_signed_volume(m, NULL, 0) < 0);
    CHECK(mesh_clean(m, NULL, &rep) == NEUV_OK);
    CHECK_INT(rep.flipped_faces, m->nf);
    CHECK(mesh_signed_volume(m, NULL, 0) > 0);
    mesh_free(m);

    /* Open grid with a minority flipped: the majority wins. */
    m = shape_grid(4, 4, 1, 1, 1);
    for (int f = 0; f < 5; f++) {
        int x = m->tri[3 * f + 1]; m->tri[3 * f + 1] = m->tri[3 * f + 2]; m->tri[3 * f + 2] = x;
        x = m->tri_uv[3 * f + 1]; m->tri_uv[3 * f + 1] = m->tri_uv[3 * f + 2]; m->tri_uv[3 * f + 2] = x;
    }
    CHECK(mesh_clean(m, NULL, &rep) == NEUV_OK);
    CHECK_INT(rep.flipped_faces, 5);
    double n[3];
    int up = 1;
    for (int f = 0; f < m->nf; f++) { mesh_face_normal(m, f, n); if (n[2] < 0.5) up = 0; }
    CHECK(up);
    /* identity UVs are still identity after the flips */
    int uv_ok = 1;
    for (int c = 0; c < 3 * m->nf; c++)
        if (m->pos[3 * m->tri[c]] != m->uv[2 * m->tri_uv[c]]) uv_ok = 0;
    CHECK(uv_ok);
    mesh_free(m);
    mesh_free(ref);

    /* Moebius strip: counted, left as it is. */
    int N = 12;
    m = mesh_create(2 * N, 2 * N, 0);
    for (int i = 0; i < N; i++) {
        double u = 2 * 3.14159265358979 * i / N;
        for (int s = 0; s < 2; s++) {
            double w = s ? 0.3 : -0.3;
            double x = (1 + w * cos(u / 2)) * cos(u), y = (1 + w * cos(u / 2)) * sin(u), z = w * sin(u / 2);
            m->pos[3 * (2 * i + s)] = x; m->pos[3 * (2 * i + s) + 1] = y; m->pos[3 * (2 * i + s) + 2] = z;
        }
    }
    for (int i = 0; i < N; i++) {
        int a = 2 * i, b = 2 * i + 1, c, d;
        if (i + 1 < N) { c = 2 * (i + 1); d = c + 1; }
        else { c = 1; d = 0; } /* the half twist */
        int *t = m->tri + 6 * i;
        t[0] = a; t[1] = c; t[2] = d; t[3] = a; t[4] = d; t[5] = b;
    }
    neuv_mesh *before = mesh_clone(m);
    CHECK(mesh_clean(m, NULL, &rep) == NEUV_OK);
    CHECK_INT(rep.nonorientable_components, 1);
    CHECK_INT(rep.flipped_faces, 0);
    CHECK(!memcmp(m->tri, before->tri, sizeof(int) * 3 * (size_t)m->nf));
    component_topology t;
    CHECK(mesh_subset_topology(m, NULL, 0, &t) == NEUV_OK);
    CHECK_INT(t.boundary_loops, 1);
    CHECK_INT(t.euler, 0);
    mesh_free(before);
    mesh_free(m);
}

static void test_bad_input(void)
{
    neuv_mesh *m = mesh_create(3, 1, 0);
    m->tri[0] = 0; m->tri[1] = 1; m->tri[2] = 5;
    CHECK(mesh_clean(m, NULL, NULL) == NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "face 0 uses vertex 5") != NULL);
    mesh_free(m);
    /* No faces at all: fine, everything unreferenced. */
    m = mesh_create(4, 0, 0);
    mesh_clean_report r;
    CHECK(mesh_clean(m, NULL, &r) == NEUV_OK);
    CHECK_INT(m->nv, 0);
    mesh_free(m);
}

/* A face-by-face soup of a shape, shuffled: cleaning recovers the shape's
 * topology and area. */
static void test_shape_soup(void)
{
    neuv_mesh *s = shape_genus2(2);
    neuv_mesh *m = mesh_create(3 * s->nf, s->nf, 0);
    for (int c = 0; c < 3 * s->nf; c++) {
        memcpy(m->pos + 3 * c, s->pos + 3 * s->tri[c], sizeof(double) * 3);
        m->tri[c] = c;
    }
    mesh_clean_report r;
    CHECK(mesh_clean(m, NULL, &r) == NEUV_OK);
    CHECK_INT(m->nv, s->nv);
    CHECK_INT(r.welded_vertices, 3 * s->nf - s->nv);
    component_topology t;
    CHECK(mesh_subset_topology(m, NULL, 0, &t) == NEUV_OK);
    CHECK_INT(t.genus, 2); CHECK(t.closed);
    CHECK_NEAR(mesh_total_area(m), 50.0, 1e-9);
    mesh_free(m);
    mesh_free(s);
}

int main(void)
{
    test_soup();
    test_weld();
    test_orientation();
    test_bad_input();
    test_shape_soup();
    return check_report("test_clean");
}
