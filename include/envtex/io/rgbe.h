/* rgbe.h - Radiance .hdr (RGBE: three 8-bit mantissas, one shared exponent), the oldest HDR
 * format for environment maps (slide 10 (High Dynamic Range)).
 *
 *     if (rgbe_read("sky.hdr", &sky, &mem, &err)) return -1;   // linear RGB float
 *     if (rgbe_write("copy.hdr", &sky, &err)) return -1;       // run-length encoded, atomic
 *
 * "#?", FORMAT=32-bit_rle_rgbe, then only "-Y H +X W"; flat, new and old RLE read.  (r, g, b,
 * e > 0) is ((r + 0.5) / 256) 2^(e - 128), e = 0 black.  Writing: negatives and NaN 0, +Inf
 * and beyond ~1.7e38 the largest.  Sizes checked first; corruption is an error.
 */
#ifndef ENVTEX_RGBE_H
#define ENVTEX_RGBE_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"

/* Read the regular file `path` into *out (owning no pixels; empty on failure).  `mem` (NULL:
 * none) is charged first: the file while read, the image (12 bytes a texel), which stays. */
int rgbe_read(const char *path, image *out, budget *mem, error *err);

/* Write `im` atomically, new-style RLE (flat for widths below 8 or above 32767). */
int rgbe_write(const char *path, const image *im, error *err);

/* The same with flat scanlines. */
int rgbe_write_flat(const char *path, const image *im, error *err);

/* One colour to RGBE bytes and back, as above. */
void rgbe_from_float(const float c[3], unsigned char out[4]);
void rgbe_to_float(const unsigned char in[4], float c[3]);

#endif
