/* budget.h - the memory budget of a run: a loader charges what a header claims BEFORE it
 * allocates, so a small hostile file is refused with one line (docs/robustness.md).
 *
 *     if (budget_charge(&mem, w * 15.0 * h, path, 0, &err, "%ld x %ld texels x 15 bytes", w, h))
 *         return -1;
 *
 * Bytes are doubles (no overflow).  A NULL budget refuses nothing.  What a structure keeps
 * stays charged for the run; a loader releases only its scratch (budget_release).
 */
#ifndef ENVTEX_BUDGET_H
#define ENVTEX_BUDGET_H

#include <stddef.h>

#include "envtex/core/error.h"

/* 2 GiB */
#define BUDGET_DEFAULT (2.0 * 1024 * 1024 * 1024)

typedef struct budget {
    double limit; /* bytes the run may hold at once, > 0 */
    double used;  /* charged and not released */
    double peak;  /* the most `used` has been */
} budget;

/* A budget of `limit` bytes (> 0), nothing used. */
void budget_init(budget *b, double limit);

/* 0 if used + bytes <= limit (or b is NULL), used grows.  Else (NaN, Inf too) -1, nothing
 * charged, *err = file, line, "CLAIM = 3.75 GiB, beyond the memory budget of 2 GiB (...)". */
int budget_charge(budget *b, double bytes, const char *file, int line, error *err,
                  const char *claim_fmt, ...) __attribute__((format(printf, 6, 7)));

/* Give back `bytes` charged before.  Safe on NULL. */
void budget_release(budget *b, double bytes);

/* "512 bytes", "12 KiB", "3.75 GiB" (powers of 1024, 3 digits) into buf (>= 16 bytes). */
void budget_format(double bytes, char *buf, size_t size);

/* "512M", "1.5GiB", "65536": a number > 0, K M G T (1024s, any case), B or iB optional.  0
 * and *bytes set, or -1. */
int budget_parse(const char *text, double *bytes);

#endif
