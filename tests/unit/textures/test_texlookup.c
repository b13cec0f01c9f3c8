/* test_texlookup.c - wrap modes on indices near and far, the (s, t) convention, nearest and
 * bilinear lookups on tiny and thin images. */
#include "envtex/textures/texlookup.h"

#include <limits.h>

#include "unit.h"

static const wrap_mode all_modes[3] = {WRAP_REPEAT, WRAP_CLAMP, WRAP_MIRROR};

/* Independent definitions in 64-bit arithmetic, straight from the header's table. */
static long long ref_mod(long long a, long long m) { return ((a % m) + m) % m; }
static long long ref_wrap(long long i, long long n, wrap_mode w)
{
    if (w == WRAP_CLAMP) return i < 0 ? 0 : i >= n ? n - 1 : i;
    if (w == WRAP_REPEAT) return ref_mod(i, n);
    long long r = ref_mod(i, 2 * n);
    return r < n ? r : 2 * n - 1 - r;
}

/* A w x h image whose texel (i, j), j counted from the BOTTOM, holds (3 i + 5 j, i, j): integer
 * values, so float storage is exact, and a linear function of the texel centre. */
static image ramp_image(int w, int h)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, w, h, &err), 0);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) image_set(&im, i, h - 1 - j, rgb_make(3 * i + 5 * j, i, j));
    return im;
}

/* |a - b| <= tol channel by channel; tol = 0 asks for exact equality */
START_TEST(test_wrap_matches_its_definition_for_indices_near_and_far)
{
    const int ns[] = {1, 2, 3, 7, 256};
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < 5; k++) {
            int n = ns[k];
            for (int i = -3 * n - 5; i <= 3 * n + 5; i++)
                ck_assert_int_eq(texlookup_wrap(i, n, all_modes[m]), ref_wrap(i, n, all_modes[m]));
            const int far[] = {INT_MIN, INT_MIN + 1, -1000000007, 1000000007, INT_MAX - 1, INT_MAX};
            for (int f = 0; f < 6; f++)
                ck_assert_int_eq(texlookup_wrap(far[f], n, all_modes[m]),
                                 ref_wrap(far[f], n, all_modes[m]));
        }
}
END_TEST

START_TEST(test_wrap_modes_follow_the_documented_sequences)
{
    /* n = 3, i = -4 .. 6 */
    const int repeat[] = {2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0};
    const int clamp[] = {0, 0, 0, 0, 0, 1, 2, 2, 2, 2, 2};
    const int mirror[] = {2, 2, 1, 0, 0, 1, 2, 2, 1, 0, 0};
    for (int i = -4; i <= 6; i++) {
        ck_assert_int_eq(texlookup_wrap(i, 3, WRAP_REPEAT), repeat[i + 4]);
        ck_assert_int_eq(texlookup_wrap(i, 3, WRAP_CLAMP), clamp[i + 4]);
        ck_assert_int_eq(texlookup_wrap(i, 3, WRAP_MIRROR), mirror[i + 4]);
    }
}
END_TEST

START_TEST(test_mirror_wrap_does_not_overflow_for_huge_n)
{
    /* the period 2n does not fit an int */
    int n = INT_MAX - 2;
    ck_assert_int_eq(texlookup_wrap(INT_MIN, n, WRAP_MIRROR), ref_wrap(INT_MIN, n, WRAP_MIRROR));
    ck_assert_int_eq(texlookup_wrap(INT_MAX, n, WRAP_MIRROR), ref_wrap(INT_MAX, n, WRAP_MIRROR));
    ck_assert_int_eq(texlookup_wrap(-1, n, WRAP_MIRROR), 0);
    ck_assert_int_eq(texlookup_wrap(n, n, WRAP_MIRROR), n - 1);
}
END_TEST

START_TEST(test_wrap_floor_agrees_with_exact_integer_wrapping_far_beyond_int_range)
{
    const double xs[] = {
        0.5,        -0.5,        2.999,  -3.001,      1e9 * 7 + 0.25, -1e9 * 7 - 0.25,
        3e12 + 1.5, -3e12 - 1.5, 0x1p52, -0x1p52 - 2, 1e15 + 3};
    const int ns[] = {1, 3, 7, 1000};
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < 4; k++)
            for (int x = 0; x < 11; x++)
                ck_assert_int_eq(texlookup_wrap_floor(xs[x], ns[k], all_modes[m]),
                                 ref_wrap((long long)floor(xs[x]), ns[k], all_modes[m]));
    /* beyond long long: still an index in range */
    for (int m = 0; m < 3; m++) {
        int i = texlookup_wrap_floor(1e300, 7, all_modes[m]);
        ck_assert(i >= 0 && i < 7);
        i = texlookup_wrap_floor(-1e300, 7, all_modes[m]);
        ck_assert(i >= 0 && i < 7);
    }
}
END_TEST

