/* test_image.c - image sizes are checked before anything is allocated (hostile headers),
 * allocation is zero filled, and freeing is idempotent. */
#include "envtex/core/image.h"

#include <string.h>

#include "unit.h"

START_TEST(test_image_check_size_rejects_empty_and_negative_sizes)
{
    error err = {0};
    ck_assert_int_eq(image_check_size(0, 1, "a.exr", &err), -1);
    ck_assert_str_eq(err.file, "a.exr");
    ck_assert_int_eq(image_check_size(1, 0, NULL, &err), -1);
    ck_assert_int_eq(image_check_size(-1, 5, NULL, &err), -1);
    ck_assert_int_eq(image_check_size(5, -1, NULL, &err), -1);
    ck_assert_int_eq(image_check_size(-2147483648L, -2147483648L, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "-2147483648"));
}
END_TEST

START_TEST(test_image_check_size_rejects_a_side_over_32768)
{
    error err = {0};
    ck_assert_int_eq(image_check_size(IMAGE_MAX_SIDE + 1, 1, "big.hdr", &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "32769"));
    ck_assert_int_eq(image_check_size(1, IMAGE_MAX_SIDE + 1, NULL, &err), -1);
    /* a hostile header: sizes whose product overflows 32 or 64 bits */
    ck_assert_int_eq(image_check_size(1L << 40, 1L << 40, NULL, &err), -1);
    ck_assert_int_eq(image_check_size(0x7fffffffL, 0x7fffffffL, NULL, &err), -1);
}
END_TEST

START_TEST(test_image_check_size_rejects_more_than_2_to_28_pixels)
{
    error err = {0};
    /* 16385 x 16384 = 2^28 + 16384 pixels, each side under the limit */
    ck_assert_int_eq(image_check_size(16385, 16384, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "2^28"));
    /* 32768 x 8193 = 2^28 + 32768 */
    ck_assert_int_eq(image_check_size(32768, 8193, NULL, &err), -1);
}
END_TEST

START_TEST(test_image_check_size_accepts_sizes_exactly_at_the_limits)
{
    error err = {0};
    ck_assert_int_eq(image_check_size(1, 1, NULL, &err), 0);
    ck_assert_int_eq(image_check_size(IMAGE_MAX_SIDE, 1, NULL, &err), 0);
    ck_assert_int_eq(image_check_size(1, IMAGE_MAX_SIDE, NULL, &err), 0);
    ck_assert_int_eq(image_check_size(16384, 16384, NULL, &err), 0); /* exactly 2^28 */
    ck_assert_int_eq(image_check_size(32768, 8192, NULL, &err), 0);  /* exactly 2^28 */
    ck_assert_int_eq(image_check_size(3, 2, NULL, NULL), 0);         /* err may be NULL */
}
END_TEST

START_TEST(test_image_alloc_is_zero_filled_and_row_major)
{
    error err = {0};
    image im = {0};
    ck_assert_int_eq(image_alloc(&im, 7, 5, &err), 0);
    ck_assert_int_eq(im.w, 7);
    ck_assert_int_eq(im.h, 5);
    for (int i = 0; i < 7 * 5 * 3; i++) ck_assert(im.px[i] == 0.0f);
    image_set(&im, 6, 4, rgb_make(1, 2, 3)); /* the last pixel is the last 3 floats */
    ck_assert(im.px[7 * 5 * 3 - 3] == 1 && im.px[7 * 5 * 3 - 1] == 3);
    image_set(&im, 2, 1, rgb_make(0.5, 0.25, 0.125)); /* row 1 starts at 3 * w floats */
    ck_assert(im.px[3 * (7 + 2) + 1] == 0.25f);
    rgb c = image_get(&im, 2, 1);
    ck_assert(c.r == 0.5 && c.g == 0.25 && c.b == 0.125);
    image_free(&im);
}
END_TEST

START_TEST(test_image_alloc_of_a_bad_size_fails_and_leaves_an_empty_image)
{
    error err = {0};
    image im;
    memset(&im, 0xff, sizeof im); /* garbage in: alloc must reset it */
    ck_assert_int_eq(image_alloc(&im, 0, 10, &err), -1);
    ck_assert_int_eq(im.w, 0);
    ck_assert_int_eq(im.h, 0);
    ck_assert_ptr_null(im.px);
    ck_assert_int_eq(image_alloc(&im, 40000, 1, &err), -1);
    ck_assert_ptr_null(im.px);
    image_free(&im); /* and the failed image is safe to free */
}
END_TEST

START_TEST(test_image_free_twice_is_safe)
{
    error err = {0};
    image im = {0};
    image_free(&im); /* a zeroed image */
    ck_assert_int_eq(image_alloc(&im, 2, 2, &err), 0);
    image_free(&im);
    ck_assert_ptr_null(im.px);
    ck_assert_int_eq(im.w, 0);
    image_free(&im); /* already freed: no double free (ASan would report it) */
    image_free(NULL);
}
END_TEST

START_TEST(test_image_bilinear_wraps_u_across_the_seam_and_clamps_v)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 4, 2, &err), 0);
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 4; x++) image_set(&im, x, y, rgb_gray(x + 10 * y));
    /* u = 0 is halfway between the last column (3) and the first (0) */
    ck_assert_near(image_bilinear_wrap_u(&im, (uv2){0.0, 0.25}).r, 1.5, 1e-12);
    ck_assert_near(image_bilinear_clamp(&im, (uv2){0.0, 0.25}).r, 0.0, 1e-12);
    /* texel centres are exact; above the top centre v clamps to row 0 */
    ck_assert_near(image_bilinear_wrap_u(&im, (uv2){2.5 / 4, 0.75}).r, 12.0, 1e-12);
    ck_assert_near(image_bilinear_wrap_u(&im, (uv2){2.5 / 4, 0.0}).r, 2.0, 1e-12);
    ck_assert_near(image_bilinear_clamp(&im, (uv2){1.0, 1.0}).r, 13.0, 1e-12);
    /* between columns 1 and 2, rows 0 and 1: the mean of 1, 2, 11, 12 */
    ck_assert_near(image_bilinear_clamp(&im, (uv2){0.5, 0.5}).r, 6.5, 1e-12);
    image_free(&im);
}
END_TEST

Suite *image_suite(void)
{
    Suite *s = suite_create("image");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_image_check_size_rejects_empty_and_negative_sizes);
    tcase_add_test(tc, test_image_check_size_rejects_a_side_over_32768);
    tcase_add_test(tc, test_image_check_size_rejects_more_than_2_to_28_pixels);
    tcase_add_test(tc, test_image_check_size_accepts_sizes_exactly_at_the_limits);
    tcase_add_test(tc, test_image_alloc_is_zero_filled_and_row_major);
    tcase_add_test(tc, test_image_alloc_of_a_bad_size_fails_and_leaves_an_empty_image);
    tcase_add_test(tc, test_image_free_twice_is_safe);
    tcase_add_test(tc, test_image_bilinear_wraps_u_across_the_seam_and_clamps_v);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(image_suite)
