/* test_compare.c - image metrics, threshold verdicts and the difference picture. */
#include <math.h>
#include <string.h>

#include "envtex/render/compare.h"
#include "envtex/io/tonemap.h"
#include "unit.h"

static void grey(image *im, int w, int h, float v)
{
    error err = {0};
    ck_assert_int_eq(image_alloc(im, w, h, &err), 0);
    for (int i = 0; i < 3 * w * h; i++) im->px[i] = v;
}

START_TEST(test_equal_images_have_zero_error_and_infinite_psnr)
{
    image a = {0}, b = {0};
    grey(&a, 4, 3, 0.5f);
    grey(&b, 4, 3, 0.5f);
    compare_result m;
    error err = {0};
    ck_assert_int_eq(compare_metrics(&a, &b, &m, &err), 0);
    ck_assert(m.rmse == 0.0 && m.relmse == 0.0 && m.max_abs == 0.0);
    ck_assert(isinf(m.psnr) && m.psnr > 0);
    ck_assert_int_eq(m.pixels, 12);
    image_free(&a);
    image_free(&b);
}
END_TEST

START_TEST(test_metrics_of_one_changed_channel_are_the_hand_computed_ones)
{
    image a = {0}, ref = {0};
    grey(&a, 2, 2, 0.0f);
    grey(&ref, 2, 2, 0.0f);
    image_px(&ref, 1, 1)[1] = 0.5f;
    image_px(&a, 1, 1)[1] = 0.6f; /* one of 12 values off by 0.1 */
    compare_result m;
    error err = {0};
    ck_assert_int_eq(compare_metrics(&a, &ref, &m, &err), 0);
    ck_assert_near(m.rmse, sqrt(0.01 / 12.0), 1e-7);
    ck_assert_near(m.psnr, -10.0 * log10(0.01 / 12.0), 1e-4);
    ck_assert_near(m.relmse, 0.01 / (0.25 + COMPARE_RELMSE_EPSILON) / 12.0, 1e-7);
    ck_assert_near(m.max_abs, 0.1, 1e-6);
    ck_assert_int_eq(m.max_x, 1);
    ck_assert_int_eq(m.max_y, 1);
    image_free(&a);
    image_free(&ref);
}
END_TEST

START_TEST(test_relmse_epsilon_guards_black_reference_pixels)
{
    image a = {0}, ref = {0};
    grey(&a, 1, 1, 0.1f);
    grey(&ref, 1, 1, 0.0f); /* ref^2 = 0: without the epsilon this divides by zero */
    compare_result m;
    error err = {0};
    ck_assert_int_eq(compare_metrics(&a, &ref, &m, &err), 0);
    ck_assert(isfinite(m.relmse));
    ck_assert_near(m.relmse, 0.01 / COMPARE_RELMSE_EPSILON, 1e-6);
    image_free(&a);
    image_free(&ref);
}
END_TEST

/* relmse_trim against a brute force: every pixel's term, sorted, the largest 0.1% (rounded
 * down, of the finite pixels) left out.  Fireflies at the first and last pixels and between,
 * growing along the scan, shrinking, and mixed (each order exercises the kept list differently);
 * NaN pixels, so that the count comes from the pixels used. */
