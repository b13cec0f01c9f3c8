/* chisq.h - Pearson's chi-square goodness-of-fit test for sampler unit tests (header only).
 *
 * Draw N samples, count how many land in each of n bins, and ask whether the counts fit the
 * probabilities the sampler claims:
 *
 *     long obs[16] = {0};
 *     for (long s = 0; s < N; s++) obs[draw()]++;
 *     chisq_result r = chisq_test(obs, prob, 16, N);      // or chisq_test_uniform(obs, 16, N)
 *     ck_assert_msg(chisq_accept(&r, N_CHISQ_TESTS), "X^2 = %g, dof %d, p = %g", r.stat, r.dof, r.p);
 *
 * The statistic is X^2 = sum_k (O_k - E_k)^2 / E_k with E_k = N p_k.  The chi-square law is
 * only a good model for X^2 when every E_k is at least CHISQ_MIN_EXPECTED, so bins below it are
 * pooled into one bin (and if that pooled bin is still below, it is merged into the smallest
 * ordinary bin).  A sample in a bin whose probability is exactly 0 is always a failure, whatever
 * the statistic says: a sampler must never return what it calls impossible.  The p-value is
 * P(chi^2_dof >= X^2) = Q(dof / 2, X^2 / 2), Q the regularized upper incomplete gamma function,
 * computed here from its power series or its continued fraction (the classic pair of expansions,
 * e.g. Numerical Recipes ch. 6.2).  A test passes when p >= CHISQ_ALPHA / n_tests: significance
 * 1% for the whole program, split over its n_tests chi-square tests (Bonferroni), so a correct
 * sampler fails a run with probability below 1% and fixed seeds make that run reproducible.
 */
#ifndef ENVTEX_CHISQ_H
#define ENVTEX_CHISQ_H

#include <float.h>
#include <math.h>

#define CHISQ_ALPHA        0.01 /* family-wise significance of one test program */
#define CHISQ_MIN_EXPECTED 5.0  /* the usual rule of thumb for the chi-square approximation */
#define CHISQ_EPS                                                                                  \
    1e-15 /* relative size of the last series term / fraction update:
                                 * a few ulps of double, the precision Q can have */
#define CHISQ_TINY                                                                                 \
    1e-300                    /* stands in for 0 in Lentz's method (avoids 1/0), far below
                                 * any value the fraction's terms take */
#define CHISQ_MAX_ITER 100000 /* both expansions need O(sqrt(a)) terms: ample for dof < 10^8 */

typedef struct chisq_result {
    double stat; /* X^2 after pooling */
    int dof;     /* degrees of freedom: bins after pooling - 1 (0 if everything is in one bin) */
    double p;    /* P(chi^2_dof >= stat); 1 when dof = 0; 0 when stray > 0 */
    long stray;  /* samples that landed in bins of probability exactly 0 */
} chisq_result;

/* Q(a, x) = Gamma(a, x) / Gamma(a) = 1 - P(a, x), a > 0, x >= 0 (NaN otherwise). */
static inline double chisq_gamma_q(double a, double x)
{
    if (!(a > 0.0) || !(x >= 0.0)) return NAN;
    if (x == 0.0) return 1.0;
    double log_front = -x + a * log(x) - lgamma(a); /* log(e^-x x^a / Gamma(a)) */
    if (x < a + 1.0) {
        /* P(a,x) = e^-x x^a / Gamma(a) * sum_{k>=0} x^k / (a (a+1) ... (a+k)) */
        double term = 1.0 / a, sum = term;
        for (int k = 1; k < CHISQ_MAX_ITER; k++) {
            term *= x / (a + k);
            sum += term;
            if (fabs(term) < fabs(sum) * CHISQ_EPS) break;
        }
        double q = 1.0 - sum * exp(log_front);
        return q < 0.0 ? 0.0 : q;
    }
    /* Q(a,x) = e^-x x^a / Gamma(a) * 1 / (x+1-a - 1(1-a) / (x+3-a - 2(2-a) / (x+5-a - ...))),
     * evaluated front to back with the modified Lentz method: h = b0, then h *= c_i / d_i */
    double b = x + 1.0 - a, c = 1.0 / CHISQ_TINY, d = 1.0 / b, h = d;
    for (int i = 1; i < CHISQ_MAX_ITER; i++) {
        double an = -i * (i - a); /* a_i = -i (i - a) */
        b += 2.0;                 /* b_i = x + 2i + 1 - a */
        d = an * d + b;
        if (fabs(d) < CHISQ_TINY) d = CHISQ_TINY;
        c = b + an / c;
        if (fabs(c) < CHISQ_TINY) c = CHISQ_TINY;
        d = 1.0 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1.0) < CHISQ_EPS) break;
    }
    return exp(log_front) * h;
}

