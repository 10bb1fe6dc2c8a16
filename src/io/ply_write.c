/* Binary little-endian PLY writer. Vertices are split only where a corner's
 * UV, normal or first-set UV differs (io/seam_split.h); the rest of what the
 * reader kept comes back as it came in (io/ply_read.c): polygons as
 * polygons, vertex colours in their type, the other vertex and face
 * properties with their names and types (a vertex's values on each of its
 * copies), the UV pair under the file's names. With attr->nuv0 > 0 the
 * first pair is the kept set and the atlas is the second, named as the
 * first with a "1" appended (s1 t1, u1 v1). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "io/byte_order.h"
#include "io/mesh_io.h"
#include "io/seam_split.h"
#include "mesh/mesh_attributes.h"

static const char *type_name(int t)
{
    static const char *names[] = {"", "char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
    return t > PLY_NONE && t <= PLY_F64 ? names[t] : "float";
}

static size_t type_bytes(int t)
{
    switch (t) {
    case PLY_I8: case PLY_U8: return 1;
    case PLY_I16: case PLY_U16: return 2;
    case PLY_F64: return 8;
    default: return 4;
    }
}

/* x in type t, little-endian; integers rounded and clamped to the type. */
static unsigned char *put_value(unsigned char *q, int t, double x)
{
    static const double lo[] = {0, -128, 0, -32768, 0, -2147483648.0, 0};
    static const double hi[] = {0, 127, 255, 32767, 65535, 2147483647.0, 4294967295.0};
    if (t == PLY_F64) return put_f64le(q, x);
    if (t < PLY_I8 || t > PLY_U32) return put_f32le(q, (float)x);
    double r = isnan(x) ? 0 : floor(x + 0.5);
    if (r < lo[t]) r = lo[t];
    if (r > hi[t]) r = hi[t];
    uint32_t u = t == PLY_U32 ? (uint32_t)r : (uint32_t)(int32_t)r;
    for (size_t k = 0; k < type_bytes(t); k++) *q++ = (unsigned char)(u >> (8 * k));
    return q;
}

/* The largest value of an integer colour type (colours are in [0,1]). */
static double color_scale(int t)
{
    static const double max[] = {1, 127, 255, 32767, 65535, 2147483647.0, 4294967295.0};
    return t >= PLY_I8 && t <= PLY_U32 ? max[t] : 1;
}

/* PLY_F32 when every value of x[0..n) is a finite float or not finite at
 * all, else PLY_F64: a UV of 1e60 written as float would read back as inf. */
static int float_or_double(const double *x, size_t n)
{
    for (size_t i = 0; x && i < n; i++)
        if (isfinite(x[i]) && fabs(x[i]) > FLT_MAX) return PLY_F64;
    return PLY_F32;
}

static int name_taken(const char *name, const char *const *taken, int n)
{
    for (int i = 0; i < n; i++) if (taken[i] && !strcmp(name, taken[i])) return 1;
    return 0;
}