START_TEST(test_wrap_floor_of_non_finite_values_is_a_valid_index)
{
    for (int m = 0; m < 3; m++) {
        ck_assert_int_eq(texlookup_wrap_floor(NAN, 5, all_modes[m]), 0);
        int i = texlookup_wrap_floor(INFINITY, 5, all_modes[m]);
        ck_assert(i >= 0 && i < 5);
    }
    ck_assert_int_eq(texlookup_wrap_floor(INFINITY, 5, WRAP_CLAMP), 4);
    ck_assert_int_eq(texlookup_wrap_floor(-INFINITY, 5, WRAP_CLAMP), 0);
}
END_TEST

START_TEST(test_wrap_names_parse_and_print_back)
{
    for (int m = 0; m < 3; m++) {
        wrap_mode w = WRAP_CLAMP == all_modes[m] ? WRAP_REPEAT : WRAP_CLAMP;
        ck_assert_int_eq(texlookup_wrap_parse(texlookup_wrap_name(all_modes[m]), &w), 0);
        ck_assert_int_eq(w, all_modes[m]);
    }
    wrap_mode w;
    ck_assert_int_eq(texlookup_wrap_parse("tile", &w), -1);
    ck_assert_int_eq(texlookup_wrap_parse("", &w), -1);
    ck_assert_int_eq(texlookup_wrap_parse(NULL, &w), -1);
    ck_assert_str_eq(texlookup_wrap_name(WRAP_MIRROR), "mirror");
}
END_TEST

START_TEST(test_st_origin_is_the_bottom_left_of_the_image)
{
    image im = ramp_image(3, 2); /* texel (i, j) holds (., i, j), j from the bottom */
    rgb bl = texlookup_nearest(&im, (uv2){0.1, 0.1}, WRAP_CLAMP);
    rgb tl = texlookup_nearest(&im, (uv2){0.1, 0.9}, WRAP_CLAMP);
    rgb tr = texlookup_nearest(&im, (uv2){0.9, 0.9}, WRAP_CLAMP);
    ck_rgb_near(bl, image_get(&im, 0, 1), 0); /* bottom-left = image row 1 (the last) */
    ck_rgb_near(tl, image_get(&im, 0, 0), 0); /* top-left = image row 0 */
    ck_rgb_near(tr, image_get(&im, 2, 0), 0);
    ck_assert(bl.b == 0 && tl.b == 1 && tr.g == 2);
    ck_rgb_near(texlookup_texel(&im, 0, 0, WRAP_CLAMP), bl, 0);
    image_free(&im);
}
END_TEST

START_TEST(test_nearest_picks_the_texel_whose_square_holds_st)
{
    image im = ramp_image(4, 3);
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 4; i++) {
            rgb want = rgb_make(3 * i + 5 * j, i, j);
            /* anywhere inside the texel's square, including its lower-left corner */
            ck_rgb_near(texlookup_nearest(&im, (uv2){(i + 0.5) / 4, (j + 0.5) / 3}, WRAP_REPEAT),
                        want, 0);
            ck_rgb_near(texlookup_nearest(&im, (uv2){(i + 0.01) / 4, (j + 0.99) / 3}, WRAP_REPEAT),
                        want, 0);
            ck_rgb_near(texlookup_nearest(&im, (uv2){i / 4.0, j / 3.0}, WRAP_REPEAT), want, 0);
        }
    /* s = 1: the next tile (repeat), the last column (clamp, mirror) */
    ck_assert(texlookup_nearest(&im, (uv2){1.0, 0.1}, WRAP_REPEAT).g == 0);
    ck_assert(texlookup_nearest(&im, (uv2){1.0, 0.1}, WRAP_CLAMP).g == 3);
    ck_assert(texlookup_nearest(&im, (uv2){1.0, 0.1}, WRAP_MIRROR).g == 3);
    image_free(&im);
}
END_TEST

