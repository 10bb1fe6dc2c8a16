/* The JSON documents of the public API other than the unwrap report. */
#include "neuv/neuv.h"
#include "api/api_json.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json_writer.h"
#include "metrics/uv_metrics.h"
#include "metrics/uv_tiles.h"
#include "mesh/mesh.h"

#include <stdio.h>
#include <string.h>

char *api_json_finish(json_writer *w)
{
    if (w->failed) {
        json_free(w);
        error_nomem("a JSON document");
        return NULL;
    }
    return w->buf;
}

char *neuv_metrics_json(const neuv_metrics *metrics, const neuv_mesh *mesh, const char *input_name)
{
    if (!metrics || !mesh) { error_set(NEUV_ERR_INPUT, "neuv_metrics_json: no metrics or no mesh"); return NULL; }
    uv_metrics mt;
    memcpy(&mt, metrics, sizeof mt);
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "version"); json_string(&w, neuv_version());
    json_key(&w, "input"); json_string(&w, input_name ? input_name : "");
    json_key(&w, "vertices"); json_int(&w, mesh->nv);
    json_key(&w, "faces"); json_int(&w, mesh->nf);
    json_key(&w, "metrics");
    json_begin_object(&w);
    uv_metrics_write_json(&mt, &w);
    json_end_object(&w);
    neuv_uv_tile *tiles = NULL;
    int ntiles = 0;
    if (mesh->nuv > 0 && mesh->tri_uv && neuv_uv_tiles(mesh, &tiles, &ntiles) != NEUV_OK) w.failed = 1;
    json_key(&w, "tiles");
    uv_tiles_write_json(tiles, ntiles, &w);
    neuv_free(tiles);
    json_end_object(&w);
    return api_json_finish(&w);
}

char *neuv_train_report_json(const neuv_train_report *r, const char *model_name)
{
    if (!r) { error_set(NEUV_ERR_INPUT, "neuv_train_report_json: no report"); return NULL; }
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "model"); json_string(&w, model_name ? model_name : "");
    json_key(&w, "shapes"); json_int(&w, r->shapes);
    json_key(&w, "faces"); json_int(&w, r->faces);
    json_key(&w, "charts"); json_int(&w, r->charts);
    json_key(&w, "patchnet_k"); json_int(&w, r->patch_k);
    json_key(&w, "patchnet_iterations"); json_int(&w, r->patch_iterations);
    json_key(&w, "patchnet_loss"); json_number(&w, r->patch_loss);
    json_key(&w, "param_iterations"); json_int(&w, r->param_iterations);
    json_key(&w, "param_loss"); json_number(&w, r->param_loss);
    json_key(&w, "seconds");
    json_begin_object(&w);
    json_key(&w, "operators"); json_number(&w, r->seconds_operators);
    json_key(&w, "patches"); json_number(&w, r->seconds_patches);
    json_key(&w, "charts"); json_number(&w, r->seconds_charts);
    json_key(&w, "param"); json_number(&w, r->seconds_param);
    json_key(&w, "total"); json_number(&w, r->seconds);
    json_end_object(&w);
    json_end_object(&w);
    return api_json_finish(&w);
}

neuv_status neuv_save_text(const char *path, const char *text)
{
    if (!path || !*path) return error_set(NEUV_ERR_INPUT, "no file name given");
    if (!text) return error_set(NEUV_ERR_INPUT, "neuv_save_text: no text");
    atomic_file af;
    neuv_status s = atomic_file_open(&af, path);
    if (s != NEUV_OK) return s;
    fputs(text, af.fp);
    fputc('\n', af.fp);
    return atomic_file_commit(&af);
}
