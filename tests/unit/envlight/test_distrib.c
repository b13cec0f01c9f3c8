/* test_distrib.c - sampling discrete 1D and 2D distributions (include/envtex/envlight/distrib.h).
 *
 * Samplers are checked the way the lecture's estimator needs them: chi-square tests of the
 * samples against the pmf (and of the alias method against the binary search's pmf), the pmf a
 * sampler reports against pmf(), exact behaviour at the edges of [0, 1), and that a bin of
 * probability 0 is never returned.  Every random number comes from a fixed-seed PCG32.
 */
#include "envtex/envlight/distrib.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "chisq.h"
#include "unit.h"

#define N_SAMPLES 200000L /* per chi-square test: a 5% error in a 10% bin is 7 sigma */
#define PMF_REL_TOL    1e-12 /* pmf agreement: the maths is exact up to a few roundings of double */
#define REM_BUCKETS_1D 4     /* each bin's remapped value is tested in 4 sub-bins ... */
#define REM_BUCKETS_2D 2     /* ... and each cell's (rem_outer, rem_inner) in 2 x 2 */
#define REM_BUCKETS    64    /* for the dedicated uniformity test of remapped values */

/* ---- a fixed-seed PCG32 (O'Neill's pcg32_random_r, XSH RR) ----------------------------------- */
typedef struct pcg32 {
    uint64_t state, inc;
} pcg32;

static uint32_t pcg32_next(pcg32 *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((0u - rot) & 31u));
}

static pcg32 pcg32_seeded(uint64_t seed)
{
    pcg32 r = {0u, (seed << 1u) | 1u};
    pcg32_next(&r);
    r.state += 0x853c49e6748fea9bULL;
    pcg32_next(&r);
    return r;
}

/* uniform in [0, 1) with 53 random bits */
static double pcg32_double(pcg32 *r)
{
    uint64_t hi = pcg32_next(r) >> 5, lo = pcg32_next(r) >> 6; /* 27 + 26 bits */
    return (double)(hi * 67108864u + lo) * 0x1p-53;
}

/* ---- the tables the lecture's cases reduce to --------------------------------------------- */
enum { T1_ONE_HOT, T1_CONSTANT, T1_SINGLE, T1_DYNAMIC, T1_POLES, T1_RANDOM, T1_COUNT };
static const char *const t1_name[T1_COUNT] = {
    "one-hot", "constant", "1 bin", "10^6 range", "first and last bins", "random with zeros"};
#define T1_MAX 128

/* Fill w with 1D table `which`; returns its size n. */
static int table1d(int which, double *w)
{
    int n = 0;
    switch (which) {
    case T1_ONE_HOT:
        n = 7;
        for (int i = 0; i < n; i++) w[i] = i == 3 ? 2.0 : 0.0;
        break;
    case T1_CONSTANT:
        n = 16;
        for (int i = 0; i < n; i++) w[i] = 2.5;
        break;
    case T1_SINGLE:
        n = 1;
        w[0] = 0.3;
        break;
    case T1_DYNAMIC: /* one bin 10^6 times the others */
        n = 64;
        for (int i = 0; i < n; i++) w[i] = 1.0 + (i % 5) * 0.25;
        w[10] = 1e6;
        break;
    case T1_POLES: /* all the mass at the two ends */
        n = 32;
        for (int i = 0; i < n; i++) w[i] = 0.0;
        w[0] = 3.0;
        w[n - 1] = 1.0;
        break;
    case T1_RANDOM: {
        pcg32 rng = pcg32_seeded(11);
        n = 100;
        for (int i = 0; i < n; i++) {
            double u = pcg32_double(&rng);
            w[i] = u < 0.2 ? 0.0 : u;
        }
        break;
    }
    }
    ck_assert(n >= 1 && n <= T1_MAX);
    return n;
}

enum { T2_ONE_HOT, T2_CONSTANT, T2_SINGLE, T2_3X2, T2_DYNAMIC, T2_POLES, T2_RANDOM, T2_COUNT };
static const char *const t2_name[T2_COUNT] = {
    "one-hot", "constant", "1 x 1", "3 x 2", "10^6 range", "pole rows", "random with zeros"};
#define T2_MAX 256

/* Fill w[outer * n_inner + inner] with 2D table `which`. */
static void table2d(int which, double *w, int *n_outer, int *n_inner)
{
    int no = 0, ni = 0;
    switch (which) {
    case T2_ONE_HOT:
        no = 5, ni = 4;
        for (int k = 0; k < no * ni; k++) w[k] = k == 2 * ni + 1 ? 1.0 : 0.0;
        break;
    case T2_CONSTANT:
        no = 8, ni = 4;
        for (int k = 0; k < no * ni; k++) w[k] = 0.7;
        break;
    case T2_SINGLE:
        no = 1, ni = 1;
        w[0] = 5.0;
        break;
    case T2_3X2: {
        static const double v[6] = {1.0, 2.0, 3.0, 0.0, 5.0, 0.25};
        no = 3, ni = 2;
        memcpy(w, v, sizeof v);
        break;
    }
    case T2_DYNAMIC: /* one cell 10^6 times the others */
        no = 16, ni = 8;
        for (int k = 0; k < no * ni; k++) w[k] = 1.0 + (k % 7) * 0.1;
        w[5 * ni + 3] = 1e6;
        break;
    case T2_POLES: /* mass only in the first and last inner rows, as at the poles */
        no = 6, ni = 10;
        for (int o = 0; o < no; o++)
            for (int i = 0; i < ni; i++)
                w[o * ni + i] = i == 0 ? 1.0 + o : i == ni - 1 ? 6.0 - o : 0.0;
        break;
    case T2_RANDOM: {
        pcg32 rng = pcg32_seeded(12);
        no = 12, ni = 9;
        for (int k = 0; k < no * ni; k++) {
            double u = pcg32_double(&rng);
            w[k] = u < 0.2 ? 0.0 : u;
        }
        for (int i = 0; i < ni; i++) w[4 * ni + i] = 0.0; /* a whole zero column */
        break;
    }
    }
    ck_assert(no * ni >= 1 && no * ni <= T2_MAX);
    *n_outer = no;
    *n_inner = ni;
}

/* Every chisq_accept that a correct sampler must pass, for the Bonferroni correction. */
#define N_CHISQ_TESTS (2 * T1_COUNT + 2 * T2_COUNT + 6)

#define ck_assert_chisq(r, what, ...)                                                              \
    ck_assert_msg(chisq_accept(&(r), N_CHISQ_TESTS),                                               \
                  what ": chi-square rejects: X^2 = %g, dof = %d, p = %g, %ld samples in "         \
                       "bins of probability 0",                                                    \
                  __VA_ARGS__, (r).stat, (r).dof, (r).p, (r).stray)

static double sum_of(const double *w, int n)
{
    double s = 0.0;
    for (int k = 0; k < n; k++) s += w[k];
    return s;
}

/* |a - b| <= PMF_REL_TOL |b|: for the pmf a sampler reports against pmf() (the same
 * subtraction of two CDF entries, so in fact equal) */
static int pmf_agrees(double a, double b) { return fabs(a - b) <= PMF_REL_TOL * fabs(b); }

/* pmf() against w / sum w, computed independently.  A CDF entry near 1 is only known to about
 * an ulp of 1 (after n roundings of the running sum), so a bin of probability p is known to
 * about DBL_EPSILON / p relative: allow PMF_REL_TOL relative plus 4 n DBL_EPSILON absolute
 * (n = bins summed).  A pmf off by a whole bin or a wrong total is far outside that. */
