/* distrib.c - sampling discrete 1D and 2D distributions with numerical CDFs
 * (see include/envtex/envlight/distrib.h; lecture slides 16-23 (Environment Maps Generally)). */
#include "envtex/envlight/distrib.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/core/stepcheck.h"

/* The largest double below 1 (1 - 2^-53): xi and remapped values are clamped to it so that
 * "in [0, 1)" holds even after rounding (xi * n, (xi - c) / p can round up to exactly 1). */
#define DISTRIB_ONE_MINUS_ULP 0x1.fffffffffffffp-1

/* xi clamped to [0, 1): NaN and negatives to 0, 1 and above to the largest double below 1. */
static double clamp_xi(double xi)
{
    if (!(xi >= 0.0)) return 0.0; /* also catches NaN */
    return xi > DISTRIB_ONE_MINUS_ULP ? DISTRIB_ONE_MINUS_ULP : xi;
}

/* Weight k from whichever array is given; NaN, +-Inf and negatives count as bad and read as 0.
 * (-0.0 is not negative: it is a plain zero.) */
static double weight_at(const double *wd, const float *wf, size_t k, int *n_bad)
{
    double w = wd ? wd[k] : (double)wf[k];
    if (isfinite(w) && w >= 0.0) return w;
    (*n_bad)++;
    return 0.0;
}

/* Fill cdf[0 .. n] from weights k = off .. off + n - 1 and put their sum in *sum.
 *   S_j = sum_{k<j} w_k (in double),  cdf[j] = S_j / S_n,  cdf[0] = 0, cdf[n] = 1 exactly.
 * Division by the positive constant S_n keeps the order, so equal partial sums (zero weights)
 * give zero-width steps and the CDF never decreases.  A sum of 0 gives the uniform CDF j / n
 * (with *sum = 0); a sum that overflows is returned as +Inf for the caller to reject. */
static void cdf_from_weights(double *cdf, const double *wd, const float *wf, size_t off, int n,
                             int *n_bad, double *sum)
{
    /* STEP(cdf): the numerical CDF of the n weights, slide 23 (How to Sample 2D Distribution):
     * "form (numerical) 1D CDFs" (the contract: distrib.h) */
    /* STUB: (void)weight_at; (void)wd; (void)wf; (void)off; (void)n_bad;
     * for (int j = 0; j <= n; j++) cdf[j] = (double)j / (double)n;
     * *sum = 1.0; */
    double s = 0.0;
    cdf[0] = 0.0;
    for (int j = 0; j < n; j++) {
        s += weight_at(wd, wf, off + (size_t)j, n_bad); /* S_{j+1} = S_j + w_j */
        cdf[j + 1] = s;
    }
    *sum = s;
    if (!isfinite(s)) return;
    if (s == 0.0) { /* no mass at all: uniform, cdf[j] = j / n */
        for (int j = 0; j <= n; j++) cdf[j] = (double)j / (double)n;
    } else {
        for (int j = 1; j < n; j++) cdf[j] /= s; /* cdf[j] = S_j / S_n */
    }
    cdf[n] = 1.0;
    /* END STEP(cdf) */
}

/* The bin i whose step contains x: the first i with cdf[i + 1] > x (upper bound over
 * cdf[1 .. n]).  x must be in [0, 1), and cdf[n] = 1 > x, so such an i exists; cdf[i] <= x
 * because i is the first, so cdf[i + 1] - cdf[i] > 0: zero-width bins are never returned. */
static int cdf_search(const double *cdf, int n, double x)
{
    /* STEP(cdf): invert the numerical CDF: the bin whose interval of the CDF holds x, slide 23 (How
     * to Sample 2D Distribution): "use numerical 1D CDF inversion" (distrib.h) */
    /* STUB: (void)cdf; (void)n; (void)x; return 0; */
    int lo = 0, count = n;
    while (count > 0) {
        int half = count / 2;
        if (cdf[lo + half + 1] <= x) {
            lo += half + 1;
            count -= half + 1;
        } else {
            count = half;
        }
    }
    return lo;
    /* END STEP(cdf) */
}

