#include "io/png_write.h"

#include <png.h>
#include <setjmp.h>

#include "core/atomic_file.h"
#include "core/error.h"

/* libpng reports errors by longjmp; keep the message for error_set. */
static void png_on_error(png_structp png, png_const_charp msg)
{
    char *buf = png_get_error_ptr(png);
    snprintf(buf, 200, "%s", msg);
    png_longjmp(png, 1);
}

static void png_on_warning(png_structp png, png_const_charp msg) { (void)png; (void)msg; }

neuv_status png_write_rgb(const char *path, int w, int h, const uint8_t *rgb)
{
    if (w <= 0 || h <= 0 || !rgb) return error_set(NEUV_ERR_INPUT, "%s: empty image", path);
    atomic_file af;
    neuv_status st = atomic_file_open(&af, path);
    if (st != NEUV_OK) return st;
    char msg[200] = "";
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, msg, png_on_error, png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        atomic_file_abort(&af);
        return error_nomem("PNG writer");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        atomic_file_abort(&af);
        return error_set(NEUV_ERR_IO, "%s: cannot write PNG: %s", path, msg);
    }
    png_init_io(png, af.fp);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, 9);
    png_write_info(png, info);
    for (int y = 0; y < h; y++) png_write_row(png, (png_const_bytep)(rgb + (size_t)y * w * 3));
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    return atomic_file_commit(&af);
}