static int pmf_matches_weight(double pmf, double want, int n)
{
    return fabs(pmf - want) <= PMF_REL_TOL * fabs(want) + 4.0 * n * DBL_EPSILON;
}

/* ---- the chi-square helper itself ----------------------------------------------------------- */

/* Catches a wrong series, a wrong continued fraction, or the wrong branch between them. */
START_TEST(test_chisq_gamma_q_matches_closed_forms_and_tables)
{
    const double xs[] = {0.01, 0.3, 1.0, 2.5, 5.9, 6.1, 12.0, 40.0};
    for (size_t k = 0; k < sizeof xs / sizeof xs[0]; k++) {
        double x = xs[k];
        ck_assert_near(chisq_gamma_q(1.0, x), exp(-x), 1e-13);       /* Q(1,x) = e^-x */
        ck_assert_near(chisq_gamma_q(0.5, x), erfc(sqrt(x)), 1e-13); /* Q(1/2,x) = erfc */
        double q5 = exp(-x) * (1 + x + x * x / 2 + x * x * x / 6 + x * x * x * x / 24);
        ck_assert_near(chisq_gamma_q(5.0, x), q5, 1e-13); /* Q(n,x) = e^-x sum_{k<n} x^k/k! */
    }
    ck_assert(chisq_gamma_q(3.0, 0.0) == 1.0);
    /* critical values from chi-square tables: P(chi^2_dof >= value) */
    ck_assert_near(chisq_p_value(6.635, 1), 0.01, 1e-5);
    ck_assert_near(chisq_p_value(18.307, 10), 0.05, 1e-5);
    ck_assert_near(chisq_p_value(135.807, 100), 0.01, 1e-5);
    ck_assert_near(chisq_p_value(124.342, 100), 0.05, 1e-5);
    ck_assert_near(chisq_p_value(1000.0, 1000), 0.4941, 1e-3); /* just above the median */
}
END_TEST

/* Catches a helper that passes everything (too lenient pooling or p-value). */
START_TEST(test_chisq_rejects_samples_from_a_slightly_different_distribution)
{
    double w[T1_MAX], w_wrong[T1_MAX];
    int n = table1d(T1_RANDOM, w);
    memcpy(w_wrong, w, sizeof w);
    int big = 0;
    for (int i = 0; i < n; i++)
        if (w[i] > w[big]) big = i;
    w_wrong[big] *= 1.3; /* that bin claims 30% more than the sampler gives */
    distrib1d d = {0}, wrong = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, n, &err), 0);
    ck_assert_int_eq(distrib1d_init(&wrong, w_wrong, n, &err), 0);
    long obs[T1_MAX] = {0};
    double prob[T1_MAX];
    for (int i = 0; i < n; i++) prob[i] = distrib1d_pmf(&wrong, i);
    pcg32 rng = pcg32_seeded(1);
    for (long s = 0; s < N_SAMPLES; s++)
        obs[distrib1d_sample(&d, pcg32_double(&rng), NULL, NULL)]++;
    chisq_result r = chisq_test(obs, prob, n, N_SAMPLES);
    ck_assert_msg(!chisq_accept(&r, N_CHISQ_TESTS), "accepted: X^2 = %g, p = %g", r.stat, r.p);
    distrib1d_free(&d);
    distrib1d_free(&wrong);
}
END_TEST

/* Catches a helper that lets a sampler return what it calls impossible. */
START_TEST(test_chisq_rejects_any_sample_in_a_zero_probability_bin)
{
    long obs[3] = {5000, 1, 4999};
    const double prob[3] = {0.5, 0.0, 0.5};
    chisq_result r = chisq_test(obs, prob, 3, 10000);
    ck_assert_int_eq(r.stray, 1);
    ck_assert(!chisq_accept(&r, 1));
    obs[1] = 0;
    obs[2] = 5000;
    r = chisq_test(obs, prob, 3, 10000);
    ck_assert(chisq_accept(&r, 1));
}
END_TEST

/* Catches pooling that drops bins, forgets the pooled bin, or keeps one below 5 expected. */
START_TEST(test_chisq_pools_bins_expected_below_five)
{
    /* 3 big bins and 20 bins expected 0.5 each: the 20 pool into one bin of 10 -> dof 3 */
    long obs[23] = {0};
    double prob[23];
    long n = 10000;
    for (int k = 0; k < 3; k++) prob[k] = (1.0 - 20 * 0.5 / n) / 3.0;
    for (int k = 3; k < 23; k++) prob[k] = 0.5 / n;
    for (int k = 0; k < 3; k++) obs[k] = 3330;
    for (int k = 3; k < 13; k++) obs[k] = 1; /* 10 samples in the pooled bins, as expected */
    chisq_result r = chisq_test(obs, prob, 23, n);
    ck_assert_int_eq(r.dof, 3);
    ck_assert(chisq_accept(&r, 1));
    /* 4 bins expected 0.5 each: pooled 2 < 5, merged into the smallest big bin -> dof 2 */
    r = chisq_test(obs, prob, 7, n);
    ck_assert_int_eq(r.dof, 2);
    /* equal bins: counts 100 each are a perfect fit */
    long flat[8] = {100, 100, 100, 100, 100, 100, 100, 100};
    r = chisq_test_uniform(flat, 8, 800);
    ck_assert_int_eq(r.dof, 7);
    ck_assert(r.stat == 0.0);
    ck_assert_near(r.p, 1.0, 1e-12);
}
END_TEST

/* ---- 1D ------------------------------------------------------------------------------------ */

/* Sample table `which` with either sampler and test the joint (bin, remapped sub-bin) counts
 * against pmf(i) / REM_BUCKETS_1D; also check pmf() = w_i / sum w and reported pmf = pmf(). */
static void check_1d_samples(int which, int use_alias)
{
    double w[T1_MAX];
    int n = table1d(which, w);
    distrib1d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, n, &err), 0);
    if (use_alias) ck_assert_int_eq(distrib1d_alias_build(&d, &err), 0);
    double sum = sum_of(w, n);
    for (int i = 0; i < n; i++)
        ck_assert_msg(pmf_matches_weight(distrib1d_pmf(&d, i), w[i] / sum, n),
                      "%s: pmf(%d) = %.17g, not %.17g", t1_name[which], i, distrib1d_pmf(&d, i),
                      w[i] / sum);

    enum { R = REM_BUCKETS_1D };
    long obs[T1_MAX * R] = {0};
    double prob[T1_MAX * R];
    for (int k = 0; k < n * R; k++) prob[k] = distrib1d_pmf(&d, k / R) / R;
    pcg32 rng = pcg32_seeded(100 + (uint64_t)which * 2 + (uint64_t)use_alias);
    long out_of_range = 0, bad_pmf = 0, bad_rem = 0;
    for (long s = 0; s < N_SAMPLES; s++) {
        double xi = pcg32_double(&rng), pmf = -1.0, rem = -1.0;
        int i = use_alias ? distrib1d_sample_alias(&d, xi, &pmf, &rem)
                          : distrib1d_sample(&d, xi, &pmf, &rem);
        if (i < 0 || i >= n) {
            out_of_range++;
            continue;
        }
        if (!(pmf > 0.0) || !pmf_agrees(pmf, distrib1d_pmf(&d, i))) bad_pmf++;
        if (!(rem >= 0.0 && rem < 1.0)) {
            bad_rem++;
            continue;
        }
        obs[i * R + (int)(rem * R)]++;
    }
    ck_assert_msg(out_of_range == 0 && bad_pmf == 0 && bad_rem == 0,
                  "%s: %ld bins out of range, %ld pmfs not pmf(), %ld remapped outside [0,1)",
                  t1_name[which], out_of_range, bad_pmf, bad_rem);
    chisq_result r = chisq_test(obs, prob, n * R, N_SAMPLES);
    ck_assert_chisq(r, "%s, %s", t1_name[which], use_alias ? "alias" : "binary search");
    distrib1d_free(&d);
}

