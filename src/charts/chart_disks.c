/* Step (c) of charts_from_labels: every chart made a topological disk.
 * Work is a stack of charts still to check; a non-disk is split into two or
 * more edge-connected parts that go back on the stack. Every split leaves
 * each part with fewer faces, and a single face is a disk, so the loop ends. */
#include "charts/chart_steps.h"

#include <stdlib.h>

#include "charts/chart_local.h"
#include "core/error.h"
#include "core/mem.h"

typedef struct chart_item { int *faces; int n, id; } chart_item;

typedef struct chart_stack { chart_item *item; int n, cap; } chart_stack;

static int stack_push(chart_stack *s, int *faces, int n, int id)
{
    if (s->n == s->cap) {
        int cap = s->cap ? 2 * s->cap : 16;
        chart_item *it = mem_realloc(s->item, sizeof *it * (size_t)cap);
        if (!it) return -1;
        s->item = it;
        s->cap = cap;
    }
    s->item[s->n++] = (chart_item){faces, n, id};
    return 0;
}

/* Parts of a non-disk chart: comp (#CF) and the count, >= 2 on success. */
static int split_parts(const chart_local *L, const chart_shape *shape, const int *vloop, int *comp,
                       charts_report *rep)
{
    if (shape->components > 1) {
        if (rep) rep->separated++;
        return chart_local_components(L, NULL, NULL, comp);
    }
    int *part = mem_alloc(sizeof(int) * (size_t)L->nf);
    if (!part) return -1;
    if (!shape->pinched && shape->genus == 0 && shape->loops >= 2) {
        unsigned char *cut = mem_alloc((size_t)L->nf * 3);
        if (!cut) { mem_free(part); return -1; }
        int found = chart_local_annulus_cut(L, vloop, cut);
        int count = found == 1 ? chart_local_components(L, NULL, cut, comp) : found;
        mem_free(cut);
        if (count >= 2) {
            mem_free(part);
            if (rep) rep->annulus_cuts++;
            return count;
        }
        /* No second path (a strip one face wide): one cut, then grow. */
        found = count < 0 ? -1 : chart_local_cut_and_grow(L, vloop, part);
        count = found == 1 ? chart_local_components(L, part, NULL, comp) : found;
        if (count < 0) { mem_free(part); return -1; }
        if (count >= 2) {
            mem_free(part);
            if (rep) rep->annulus_cuts++;
            return count;
        }
    }
    if (chart_local_grow2(L, part) != NEUV_OK) { mem_free(part); return -1; }
    int count = chart_local_components(L, part, NULL, comp);
    mem_free(part);
    if (rep && count >= 2) rep->region_splits++;
    return count;
}

neuv_status charts_make_disks(const neuv_mesh *m, const face_graph *g, int *face_chart, int *n_charts,
                              int only_id, charts_report *report)
{
    int nc = *n_charts, nf = m->nf;
    chart_stack stack = {0};
    chart_scratch scratch = {0};
    int *count = mem_calloc((size_t)(nc > 0 ? nc : 1), sizeof(int));
    neuv_status st = NEUV_OK;
    if (!count || chart_scratch_init(&scratch, nf, m->nv) != NEUV_OK) goto oom;
    for (int f = 0; f < nf; f++) count[face_chart[f]]++;
    /* Face lists in ascending face order, pushed last id first so charts
     * are processed in id order. */
    for (int c = nc - 1; c >= 0; c--) {
        if (only_id >= 0 && c != only_id) continue;
        if (count[c] == 0) continue;
        int *faces = mem_alloc(sizeof(int) * (size_t)count[c]);
        if (!faces) goto oom;
        int n = 0;
        for (int f = 0; f < nf; f++)
            if (face_chart[f] == c) faces[n++] = f;
        if (stack_push(&stack, faces, n, c) != 0) { mem_free(faces); goto oom; }
    }
    while (stack.n > 0) {
        chart_item it = stack.item[--stack.n];
        if (it.n == 1) { mem_free(it.faces); continue; }
        chart_local L;
        chart_shape shape;
        int *vloop = NULL, *comp = NULL;
        if (chart_local_build(m, g, it.faces, it.n, &scratch, &L) != NEUV_OK) { mem_free(it.faces); goto oom; }
        vloop = mem_alloc(sizeof(int) * (size_t)L.nv);
        comp = mem_alloc(sizeof(int) * (size_t)L.nf);
        if (!vloop || !comp || chart_local_shape(&L, &shape, vloop) != NEUV_OK) {
            mem_free(vloop); mem_free(comp); chart_local_free(&L); mem_free(it.faces);
            goto oom;
        }
        if (shape.disk) {
            mem_free(vloop); mem_free(comp); chart_local_free(&L); mem_free(it.faces);
            continue;
        }
        int parts = split_parts(&L, &shape, vloop, comp, report);
        mem_free(vloop);
        chart_local_free(&L);
        if (parts < 0) { mem_free(comp); mem_free(it.faces); goto oom; }
        if (parts < 2) {
            mem_free(comp); mem_free(it.faces);
            st = error_set(NEUV_ERR_INTERNAL, "chart %d (%d faces) is not a disk and could not be split",
                           it.id, it.n);
            goto fail;
        }
        int *sizes = mem_calloc((size_t)parts, sizeof(int));
        int **lists = mem_calloc((size_t)parts, sizeof(int *));
        int ok = sizes && lists;
        if (ok) {
            for (int i = 0; i < it.n; i++) sizes[comp[i]]++;
            for (int p = 0; p < parts && ok; p++) ok = (lists[p] = mem_alloc(sizeof(int) * (size_t)sizes[p])) != NULL;
        }
        if (ok) {
            for (int p = 0; p < parts; p++) sizes[p] = 0;
            for (int i = 0; i < it.n; i++) lists[comp[i]][sizes[comp[i]]++] = it.faces[i];
            for (int p = parts - 1; p >= 0 && ok; p--) {
                int id = p == 0 ? it.id : nc + p - 1;
                for (int i = 0; i < sizes[p]; i++) face_chart[lists[p][i]] = id;
                ok = stack_push(&stack, lists[p], sizes[p], id) == 0;
                if (ok) lists[p] = NULL;
            }
            nc += parts - 1;
        }
        if (lists)
            for (int p = 0; p < parts; p++) mem_free(lists[p]);
        mem_free(lists); mem_free(sizes); mem_free(comp); mem_free(it.faces);
        if (!ok) goto oom;
    }
    goto done;
oom:
    st = error_nomem("chart disks");
fail:
done:
    for (int i = 0; i < stack.n; i++) mem_free(stack.item[i].faces);
    mem_free(stack.item);
    mem_free(count);
    chart_scratch_free(&scratch);
    *n_charts = nc;
    return st;
}
