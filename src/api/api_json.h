/* What the public API's JSON documents share. */
#ifndef NEUV_API_API_JSON_H
#define NEUV_API_API_JSON_H

#include "core/json_writer.h"

/* The finished text of w, handed to the caller (released with neuv_free);
 * NULL, with the error set, when w ran out of memory (w is then freed). */
char *api_json_finish(json_writer *w);

#endif
