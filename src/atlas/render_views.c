#include "atlas/render_views.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

const uint8_t render_background[3] = {36, 38, 44};

/* A camera looking at the origin: rows of `rot` are right, up and forward. */
typedef struct view_camera {
    double rot[3][3];
    double dist;   /* eye at -dist * forward */
    double focal;  /* screen half-size / tan(half field of view) */
} view_camera;

typedef struct render_ctx {
    const neuv_mesh *m;
    const int *label;
    raster_image *img;
    float *depth;         /* 1/z per pixel of the whole image (larger = nearer) */
    int ox, oy, cell;     /* the view's cell inside the image */
    double inv_z[3];      /* per corner 1/z */
    double uvz[3][2];     /* per corner uv/z */
    int has_uv;
    double shade;
    uint8_t base[3];      /* label colour */
    double freq, uv0[2];  /* checker squares per UV unit, UV origin */
} render_ctx;

static void shade_pixel(void *user, int x, int y, const double b[3])
{
    render_ctx *r = user;
    int px = r->ox + x, py = r->oy + y;
    size_t i = (size_t)py * r->img->w + px;
    /* Perspective-correct: 1/z, uv/z are affine in screen space. */
    double iz = b[0] * r->inv_z[0] + b[1] * r->inv_z[1] + b[2] * r->inv_z[2];
    if (iz <= r->depth[i]) return;
    r->depth[i] = (float)iz;
    uint8_t c[3];
    if (r->label) {
        memcpy(c, r->base, 3);
    } else if (r->has_uv) {
        double u = (b[0] * r->uvz[0][0] + b[1] * r->uvz[1][0] + b[2] * r->uvz[2][0]) / iz;
        double v = (b[0] * r->uvz[0][1] + b[1] * r->uvz[1][1] + b[2] * r->uvz[2][1]) / iz;
        long cu = (long)floor((u - r->uv0[0]) * r->freq), cv = (long)floor((v - r->uv0[1]) * r->freq);
        static const uint8_t light[3] = {236, 236, 228}, dark[3] = {214, 96, 52};
        memcpy(c, ((cu + cv) & 1) ? dark : light, 3);
    } else {
        c[0] = c[1] = c[2] = 160;
    }
    uint8_t *p = r->img->rgb + 3 * i;
    for (int k = 0; k < 3; k++) p[k] = (uint8_t)lround(c[k] * r->shade);
}

static void make_camera(view_camera *cam, const double fwd[3], const double up[3], double radius)
{
    double right[3] = {up[1] * fwd[2] - up[2] * fwd[1], up[2] * fwd[0] - up[0] * fwd[2], up[0] * fwd[1] - up[1] * fwd[0]};
    /* right = up x forward gives a right-handed screen with y up when looking along forward. */
    for (int k = 0; k < 3; k++) { cam->rot[0][k] = -right[k]; cam->rot[1][k] = up[k]; cam->rot[2][k] = fwd[k]; }
    cam->dist = 3.0 * radius;
    double half = asin(1.0 / 3.0) * 1.08; /* a little margin around the bounding sphere */
    cam->focal = 1.0 / tan(half);
}

static void render_view(render_ctx *r, const view_camera *cam, const double *center, double radius)
{
    const neuv_mesh *m = r->m;
    const double half = 0.5 * r->cell;
    /* Light from the viewer, a little from the upper left, so facing surfaces are bright. */
    double light[3];
    for (int k = 0; k < 3; k++) light[k] = -cam->rot[2][k] + 0.35 * cam->rot[1][k] - 0.25 * cam->rot[0][k];
    double ln = sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
    for (int k = 0; k < 3; k++) light[k] /= ln;
    for (int f = 0; f < m->nf; f++) {
        double p[3][2];
        int ok = 1;
        for (int c = 0; c < 3 && ok; c++) {
            const double *x = m->pos + 3 * m->tri[3 * f + c];
            double d[3] = {(x[0] - center[0]) / radius, (x[1] - center[1]) / radius, (x[2] - center[2]) / radius};
            double cx = cam->rot[0][0] * d[0] + cam->rot[0][1] * d[1] + cam->rot[0][2] * d[2];
            double cy = cam->rot[1][0] * d[0] + cam->rot[1][1] * d[1] + cam->rot[1][2] * d[2];
            double cz = cam->rot[2][0] * d[0] + cam->rot[2][1] * d[1] + cam->rot[2][2] * d[2] + cam->dist / radius;
            if (!(cz > 1e-6)) { ok = 0; break; }
            p[c][0] = half + half * cam->focal * cx / cz;
            p[c][1] = half - half * cam->focal * cy / cz;
            r->inv_z[c] = 1.0 / cz;
            if (r->has_uv) {
                const double *uv = m->uv + 2 * m->tri_uv[3 * f + c];
                r->uvz[c][0] = uv[0] / cz;
                r->uvz[c][1] = uv[1] / cz;
            }
        }
        if (!ok) continue;
        double n[3];
        mesh_face_normal(m, f, n);
        double lam = fabs(n[0] * light[0] + n[1] * light[1] + n[2] * light[2]);
        r->shade = 0.28 + 0.72 * lam; /* two-sided, so open meshes show their inside */
        if (r->label) {
            if (r->label[f] >= 0) raster_palette(r->label[f], r->base);
            else r->base[0] = r->base[1] = r->base[2] = 150;
        }
        raster_triangle(p, r->cell, r->cell, shade_pixel, r);
    }
}

