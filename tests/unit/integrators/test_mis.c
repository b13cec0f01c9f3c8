/* test_mis.c - multiple importance sampling's weight alone (include/envtex/integrators/
 * integrator.h: integrator_power_heuristic), the step `mis` of tests/steps: Veach's power
 * heuristic, not the balance heuristic (both unbiased: no render can tell them apart quickly),
 * the two strategies' weights summing to 1, and the guards for a zero, NaN or infinite pdf. */
#include "envtex/integrators/integrator.h"

#include <math.h>

#include "unit.h"

/* w = (nf pf)^2 / ((nf pf)^2 + (ng pg)^2): the balance heuristic nf pf / (nf pf + ng pg) would
 * give 2/3, 1/4 and 2/3 here */
START_TEST(test_mis_power_heuristic_squares_the_weighted_pdfs)
{
    ck_assert_near(integrator_power_heuristic(1, 2, 1, 1), 0.8, 1e-15);   /* 4 / (4 + 1) */
    ck_assert_near(integrator_power_heuristic(1, 1, 3, 1), 0.1, 1e-15);   /* 1 / (1 + 9) */
    ck_assert_near(integrator_power_heuristic(4, 0.5, 1, 1), 0.8, 1e-15); /* nf pf = 2 */
    ck_assert_near(integrator_power_heuristic(1, 1, 1, 1), 0.5, 1e-15);
}
END_TEST

/* the light sample's weight and the BRDF sample's weight of one direction add up to 1 (the
 * estimator stays unbiased), over pdfs of very different sizes (whose squares stay normal) */
START_TEST(test_mis_weights_of_the_two_strategies_sum_to_one)
{
    const double p[] = {1e-100, 1e-8, 0.01, 0.3, 1, 2.5, 70, 1e8, 1e100};
    const double n[] = {1, 4, 16};
    for (int i = 0; i < 9; i++)
        for (int j = 0; j < 9; j++)
            for (int k = 0; k < 3; k++) {
                double wl = integrator_power_heuristic(n[k], p[i], 1, p[j]);
                double wb = integrator_power_heuristic(1, p[j], n[k], p[i]);
                ck_require_msg(wl >= 0 && wl <= 1 && fabs(wl + wb - 1) < 1e-12,
                               "pl %g pb %g n %g: %g + %g", p[i], p[j], n[k], wl, wb);
            }
}
END_TEST

/* a strategy that cannot make the direction (pdf 0, or NaN) gets 0, the other all of it; a delta
 * (an infinite pdf) gets 1 without Inf / Inf */
START_TEST(test_mis_zero_nan_and_infinite_pdfs_are_guarded)
{
    ck_assert(integrator_power_heuristic(1, 0, 1, 1) == 0);
    ck_assert(integrator_power_heuristic(1, NAN, 1, 1) == 0);
    ck_assert(integrator_power_heuristic(1, 1, 1, 0) == 1);
    ck_assert(integrator_power_heuristic(1, INFINITY, 1, 1e300) == 1);
    ck_assert(integrator_power_heuristic(1, INFINITY, 1, INFINITY) == 1);
}
END_TEST

/* pdfs whose squares underflow or overflow the doubles (a sun's pdf of 1e200, a BRDF lobe's
 * 1e-200 far from its peak) still give weights in [0, 1] that sum to one, and the power
 * heuristic's value.  Catches (n p)^2 / ((n p)^2 + (n q)^2), which is 0 / 0 = NaN when both
 * squares underflow and Inf / Inf when both overflow: a NaN pixel. */
START_TEST(test_mis_weights_of_pdfs_whose_squares_underflow_or_overflow)
{
    ck_assert_near(integrator_power_heuristic(1, 1e-200, 1, 1e-200), 0.5, 1e-15);
    ck_assert_near(integrator_power_heuristic(1, 1e200, 1, 1e200), 0.5, 1e-15);
    ck_assert_near(integrator_power_heuristic(1, 2e-170, 1, 1e-170), 0.8, 1e-15);
    ck_assert_near(integrator_power_heuristic(1, 1e-300, 1, 1e-290), 1e-20, 1e-30);
    ck_assert(integrator_power_heuristic(1, 1e-300, 1, 1e300) == 0);
    const double p[] = {1e-320, 1e-300, 1e-200, 1e-160, 1, 1e160, 1e200, 1e300};
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 8; j++) {
            double wl = integrator_power_heuristic(1, p[i], 1, p[j]);
            double wb = integrator_power_heuristic(1, p[j], 1, p[i]);
            ck_require_msg(wl >= 0 && wl <= 1 && fabs(wl + wb - 1) < 1e-12,
                           "pl %g pb %g: %g + %g", p[i], p[j], wl, wb);
        }
}
END_TEST

static Suite *mis_suite(void)
{
    Suite *s = suite_create("mis");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_mis_power_heuristic_squares_the_weighted_pdfs);
    tcase_add_test(tc, test_mis_weights_of_the_two_strategies_sum_to_one);
    tcase_add_test(tc, test_mis_zero_nan_and_infinite_pdfs_are_guarded);
    tcase_add_test(tc, test_mis_weights_of_pdfs_whose_squares_underflow_or_overflow);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(mis_suite)
