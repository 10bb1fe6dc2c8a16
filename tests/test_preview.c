/* Preview pictures: both PNGs exist with the expected size (read back with
 * libpng), the checker render covers a plausible share of its image, the UV
 * picture shows the charts where the UVs are, and a label picture works. */
#include "check.h"

#include <png.h>

#include "atlas/preview.h"
#include "atlas/render_views.h"
#include "mesh/mesh.h"
#include "mesh/shapes.h"

/* Reads an RGB(A) PNG into 8-bit RGB; returns NULL on failure. */
static unsigned char *read_png(const char *path, int *w, int *h)
{
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path)) return NULL;
    img.format = PNG_FORMAT_RGB;
    unsigned char *buf = malloc(PNG_IMAGE_SIZE(img));
    if (!buf || !png_image_finish_read(&img, NULL, buf, 0, NULL)) { free(buf); png_image_free(&img); return NULL; }
    *w = (int)img.width; *h = (int)img.height;
    return buf;
}

static double share_not(const unsigned char *rgb, int w, int h, const uint8_t bg[3])
{
    long n = 0;
    for (long i = 0; i < (long)w * h; i++)
        if (memcmp(rgb + 3 * i, bg, 3)) n++;
    return (double)n / ((double)w * h);
}

/* A cylinder-like tube with an unrolled UV map (one seam), UVs in [0,1]^2. */
static neuv_mesh *tube(int nu, int nv)
{
    neuv_mesh *m = mesh_create((nu + 1) * (nv + 1), 2 * nu * nv, (nu + 1) * (nv + 1));
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            int k = j * (nu + 1) + i;
            double t = 6.283185307179586 * i / nu;
            m->pos[3 * k] = cos(t); m->pos[3 * k + 1] = 2.0 * j / nv - 1; m->pos[3 * k + 2] = sin(t);
            m->uv[2 * k] = 0.05 + 0.9 * i / nu; m->uv[2 * k + 1] = 0.3 + 0.3 * j / nv;
        }
    int f = 0;
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            int a = j * (nu + 1) + i, b = a + 1, c = a + nu + 2, d = a + nu + 1;
            int t1[3] = {a, c, b}, t2[3] = {a, d, c};
            memcpy(m->tri + 3 * f, t1, sizeof t1); memcpy(m->tri_uv + 3 * f, t1, sizeof t1); f++;
            memcpy(m->tri + 3 * f, t2, sizeof t2); memcpy(m->tri_uv + 3 * f, t2, sizeof t2); f++;
        }
    /* Close the tube: the last column's positions are the first column's. */
    for (int j = 0; j <= nv; j++) {
        int first = j * (nu + 1), last = first + nu;
        for (int d = 0; d < 3; d++) m->pos[3 * last + d] = m->pos[3 * first + d];
    }
    return m;
}

int main(void)
{
    neuv_mesh *m = tube(48, 16);
    const char *prefix = tmp_path("preview-tube");
    CHECK_INT(preview_write(m, prefix, PREVIEW_COLOR_CHART), NEUV_OK);
    char path[4200];
    int w = 0, h = 0;

    snprintf(path, sizeof path, "%s-uv.png", prefix);
    unsigned char *uv = read_png(path, &w, &h);
    CHECK(uv != NULL);
    if (uv) {
        CHECK_INT(w, 1024);
        CHECK_INT(h, 1024);
        /* The map fills u in [0.05,0.95], v in [0.3,0.6]: a pixel inside is
         * coloured (not the white background), one outside is white. */
        const unsigned char *in = uv + 3 * ((size_t)(1024 - (int)(0.45 * 1024)) * 1024 + 512);
        const unsigned char *out = uv + 3 * ((size_t)(1024 - (int)(0.8 * 1024)) * 1024 + 512);
        CHECK(!(in[0] == 250 && in[1] == 250 && in[2] == 250));
        CHECK(out[0] == 250 && out[1] == 250 && out[2] == 250);
        /* No overlaps in this map: no magenta pixel anywhere. */
        long magenta = 0;
        for (long i = 0; i < 1024L * 1024; i++)
            if (uv[3 * i] == 255 && uv[3 * i + 1] == 0 && uv[3 * i + 2] == 255) magenta++;
        CHECK_INT(magenta, 0);
        free(uv);
    }

    snprintf(path, sizeof path, "%s-checker.png", prefix);
    unsigned char *ck = read_png(path, &w, &h);
    CHECK(ck != NULL);
    if (ck) {
        CHECK_INT(w, 1024);
        CHECK_INT(h, 1024);
        double s = share_not(ck, w, h, render_background);
        printf("checker render covers %.1f%% of the image\n", 100 * s);
        CHECK(s > 0.10 && s < 0.80);
        free(ck);
    }

    /* Folding the map onto itself must show overlaps in magenta. */
    for (int u = 0; u < m->nuv; u++)
        if (m->uv[2 * u] > 0.5) m->uv[2 * u] = 1.0 - m->uv[2 * u];
    const char *fold = tmp_path("preview-fold");
    CHECK_INT(preview_write(m, fold, PREVIEW_COLOR_QCE), NEUV_OK);
    snprintf(path, sizeof path, "%s-uv.png", fold);
    uv = read_png(path, &w, &h);
    CHECK(uv != NULL);
    if (uv) {
        long magenta = 0;
        for (long i = 0; i < (long)w * h; i++)
            if (uv[3 * i] == 255 && uv[3 * i + 1] == 0 && uv[3 * i + 2] == 255) magenta++;
        CHECK(magenta > 1000);
        free(uv);
    }

    /* Labels: four views coloured by label. */
    int *label = malloc(sizeof(int) * m->nf);
    for (int f = 0; f < m->nf; f++) label[f] = f % 3;
    const char *lp = tmp_path("preview-labels.png");
    CHECK_INT(preview_write_labels(m, label, lp), NEUV_OK);
    unsigned char *lb = read_png(lp, &w, &h);
    CHECK(lb != NULL);
    if (lb) {
        CHECK_INT(w, 1024);
        double s = share_not(lb, w, h, render_background);
        CHECK(s > 0.10 && s < 0.80);
        free(lb);
    }
    free(label);

    /* Sized variant and bad input. */
    CHECK_INT(preview_write_sized(m, tmp_path("preview-small"), PREVIEW_COLOR_AREA, 256), NEUV_OK);
    snprintf(path, sizeof path, "%s-checker.png", tmp_path("preview-small"));
    unsigned char *sm = read_png(path, &w, &h);
    CHECK(sm != NULL && w == 256 && h == 256);
    free(sm);
    neuv_mesh *bare = shape_cube(2);
    if (bare) CHECK_INT(preview_write(bare, tmp_path("preview-bare"), PREVIEW_COLOR_CHART), NEUV_ERR_INPUT);
    mesh_free(bare);
    CHECK(preview_write(m, "/nonexistent-dir/x", PREVIEW_COLOR_CHART) != NEUV_OK);
    mesh_free(m);
    return check_report("test_preview");
}
