/* neuv_atlas_output_mesh: the mesh as it came in, with the packed atlas as
 * its UVs. The atlas is made on a cleaned copy (welded, without degenerate
 * or duplicate faces, split where non-manifold, reoriented); each cleaned
 * face and corner knows the input face and vertex it came from
 * (api_atlas_origins), so each corner of the input takes the UV of its
 * cleaned corner and everything else the input carries stays as it is. */
#include <stdint.h>
#include <string.h>

#include "api/api_atlas.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "mesh/mesh.h"
#include "mesh/mesh_attributes.h"

/* input is the mesh added as mesh `index`: same vertices, same faces. */
static int is_added_mesh(const api_atlas_origin *o, const neuv_mesh *input)
{
    if (input->nv != o->v1 - o->v0 || input->nf != o->f1 - o->f0) return 0;
    if (memcmp(input->pos, o->input->pos + 3 * (size_t)o->v0, sizeof(double) * 3 * (size_t)input->nv) != 0) return 0;
    for (size_t c = 0; c < 3 * (size_t)input->nf; c++)
        if (input->tri[c] + o->v0 != o->input->tri[3 * (size_t)o->f0 + c]) return 0;
    return 1;
}

/* UV index (into the packed mesh's UVs) of every corner of input. A face
 * the cleaning dropped (degenerate or duplicate) has no place in the atlas:
 * its three corners take one UV, of one of its vertices at a kept corner
 * (-1 where none has one), so that it covers no texture and is neither
 * flipped nor overlapping (a zero-area UV triangle). Returns those faces. */
static int corner_uvs(const api_atlas_origin *o, const neuv_mesh *input, int *corner_uv, int *vertex_uv,
                      unsigned char *reversed)
{
    const neuv_mesh *m = o->packed;
    memset(reversed, 0, (size_t)input->nf);
    for (size_t c = 0; c < 3 * (size_t)input->nf; c++) corner_uv[c] = -1;
    for (int v = 0; v < input->nv; v++) vertex_uv[v] = -1;
    for (int f = 0; f < m->nf; f++) {
        int i = o->face_origin[f];
        if (i < o->f0 || i >= o->f1) continue;
        const int *t = input->tri + 3 * (size_t)(i - o->f0);
        int at[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++) {
            int v = o->corner_origin[3 * (size_t)f + k] - o->v0;
            int uv = m->tri_uv[3 * (size_t)f + k];
            for (int j = 0; j < 3; j++)
                if (t[j] == v) { corner_uv[3 * (size_t)(i - o->f0) + j] = uv; at[k] = j; }
            if (vertex_uv[v] < 0) vertex_uv[v] = uv;
        }
        reversed[i - o->f0] = (at[1] - at[0] + 3) % 3 == 2;
    }
    int dropped = 0;
    for (int f = 0; f < input->nf; f++) {
        int *c = corner_uv + 3 * (size_t)f;
        if (c[0] >= 0 && c[1] >= 0 && c[2] >= 0) continue;
        const int *t = input->tri + 3 * (size_t)f;
        int uv = vertex_uv[t[0]] >= 0 ? vertex_uv[t[0]] : vertex_uv[t[1]] >= 0 ? vertex_uv[t[1]] : vertex_uv[t[2]];
        c[0] = c[1] = c[2] = uv;
        dropped++;
    }
    return dropped;
}

/* Swaps corners 1 and 2 of face f in a per-corner array (NULL: none). */
static void swap_corners(int *a, int f)
{
    if (!a) return;
    int x = a[3 * (size_t)f + 1];
    a[3 * (size_t)f + 1] = a[3 * (size_t)f + 2];
    a[3 * (size_t)f + 2] = x;
}

/* The faces the cleaning turned over (to agree with their neighbours, or a
 * closed surface outward) are written turned over, with their UVs, normals
 * and first UV set: in the file's own winding their UVs would be mirrored
 * against the rest of their chart. A polygon all of whose triangles turned
 * lists its corners the other way round. */
static void turn_over(neuv_mesh *m, const unsigned char *reversed, int *corner_uv)
{
    for (int f = 0; f < m->nf; f++) {
        if (!reversed[f]) continue;
        swap_corners(m->tri, f);
        swap_corners(corner_uv, f);
        swap_corners(m->tri_normal, f);
        if (m->attr) swap_corners(m->attr->tri_uv0, f);
    }
    for (int p = 0; p < m->np; p++) {
        int c0 = m->poly_start[p], c1 = m->poly_start[p + 1], all = 1;
        for (int c = c0; c < c1; c++) {
            int fc = m->poly_corner[c];
            if (fc < 0) continue;
            if (!reversed[fc / 3]) { all = 0; continue; }
            if (fc % 3) m->poly_corner[c] = fc % 3 == 1 ? fc + 1 : fc - 1;
        }
        for (int a = c0 + 1, b = c1 - 1; all && a < b; a++, b--) { /* the first corner stays first */
            int x = m->poly_corner[a];
            m->poly_corner[a] = m->poly_corner[b];
            m->poly_corner[b] = x;
        }
    }
}

