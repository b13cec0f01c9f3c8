/* pngfile.h - PNG images through libpng (named pngfile, not png, so it never shadows libpng's
 * own <png.h>).  Lecture slide 10: PNG is the low dynamic range format; its 8- or 16-bit values
 * are encoded (sRGB, or a power law its gAMA chunk names), so reading decodes them to linear
 * radiance, and writing tone maps first.
 *
 *     image tex = {0};
 *     if (pngfile_read("wood.png", &tex, &mem, &err)) return -1;          // linear RGB in [0,1]
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
 * Writing makes an 8-bit RGB PNG labelled with the curve its bytes are actually in, so viewers
 * and pngfile_read decode it back to the linear values: an sRGB chunk for the sRGB curve (the
 * default tone mapping), a gAMA chunk of 1/g and no sRGB chunk for c^(1/g) (a scene's `gamma g`).
 * The file is complete or absent (imageio_tmp_*).
 */
#ifndef ENVTEX_PNGFILE_H
#define ENVTEX_PNGFILE_H

#include <stdint.h>

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/io/tonemap.h"

/* The 8-byte PNG signature. */
#define PNGFILE_MAGIC "\x89PNG\r\n\x1a\n"

/* Read the regular file `path` into *out (linear RGB; *out must not own pixels; it stays empty
 * on failure).  Charged to `mem` from IHDR, before any pixel memory (budget.h; NULL: none): 15
 * bytes a texel (18 for 16-bit files): the image's 12, which stay charged, and libpng's decoded
 * rows, released when read. */
int pngfile_read(const char *path, image *out, budget *mem, error *err);

/* The largest gamma a PNG can record, and 1/PNGFILE_GAMMA_MAX the smallest: a gAMA chunk holds
 * the file gamma 1/g in units of 1e-5, and libpng accepts 16 to 625000000 of them. */
#define PNGFILE_GAMMA_MAX 6250.0

/* Tone map `im` with `tm` (NULL: tonemap_defaults()) and write it as 8-bit RGB, atomically,
 * labelled with the curve tm encoded it with: tm->gamma <= 0 (the sRGB curve) as
 * pngfile_write_rgb8 does, tm->gamma > 0 (c^(1/gamma)) as pngfile_write_rgb8_gamma does (so a
 * gamma outside [1/PNGFILE_GAMMA_MAX, PNGFILE_GAMMA_MAX] is an error). */
int pngfile_write(const char *path, const image *im, const tonemap_params *tm, error *err);

/* Write w x h pixels of already sRGB-encoded 8-bit RGB (row 0 at the top, 3 bytes a pixel, no
 * row padding) as an 8-bit RGB PNG with an sRGB chunk, atomically. */
int pngfile_write_rgb8(const char *path, int w, int h, const uint8_t *rgb8, error *err);

/* The same for bytes encoded with a power law, byte = round(255 c^(1/gamma)) (tonemap_params'
 * gamma > 0): the file gets a gAMA chunk of 1/gamma (PNG's file gamma: encoded =
 * linear^file_gamma; 2.2 is stored as 0.45455) and no sRGB chunk, so it decodes as code^gamma.
 * gamma must lie in [1/PNGFILE_GAMMA_MAX, PNGFILE_GAMMA_MAX]: otherwise an error, and nothing is
 * written. */
int pngfile_write_rgb8_gamma(const char *path, int w, int h, const uint8_t *rgb8, double gamma,
                             error *err);

#endif
