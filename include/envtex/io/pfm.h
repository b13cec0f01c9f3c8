/* pfm.h - Portable Float Map images: a tiny text header and raw 32-bit floats.  Lecture slide
 * 10 (HDR images): the simplest lossless HDR format, handy for tests and tools.
 *
 *     if (pfm_write("render.pfm", &im, &err)) return -1;   // exact floats, atomic
 *     if (pfm_read("render.pfm", &back, &mem, &err)) return -1;
 *
 * Format: "PF" (colour) or "Pf" (grey, replicated to r = g = b on read), white space, width,
 * height, white space, a scale whose sign gives the byte order (negative: little endian,
 * positive: big endian; its magnitude is ignored), exactly one white-space character (or a
 * Windows line end "\r\n", when the file has room for the pixels after it), then
 * w * h * (3 or 1) floats.  Rows are stored BOTTOM to TOP; our images keep row 0 at the top, so
 * both functions flip.  Sizes are checked before allocation; a file shorter than its header
 * promises is an error.  Writing uses "PF", little endian (scale -1.0), atomically.
 */
#ifndef ENVTEX_PFM_H
#define ENVTEX_PFM_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"

/* Read the regular file `path` into *out (which must not own pixels; it stays empty on
 * failure).  Charged to `mem` before allocating (budget.h; NULL: none): the file's bytes while
 * it is read, and the image, 12 bytes a texel of the header's size, which stays charged. */
int pfm_read(const char *path, image *out, budget *mem, error *err);

/* Write `im` as a colour PFM, little endian, atomically.  Floats are stored exactly. */
int pfm_write(const char *path, const image *im, error *err);

#endif
