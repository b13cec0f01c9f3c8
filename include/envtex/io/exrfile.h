/* exrfile.h - OpenEXR images through OpenEXR's C API (OpenEXRCore 3.1).  Lecture slide 10 (HDR
 * images): OpenEXR stores linear radiance as half or float, which is why environment maps use it.
 *
 *     image sky = {0};
 *     if (exrfile_read("sky.exr", &sky, &mem, &err)) return -1;     // linear RGB float
 *     if (exrfile_write("out.exr", &sky, 1, &err)) return -1; // half float, ZIP, atomic
 *     image_free(&sky);
 *
 * Reading (part 0 of the file):
 * - scanline and tiled parts (tiled: level 0 of a mip/rip map); deep parts are refused;
 * - channels, matched case-sensitively as OpenEXR does: R, G, B (A and others ignored); else Y
 *   alone (grey, replicated to r = g = b); else one layer's "LAYER.R", "LAYER.G", "LAYER.B" when
 *   exactly one layer has all three.  Luminance-chroma files (Y with RY/BY) and sub-sampled
 *   channels are refused;
 * - pixel types half, float and uint (uint converted to float as is);
 * - every compression OpenEXRCore 3.1 decodes: none, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A.
 *   DWAA / DWAB are refused with a message saying how to re-save the file;
 * - the image is the display window; data-window pixels land at (x - display.min.x,
 *   y - display.min.y), pixels of the display window outside the data window are 0, and
 *   data-window pixels outside the display window are dropped;
 * - sizes are checked (image_check_size) before anything is allocated; a truncated or corrupt
 *   file is an error naming the file, never a crash.
 * Writing: one scanline part, channels R, G, B as float (half = 0) or half (half = 1, values
 * rounded to nearest: below 65520 in magnitude at most the largest half, 65504; from +-65520
 * on, +-Inf), ZIP compression, increasing y, display window = data window = (0,0)-(w-1,h-1).
 * Atomic: a temporary file beside `path` is renamed over it only when complete
 * (imageio_tmp_*).
 */
#ifndef ENVTEX_EXRFILE_H
#define ENVTEX_EXRFILE_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"

/* The 4 magic bytes that open every OpenEXR file: 76 2f 31 01. */
#define EXRFILE_MAGIC "\x76\x2f\x31\x01"

/* Read the regular file `path` into *out (which must not own pixels; it stays empty on
 * failure).  Charged to `mem` from the header before allocating (budget.h; NULL: none): the
 * image, 12 bytes a texel of the display window, which stays charged, and the buffers that
 * decode the largest chunk (ours, 12 bytes a texel, and the library's packed and unpacked
 * bytes), released when read. */
int exrfile_read(const char *path, image *out, budget *mem, error *err);

/* Write `im` to `path`: RGB float (half == 0) or half (half != 0), ZIP, scanline, atomic. */
int exrfile_write(const char *path, const image *im, int half, error *err);

#endif
