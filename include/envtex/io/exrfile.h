/* exrfile.h - OpenEXR images (linear half or float radiance, lecture slide 10 (High Dynamic Range))
 * through OpenEXRCore 3.1.
 *
 *     if (exrfile_read("sky.exr", &sky, &mem, &err)) return -1;    // linear RGB float
 *     if (exrfile_write("out.exr", &sky, 1, &err)) return -1;      // half float, ZIP, atomic
 *     exrfile_attrs at = {.spp = 64};                              // what a render records
 *     if (exrfile_write_attrs("img.exr", &sky, 0, &at, &err)) return -1;
 *
 * Reading takes part 0 (scanline, or level 0 of tiles), half, float or uint, any compression
 * but DWAA / DWAB; channels R, G, B, else Y (grey), else one layer's "LAYER.R/G/B".  The image
 * is the display window (pixels outside the data window are 0).  Writing: one scanline part,
 * R, G, B, ZIP, windows (0,0)-(w-1,h-1), atomic (fileio.h).  Errors name the file; a corrupt
 * or hostile file is an error, never a crash.
 */
#ifndef ENVTEX_EXRFILE_H
#define ENVTEX_EXRFILE_H

#include <stdint.h>

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/io/exrattrs.h"

/* The 4 magic bytes that open every OpenEXR file: 76 2f 31 01. */
#define EXRFILE_MAGIC "\x76\x2f\x31\x01"

/* Read the regular file `path` into *out (which must not own pixels; it stays empty on
 * failure).  Refused: deep parts, luminance-chroma and sub-sampled channels, sizes
 * image_check_size refuses, a header claiming more than the file holds.  Charged to `mem`
 * before allocating (NULL: none): the image (stays charged) and the largest chunk's decoding
 * buffers (released when read). */
int exrfile_read(const char *path, image *out, budget *mem, error *err);

/* Write `im` to `path`: float (half == 0) or half (rounded to nearest, beyond it +-Inf), ZIP,
 * atomic: nothing is left on failure. */
int exrfile_write(const char *path, const image *im, int half, error *err);

/* exrfile_write with `at`'s fields added to the header (at may be NULL: exrfile_write).
 * Strings are cut to EXRFILE_TEXT_MAX - 1 bytes. */
int exrfile_write_attrs(const char *path, const image *im, int half, const exrfile_attrs *at,
                        error *err);

/* The envtex attributes of `path` into *at (absent: 0 / ""), from the header only.  0, or -1
 * with *err (cannot open, not OpenEXR, an attribute of the wrong type or spp < 1) and *at
 * unknown. */
int exrfile_read_attrs(const char *path, exrfile_attrs *at, error *err);

#endif
