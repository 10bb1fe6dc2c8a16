#include "atlas/preview.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/raster_image.h"
#include "atlas/render_views.h"
#include "atlas/uv_charts.h"
#include "core/error.h"
#include "core/mem.h"
#include "io/png_write.h"

static const int checker_squares = 32;

/* Signed UV area of face f (positive counter-clockwise). */
static double uv_signed_area(const neuv_mesh *m, int f)
{
    const double *a = m->uv + 2 * m->tri_uv[3 * f], *b = m->uv + 2 * m->tri_uv[3 * f + 1],
                 *c = m->uv + 2 * m->tri_uv[3 * f + 2];
    return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

/* Quasi-conformal error s1/s2 of the map from the 3D triangle (flattened in
 * its plane) to its UV triangle (SPEC.md section 5); INFINITY when degenerate. */
static double face_qce(const neuv_mesh *m, int f)
{
    const double *p0 = m->pos + 3 * m->tri[3 * f], *p1 = m->pos + 3 * m->tri[3 * f + 1],
                 *p2 = m->pos + 3 * m->tri[3 * f + 2];
    double e1[3], e2[3];
    for (int d = 0; d < 3; d++) { e1[d] = p1[d] - p0[d]; e2[d] = p2[d] - p0[d]; }
    double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    if (!(l1 > 0)) return INFINITY;
    double x2 = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1;
    double y2 = sqrt(fmax(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2] - x2 * x2, 0));
    if (!(y2 > 0)) return INFINITY;
    const double *u0 = m->uv + 2 * m->tri_uv[3 * f], *u1 = m->uv + 2 * m->tri_uv[3 * f + 1],
                 *u2 = m->uv + 2 * m->tri_uv[3 * f + 2];
    double a = (u1[0] - u0[0]) / l1, c = (u1[1] - u0[1]) / l1;
    double b = ((u2[0] - u0[0]) - a * x2) / y2, d = ((u2[1] - u0[1]) - c * x2) / y2;
    double fro = a * a + b * b + c * c + d * d, det = fabs(a * d - b * c);
    double disc = sqrt(fmax(fro * fro - 4 * det * det, 0));
    double s1 = sqrt(0.5 * (fro + disc)), s2 = sqrt(fmax(0.5 * (fro - disc), 0));
    return s2 > 0 ? s1 / s2 : INFINITY;
}

/* Sequential ramp for qce: t in [0,1], blue -> green -> yellow -> red. */
static void ramp_color(double t, uint8_t c[3])
{
    static const double stops[4][3] = {{40, 90, 200}, {60, 180, 110}, {240, 210, 60}, {210, 40, 40}};
    t = fmin(fmax(t, 0), 1) * 3;
    int i = (int)t;
    if (i > 2) i = 2;
    double f = t - i;
    for (int k = 0; k < 3; k++) c[k] = (uint8_t)lround(stops[i][k] + f * (stops[i + 1][k] - stops[i][k]));
}

/* Diverging ramp for log area ratio: t in [-1,1], blue -> white -> red. */
static void diverging_color(double t, uint8_t c[3])
{
    static const double lo[3] = {50, 100, 210}, mid[3] = {245, 245, 245}, hi[3] = {210, 50, 40};
    t = fmin(fmax(t, -1), 1);
    const double *e = t < 0 ? lo : hi;
    double f = fabs(t);
    for (int k = 0; k < 3; k++) c[k] = (uint8_t)lround(mid[k] + f * (e[k] - mid[k]));
}

typedef struct uv_paint {
    raster_image *img;
    unsigned char *count; /* faces covering each pixel (saturating) */
    int *owner;           /* last face drawn on each pixel */
} uv_paint;

static void count_pixel(void *user, int x, int y, const double b[3])
{
    (void)b;
    uv_paint *p = user;
    size_t i = (size_t)y * p->img->w + x;
    if (p->count[i] < 255) p->count[i]++;
}

typedef struct face_fill { uv_paint *p; int face; } face_fill;

static void owner_pixel(void *user, int x, int y, const double b[3])
{
    (void)b;
    face_fill *ff = user;
    ff->p->owner[(size_t)y * ff->p->img->w + x] = ff->face;
}

/* UVs in UDIM tiles (texels per unit: every face within one unit square of
 * [0,10]^2): the occupied tiles, as bits u0 + 10 v0 of tiles[100]; 0 when
 * the UVs are not laid out so. */
static int uv_tile_cells(const neuv_mesh *m, unsigned char tiles[100])
{
    memset(tiles, 0, 100);
    int n = 0;
    for (int f = 0; f < m->nf; f++) {
        int cell[2];
        for (int d = 0; d < 2; d++) {
            double lo = INFINITY, hi = -INFINITY;
            for (int c = 0; c < 3; c++) {
                double x = m->uv[2 * m->tri_uv[3 * f + c] + d];
                lo = fmin(lo, x);
                hi = fmax(hi, x);
            }
            double mid = floor(0.5 * (lo + hi));
            if (!(mid >= 0 && mid < 10) || lo < mid - 1e-9 || hi > mid + 1 + 1e-9) return 0;
            cell[d] = (int)mid;
        }
        unsigned char *t = &tiles[cell[0] + 10 * cell[1]];
        n += !*t;
        *t = 1;
    }
    return n;
}

