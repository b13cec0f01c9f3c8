/* distrib.h - sampling discrete 1D and 2D distributions with numerical CDFs.
 * Lecture slides 16-23: "importance sample the environment map" and "sampling 2D distributions":
 * pick the OUTER variable from its marginal 1D CDF, then the INNER variable from the conditional
 * CDF of the chosen column.  Pure maths: nothing here knows about environment maps or scenes.
 *
 *     double w[4 * 2] = {...};             // w[outer * n_inner + inner] >= 0
 *     distrib2d d = {0};
 *     if (distrib2d_init(&d, w, 4, 2, &err)) return -1;
 *     int o, i;
 *     double pmf, ro, ri;
 *     distrib2d_sample(&d, xi1, xi2, &o, &i, &pmf, &ro, &ri); // cell (o, i), chosen with prob. pmf
 *     double u = (o + ro) / 4.0;                              // a continuous point in the cell
 *     distrib2d_free(&d);
 *
 * Two ways to sample the same distribution:
 *   - inversion by binary search over the CDF (`*_sample`): O(log n), and MONOTONE: a larger
 *     xi never gives a smaller bin, and within one bin the remapped value grows with xi.  Stratified or
 *     low-discrepancy inputs stay stratified, so use this one for them;
 *   - the alias method of Walker, built in O(n) with Vose's algorithm (`*_sample_alias`, after
 *     `*_alias_build`): O(1), but it scrambles the order of xi, so it does NOT preserve
 *     stratification; use it for independent random numbers.
 *
 * Conventions shared by every function:
 *   - xi in [0, 1).  Values outside are clamped, not rejected: xi < 0 or NaN acts as 0 and
 *     xi >= 1 (exactly 1 included) acts as the largest double below 1.  For the inversion
 *     samplers (`*_sample`) that always lands in the LAST bin of non-zero probability; an alias
 *     sampler reads the last cell, which may hand the pick to that cell's alias (still a bin of
 *     non-zero probability).
 *   - A bin of probability 0 is never returned, whatever xi: the search takes the first bin whose
 *     CDF value is > xi, so zero-width bins are skipped.
 *   - "pmf" is the discrete probability of the returned bin (it sums to 1 over the bins), not a
 *     density: a caller that wants a density over [0,1)^2 multiplies by n_outer * n_inner.
 *     The pmf a sampler returns is bit-for-bit what `distrib1d_pmf` / `distrib2d_pmf` return.
 *   - "remapped" is xi rescaled to [0, 1) within the chosen bin: uniform on [0, 1) and
 *     independent of the bin, so it can place a continuous point inside the bin or feed the
 *     next dimension.
 *   - Weights that are NaN, +-Inf or negative are counted in `n_bad` and treated as 0; if every
 *     weight is 0 the distribution falls back to uniform and sets `fell_back_to_uniform`.
 *   - pmf is a difference of two CDF entries, each known to about an ulp of 1, so a bin of
 *     probability p has a pmf within ~1e-16 / p relative of w / total (2e-8 for the dim cells
 *     beside a sun 10^8 times brighter).  A positive weight below ~1e-16 of the running sum
 *     before it gets a CDF step that rounds away: pmf 0, never chosen, like a zero weight
 *     (near the start of the CDF doubles are finer: weights {1e-30, 1} keep pmf 1e-30 for the
 *     first bin, {1, 1e-30} give the second pmf 0).
 *   - Sampling and pmf functions allocate nothing and do not modify the tables.
 *
 * Precision and memory.  CDFs are accumulated AND stored in double.  Storing the conditional
 * CDFs as float (half the memory) was measured and rejected: in a 4096-cell column holding a sun
 * 10^3 times brighter than the sky, float CDF steps put the pmf of the dim cells after the sun
 * off by up to 5%; at 10^5 some dim cells get a zero-width step and are NEVER sampled although
 * their weight is positive (a biased estimator); at 10^8 (a real sun) 2553 of 4096 cells vanish.
 * In double the CDF of an 8192 x 4096 grid (33.5M cells) is 268 MB, its last entries are
 * exactly 1 and the pmf sums to 1 within rounding (tested: < 1e-6).  Alias tables take 8 bytes a cell: a float threshold and an int32 alias.  The float
 * threshold rounds a cell's split by up to ~3e-8 of a cell.  The build hands the alias what the
 * stored threshold gives it (1 - prob, not 1 - q), so each rounding stays in the cell it
 * happened in and the roundings of many donors do not add up on one bin: a bin's sampled
 * probability is its pmf within ~3e-8 / (n pmf) relative (6e-8 for a bin of average
 * probability), far below Monte Carlo noise.
 */