START_TEST(test_one_by_one_image_reads_its_texel_everywhere)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 1, 1, &err), 0);
    image_set(&im, 0, 0, rgb_make(0.25, 0.5, 0.75));
    const double c[] = {0, 0.5, 1, -0.3, 1.7, -1e9, 1e9, 123.456};
    for (int m = 0; m < 3; m++)
        for (int a = 0; a < 8; a++)
            for (int b = 0; b < 8; b++) {
                uv2 st = {c[a], c[b]};
                ck_rgb_near(texlookup_nearest(&im, st, all_modes[m]), rgb_make(0.25, 0.5, 0.75), 0);
                ck_rgb_near(texlookup_bilinear(&im, st, all_modes[m]), rgb_make(0.25, 0.5, 0.75),
                            1e-15);
            }
    image_free(&im);
}
END_TEST

START_TEST(test_bilinear_returns_each_texel_at_its_centre)
{
    image im = ramp_image(5, 3);
    for (int m = 0; m < 3; m++)
        for (int j = 0; j < 3; j++)
            for (int i = 0; i < 5; i++)
                ck_rgb_near(
                    texlookup_bilinear(&im, (uv2){(i + 0.5) / 5, (j + 0.5) / 3}, all_modes[m]),
                    rgb_make(3 * i + 5 * j, i, j), 1e-12);
    image_free(&im);
}
END_TEST

START_TEST(test_bilinear_is_exact_on_a_linear_ramp_between_centres)
{
    image im = ramp_image(7, 4);
    for (int m = 0; m < 3; m++)
        for (int a = 0; a <= 40; a++)
            for (int b = 0; b <= 40; b++) {
                /* s, t between the first and last texel centres */
                double s = (0.5 + 6.0 * a / 40) / 7, t = (0.5 + 3.0 * b / 40) / 4;
                double x = s * 7 - 0.5, y = t * 4 - 0.5;
                ck_rgb_near(texlookup_bilinear(&im, (uv2){s, t}, all_modes[m]),
                            rgb_make(3 * x + 5 * y, x, y), 1e-12);
            }
    image_free(&im);
}
END_TEST

START_TEST(test_bilinear_borders_follow_the_wrap_mode)
{
    image im = ramp_image(4, 1); /* g = column index 0..3 */
    /* s = 0 is halfway between column 0 and column -1 */
    ck_assert_near(texlookup_bilinear(&im, (uv2){0.0, 0.5}, WRAP_REPEAT).g, 1.5,
                   1e-12); /* (0 + 3) / 2 */
    ck_assert_near(texlookup_bilinear(&im, (uv2){0.0, 0.5}, WRAP_CLAMP).g, 0.0, 1e-12);
    ck_assert_near(texlookup_bilinear(&im, (uv2){0.0, 0.5}, WRAP_MIRROR).g, 0.0, 1e-12);
    /* s = 1 + 3/16: x = s W - 1/2 = 4.25, a quarter of the way from column 4 to column 5 */
    ck_assert_near(texlookup_bilinear(&im, (uv2){1.1875, 0.5}, WRAP_REPEAT).g, 0.75 * 0 + 0.25 * 1,
                   1e-12);
    ck_assert_near(texlookup_bilinear(&im, (uv2){1.1875, 0.5}, WRAP_CLAMP).g, 3.0, 1e-12);
    ck_assert_near(texlookup_bilinear(&im, (uv2){1.1875, 0.5}, WRAP_MIRROR).g, 0.75 * 3 + 0.25 * 2,
                   1e-12);
    /* the outer half texel is flat with clamp */
    ck_assert_near(texlookup_bilinear(&im, (uv2){0.01, 0.5}, WRAP_CLAMP).g, 0.0, 1e-12);
    image_free(&im);
}
END_TEST

START_TEST(test_thin_images_interpolate_only_along_their_length)
{
    image col = ramp_image(1, 6), row = ramp_image(6, 1);
    for (int m = 0; m < 3; m++)
        for (int a = 0; a <= 20; a++) {
            double u = (0.5 + 5.0 * a / 20) / 6, x = u * 6 - 0.5;
            ck_rgb_near(texlookup_bilinear(&col, (uv2){0.37, u}, all_modes[m]),
                        rgb_make(5 * x, 0, x), 1e-12);
            ck_rgb_near(texlookup_bilinear(&row, (uv2){u, -4.2}, all_modes[m]),
                        rgb_make(3 * x, x, 0), 1e-12);
        }
    image_free(&col);
    image_free(&row);
}
END_TEST

