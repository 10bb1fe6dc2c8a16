/* Topology: components, Euler characteristic, genus and ordered boundary
 * loops of whole meshes and of face subsets. */
#include <stdlib.h>
#include <string.h>

#include "check.h"

#include "mesh/shapes.h"
#include "mesh/edge_faces.h"
#include "mesh/seam_cut.h"
#include "mesh/topology.h"

/* 1 when loop[0..n) is a closed chain of boundary edges, each running in the
 * direction of the face that owns it (a -> b appears in some face). */
static int loop_follows_faces(const neuv_mesh *m, const int *face_label, int label, const int *loop, int n)
{
    for (int i = 0; i < n; i++) {
        int a = loop[i], b = loop[(i + 1) % n], found = 0;
        for (int f = 0; f < m->nf && !found; f++) {
            if (face_label && face_label[f] != label) continue;
            for (int k = 0; k < 3; k++)
                if (m->tri[3 * f + k] == a && m->tri[3 * f + (k + 1) % 3] == b) found = 1;
        }
        if (!found) return 0;
    }
    return 1;
}

static void test_grid(void)
{
    int nx = 6, ny = 4;
    neuv_mesh *m = shape_grid(nx, ny, 3, 2, 0);
    int *start, *verts;
    int n = mesh_boundary_loops(m, NULL, 0, &start, &verts);
    CHECK_INT(n, 1);
    CHECK_INT(start[0], 0);
    CHECK_INT(start[1], 2 * (nx + ny));
    CHECK(loop_follows_faces(m, NULL, 0, verts, start[1]));
    /* Counter-clockwise faces seen from +z: the loop encloses positive area. */
    double area = 0;
    int len = start[1];
    for (int i = 0; i < len; i++) {
        const double *p = m->pos + 3 * verts[i], *q = m->pos + 3 * verts[(i + 1) % len];
        area += 0.5 * (p[0] * q[1] - p[1] * q[0]);
    }
    CHECK_NEAR(area, 6.0, 1e-12);
    /* No vertex twice, every vertex on the border of the rectangle. */
    int ok = 1;
    for (int i = 0; i < len; i++) {
        const double *p = m->pos + 3 * verts[i];
        if (!(p[0] == 0 || p[0] == 3 || p[1] == 0 || p[1] == 2)) ok = 0;
        for (int j = 0; j < i; j++) if (verts[j] == verts[i]) ok = 0;
    }
    CHECK(ok);
    free(start); free(verts);

    /* Two cells touching at a corner: two loops through the shared vertex. */
    int *label = calloc((size_t)m->nf, sizeof(int));
    /* cells (0,0) and (1,1): faces 0,1 and 2*(nx+1)+0,1 */
    label[0] = label[1] = 1;
    label[2 * (nx + 1)] = label[2 * (nx + 1) + 1] = 1;
    component_topology t;
    CHECK(mesh_subset_topology(m, label, 1, &t) == NEUV_OK);
    CHECK_INT(t.faces, 4); CHECK_INT(t.vertices, 7); CHECK_INT(t.edges, 10);
    CHECK_INT(t.boundary_loops, 2);
    n = mesh_boundary_loops(m, label, 1, &start, &verts);
    CHECK_INT(n, 2);
    CHECK_INT(start[1] - start[0], 4); CHECK_INT(start[2] - start[1], 4);
    CHECK(loop_follows_faces(m, label, 1, verts + start[0], 4));
    CHECK(loop_follows_faces(m, label, 1, verts + start[1], 4));
    free(start); free(verts);
    /* The rest of the grid: cell (1,1) is a hole whose rim touches the
     * outer rim at vertex (1,1). Loops are traced through each fan there,
     * so they join into one loop passing (1,1) twice; Euler counts the
     * vertex once (0), so the pinched region is not mistaken for a disk. */
    CHECK(mesh_subset_topology(m, label, 0, &t) == NEUV_OK);
    CHECK_INT(t.faces, m->nf - 4);
    CHECK_INT(t.vertices, (nx + 1) * (ny + 1) - 1);
    CHECK_INT(t.boundary_loops, 1); CHECK_INT(t.euler, 0);
    n = mesh_boundary_loops(m, label, 0, &start, &verts);
    CHECK_INT(n, 1);
    CHECK_INT(start[1], 2 * (nx + ny) + 4);
    CHECK(loop_follows_faces(m, label, 0, verts, start[1]));
    free(start); free(verts);
    free(label);
    mesh_free(m);
}

