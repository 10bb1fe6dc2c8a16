/* OBJ output: positions (with the file's vertex colours), the atlas's UVs,
 * the file's normals, and faces with what the file said about them: its
 * material library and materials, its o / g / s statements, and its
 * polygons, each written back as one polygon when its corners agree (one
 * UV and one normal per corner), else as its triangles. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/json_writer.h"
#include "core/log.h"
#include "io/mesh_io.h"
#include "mesh/mesh_attributes.h"

/* A triangle corner c has the same vertex, UV and normal as corner d. */
static int same_corner(const neuv_mesh *m, int c, int d)
{
    if (m->tri[c] != m->tri[d]) return 0;
    if (m->tri_uv && m->nuv > 0 && m->tri_uv[c] != m->tri_uv[d]) return 0;
    if (m->tri_normal && m->nn > 0 && m->tri_normal[c] != m->tri_normal[d]) return 0;
    return 1;
}

/* Polygon p can be written as one face: every triangle corner of it is the
 * same as the polygon corner at its vertex. */
static int polygon_whole(const neuv_mesh *m, int p, int first_face)
{
    int c0 = m->poly_start[p], c1 = m->poly_start[p + 1];
    for (int c = c0; c < c1; c++)
        if (m->poly_corner[c] < 0) return 0;
    for (int f = first_face; f < m->nf && m->face_polygon[f] == p; f++)
        for (int k = 0; k < 3; k++) {
            int tc = 3 * f + k, found = 0;
            for (int c = c0; c < c1 && !found; c++)
                if (m->tri[m->poly_corner[c]] == m->tri[tc]) {
                    if (!same_corner(m, m->poly_corner[c], tc)) return 0;
                    found = 1;
                }
            if (!found) return 0;
        }
    return 1;
}

static void write_corner(const neuv_mesh *m, int c, FILE *fp)
{
    int with_uv = m->nuv > 0 && m->tri_uv, with_n = m->nn > 0 && m->tri_normal;
    fprintf(fp, " %d", m->tri[c] + 1);
    if (with_uv && with_n) fprintf(fp, "/%d/%d", m->tri_uv[c] + 1, m->tri_normal[c] + 1);
    else if (with_uv) fprintf(fp, "/%d", m->tri_uv[c] + 1);
    else if (with_n) fprintf(fp, "//%d", m->tri_normal[c] + 1);
}

/* Shortest decimal that reads back to the same float (colours are kept as
 * floats, so 0.2 goes out as 0.2, not 0.200000003). */
static void format_float_exact(char *buf, size_t n, float x)
{
    for (int digits = 1; digits <= 9; digits++) {
        snprintf(buf, n, "%.*g", digits, (double)x);
        if ((float)strtod(buf, NULL) == x) return;
    }
}

/* The o / g / s statements that take the group state from `was` to `now`. */
static void write_group_change(const obj_group_state *was, const obj_group_state *now, FILE *fp)
{
    if (now->object && !attr_same_text(was ? was->object : NULL, now->object)) fprintf(fp, "o %s\n", now->object);
    if (now->group && !attr_same_text(was ? was->group : NULL, now->group)) fprintf(fp, "g %s\n", now->group);
    if (now->smooth && !attr_same_text(was ? was->smooth : NULL, now->smooth)) fprintf(fp, "s %s\n", now->smooth);
}

static void write_material(const neuv_mesh *m, int k, FILE *fp)
{
    const mesh_attributes *a = m->attr;
    if (a && k < a->n_materials && a->material_name && a->material_name[k]) fprintf(fp, "usemtl %s\n", a->material_name[k]);
    else if (!(a && k < a->n_materials)) fprintf(fp, "usemtl material%d\n", k); /* materials without names (glTF) */
    /* else the faces before the file's first usemtl: nothing to say */
}

/* Faces in order: each statement that changes before a face, then the
 * face. Returns the polygons written as their triangles. */
