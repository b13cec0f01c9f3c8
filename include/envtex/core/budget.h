/* budget.h - the memory budget of one run: every loader charges what a file's header claims,
 * times the bytes each decoded element will take, BEFORE it allocates, so a small hostile file
 * (a decompression bomb, a mesh named four hundred times) is refused at once with one line
 * instead of costing gigabytes.  docs/robustness.md, "The memory budget", lists what is charged.
 *
 *     budget mem;
 *     budget_init(&mem, BUDGET_DEFAULT);
 *     if (budget_charge(&mem, (double)w * h * 15, path, 0, &err, "%ld x %ld texels x 15 bytes",
 *                       w, h))
 *         return -1;  // "a.png: 16384 x 16384 texels x 15 bytes = 3.75 GiB, beyond the memory ..."
 *     ... allocate, decode ...
 *     budget_release(&mem, (double)w * h * 3);  // the row buffer, freed again
 *
 * Conventions: sizes are bytes held in doubles (exact below 2^53, and the product of a hostile
 * header's fields cannot overflow before it is compared).  A NULL budget charges nothing and
 * refuses nothing: only the hard limits (IMAGE_MAX_PIXELS, SCENE_MAX_PRIMS, ...) apply.  The
 * library keeps no budget of its own: the caller passes one in the load options (scene_load_opts,
 * render_opts) or as the readers' `mem` argument.  What a structure keeps stays charged for the
 * run (freeing it does not release it); a loader releases only its own scratch buffers.
 */
#ifndef ENVTEX_BUDGET_H
#define ENVTEX_BUDGET_H

#include <stddef.h>

#include "envtex/core/error.h"

/* The default for a run: 2 GiB.  Below the 3 GiB one 2^28-texel float image (IMAGE_MAX_PIXELS)
 * takes, above a 16384 x 8192 map's 1.5 GiB. */
#define BUDGET_DEFAULT (2.0 * 1024 * 1024 * 1024)

typedef struct budget {
    double limit; /* bytes the run may hold at once, > 0 */
    double used;  /* charged and not released */
    double peak;  /* the most `used` has been */
} budget;

/* A budget of `limit` bytes (> 0), nothing used. */
void budget_init(budget *b, double limit);

/* Charge `bytes` (>= 0): 0 if used + bytes <= limit (or b is NULL), and then used grows by it.
 * Otherwise -1 and nothing charged, with *err set as error_set(err, file, line, ...) does to
 *     "CLAIM = 3.75 GiB, beyond the memory budget of 2 GiB (12 MiB of it in use; envtex
 *      --memory-budget SIZE sets it)"
 * where CLAIM is claim_fmt formatted as printf does: what the bytes are ("16384 x 16384 texels
 * x 15 bytes").  A NaN or infinite `bytes` is refused too. */
int budget_charge(budget *b, double bytes, const char *file, int line, error *err,
                  const char *claim_fmt, ...) __attribute__((format(printf, 6, 7)));

/* Give back `bytes` charged before (a freed scratch buffer).  Safe on NULL. */
void budget_release(budget *b, double bytes);

/* Bytes as a person writes them, into buf (at least 16 bytes): "512 bytes", "12 KiB",
 * "3.75 GiB" (powers of 1024, three significant digits). */
void budget_format(double bytes, char *buf, size_t size);

/* A size as the command line gives it: a number > 0 with an optional suffix K, M, G or T
 * (powers of 1024, either case, optionally followed by B or iB): "512M", "4G", "1.5GiB",
 * "65536".  0 and *bytes set, or -1 for anything else. */
int budget_parse(const char *text, double *bytes);

#endif
