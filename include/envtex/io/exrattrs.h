/* exrattrs.h - the envtex attributes of an OpenEXR header, on a context exrfile.c has open
 * (the public calls: exrfile_write_attrs, exrfile_read_attrs in exrfile.h).
 *
 *     r = exrattrs_set(ctx, part, &at);          // before exr_write_header
 *     if (exrattrs_get(ctx, &at, path, &err)) return -1;
 */
#ifndef ENVTEX_EXRATTRS_H
#define ENVTEX_EXRATTRS_H

#include <openexr.h>
#include <stdint.h>

#include "envtex/core/error.h"

/* What a render records in its header: envtex:spp (int), envtex:seed (decimal string, 64 bits),
 * envtex:integrator, envtex:scene (strings).  A field 0 / "" / has_seed 0 is not written, and
 * reads back so when absent. */
#define EXRFILE_TEXT_MAX 256
typedef struct exrfile_attrs {
    int spp;      /* samples per pixel, >= 1; 0: unknown */
    int has_seed; /* 1 when seed holds the render's seed */
    uint64_t seed;
    char integrator[EXRFILE_TEXT_MAX]; /* the scene's `integrator` name, "" unknown */
    char scene[EXRFILE_TEXT_MAX];      /* the scene file as named on the command line */
} exrfile_attrs;

/* Set at's known fields (NULL: none) on `part` before the header is written; OpenEXRCore's
 * result. */
exr_result_t exrattrs_set(exr_context_t ctx, int part, const exrfile_attrs *at);

/* Part 0's attributes into *at (absent fields are left alone).  0, or -1 with err naming `path`:
 * envtex:spp not an int >= 1, envtex:seed not a whole number, a text one not a string. */
int exrattrs_get(exr_context_t ctx, exrfile_attrs *at, const char *path, error *err);

#endif
