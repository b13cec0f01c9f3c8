/* distrib.h - sampling 1D and 2D distributions by numerical CDFs (slides 22-23 (Sampling General 2D
 * Distributions): the OUTER variable from its marginal CDF, then the INNER from the column's
 * conditional).  Pure maths.
 *
 *     if (distrib2d_init(&d, w, 4, 2, &err)) return -1;      // w[outer * 2 + inner] >= 0
 *     distrib2d_sample(&d, xi1, xi2, &o, &i, &pmf, &ro, &ri); // cell (o, i), probability pmf
 *     double u = (o + ro) / 4.0;                              // a point inside the cell
 *
 * Conventions: xi in [0, 1), clamped (NaN -> 0, >= 1 -> the last bin of pmf > 0); pmf: a
 * probability, not a density; remapped: xi rescaled to [0, 1) in its bin.  No bin of pmf 0 is
 * returned.  *_sample: binary search, monotone in xi; *_sample_alias: Walker's, O(1), not.  Bad
 * weights (NaN, Inf, < 0) act as 0 (n_bad); all 0: uniform.  Double CDFs: pmf p within
 * ~1e-16 / p of w / total (docs/design-notes.md).  Sampling allocates nothing.
 */
#ifndef ENVTEX_DISTRIB_H
#define ENVTEX_DISTRIB_H

#include <stdint.h>

#include "envtex/core/error.h"

/* The most bins of one table (n, or n_outer n_inner): indices and counts fit in an int. */
#define DISTRIB_MAX_BINS (1L << 28)

/* An alias cell: u uniform in [0,1) in cell i picks i if u < prob, else alias (pmf > 0). */
typedef struct distrib_alias {
    float prob;
    int32_t alias;
} distrib_alias;

/* A discrete distribution over bins 0 .. n-1. */
typedef struct distrib1d {
    int n;                    /* bins, >= 1 */
    double *cdf;              /* n + 1: cdf[0] = 0, cdf[n] = 1 exactly, non-decreasing */
    double total;             /* sum of the weights used (n if all were 0) */
    int n_bad;                /* weights NaN, +-Inf or negative (used as 0) */
    int fell_back_to_uniform; /* every weight was 0: uniform */
    int first_nonzero;        /* first and last bin of positive pmf */
    int last_nonzero;
    distrib_alias *alias; /* n cells after distrib1d_alias_build, else NULL */
} distrib1d;

/* Build *d from n weights (double or float); free with distrib1d_free.  -1 if n is outside
 * [1, DISTRIB_MAX_BINS], the sum overflows or memory runs out: *d is then empty (safe to free). */
int distrib1d_init(distrib1d *d, const double *w, int n, error *err);
int distrib1d_init_float(distrib1d *d, const float *w, int n, error *err);

/* Add the alias table (8n bytes) for distrib1d_sample_alias.  -1 only if memory runs out (the
 * CDF stays usable).  A second call does nothing. */
int distrib1d_alias_build(distrib1d *d, error *err);

/* Free what *d owns and zero it; safe on a zeroed or freed table. */
void distrib1d_free(distrib1d *d);

/* p_i = cdf[i + 1] - cdf[i]; i in [0, n) (assert). */
double distrib1d_pmf(const distrib1d *d, int i);

/* The bin i with cdf[i] <= xi < cdf[i + 1], by binary search; *pmf = p_i, *remapped =
 * (xi - cdf[i]) / p_i (either may be NULL). */
int distrib1d_sample(const distrib1d *d, double xi, double *pmf, double *remapped);

/* The same by the alias method (after distrib1d_alias_build, assert); *pmf = distrib1d_pmf. */
int distrib1d_sample_alias(const distrib1d *d, double xi, double *pmf, double *remapped);

/* An n_outer x n_inner grid, w[outer * n_inner + inner]: p(outer) = sum_inner w / total, the
 * marginal, and p(inner | outer) = w / sum_inner w, the conditional. */
typedef struct distrib2d {
    int n_outer, n_inner;
    distrib1d marginal; /* p(outer): n_outer bins */
    double *cond_cdf;   /* column o's CDF at cond_cdf + o (n_inner + 1) */
    double total;       /* as in distrib1d */
    int n_bad;
    int fell_back_to_uniform;
    distrib_alias *cond_alias; /* n_outer n_inner cells after distrib2d_alias_build, else NULL */
} distrib2d;

/* As distrib1d_init for n_outer n_inner weights (free with distrib2d_free); -1 also if a side
 * is < 1. */
int distrib2d_init(distrib2d *d, const double *w, int n_outer, int n_inner, error *err);
int distrib2d_init_float(distrib2d *d, const float *w, int n_outer, int n_inner, error *err);

/* The bytes distrib2d_init holds, and distrib2d_alias_build adds (~8 a cell each). */
double distrib2d_bytes(int n_outer, int n_inner);
double distrib2d_alias_bytes(int n_outer, int n_inner);

/* As distrib1d_alias_build, for distrib2d_sample_alias. */
int distrib2d_alias_build(distrib2d *d, error *err);

/* As distrib1d_free. */
void distrib2d_free(distrib2d *d);

/* p(outer, inner) = p(outer) p(inner | outer); then the marginal p(outer) and the conditional
 * p(inner | outer) (uniform in a column of weight 0).  Indices in range (assert). */
double distrib2d_pmf(const distrib2d *d, int outer, int inner);
double distrib2d_pmf_outer(const distrib2d *d, int outer);
double distrib2d_pmf_inner(const distrib2d *d, int outer, int inner);

/* Outer from the marginal CDF with xi_outer, then inner from that column's CDF with xi_inner
 * (binary search twice).  *pmf = distrib2d_pmf; rem_* the remapped xi; pmf, rem_* may be NULL,
 * outer and inner not. */
void distrib2d_sample(const distrib2d *d, double xi_outer, double xi_inner, int *outer, int *inner,
                      double *pmf, double *rem_outer, double *rem_inner);

/* The same by the alias method at both levels (after distrib2d_alias_build, assert). */
void distrib2d_sample_alias(const distrib2d *d, double xi_outer, double xi_inner, int *outer,
                            int *inner, double *pmf, double *rem_outer, double *rem_inner);

#endif