/* P(chi^2_dof >= stat) = Q(dof / 2, stat / 2); 1 for dof < 1 (nothing left to test). */
static inline double chisq_p_value(double stat, int dof)
{
    if (dof < 1) return 1.0;
    return chisq_gamma_q(0.5 * dof, 0.5 * (stat > 0.0 ? stat : 0.0));
}

/* prob[k], or 1 / n when prob is NULL (equal-probability bins) */
static inline double chisq_prob_at(const double *prob, int k, int n)
{
    return prob ? prob[k] : 1.0 / n;
}

/* Test counts observed[0 .. n-1] of n_samples samples against probabilities prob[0 .. n-1]
 * (which should sum to 1; expected count E_k = n_samples prob_k).  prob = NULL means n bins of
 * equal probability 1 / n. */
static inline chisq_result chisq_test(const long *observed, const double *prob, int n,
                                      long n_samples)
{
    chisq_result r = {0.0, 0, 1.0, 0};
    double pooled_e = 0.0, pooled_o = 0.0;
    int n_regular = 0, smallest = -1;
    for (int k = 0; k < n; k++) {
        double pk = chisq_prob_at(prob, k, n), e = pk * (double)n_samples;
        if (pk <= 0.0) {
            r.stray += observed[k];
        } else if (e < CHISQ_MIN_EXPECTED) {
            pooled_e += e;
            pooled_o += (double)observed[k];
        } else {
            n_regular++;
            if (smallest < 0 || pk < chisq_prob_at(prob, smallest, n)) smallest = k;
        }
    }
    /* a pooled bin still too small is merged into the smallest ordinary bin */
    int merge = pooled_e > 0.0 && pooled_e < CHISQ_MIN_EXPECTED && smallest >= 0;
    int n_bins = n_regular + (pooled_e > 0.0 && !merge);
    double stat = 0.0;
    for (int k = 0; k < n; k++) {
        double pk = chisq_prob_at(prob, k, n), e = pk * (double)n_samples;
        if (pk <= 0.0 || e < CHISQ_MIN_EXPECTED) continue;
        double o = (double)observed[k];
        if (merge && k == smallest) {
            e += pooled_e;
            o += pooled_o;
        }
        stat += (o - e) * (o - e) / e; /* (O - E)^2 / E */
    }
    if (pooled_e > 0.0 && !merge) stat += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
    r.stat = stat;
    r.dof = n_bins - 1;
    r.p = r.stray > 0 ? 0.0 : chisq_p_value(stat, r.dof);
    return r;
}

/* The same against n bins of equal probability 1 / n. */
static inline chisq_result chisq_test_uniform(const long *observed, int n, long n_samples)
{
    return chisq_test(observed, NULL, n, n_samples);
}

/* 1 if the test passes: no stray sample and p >= CHISQ_ALPHA / n_tests (Bonferroni). */
static inline int chisq_accept(const chisq_result *r, int n_tests)
{
    return r->stray == 0 && r->p >= CHISQ_ALPHA / (n_tests > 0 ? n_tests : 1);
}

#endif
