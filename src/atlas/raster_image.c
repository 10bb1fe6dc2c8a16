#include "atlas/raster_image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/mem.h"

int raster_image_init(raster_image *img, int w, int h, const uint8_t c[3])
{
    img->w = w; img->h = h;
    img->rgb = mem_alloc((size_t)w * (size_t)h * 3);
    if (!img->rgb) return -1;
    for (size_t i = 0; i < (size_t)w * h; i++) memcpy(img->rgb + 3 * i, c, 3);
    return 0;
}

void raster_image_free(raster_image *img)
{
    mem_free(img->rgb);
    img->rgb = NULL;
    img->w = img->h = 0;
}

void raster_blend(raster_image *img, int x, int y, const uint8_t c[3], double alpha)
{
    if (x < 0 || y < 0 || x >= img->w || y >= img->h) return;
    uint8_t *p = img->rgb + 3 * ((size_t)y * img->w + x);
    for (int k = 0; k < 3; k++) p[k] = (uint8_t)lround(p[k] + alpha * (c[k] - p[k]));
}

void raster_line(raster_image *img, double x0, double y0, double x1, double y1, const uint8_t c[3], double alpha)
{
    double dx = x1 - x0, dy = y1 - y0;
    int n = (int)ceil(fmax(fabs(dx), fabs(dy)));
    if (n > 100000) n = 100000; /* a wild coordinate must not stall the picture */
    for (int i = 0; i <= n; i++) {
        double t = n ? (double)i / n : 0;
        raster_blend(img, (int)floor(x0 + t * dx), (int)floor(y0 + t * dy), c, alpha);
    }
}

void raster_fill_rect(raster_image *img, int x0, int y0, int x1, int y1, const uint8_t c[3])
{
    for (int y = y0 < 0 ? 0 : y0; y < y1 && y < img->h; y++)
        for (int x = x0 < 0 ? 0 : x0; x < x1 && x < img->w; x++)
            memcpy(img->rgb + 3 * ((size_t)y * img->w + x), c, 3);
}

/* 3 by 5 glyphs, one row of 3 bits per entry, top row first. */
static const uint8_t *glyph(char ch)
{
    static const uint8_t digits[10][5] = {
        {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
        {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};
    static const uint8_t dot[5] = {0, 0, 0, 0, 2}, minus[5] = {0, 0, 7, 0, 0}, plus[5] = {0, 2, 7, 2, 0};
    if (ch >= '0' && ch <= '9') return digits[ch - '0'];
    if (ch == '.') return dot;
    if (ch == '-') return minus;
    if (ch == '+') return plus;
    return NULL;
}

void raster_text(raster_image *img, int x, int y, const char *s, int scale, const uint8_t c[3])
{
    for (; *s; s++, x += 4 * scale) {
        const uint8_t *g = glyph(*s);
        if (!g) continue;
        for (int r = 0; r < 5; r++)
            for (int b = 0; b < 3; b++)
                if (g[r] >> (2 - b) & 1)
                    raster_fill_rect(img, x + b * scale, y + r * scale, x + (b + 1) * scale, y + (r + 1) * scale, c);
    }
}

/* Edge function of point (x, y) against the edge a -> b, evaluated with the
 * endpoints in a canonical order so that the two triangles sharing an edge
 * get exactly opposite values (no rounding disagreement on the seam). */
static double edge_value(const double *a, const double *b, double x, double y, int *top_left)
{
    int swap = (b[0] < a[0]) || (b[0] == a[0] && b[1] < a[1]);
    const double *s = swap ? b : a, *t = swap ? a : b;
    double e = (t[0] - s[0]) * (y - s[1]) - (t[1] - s[1]) * (x - s[0]);
    /* Owner of a point exactly on the edge: the side the canonical normal points to. */
    *top_left = swap;
    return swap ? -e : e;
}

void raster_triangle(const double p[3][2], int w, int h, raster_pixel_fn fn, void *user)
{
    double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if (!(area != 0) || !isfinite(area)) return;
    double sgn = area > 0 ? 1 : -1;
    double xmin = fmin(p[0][0], fmin(p[1][0], p[2][0])), xmax = fmax(p[0][0], fmax(p[1][0], p[2][0]));
    double ymin = fmin(p[0][1], fmin(p[1][1], p[2][1])), ymax = fmax(p[0][1], fmax(p[1][1], p[2][1]));
    if (xmax < 0 || ymax < 0 || xmin > w || ymin > h) return;
    int x0 = (int)floor(xmin), x1 = (int)ceil(xmax), y0 = (int)floor(ymin), y1 = (int)ceil(ymax);
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > w - 1) x1 = w - 1;
    if (y1 > h - 1) y1 = h - 1;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            double cx = x + 0.5, cy = y + 0.5, e[3];
            int inside = 1;
            for (int k = 0; k < 3 && inside; k++) {
                int owner;
                e[k] = sgn * edge_value(p[(k + 1) % 3], p[(k + 2) % 3], cx, cy, &owner);
                /* On the edge: keep it only for one of the two triangles, chosen by
                 * the orientation of this triangle relative to the canonical edge. */
                if (e[k] < 0 || (e[k] == 0 && ((sgn > 0) == (owner != 0)))) inside = 0;
            }
            if (!inside) continue;
            double s = e[0] + e[1] + e[2];
            double b[3] = {e[0] / s, e[1] / s, e[2] / s};
            fn(user, x, y, b);
        }
}

void raster_palette(int id, uint8_t c[3])
{
    /* Golden-ratio hue steps keep neighbouring ids apart; saturation and
     * value vary slowly so many charts stay distinguishable. */
    double hue = fmod(0.13 + 0.618033988749895 * id, 1.0) * 6;
    double sat = 0.45 + 0.2 * ((id * 7) % 3) / 2.0, val = 0.80 + 0.15 * ((id * 5) % 4) / 3.0;
    int i = (int)hue;
    double f = hue - i, pp = val * (1 - sat), q = val * (1 - sat * f), t = val * (1 - sat * (1 - f));
    double r, g, b;
    switch (i % 6) {
    case 0: r = val; g = t; b = pp; break;
    case 1: r = q; g = val; b = pp; break;
    case 2: r = pp; g = val; b = t; break;
    case 3: r = pp; g = q; b = val; break;
    case 4: r = t; g = pp; b = val; break;
    default: r = val; g = pp; b = q; break;
    }
    c[0] = (uint8_t)lround(255 * r); c[1] = (uint8_t)lround(255 * g); c[2] = (uint8_t)lround(255 * b);
}
