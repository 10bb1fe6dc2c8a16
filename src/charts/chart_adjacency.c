/* Which charts touch along edges, and over what length: the repair stage
 * uses it to choose where a small chart goes, the packer to keep
 * neighbours close. */
#include "charts/charts.h"

#include <stdlib.h>
#include <string.h>

#include "charts/face_graph.h"
#include "core/error.h"
#include "core/mem.h"

typedef struct chart_pair { int a, b; double len; } chart_pair;

static int chart_pair_cmp(const void *pa, const void *pb)
{
    const chart_pair *a = pa, *b = pb;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    return (a->b > b->b) - (a->b < b->b);
}

void chart_adjacency_free(chart_adjacency *adj)
{
    mem_free(adj->a); mem_free(adj->b); mem_free(adj->length);
    memset(adj, 0, sizeof *adj);
}

neuv_status chart_adjacency_build(const neuv_mesh *m, const int *face_chart, chart_adjacency *adj)
{
    memset(adj, 0, sizeof *adj);
    face_graph g;
    neuv_status st = face_graph_build(m, &g);
    if (st != NEUV_OK) return st;
    size_t count = 0;
    for (int f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++) {
            int o = g.adj[3 * f + k];
            if (o > f && face_chart[o] != face_chart[f]) count++;
        }
    chart_pair *pairs = mem_alloc(sizeof *pairs * (count > 0 ? count : 1));
    if (!pairs) { face_graph_free(&g); return error_nomem("chart adjacency"); }
    count = 0;
    for (int f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++) {
            int o = g.adj[3 * f + k];
            if (o > f && face_chart[o] != face_chart[f]) {
                int a = face_chart[f], b = face_chart[o];
                pairs[count++] = (chart_pair){a < b ? a : b, a < b ? b : a, g.elen[3 * f + k]};
            }
        }
    face_graph_free(&g);
    qsort(pairs, count, sizeof *pairs, chart_pair_cmp);
    size_t distinct = 0;
    for (size_t i = 0; i < count; i++)
        if (i == 0 || pairs[i].a != pairs[i - 1].a || pairs[i].b != pairs[i - 1].b) distinct++;
    size_t d1 = distinct > 0 ? distinct : 1;
    adj->a = mem_alloc(sizeof(int) * d1);
    adj->b = mem_alloc(sizeof(int) * d1);
    adj->length = mem_alloc(sizeof(double) * d1);
    if (!adj->a || !adj->b || !adj->length) {
        mem_free(pairs);
        chart_adjacency_free(adj);
        return error_nomem("chart adjacency");
    }
    int n = -1;
    for (size_t i = 0; i < count; i++) {
        if (i == 0 || pairs[i].a != pairs[i - 1].a || pairs[i].b != pairs[i - 1].b) {
            n++;
            adj->a[n] = pairs[i].a;
            adj->b[n] = pairs[i].b;
            adj->length[n] = 0.0;
        }
        adj->length[n] += pairs[i].len;
    }
    adj->n = (int)distinct;
    mem_free(pairs);
    return NEUV_OK;
}