START_TEST(test_relmse_trim_leaves_out_the_largest_tenth_of_a_percent)
{
    enum { W = 81, H = 50 }; /* 4050 pixels, 1100 NaN: 2950 used, 2 left out (not 4) */
    static double term[W * H];
    for (int order = 0; order < 3; order++) {
        image a = {0}, ref = {0};
        grey(&a, W, H, 0.0f);
        grey(&ref, W, H, 0.0f);
        int n = 0;
        unsigned s = 12345;
        for (int i = 0; i < W * H; i++) {
            float *p = a.px + 3 * i, *q = ref.px + 3 * i;
            int nan_px = i % W >= 59; /* 22 a row */
            int firefly = !nan_px && (i == 0 || i == W * H - 23 || i == 1777 || i % 397 == 5);
            float size = order == 0   ? (float)(i + 1) / 10
                         : order == 1 ? (float)(W * H - i) / 10
                                      : (float)(i % 7 + 1) * 100;
            double t = 0;
            for (int k = 0; k < 3; k++) {
                s = s * 1103515245u + 12345u;
                q[k] = (float)((s >> 8) % 1000) / 500.0f;        /* 0 .. 2 */
                p[k] = q[k] + (float)((s >> 4) % 100) / 1000.0f; /* + 0 .. 0.1 */
                if (firefly) { /* on a reference of 1: its term grows with its size */
                    q[k] = 1.0f;
                    p[k] = 1.0f + size;
                }
                double d = (double)p[k] - (double)q[k];
                t += d * d / ((double)q[k] * q[k] + COMPARE_RELMSE_EPSILON);
            }
            if (nan_px)
                p[1] = NAN;
            else
                term[n++] = t;
        }
        ck_assert_int_eq(n, 2950);
        for (int i = 1; i < n; i++) /* insertion sort, descending */
            for (int j = i; j > 0 && term[j] > term[j - 1]; j--) {
                double x = term[j];
                term[j] = term[j - 1];
                term[j - 1] = x;
            }
        double all = 0, rest = 0;
        for (int i = 0; i < n; i++) {
            all += term[i];
            if (i >= 2) rest += term[i];
        }
        compare_result m;
        error err = {0};
        ck_assert_int_eq(compare_metrics(&a, &ref, &m, &err), 0);
        ck_assert_int_eq(m.pixels, 2950);
        ck_assert_double_eq_tol(m.relmse, all / (3.0 * n), 1e-12 * m.relmse);
        ck_assert_msg(fabs(m.relmse_trim - rest / (3.0 * (n - 2))) <= 1e-9 * m.relmse_trim,
                      "order %d: relmse_trim %.12g, want %.12g", order, m.relmse_trim,
                      rest / (3.0 * (n - 2)));
        ck_assert(m.relmse_trim < m.relmse);
        image_free(&a);
        image_free(&ref);
    }
}
END_TEST

/* Under 1000 pixels nothing is left out: relmse_trim is relmse. */
START_TEST(test_relmse_trim_of_a_small_image_is_relmse)
{
    image a = {0}, ref = {0};
    grey(&a, 31, 32, 0.5f); /* 992 pixels */
    grey(&ref, 31, 32, 0.25f);
    image_px(&a, 3, 4)[0] = 1000.0f;
    compare_result m;
    error err = {0};
    ck_assert_int_eq(compare_metrics(&a, &ref, &m, &err), 0);
    ck_assert(m.relmse_trim == m.relmse && m.relmse > 1000);
    image_free(&a);
    image_free(&ref);
}
END_TEST

START_TEST(test_nonfinite_pixels_are_counted_and_left_out)
{
    image a = {0}, ref = {0};
    grey(&a, 3, 1, 0.25f);
    grey(&ref, 3, 1, 0.25f);
    a.px[0] = NAN;
    ref.px[8] = INFINITY;
    compare_result m;
    error err = {0};
    ck_assert_int_eq(compare_metrics(&a, &ref, &m, &err), 0);
    ck_assert_int_eq(m.nonfinite, 1);
    ck_assert_int_eq(m.ref_nonfinite, 1);
    ck_assert_int_eq(m.pixels, 1);
    ck_assert(m.rmse == 0.0);
    a.px[3] = a.px[6] = NAN; /* nothing left to compare: the metrics are undefined */
    ck_assert_int_eq(compare_metrics(&a, &ref, &m, &err), 0);
    ck_assert(isnan(m.rmse) && isnan(m.psnr));
    image_free(&a);
    image_free(&ref);
}
END_TEST

START_TEST(test_different_sizes_are_an_error_and_a_failed_verdict)
{
    image a = {0}, ref = {0}, d = {0};
    grey(&a, 2, 2, 0.0f);
    grey(&ref, 2, 3, 0.0f);
    compare_result m;
    error err = {0};
    ck_assert_int_eq(compare_metrics(&a, &ref, &m, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "sizes differ"));
    compare_thresholds_params p = compare_thresholds_defaults();
    compare_verdict v;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), -1);
    ck_assert_int_eq(v.pass, 0);
    ck_assert_ptr_nonnull(strstr(v.why, "sizes differ"));
    ck_assert_int_eq(compare_diff_image(&a, &ref, &d, &err), -1);
    ck_assert_ptr_null(d.px);
    image_free(&a);
    image_free(&ref);
}
END_TEST