/* Catches a wrong CDF, an off-by-one search, a wrong remap, or a reported pmf that is not the
 * bin's. */
START_TEST(test_distrib1d_binary_search_samples_fit_the_pmf) { check_1d_samples(_i, 0); }
END_TEST

/* Catches a wrong alias table (Vose's bookkeeping) or alias remap: the alias samples must
 * follow the binary search's pmf. */
START_TEST(test_distrib1d_alias_samples_fit_the_binary_search_pmf) { check_1d_samples(_i, 1); }
END_TEST

/* The remapped value alone over all samples: REM_BUCKETS equal bins. */
static void check_1d_remapped_uniform(int use_alias)
{
    double w[T1_MAX];
    int n = table1d(T1_RANDOM, w);
    distrib1d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, n, &err), 0);
    ck_assert_int_eq(distrib1d_alias_build(&d, &err), 0);
    long obs[REM_BUCKETS] = {0}, outside = 0;
    pcg32 rng = pcg32_seeded(200 + (uint64_t)use_alias);
    for (long s = 0; s < N_SAMPLES; s++) {
        double rem = -1.0, xi = pcg32_double(&rng);
        if (use_alias)
            distrib1d_sample_alias(&d, xi, NULL, &rem);
        else
            distrib1d_sample(&d, xi, NULL, &rem);
        if (!(rem >= 0.0 && rem < 1.0)) {
            outside++;
            continue;
        }
        obs[(int)(rem * REM_BUCKETS)]++;
    }
    ck_assert_int_eq(outside, 0);
    chisq_result r = chisq_test_uniform(obs, REM_BUCKETS, N_SAMPLES);
    ck_assert_chisq(r, "remapped, %s", use_alias ? "alias" : "binary search");
    distrib1d_free(&d);
}

/* Catches a remap that divides by the wrong width or forgets to subtract the bin's start. */
START_TEST(test_distrib1d_remapped_values_are_uniform_on_0_1)
{
    check_1d_remapped_uniform(0);
    check_1d_remapped_uniform(1);
}
END_TEST

/* The probability an alias table actually samples, read off the table (cell c gives prob_c of
 * a cell to c and 1 - prob_c to its alias), against the pmf it reports.  A million bins of
 * weight 1 give their spare ~1e-7 each to one heavier bin; their float thresholds all round the
 * same way.  Catches a build that charges the alias 1 - q (the double) while storing the
 * rounded float: the roundings add up on the heavy bin (1.7% off). */
START_TEST(test_distrib1d_alias_table_samples_its_pmf_with_a_million_donors)
{
    const int n = 1000000;
    double *w = malloc((size_t)n * sizeof *w), *got = calloc((size_t)n, sizeof *got);
    ck_assert(w && got);
    w[0] = 1.0 + (n - 1) * 1e-7;
    for (int k = 1; k < n; k++) w[k] = 1.0;
    distrib1d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, n, &err), 0);
    ck_assert_int_eq(distrib1d_alias_build(&d, &err), 0);
    for (int c = 0; c < n; c++) {
        got[c] += d.alias[c].prob;
        got[d.alias[c].alias] += 1.0 - d.alias[c].prob;
    }
    double worst = 0.0;
    int at = -1;
    for (int i = 0; i < n; i++) {
        double pmf = distrib1d_pmf(&d, i), rel = fabs(got[i] / n - pmf) / pmf;
        if (rel > worst) worst = rel, at = i;
    }
    ck_assert_msg(worst < 1e-6, "bin %d is sampled with probability %.3g relative off its pmf", at,
                  worst);
    distrib1d_free(&d);
    free(w);
    free(got);
}
END_TEST

/* xi values at and beyond the ends of [0, 1) */
static const double xi_low[] = {0.0, -0.0, 0x1p-53, -1e-300, -1.0, -INFINITY, NAN};
static const double xi_high[] = {1.0 - 0x1p-24, 1.0 - 0x1p-53, 1.0, 1.0 + 1e-9, 2.0, INFINITY};
#define N_XI_LOW  ((int)(sizeof xi_low / sizeof xi_low[0]))
#define N_XI_HIGH ((int)(sizeof xi_high / sizeof xi_high[0]))

/* Catches a search that returns a zero-width bin at the ends (the first bin at xi = 0, the
 * trailing zero bins at xi = 1) or runs off the end of the CDF. */
START_TEST(test_distrib1d_edge_xi_give_the_first_and_last_nonzero_bins)
{
    const double w[7] = {0.0, 0.0, 1.0, 0.0, 2.0, 0.0, 0.0};
    distrib1d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, 7, &err), 0);
    ck_assert_int_eq(distrib1d_alias_build(&d, &err), 0);
    ck_assert_int_eq(d.first_nonzero, 2);
    ck_assert_int_eq(d.last_nonzero, 4);
    for (int k = 0; k < N_XI_LOW + N_XI_HIGH; k++) {
        int low = k < N_XI_LOW;
        double xi = low ? xi_low[k] : xi_high[k - N_XI_LOW], pmf, rem;
        int i = distrib1d_sample(&d, xi, &pmf, &rem);
        ck_assert_msg(i == (low ? 2 : 4), "xi = %.17g gave bin %d", xi, i);
        ck_assert(pmf > 0.0 && rem >= 0.0 && rem < 1.0);
        i = distrib1d_sample_alias(&d, xi, &pmf, &rem);
        ck_assert_msg(i == 2 || i == 4, "alias: xi = %.17g gave bin %d", xi, i);
        ck_assert(pmf > 0.0 && rem >= 0.0 && rem < 1.0);
    }
    distrib1d_free(&d);
}
END_TEST

/* Catches clamping xi = 1 to 1 - 2^-24 (float's last value) instead of the last double below
 * one: a last bin of probability 1e-15 must still be reachable, and remapped stays below 1. */
START_TEST(test_distrib1d_xi_of_one_reaches_a_tiny_last_bin)
{
    const double w[3] = {1.0, 1e-15, 0.0};
    distrib1d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, 3, &err), 0);
    double rem;
    ck_assert_int_eq(distrib1d_sample(&d, 1.0 - 0x1p-24, NULL, &rem), 0);
    ck_assert_int_eq(distrib1d_sample(&d, 1.0 - 0x1p-53, NULL, &rem), 1);
    ck_assert(rem >= 0.0 && rem < 1.0);
    ck_assert_int_eq(distrib1d_sample(&d, 1.0, NULL, &rem), 1);
    ck_assert(rem >= 0.0 && rem < 1.0);
    distrib1d_free(&d);
}
END_TEST

/* Catches a remap without its clamp: (x - cdf[i]) / p rounds up to exactly 1 for some x just
 * below a CDF step (x = 1 - 2^-53 with weights {0.46274883486330509, 0.71087739639915526} does),
 * and remapped must stay in [0, 1).  Every bin of 2000 random tables, 1D and a 2D column, at the
 * last double below its step.  The alias remap too: weights {3 2^-55, 1} give cell 0 the
 * probability 3 2^-54, and at xi = 1/2 - 2^-54 (f = 1 - 2^-53, its alias's part) both
 * f - prob and 1 - prob round to 1 - 2^-52, so (f - prob) / (1 - prob) is exactly 1. */
