/* test_tonemap.c - tone mapping curves, the sRGB transfer function, NaN / Inf handling. */
#include <math.h>
#include <string.h>

#include "envtex/io/tonemap.h"
#include "unit.h"

static void px(const tonemap_params *tm, double r, double g, double b, uint8_t out[3])
{
    tonemap_pixel(tm, rgb_make(r, g, b), out);
}

START_TEST(test_srgb_curve_matches_iec_61966_values)
{
    ck_assert_near(tonemap_srgb_encode(0.0), 0.0, 1e-12);
    ck_assert_near(tonemap_srgb_encode(1.0), 1.0, 1e-12);
    ck_assert_near(tonemap_srgb_encode(0.0031308), 0.04045, 1e-5); /* the two pieces meet */
    ck_assert_near(tonemap_srgb_encode(0.001), 0.01292, 1e-12);    /* linear piece: 12.92 l */
    ck_assert_near(tonemap_srgb_decode(0.5), 0.214041140, 1e-8);
    ck_assert_near(tonemap_srgb_decode(0.04045), 0.04045 / 12.92, 1e-12);
    for (int i = 0; i <= 100; i++) {
        double l = i / 100.0;
        ck_assert_near(tonemap_srgb_decode(tonemap_srgb_encode(l)), l, 1e-12);
    }
}
END_TEST

START_TEST(test_clamp_operator_with_srgb_and_gamma)
{
    tonemap_params tm = tonemap_defaults();
    ck_assert_int_eq(tm.op, TONEMAP_CLAMP);
    ck_assert(tm.exposure == 0.0 && tm.gamma == 0.0);
    uint8_t o[3];
    px(&tm, 0.0, 1.0, 7.0, o);
    ck_assert(o[0] == 0 && o[1] == 255 && o[2] == 255);
    px(&tm, 0.2, 0.001, -3.0, o); /* sRGB(0.2) = 0.48453 -> 123.56 rounds to 124 */
    ck_assert_int_eq(o[0], 124);
    ck_assert_int_eq(o[1], 3); /* 0.01292 * 255 = 3.29 */
    ck_assert_int_eq(o[2], 0);
    tm.gamma = 2.2;
    px(&tm, 0.5, 0.5, 0.5, o); /* 0.5^(1/2.2) = 0.72974 -> 186.08 */
    ck_assert_int_eq(o[0], 186);
}
END_TEST

START_TEST(test_reinhard_and_aces_curves_give_their_formula_values)
{
    tonemap_params tm = tonemap_defaults();
    tm.gamma = 1.0; /* no encoding: see the operator alone */
    uint8_t o[3];
    tm.op = TONEMAP_REINHARD;
    px(&tm, 3.0, 1.0, 1e9, o); /* 3/4 -> 191.25; 1/2 -> 128; -> 1 */
    ck_assert_int_eq(o[0], 191);
    ck_assert_int_eq(o[1], 128);
    ck_assert_int_eq(o[2], 255);
    px(&tm, -1.0, -0.5, 0.0, o); /* 1 + x = 0 at x = -1: negatives must be 0 before dividing */
    ck_assert(o[0] == 0 && o[1] == 0 && o[2] == 0);
    tm.op = TONEMAP_ACES;
    px(&tm, 1.0, 0.1, 100.0, o);
    ck_assert_int_eq(o[0], 205); /* 2.54 / 3.16 = 0.80380 -> 204.97 */
    /* 0.1 (0.251 + 0.03) / (0.1 (0.243 + 0.59) + 0.14) = 0.0281 / 0.2233 = 0.12584 -> 32.09 */
    ck_assert_int_eq(o[1], 32);
    ck_assert_int_eq(o[2], 255); /* the fit tends to 2.51 / 2.43 > 1: clamped */
}
END_TEST

START_TEST(test_exposure_multiplies_by_two_to_the_ev)
{
    tonemap_params tm = tonemap_defaults();
    tm.gamma = 1.0;
    uint8_t o[3];
    tm.exposure = 2.0;
    px(&tm, 0.25, 0.125, 0.0, o); /* x 4 */
    ck_assert_int_eq(o[0], 255);
    ck_assert_int_eq(o[1], 128);
    tm.exposure = -1.0;
    px(&tm, 1.0, 0.0, 0.0, o); /* x 1/2 */
    ck_assert_int_eq(o[0], 128);
    /* the image path scales by 2^EV too (it computes its own scale; with EV = 0 only, e^EV would
     * pass): 0.75 x 2^-1.5 = 0.265 -> 68, where e^-1.5 would give 0.167 -> 43 */
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 1, 1, &err), 0);
    im.px[0] = im.px[1] = im.px[2] = 0.75f;
    tm.exposure = -1.5;
    uint8_t out[3];
    tonemap_image(&tm, &im, out);
    px(&tm, 0.75, 0.75, 0.75, o);
    ck_assert_int_eq(o[0], 68);
    ck_assert(out[0] == o[0] && out[1] == o[1] && out[2] == o[2]);
    image_free(&im);
}
END_TEST

