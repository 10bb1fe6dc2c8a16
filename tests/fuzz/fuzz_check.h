/* What every fuzz target checks of a reader's answer, whatever the input:
 * a mesh that is whole (indices in range, finite positions), or a failure
 * that is NEUV_ERR_INPUT (NEUV_ERR_NOMEM where a count asks for too much)
 * with one non-empty line of message and no output. A violation aborts, so
 * that libFuzzer and the corpus replay (tests/fuzz/replay_main.c) report it. */
#ifndef NEUV_TESTS_FUZZ_CHECK_H
#define NEUV_TESTS_FUZZ_CHECK_H

#include <math.h>
#include <stdio.h>
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
    /* The file's polygons: each face in one, each corner a face corner. */
    if (m->np < 0 || (m->np > 0 && (!m->face_polygon || !m->poly_start || !m->poly_corner))) abort();
    for (int p = 0; p < m->np; p++)
        if (m->poly_start[p + 1] < m->poly_start[p] + 3) abort();
    for (int c = 0; m->np > 0 && c < m->poly_start[m->np]; c++)
        if (m->poly_corner[c] < -1 || m->poly_corner[c] >= 3 * m->nf) abort();
    for (int f = 0; m->np > 0 && f < m->nf; f++)
        if (m->face_polygon[f] < 0 || m->face_polygon[f] >= m->np || (f > 0 && m->face_polygon[f] < m->face_polygon[f - 1]))
            abort();
}

/* The mesh written by `write` and read back by `read` (NULL: not read):
 * the writer succeeds, and the reader takes its output with the same
 * vertices (when the format keeps them) and faces. */
static inline void fuzz_check_write_back(const neuv_mesh *m, neuv_status (*write)(const neuv_mesh *, FILE *),
                                         neuv_status (*read)(const char *, size_t, neuv_mesh **), int same_vertices)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&buf, &len);
    if (!fp) return;
    neuv_status s = write(m, fp);
    fclose(fp);
    if (s != NEUV_OK && s != NEUV_ERR_NOMEM) abort();
    if (s == NEUV_OK && read) {
        neuv_mesh *back = NULL;
        s = read(buf, len, &back);
        if (s == NEUV_OK) {
            fuzz_check_mesh(back);
            if (back->nf != m->nf || (same_vertices && back->nv != m->nv)) abort();
        } else if (s != NEUV_ERR_NOMEM) {
            abort();
        }
        mesh_free(back);
    }
    free(buf);
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