START_TEST(test_distrib_remapped_stays_below_one_just_below_a_step)
{
    const double w2[2] = {0.46274883486330509, 0.71087739639915526};
    distrib1d d = {0};
    error err = {0};
    double rem;
    ck_assert_int_eq(distrib1d_init(&d, w2, 2, &err), 0);
    ck_assert_int_eq(distrib1d_sample(&d, 1.0 - 0x1p-53, NULL, &rem), 1);
    ck_assert_msg(rem < 1.0, "remapped %.17g", rem);
    distrib1d_free(&d);
    const double w_alias[2] = {0x3p-55, 1.0};
    ck_assert_int_eq(distrib1d_init(&d, w_alias, 2, &err), 0);
    ck_assert_int_eq(distrib1d_alias_build(&d, &err), 0);
    ck_assert_int_eq(distrib1d_sample_alias(&d, 0.5 - 0x1p-54, NULL, &rem), 1);
    ck_assert_msg(rem < 1.0, "alias: remapped %.17g", rem);
    distrib1d_free(&d);
    pcg32 rng = pcg32_seeded(29);
    long bad = 0;
    for (int t = 0; t < 2000; t++) {
        int n = 2 + (int)(pcg32_double(&rng) * 7);
        double w[8];
        for (int k = 0; k < n; k++) w[k] = pcg32_double(&rng);
        distrib2d d2 = {0};
        ck_assert_int_eq(distrib1d_init(&d, w, n, &err), 0);
        ck_assert_int_eq(distrib2d_init(&d2, w, 1, n, &err), 0); /* one column: the same CDF */
        for (int i = 0; i < n; i++) {
            double x = nextafter(d.cdf[i + 1], 0.0), r2;
            int o, j;
            distrib1d_sample(&d, x, NULL, &rem);
            distrib2d_sample(&d2, 0.5, x, &o, &j, NULL, NULL, &r2);
            bad += !(rem >= 0.0 && rem < 1.0) || !(r2 >= 0.0 && r2 < 1.0);
        }
        distrib1d_free(&d);
        distrib2d_free(&d2);
    }
    ck_assert_msg(bad == 0, "%ld remapped values outside [0, 1)", bad);
}
END_TEST

/* Catches a zero bin reachable anywhere inside [0, 1) (e.g. a search for cdf >= xi). */
START_TEST(test_distrib1d_zero_bins_are_never_chosen_over_a_sweep_of_xi)
{
    double w[40];
    for (int i = 0; i < 40; i++) w[i] = (i % 3 == 0 || i < 2 || i > 36) ? 0.0 : 1.0 + i;
    distrib1d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, 40, &err), 0);
    ck_assert_int_eq(distrib1d_alias_build(&d, &err), 0);
    long zero_hits = 0;
    for (int k = 0; k <= 100000 + N_XI_LOW + N_XI_HIGH; k++) {
        double xi = k <= 100000              ? k / 100000.0
                    : k <= 100000 + N_XI_LOW ? xi_low[k - 100001]
                                             : xi_high[k - 100001 - N_XI_LOW];
        /* also every CDF value itself and its neighbours, where a >= / > slip would show */
        int i = distrib1d_sample(&d, xi, NULL, NULL);
        zero_hits += w[i] == 0.0;
        i = distrib1d_sample_alias(&d, xi, NULL, NULL);
        zero_hits += w[i] == 0.0;
    }
    for (int j = 0; j <= 40; j++) {
        double c = d.cdf[j];
        const double xs[3] = {c, nextafter(c, 0.0), nextafter(c, 1.0)};
        for (int k = 0; k < 3; k++) {
            zero_hits += w[distrib1d_sample(&d, xs[k], NULL, NULL)] == 0.0;
            zero_hits += w[distrib1d_sample_alias(&d, xs[k], NULL, NULL)] == 0.0;
        }
    }
    ck_assert_int_eq(zero_hits, 0);
    distrib1d_free(&d);
}
END_TEST

/* The bin of x by definition: the first i with cdf[i + 1] > x, by a plain linear scan. */
static int linear_bin(const double *cdf, int n, double x)
{
    if (!(x >= 0.0)) x = 0.0;
    if (x >= 1.0) x = nextafter(1.0, 0.0);
    int i = 0;
    while (i < n - 1 && !(cdf[i + 1] > x)) i++;
    return i;
}

/* Probe point k of n + 2002: every CDF value, then a grid of 2001. */
static double probe_point(const double *cdf, int n, int k)
{
    if (k <= n) return cdf[k];
    return (k - n - 1) / 2000.0;
}

/* Compare the 1D search, and the 2D search within a column, with linear_bin at every probe
 * point and 3 ulps either side (only near `only` if it is >= 0). */
static long count_search_disagreements_near(const double *w, int n, double only)
{
    distrib1d d = {0};
    distrib2d d2 = {0};
    error err = {0};
    double *w2 = malloc(2 * (size_t)n * sizeof *w2); /* column 1 = w, column 0 = all ones */
    ck_assert_ptr_nonnull(w2);
    for (int i = 0; i < n; i++) {
        w2[i] = 1.0;
        w2[n + i] = w[i];
    }
    ck_assert_int_eq(distrib1d_init(&d, w, n, &err), 0);
    ck_assert_int_eq(distrib2d_init(&d2, w2, 2, n, &err), 0);
    const double *col = d2.cond_cdf + (size_t)(n + 1);
    long bad = 0;
    for (int k = 0; k < (only >= 0.0 ? 1 : n + 2002); k++) {
        double x = only >= 0.0 ? only : probe_point(d.cdf, n, k);
        for (int u = 0; u < 3; u++) x = nextafter(x, -1.0);
        for (int u = 0; u < 7; u++, x = nextafter(x, 2.0)) {
            bad += distrib1d_sample(&d, x, NULL, NULL) != linear_bin(d.cdf, n, x);
            int o, i;
            distrib2d_sample(&d2, 1.0, x, &o, &i, NULL, NULL, NULL);
            bad += o != 1 || i != linear_bin(col, n, x);
        }
    }
    distrib1d_free(&d);
    distrib2d_free(&d2);
    free(w2);
    return bad;
}

static long count_search_disagreements(const double *w, int n)
{
    return count_search_disagreements_near(w, n, -1.0);
}

/* Catches a binary search (1D and 2D) that stops one bin early or late, at a CDF step or an
 * ulp beside it. */
START_TEST(test_distrib1d_search_agrees_with_a_linear_scan)
{
    double w[1000];
    for (int i = 0; i < 12; i++) w[i] = 1.0; /* CDF steps on thirds: 1/3 is not a double */
    ck_assert_int_eq(count_search_disagreements(w, 12), 0);
    for (int n = 1; n <= 9; n++) { /* every small size, so m and n / m vary */
        for (int i = 0; i < n; i++) w[i] = (i * 7 % 3 == 0) ? 0.0 : 0.1 * (i + 1);
        w[n - 1] = 1.0;
        ck_assert_int_eq(count_search_disagreements(w, n), 0);
    }
    pcg32 rng = pcg32_seeded(13);
    for (int i = 0; i < 1000; i++) {
        double u = pcg32_double(&rng);
        w[i] = u < 0.3 ? 0.0 : u < 0.31 ? 1e4 * u : u; /* zeros and a few bright bins */
    }
    ck_assert_int_eq(count_search_disagreements(w, 1000), 0);

    /* A CDF step at c = g/m, or one ulp above, with a long run of zero bins after it: the
     * search must land on the bin before the run or the one after it, never inside.  Weights
     * {c, 0, ..., 0, 1 - c} put cdf[1] at c. */
    long exact_steps = 0, bad = 0;
    for (int m = 2; m <= 48; m++) {
        for (int g = 1; g < m; g++) {
            for (int up = 0; up < 2; up++) {
                double c = (double)g / m, v[4 * 48] = {0};
                if (up) c = nextafter(c, 1.0);
                v[0] = c;
                v[4 * m - 1] = 1.0 - c;
                if (c / (c + (1.0 - c)) != c) continue; /* 1 - c rounded: step not at c */
                exact_steps++;
                bad += count_search_disagreements_near(v, 4 * m, c);
            }
        }
    }
    ck_assert_int_gt(exact_steps, 1000);
    ck_assert_int_eq(bad, 0);
}
END_TEST

