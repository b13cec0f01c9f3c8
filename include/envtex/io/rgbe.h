/* rgbe.h - Radiance .hdr images (RGBE: three 8-bit mantissas sharing one 8-bit exponent, Greg
 * Ward's format).  Lecture slide 10 (HDR images): the oldest common HDR format for
 * environment maps.
 *
 *     image sky = {0};
 *     if (rgbe_read("sky.hdr", &sky, &mem, &err)) return -1;   // linear RGB float
 *     if (rgbe_write("copy.hdr", &sky, &err)) return -1;  // run-length encoded, atomic
 *
 * Format: a text header whose first line starts with "#?" (usually "#?RADIANCE" or "#?RGBE"),
 * variable lines up to an empty line (FORMAT= must be 32-bit_rle_rgbe; other variables such as
 * EXPOSURE are ignored, as most readers do), then the resolution line.  Only the standard
 * orientation "-Y H +X W" (rows top to bottom, left to right) is accepted; others are refused
 * with a message.  Scanlines may be new-style run-length encoded, flat, or old-style RLE.
 * A pixel (r, g, b, e) with e > 0 decodes to ((r + 0.5) / 256) 2^(e - 128) (Radiance's own
 * rounding: the middle of the mantissa bin); e = 0 is black.
 * Sizes are checked (image_check_size) before allocation; truncated data, runs that overflow
 * the scanline and other corruption are errors, never crashes.
 * Writing: values below 0 and NaN store as 0, +Inf and values beyond the largest RGBE value
 * (about 1.7e38) as the largest.  Relative precision is 1/256 of the brightest channel.
 */
#ifndef ENVTEX_RGBE_H
#define ENVTEX_RGBE_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"

/* Read the regular file `path` into *out (which must not own pixels; it stays empty on
 * failure).  Charged to `mem` before allocating (budget.h; NULL: none): the file's bytes while
 * it is read, and the image, 12 bytes a texel of the header's size, which stays charged. */
int rgbe_read(const char *path, image *out, budget *mem, error *err);

/* Write `im` with new-style run-length encoded scanlines (flat when the width is below 8 or
 * above 32767, where RLE is not defined), atomically. */
int rgbe_write(const char *path, const image *im, error *err);

/* Write `im` with flat (uncompressed) scanlines, atomically. */
int rgbe_write_flat(const char *path, const image *im, error *err);

/* One colour to RGBE bytes and back (the per-pixel rules above). */
void rgbe_from_float(const float c[3], unsigned char out[4]);
void rgbe_to_float(const unsigned char in[4], float c[3]);

#endif
