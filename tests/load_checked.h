/* Loading a mesh in a test: the load must succeed (a CHECK), and the
 * library's message is printed when it does not. */
#ifndef NEUV_TESTS_LOAD_CHECKED_H
#define NEUV_TESTS_LOAD_CHECKED_H

#include <stdio.h>

#include "check.h"
#include "neuv/neuv.h"

static inline neuv_mesh *load(const char *path)
{
    neuv_mesh *m = NULL;
    neuv_status s = neuv_mesh_load(path, NULL, &m);
    if (s != NEUV_OK) fprintf(stderr, "%s: %s\n", path, neuv_last_error());
    CHECK(s == NEUV_OK && m);
    return m;
}

#endif