/* Catches a search or remap that is not monotone (which would break stratified sampling). */
START_TEST(test_distrib1d_inversion_is_monotone_in_xi)
{
    const double w[6] = {0.0, 1.0, 3.0, 0.0, 2.0, 0.5};
    distrib1d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, 6, &err), 0);
    int prev_i = -1;
    double prev_rem = -1.0;
    long not_monotone = 0, outside = 0;
    for (int k = 0; k <= 65536 + 2; k++) {
        double xi = k <= 65536 ? k / 65537.0 : k == 65537 ? 1.0 - 0x1p-53 : 1.0, rem;
        int i = distrib1d_sample(&d, xi, NULL, &rem);
        if (i < prev_i || (i == prev_i && rem < prev_rem)) not_monotone++;
        if (!(rem >= 0.0 && rem < 1.0)) outside++;
        prev_i = i;
        prev_rem = rem;
    }
    ck_assert_int_eq(not_monotone, 0);
    ck_assert_int_eq(outside, 0);
    ck_assert_int_eq(prev_i, 5);
    distrib1d_free(&d);
}
END_TEST

/* Catches a divide by a zero total (NaN CDF) or a missing fallback flag. */
START_TEST(test_distrib1d_all_zero_weights_fall_back_to_uniform)
{
    const double w[5] = {0.0, 0.0, -0.0, 0.0, 0.0};
    distrib1d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, 5, &err), 0);
    ck_assert_int_eq(d.fell_back_to_uniform, 1);
    ck_assert_int_eq(d.n_bad, 0);
    for (int i = 0; i < 5; i++) ck_assert_near(distrib1d_pmf(&d, i), 0.2, 1e-15);
    ck_assert_int_eq(distrib1d_sample(&d, 0.5, NULL, NULL), 2);
    ck_assert_int_eq(distrib1d_sample(&d, 1.0, NULL, NULL), 4);
    ck_assert(d.cdf[5] == 1.0);
    ck_assert(d.total == 5.0); /* n, as distrib.h promises, not the sum 0 */
    distrib1d_free(&d);

    const double w_ok[2] = {0.0, 1.0};
    ck_assert_int_eq(distrib1d_init(&d, w_ok, 2, &err), 0);
    ck_assert_int_eq(d.fell_back_to_uniform, 0);
    ck_assert(d.total == 1.0);
    distrib1d_free(&d);
}
END_TEST

/* Catches NaN / Inf / negative weights leaking into the CDF (NaN everywhere, negative pmf)
 * or not being counted; -0.0 is a plain zero, not a bad weight. */
START_TEST(test_distrib1d_bad_weights_are_counted_and_used_as_zero)
{
    const double w[8] = {1.0, NAN, 2.0, INFINITY, -INFINITY, -3.0, -0.0, 4.0};
    const float wf[8] = {1.0f, NAN, 2.0f, INFINITY, -INFINITY, -3.0f, -0.0f, 4.0f};
    const double good[8] = {1.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 4.0};
    distrib1d d = {0}, df = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, 8, &err), 0);
    ck_assert_int_eq(distrib1d_init_float(&df, wf, 8, &err), 0);
    ck_assert_int_eq(d.n_bad, 4);
    ck_assert_int_eq(df.n_bad, 4);
    ck_assert_int_eq(d.fell_back_to_uniform, 0);
    for (int i = 0; i < 8; i++) {
        ck_assert(pmf_matches_weight(distrib1d_pmf(&d, i), good[i] / 7.0, 8));
        ck_assert(distrib1d_pmf(&df, i) == distrib1d_pmf(&d, i));
    }
    ck_assert(d.total == 7.0);
    distrib1d_free(&d);
    distrib1d_free(&df);

    const double all_bad[3] = {NAN, -1.0, INFINITY}; /* nothing left: uniform, all counted */
    ck_assert_int_eq(distrib1d_init(&d, all_bad, 3, &err), 0);
    ck_assert_int_eq(d.n_bad, 3);
    ck_assert_int_eq(d.fell_back_to_uniform, 1);
    distrib1d_free(&d);
}
END_TEST

/* Catches a missing size check (a huge malloc, a negative size) or an overflowing sum turned
 * into a CDF of NaN; the table is left empty and safe to free. */
START_TEST(test_distrib1d_rejects_bad_sizes_and_overflowing_sums)
{
    const double w[2] = {DBL_MAX, DBL_MAX};
    distrib1d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, 0, &err), -1);
    ck_assert(err.msg[0] != '\0');
    ck_assert_int_eq(distrib1d_init(&d, w, -3, &err), -1);
    ck_assert_int_eq(distrib1d_init(&d, w, (int)DISTRIB_MAX_BINS + 1, &err), -1);
    err.msg[0] = '\0';
    ck_assert_int_eq(distrib1d_init(&d, w, 2, &err), -1);
    ck_assert_msg(strstr(err.msg, "overflow") != NULL, "message: %s", err.msg);
    ck_assert(d.cdf == NULL && d.n == 0);
    distrib1d_free(&d);
    ck_assert_int_eq(distrib1d_init(&d, w, 1, &err), 0); /* DBL_MAX alone is fine */
    ck_assert(distrib1d_pmf(&d, 0) == 1.0);
    distrib1d_free(&d);
    distrib1d_free(&d); /* twice is harmless */
}
END_TEST

/* Catches a float path that reads the array with the wrong stride or type. */
START_TEST(test_distrib1d_float_weights_give_the_same_table)
{
    double w[T1_MAX];
    float wf[T1_MAX];
    int n = table1d(T1_RANDOM, w);
    for (int i = 0; i < n; i++) {
        wf[i] = (float)w[i];
        w[i] = wf[i];
    }
    distrib1d d = {0}, df = {0};
    error err = {0};
    ck_assert_int_eq(distrib1d_init(&d, w, n, &err), 0);
    ck_assert_int_eq(distrib1d_init_float(&df, wf, n, &err), 0);
    for (int i = 0; i <= n; i++) ck_assert(d.cdf[i] == df.cdf[i]);
    ck_assert_int_eq(distrib1d_alias_build(&d, &err), 0);
    ck_assert_int_eq(distrib1d_alias_build(&d, &err), 0); /* twice is harmless */
    distrib1d_free(&d);
    distrib1d_free(&df);
}
END_TEST

/* ---- 2D ------------------------------------------------------------------------------------ */

/* Catches a transposed layout (inner-major), a marginal over the wrong variable, or a pmf that
 * is not p(outer) p(inner | outer). */
START_TEST(test_distrib2d_pmf_is_weight_over_total_with_outer_major_layout)
{
    double w[T2_MAX];
    int no, ni;
    table2d(T2_3X2, w, &no, &ni);
    distrib2d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init(&d, w, no, ni, &err), 0);
    ck_assert_int_eq(d.n_outer, 3);
    ck_assert_int_eq(d.n_inner, 2);
    double total = sum_of(w, no * ni);
    for (int o = 0; o < no; o++) {
        double col = w[o * ni] + w[o * ni + 1];
        ck_assert(pmf_matches_weight(distrib2d_pmf_outer(&d, o), col / total, no));
        for (int i = 0; i < ni; i++) {
            ck_assert(pmf_matches_weight(distrib2d_pmf(&d, o, i), w[o * ni + i] / total, no + ni));
            ck_assert(pmf_matches_weight(distrib2d_pmf_inner(&d, o, i), w[o * ni + i] / col, ni));
        }
    }
    ck_assert(distrib2d_pmf(&d, 1, 1) == 0.0);
    distrib2d_free(&d);
}
END_TEST