#ifndef ENVTEX_DISTRIB_H
#define ENVTEX_DISTRIB_H

#include <stdint.h>

#include "envtex/core/error.h"

/* The most bins one table may have (1D: n; 2D: n_outer * n_inner), checked before allocating:
 * 2^28 like IMAGE_MAX_PIXELS, so indices and counts fit in an int. */
#define DISTRIB_MAX_BINS (1L << 28)

/* One cell of an alias table (Walker): with u uniform in [0,1) inside cell i, return i if
 * u < prob, else alias.  prob in [0, 1]; alias is a bin of positive probability. */
typedef struct distrib_alias {
    float prob;
    int32_t alias;
} distrib_alias;

/* A discrete distribution over bins 0 .. n-1. */
typedef struct distrib1d {
    int n;                    /* number of bins, >= 1 */
    double *cdf;              /* n + 1 entries: cdf[0] = 0, cdf[n] = 1 exactly, non-decreasing */
    double total;             /* sum of the weights used (bad weights as 0; n if all were 0) */
    int n_bad;                /* how many weights were NaN, +-Inf or negative (and used as 0) */
    int fell_back_to_uniform; /* 1 if every weight was 0 and the table is uniform */
    int first_nonzero;        /* first bin with positive pmf */
    int last_nonzero;         /* last bin with positive pmf */
    distrib_alias *alias;     /* n cells after distrib1d_alias_build, else NULL */
} distrib1d;

/* Build *d from n weights w[0 .. n-1] (double or float).  Allocates; free with distrib1d_free.
 * -1 if n < 1 or n > DISTRIB_MAX_BINS, if the weights' sum overflows a double, or if memory
 * runs out; *d is then left empty (safe to free).  Bad weights are not an error (see n_bad). */
int distrib1d_init(distrib1d *d, const double *w, int n, error *err);
int distrib1d_init_float(distrib1d *d, const float *w, int n, error *err);

/* Add an alias table to a built *d (O(n) time, 8n bytes) so distrib1d_sample_alias works.
 * -1 only if memory runs out (the CDF part stays usable).  Calling it twice is harmless. */
int distrib1d_alias_build(distrib1d *d, error *err);

/* Free everything *d owns and zero it.  Safe on a zeroed or already freed table. */
void distrib1d_free(distrib1d *d);

/* p_i = cdf[i + 1] - cdf[i], the probability of bin i; i must be in [0, n) (assert). */
double distrib1d_pmf(const distrib1d *d, int i);

/* Inversion by binary search: the bin i with cdf[i] <= xi < cdf[i + 1] (so p_i > 0).
 * *pmf = p_i; *remapped = (xi - cdf[i]) / p_i in [0, 1), non-decreasing in xi within a bin.
 * pmf and remapped may be NULL.  O(log n). */
int distrib1d_sample(const distrib1d *d, double xi, double *pmf, double *remapped);

/* The same distribution by the alias method, O(1); distrib1d_alias_build must have been called
 * (assert).  *pmf = p_i exactly as distrib1d_pmf; *remapped uniform in [0, 1) but NOT monotone
 * in xi.  pmf and remapped may be NULL. */
int distrib1d_sample_alias(const distrib1d *d, double xi, double *pmf, double *remapped);

