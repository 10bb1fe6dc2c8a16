/* Public meshes from the caller's arrays, and back out to arrays. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "neuv/neuv.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "mesh/clean.h"
#include "mesh/mesh.h"

void neuv_mesh_decl_init(neuv_mesh_decl *d)
{
    memset(d, 0, sizeof *d);
    d->position_type = NEUV_FLOAT32;
    d->index_type = NEUV_UINT32;
    d->uv_type = NEUV_FLOAT32;
}

static size_t scalar_size(neuv_scalar_type t) { return t == NEUV_FLOAT64 ? 8 : 4; }

static double read_scalar(const void *base, size_t stride, int i, int k, neuv_scalar_type t)
{
    const unsigned char *p = (const unsigned char *)base + stride * (size_t)i + scalar_size(t) * (size_t)k;
    if (t == NEUV_FLOAT64) { double v; memcpy(&v, p, sizeof v); return v; }
    float v;
    memcpy(&v, p, sizeof v);
    return v;
}

static long long read_index(const void *base, int i, neuv_index_type t)
{
    if (t == NEUV_UINT16) return ((const uint16_t *)base)[i];
    if (t == NEUV_INT32) return ((const int32_t *)base)[i];
    return ((const uint32_t *)base)[i];
}

static neuv_status check_decl(const neuv_mesh_decl *d)
{
    if (!d) return error_set(NEUV_ERR_INPUT, "no mesh description");
    if (d->position_type != NEUV_FLOAT32 && d->position_type != NEUV_FLOAT64)
        return error_set(NEUV_ERR_INPUT, "position_type must be NEUV_FLOAT32 or NEUV_FLOAT64");
    if (d->uvs && d->uv_type != NEUV_FLOAT32 && d->uv_type != NEUV_FLOAT64)
        return error_set(NEUV_ERR_INPUT, "uv_type must be NEUV_FLOAT32 or NEUV_FLOAT64");
    if (d->indices && d->index_type != NEUV_UINT32 && d->index_type != NEUV_UINT16 && d->index_type != NEUV_INT32)
        return error_set(NEUV_ERR_INPUT, "index_type must be NEUV_UINT32, NEUV_UINT16 or NEUV_INT32");
    if (!d->positions || d->vertex_count <= 0) return error_set(NEUV_ERR_INPUT, "no vertices");
    if (d->position_stride && d->position_stride < 3 * scalar_size(d->position_type))
        return error_set(NEUV_ERR_INPUT, "position_stride %zu is smaller than one position (%zu bytes)",
                         d->position_stride, 3 * scalar_size(d->position_type));
    if (d->uvs && d->uv_stride && d->uv_stride < 2 * scalar_size(d->uv_type))
        return error_set(NEUV_ERR_INPUT, "uv_stride %zu is smaller than one UV (%zu bytes)", d->uv_stride,
                         2 * scalar_size(d->uv_type));
    int corners = d->indices ? d->index_count : d->vertex_count;
    if (corners <= 0) return error_set(NEUV_ERR_INPUT, "no triangles");
    if (corners % 3 != 0)
        return error_set(NEUV_ERR_INPUT, "%s %d is not a multiple of 3 (triangles only)",
                         d->indices ? "index_count" : "vertex_count (no indices)", corners);
    return NEUV_OK;
}

neuv_status neuv_mesh_create(const neuv_mesh_decl *d, neuv_mesh **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_mesh_create: no output pointer");
    *out = NULL;
    neuv_status s = check_decl(d);
    if (s != NEUV_OK) return s;
    int corners = d->indices ? d->index_count : d->vertex_count;
    size_t pstride = d->position_stride ? d->position_stride : 3 * scalar_size(d->position_type);
    size_t ustride = d->uv_stride ? d->uv_stride : 2 * scalar_size(d->uv_type);
    for (int i = 0; i < d->vertex_count; i++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(read_scalar(d->positions, pstride, i, k, d->position_type)))
                return error_set(NEUV_ERR_INPUT, "vertex %d has a coordinate that is not a finite number", i);
    if (d->uvs)
        for (int i = 0; i < d->vertex_count; i++)
            for (int k = 0; k < 2; k++)
                if (!isfinite(read_scalar(d->uvs, ustride, i, k, d->uv_type)))
                    return error_set(NEUV_ERR_INPUT, "vertex %d has a UV that is not a finite number", i);
    if (d->indices)
        for (int c = 0; c < corners; c++) {
            long long v = read_index(d->indices, c, d->index_type);
            if (v < 0 || v >= d->vertex_count)
                return error_set(NEUV_ERR_INPUT, "index %d is %lld, outside 0..%d (vertex_count %d)", c, v,
                                 d->vertex_count - 1, d->vertex_count);
        }
    neuv_mesh *m = mesh_create(d->vertex_count, corners / 3, d->uvs ? d->vertex_count : 0);
    if (!m) return error_nomem("the mesh");
    for (int i = 0; i < d->vertex_count; i++)
        for (int k = 0; k < 3; k++) m->pos[3 * i + k] = read_scalar(d->positions, pstride, i, k, d->position_type);
    for (int c = 0; c < corners; c++) {
        m->tri[c] = d->indices ? (int)read_index(d->indices, c, d->index_type) : c;
        if (d->uvs) m->tri_uv[c] = m->tri[c];
    }
    if (d->uvs)
        for (int i = 0; i < d->vertex_count; i++)
            for (int k = 0; k < 2; k++) m->uv[2 * i + k] = read_scalar(d->uvs, ustride, i, k, d->uv_type);
    *out = m;
    return NEUV_OK;
}

void neuv_mesh_get_positions(const neuv_mesh *m, double *positions)
{
    if (m && positions) memcpy(positions, m->pos, sizeof(double) * 3 * (size_t)m->nv);
}

void neuv_mesh_get_indices(const neuv_mesh *m, int *indices)
{
    if (m && indices) memcpy(indices, m->tri, sizeof(int) * 3 * (size_t)m->nf);
}

int neuv_mesh_get_corner_uvs(const neuv_mesh *m, double *uvs)
{
    if (!m || m->nuv == 0 || !m->tri_uv) return 0;
    if (!uvs) return 1;
    for (size_t c = 0; c < 3 * (size_t)m->nf; c++) {
        uvs[2 * c] = m->uv[2 * m->tri_uv[c]];
        uvs[2 * c + 1] = m->uv[2 * m->tri_uv[c] + 1];
    }
    return 1;
}

_Static_assert(sizeof(neuv_clean_report) == sizeof(mesh_clean_report), "public and internal clean reports differ");

neuv_status neuv_mesh_clean(neuv_mesh *m, const neuv_callbacks *cb, neuv_clean_report *report)
{
    if (!m) return error_set(NEUV_ERR_INPUT, "neuv_mesh_clean: no mesh");
    mesh_clean_report r;
    log_scope scope;
    log_scope_open(&scope, cb);
    neuv_status s = mesh_clean(m, NULL, &r);
    log_scope_close(&scope);
    if (s != NEUV_OK) return s;
    if (report) memcpy(report, &r, sizeof *report);
    if (m->nf == 0) return error_set(NEUV_ERR_INPUT, "no faces left after cleaning (every face was degenerate)");
    return NEUV_OK;
}

neuv_status neuv_mesh_weld(neuv_mesh *m, int *welded)
{
    if (!m) return error_set(NEUV_ERR_INPUT, "neuv_mesh_weld: no mesh");
    int n = mesh_weld_positions(m);
    if (n < 0) return error_nomem("welding vertices");
    if (welded) *welded = n;
    return NEUV_OK;
}