static int write_faces(const neuv_mesh *m, FILE *fp)
{
    const mesh_attributes *a = m->attr;
    const int *group = a && a->face_group ? a->face_group : NULL;
    int material = -1, g = -1, split = 0;
    for (int f = 0; f < m->nf; f++) {
        if (group && group[f] >= 0 && group[f] != g) {
            write_group_change(g >= 0 ? &a->groups[g] : NULL, &a->groups[group[f]], fp);
            g = group[f];
        }
        if (m->face_material && m->face_material[f] != material) {
            material = m->face_material[f];
            write_material(m, material, fp);
        }
        int p = m->np > 0 ? m->face_polygon[f] : -1;
        if (p >= 0 && (f == 0 || m->face_polygon[f - 1] != p)) {
            int n = 0;
            while (f + n < m->nf && m->face_polygon[f + n] == p) n++;
            if (m->poly_start[p + 1] - m->poly_start[p] > 3 && polygon_whole(m, p, f)) {
                fputs("f", fp);
                for (int c = m->poly_start[p]; c < m->poly_start[p + 1]; c++) write_corner(m, m->poly_corner[c], fp);
                fputs("\n", fp);
                f += n - 1;
                continue;
            }
            split += m->poly_start[p + 1] - m->poly_start[p] > 3;
        }
        fputs("f", fp);
        for (int k = 0; k < 3; k++) write_corner(m, 3 * f + k, fp);
        fputs("\n", fp);
    }
    return split;
}

neuv_status io_write_obj(const neuv_mesh *m, FILE *fp)
{
    const mesh_attributes *a = m->attr;
    if (a && a->nuv0 > 0)
        return error_set(NEUV_ERR_INPUT, "OBJ holds one UV set; a second one (uv channel 1) needs .ply, .glb or .gltf");
    fprintf(fp, "# neuv %s: %d vertices, %d faces%s\n", neuv_version(), m->nv, m->nf,
            m->nuv > 0 ? ", per-corner UVs" : "");
    if (a && a->material_library) fprintf(fp, "mtllib %s\n", a->material_library);
    char x[32], y[32], z[32];
    /* Shortest decimal that reads back to the same double: a round trip
     * through OBJ keeps positions bit for bit. */
    int colors = a && a->color && a->color_channels >= 3;
    for (int v = 0; v < m->nv; v++) {
        const double *p = m->pos + 3 * (size_t)v;
        format_double_exact(x, p[0]);
        format_double_exact(y, p[1]);
        format_double_exact(z, p[2]);
        fprintf(fp, "v %s %s %s", x, y, z);
        if (colors) {
            const float *c = a->color + (size_t)a->color_channels * (size_t)v;
            for (int k = 0; k < 3; k++) {
                format_float_exact(x, sizeof x, c[k]);
                fprintf(fp, " %s", x);
            }
        }
        fputs("\n", fp);
    }
    if (m->nuv > 0 && m->tri_uv)
        for (int t = 0; t < m->nuv; t++) {
            format_double_exact(x, m->uv[2 * (size_t)t]);
            format_double_exact(y, m->uv[2 * (size_t)t + 1]);
            fprintf(fp, "vt %s %s\n", x, y);
        }
    if (m->nn > 0 && m->tri_normal)
        for (int n = 0; n < m->nn; n++) {
            const double *p = m->normal + 3 * (size_t)n;
            format_double_exact(x, p[0]);
            format_double_exact(y, p[1]);
            format_double_exact(z, p[2]);
            fprintf(fp, "vn %s %s %s\n", x, y, z);
        }
    int split = write_faces(m, fp);
    if (split > 0)
        log_message(NEUV_LOG_WARN, "%d polygon%s written as %s triangles: a UV seam runs through %s", split,
                    split == 1 ? "" : "s", split == 1 ? "its" : "their", split == 1 ? "it" : "them");
    return ferror(fp) ? error_set(NEUV_ERR_IO, "write failed (disk full?)") : NEUV_OK;
}
