/* test_cylindrical.c - the cylindrical map: orientation, extent, poles, seam, round trips. */
#include "envtex/envmaps/cylindrical.h"
#include "envtex/core/rng.h"
#include "envtex/core/sampling.h"
#include "unit.h"

#include <float.h>

#define RANDOM_DIRECTIONS 1000000
#define ROUNDTRIP_TOL     1e-6 /* radians; the brief's bound (doubles give ~1e-15) */

static uv2 to_uv(vec3 d, double h)
{
    uv2 uv = {NAN, NAN};
    ck_assert_int_eq(cylindrical_dir_to_uv(d, h, &uv), 0);
    return uv;
}

static vec3 to_dir(uv2 uv, double h)
{
    vec3 d = {NAN, NAN, NAN};
    ck_assert_int_eq(cylindrical_uv_to_dir(uv, h, &d), 0);
    return d;
}

/* Known answers: up is the top row, phi grows to the right, rows uniform in cot theta.
 * Catches v measured upwards, rows uniform in angle, a phi offset, h used as the full extent. */
START_TEST(test_cylindrical_orientation_has_up_at_the_top_and_phi_to_the_right)
{
    ck_assert_double_eq(to_uv(vec3_make(1, 0, 0), 1.0).u, 0.0);
    ck_assert_double_eq(to_uv(vec3_make(1, 0, 0), 1.0).v, 0.5);
    ck_assert_near(to_uv(vec3_make(0, 1, 0), 1.0).u, 0.25, 1e-15);
    ck_assert_near(to_uv(vec3_make(-1, 0, 0), 1.0).u, 0.5, 1e-15);
    ck_assert_near(to_uv(vec3_make(0, -1, 0), 1.0).u, 0.75, 1e-15);
    ck_assert_double_eq(to_uv(vec3_make(1, 0, 1), 1.0).v, 0.0);   /* 45 deg up: the top edge */
    ck_assert_double_eq(to_uv(vec3_make(1, 0, -1), 1.0).v, 1.0);  /* 45 deg down: the bottom */
    ck_assert_double_eq(to_uv(vec3_make(0, 2, 1), 1.0).v, 0.25);  /* z_cyl = 1/2 */
    ck_assert_double_eq(to_uv(vec3_make(0, 2, 1), 2.0).v, 0.375); /* z_cyl = 1/2 of h = 2 */
    /* 30 degrees of elevation: z_cyl = tan 30 = 0.577..., not 30/45 of the way up */
    ck_assert_near(to_uv(vec3_make(cos(M_PI / 6), 0, sin(M_PI / 6)), 1.0).v,
                   0.5 - tan(M_PI / 6) / 2, 1e-15);
    vec3 d = to_dir((uv2){0.25, 0.0}, 1.0);
    ck_assert_near(d.x, 0, 1e-15);
    ck_assert_near(d.y, sqrt(0.5), 1e-15);
    ck_assert_near(d.z, sqrt(0.5), 1e-15);
}
END_TEST

/* 10^6 uniform directions: those inside the extent come back to within 1e-6 rad, and the share
 * accepted is the known P(|z| <= h / sqrt(1 + h^2)) = h / sqrt(1 + h^2).  Catches a wrong
 * extent test (e.g. comparing z instead of z_cyl with h). */
START_TEST(test_cylindrical_roundtrip_is_exact_inside_the_extent)
{
    const double h = 3.0;
    rng r;
    rng_seed(&r, 168, 8);
    double worst = 0;
    long accepted = 0, bad = 0; /* counted, not asserted, in the loop: Check writes a file on
                                   every assert */
    for (int k = 0; k < RANDOM_DIRECTIONS; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        uv2 uv;
        if (cylindrical_dir_to_uv(d, h, &uv)) continue;
        accepted++;
        bad += !(uv.u >= 0 && uv.u < 1 && uv.v >= 0 && uv.v <= 1);
        vec3 back;
        bad += cylindrical_uv_to_dir(uv, h, &back) != 0;
        double a = vec3_angle(back, d);
        if (!(a <= worst)) worst = a;
    }
    ck_assert_int_eq(bad, 0);
    ck_assert_msg(worst < ROUNDTRIP_TOL, "worst round-trip error %g rad", worst);
    double p = h / sqrt(1 + h * h), n = RANDOM_DIRECTIONS;
    double sigma = sqrt(n * p * (1 - p));
    ck_assert_msg(fabs(accepted - n * p) < 5 * sigma, "accepted %ld, expected %g", accepted, n * p);
}
END_TEST