START_TEST(test_nan_is_black_and_inf_is_white_and_both_are_counted_per_pixel)
{
    tonemap_params tm = tonemap_defaults();
    for (int op = TONEMAP_CLAMP; op <= TONEMAP_ACES; op++) {
        tm.op = (tonemap_op)op;
        uint8_t o[3];
        px(&tm, NAN, INFINITY, -INFINITY, o);
        ck_assert(o[0] == 0 && o[1] == 255 && o[2] == 0);
    }
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 3, 1, &err), 0);
    im.px[0] = NAN;
    im.px[1] = NAN; /* two bad channels in one pixel count once */
    im.px[5] = INFINITY;
    im.px[6] = 0.5f;
    uint8_t out[9];
    memset(out, 7, sizeof out);
    ck_assert_int_eq(tonemap_image(&tm, &im, out), 2);
    ck_assert(out[0] == 0 && out[1] == 0 && out[5] == 255);
    uint8_t one[3];
    tonemap_pixel(&tm, rgb_make(0.5, 0, 0), one);
    ck_assert_int_eq(out[6], one[0]); /* the image path agrees with the pixel path */
    image_free(&im);
}
END_TEST

/* Extreme exposures and values keep the contract for every operator: anything over white is
 * white, +Inf is white and -Inf black at any exposure.  Catches ACES's x^2 overflowing (x above
 * 1e154: Inf / Inf = NaN, cast to a byte: undefined behaviour, 0 on x86) and +Inf scaled by an
 * exposure that underflowed 2^EV to 0 (Inf * 0 = NaN: black); both found by an audit. */
START_TEST(test_extreme_exposures_and_values_keep_white_white)
{
    tonemap_params tm = tonemap_defaults();
    for (int op = TONEMAP_CLAMP; op <= TONEMAP_ACES; op++) {
        tm.op = (tonemap_op)op;
        uint8_t o[3];
        tm.exposure = 0;
        px(&tm, 1e200, 1e300, 8.0, o);
        ck_assert_msg(o[0] == 255 && o[1] == 255, "op %d: %d %d", op, o[0], o[1]);
        tm.exposure = 1000; /* 2^1000 = 1e301: 1 x that is finite, 1e10 x that is Inf */
        px(&tm, 1.0, 1e10, 1e-300, o);
        ck_assert_msg(o[0] == 255 && o[1] == 255 && o[2] > 0, "op %d: %d %d %d", op, o[0], o[1],
                      o[2]);
        tm.exposure = -2000; /* 2^-2000 = 0 */
        px(&tm, INFINITY, 1e38, -INFINITY, o);
        ck_assert_msg(o[0] == 255 && o[1] == 0 && o[2] == 0, "op %d: %d %d %d", op, o[0], o[1],
                      o[2]);
    }
    tm.op = TONEMAP_ACES; /* the curve at the guard's edge: 7.24 -> 1.0000, 8 -> 1.003 */
    tm.exposure = 0;
    tm.gamma = 1.0;
    uint8_t o[3];
    px(&tm, 7.0, 7.999, 8.0, o);
    ck_assert(o[0] == 255 && o[1] == 255 && o[2] == 255);
    px(&tm, 5.0, 6.0, 0.5, o); /* 0.98528, 0.99320 -> 251, 253 (the guard is not earlier) */
    ck_assert_int_eq(o[0], 251);
    ck_assert_int_eq(o[1], 253);
}
END_TEST

START_TEST(test_operator_names_parse_and_unknown_ones_fail)
{
    tonemap_op op = TONEMAP_CLAMP;
    ck_assert_int_eq(tonemap_op_parse("aces", &op), 0);
    ck_assert_int_eq(op, TONEMAP_ACES);
    ck_assert_int_eq(tonemap_op_parse("reinhard", &op), 0);
    ck_assert_int_eq(op, TONEMAP_REINHARD);
    ck_assert_int_eq(tonemap_op_parse("clamp", &op), 0);
    ck_assert_int_eq(op, TONEMAP_CLAMP);
    ck_assert_int_eq(tonemap_op_parse("filmic", &op), -1);
    ck_assert_int_eq(op, TONEMAP_CLAMP); /* unchanged on failure */
}
END_TEST

Suite *tonemap_suite(void)
{
    Suite *s = suite_create("tonemap");
    TCase *tc = tcase_create("tonemap");
    tcase_add_test(tc, test_srgb_curve_matches_iec_61966_values);
    tcase_add_test(tc, test_clamp_operator_with_srgb_and_gamma);
    tcase_add_test(tc, test_reinhard_and_aces_curves_give_their_formula_values);
    tcase_add_test(tc, test_exposure_multiplies_by_two_to_the_ev);
    tcase_add_test(tc, test_nan_is_black_and_inf_is_white_and_both_are_counted_per_pixel);
    tcase_add_test(tc, test_extreme_exposures_and_values_keep_white_white);
    tcase_add_test(tc, test_operator_names_parse_and_unknown_ones_fail);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(tonemap_suite)