static void test_cylinder(void)
{
    int slices = 20, stacks = 5;
    neuv_mesh *m = shape_cylinder(1, 2, slices, stacks);
    int *start, *verts;
    int n = mesh_boundary_loops(m, NULL, 0, &start, &verts);
    CHECK_INT(n, 2);
    for (int l = 0; l < n; l++) {
        int len = start[l + 1] - start[l];
        CHECK_INT(len, slices);
        CHECK(loop_follows_faces(m, NULL, 0, verts + start[l], len));
        /* all vertices of a loop at one height, the loop is one of the rims */
        double z = m->pos[3 * verts[start[l]] + 2];
        int same = 1;
        for (int i = start[l]; i < start[l + 1]; i++) if (m->pos[3 * verts[i] + 2] != z) same = 0;
        CHECK(same);
        CHECK_NEAR(fabs(z), 1.0, 1e-12);
    }
    CHECK(m->pos[3 * verts[start[0]] + 2] != m->pos[3 * verts[start[1]] + 2]);
    free(start); free(verts);
    component_topology t;
    CHECK(mesh_subset_topology(m, NULL, 0, &t) == NEUV_OK);
    CHECK_INT(t.euler, 0); CHECK_INT(t.genus, 0); CHECK_INT(t.boundary_loops, 2);
    CHECK_INT(t.edges, slices * (3 * stacks + 1));
    mesh_free(m);
}

static void test_sphere_and_torus(void)
{
    /* Northern hemisphere of a UV sphere: a disk. */
    neuv_mesh *m = shape_uv_sphere(24, 12, 1);
    int *label = malloc(sizeof(int) * (size_t)m->nf);
    int half = 0;
    for (int f = 0; f < m->nf; f++) {
        double z = 0;
        for (int k = 0; k < 3; k++) z += m->pos[3 * m->tri[3 * f + k] + 2];
        label[f] = z > 0 ? 3 : 4;
        half += label[f] == 3;
    }
    component_topology t;
    CHECK(mesh_subset_topology(m, label, 3, &t) == NEUV_OK);
    CHECK_INT(t.faces, half);
    CHECK_INT(t.boundary_loops, 1); CHECK_INT(t.genus, 0); CHECK_INT(t.euler, 1); CHECK(!t.closed);
    CHECK_INT(t.vertices, 1 + 6 * 24);
    /* The explicit face list gives the same answer. */
    int *faces = malloc(sizeof(int) * (size_t)half), n = 0;
    for (int f = 0; f < m->nf; f++) if (label[f] == 3) faces[n++] = f;
    component_topology t2;
    CHECK(mesh_faces_topology(m, faces, n, &t2) == NEUV_OK);
    CHECK(!memcmp(&t, &t2, sizeof t));
    int *start, *verts;
    CHECK_INT(mesh_faces_boundary_loops(m, faces, n, &start, &verts), 1);
    CHECK_INT(start[1], 24);
    free(start); free(verts);
    free(faces);
    CHECK(mesh_subset_topology(m, NULL, 0, &t) == NEUV_OK);
    CHECK_INT(t.euler, 2); CHECK(t.closed);
    /* Empty subset. */
    CHECK(mesh_subset_topology(m, label, 99, &t) == NEUV_OK);
    CHECK_INT(t.faces, 0); CHECK_INT(t.vertices, 0); CHECK_INT(t.boundary_loops, 0);
    free(label);
    mesh_free(m);

    /* Torus: Euler 0, genus 1; half of it (u < pi) is an annulus. */
    m = shape_torus(3, 1, 32, 16);
    CHECK(mesh_subset_topology(m, NULL, 0, &t) == NEUV_OK);
    CHECK_INT(t.euler, 0); CHECK_INT(t.genus, 1); CHECK(t.closed);
    CHECK_INT(t.vertices, 32 * 16); CHECK_INT(t.edges, 3 * 32 * 16);
    label = malloc(sizeof(int) * (size_t)m->nf);
    for (int f = 0; f < m->nf; f++) label[f] = f < m->nf / 2;
    CHECK(mesh_subset_topology(m, label, 1, &t) == NEUV_OK);
    CHECK_INT(t.boundary_loops, 2); CHECK_INT(t.genus, 0); CHECK_INT(t.euler, 0);
    free(label);
    mesh_free(m);

    /* Components: three shapes in one mesh. */
    neuv_mesh *a = shape_icosphere(1, 1), *b = shape_torus(2, 0.5, 8, 6), *c = shape_grid(2, 2, 1, 1, 0);
    m = mesh_create(a->nv + b->nv + c->nv, a->nf + b->nf + c->nf, 0);
    memcpy(m->pos, a->pos, sizeof(double) * 3 * (size_t)a->nv);
    memcpy(m->pos + 3 * a->nv, b->pos, sizeof(double) * 3 * (size_t)b->nv);
    memcpy(m->pos + 3 * (a->nv + b->nv), c->pos, sizeof(double) * 3 * (size_t)c->nv);
    /* interleave: grid faces first, then sphere, then torus */
    int f = 0;
    for (int i = 0; i < c->nf; i++, f++) for (int k = 0; k < 3; k++) m->tri[3 * f + k] = c->tri[3 * i + k] + a->nv + b->nv;
    for (int i = 0; i < a->nf; i++, f++) for (int k = 0; k < 3; k++) m->tri[3 * f + k] = a->tri[3 * i + k];
    for (int i = 0; i < b->nf; i++, f++) for (int k = 0; k < 3; k++) m->tri[3 * f + k] = b->tri[3 * i + k] + a->nv;
    int *comp = malloc(sizeof(int) * (size_t)m->nf);
    CHECK_INT(mesh_face_components(m, comp), 3);
    CHECK_INT(comp[0], 0); CHECK_INT(comp[c->nf], 1); CHECK_INT(comp[m->nf - 1], 2);
    CHECK(mesh_subset_topology(m, comp, 2, &t) == NEUV_OK);
    CHECK_INT(t.genus, 1); CHECK_INT(t.faces, b->nf);
    CHECK(mesh_subset_topology(m, comp, 1, &t) == NEUV_OK);
    CHECK_INT(t.genus, 0); CHECK(t.closed); CHECK_INT(t.vertices, a->nv);
    CHECK(mesh_subset_topology(m, comp, 0, &t) == NEUV_OK);
    CHECK_INT(t.boundary_loops, 1); CHECK_INT(t.euler, 1);
    free(comp);
    mesh_free(a); mesh_free(b); mesh_free(c); mesh_free(m);
}