/* uv -> direction -> uv on a grid including the seam column and both cut rows. */
START_TEST(test_cylindrical_uv_roundtrip_on_a_grid)
{
    const double heights[] = {0.25, 1.0, 10.0};
    for (size_t k = 0; k < 3; k++)
        for (int j = 0; j <= 64; j++)
            for (int i = 0; i < 64; i++) {
                uv2 uv = {i / 64.0, j / 64.0};
                uv2 back;
                /* the cut rows may land an ulp outside the extent: accept either answer */
                if (cylindrical_dir_to_uv(to_dir(uv, heights[k]), heights[k], &back)) {
                    ck_assert(j == 0 || j == 64);
                    continue;
                }
                ck_assert_near(back.u, uv.u, 1e-12);
                ck_assert_near(back.v, uv.v, 1e-12);
            }
}
END_TEST

/* Beyond the cut and at the poles there is no image point.  Catches an unguarded z / 0 and a
 * missing extent test (v outside [0, 1], read out of the image). */
START_TEST(test_cylindrical_rejects_poles_and_directions_beyond_the_extent)
{
    const vec3 out[] = {
        {0, 0, 1},         {0, 0, -1},          {-0.0, 0, 5},  {-0.0, -0.0, -1e-300},
        {1, 0, 1.0000001}, {0, -1, -1.0000001}, {1e-300, 0, 1}};
    for (size_t k = 0; k < sizeof out / sizeof out[0]; k++) {
        uv2 uv = {-5, -5};
        ck_assert_int_eq(cylindrical_dir_to_uv(out[k], 1.0, &uv), -1);
        ck_assert_double_eq(uv.u, -5);
    }
    /* the exact cut is inside: (2, 0, 1) has z_cyl = 1/2 exactly */
    ck_assert_double_eq(to_uv(vec3_make(2, 0, 1), 0.5).v, 0.0);
    ck_assert_double_eq(to_uv(vec3_make(-2, 0, -1), 0.5).v, 1.0);
    /* uv_to_dir: v outside [0, 1] has no direction on the cut cylinder */
    vec3 d = {7, 7, 7};
    ck_assert_int_eq(cylindrical_uv_to_dir((uv2){0.5, -1e-9}, 1.0, &d), -1);
    ck_assert_int_eq(cylindrical_uv_to_dir((uv2){0.5, 1.0 + 1e-9}, 1.0, &d), -1);
    ck_assert_int_eq(cylindrical_uv_to_dir((uv2){NAN, 0.5}, 1.0, &d), -1);
    ck_assert_int_eq(cylindrical_uv_to_dir((uv2){0.5, NAN}, 1.0, &d), -1);
    ck_assert_int_eq(cylindrical_uv_to_dir((uv2){INFINITY, 0.5}, 1.0, &d), -1);
    ck_assert_double_eq(d.x, 7);
}
END_TEST

/* max_height is a divisor: zero, negative, NaN and infinity are refused by all three
 * functions.  Catches the division by 2 h with h = 0. */
START_TEST(test_cylindrical_rejects_a_bad_max_height)
{
    const double bad[] = {0.0, -0.0, -1.0, NAN, INFINITY};
    image map = {1, 1, (float[]){1, 1, 1}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        uv2 uv;
        vec3 d;
        ck_assert_int_eq(cylindrical_dir_to_uv(vec3_make(1, 0, 0), bad[k], &uv), -1);
        ck_assert_int_eq(cylindrical_uv_to_dir((uv2){0.5, 0.5}, bad[k], &d), -1);
        ck_assert(rgb_is_black(cylindrical_lookup_bilinear(&map, bad[k], vec3_make(1, 0, 0))));
    }
}
END_TEST

/* Catches a missing validity check (NaN coordinates). */
START_TEST(test_cylindrical_rejects_zero_infinite_and_nan_directions)
{
    const vec3 bad[] = {{0, 0, 0}, {-0.0, -0.0, -0.0}, {NAN, 0, 1}, {1, 0, NAN}, {0, -INFINITY, 0}};
    image map = {1, 1, (float[]){1, 1, 1}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        uv2 uv = {-5, -5};
        ck_assert_int_eq(cylindrical_dir_to_uv(bad[k], 1.0, &uv), -1);
        ck_assert_double_eq(uv.u, -5);
        ck_assert(rgb_is_black(cylindrical_lookup_bilinear(&map, 1.0, bad[k])));
    }
}
END_TEST