/* Sample table `which` and test joint (cell, rem_outer half, rem_inner half) counts. */
static void check_2d_samples(int which, int use_alias)
{
    double w[T2_MAX];
    int no, ni;
    table2d(which, w, &no, &ni);
    distrib2d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init(&d, w, no, ni, &err), 0);
    if (use_alias) ck_assert_int_eq(distrib2d_alias_build(&d, &err), 0);
    double total = sum_of(w, no * ni);
    for (int k = 0; k < no * ni; k++)
        ck_assert_msg(pmf_matches_weight(distrib2d_pmf(&d, k / ni, k % ni), w[k] / total, no + ni),
                      "%s: pmf(%d, %d) = %.17g, not %.17g", t2_name[which], k / ni, k % ni,
                      distrib2d_pmf(&d, k / ni, k % ni), w[k] / total);

    enum { R = REM_BUCKETS_2D, RR = REM_BUCKETS_2D * REM_BUCKETS_2D };
    long obs[T2_MAX * RR] = {0};
    double prob[T2_MAX * RR];
    for (int k = 0; k < no * ni * RR; k++)
        prob[k] = distrib2d_pmf(&d, (k / RR) / ni, (k / RR) % ni) / RR;
    pcg32 rng = pcg32_seeded(300 + (uint64_t)which * 2 + (uint64_t)use_alias);
    long out_of_range = 0, bad_pmf = 0, bad_rem = 0;
    for (long s = 0; s < N_SAMPLES; s++) {
        double x1 = pcg32_double(&rng), x2 = pcg32_double(&rng);
        int o = -1, i = -1;
        double pmf = -1.0, ro = -1.0, ri = -1.0;
        if (use_alias)
            distrib2d_sample_alias(&d, x1, x2, &o, &i, &pmf, &ro, &ri);
        else
            distrib2d_sample(&d, x1, x2, &o, &i, &pmf, &ro, &ri);
        if (o < 0 || o >= no || i < 0 || i >= ni) {
            out_of_range++;
            continue;
        }
        if (!(pmf > 0.0) || !pmf_agrees(pmf, distrib2d_pmf(&d, o, i))) bad_pmf++;
        if (!(ro >= 0.0 && ro < 1.0 && ri >= 0.0 && ri < 1.0)) {
            bad_rem++;
            continue;
        }
        obs[(o * ni + i) * RR + (int)(ro * R) * R + (int)(ri * R)]++;
    }
    ck_assert_msg(out_of_range == 0 && bad_pmf == 0 && bad_rem == 0,
                  "%s: %ld cells out of range, %ld pmfs not pmf(), %ld remapped outside [0,1)",
                  t2_name[which], out_of_range, bad_pmf, bad_rem);
    chisq_result r = chisq_test(obs, prob, no * ni * RR, N_SAMPLES);
    ck_assert_chisq(r, "%s, %s", t2_name[which], use_alias ? "alias" : "binary search");
    distrib2d_free(&d);
}

/* Catches a wrong marginal or conditional CDF, the wrong column's conditional, or a bad
 * remap in either dimension. */
START_TEST(test_distrib2d_binary_search_samples_fit_the_pmf) { check_2d_samples(_i, 0); }
END_TEST

/* Catches wrong alias tables at either level: alias samples must follow the binary pmf. */
START_TEST(test_distrib2d_alias_samples_fit_the_binary_search_pmf) { check_2d_samples(_i, 1); }
END_TEST

/* rem_outer and rem_inner alone, each in REM_BUCKETS equal bins. */
static void check_2d_remapped_uniform(int use_alias)
{
    double w[T2_MAX];
    int no, ni;
    table2d(T2_RANDOM, w, &no, &ni);
    distrib2d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init(&d, w, no, ni, &err), 0);
    ck_assert_int_eq(distrib2d_alias_build(&d, &err), 0);
    long obs_o[REM_BUCKETS] = {0}, obs_i[REM_BUCKETS] = {0}, outside = 0;
    pcg32 rng = pcg32_seeded(400 + (uint64_t)use_alias);
    for (long s = 0; s < N_SAMPLES; s++) {
        double x1 = pcg32_double(&rng), x2 = pcg32_double(&rng), ro = -1.0, ri = -1.0;
        int o, i;
        if (use_alias)
            distrib2d_sample_alias(&d, x1, x2, &o, &i, NULL, &ro, &ri);
        else
            distrib2d_sample(&d, x1, x2, &o, &i, NULL, &ro, &ri);
        if (!(ro >= 0.0 && ro < 1.0 && ri >= 0.0 && ri < 1.0)) {
            outside++;
            continue;
        }
        obs_o[(int)(ro * REM_BUCKETS)]++;
        obs_i[(int)(ri * REM_BUCKETS)]++;
    }
    ck_assert_int_eq(outside, 0);
    chisq_result r = chisq_test_uniform(obs_o, REM_BUCKETS, N_SAMPLES);
    ck_assert_chisq(r, "rem_outer, %s", use_alias ? "alias" : "binary search");
    r = chisq_test_uniform(obs_i, REM_BUCKETS, N_SAMPLES);
    ck_assert_chisq(r, "rem_inner, %s", use_alias ? "alias" : "binary search");
    distrib2d_free(&d);
}

/* Catches a remap in either dimension that is not uniform. */
START_TEST(test_distrib2d_remapped_values_are_uniform_on_0_1)
{
    check_2d_remapped_uniform(0);
    check_2d_remapped_uniform(1);
}
END_TEST

/* A 7 x 6 grid with zero columns 0, 3, 6 and zero cells at both ends of every column. */
static void zero_grid(double *w, int *no, int *ni)
{
    *no = 7;
    *ni = 6;
    for (int o = 0; o < 7; o++)
        for (int i = 0; i < 6; i++)
            w[o * 6 + i] = (o % 3 == 0 || i == 0 || i == 5 || (i + o) % 4 == 0) ? 0.0 : 1.0 + i + o;
}

/* The sweeps of xi below: k / SWEEP_STEPS for k = 0 .. SWEEP_STEPS, then the edge values
 * xi_low and xi_high (NaN, infinities and out-of-range values among them). */
enum { SWEEP_STEPS = 400, N_SWEEP = SWEEP_STEPS + 1 + N_XI_LOW + N_XI_HIGH };
static double sweep_xi(int k)
{
    return k <= SWEEP_STEPS              ? (double)k / SWEEP_STEPS
           : k <= SWEEP_STEPS + N_XI_LOW ? xi_low[k - SWEEP_STEPS - 1]
                                         : xi_high[k - SWEEP_STEPS - 1 - N_XI_LOW];
}

/* zero_grid's weights in d, with the CDFs and the alias tables built (d is freed by the caller) */
static void zero_grid_tables(distrib2d *d, double *w, int *no, int *ni)
{
    error err = {0};
    zero_grid(w, no, ni);
    ck_assert_int_eq(distrib2d_init(d, w, *no, *ni, &err), 0);
    ck_assert_int_eq(distrib2d_alias_build(d, &err), 0);
}