START_TEST(test_far_and_negative_coordinates_wrap_like_near_ones)
{
    image im = ramp_image(5, 3);
    uv2 near = {0.3, 0.45};
    rgb want = texlookup_bilinear(&im, near, WRAP_REPEAT);
    /* repeat: whole tiles away; 1e9 carries a rounding error of about 1e-7 in s */
    ck_rgb_near(texlookup_bilinear(&im, (uv2){0.3 - 3, 0.45 + 2}, WRAP_REPEAT), want, 1e-12);
    ck_rgb_near(texlookup_bilinear(&im, (uv2){0.3 + 1e9, 0.45 - 1e9}, WRAP_REPEAT), want, 1e-5);
    ck_rgb_near(texlookup_nearest(&im, (uv2){0.3 - 1e9, 0.45 + 1e9}, WRAP_REPEAT),
                texlookup_nearest(&im, near, WRAP_REPEAT), 0);
    /* mirror: s -> -s and s -> 2 - s reflect; period 2 */
    rgb m = texlookup_bilinear(&im, near, WRAP_MIRROR);
    ck_rgb_near(texlookup_bilinear(&im, (uv2){-0.3, -0.45}, WRAP_MIRROR), m, 1e-12);
    ck_rgb_near(texlookup_bilinear(&im, (uv2){2 - 0.3, 2 + 0.45}, WRAP_MIRROR), m, 1e-12);
    ck_rgb_near(texlookup_bilinear(&im, (uv2){0.3 - 2e9, 0.45 + 2e9}, WRAP_MIRROR), m, 1e-5);
    /* clamp: the border texels, however far */
    ck_rgb_near(texlookup_bilinear(&im, (uv2){-1e9, 1e9}, WRAP_CLAMP), rgb_make(0 + 5 * 2, 0, 2),
                0);
    ck_rgb_near(texlookup_bilinear(&im, (uv2){1e9, -1e9}, WRAP_CLAMP), rgb_make(3 * 4, 4, 0), 0);
    image_free(&im);
}
END_TEST

START_TEST(test_non_finite_coordinates_give_a_finite_colour)
{
    image im = ramp_image(5, 3);
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < 3; k++) {
            ck_assert(rgb_is_finite(texlookup_bilinear(&im, (uv2){bad[k], 0.5}, all_modes[m])));
            ck_assert(rgb_is_finite(texlookup_bilinear(&im, (uv2){0.5, bad[k]}, all_modes[m])));
            ck_assert(rgb_is_finite(texlookup_nearest(&im, (uv2){bad[k], bad[k]}, all_modes[m])));
        }
    image_free(&im);
}
END_TEST

Suite *texlookup_suite(void)
{
    Suite *s = suite_create("texlookup");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_wrap_matches_its_definition_for_indices_near_and_far);
    tcase_add_test(tc, test_wrap_modes_follow_the_documented_sequences);
    tcase_add_test(tc, test_mirror_wrap_does_not_overflow_for_huge_n);
    tcase_add_test(tc, test_wrap_floor_agrees_with_exact_integer_wrapping_far_beyond_int_range);
    tcase_add_test(tc, test_wrap_floor_of_non_finite_values_is_a_valid_index);
    tcase_add_test(tc, test_wrap_names_parse_and_print_back);
    tcase_add_test(tc, test_st_origin_is_the_bottom_left_of_the_image);
    tcase_add_test(tc, test_nearest_picks_the_texel_whose_square_holds_st);
    tcase_add_test(tc, test_one_by_one_image_reads_its_texel_everywhere);
    tcase_add_test(tc, test_bilinear_returns_each_texel_at_its_centre);
    tcase_add_test(tc, test_bilinear_is_exact_on_a_linear_ramp_between_centres);
    tcase_add_test(tc, test_bilinear_borders_follow_the_wrap_mode);
    tcase_add_test(tc, test_thin_images_interpolate_only_along_their_length);
    tcase_add_test(tc, test_far_and_negative_coordinates_wrap_like_near_ones);
    tcase_add_test(tc, test_non_finite_coordinates_give_a_finite_colour);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(texlookup_suite)
