/* What every fuzz target checks of a reader's answer, whatever the input:
 * a mesh that is whole (indices in range, finite positions), or a failure
 * that is NEUV_ERR_INPUT (NEUV_ERR_NOMEM where a count asks for too much)
 * with one non-empty line of message and no output. A violation aborts, so
 * that libFuzzer and the corpus replay (tests/fuzz/replay_main.c) report it. */
#ifndef NEUV_TESTS_FUZZ_CHECK_H
#define NEUV_TESTS_FUZZ_CHECK_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh.h"

static inline void fuzz_check_mesh(const neuv_mesh *m)
{
    if (!m || m->nv <= 0 || m->nf <= 0 || !m->pos || !m->tri) abort();
    for (long i = 0; i < 3L * m->nv; i++)
        if (!isfinite(m->pos[i])) abort();
    for (long c = 0; c < 3L * m->nf; c++) {
        if (m->tri[c] < 0 || m->tri[c] >= m->nv) abort();
        if (m->nuv > 0 && (!m->tri_uv || m->tri_uv[c] < 0 || m->tri_uv[c] >= m->nuv)) abort();
    }
    if (m->nuv < 0 || (m->nuv == 0 && (m->uv || m->tri_uv))) abort();
}

static inline void fuzz_check_failure(neuv_status s, const void *out)
{
    const char *msg = neuv_last_error();
    if (s != NEUV_ERR_INPUT && s != NEUV_ERR_NOMEM) abort();
    if (!msg || !msg[0] || strchr(msg, '\n') || out) abort();
}

/* A NUL-terminated copy of the input, as the text readers take it. */
static inline char *fuzz_text_copy(const unsigned char *data, size_t size)
{
    char *t = malloc(size + 1);
    if (!t) return NULL;
    memcpy(t, data, size);
    t[size] = '\0';
    return t;
}

#endif
