/* The stage options of the public API written into (or read from) the
 * pipeline's one neuv_unwrap_options. */
#ifndef NEUV_API_API_OPTIONS_H
#define NEUV_API_API_OPTIONS_H

#include "neuv/neuv.h"

void api_options_set_charts(neuv_unwrap_options *u, const neuv_chart_options *o);
void api_options_set_param(neuv_unwrap_options *u, const neuv_param_options *o);
void api_options_set_pack(neuv_unwrap_options *u, const neuv_pack_options *o);
#endif