neuv_status io_write_ply(const neuv_mesh *m, FILE *fp)
{
    seam_split sp;
    neuv_status s = seam_split_vertices(m, &sp);
    if (s != NEUV_OK) return s;
    const mesh_attributes *a = m->attr;
    static const char *const color_names[] = {"red", "green", "blue", "alpha"};
    int channels = a && a->color && (a->color_channels == 3 || a->color_channels == 4) ? a->color_channels : 0;
    int color_type = a && a->color_type > PLY_NONE && a->color_type <= PLY_F64 ? a->color_type : PLY_U8;
    const ply_extra *vx = a && a->ply_vertex.count > 0 && a->ply_vertex.elements == m->nv ? &a->ply_vertex : NULL;
    int polygons = m->np > 0 && m->poly_start && m->poly_corner;
    for (int p = 0; polygons && p < m->np; p++)
        polygons = m->poly_start[0] == 0 && m->poly_start[p + 1] - m->poly_start[p] >= 3;
    for (int i = 0; polygons && i < m->poly_start[m->np]; i++)
        polygons = m->poly_corner[i] >= 0 && m->poly_corner[i] < 3 * m->nf;
    for (int f = 0; polygons && f < m->nf; f++)
        polygons = m->face_polygon && m->face_polygon[f] >= 0 && m->face_polygon[f] < m->np &&
                   (f == 0 ? m->face_polygon[f] == 0 : (unsigned)(m->face_polygon[f] - m->face_polygon[f - 1]) <= 1u) &&
                   (f < m->nf - 1 || m->face_polygon[f] == m->np - 1);
    /* A polygon is written whole when each of its corners has one output
     * vertex (a seam may cut it along a diagonal: then its triangles are
     * written, each with the polygon's face values). */
    char *whole = polygons ? mem_alloc((size_t)m->np) : NULL;
    int *stamp = polygons ? mem_alloc(sizeof(int) * (size_t)(sp.nv > 0 ? sp.nv : 1)) : NULL;
    int *face_start = polygons ? mem_alloc(sizeof(int) * ((size_t)m->np + 1)) : NULL;
    if (polygons && (!whole || !stamp || !face_start)) {
        mem_free(whole); mem_free(stamp); mem_free(face_start); seam_split_free(&sp);
        return error_nomem("the PLY polygons");
    }
    int nfaces = polygons ? 0 : m->nf;
    if (polygons) {
        for (int v = 0; v < sp.nv; v++) stamp[v] = -1;
        for (int p = 0, f = 0; p < m->np; p++) {
            face_start[p] = f;
            while (f < m->nf && m->face_polygon[f] == p) f++;
            face_start[p + 1] = f;
        }
        for (int p = 0; p < m->np; p++) {
            for (int k = m->poly_start[p]; k < m->poly_start[p + 1]; k++) stamp[sp.tri[m->poly_corner[k]]] = p;
            whole[p] = 1;
            for (int c = 3 * face_start[p]; c < 3 * face_start[p + 1] && whole[p]; c++) whole[p] = stamp[sp.tri[c]] == p;
            nfaces += whole[p] ? 1 : face_start[p + 1] - face_start[p];
        }
    }
    int nface_values = polygons ? m->np : m->nf;
    const ply_extra *fx = a && a->ply_face.count > 0 && a->ply_face.elements == nface_values ? &a->ply_face : NULL;

    /* The UV pairs' names: the file's, else s t; the atlas's second pair
     * appends "1". */
    char uv_name[2][80], uv1_name[2][80];
    for (int k = 0; k < 2; k++) {
        const char *n = a && a->ply_uv_name[0] && a->ply_uv_name[1] && strlen(a->ply_uv_name[k]) < 64 ? a->ply_uv_name[k]
                                                                                                     : k ? "t" : "s";
        snprintf(uv_name[k], sizeof uv_name[k], "%s", n);
        snprintf(uv1_name[k], sizeof uv1_name[k], "%s1", n);
    }
    const double *first = sp.uv0 ? sp.uv0 : sp.uv, *second = sp.uv0 ? sp.uv : NULL;

    fprintf(fp, "ply\nformat binary_little_endian 1.0\ncomment neuv %s\n", neuv_version());
    /* double positions so a round trip is exact; float UVs and normals as other tools expect
     * (double where a value is beyond float's range). */
    fprintf(fp, "element vertex %d\nproperty double x\nproperty double y\nproperty double z\n", sp.nv);
    const char *taken[16] = {"x", "y", "z"};
    int ntaken = 3;
    int normal_type = float_or_double(sp.normal, 3 * (size_t)sp.nv);
    int first_type = float_or_double(first, 2 * (size_t)sp.nv), second_type = float_or_double(second, 2 * (size_t)sp.nv);
    if (sp.normal) {
        fprintf(fp, "property %s nx\nproperty %s ny\nproperty %s nz\n", type_name(normal_type),
                type_name(normal_type), type_name(normal_type));
        taken[ntaken++] = "nx"; taken[ntaken++] = "ny"; taken[ntaken++] = "nz";
    }
    if (first) {
        fprintf(fp, "property %s %s\nproperty %s %s\n", type_name(first_type), uv_name[0], type_name(first_type),
                uv_name[1]);
        taken[ntaken++] = uv_name[0]; taken[ntaken++] = uv_name[1];
    }
    if (second) {
        fprintf(fp, "property %s %s\nproperty %s %s\n", type_name(second_type), uv1_name[0], type_name(second_type),
                uv1_name[1]);
        taken[ntaken++] = uv1_name[0]; taken[ntaken++] = uv1_name[1];
    }
    for (int c = 0; c < channels; c++) {
        fprintf(fp, "property %s %s\n", type_name(color_type), color_names[c]);
        taken[ntaken++] = color_names[c];
    }
    /* An extra that a written property replaces (a second UV pair read
     * back, written again as the atlas) is left out. */
    int nvx = vx ? vx->count : 0, nfx = fx ? fx->count : 0;
    char *keep_vx = mem_calloc((size_t)nvx + (size_t)nfx + 1, 1);
    int max_corners = 3;
    for (int p = 0; polygons && p < m->np; p++)
        if (m->poly_start[p + 1] - m->poly_start[p] > max_corners) max_corners = m->poly_start[p + 1] - m->poly_start[p];
    size_t rec_cap = 128 + 8 * ((size_t)nvx + (size_t)nfx) + 4 * ((size_t)max_corners + 1);
    unsigned char *rec = mem_alloc(rec_cap);
    if (!keep_vx || !rec) {
        mem_free(keep_vx); mem_free(rec); mem_free(whole); mem_free(stamp); mem_free(face_start); seam_split_free(&sp);
        return error_nomem("the PLY records");
    }
    for (int i = 0; i < nvx; i++) {
        keep_vx[i] = vx->name[i] && vx->name[i][0] && !name_taken(vx->name[i], taken, ntaken);
        if (keep_vx[i]) fprintf(fp, "property %s %s\n", type_name(vx->type[i]), vx->name[i]);
    }
    fprintf(fp, "element face %d\nproperty list %s int vertex_indices\n", nfaces, max_corners > 255 ? "int" : "uchar");
    char *keep_fx = keep_vx + nvx;
    for (int i = 0; i < nfx; i++) {
        keep_fx[i] = fx->name[i] && fx->name[i][0] && strcmp(fx->name[i], "vertex_indices") != 0;
        if (keep_fx[i]) fprintf(fp, "property %s %s\n", type_name(fx->type[i]), fx->name[i]);
    }
    fprintf(fp, "end_header\n");

    for (int v = 0; v < sp.nv; v++) {
        int src = sp.src[v];
        const double *p = m->pos + 3 * (size_t)src;
        unsigned char *q = rec;
        for (int k = 0; k < 3; k++) q = put_f64le(q, p[k]);
        if (sp.normal) for (int k = 0; k < 3; k++) q = put_value(q, normal_type, sp.normal[3 * (size_t)v + k]);
        for (int k = 0; first && k < 2; k++) q = put_value(q, first_type, first[2 * (size_t)v + k]);
        for (int k = 0; second && k < 2; k++) q = put_value(q, second_type, second[2 * (size_t)v + k]);
        for (int c = 0; c < channels; c++) {
            double x = a->color[(size_t)channels * (size_t)src + (size_t)c];
            if (color_type != PLY_F32 && color_type != PLY_F64) x = (x < 0 ? 0 : x > 1 ? 1 : x) * color_scale(color_type);
            q = put_value(q, color_type, x);
        }
        for (int i = 0; i < nvx; i++)
            if (keep_vx[i]) q = put_value(q, vx->type[i], vx->value[(size_t)src * (size_t)nvx + (size_t)i]);
        fwrite(rec, 1, (size_t)(q - rec), fp);
    }
    /* Polygon p: one face when whole, else its triangles; each with the
     * polygon's face values (a face's own when there are no polygons). */
    for (int p = 0, f = 0; f < m->nf; p++) {
        int last = polygons ? face_start[p + 1] : f + 1;
        int as_polygon = polygons && whole[p];
        for (; f < last; f++) {
            unsigned char *q = rec;
            int n = as_polygon ? m->poly_start[p + 1] - m->poly_start[p] : 3;
            if (max_corners > 255) q = put_u32le(q, (uint32_t)n);
            else *q++ = (unsigned char)n;
            for (int k = 0; k < n; k++) {
                int c = as_polygon ? m->poly_corner[m->poly_start[p] + k] : 3 * f + k;
                q = put_u32le(q, (uint32_t)sp.tri[c]);
            }
            for (int i = 0; i < nfx; i++)
                if (keep_fx[i]) q = put_value(q, fx->type[i], fx->value[(size_t)p * (size_t)nfx + (size_t)i]);
            fwrite(rec, 1, (size_t)(q - rec), fp);
            if (as_polygon) f = last - 1;
        }
    }
    mem_free(whole);
    mem_free(stamp);
    mem_free(face_start);
    mem_free(keep_vx);
    mem_free(rec);
    seam_split_free(&sp);
    return ferror(fp) ? error_set(NEUV_ERR_IO, "write failed (disk full?)") : NEUV_OK;
}
