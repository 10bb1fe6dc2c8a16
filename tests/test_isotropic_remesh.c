/* Isotropic remeshing (CGAL behind a C interface): a sphere towards twice
 * its faces stays on the input surface with edges near the target and
 * vertices of its own; a cube keeps its 12 edges and 8 corners exactly; a
 * flat grid keeps its boundary; bad inputs give NEUV_ERR_INPUT. */
#include "check.h"
#include "mesh/edge_faces.h"
#include "mesh/shapes.h"
#include "mesh/signed_volume.h"
#include "mesh/topology.h"
#include "remesh/isotropic_remesh.h"
#include "spatial/bvh.h"
#include "surface_distance.h"


static double edge_length(const neuv_mesh *m, int a, int b)
{
    const double *p = m->pos + 3 * a, *q = m->pos + 3 * b;
    return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

/* 1 when every edge of m has exactly two faces (a closed surface). */
static int is_closed(const neuv_mesh *m)
{
    edge_faces ef;
    if (edge_faces_build(&ef, m)) return 0;
    int ok = 1;
    for (int e = 0; e < ef.ne; e++) ok &= edge_faces_count(&ef, e) == 2;
    edge_faces_free(&ef);
    return ok;
}

static double mean_edge_length(const neuv_mesh *m)
{
    edge_faces ef;
    if (edge_faces_build(&ef, m)) return 0;
    double sum = 0;
    for (int e = 0; e < ef.ne; e++) sum += edge_length(m, ef.edge_v[2 * e], ef.edge_v[2 * e + 1]);
    int ne = ef.ne;
    edge_faces_free(&ef);
    return ne ? sum / ne : 0;
}

/* Output vertices at exactly the position of an input vertex. */
static int shared_vertices(const neuv_mesh *in, const neuv_mesh *out)
{
    int shared = 0;
    for (int v = 0; v < out->nv; v++)
        for (int u = 0; u < in->nv; u++)
            if (!memcmp(out->pos + 3 * v, in->pos + 3 * u, sizeof(double) * 3)) { shared++; break; }
    return shared;
}

static void test_sphere(void)
{
    neuv_mesh *ico = shape_icosphere(3, 1.0); /* 1280 faces */
    isotropic_options o;
    isotropic_report rep;
    isotropic_default_options(&o);
    o.target_faces = 2 * ico->nf;
    neuv_mesh *r = NULL;
    CHECK_INT(mesh_remesh_isotropic(ico, &o, &r, &rep), NEUV_OK);
    if (!r) { mesh_free(ico); return; }
    printf("sphere: %d -> %d faces, L %.4f, %d rounds, max distance %.3g\n", rep.faces_in, rep.faces_out,
           rep.edge_length, rep.rounds, rep.max_distance);
    CHECK_INT(rep.faces_in, ico->nf);
    CHECK_INT(rep.faces_out, r->nf);
    CHECK(abs(r->nf - o.target_faces) <= 0.25 * o.target_faces);
    CHECK(rep.rounds >= 1 && rep.rounds <= 3);
    CHECK_INT(r->nuv, 0);
    /* Projected onto the faceted input: on it up to rounding, so inside the
     * unit sphere by at most the facets' sag. */
    double dev = max_deviation(ico, r);
    CHECK(dev < 1e-6);
    CHECK(rep.max_distance < 1e-6);
    CHECK_NEAR(rep.max_distance, dev, 1e-12);
    double plane_min = 1;
    for (int f = 0; f < ico->nf; f++) {
        double n[3];
        mesh_face_normal(ico, f, n);
        const double *a = ico->pos + 3 * ico->tri[3 * f];
        plane_min = fmin(plane_min, fabs(n[0] * a[0] + n[1] * a[1] + n[2] * a[2]));
    }
    double rmin = INFINITY, rmax = 0;
    for (int v = 0; v < r->nv; v++) {
        const double *p = r->pos + 3 * v;
        double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        rmin = fmin(rmin, len);
        rmax = fmax(rmax, len);
    }
    CHECK(rmax <= 1 + 1e-9);
    CHECK(rmin >= plane_min - 1e-9);
    CHECK(fabs(mean_edge_length(r) - rep.edge_length) <= 0.2 * rep.edge_length);
    /* Independence: (almost) no vertex where an input vertex was. */
    CHECK(shared_vertices(ico, r) <= 0.05 * r->nv);
    CHECK(is_closed(r));
    component_topology t;
    CHECK_INT(mesh_subset_topology(r, NULL, 0, &t), NEUV_OK);
    CHECK_INT(t.euler, 2);
    /* Faces still point outward, volume kept. */
    double vin = mesh_signed_volume(ico, NULL, 0), vout = mesh_signed_volume(r, NULL, 0);
    CHECK(vout > 0 && fabs(vout - vin) < 0.01 * vin);
    CHECK_INT(rep.feature_edges_in, 0);
    CHECK_INT(rep.corners, 0);

    /* Same input, same output. */
    neuv_mesh *r2 = NULL;
    CHECK_INT(mesh_remesh_isotropic(ico, &o, &r2, NULL), NEUV_OK);
    CHECK(r2 && r2->nv == r->nv && r2->nf == r->nf &&
          !memcmp(r2->pos, r->pos, sizeof(double) * 3 * r->nv) && !memcmp(r2->tri, r->tri, sizeof(int) * 3 * r->nf));
    mesh_free(r2);
    mesh_free(r);
    mesh_free(ico);
}

/* Which of the cube's 12 edge lines p lies on (two coordinates at +-1), or -1. */
static int cube_edge(const double *p)
{
    int at[3], n = 0;
    for (int i = 0; i < 3; i++) { at[i] = fabs(fabs(p[i]) - 1) < 1e-12; n += at[i]; }
    if (n != 2) return -1;
    int free_axis = !at[0] ? 0 : !at[1] ? 1 : 2;
    int a = (free_axis + 1) % 3, b = (free_axis + 2) % 3;
    return 4 * free_axis + 2 * (p[a] > 0) + (p[b] > 0);
}

static void test_cube(void)
{
    neuv_mesh *cube = shape_cube(4); /* [-1,1]^3, 192 faces, edges of 0.5 */
    isotropic_options o;
    isotropic_report rep;
    isotropic_default_options(&o);
    o.target_edge_length = 0.2;
    neuv_mesh *r = NULL;
    CHECK_INT(mesh_remesh_isotropic(cube, &o, &r, &rep), NEUV_OK);
    if (!r) { mesh_free(cube); return; }
    printf("cube: %d -> %d faces, %d feature edges in, %d out, %d corners, max distance %.3g\n", rep.faces_in,
           rep.faces_out, rep.feature_edges_in, rep.feature_edges_out, rep.corners, rep.max_distance);
    CHECK_INT(rep.rounds, 1);
    CHECK_NEAR(rep.edge_length, 0.2, 0);
    CHECK_INT(rep.feature_edges_in, 12 * 4);
    CHECK_INT(rep.corners, 8);
    CHECK(rep.feature_edges_out >= 12 * 8); /* 2 / 0.2 = 10 segments per edge, give or take */
    CHECK(max_deviation(cube, r) < 1e-9);
    /* The 8 corners, each exactly once. */
    for (int c = 0; c < 8; c++) {
        double corner[3] = {c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1};
        int found = 0;
        for (int v = 0; v < r->nv; v++) found += !memcmp(r->pos + 3 * v, corner, sizeof corner);
        CHECK_INT(found, 1);
    }
    /* The 12 edges are polylines of the output: vertices on every edge line,
     * and the output edges along them add up to the cube's 24. */
    int on_line[12] = {0}, on_lines = 0;
    for (int v = 0; v < r->nv; v++) {
        int e = cube_edge(r->pos + 3 * v);
        if (e >= 0) { on_line[e]++; on_lines++; }
    }
    CHECK(on_lines > 0);
    for (int e = 0; e < 12; e++) CHECK(on_line[e] >= 5);
    edge_faces ef;
    CHECK_INT(edge_faces_build(&ef, r), 0);
    double along = 0;
    for (int e = 0; e < ef.ne; e++) {
        int a = ef.edge_v[2 * e], b = ef.edge_v[2 * e + 1];
        /* Inside the cube a coordinate of the midpoint is +-1 only when it is at both ends. */
        double mid[3];
        for (int i = 0; i < 3; i++) mid[i] = 0.5 * (r->pos[3 * a + i] + r->pos[3 * b + i]);
        if (cube_edge(mid) >= 0) along += edge_length(r, a, b);
    }
    edge_faces_free(&ef);
    CHECK_NEAR(along, 24, 1e-9);
    CHECK_NEAR(mesh_total_area(r), 24, 0.01 * 24);
    CHECK(is_closed(r));
    /* Input vertices survive only on the edges, where an even split of the
     * input's segments puts a vertex right back. */
    int shared_inside = 0;
    for (int v = 0; v < r->nv; v++)
        for (int u = 0; u < cube->nv; u++)
            if (!memcmp(r->pos + 3 * v, cube->pos + 3 * u, sizeof(double) * 3) && cube_edge(r->pos + 3 * v) < 0) {
                int corner = 1;
                for (int i = 0; i < 3; i++) corner &= fabs(r->pos[3 * v + i]) == 1;
                shared_inside += !corner;
            }
    CHECK_INT(shared_inside, 0);
    CHECK(mesh_signed_volume(r, NULL, 0) > 7.9);
    mesh_free(r);
    mesh_free(cube);
}

/* An open flat grid with UVs: the boundary stays, the UVs go. */
static void test_grid(void)
{
    neuv_mesh *g = shape_grid(8, 6, 2.0, 1.5, 1);
    isotropic_options o;
    isotropic_report rep;
    isotropic_default_options(&o);
    o.target_edge_length = 0.1;
    neuv_mesh *r = NULL;
    CHECK_INT(mesh_remesh_isotropic(g, &o, &r, &rep), NEUV_OK);
    if (!r) { mesh_free(g); return; }
    CHECK_INT(r->nuv, 0);
    CHECK(r->uv == NULL && r->tri_uv == NULL);
    CHECK_NEAR(mesh_total_area(r), 3.0, 1e-9);
    double lo[3], hi[3];
    mesh_bounding_box(r, lo, hi);
    CHECK(lo[0] == 0 && lo[1] == 0 && hi[0] == 2.0 && hi[1] == 1.5 && lo[2] == 0 && hi[2] == 0);
    CHECK_INT(rep.corners, 4);
    component_topology t;
    CHECK_INT(mesh_subset_topology(r, NULL, 0, &t), NEUV_OK);
    CHECK_INT(t.boundary_loops, 1);
    CHECK_INT(t.euler, 1);
    /* Every face keeps the input's orientation (+z). */
    int up = 0;
    for (int f = 0; f < r->nf; f++) {
        double n[3];
        mesh_face_normal(r, f, n);
        up += n[2] > 0.99;
    }
    CHECK_INT(up, r->nf);
    CHECK(fabs(r->nf - 3.0 * 4 / (sqrt(3) * 0.01)) < 0.3 * r->nf);
    mesh_free(r);
    mesh_free(g);
}

static void test_errors(void)
{
    isotropic_options o;
    isotropic_default_options(&o);
    neuv_mesh *r = (neuv_mesh *)1;
    neuv_mesh *ico = shape_icosphere(1, 1.0);
    /* No target. */
    CHECK_INT(mesh_remesh_isotropic(ico, &o, &r, NULL), NEUV_ERR_INPUT);
    CHECK(r == NULL);
    CHECK_INT(mesh_remesh_isotropic(ico, NULL, &r, NULL), NEUV_ERR_INPUT);
    o.target_edge_length = -1;
    CHECK_INT(mesh_remesh_isotropic(ico, &o, &r, NULL), NEUV_ERR_INPUT);
    o.target_edge_length = 0;
    o.target_faces = 3;
    CHECK_INT(mesh_remesh_isotropic(ico, &o, &r, NULL), NEUV_ERR_INPUT);
    /* A target needing billions of faces is refused, not attempted. */
    o.target_edge_length = 1e-6;
    CHECK_INT(mesh_remesh_isotropic(ico, &o, &r, NULL), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "faces") != NULL);
    o.target_edge_length = 0.3;

    /* Three faces on one edge. */
    neuv_mesh *fin = mesh_create(5, 3, 0);
    const double fp[15] = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1};
    const int ft[9] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    memcpy(fin->pos, fp, sizeof fp);
    memcpy(fin->tri, ft, sizeof ft);
    CHECK_INT(mesh_remesh_isotropic(fin, &o, &r, NULL), NEUV_ERR_INPUT);
    CHECK(r == NULL);
    CHECK(strstr(neuv_last_error(), "manifold") != NULL);
    CHECK(strchr(neuv_last_error(), '\n') == NULL);
    /* Two faces of opposite orientation. */
    fin->nf = 2;
    fin->tri[3] = 0; fin->tri[4] = 1; fin->tri[5] = 3;
    CHECK_INT(mesh_remesh_isotropic(fin, &o, &r, NULL), NEUV_ERR_INPUT);
    /* A repeated vertex, an index out of range. */
    fin->tri[3] = 1; fin->tri[4] = 1; fin->tri[5] = 3;
    CHECK_INT(mesh_remesh_isotropic(fin, &o, &r, NULL), NEUV_ERR_INPUT);
    fin->tri[3] = 1; fin->tri[4] = 0; fin->tri[5] = 7;
    CHECK_INT(mesh_remesh_isotropic(fin, &o, &r, NULL), NEUV_ERR_INPUT);
    /* No faces. */
    fin->nf = 0;
    CHECK_INT(mesh_remesh_isotropic(fin, &o, &r, NULL), NEUV_ERR_INPUT);
    CHECK(r == NULL);
    mesh_free(fin);
    mesh_free(ico);
}

int main(void)
{
    test_sphere();
    test_cube();
    test_grid();
    test_errors();
    return check_report("test_isotropic_remesh");
}