/* The UV picture: the view is the unit square when the UVs lie in it, the
 * tiles side by side when they lie in UDIM tiles, otherwise the square
 * around their bounding box (and the unit square). */
static neuv_status write_uv_png(const neuv_mesh *m, const char *path, preview_color color, int S)
{
    static const uint8_t outside[3] = {52, 54, 60}, inside[3] = {250, 250, 250};
    raster_image img;
    if (raster_image_init(&img, S, S, outside) != 0) return error_nomem("preview image");
    int *chart = mem_alloc(sizeof *chart * (size_t)(m->nf > 0 ? m->nf : 1));
    unsigned char *flipped = mem_calloc((size_t)(m->nf > 0 ? m->nf : 1), 1);
    double *value = mem_alloc(sizeof *value * (size_t)(m->nf > 0 ? m->nf : 1));
    uv_paint paint = {&img, mem_calloc((size_t)S * S, 1), mem_alloc(sizeof(int) * (size_t)S * S)};
    double *chart_sign = NULL;
    neuv_status st = NEUV_OK;
    int nc = (chart && flipped && value && paint.count && paint.owner) ? uv_charts(m, chart) : -1;
    if (nc >= 0) chart_sign = mem_calloc((size_t)nc + 1, sizeof *chart_sign);
    if (nc < 0 || !chart_sign) { st = error_nomem("preview"); goto done; }

    double lo[2] = {0, 0}, hi[2] = {1, 1};
    for (int u = 0; u < m->nuv; u++)
        for (int d = 0; d < 2; d++)
            if (isfinite(m->uv[2 * u + d])) {
                lo[d] = fmin(lo[d], m->uv[2 * u + d]);
                hi[d] = fmax(hi[d], m->uv[2 * u + d]);
            }
    unsigned char tiles[100];
    int ntiles = uv_tile_cells(m, tiles);
    if (ntiles > 1 || (ntiles == 1 && !tiles[0])) {
        lo[0] = lo[1] = 0;
        for (int d = 0; d < 2; d++) hi[d] = ceil(hi[d] - 1e-9);
    } else {
        ntiles = 1;
        memset(tiles, 0, sizeof tiles);
        tiles[0] = 1;
    }
    double ext = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(ext > 0)) ext = 1;
    double scale = S / ext;
    /* The unit square (or each tile, a pixel apart) in white so the atlas's free space shows. */
    int gap = ntiles > 1 ? 1 : 0;
    for (int k = 0; k < 100; k++)
        if (tiles[k]) {
            double u0 = k % 10, v0 = k / 10;
            raster_fill_rect(&img, (int)lround((u0 - lo[0]) * scale) + gap, (int)lround(S - (v0 + 1 - lo[1]) * scale) + gap,
                             (int)lround((u0 + 1 - lo[0]) * scale) - gap, (int)lround(S - (v0 - lo[1]) * scale) - gap,
                             inside);
        }

    /* Flipped faces: orientation against the area-weighted majority of the chart. */
    for (int f = 0; f < m->nf; f++) chart_sign[chart[f]] += uv_signed_area(m, f);
    for (int f = 0; f < m->nf; f++) {
        double a = uv_signed_area(m, f);
        flipped[f] = (a != 0) && ((a > 0) != (chart_sign[chart[f]] >= 0));
    }
    double total_uv = 0, total_3d = 0;
    for (int f = 0; f < m->nf; f++) { total_uv += fabs(uv_signed_area(m, f)); total_3d += mesh_face_area(m, f); }
    double log_ratio = (total_uv > 0 && total_3d > 0) ? log(total_uv / total_3d) : 0;
    for (int f = 0; f < m->nf; f++) {
        if (color == PREVIEW_COLOR_QCE) value[f] = face_qce(m, f);
        else if (color == PREVIEW_COLOR_AREA) {
            double a3 = mesh_face_area(m, f), au = fabs(uv_signed_area(m, f));
            value[f] = (a3 > 0 && au > 0) ? log(au / a3) - log_ratio : (au > 0 ? INFINITY : -INFINITY);
        }
    }

    for (size_t i = 0; i < (size_t)S * S; i++) paint.owner[i] = -1;
    for (int f = 0; f < m->nf; f++) {
        double p[3][2];
        for (int c = 0; c < 3; c++) {
            const double *uv = m->uv + 2 * m->tri_uv[3 * f + c];
            p[c][0] = (uv[0] - lo[0]) * scale;
            p[c][1] = S - (uv[1] - lo[1]) * scale;
        }
        raster_triangle(p, S, S, count_pixel, &paint);
        face_fill ff = {&paint, f};
        raster_triangle(p, S, S, owner_pixel, &ff);
    }
    static const uint8_t red[3] = {230, 20, 20}, magenta[3] = {255, 0, 255}, qce_bad[3] = {120, 0, 0};
    for (size_t i = 0; i < (size_t)S * S; i++) {
        int f = paint.owner[i];
        if (f < 0) continue;
        uint8_t c[3];
        if (paint.count[i] >= 2) memcpy(c, magenta, 3);
        else if (flipped[f]) memcpy(c, red, 3);
        else if (color == PREVIEW_COLOR_QCE) {
            if (isfinite(value[f])) ramp_color(value[f] - 1, c); /* qce 1..2 */
            else memcpy(c, qce_bad, 3);
        } else if (color == PREVIEW_COLOR_AREA) diverging_color(value[f], c); /* log ratio -1..1 */
        else raster_palette(chart[f], c);
        memcpy(img.rgb + 3 * i, c, 3);
    }
    /* Edges: faint inside charts so the triangulation shows without darkening small charts. */
    static const uint8_t ink[3] = {20, 20, 24};
    double alpha = m->nf > 20000 ? 0.12 : 0.25;
    for (int f = 0; f < m->nf; f++)
        for (int c = 0; c < 3; c++) {
            const double *a = m->uv + 2 * m->tri_uv[3 * f + c], *b = m->uv + 2 * m->tri_uv[3 * f + (c + 1) % 3];
            raster_line(&img, (a[0] - lo[0]) * scale, S - (a[1] - lo[1]) * scale, (b[0] - lo[0]) * scale,
                        S - (b[1] - lo[1]) * scale, ink, alpha);
        }
    if (color != PREVIEW_COLOR_CHART) {
        /* Legend: a bar along the bottom-left with its end values. */
        int x0 = 16, y0 = S - 40, bw = 256, bh = 14;
        static const uint8_t frame[3] = {0, 0, 0}, white[3] = {255, 255, 255};
        raster_fill_rect(&img, x0 - 6, y0 - 6, x0 + bw + 6, y0 + bh + 30, white);
        raster_fill_rect(&img, x0 - 1, y0 - 1, x0 + bw + 1, y0 + bh + 1, frame);
        for (int x = 0; x < bw; x++) {
            uint8_t c[3];
            double t = (double)x / (bw - 1);
            if (color == PREVIEW_COLOR_QCE) ramp_color(t, c);
            else diverging_color(2 * t - 1, c);
            raster_fill_rect(&img, x0 + x, y0, x0 + x + 1, y0 + bh, c);
        }
        const char *left = color == PREVIEW_COLOR_QCE ? "1" : "-1";
        const char *mid = color == PREVIEW_COLOR_QCE ? "1.5" : "0";
        const char *right = color == PREVIEW_COLOR_QCE ? "2+" : "+1";
        raster_text(&img, x0, y0 + bh + 4, left, 2, frame);
        raster_text(&img, x0 + bw / 2 - 4 * (int)strlen(mid), y0 + bh + 4, mid, 2, frame);
        raster_text(&img, x0 + bw - 8 * (int)strlen(right), y0 + bh + 4, right, 2, frame);
    }
    st = png_write_rgb(path, img.w, img.h, img.rgb);
