/* Public reading of checkpoint files (`neuv inspect`): the configuration
 * and each tensor's shape and value range. */
#include <math.h>
#include <string.h>

#include "neuv/neuv.h"
#include "api/api_json.h"
#include "core/error.h"
#include "core/mem.h"
#include "nn/checkpoint.h"

struct neuv_checkpoint {
    nn_checkpoint c;
};

neuv_status neuv_checkpoint_load(const char *path, neuv_checkpoint **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_checkpoint_load: no output pointer");
    *out = NULL;
    if (!path) return error_set(NEUV_ERR_INPUT, "no checkpoint file name given");
    neuv_checkpoint *c = mem_calloc(1, sizeof *c);
    if (!c) return error_nomem("the checkpoint");
    neuv_status s = nn_checkpoint_load(path, &c->c);
    if (s != NEUV_OK) { mem_free(c); return s; }
    *out = c;
    return NEUV_OK;
}

void neuv_checkpoint_free(neuv_checkpoint *c)
{
    if (!c) return;
    nn_checkpoint_free(&c->c);
    mem_free(c);
}

unsigned neuv_checkpoint_version(const neuv_checkpoint *c) { return c ? c->c.version : 0; }

const char *neuv_checkpoint_config(const neuv_checkpoint *c) { return c && c->c.config ? c->c.config : ""; }

int neuv_checkpoint_tensor_count(const neuv_checkpoint *c) { return c ? c->c.n : 0; }

long long neuv_checkpoint_parameter_count(const neuv_checkpoint *c)
{
    long long n = 0;
    for (int i = 0; c && i < c->c.n; i++) n += (long long)c->c.t[i].rows * c->c.t[i].cols;
    return n;
}

neuv_status neuv_checkpoint_get_tensor(const neuv_checkpoint *c, int index, neuv_tensor_info *out)
{
    if (!c || !out) return error_set(NEUV_ERR_INPUT, "neuv_checkpoint_get_tensor: no checkpoint or no output");
    if (index < 0 || index >= c->c.n)
        return error_set(NEUV_ERR_INPUT, "tensor %d is out of range: the checkpoint has %d", index, c->c.n);
    const nn_checkpoint_tensor *t = &c->c.t[index];
    memset(out, 0, sizeof *out);
    out->name = t->name;
    out->rows = t->rows;
    out->cols = t->cols;
    out->min = INFINITY;
    out->max = -INFINITY;
    double sq = 0;
    long long n = (long long)t->rows * t->cols, finite = 0;
    for (long long i = 0; i < n; i++) {
        double v = t->data[i];
        if (!isfinite(v)) { out->nonfinite++; continue; }
        finite++;
        if (v < out->min) out->min = v;
        if (v > out->max) out->max = v;
        sq += v * v;
    }
    if (finite) out->rms = sqrt(sq / (double)finite);
    else out->min = out->max = NAN;
    return NEUV_OK;
}

char *neuv_checkpoint_json(const neuv_checkpoint *c, const char *file_name)
{
    if (!c) { error_set(NEUV_ERR_INPUT, "neuv_checkpoint_json: no checkpoint"); return NULL; }
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "file"); json_string(&w, file_name ? file_name : "");
    json_key(&w, "version"); json_int(&w, c->c.version);
    json_key(&w, "config"); json_string(&w, neuv_checkpoint_config(c));
    json_key(&w, "parameters"); json_int(&w, neuv_checkpoint_parameter_count(c));
    json_key(&w, "tensors");
    json_begin_array(&w);
    for (int i = 0; i < c->c.n; i++) {
        neuv_tensor_info t;
        neuv_checkpoint_get_tensor(c, i, &t);
        json_begin_object(&w);
        json_key(&w, "name"); json_string(&w, t.name);
        json_key(&w, "rows"); json_int(&w, t.rows);
        json_key(&w, "cols"); json_int(&w, t.cols);
        json_key(&w, "min"); json_number(&w, t.min);
        json_key(&w, "max"); json_number(&w, t.max);
        json_key(&w, "rms"); json_number(&w, t.rms);
        json_key(&w, "nonfinite"); json_int(&w, t.nonfinite);
        json_end_object(&w);
    }
    json_end_array(&w);
    json_end_object(&w);
    return api_json_finish(&w);
}