/* Catches a zero column or zero cell reachable from any xi pair, edges included. */
START_TEST(test_distrib2d_zero_columns_and_cells_are_never_chosen)
{
    double w[T2_MAX];
    int no, ni;
    distrib2d d = {0};
    zero_grid_tables(&d, w, &no, &ni);
    long zero_hits = 0, out_of_range = 0;
    for (int a = 0; a < N_SWEEP; a++) {
        for (int b = 0; b < N_SWEEP; b++) {
            double xs[2] = {sweep_xi(a), sweep_xi(b)};
            for (int alias = 0; alias < 2; alias++) {
                int o = -1, i = -1;
                double pmf = 0.0;
                if (alias)
                    distrib2d_sample_alias(&d, xs[0], xs[1], &o, &i, &pmf, NULL, NULL);
                else
                    distrib2d_sample(&d, xs[0], xs[1], &o, &i, &pmf, NULL, NULL);
                if (o < 0 || o >= no || i < 0 || i >= ni) {
                    out_of_range++;
                    continue;
                }
                zero_hits += w[o * ni + i] == 0.0 || !(pmf > 0.0);
            }
        }
    }
    ck_assert_int_eq(out_of_range, 0);
    ck_assert_int_eq(zero_hits, 0);
    distrib2d_free(&d);
}
END_TEST

START_TEST(test_distrib2d_edge_xi_give_the_first_and_last_nonzero_cells)
{
    double w[T2_MAX];
    int no, ni;
    zero_grid(w, &no, &ni);
    distrib2d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init(&d, w, no, ni, &err), 0);
    /* nonzero columns: 1, 2, 4, 5.  Column 1: cells 1, 2, 4 (3 is zero); column 5: 1, 2, 4 */
    for (int a = 0; a < N_XI_LOW + N_XI_HIGH; a++) {
        for (int b = 0; b < N_XI_LOW + N_XI_HIGH; b++) {
            int low_a = a < N_XI_LOW, low_b = b < N_XI_LOW;
            double xa = low_a ? xi_low[a] : xi_high[a - N_XI_LOW];
            double xb = low_b ? xi_low[b] : xi_high[b - N_XI_LOW];
            int o, i;
            double pmf, ro, ri;
            distrib2d_sample(&d, xa, xb, &o, &i, &pmf, &ro, &ri);
            ck_assert_msg(o == (low_a ? 1 : 5), "xi_outer = %.17g gave column %d", xa, o);
            int first = 1, last = 4;
            ck_assert_msg(i == (low_b ? first : last), "xi_inner = %.17g gave cell %d", xb, i);
            ck_assert(pmf > 0.0 && ro >= 0.0 && ro < 1.0 && ri >= 0.0 && ri < 1.0);
        }
    }
    distrib2d_free(&d);
}
END_TEST

/* Catches a 2D inversion that breaks stratification: for a fixed column, a larger xi_inner
 * never gives a smaller cell or (in the same cell) a smaller rem_inner; likewise for outer. */
START_TEST(test_distrib2d_inversion_is_monotone_in_each_xi)
{
    double w[T2_MAX];
    int no, ni;
    table2d(T2_RANDOM, w, &no, &ni);
    distrib2d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init(&d, w, no, ni, &err), 0);
    long not_monotone = 0;
    for (int fixed = 0; fixed <= 8; fixed++) {
        double xf = fixed / 8.0;
        int prev_o = -1, prev_i = -1, prev_col = -1;
        double prev_ro = -1.0, prev_ri = -1.0;
        for (int k = 0; k <= 20000; k++) {
            double xs = k / 20000.0, ro, ri;
            int o, i;
            distrib2d_sample(&d, xs, xf, &o, &i, NULL, &ro, NULL); /* sweep outer */
            if (o < prev_o || (o == prev_o && ro < prev_ro)) not_monotone++;
            prev_o = o;
            prev_ro = ro;
            distrib2d_sample(&d, xf, xs, &o, &i, NULL, NULL, &ri); /* sweep inner */
            if (prev_col >= 0 && o != prev_col) not_monotone++;    /* column must not move */
            if (i < prev_i || (i == prev_i && ri < prev_ri)) not_monotone++;
            prev_col = o;
            prev_i = i;
            prev_ri = ri;
        }
    }
    ck_assert_int_eq(not_monotone, 0);
    distrib2d_free(&d);
}
END_TEST

/* Catches a zero grid turned into NaNs, or zero columns given a NaN conditional. */
START_TEST(test_distrib2d_all_zero_weights_fall_back_to_uniform)
{
    double w[12] = {0};
    w[5] = -1.0; /* bad, counted, used as 0 */
    distrib2d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init(&d, w, 4, 3, &err), 0);
    ck_assert_int_eq(d.fell_back_to_uniform, 1);
    ck_assert_int_eq(d.n_bad, 1);
    ck_assert(d.total == 12.0); /* n_outer n_inner, as distrib.h promises */
    for (int o = 0; o < 4; o++)
        for (int i = 0; i < 3; i++) ck_assert_near(distrib2d_pmf(&d, o, i), 1.0 / 12.0, 1e-15);
    ck_assert_int_eq(distrib2d_alias_build(&d, &err), 0);
    int o, i;
    distrib2d_sample_alias(&d, 0.99, 0.5, &o, &i, NULL, NULL, NULL);
    ck_assert_int_eq(o, 3);
    ck_assert_int_eq(i, 1);
    distrib2d_free(&d);
}
END_TEST

/* Catches bad weights in the grid (double or float input) leaking into the CDFs. */
START_TEST(test_distrib2d_bad_weights_are_counted_and_used_as_zero)
{
    const double w[6] = {1.0, NAN, -2.0, 3.0, INFINITY, 4.0};
    const float wf[6] = {1.0f, NAN, -2.0f, 3.0f, INFINITY, 4.0f};
    distrib2d d = {0}, df = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init(&d, w, 3, 2, &err), 0);
    ck_assert_int_eq(distrib2d_init_float(&df, wf, 3, 2, &err), 0);
    ck_assert_int_eq(d.n_bad, 3);
    ck_assert_int_eq(df.n_bad, 3);
    const double good[6] = {1.0, 0.0, 0.0, 3.0, 0.0, 4.0};
    for (int k = 0; k < 6; k++) {
        ck_assert(pmf_matches_weight(distrib2d_pmf(&d, k / 2, k % 2), good[k] / 8.0, 5));
        ck_assert(distrib2d_pmf(&df, k / 2, k % 2) == distrib2d_pmf(&d, k / 2, k % 2));
    }
    ck_assert(d.total == 8.0);
    distrib2d_free(&d);
    distrib2d_free(&df);
}
END_TEST

/* Catches a missing size check, an int overflow of n_outer * n_inner, or an overflowing sum
 * (in one column, or only in the total) turned into NaN CDFs. */
START_TEST(test_distrib2d_rejects_bad_sizes_and_overflowing_sums)
{
    double w[4] = {1.0, 1.0, 1.0, 1.0};
    distrib2d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init(&d, w, 0, 4, &err), -1);
    ck_assert_int_eq(distrib2d_init(&d, w, 4, 0, &err), -1);
    ck_assert_int_eq(distrib2d_init(&d, w, -2, -2, &err), -1);
    ck_assert_int_eq(distrib2d_init(&d, w, 1 << 15, 1 << 14, &err), -1); /* 2^29 cells */
    ck_assert_int_eq(distrib2d_init(&d, w, 1 << 20, 1 << 20, &err), -1); /* 2^40: int overflow */
    ck_assert(err.msg[0] != '\0');
    w[0] = w[1] = DBL_MAX; /* column 0 overflows */
    ck_assert_int_eq(distrib2d_init(&d, w, 2, 2, &err), -1);
    ck_assert_msg(strstr(err.msg, "overflow") != NULL, "message: %s", err.msg);
    w[1] = 0.0;
    w[2] = DBL_MAX; /* each column fits, the total does not */
    ck_assert_int_eq(distrib2d_init(&d, w, 2, 2, &err), -1);
    ck_assert_msg(strstr(err.msg, "overflow") != NULL, "message: %s", err.msg);
    ck_assert(d.cond_cdf == NULL && d.marginal.cdf == NULL && d.n_outer == 0);
    distrib2d_free(&d);
    distrib2d_free(&d);
}
END_TEST