/* remapped = (x - cdf[i]) / p_i: x rescaled to [0, 1) within bin i (p_i > 0). */
static double cdf_remap(const double *cdf, int i, double x, double p)
{
    double r = (x - cdf[i]) / p;
    return r > DISTRIB_ONE_MINUS_ULP ? DISTRIB_ONE_MINUS_ULP : r;
}

/* Vose's alias table for the n bins of `cdf`, with scratch q (n doubles), small and large
 * (n ints each).  Every bin i gets q_i = n p_i (mean 1); a bin with q < 1 is filled up to 1
 * with mass from a bin with q >= 1, which becomes its alias.  Aliases are always bins that had
 * q >= 1, so of positive probability; a zero bin gets prob 0 and always goes to its alias. */
static void alias_build_table(const double *cdf, int n, distrib_alias *t, double *q, int *small,
                              int *large)
{
    int ns = 0, nl = 0, best = 0;
    for (int i = 0; i < n; i++) {
        q[i] = (cdf[i + 1] - cdf[i]) * (double)n; /* q_i = n p_i */
        if (q[i] > q[best]) best = i;
        if (q[i] < 1.0)
            small[ns++] = i;
        else
            large[nl++] = i;
    }
    /* STEP(alias): Vose's alias table (Vose 1991; no slide: an O(1) alternative to the inversion of
     * slide 23 (How to Sample 2D Distribution)): each small bin filled up to 1 by a large bin,
     * which becomes its alias (distrib.h) */
    /* STUB: (void)small; (void)large; (void)ns; (void)nl;
     * for (int i = 0; i < n; i++) {
     *     t[i].prob = q[i] > 0 ? 1.0f : 0.0f;
     *     t[i].alias = q[i] > 0 ? i : best;
     * } */
    while (ns > 0 && nl > 0) {
        int s = small[--ns], l = large[nl - 1];
        float prob = (float)q[s];
        t[s].prob = prob;
        t[s].alias = l;
        /* l gives what the stored threshold hands it, 1 - prob (exact in double), not 1 - q_s:
         * so each float rounding stays in its own cell instead of adding up on l over many
         * donors (docs/design-notes.md); q_l >= 1 so it stays >= prob >= 0 */
        q[l] -= 1.0 - (double)prob;
        if (q[l] < 1.0) {
            nl--;
            small[ns++] = l;
        }
    }
    /* Leftovers have q = 1 up to rounding: they keep themselves.  A leftover of probability 0
     * would need the other leftovers to hold its share, impossible beyond rounding; guard it
     * anyway so that a zero bin can never be returned. */
    while (nl > 0) {
        int l = large[--nl];
        t[l].prob = 1.0f;
        t[l].alias = l;
    }
    while (ns > 0) {
        int s = small[--ns];
        int zero = !(cdf[s + 1] > cdf[s]);
        t[s].prob = zero ? 0.0f : 1.0f;
        t[s].alias = zero ? best : s;
    }
    /* END STEP(alias) */
}

/* O(1) alias sampling: u = x n picks the cell i = floor(u), and f = u - i, uniform in [0, 1),
 * picks i itself (f < prob_i) or its alias; f is then rescaled to [0, 1) within that part. */
static inline int alias_pick(const distrib_alias *t, int n, double xi, double *remapped)
{
    double u = clamp_xi(xi) * (double)n;
    int i = (int)u;
    if (i > n - 1) i = n - 1; /* u rounds up to n when xi is within an ulp of 1 */
    double f = u - (double)i;
    f = f < DISTRIB_ONE_MINUS_ULP ? f : DISTRIB_ONE_MINUS_ULP;
    double prob = (double)t[i].prob;
    int bin;
    double r;
    if (f < prob) { /* here prob > 0 */
        bin = i;
        r = f / prob;
    } else { /* here prob <= f < 1, so 1 - prob > 0 */
        bin = t[i].alias;
        r = (f - prob) / (1.0 - prob);
    }
    STEPCHECK_INDEX(bin, n, "alias", "bin");
    if (remapped) *remapped = r < DISTRIB_ONE_MINUS_ULP ? r : DISTRIB_ONE_MINUS_ULP;
    return bin;
}

