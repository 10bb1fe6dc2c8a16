/* Step (b) of charts_from_labels: tiny pieces of a label field (a stray
 * face with another argmax, a sliver along a patch border) are not worth a
 * chart of their own, so they join the neighbour they share most border
 * with, which keeps the merged chart's boundary short. */
#include "charts/chart_steps.h"

#include <stdlib.h>

#include "charts/min_heap.h"
#include "core/error.h"
#include "core/mem.h"

typedef struct neighbour_list {
    int *id;
    double *len;
    int n, cap;
} neighbour_list;

typedef struct piece_pair { int a, b; double len; } piece_pair;

static int pair_cmp(const void *pa, const void *pb)
{
    const piece_pair *a = pa, *b = pb;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    return (a->b > b->b) - (a->b < b->b);
}

static int find_entry(const neighbour_list *l, int id)
{
    for (int i = 0; i < l->n; i++)
        if (l->id[i] == id) return i;
    return -1;
}

static int add_length(neighbour_list *l, int id, double len)
{
    int i = find_entry(l, id);
    if (i >= 0) { l->len[i] += len; return 0; }
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 4;
        int *ids = mem_realloc(l->id, sizeof(int) * (size_t)cap);
        if (!ids) return -1;
        l->id = ids;
        double *lens = mem_realloc(l->len, sizeof(double) * (size_t)cap);
        if (!lens) return -1;
        l->len = lens;
        l->cap = cap;
    }
    l->id[l->n] = id;
    l->len[l->n] = len;
    l->n++;
    return 0;
}

static void remove_entry(neighbour_list *l, int id)
{
    int i = find_entry(l, id);
    if (i < 0) return;
    l->n--;
    l->id[i] = l->id[l->n];
    l->len[i] = l->len[l->n];
}

/* Builds the symmetric neighbour lists with shared boundary lengths. */
static int build_neighbours(const face_graph *g, const int *piece, neighbour_list *nb)
{
    size_t count = 0;
    for (int f = 0; f < g->nf; f++)
        for (int k = 0; k < 3; k++) {
            int o = g->adj[3 * f + k];
            if (o > f && piece[o] != piece[f]) count++;
        }
    piece_pair *pairs = mem_alloc(sizeof *pairs * (count > 0 ? count : 1));
    if (!pairs) return -1;
    count = 0;
    for (int f = 0; f < g->nf; f++)
        for (int k = 0; k < 3; k++) {
            int o = g->adj[3 * f + k];
            if (o > f && piece[o] != piece[f]) {
                int a = piece[f], b = piece[o];
                pairs[count++] = (piece_pair){a < b ? a : b, a < b ? b : a, g->elen[3 * f + k]};
            }
        }
    qsort(pairs, count, sizeof *pairs, pair_cmp);
    for (size_t i = 0; i < count;) {
        size_t j = i;
        double len = 0.0;
        while (j < count && pairs[j].a == pairs[i].a && pairs[j].b == pairs[i].b) len += pairs[j++].len;
        if (add_length(&nb[pairs[i].a], pairs[i].b, len) != 0 ||
            add_length(&nb[pairs[i].b], pairs[i].a, len) != 0) {
            mem_free(pairs);
            return -1;
        }
        i = j;
    }
    mem_free(pairs);
    return 0;
}

/* Moves a's border into b and redirects a's neighbours to b. */
static int absorb(neighbour_list *nb, int a, int b)
{
    for (int i = 0; i < nb[a].n; i++) {
        int n = nb[a].id[i];
        double len = nb[a].len[i];
        if (n == b) continue;
        if (add_length(&nb[b], n, len) != 0 || add_length(&nb[n], b, len) != 0) return -1;
        remove_entry(&nb[n], a);
    }
    remove_entry(&nb[b], a);
    mem_free(nb[a].id); mem_free(nb[a].len);
    nb[a] = (neighbour_list){0};
    return 0;
}

neuv_status charts_merge_fragments(const neuv_mesh *m, const face_graph *g, int *piece, int *n_pieces,
                                   double min_area, int *merged)
{
    int np = *n_pieces;
    size_t np1 = (size_t)(np > 0 ? np : 1);
    *merged = 0;
    double *area = mem_calloc(np1, sizeof(double));
    int *into = mem_alloc(sizeof(int) * np1);
    neighbour_list *nb = mem_calloc(np1, sizeof *nb);
    min_heap h = {0};
    neuv_status st = NEUV_OK;
    if (!area || !into || !nb || min_heap_init(&h, np) != 0 || build_neighbours(g, piece, nb) != 0) {
        st = error_nomem("fragment merge");
        goto done;
    }
    for (int f = 0; f < m->nf; f++) area[piece[f]] += g->area[f];
    for (int p = 0; p < np; p++) {
        into[p] = -1;
        if (area[p] < min_area && min_heap_push(&h, area[p], p) != 0) {
            st = error_nomem("fragment merge");
            goto done;
        }
    }
    double key;
    int a;
    while (min_heap_pop(&h, &key, &a) == 0) {
        /* Skip entries made stale by an earlier merge. */
        if (into[a] >= 0 || key != area[a] || area[a] >= min_area) continue;
        int best = -1;
        for (int i = 0; i < nb[a].n; i++) {
            int n = nb[a].id[i];
            if (best < 0 || nb[a].len[i] > nb[a].len[best] ||
                (nb[a].len[i] == nb[a].len[best] && n < nb[a].id[best]))
                best = i;
        }
        if (best < 0) continue; /* a whole small component: nothing to join */
        int b = nb[a].id[best];
        if (absorb(nb, a, b) != 0) { st = error_nomem("fragment merge"); goto done; }
        into[a] = b;
        area[b] += area[a];
        (*merged)++;
        if (area[b] < min_area && min_heap_push(&h, area[b], b) != 0) {
            st = error_nomem("fragment merge");
            goto done;
        }
    }
    for (int f = 0; f < m->nf; f++) {
        int p = piece[f];
        while (into[p] >= 0) p = into[p];
        piece[f] = p;
    }
    int n = charts_renumber(m->nf, piece);
    if (n < 0) st = error_nomem("fragment merge");
    else *n_pieces = n;
done:
    if (nb)
        for (int p = 0; p < np; p++) { mem_free(nb[p].id); mem_free(nb[p].len); }
    mem_free(nb); mem_free(area); mem_free(into);
    min_heap_free(&h);
    return st;
}
