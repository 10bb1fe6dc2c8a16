/* The built-in procedural shapes, by name. */
#include <stdint.h>
#include <string.h>

#include "neuv/neuv.h"
#include "core/error.h"
#include "mesh/blob_family.h"
#include "mesh/shape_family.h"
#include "mesh/shapes.h"

neuv_status neuv_shape(const char *name, int member, neuv_mesh **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_shape: no output pointer");
    *out = NULL;
    if (!name) return error_set(NEUV_ERR_INPUT, "no shape name given");
    int family = !strcmp(name, "bent-capsule") || !strcmp(name, "blob");
    if (member != -1 && !family) return error_set(NEUV_ERR_INPUT, "a member index applies to the bent-capsule and blob families only");
    if (family && member < 0) return error_set(NEUV_ERR_INPUT, "%s is a family: it needs a member index >= 0", name);
    neuv_mesh *m = NULL;
    if (!strcmp(name, "bent-capsule")) m = shape_capsule_family((uint64_t)member);
    else if (family) m = shape_blob_family((uint64_t)member);
    else if (!strcmp(name, "bumpy-torus")) m = shape_bumpy_torus(1.0, 0.4, 0.25, 96, 40);
    else if (!strcmp(name, "sphere")) m = shape_icosphere(4, 1.0);
    else if (!strcmp(name, "capsule")) m = shape_capsule(0.5, 1.5, 32, 8);
    else if (!strcmp(name, "cube")) m = shape_cube(16);
    else if (!strcmp(name, "genus2")) m = shape_genus2(4);
    else
        return error_set(NEUV_ERR_INPUT,
                         "unknown shape '%s' (expected bumpy-torus, sphere, capsule, cube, genus2, bent-capsule or blob)",
                         name);
    if (!m) return error_nomem("the shape");
    *out = m;
    return NEUV_OK;
}