static void test_genus2(void)
{
    neuv_mesh *m = shape_genus2(2);
    component_topology t;
    CHECK(mesh_subset_topology(m, NULL, 0, &t) == NEUV_OK);
    CHECK_INT(t.genus, 2); CHECK_INT(t.euler, -2);
    /* The top face (z = 0.5) alone: a rectangle with two holes, 3 loops. */
    int *label = malloc(sizeof(int) * (size_t)m->nf);
    for (int f = 0; f < m->nf; f++) {
        int top = 1;
        for (int k = 0; k < 3; k++) if (m->pos[3 * m->tri[3 * f + k] + 2] != 0.5) top = 0;
        label[f] = top;
    }
    CHECK(mesh_subset_topology(m, label, 1, &t) == NEUV_OK);
    CHECK_INT(t.boundary_loops, 3); CHECK_INT(t.genus, 0); CHECK_INT(t.euler, -1);
    free(label);
    mesh_free(m);
}

/* Seams: a cube's 12 edges are its only edges above any angle in (0, 90)
 * and none above 90; cut along them it falls into its six sides, each a
 * disk of (n+1)^2 vertices; joined again it is the cube. A user pair given
 * by positions finds its edge; a pair that is no edge is counted. */
static void test_seam_cut(void)
{
    int n = 5;
    neuv_mesh *m = shape_cube(n);
    edge_faces ef;
    CHECK(edge_faces_build(&ef, m) == 0);
    unsigned char *seam = calloc((size_t)ef.ne, 1);
    CHECK_INT(seam_mark_angle(m, &ef, 89.9, seam), 12 * n);
    CHECK_INT(seam_mark_angle(m, &ef, 1.0, seam), 0); /* already marked: nothing new, faces are flat */
    unsigned char *none = calloc((size_t)ef.ne, 1);
    CHECK_INT(seam_mark_angle(m, &ef, 90.1, none), 0);
    neuv_mesh *cut = NULL;
    int *origin = NULL;
    CHECK(mesh_cut_seams(m, &ef, seam, &cut, &origin) == NEUV_OK);
    CHECK_INT(cut->nv, 6 * (n + 1) * (n + 1));
    CHECK_INT(cut->nf, m->nf);
    int *comp = malloc(sizeof(int) * (size_t)cut->nf);
    CHECK_INT(mesh_face_components(cut, comp), 6);
    for (int c = 0; c < 6; c++) {
        component_topology t;
        int f = 0;
        while (comp[f] != c) f++;
        CHECK(mesh_subset_topology(cut, comp, c, &t) == NEUV_OK);
        CHECK(t.euler == 1 && t.boundary_loops == 1);
        CHECK_INT(t.vertices, (n + 1) * (n + 1));
    }
    for (int v = 0; v < cut->nv; v++)
        CHECK(!memcmp(cut->pos + 3 * v, m->pos + 3 * origin[v], sizeof(double) * 3));
    mesh_join_seams(cut, origin, m->nv);
    CHECK_INT(cut->nv, m->nv);
    CHECK(!memcmp(cut->tri, m->tri, sizeof(int) * 3 * (size_t)m->nf));

    /* By positions: the first edge of the cube's first face, and a pair of
     * two vertices that share no edge (opposite corners of the cube). */
    memset(seam, 0, (size_t)ef.ne);
    double ends[12];
    int a = m->tri[0], b = m->tri[1];
    memcpy(ends, m->pos + 3 * a, sizeof(double) * 3);
    memcpy(ends + 3, m->pos + 3 * b, sizeof(double) * 3);
    double far0[3] = {-1, -1, -1}, far1[3] = {1, 1, 1};
    memcpy(ends + 6, far0, sizeof far0);
    memcpy(ends + 9, far1, sizeof far1);
    int unmatched = -1;
    CHECK_INT(seam_mark_positions(m, &ef, ends, 2, seam, &unmatched), 1);
    CHECK_INT(unmatched, 1);
    CHECK_INT(seam[ef.face_edge[0]], 1);
    free(comp);
    free(origin);
    free(seam);
    free(none);
    mesh_free(cut);
    edge_faces_free(&ef);
    mesh_free(m);
}

int main(void)
{
    test_grid();
    test_cylinder();
    test_sphere_and_torus();
    test_genus2();
    test_seam_cut();
    return check_report("test_topology");
}