/* ---- 1D ------------------------------------------------------------------------------------ */

static int distrib1d_build(distrib1d *d, const double *wd, const float *wf, int n, error *err)
{
    memset(d, 0, sizeof *d);
    if (n < 1 || n > DISTRIB_MAX_BINS)
        return error_set(err, NULL, 0, "distrib1d: %d bins is out of range [1, %ld]", n,
                         DISTRIB_MAX_BINS);
    double *cdf = malloc(((size_t)n + 1) * sizeof *cdf);
    if (!cdf) return error_set(err, NULL, 0, "distrib1d: out of memory for %d bins", n);
    int n_bad = 0;
    double sum;
    cdf_from_weights(cdf, wd, wf, 0, n, &n_bad, &sum);
    if (!isfinite(sum)) {
        free(cdf);
        return error_set(err, NULL, 0, "distrib1d: the sum of the %d weights overflows a double",
                         n);
    }
    d->n = n;
    d->cdf = cdf;
    d->n_bad = n_bad;
    d->fell_back_to_uniform = sum == 0.0;
    d->total = sum == 0.0 ? (double)n : sum;
    d->first_nonzero = 0;
    while (!(cdf[d->first_nonzero + 1] > cdf[d->first_nonzero])) d->first_nonzero++;
    d->last_nonzero = n - 1;
    while (!(cdf[d->last_nonzero + 1] > cdf[d->last_nonzero])) d->last_nonzero--;
    return 0;
}

int distrib1d_init(distrib1d *d, const double *w, int n, error *err)
{
    assert(d && (w || n < 1));
    return distrib1d_build(d, w, NULL, n, err);
}

int distrib1d_init_float(distrib1d *d, const float *w, int n, error *err)
{
    assert(d && (w || n < 1));
    return distrib1d_build(d, NULL, w, n, err);
}

int distrib1d_alias_build(distrib1d *d, error *err)
{
    assert(d && d->cdf);
    if (d->alias) return 0;
    int n = d->n;
    distrib_alias *t = malloc((size_t)n * sizeof *t);
    double *q = malloc((size_t)n * sizeof *q);
    int *small = malloc((size_t)n * sizeof *small);
    int *large = malloc((size_t)n * sizeof *large);
    int rc = 0;
    if (!t || !q || !small || !large) {
        rc = error_set(err, NULL, 0, "distrib1d: out of memory for an alias table of %d bins", n);
        free(t);
        goto done;
    }
    alias_build_table(d->cdf, n, t, q, small, large);
    d->alias = t;
done:
    free(q);
    free(small);
    free(large);
    return rc;
}

void distrib1d_free(distrib1d *d)
{
    if (!d) return;
    free(d->cdf);
    free(d->alias);
    memset(d, 0, sizeof *d);
}

double distrib1d_pmf(const distrib1d *d, int i)
{
    assert(i >= 0 && i < d->n);
    return d->cdf[i + 1] - d->cdf[i]; /* p_i = cdf[i+1] - cdf[i] */
}

int distrib1d_sample(const distrib1d *d, double xi, double *pmf, double *remapped)
{
    double x = clamp_xi(xi);
    int i = cdf_search(d->cdf, d->n, x);
    STEPCHECK_INDEX(i, d->n, "cdf", "bin");
    double p = d->cdf[i + 1] - d->cdf[i];
    if (pmf) *pmf = p;
    if (remapped) *remapped = cdf_remap(d->cdf, i, x, p);
    return i;
}