/* Catches CDFs accumulated or stored in float: in a column where a sun is 10^8 times the sky,
 * float steps would give the dim cells after it a wrong pmf, most of them 0 (never sampled). */
START_TEST(test_distrib2d_dim_cells_beside_a_sun_keep_their_probability)
{
    enum { NO = 2, NI = 4096, SUN = 1000 };
    double *w = malloc(NO * NI * sizeof *w);
    ck_assert_ptr_nonnull(w);
    for (int k = 0; k < NO * NI; k++) w[k] = 1.0 + (k % 13) * 0.01;
    w[SUN] = 1e8;
    distrib2d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init(&d, w, NO, NI, &err), 0);
    double col = sum_of(w, NI);
    double worst = 0.0;
    for (int i = 0; i < NI; i++) {
        double want = w[i] / col, rel = fabs(distrib2d_pmf_inner(&d, 0, i) - want) / want;
        if (rel > worst) worst = rel;
    }
    /* double: ~2e-8 here (DBL_EPSILON / 1e-8); float steps: errors of 70x and empty cells */
    ck_assert_msg(worst < 1e-6, "worst relative pmf error %g", worst);
    /* the last CDF step before 1 is a dim cell after the sun: reachable at xi just below 1 */
    int o, i;
    distrib2d_sample(&d, 0.0, 1.0, &o, &i, NULL, NULL, NULL);
    ck_assert_int_eq(o, 0);
    ck_assert_int_eq(i, NI - 1);
    free(w);
    distrib2d_free(&d);
}
END_TEST

/* Catches normalization lost over a large grid (sums of millions of cells in float, a last
 * CDF entry that is not exactly 1).  8192 x 4096 = 33.5M cells, the size of a 8K envmap; it
 * builds in ~0.3 s (~1 s under AddressSanitizer), inside Check's 4 s limit. */
START_TEST(test_distrib2d_8192_by_4096_table_is_normalized)
{
    enum { NO = 8192, NI = 4096 };
    float *w = malloc((size_t)NO * NI * sizeof *w);
    ck_assert_ptr_nonnull(w);
    for (size_t k = 0; k < (size_t)NO * NI; k++) {
        uint32_t h = (uint32_t)k * 2654435761u; /* Knuth's multiplicative hash: a rough sky */
        w[k] = 0.01f + (float)(h >> 16) * (1.0f / 65536.0f);
    }
    for (int i = 0; i < NI; i++) w[(size_t)77 * NI + i] = 0.0f; /* a black column */
    w[(size_t)4000 * NI + 2000] = 1e6f;                         /* a sun */
    distrib2d d = {0};
    error err = {0};
    ck_assert_int_eq(distrib2d_init_float(&d, w, NO, NI, &err), 0);
    free(w);
    ck_assert(d.marginal.cdf[NO] == 1.0);
    double sum = 0.0;
    long last_not_one = 0;
    for (int o = 0; o < NO; o++) {
        const double *cdf = d.cond_cdf + (size_t)o * (NI + 1);
        last_not_one += cdf[NI] != 1.0;
        double col = 0.0;
        for (int i = 0; i < NI; i++) col += distrib2d_pmf(&d, o, i);
        sum += col;
    }
    ck_assert_int_eq(last_not_one, 0);
    ck_assert_msg(fabs(sum - 1.0) < 1e-6, "sum of pmf = %.17g", sum);
    ck_assert(distrib2d_pmf_outer(&d, 77) == 0.0);
    distrib2d_free(&d);
}
END_TEST

Suite *distrib_suite(void)
{
    Suite *s = suite_create("distrib");
    TCase *tc = tcase_create("chisq");
    tcase_add_test(tc, test_chisq_gamma_q_matches_closed_forms_and_tables);
    tcase_add_test(tc, test_chisq_rejects_samples_from_a_slightly_different_distribution);
    tcase_add_test(tc, test_chisq_rejects_any_sample_in_a_zero_probability_bin);
    tcase_add_test(tc, test_chisq_pools_bins_expected_below_five);
    suite_add_tcase(s, tc);

    tc = tcase_create("distrib1d");
    tcase_add_loop_test(tc, test_distrib1d_binary_search_samples_fit_the_pmf, 0, T1_COUNT);
    tcase_add_loop_test(tc, test_distrib1d_alias_samples_fit_the_binary_search_pmf, 0, T1_COUNT);
    tcase_add_test(tc, test_distrib1d_remapped_values_are_uniform_on_0_1);
    tcase_add_test(tc, test_distrib1d_alias_table_samples_its_pmf_with_a_million_donors);
    tcase_add_test(tc, test_distrib_remapped_stays_below_one_just_below_a_step);
    tcase_add_test(tc, test_distrib1d_edge_xi_give_the_first_and_last_nonzero_bins);
    tcase_add_test(tc, test_distrib1d_xi_of_one_reaches_a_tiny_last_bin);
    tcase_add_test(tc, test_distrib1d_zero_bins_are_never_chosen_over_a_sweep_of_xi);
    tcase_add_test(tc, test_distrib1d_search_agrees_with_a_linear_scan);
    tcase_add_test(tc, test_distrib1d_inversion_is_monotone_in_xi);
    tcase_add_test(tc, test_distrib1d_all_zero_weights_fall_back_to_uniform);
    tcase_add_test(tc, test_distrib1d_bad_weights_are_counted_and_used_as_zero);
    tcase_add_test(tc, test_distrib1d_rejects_bad_sizes_and_overflowing_sums);
    tcase_add_test(tc, test_distrib1d_float_weights_give_the_same_table);
    suite_add_tcase(s, tc);

    tc = tcase_create("distrib2d");
    unit_slow(tc); /* a slow case (unit.h) */
    tcase_add_test(tc, test_distrib2d_pmf_is_weight_over_total_with_outer_major_layout);
    tcase_add_loop_test(tc, test_distrib2d_binary_search_samples_fit_the_pmf, 0, T2_COUNT);
    tcase_add_loop_test(tc, test_distrib2d_alias_samples_fit_the_binary_search_pmf, 0, T2_COUNT);
    tcase_add_test(tc, test_distrib2d_remapped_values_are_uniform_on_0_1);
    tcase_add_test(tc, test_distrib2d_zero_columns_and_cells_are_never_chosen);
    tcase_add_test(tc, test_distrib2d_edge_xi_give_the_first_and_last_nonzero_cells);
    tcase_add_test(tc, test_distrib2d_inversion_is_monotone_in_each_xi);
    tcase_add_test(tc, test_distrib2d_all_zero_weights_fall_back_to_uniform);
    tcase_add_test(tc, test_distrib2d_bad_weights_are_counted_and_used_as_zero);
    tcase_add_test(tc, test_distrib2d_rejects_bad_sizes_and_overflowing_sums);
    tcase_add_test(tc, test_distrib2d_dim_cells_beside_a_sun_keep_their_probability);
    tcase_add_test(tc, test_distrib2d_8192_by_4096_table_is_normalized);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(distrib_suite)
