/* Public calls on UV maps the caller already has: their metrics, and
 * packing their charts into one square. */
#include <string.h>

#include "neuv/neuv.h"
#include "atlas/pack.h"
#include "atlas/preview.h"
#include "atlas/uv_charts.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "mesh/clean.h"
#include "metrics/uv_metrics.h"
#include "nn/nn.h"
#include "metrics/uv_tiles.h"

neuv_status neuv_evaluate(const neuv_mesh *mesh, const neuv_callbacks *cb, neuv_metrics *out)
{
    if (!mesh || !out) return error_set(NEUV_ERR_INPUT, "neuv_evaluate: no mesh or no output");
    if (mesh->nuv == 0 || !mesh->tri_uv) return error_set(NEUV_ERR_INPUT, "no UVs to evaluate");
    neuv_mesh *m = mesh_clone(mesh);
    if (!m) return error_nomem("the mesh");
    neuv_status s = mesh_weld_positions(m) < 0 ? error_nomem("welding vertices") : NEUV_OK;
    uv_metrics mt;
    log_scope scope;
    log_scope_open(&scope, cb);
    if (s == NEUV_OK) s = uv_metrics_compute(m, &mt);
    log_scope_close(&scope);
    mesh_free(m);
    if (s == NEUV_OK) memcpy(out, &mt, sizeof *out);
    return s;
}

neuv_status neuv_uv_tiles(const neuv_mesh *mesh, neuv_uv_tile **tiles, int *count)
{
    if (!tiles || !count) return error_set(NEUV_ERR_INPUT, "neuv_uv_tiles: no output");
    *tiles = NULL;
    *count = 0;
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_uv_tiles: no mesh");
    if (mesh->nuv == 0 || !mesh->tri_uv) return error_set(NEUV_ERR_INPUT, "no UVs to lay out in tiles");
    /* Charts across shared edges, as neuv_evaluate finds them. */
    neuv_mesh *m = mesh_clone(mesh);
    if (!m) return error_nomem("the mesh");
    neuv_status s = mesh_weld_positions(m) < 0 ? error_nomem("welding vertices") : NEUV_OK;
    if (s == NEUV_OK) s = uv_tiles_compute(m, tiles, count);
    mesh_free(m);
    return s;
}

neuv_status neuv_pack_uvs(neuv_mesh *m, const neuv_pack_options *o, const neuv_callbacks *cb,
                          neuv_pack_report *report)
{
    if (!m) return error_set(NEUV_ERR_INPUT, "neuv_pack_uvs: no mesh");
    if (m->nuv == 0 || !m->tri_uv) return error_set(NEUV_ERR_INPUT, "no UVs: packing needs a mesh with texture coordinates");
    neuv_pack_options def;
    if (!o) { neuv_pack_options_init(&def); o = &def; }
    atlas_pack_options po;
    atlas_pack_options_default(&po);
    po.resolution = o->resolution;
    po.padding = o->padding;
    po.keep_scale = o->keep_scale;
    po.texels_per_unit = o->texels_per_unit;
    if (po.resolution < 8 || po.resolution > 32768)
        return error_set(NEUV_ERR_INPUT, "resolution must be between 8 and 32768 px, got %d", po.resolution);
    if (po.padding < 0 || 2 * po.padding + 1 > po.resolution)
        return error_set(NEUV_ERR_INPUT, "padding must be between 0 and %d px for a %d px atlas, got %d",
                         (po.resolution - 1) / 2, po.resolution, po.padding);
    /* Charts are found across shared edges, which needs shared vertex
     * indices; welding merges only identical positions. */
    if (mesh_weld_positions(m) < 0) return error_nomem("welding vertices");
    int *chart = mem_alloc(sizeof *chart * (size_t)(m->nf > 0 ? m->nf : 1));
    int nc = chart ? uv_charts(m, chart) : -1;
    if (nc < 0) { mem_free(chart); return error_nomem("charts"); }
    atlas_pack_result res;
    log_scope scope;
    log_scope_open(&scope, cb);
    nn_set_threads(o->threads);
    neuv_status s = atlas_pack(m, chart, nc, &po, NULL, &res);
    log_scope_close(&scope);
    mem_free(chart);
    if (s == NEUV_OK && report) {
        report->charts = nc;
        report->attempts = res.attempts;
        report->texel_scale = res.texel_scale;
        report->tiles = res.tiles;
    }
    return s;
}

neuv_status neuv_write_preview(const neuv_mesh *mesh, const char *prefix, neuv_preview_color color,
                               const neuv_callbacks *cb)
{
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_write_preview: no mesh");
    if (!prefix || !*prefix) return error_set(NEUV_ERR_INPUT, "no picture prefix given");
    if (mesh->nuv == 0 || !mesh->tri_uv) return error_set(NEUV_ERR_INPUT, "no UVs to draw");
    if (color != NEUV_PREVIEW_CHART && color != NEUV_PREVIEW_QCE && color != NEUV_PREVIEW_AREA)
        return error_set(NEUV_ERR_INPUT, "unknown preview colouring %d", (int)color);
    log_scope scope;
    log_scope_open(&scope, cb);
    neuv_status s = preview_write(mesh, prefix, color == NEUV_PREVIEW_QCE ? PREVIEW_COLOR_QCE
                                                : color == NEUV_PREVIEW_AREA ? PREVIEW_COLOR_AREA : PREVIEW_COLOR_CHART);
    log_scope_close(&scope);
    return s;
}
