/* pfm.h - Portable Float Map: a text header and raw floats, slide 10 (High Dynamic Range)'s
 * simplest HDR format.
 *
 *     if (pfm_write("render.pfm", &im, &err)) return -1;   // exact floats, atomic
 *
 * "PF" (colour) or "Pf" (grey, replicated), w, h, a scale whose sign is the byte order (< 0:
 * little endian), one white space (or "\r\n"), the floats, rows BOTTOM to TOP (flipped).
 */
#ifndef ENVTEX_PFM_H
#define ENVTEX_PFM_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"

/* Read the regular file `path` into *out (owning no pixels; empty on failure).  `mem` (NULL:
 * none) is charged first: the file while read, the image (12 bytes a texel), which stays. */
int pfm_read(const char *path, image *out, budget *mem, error *err);

/* Write `im` as an exact colour PFM, little endian, atomically. */
int pfm_write(const char *path, const image *im, error *err);

#endif