/* The seam phi = 0 = 2 pi: y = +0, -0 and -tiny all give u = +0.  Catches u = 1 (column W). */
START_TEST(test_cylindrical_phi_seam_is_u_zero_from_both_sides)
{
    const vec3 seam[] = {{1, 0, 0}, {1, -0.0, 0}, {1, -1e-300, 0.5}, {2, -0x1p-1074, -1}};
    for (size_t k = 0; k < sizeof seam / sizeof seam[0]; k++) {
        uv2 uv = to_uv(seam[k], 1.0);
        ck_assert_double_eq(uv.u, 0.0);
        ck_assert(!signbit(uv.u));
    }
}
END_TEST

/* Only the direction matters.  Catches x^2 + y^2 overflowing or underflowing. */
START_TEST(test_cylindrical_ignores_the_length_of_the_direction)
{
    const double scales[] = {7.25, 1e-300, 1e300, DBL_MAX / 2};
    rng r;
    rng_seed(&r, 7, 9);
    int tested = 0;
    for (int k = 0; k < 1000; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        uv2 want;
        if (cylindrical_dir_to_uv(d, 2.0, &want)) continue;
        tested++;
        for (size_t s = 0; s < sizeof scales / sizeof scales[0]; s++) {
            uv2 uv = to_uv(vec3_scale(d, scales[s]), 2.0);
            ck_assert_near(uv.u, want.u, 1e-15);
            ck_assert_near(uv.v, want.v, 1e-14);
        }
    }
    ck_assert_int_gt(tested, 500);
}
END_TEST

/* Texel (c, r) = c + 10 r.  Texel centres return their texel; the seam blends the first and
 * last columns; beyond the cut is black.  Catches a half-texel offset and a clamped seam. */
START_TEST(test_cylindrical_lookup_wraps_the_seam_and_is_black_beyond_the_cut)
{
    const int w = 8, h = 4;
    const double mh = 1.5;
    image map = {0};
    ck_assert_int_eq(image_alloc(&map, w, h, NULL), 0);
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) image_set(&map, c, r, rgb_gray(1 + c + 10 * r));
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) {
            vec3 d = to_dir((uv2){(c + 0.5) / w, (r + 0.5) / h}, mh);
            ck_assert_near(cylindrical_lookup_bilinear(&map, mh, d).r, 1 + c + 10 * r, 1e-9);
        }
    for (int r = 0; r < h; r++) {
        vec3 d = to_dir((uv2){0.0, (r + 0.5) / h}, mh);
        d.y = 0.0; /* exactly on the seam */
        ck_assert_near(cylindrical_lookup_bilinear(&map, mh, d).r, 1 + 3.5 + 10 * r, 1e-9);
        d.y = -0.0;
        ck_assert_near(cylindrical_lookup_bilinear(&map, mh, d).r, 1 + 3.5 + 10 * r, 1e-9);
    }
    ck_assert(rgb_is_black(cylindrical_lookup_bilinear(&map, mh, vec3_make(1, 0, 1.6))));
    ck_assert(rgb_is_black(cylindrical_lookup_bilinear(&map, mh, vec3_make(0, 0, -1))));
    /* on the cut itself: the top row (clamped), blended across the seam */
    ck_assert_near(cylindrical_lookup_bilinear(&map, 0.5, vec3_make(2, 0, 1)).r, 1 + 3.5, 1e-12);
    image_free(&map);
}
END_TEST

Suite *cylindrical_suite(void)
{
    Suite *s = suite_create("cylindrical");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_cylindrical_orientation_has_up_at_the_top_and_phi_to_the_right);
    tcase_add_test(tc, test_cylindrical_roundtrip_is_exact_inside_the_extent);
    tcase_add_test(tc, test_cylindrical_uv_roundtrip_on_a_grid);
    tcase_add_test(tc, test_cylindrical_rejects_poles_and_directions_beyond_the_extent);
    tcase_add_test(tc, test_cylindrical_rejects_a_bad_max_height);
    tcase_add_test(tc, test_cylindrical_rejects_zero_infinite_and_nan_directions);
    tcase_add_test(tc, test_cylindrical_phi_seam_is_u_zero_from_both_sides);
    tcase_add_test(tc, test_cylindrical_ignores_the_length_of_the_direction);
    tcase_add_test(tc, test_cylindrical_lookup_wraps_the_seam_and_is_black_beyond_the_cut);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(cylindrical_suite)