START_TEST(test_threshold_verdicts_follow_the_percent_hard_and_nan_rules)
{
    image a = {0}, ref = {0};
    grey(&a, 10, 10, 0.5f);
    grey(&ref, 10, 10, 0.5f);
    image_px(&a, 3, 4)[2] = 0.51f; /* 1 pixel of 100 off by 0.01 */
    compare_thresholds_params p = compare_thresholds_defaults();
    compare_verdict v;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), -1); /* 1% > 0.02% */
    ck_assert_int_eq(v.failed, 1);
    ck_assert_near(v.failed_percent, 1.0, 1e-12);
    ck_assert_int_eq(v.max_x, 3);
    ck_assert_int_eq(v.max_y, 4);
    p.fail_percent = 2.0;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), 0);
    ck_assert_int_eq(v.pass, 1);
    p.hard_thresh = 0.005; /* but no pixel may differ more than 0.005 */
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), -1);
    ck_assert_int_eq(v.hard_failed, 1);
    p.hard_thresh = INFINITY;
    image_px(&a, 0, 0)[0] = NAN;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), -1);
    ck_assert_int_eq(v.nonfinite, 1);
    ck_assert_ptr_nonnull(strstr(v.why, "NaN"));
    ck_assert_ptr_nonnull(strstr(v.why, "at (3, 4)")); /* where the largest difference is */
    /* no finite pixel pair at all: no place to name (it once said "at (-1, -1)") */
    for (int y = 0; y < 10; y++)
        for (int x = 0; x < 10; x++) image_px(&a, x, y)[1] = NAN;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), -1);
    ck_assert_int_eq(v.nonfinite, 100);
    ck_assert_int_eq(v.max_x, -1);
    ck_assert_msg(strstr(v.why, "(-1") == NULL, "why: %s", v.why);
    image_free(&a);
    image_free(&ref);
}
END_TEST

/* compare.h: a pixel's difference is its LARGEST channel |a - ref|, and a pixel fails only if
 * that EXCEEDS fail_thresh (or hard_thresh): a difference of exactly the threshold passes.
 * Differences of 0.25 and 0.125 are exact in float.  Catches the last channel taken for the
 * pixel's difference and >= in place of > for either threshold. */
START_TEST(test_threshold_uses_the_largest_channel_and_exactly_the_threshold_passes)
{
    image a = {0}, ref = {0};
    grey(&a, 10, 10, 0.5f);
    grey(&ref, 10, 10, 0.5f);
    image_px(&a, 2, 3)[0] = 0.75f;  /* 0.25 in the first channel */
    image_px(&a, 2, 3)[1] = 0.625f; /* 0.125 in the second, 0 in the last */
    compare_thresholds_params p = compare_thresholds_defaults();
    p.fail_thresh = 0.25;
    p.fail_percent = 0.0;
    p.hard_thresh = 0.25;
    compare_verdict v;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), 0);
    ck_assert_int_eq(v.failed, 0);
    ck_assert_int_eq(v.hard_failed, 0);
    ck_assert_double_eq(v.max_diff, 0.25);
    ck_assert_int_eq(v.max_x, 2);
    ck_assert_int_eq(v.max_y, 3);
    p.fail_thresh = 0.2; /* now 0.25 is more than either limit */
    p.hard_thresh = 0.2;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), -1);
    ck_assert_int_eq(v.failed, 1);
    ck_assert_int_eq(v.hard_failed, 1);
    image_free(&a);
    image_free(&ref);
}
END_TEST

/* A NaN or Inf in the reference fails the comparison as one in the image under test does
 * (compare.h: "any pixel of either image").  Catches only `a` being checked. */
START_TEST(test_threshold_fails_on_a_nonfinite_reference_pixel)
{
    image a = {0}, ref = {0};
    grey(&a, 4, 4, 0.5f);
    grey(&ref, 4, 4, 0.5f);
    image_px(&ref, 1, 2)[2] = INFINITY;
    compare_thresholds_params p = compare_thresholds_defaults();
    compare_verdict v;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), -1);
    ck_assert_int_eq(v.nonfinite, 1);
    ck_assert_int_eq(v.pass, 0);
    image_free(&a);
    image_free(&ref);
}
END_TEST

