/* pngfile.h - PNG images through libpng (named pngfile, not png, so it never shadows libpng's
 * own <png.h>).  Lecture slide 10: PNG is the low dynamic range format; its 8- or 16-bit values
 * are encoded (sRGB, or a power law its gAMA chunk names), so reading decodes them to linear
 * radiance, and writing tone maps first.
 *
 *     image tex = {0};
 *     if (pngfile_read("wood.png", &tex, &err)) return -1;          // linear RGB in [0,1]
 *     if (pngfile_write("out.png", &render, NULL, &err)) return -1;  // tone mapped, atomic
 *
 * Reading accepts every PNG colour type and depth: grey (1-16 bit, replicated to r = g = b),
 * grey + alpha, RGB, RGBA (8 or 16 bit) and palette; alpha is dropped; interlaced files are
 * fine.  The decoding curve follows libpng's rule: a file with an sRGB chunk, an iCCP chunk
 * (the profile itself is not applied) or no colour chunk at all is sRGB encoded and decoded
 * with tonemap_srgb_decode; a gAMA chunk without sRGB or iCCP is a power law, encoded =
 * linear^file_gamma, decoded as linear = code^(1/file_gamma) (gAMA 0.45455: code^2.2).  cHRM is
 * ignored (the primaries are taken as sRGB's).  The size in IHDR is checked with
 * image_check_size before any pixel memory is allocated; a corrupt or truncated file is an
 * error, never a crash (libpng errors are caught with setjmp / longjmp).
 * Writing makes an 8-bit RGB PNG; the file is complete or absent (imageio_tmp_*).
 */
#ifndef ENVTEX_PNGFILE_H
#define ENVTEX_PNGFILE_H

#include <stdint.h>

#include "envtex/error.h"
#include "envtex/image.h"
#include "envtex/tonemap.h"

/* The 8-byte PNG signature. */
#define PNGFILE_MAGIC "\x89PNG\r\n\x1a\n"

/* Read `path` into *out (linear RGB; *out must not own pixels; it stays empty on failure). */
int pngfile_read(const char *path, image *out, error *err);

/* Tone map `im` with `tm` (NULL: tonemap_defaults()) and write it as 8-bit RGB, atomically. */
int pngfile_write(const char *path, const image *im, const tonemap_params *tm, error *err);

/* Write w x h pixels of already encoded 8-bit RGB (row 0 at the top, 3 bytes a pixel, no row
 * padding) as an 8-bit RGB PNG, atomically.  An sRGB chunk is written: the bytes are taken as
 * sRGB. */
int pngfile_write_rgb8(const char *path, int w, int h, const uint8_t *rgb8, error *err);

#endif