done:
    raster_image_free(&img);
    mem_free(chart); mem_free(flipped); mem_free(value); mem_free(paint.count); mem_free(paint.owner); mem_free(chart_sign);
    return st;
}

static neuv_status write_views_png(const neuv_mesh *m, const int *label, const char *path, int size)
{
    raster_image img;
    neuv_status st = render_four_views(m, label, checker_squares, size, &img);
    if (st != NEUV_OK) return st;
    st = png_write_rgb(path, img.w, img.h, img.rgb);
    raster_image_free(&img);
    return st;
}

neuv_status preview_write(const neuv_mesh *m, const char *prefix, preview_color color)
{
    return preview_write_sized(m, prefix, color, 1024);
}

neuv_status preview_write_sized(const neuv_mesh *m, const char *prefix, preview_color color, int size)
{
    if (size < 64 || size > 16384) return error_set(NEUV_ERR_INPUT, "preview size %d px is outside 64..16384", size);
    if (!m || m->nuv <= 0 || !m->tri_uv) return error_set(NEUV_ERR_INPUT, "preview needs a mesh with UVs");
    size_t n = strlen(prefix) + 16;
    char *path = mem_alloc(n);
    if (!path) return error_nomem("preview path");
    snprintf(path, n, "%s-uv.png", prefix);
    neuv_status st = write_uv_png(m, path, color, size);
    if (st == NEUV_OK) {
        snprintf(path, n, "%s-checker.png", prefix);
        st = write_views_png(m, NULL, path, size);
    }
    mem_free(path);
    return st;
}

neuv_status preview_write_labels(const neuv_mesh *m, const int *face_label, const char *path)
{
    if (!m || !face_label) return error_set(NEUV_ERR_INPUT, "label preview needs a mesh and a label per face");
    return write_views_png(m, face_label, path, 1024);
}