int distrib1d_sample_alias(const distrib1d *d, double xi, double *pmf, double *remapped)
{
    assert(d->alias && "call distrib1d_alias_build first");
    int i = alias_pick(d->alias, d->n, xi, remapped);
    if (pmf) *pmf = d->cdf[i + 1] - d->cdf[i];
    return i;
}

/* ---- 2D ------------------------------------------------------------------------------------ */

static const double *column_cdf(const distrib2d *d, int outer)
{
    return d->cond_cdf + (size_t)outer * ((size_t)d->n_inner + 1);
}

static int distrib2d_build(distrib2d *d, const double *wd, const float *wf, int n_outer,
                           int n_inner, error *err)
{
    memset(d, 0, sizeof *d);
    if (n_outer < 1 || n_inner < 1 || (long long)n_outer * n_inner > DISTRIB_MAX_BINS)
        return error_set(err, NULL, 0,
                         "distrib2d: a %d x %d grid is empty or over the limit of %ld cells",
                         n_outer, n_inner, DISTRIB_MAX_BINS);
    size_t row = (size_t)n_inner + 1;
    double *cond = malloc((size_t)n_outer * row * sizeof *cond);
    double *colsum = malloc((size_t)n_outer * sizeof *colsum);
    int rc = 0, n_bad = 0;
    if (!cond || !colsum) {
        rc = error_set(err, NULL, 0, "distrib2d: out of memory for a %d x %d grid", n_outer,
                       n_inner);
        goto fail;
    }
    /* p(inner | outer) = w(outer, inner) / sum_inner w(outer, inner) : one CDF per column */
    for (int o = 0; o < n_outer; o++) {
        cdf_from_weights(cond + (size_t)o * row, wd, wf, (size_t)o * (size_t)n_inner, n_inner,
                         &n_bad, &colsum[o]);
        if (!isfinite(colsum[o])) {
            rc = error_set(err, NULL, 0,
                           "distrib2d: the sum of the weights of column %d overflows a double", o);
            goto fail;
        }
    }
    /* p(outer) = sum_inner w(outer, inner) / total : the marginal over the outer variable.
     * All columns 0 -> the marginal is uniform and so is every column: the uniform fallback. */
    if (distrib1d_init(&d->marginal, colsum, n_outer, err)) {
        rc = error_prefix(err, "distrib2d marginal");
        goto fail;
    }
    free(colsum);
    d->n_outer = n_outer;
    d->n_inner = n_inner;
    d->cond_cdf = cond;
    d->n_bad = n_bad;
    d->fell_back_to_uniform = d->marginal.fell_back_to_uniform;
    d->total = d->fell_back_to_uniform ? (double)n_outer * n_inner : d->marginal.total;
    return 0;
fail:
    free(cond);
    free(colsum);
    distrib1d_free(&d->marginal);
    memset(d, 0, sizeof *d);
    return rc;
}

double distrib2d_bytes(int n_outer, int n_inner)
{
    double conditional = (double)n_outer * (n_inner + 1) * sizeof(double);
    /* the marginal's cdf, and the column sums it is built from */
    double marginal = (double)(n_outer + 1) * sizeof(double) + (double)n_outer * sizeof(double);
    return conditional + marginal;
}

double distrib2d_alias_bytes(int n_outer, int n_inner)
{
    double cells = (double)n_outer * n_inner;
    /* the cells of every column and of the marginal, and one column's scratch (q, small, large) */
    return (cells + n_outer) * sizeof(distrib_alias) +
           (double)(n_inner > n_outer ? n_inner : n_outer) * (sizeof(double) + 2 * sizeof(int));
}

int distrib2d_init(distrib2d *d, const double *w, int n_outer, int n_inner, error *err)
{
    assert(d && (w || n_outer < 1 || n_inner < 1));
    return distrib2d_build(d, w, NULL, n_outer, n_inner, err);
}

