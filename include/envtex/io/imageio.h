/* imageio.h - images by file name, the entry point the rest of envtex uses (slide 10 (High Dynamic
 * Range), HDR images): OpenEXR, Radiance RGBE, PFM, PNG (exrfile.h, rgbe.h, pfm.h, pngfile.h).
 *
 *     if (imageio_read("sky.exr", &im, &mem, &err)) ...       // "sky.exr: truncated ..."
 *
 * Reading picks the format by magic bytes, writing by extension; writes are atomic.  Only
 * regular files are read (infile.h); a hostile header is refused before allocation (`mem`,
 * NULL: none, keeps the image charged).  Errors name the file.
 */
#ifndef ENVTEX_IMAGEIO_H
#define ENVTEX_IMAGEIO_H

#include <stdio.h>

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/io/exrfile.h"
#include "envtex/io/tonemap.h"

/* An image into *out (linear RGB; grey replicated, alpha dropped), owning no pixels before;
 * empty on failure. */
int imageio_read(const char *path, image *out, budget *mem, error *err);

/* The format by magic bytes; IMAGEIO_UNKNOWN if unreadable, not regular, or none of them. */
typedef enum imageio_format {
    IMAGEIO_UNKNOWN,
    IMAGEIO_EXR,
    IMAGEIO_PNG,
    IMAGEIO_RGBE,
    IMAGEIO_PFM
} imageio_format;
imageio_format imageio_detect(const char *path);

/* Write `im` by extension (.exr .png .pfm .hdr, any case; others fail), `tm` for .png (NULL:
 * tonemap_defaults()).  An empty or oversized image fails, writing nothing. */
int imageio_write(const char *path, const image *im, const tonemap_params *tm, error *err);

/* The same in `format` whatever the name (IMAGEIO_UNKNOWN: by the extension). */
int imageio_write_as(const char *path, imageio_format format, const image *im,
                     const tonemap_params *tm, error *err);

/* n (1..IMAGEIO_SET_MAX) images, all or none: renamed into place only when all are written;
 * a failure leaves every target untouched (a failed rename says how many were replaced).
 * tms[k], formats[k] as imageio_write_as's; either array may be NULL. */
#define IMAGEIO_SET_MAX 6
int imageio_write_set(int n, const char *const *paths, const image *const *images,
                      const tonemap_params *const *tms, const imageio_format *formats, error *err);

/* imageio_write_set with the attributes `at` (exrfile.h) in the header of each OpenEXR file of
 * the set; other formats have no place for them.  at may be NULL: imageio_write_set. */
int imageio_write_set_attrs(int n, const char *const *paths, const image *const *images,
                            const tonemap_params *const *tms, const imageio_format *formats,
                            const exrfile_attrs *at, error *err);

/* 1 if imageio_write knows the extension of `path`, else 0. */
int imageio_can_write(const char *path);

#endif
