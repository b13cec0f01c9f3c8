/* test_stratified.c - stratified light samples alone (include/envtex/integrators/integrator.h:
 * integrator_strata, integrator_stratum), the step `stratified` of tests/steps: sample j of an
 * m x m grid lands in cell (j mod m, j / m), jittered inside it; the m x m samples fill every
 * cell once; samples past m^2 keep their numbers. */
#include "envtex/integrators/integrator.h"

#include <math.h>

#include "unit.h"

START_TEST(test_stratified_sample_j_lands_in_cell_j_mod_m_j_div_m)
{
    double a = 0.5, b = 0.25;
    ck_assert(integrator_stratum(3, 2, &a, &b)); /* cell (1, 1) */
    ck_assert_near(a, 0.75, 1e-15);
    ck_assert_near(b, 0.625, 1e-15);
    a = 0.5, b = 0.25;
    ck_assert(integrator_stratum(2, 2, &a, &b)); /* cell (0, 1) */
    ck_assert_near(a, 0.25, 1e-15);
    ck_assert_near(b, 0.625, 1e-15);
    a = 0.1, b = 0.9;
    ck_assert(integrator_stratum(5, 3, &a, &b)); /* cell (2, 1) of 3 x 3 */
    ck_assert_near(a, 2.1 / 3, 1e-15);
    ck_assert_near(b, 1.9 / 3, 1e-15);
}
END_TEST

/* the m^2 samples of one pixel fill the grid: each cell once, the jitter inside its own cell */
START_TEST(test_stratified_every_cell_of_the_grid_gets_one_sample)
{
    for (int m = 1; m <= 8; m++) {
        int count[64] = {0};
        for (int j = 0; j < m * m; j++) {
            double a = 0.999 * ((j * 7) % 10) / 10 + 1e-3, b = 0.999 * ((j * 3) % 10) / 10 + 1e-3;
            ck_require(integrator_stratum(j, m, &a, &b));
            ck_require_msg(a > 0 && a < 1 && b > 0 && b < 1, "m %d j %d: (%g, %g)", m, j, a, b);
            count[(int)floor(b * m) * m + (int)floor(a * m)]++;
        }
        for (int c = 0; c < m * m; c++)
            ck_require_msg(count[c] == 1, "m %d: cell %d has %d", m, c, count[c]);
    }
}
END_TEST

/* n samples use the largest m with m^2 <= n; the samples left over are not moved */
START_TEST(test_stratified_grid_side_and_the_samples_left_over)
{
    ck_assert_int_eq(integrator_strata(16, 1), 4);
    ck_assert_int_eq(integrator_strata(15, 1), 3);
    ck_assert_int_eq(integrator_strata(1, 1), 1);
    ck_assert_int_eq(integrator_strata(16, 0), 0);
    double a = 0.999, b = 0.999;
    ck_assert(!integrator_stratum(4, 2, &a, &b)); /* the fifth of 5: left over */
    ck_assert(a == 0.999 && b == 0.999);
    ck_assert(!integrator_stratum(0, 0, &a, &b)); /* not stratifying */
    ck_assert(a == 0.999 && b == 0.999);
}
END_TEST

static Suite *stratified_suite(void)
{
    Suite *s = suite_create("stratified");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_stratified_sample_j_lands_in_cell_j_mod_m_j_div_m);
    tcase_add_test(tc, test_stratified_every_cell_of_the_grid_gets_one_sample);
    tcase_add_test(tc, test_stratified_grid_side_and_the_samples_left_over);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(stratified_suite)