int distrib2d_init_float(distrib2d *d, const float *w, int n_outer, int n_inner, error *err)
{
    assert(d && (w || n_outer < 1 || n_inner < 1));
    return distrib2d_build(d, NULL, w, n_outer, n_inner, err);
}

int distrib2d_alias_build(distrib2d *d, error *err)
{
    assert(d && d->cond_cdf);
    if (d->cond_alias) return 0;
    if (distrib1d_alias_build(&d->marginal, err)) return error_prefix(err, "distrib2d marginal");
    int n = d->n_inner;
    distrib_alias *t = malloc((size_t)d->n_outer * (size_t)n * sizeof *t);
    double *q = malloc((size_t)n * sizeof *q);
    int *small = malloc((size_t)n * sizeof *small);
    int *large = malloc((size_t)n * sizeof *large);
    int rc = 0;
    if (!t || !q || !small || !large) {
        rc = error_set(err, NULL, 0, "distrib2d: out of memory for alias tables of %d x %d",
                       d->n_outer, n);
        free(t);
        goto done;
    }
    for (int o = 0; o < d->n_outer; o++)
        alias_build_table(column_cdf(d, o), n, t + (size_t)o * (size_t)n, q, small, large);
    d->cond_alias = t;
done:
    free(q);
    free(small);
    free(large);
    return rc;
}

void distrib2d_free(distrib2d *d)
{
    if (!d) return;
    distrib1d_free(&d->marginal);
    free(d->cond_cdf);
    free(d->cond_alias);
    memset(d, 0, sizeof *d);
}

double distrib2d_pmf_outer(const distrib2d *d, int outer)
{
    return distrib1d_pmf(&d->marginal, outer);
}

double distrib2d_pmf_inner(const distrib2d *d, int outer, int inner)
{
    assert(outer >= 0 && outer < d->n_outer && inner >= 0 && inner < d->n_inner);
    const double *cdf = column_cdf(d, outer);
    return cdf[inner + 1] - cdf[inner];
}

double distrib2d_pmf(const distrib2d *d, int outer, int inner)
{
    /* p(outer, inner) = p(outer) p(inner | outer) */
    return distrib2d_pmf_outer(d, outer) * distrib2d_pmf_inner(d, outer, inner);
}

void distrib2d_sample(const distrib2d *d, double xi_outer, double xi_inner, int *outer, int *inner,
                      double *pmf, double *rem_outer, double *rem_inner)
{
    assert(outer && inner);
    double p_outer;
    int o = distrib1d_sample(&d->marginal, xi_outer, &p_outer, rem_outer); /* p(outer) */
    const double *cdf = column_cdf(d, o);
    double x = clamp_xi(xi_inner);
    int i = cdf_search(cdf, d->n_inner, x); /* p(inner | outer): the column's conditional CDF */
    STEPCHECK_INDEX(i, d->n_inner, "cdf", "bin");
    double p_inner = cdf[i + 1] - cdf[i];
    if (pmf) *pmf = p_outer * p_inner; /* p(outer, inner) = p(outer) p(inner | outer) */
    if (rem_inner) *rem_inner = cdf_remap(cdf, i, x, p_inner);
    *outer = o;
    *inner = i;
}

void distrib2d_sample_alias(const distrib2d *d, double xi_outer, double xi_inner, int *outer,
                            int *inner, double *pmf, double *rem_outer, double *rem_inner)
{
    assert(outer && inner);
    assert(d->cond_alias && "call distrib2d_alias_build first");
    int o = alias_pick(d->marginal.alias, d->n_outer, xi_outer, rem_outer);
    int i =
        alias_pick(d->cond_alias + (size_t)o * (size_t)d->n_inner, d->n_inner, xi_inner, rem_inner);
    if (pmf) *pmf = distrib2d_pmf(d, o, i); /* p(outer) p(inner | outer) */
    *outer = o;
    *inner = i;
}
