/* Boundary smoothing of charts: faces that stick out of their chart (a
 * saw-tooth spike along a boundary grown on the face graph) or fill a notch
 * of a neighbour move to the neighbour they share more boundary length with.
 * Spikes hurt twice downstream: LSCM stretches the thin tips, and the packer
 * sees a footprint with teeth.
 *
 * A move keeps both charts disks (charts/face_move.h). Every move shortens
 * the total boundary by a positive length, so the sweeps end. */
#include "charts/charts.h"

#include <stdlib.h>
#include <string.h>

#include "charts/face_graph.h"
#include "charts/face_move.h"
#include "core/error.h"
#include "core/mem.h"

neuv_status charts_smooth_boundaries(const neuv_mesh *m, const int *active, int *face_chart, int max_sweeps,
                                     int *moves)
{
    if (moves) *moves = 0;
    if (!m || !face_chart) return error_set(NEUV_ERR_INPUT, "charts_smooth_boundaries: missing mesh or charts");
    if (m->nf == 0) return NEUV_OK;
    face_graph g;
    neuv_status st = face_graph_build(m, &g);
    if (st != NEUV_OK) return st;
    face_star s = {0};
    if ((st = face_star_build(m, &g, &s)) != NEUV_OK) { face_graph_free(&g); return st; }
    int total = 0;
    for (int sweep = 0; sweep < max_sweeps; sweep++) {
        int moved = 0;
        for (int f = 0; f < m->nf; f++) {
            int a = face_chart[f];
            if (active && !active[a]) continue;
            /* Boundary length shared with each neighbouring chart (at most 3). */
            int nb[3], nn = 0;
            double len[3] = {0, 0, 0}, own = 0;
            for (int e = 0; e < 3; e++) {
                int o = g.adj[3 * f + e];
                if (o < 0) continue;
                int c = face_chart[o];
                if (c == a) { own += g.elen[3 * f + e]; continue; }
                int i = 0;
                while (i < nn && nb[i] != c) i++;
                if (i == nn) nb[nn++] = c;
                len[i] += g.elen[3 * f + e];
            }
            int best = -1;
            for (int i = 0; i < nn; i++) {
                if (active && !active[nb[i]]) continue;
                /* Strictly longer (relative margin against round-off), so
                 * the total boundary length falls with every move. */
                if (!(len[i] > own * (1.0 + 1e-9) + 1e-300)) continue;
                if (best < 0 || len[i] > len[best] || (len[i] == len[best] && nb[i] < nb[best])) best = i;
            }
            if (best < 0) continue;
            int b = nb[best];
            if (!face_move_keeps_disk(m, &g, &s, face_chart, f, a, 1)) continue;
            if (!face_move_keeps_disk(m, &g, &s, face_chart, f, b, 0)) continue;
            face_chart[f] = b;
            moved++;
        }
        total += moved;
        if (moved == 0) break;
    }
    face_star_free(&s);
    face_graph_free(&g);
    if (moves) *moves = total;
    return NEUV_OK;
}