/* A discrete distribution over an n_outer x n_inner grid of cells (lecture: outer = columns of
 * the environment map = phi, inner = rows = cos theta).  Weights are laid out outer-major:
 * w[outer * n_inner + inner].  p(outer) = sum_inner w / total is the marginal; within column
 * `outer`, p(inner | outer) = w / sum_inner w is the conditional. */
typedef struct distrib2d {
    int n_outer, n_inner;
    distrib1d marginal;       /* p(outer): n_outer bins */
    double *cond_cdf;         /* n_outer rows of n_inner + 1 entries: the conditional CDF of
                               * column o is cond_cdf + o * (n_inner + 1); a column of weight 0
                               * gets a uniform one (its marginal is 0, so it is used only
                               * when every column is 0: the uniform fallback) */
    double total;             /* sum of all weights used (n_outer n_inner if all were 0) */
    int n_bad;                /* weights that were NaN, +-Inf or negative (used as 0) */
    int fell_back_to_uniform; /* 1 if every weight was 0 and the grid is uniform */
    distrib_alias *cond_alias; /* n_outer * n_inner cells after distrib2d_alias_build, else NULL */
} distrib2d;

/* Build *d from w[outer * n_inner + inner], n_outer * n_inner weights (double or float).
 * Allocates about 8 bytes a cell; free with distrib2d_free.  -1 if a side is < 1, the cell count
 * is over DISTRIB_MAX_BINS, the sum of the weights overflows a double, or memory runs out; *d is
 * then left empty (safe to free). */
int distrib2d_init(distrib2d *d, const double *w, int n_outer, int n_inner, error *err);
int distrib2d_init_float(distrib2d *d, const float *w, int n_outer, int n_inner, error *err);

/* The most bytes distrib2d_init holds for an n_outer x n_inner grid (about 8 a cell), and the
 * most distrib2d_alias_build adds to them (about 8 a cell), for a memory budget charged before
 * the tables are built (budget.h). */
double distrib2d_bytes(int n_outer, int n_inner);
double distrib2d_alias_bytes(int n_outer, int n_inner);

/* Add alias tables for the marginal and every conditional (8 bytes a cell) so
 * distrib2d_sample_alias works.  -1 only if memory runs out.  Calling it twice is harmless. */
int distrib2d_alias_build(distrib2d *d, error *err);

/* Free everything *d owns and zero it.  Safe on a zeroed or already freed table. */
void distrib2d_free(distrib2d *d);

/* p(outer, inner) = p(outer) p(inner | outer); indices must be in range (assert). */
double distrib2d_pmf(const distrib2d *d, int outer, int inner);
/* p(outer) = sum_inner p(outer, inner), the marginal. */
double distrib2d_pmf_outer(const distrib2d *d, int outer);
/* p(inner | outer), the conditional (uniform for a column of weight 0). */
double distrib2d_pmf_inner(const distrib2d *d, int outer, int inner);

/* Inversion, binary search twice: outer from the marginal CDF with xi_outer, then inner from
 * the conditional CDF of that column with xi_inner.  *outer, *inner: the cell (never one of
 * pmf 0); *pmf = distrib2d_pmf(d, *outer, *inner); *rem_outer, *rem_inner in [0, 1) as in
 * distrib1d_sample (monotone).  outer and inner must not be NULL; pmf, rem_* may be NULL. */
void distrib2d_sample(const distrib2d *d, double xi_outer, double xi_inner, int *outer,
                      int *inner, double *pmf, double *rem_outer, double *rem_inner);

/* The same distribution with the alias method at both levels, O(1); distrib2d_alias_build must
 * have been called (assert).  Same outputs as distrib2d_sample, not monotone in xi. */
void distrib2d_sample_alias(const distrib2d *d, double xi_outer, double xi_inner, int *outer,
                            int *inner, double *pmf, double *rem_outer, double *rem_inner);

#endif
