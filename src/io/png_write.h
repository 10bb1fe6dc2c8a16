/* PNG output through libpng, written atomically (temporary file, then rename). */
#ifndef NEUV_IO_PNG_WRITE_H
#define NEUV_IO_PNG_WRITE_H

#include <stdint.h>

#include "neuv/neuv.h"

/* Writes an 8-bit RGB image.
 * Inputs: path, w by h pixels, rgb (#h by #w by 3) rows top to bottom.
 * Returns NEUV_OK, NEUV_ERR_IO when the path cannot be written,
 * NEUV_ERR_INPUT for an empty image. */
neuv_status png_write_rgb(const char *path, int w, int h, const uint8_t *rgb);

#endif
