#include "atlas/convex_hull.h"

#include <stdlib.h>

#include "core/mem.h"

typedef struct hull_sort_ctx { const double *p; int i; } hull_sort_ctx;

static int cmp_point(const void *a, const void *b)
{
    const hull_sort_ctx *x = a, *y = b;
    const double *u = x->p + 2 * x->i, *v = y->p + 2 * y->i;
    if (u[0] != v[0]) return u[0] < v[0] ? -1 : 1;
    if (u[1] != v[1]) return u[1] < v[1] ? -1 : 1;
    return x->i - y->i; /* stable, so the result is deterministic */
}

static double cross(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

int convex_hull_2d(const double *p, int n, int *hull)
{
    if (n <= 0) return 0;
    hull_sort_ctx *s = mem_alloc(sizeof *s * (size_t)n);
    int *h = mem_alloc(sizeof *h * (size_t)(2 * n + 1));
    if (!s || !h) { mem_free(s); mem_free(h); return -1; }
    for (int i = 0; i < n; i++) { s[i].p = p; s[i].i = i; }
    qsort(s, (size_t)n, sizeof *s, cmp_point);
    /* Drop exact duplicates so degenerate charts give 1 or 2 hull points. */
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double *q = p + 2 * s[i].i;
        if (m > 0) {
            const double *r = p + 2 * s[m - 1].i;
            if (q[0] == r[0] && q[1] == r[1]) continue;
        }
        s[m++] = s[i];
    }
    if (m <= 2) {
        for (int i = 0; i < m; i++) hull[i] = s[i].i;
        mem_free(s); mem_free(h);
        return m;
    }
    int k = 0;
    for (int i = 0; i < m; i++) { /* lower chain */
        while (k >= 2 && cross(p + 2 * h[k - 2], p + 2 * h[k - 1], p + 2 * s[i].i) <= 0) k--;
        h[k++] = s[i].i;
    }
    for (int i = m - 2, lo = k + 1; i >= 0; i--) { /* upper chain */
        while (k >= lo && cross(p + 2 * h[k - 2], p + 2 * h[k - 1], p + 2 * s[i].i) <= 0) k--;
        h[k++] = s[i].i;
    }
    k--; /* the last point repeats the first */
    if (k < 2) k = 2; /* all points collinear: keep the two extremes */
    for (int i = 0; i < k; i++) hull[i] = h[i];
    mem_free(s); mem_free(h);
    return k;
}
