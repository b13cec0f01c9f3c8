/* pngfile.h - PNG through libpng (pngfile: it never shadows <png.h>), slide 10 (High Dynamic
 * Range)'s low dynamic range format: reading decodes to linear radiance, writing tone maps first.
 *
 *     if (pngfile_read("wood.png", &tex, &mem, &err)) return -1;     // linear RGB in [0,1]
 *
 * Every colour type and depth is read (grey replicated, alpha dropped).  As libpng: sRGB,
 * iCCP (not applied) or no chunk is sRGB; a lone gAMA a power law, code^(1/file_gamma); cHRM
 * ignored.  A corrupt file is an error.
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

/* Read the regular file `path` into *out (owning no pixels; empty on failure).  `mem` (NULL:
 * none) is charged from IHDR first, 15 bytes a texel (18 if 16-bit): the image's 12 stay,
 * libpng's rows are released. */
int pngfile_read(const char *path, image *out, budget *mem, error *err);

/* The largest gamma a gAMA chunk records; 1/PNGFILE_GAMMA_MAX the smallest. */
#define PNGFILE_GAMMA_MAX 6250.0

/* Tone map `im` with `tm` (NULL: tonemap_defaults()) and write 8-bit RGB atomically, as
 * pngfile_write_rgb8 (gamma <= 0) or pngfile_write_rgb8_gamma (gamma > 0) label it. */
int pngfile_write(const char *path, const image *im, const tonemap_params *tm, error *err);

/* w x h sRGB-encoded pixels (row 0 at the top, 3 bytes each, no padding) as an 8-bit RGB PNG
 * with an sRGB chunk, atomically. */
int pngfile_write_rgb8(const char *path, int w, int h, const uint8_t *rgb8, error *err);

/* The same for bytes round(255 c^(1/gamma)): a gAMA chunk of 1/gamma, no sRGB chunk.  gamma
 * outside [1/PNGFILE_GAMMA_MAX, PNGFILE_GAMMA_MAX] fails, writing nothing. */
int pngfile_write_rgb8_gamma(const char *path, int w, int h, const uint8_t *rgb8, double gamma,
                             error *err);

#endif
