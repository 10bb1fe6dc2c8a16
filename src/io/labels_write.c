/* Per-face labels: see labels_write.h. */
#include "io/labels_write.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/mem.h"

static void write_vertices(FILE *fp, const neuv_mesh *m, const char *prefix)
{
    for (int v = 0; v < m->nv; v++) {
        const double *p = m->pos + 3 * (size_t)v;
        fprintf(fp, "%s%.17g %.17g %.17g\n", prefix, p[0], p[1], p[2]);
    }
}

static void write_ply(FILE *fp, const neuv_mesh *m, const int *label)
{
    fprintf(fp, "ply\nformat ascii 1.0\ncomment neuv segment: chart id per face\n");
    fprintf(fp, "element vertex %d\nproperty double x\nproperty double y\nproperty double z\n", m->nv);
    fprintf(fp, "element face %d\nproperty list uchar int vertex_indices\nproperty int chart\nend_header\n", m->nf);
    write_vertices(fp, m, "");
    for (int f = 0; f < m->nf; f++) {
        const int *t = m->tri + 3 * (size_t)f;
        fprintf(fp, "3 %d %d %d %d\n", t[0], t[1], t[2], label[f]);
    }
}

/* Groups in increasing label order; faces keep their relative order inside a group. */
static neuv_status write_obj(FILE *fp, const neuv_mesh *m, const int *label, int max_label)
{
    int *start = mem_calloc((size_t)max_label + 2, sizeof(int));
    int *order = mem_alloc(sizeof(int) * (size_t)(m->nf ? m->nf : 1));
    if (!start || !order) { mem_free(start); mem_free(order); return error_nomem("label groups"); }
    for (int f = 0; f < m->nf; f++) start[label[f] + 1]++;
    for (int l = 0; l <= max_label; l++) start[l + 1] += start[l];
    int *fill = mem_alloc(sizeof(int) * ((size_t)max_label + 1));
    if (!fill) { mem_free(start); mem_free(order); return error_nomem("label groups"); }
    memcpy(fill, start, sizeof(int) * ((size_t)max_label + 1));
    for (int f = 0; f < m->nf; f++) order[fill[label[f]]++] = f;
    mem_free(fill);
    fprintf(fp, "# neuv segment: one group per chart\n");
    write_vertices(fp, m, "v ");
    for (int l = 0; l <= max_label; l++) {
        if (start[l] == start[l + 1]) continue;
        fprintf(fp, "g chart_%d\n", l);
        for (int i = start[l]; i < start[l + 1]; i++) {
            const int *t = m->tri + 3 * (size_t)order[i];
            fprintf(fp, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
        }
    }
    mem_free(start);
    mem_free(order);
    return NEUV_OK;
}

neuv_status labels_write(const char *path, const neuv_mesh *m, const int *label)
{
    const char *dot = strrchr(path, '.');
    int ply = dot && !strcasecmp(dot, ".ply"), obj = dot && !strcasecmp(dot, ".obj");
    if (!ply && !obj)
        return error_set(NEUV_ERR_INPUT, "chart labels are written as .ply or .obj, not '%s'", dot ? dot : path);
    int max_label = -1;
    for (int f = 0; f < m->nf; f++) {
        if (label[f] < 0) return error_set(NEUV_ERR_INPUT, "face %d has a negative label %d", f, label[f]);
        if (label[f] > max_label) max_label = label[f];
    }
    atomic_file af;
    neuv_status st = atomic_file_open(&af, path);
    if (st) return st;
    if (ply) write_ply(af.fp, m, label);
    else if ((st = write_obj(af.fp, m, label, max_label))) { atomic_file_abort(&af); return st; }
    if (ferror(af.fp)) { atomic_file_abort(&af); return error_set(NEUV_ERR_IO, "%s: write failed (disk full?)", path); }
    return atomic_file_commit(&af);
}
