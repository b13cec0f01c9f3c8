/* imageio.h - read and write images by file name: the one entry point the rest of envtex uses.
 * Lecture slide 10 (HDR images): environment maps are OpenEXR (.exr), Radiance (.hdr, RGBE) or
 * PFM; textures may also be PNG.
 *
 *     image im = {0};
 *     if (imageio_read("data/envmaps/sky.exr", &im, &mem, &err)) ... // "sky.exr: truncated ..."
 *     if (imageio_write("out/demo.png", &im, NULL, &err)) ...  // tone mapped sRGB, atomic
 *
 * Reading picks the format by the file's magic bytes (not its name): OpenEXR (76 2f 31 01),
 * PNG (its 8-byte signature), Radiance ("#?"), PFM ("PF" or "Pf").  Writing picks it by the
 * extension: .exr (linear float RGB, ZIP), .png (8-bit after tone mapping: sRGB, or c^(1/g) with
 * tm->gamma g, the file labelled with which), .pfm (linear float), .hdr (Radiance RGBE, run-length encoded).  Every write goes to a temporary file
 * "PATH.tmp.XXXXXX" in the same folder and is renamed over the target only when complete, so a
 * failure never leaves a partial file and an existing target stays byte-identical.
 * Errors name the file (err->file) and say what is wrong ("cannot open: No such file or
 * directory", "cannot open: it is a FIFO, not a regular file", "unknown image format ..."):
 * only regular files are read, opened without blocking (infile.h).  Hostile headers are refused
 * before any allocation: by the hard limits (image_check_size), by what the file can hold, and
 * by the memory budget `mem` (budget.h; NULL: none), charged with the decoded bytes the header
 * claims.  The image a reader returns stays charged; its scratch buffers are released.  The
 * formats themselves are in exrfile.h, pngfile.h, rgbe.h and pfm.h.
 */
#ifndef ENVTEX_IMAGEIO_H
#define ENVTEX_IMAGEIO_H

#include <stdio.h>

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/io/exrfile.h"
#include "envtex/io/tonemap.h"

/* Read any supported image into *out (linear RGB; PNG colour is decoded from sRGB, or with the
 * power law of a lone gAMA chunk (pngfile.h); grey is replicated, alpha dropped).  *out must
 * not own pixels; on failure it stays empty. */
int imageio_read(const char *path, image *out, budget *mem, error *err);

/* The format of the file at `path` by its magic bytes, as imageio_read picks it; unknown when
 * the file cannot be read (or is not a regular file) or is none of the four (imageio_read then
 * says why).  A PNG holds 8 bits a channel clamped to [0, 1]: a tester of linear HDR renders
 * refuses it (main.c). */
typedef enum imageio_format {
    IMAGEIO_UNKNOWN, IMAGEIO_EXR, IMAGEIO_PNG, IMAGEIO_RGBE, IMAGEIO_PFM
} imageio_format;
imageio_format imageio_detect(const char *path);

/* Write `im` to `path`, format by extension (.exr .png .pfm .hdr, case-insensitive; an
 * unknown extension is an error).  `tm` is used for .png only; NULL means tonemap_defaults().
 * An empty image (no pixels, or a size image_check_size refuses) is an error and nothing is
 * written.  Atomic (temporary file + rename). */
int imageio_write(const char *path, const image *im, const tonemap_params *tm, error *err);

/* imageio_write in the given format whatever the name says (IMAGEIO_UNKNOWN: by the
 * extension, as imageio_write).  For a scene's `output` without a known extension, which the
 * course skeleton writes as a PNG under that exact name. */
int imageio_write_as(const char *path, imageio_format format, const image *im, const tonemap_params *tm,
                     error *err);

/* Write n images (1 <= n <= IMAGEIO_SET_MAX) as one output, all or none: each goes first to
 * PATH with ".partial-PID" before its extension (a sibling, so the rename never crosses file
 * systems), and only when every one is complete are they renamed over their targets.  A failed
 * write removes the finished ones and leaves every target untouched; its error names the
 * target, not the temporary.  (Should a rename itself fail half way, the message says how many
 * targets were already replaced.)  One image is imageio_write itself.  tms[k] as imageio_write's
 * tm; tms may be NULL.  formats[k] as imageio_write_as's format; formats may be NULL (every
 * format by its extension).  Used for a render with its --variance image and for the six faces of a
 * cube map. */
#define IMAGEIO_SET_MAX 6
int imageio_write_set(int n, const char *const *paths, const image *const *images,
                      const tonemap_params *const *tms, const imageio_format *formats, error *err);

/* imageio_write_set with the attributes `at` (exrfile.h) in the header of each OpenEXR file of
 * the set; other formats have no place for them.  at may be NULL: imageio_write_set. */
int imageio_write_set_attrs(int n, const char *const *paths, const image *const *images,
                            const tonemap_params *const *tms, const imageio_format *formats,
                            const exrfile_attrs *at, error *err);

/* 1 if `path` ends in an extension imageio_write knows, else 0. */
int imageio_can_write(const char *path);

#endif