/* The UVs used by the corners, numbered in order of first use, into out. */
static neuv_status compact_uvs(const neuv_mesh *m, const int *corner_uv, int nc, neuv_mesh *out)
{
    int *renum = mem_alloc(sizeof(int) * (size_t)(m->nuv + 1));
    int *tri_uv = mem_alloc(sizeof(int) * (size_t)(nc > 0 ? nc : 1));
    double *uv = mem_alloc(sizeof(double) * 2 * (size_t)(m->nuv + 1));
    if (!renum || !tri_uv || !uv) {
        mem_free(renum); mem_free(tri_uv); mem_free(uv);
        return error_nomem("the output UVs");
    }
    /* renum[m->nuv] is the (0,0) of corners without a UV. */
    for (int t = 0; t <= m->nuv; t++) renum[t] = -1;
    int n = 0;
    for (int c = 0; c < nc; c++) {
        int t = corner_uv[c] < 0 ? m->nuv : corner_uv[c];
        if (renum[t] < 0) {
            renum[t] = n;
            uv[2 * (size_t)n] = t < m->nuv ? m->uv[2 * (size_t)t] : 0.0;
            uv[2 * (size_t)n + 1] = t < m->nuv ? m->uv[2 * (size_t)t + 1] : 0.0;
            n++;
        }
        tri_uv[c] = renum[t];
    }
    mem_free(renum);
    neuv_status s = mesh_set_uv(out, n, uv, tri_uv);
    mem_free(uv);
    mem_free(tri_uv);
    return s;
}

/* Moves out's own UVs to the attributes' first set. */
static neuv_status keep_first_uvs(neuv_mesh *out)
{
    if (!out->attr && !(out->attr = mesh_attributes_new())) return error_nomem("the first UV set");
    mesh_attributes *a = out->attr;
    mem_free(a->uv0);
    mem_free(a->tri_uv0);
    a->nuv0 = out->nuv;
    a->uv0 = out->uv;
    a->tri_uv0 = out->tri_uv;
    out->nuv = 0;
    out->uv = NULL;
    out->tri_uv = NULL;
    return NEUV_OK;
}

neuv_status neuv_atlas_output_mesh(neuv_atlas *atlas, int index, const neuv_mesh *input, int uv_channel,
                                   neuv_mesh **out)
{
    if (!out || !input) return error_set(NEUV_ERR_INPUT, "neuv_atlas_output_mesh: no mesh or no output pointer");
    *out = NULL;
    if (uv_channel != 0 && uv_channel != 1)
        return error_set(NEUV_ERR_INPUT, "uv_channel %d: 0 (the atlas replaces the UVs) or 1 (a second UV set)",
                         uv_channel);
    if (uv_channel == 1 && (input->nuv == 0 || !input->tri_uv))
        return error_set(NEUV_ERR_INPUT, "uv_channel 1 keeps the mesh's UVs as the first set, but it has none");
    api_atlas_origin o;
    neuv_status s = api_atlas_origins(atlas, index, &o);
    if (s != NEUV_OK) return s;
    if (!is_added_mesh(&o, input))
        return error_set(NEUV_ERR_INPUT, "neuv_atlas_output_mesh: not the mesh added as mesh %d", index);

    neuv_mesh *m = mesh_clone(input);
    int *corner_uv = mem_alloc(sizeof(int) * 3 * (size_t)input->nf);
    int *vertex_uv = mem_alloc(sizeof(int) * (size_t)(input->nv > 0 ? input->nv : 1));
    unsigned char *reversed = mem_alloc((size_t)input->nf);
    if (!m || !corner_uv || !vertex_uv || !reversed) { s = error_nomem("the output mesh"); goto done; }
    if ((s = mesh_copy_file_structure(m, input)) != NEUV_OK) goto done;
    if (uv_channel == 1 && (s = keep_first_uvs(m)) != NEUV_OK) goto done;
    int dropped = corner_uvs(&o, input, corner_uv, vertex_uv, reversed);
    turn_over(m, reversed, corner_uv);
    if (dropped > 0)
        log_message(NEUV_LOG_INFO, "%d face%s the cleaning dropped (degenerate or duplicate) written with a "
                    "zero-area UV triangle", dropped, dropped == 1 ? "" : "s");
    s = compact_uvs(o.packed, corner_uv, 3 * input->nf, m);
done:
    mem_free(corner_uv);
    mem_free(vertex_uv);
    mem_free(reversed);
    if (s != NEUV_OK) { mesh_free(m); return s; }
    *out = m;
    return NEUV_OK;
}