neuv_status render_four_views(const neuv_mesh *m, const int *face_label, int checker_squares, int size,
                              raster_image *out)
{
    memset(out, 0, sizeof *out);
    if (size < 16) size = 16;
    int cell = size / 2;
    if (raster_image_init(out, 2 * cell, 2 * cell, render_background) != 0) return error_nomem("preview image");
    float *depth = mem_alloc(sizeof *depth * (size_t)out->w * out->h);
    if (!depth) { raster_image_free(out); return error_nomem("preview depth buffer"); }
    for (size_t i = 0; i < (size_t)out->w * out->h; i++) depth[i] = 0;
    double lo[3], hi[3], center[3], radius = 0;
    mesh_bounding_box(m, lo, hi);
    for (int k = 0; k < 3; k++) center[k] = 0.5 * (lo[k] + hi[k]);
    for (int v = 0; v < m->nv; v++) {
        const double *x = m->pos + 3 * v;
        double d = sqrt((x[0] - center[0]) * (x[0] - center[0]) + (x[1] - center[1]) * (x[1] - center[1]) +
                        (x[2] - center[2]) * (x[2] - center[2]));
        if (d > radius) radius = d;
    }
    if (!(radius > 0) || !isfinite(radius)) radius = 1;

    render_ctx r;
    memset(&r, 0, sizeof r);
    r.m = m; r.label = face_label; r.img = out; r.depth = depth; r.cell = cell;
    r.has_uv = m->nuv > 0 && m->tri_uv != NULL;
    if (r.has_uv && !face_label) {
        double ulo[2] = {DBL_MAX, DBL_MAX}, uhi[2] = {-DBL_MAX, -DBL_MAX};
        for (int u = 0; u < m->nuv; u++)
            for (int d = 0; d < 2; d++) {
                ulo[d] = fmin(ulo[d], m->uv[2 * u + d]);
                uhi[d] = fmax(uhi[d], m->uv[2 * u + d]);
            }
        int unit = ulo[0] >= 0 && ulo[1] >= 0 && uhi[0] <= 1 && uhi[1] <= 1;
        double ext = unit ? 1 : fmax(uhi[0] - ulo[0], uhi[1] - ulo[1]);
        r.uv0[0] = unit ? 0 : ulo[0];
        r.uv0[1] = unit ? 0 : ulo[1];
        r.freq = ext > 0 ? checker_squares / ext : 1;
    }
    /* front (from +z), back (from -z), left (from -x), top (from +y, front edge down). */
    static const double fwd[4][3] = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {0, -1, 0}};
    static const double up[4][3] = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 0, -1}};
    for (int v = 0; v < 4; v++) {
        view_camera cam;
        make_camera(&cam, fwd[v], up[v], radius);
        cam.dist = 3.0 * radius;
        r.ox = (v % 2) * cell;
        r.oy = (v / 2) * cell;
        render_view(&r, &cam, center, radius);
    }
    /* Thin separators between the views. */
    static const uint8_t sep[3] = {70, 72, 80};
    raster_fill_rect(out, cell - 1, 0, cell + 1, out->h, sep);
    raster_fill_rect(out, 0, cell - 1, out->w, cell + 1, sep);
    mem_free(depth);
    return NEUV_OK;
}