START_TEST(test_relative_mode_forgives_bright_pixels_only)
{
    image a = {0}, ref = {0};
    grey(&a, 2, 1, 10.0f);
    grey(&ref, 2, 1, 10.0f);
    image_px(&a, 0, 0)[0] = 10.05f; /* 0.5% of a bright value */
    compare_thresholds_params p = compare_thresholds_defaults();
    p.fail_percent = 0.0;
    p.fail_relative = 0.01;
    compare_verdict v;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), 0);
    /* the relative limit is fail_relative times the MEAN of |a| and |ref|: 0.15 on 10 is over
     * 0.01 * 10.075 (and would pass against their sum, 0.01 * 20.15) */
    image_px(&a, 0, 0)[0] = 10.15f;
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), -1);
    image_px(&a, 0, 0)[0] = 10.05f;
    image_px(&ref, 1, 0)[1] = 0.1f;
    image_px(&a, 1, 0)[1] = 0.15f; /* 0.05 on a dim value: 40% relative */
    ck_assert_int_eq(compare_thresholds(&a, &ref, &p, &v), -1);
    ck_assert_int_eq(v.failed, 1);
    image_free(&a);
    image_free(&ref);
}
END_TEST

START_TEST(test_difference_image_uses_one_colour_per_decade)
{
    image a = {0}, ref = {0}, d = {0};
    grey(&ref, 6, 1, 0.5f);
    grey(&a, 6, 1, 0.5f);
    float diffs[5] = {0.0f, 1e-3f, 1e-2f, 1e-1f, 2.0f};
    for (int x = 0; x < 5; x++) image_px(&a, x, 0)[1] += diffs[x];
    image_px(&a, 5, 0)[0] = NAN;
    error err = {0};
    ck_assert_int_eq(compare_diff_image(&a, &ref, &d, &err), 0);
    static const uint8_t want[6][3] = {{0, 0, 0},     {0, 0, 255}, {0, 255, 0},
                                       {255, 255, 0}, {255, 0, 0}, {255, 0, 255}};
    tonemap_params tm = tonemap_defaults(); /* what imageio_write uses for a .png */
    for (int x = 0; x < 6; x++) {
        uint8_t o[3];
        tonemap_pixel(&tm, image_get(&d, x, 0), o);
        for (int k = 0; k < 3; k++)
            ck_assert_msg(abs(o[k] - want[x][k]) <= 1, "pixel %d channel %d: %d, want %d", x, k,
                          o[k], want[x][k]);
    }
    image_free(&a);
    image_free(&ref);
    image_free(&d);
}
END_TEST

Suite *compare_suite(void)
{
    Suite *s = suite_create("compare");
    TCase *tc = tcase_create("compare");
    tcase_add_test(tc, test_equal_images_have_zero_error_and_infinite_psnr);
    tcase_add_test(tc, test_metrics_of_one_changed_channel_are_the_hand_computed_ones);
    tcase_add_test(tc, test_relmse_epsilon_guards_black_reference_pixels);
    tcase_add_test(tc, test_relmse_trim_leaves_out_the_largest_tenth_of_a_percent);
    tcase_add_test(tc, test_relmse_trim_of_a_small_image_is_relmse);
    tcase_add_test(tc, test_nonfinite_pixels_are_counted_and_left_out);
    tcase_add_test(tc, test_different_sizes_are_an_error_and_a_failed_verdict);
    tcase_add_test(tc, test_threshold_verdicts_follow_the_percent_hard_and_nan_rules);
    tcase_add_test(tc, test_threshold_uses_the_largest_channel_and_exactly_the_threshold_passes);
    tcase_add_test(tc, test_threshold_fails_on_a_nonfinite_reference_pixel);
    tcase_add_test(tc, test_relative_mode_forgives_bright_pixels_only);
    tcase_add_test(tc, test_difference_image_uses_one_colour_per_decade);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(compare_suite)
