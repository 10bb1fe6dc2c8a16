/* Defaults of the public options structs; the stage options are the
 * fields of neuv_unwrap_options that each stage reads. */
#include <string.h>

#include "neuv/neuv.h"
#include "api/api_options.h"

void neuv_chart_options_init(neuv_chart_options *o)
{
    neuv_unwrap_options u;
    neuv_unwrap_options_init(&u);
    memset(o, 0, sizeof *o);
    o->preset = u.preset;
    o->charts = u.charts;
    o->max_distortion = u.max_distortion;
    o->iters = u.iters;
    o->seed = u.seed;
    o->threads = u.threads;
    o->use_cache = u.use_cache;
    o->max_memory_mb = u.max_memory_mb;
    o->hard_edges = u.hard_edges;
}

void neuv_param_options_init(neuv_param_options *o)
{
    neuv_unwrap_options u;
    neuv_unwrap_options_init(&u);
    memset(o, 0, sizeof *o);
    o->method = u.method;
    o->preset = u.preset;
    o->iters = u.iters;
    o->refine = u.refine;
    o->seed = u.seed;
    o->threads = u.threads;
    o->allow_overlaps = u.allow_overlaps;
}

void neuv_pack_options_init(neuv_pack_options *o)
{
    neuv_unwrap_options u;
    neuv_unwrap_options_init(&u);
    memset(o, 0, sizeof *o);
    o->resolution = u.resolution;
    o->padding = u.padding;
    o->threads = u.threads;
}

void neuv_apply_options_init(neuv_apply_options *o)
{
    memset(o, 0, sizeof *o);
    o->use_cache = 1;
    o->refine = -1;
    o->padding = -1;
}

void api_options_set_charts(neuv_unwrap_options *u, const neuv_chart_options *o)
{
    u->preset = o->preset;
    u->charts = o->charts;
    u->max_distortion = o->max_distortion;
    u->iters = o->iters;
    u->seed = o->seed;
    u->threads = o->threads;
    u->use_cache = o->use_cache;
    u->max_memory_mb = o->max_memory_mb;
    u->seam_angle = o->seam_angle;
    u->seam_edges = o->seam_edges;
    u->seam_edge_count = o->seam_edge_count;
    u->hard_edges = o->hard_edges;
}

void api_options_set_param(neuv_unwrap_options *u, const neuv_param_options *o)
{
    u->method = o->method;
    u->preset = o->preset;
    u->iters = o->iters;
    u->refine = o->refine;
    u->seed = o->seed;
    u->threads = o->threads;
    u->allow_overlaps = o->allow_overlaps;
}

void api_options_set_pack(neuv_unwrap_options *u, const neuv_pack_options *o)
{
    u->resolution = o->resolution;
    u->padding = o->padding;
    u->texels_per_unit = o->texels_per_unit;
    u->threads = o->threads;
}

