#include "charts/charts.h"

#include <stdlib.h>

#include "core/mem.h"

int charts_renumber(int nf, int *face_chart)
{
    int max_id = -1;
    for (int f = 0; f < nf; f++)
        if (face_chart[f] > max_id) max_id = face_chart[f];
    int *new_id = mem_alloc(sizeof(int) * (size_t)(max_id + 1 > 0 ? max_id + 1 : 1));
    if (!new_id) return -1;
    for (int i = 0; i <= max_id; i++) new_id[i] = -1;
    int count = 0;
    for (int f = 0; f < nf; f++) {
        int c = face_chart[f];
        if (c < 0) continue;
        if (new_id[c] < 0) new_id[c] = count++;
        face_chart[f] = new_id[c];
    }
    mem_free(new_id);
    return count;
}
