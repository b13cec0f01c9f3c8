/* test_angular.c - the angular map: orientation, angle law, round trips, the rim. */
#include "envtex/envmaps/angular.h"
#include "envtex/envmaps/mirrorball.h"
#include "envtex/core/rng.h"
#include "envtex/core/sampling.h"
#include "unit.h"

#include <float.h>

#define RANDOM_DIRECTIONS 1000000
#define ROUNDTRIP_TOL     1e-6 /* radians; the brief's bound */

static uv2 to_uv(vec3 d)
{
    uv2 uv = {NAN, NAN};
    ck_assert_int_eq(angular_dir_to_uv(d, &uv), 0);
    return uv;
}

static vec3 to_dir(uv2 uv)
{
    vec3 d = {NAN, NAN, NAN};
    ck_assert_int_eq(angular_uv_to_dir(uv, &d), 0);
    return d;
}

/* Known answers: centre +x, up +z, right +y, half-way out 90 degrees, rim -x.
 * Catches a mirrored image, v measured upwards, the mirror ball's radius law (1/sqrt 2 for 90). */
START_TEST(test_angular_orientation_centre_is_back_at_the_camera_and_up_is_z)
{
    ck_dir_near(to_dir((uv2){0.5, 0.5}), vec3_make(1, 0, 0), 0.0);
    ck_dir_near(to_dir((uv2){0.75, 0.5}), vec3_make(0, 1, 0), 1e-15);  /* right: +y */
    ck_dir_near(to_dir((uv2){0.25, 0.5}), vec3_make(0, -1, 0), 1e-15); /* left: -y */
    ck_dir_near(to_dir((uv2){0.5, 0.25}), vec3_make(0, 0, 1), 1e-15);  /* up: +z */
    ck_dir_near(to_dir((uv2){0.5, 0.75}), vec3_make(0, 0, -1), 1e-15); /* down: -z */
    uv2 uv = to_uv(vec3_make(1, 0, 1)); /* 45 degrees towards +z: rho = 1/4 */
    ck_assert_near(uv.u, 0.5, 1e-15);
    ck_assert_near(uv.v, 0.375, 1e-15);
    uv = to_uv(vec3_make(-1, -1, 0)); /* 135 degrees towards -y: rho = 3/4 */
    ck_assert_near(uv.u, 0.125, 1e-15);
    ck_assert_near(uv.v, 0.5, 1e-15);
    uv = to_uv(vec3_make(2, 0, 0));
    ck_assert_double_eq(uv.u, 0.5);
    ck_assert_double_eq(uv.v, 0.5);
}
END_TEST

/* The defining law, checked without the module's formula: the distance from the centre is
 * the angle from +x over pi, and the image point lies in the direction of (y, z).  Catches the
 * mirror ball's law and a wrong azimuth. */
START_TEST(test_angular_distance_from_centre_is_proportional_to_angle)
{
    rng r;
    rng_seed(&r, 11, 16);
    double worst_rho = 0, worst_azimuth = 0;
    int wrong_side = 0; /* counted, not asserted, in the loop: Check writes a file per assert */
    for (int k = 0; k < 100000; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        uv2 uv = to_uv(d);
        double a = 2 * uv.u - 1, b = 1 - 2 * uv.v;
        double rho = sqrt(a * a + b * b);
        double e = fabs(rho - vec3_angle(d, vec3_make(1, 0, 0)) / M_PI);
        if (!(e <= worst_rho)) worst_rho = e;
        /* (a, b) parallel to (y, z): a z - b y = 0 and a y + b z >= 0 */
        double cross = fabs(a * d.z - b * d.y), dot = a * d.y + b * d.z;
        if (!(cross <= worst_azimuth)) worst_azimuth = cross;
        wrong_side += !(dot >= 0);
    }
    ck_assert_int_eq(wrong_side, 0);
    ck_assert_msg(worst_rho < 1e-14, "rho off by %g", worst_rho);
    ck_assert_msg(worst_azimuth < 1e-14, "azimuth off by %g", worst_azimuth);
}
END_TEST

/* Same frame as the mirror ball: a direction's image point lies in the same direction from the
 * centre on both maps (only the radius law differs).  Catches the two modules disagreeing on
 * the view axis or on which way is up. */
START_TEST(test_angular_shares_the_mirror_ball_frame)
{
    rng r;
    rng_seed(&r, 3, 17);
    for (int k = 0; k < 1000; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        uv2 p = to_uv(d), q;
        ck_assert_int_eq(mirrorball_dir_to_uv(d, &q), 0);
        double a1 = 2 * p.u - 1, b1 = 1 - 2 * p.v, a2 = 2 * q.u - 1, b2 = 1 - 2 * q.v;
        ck_assert_near(atan2(b1, a1), atan2(b2, a2), 1e-9);
    }
}
END_TEST

/* Catches any inconsistency between the two directions of the map.  Random directions never
 * come near the singular -x closely enough to matter (the map is well conditioned anyway). */
START_TEST(test_angular_roundtrip_is_exact_for_random_directions)
{
    rng r;
    rng_seed(&r, 168, 18);
    double worst = 0;
    int bad = 0; /* counted, not asserted, in the loop: Check writes a file on every assert */
    for (int k = 0; k < RANDOM_DIRECTIONS; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        uv2 uv;
        vec3 back = {NAN, NAN, NAN};
        bad += angular_dir_to_uv(d, &uv) != 0;
        bad += angular_uv_to_dir(uv, &back) != 0;
        double a = vec3_angle(back, d);
        if (!(a <= worst)) worst = a;
    }
    ck_assert_int_eq(bad, 0);
    ck_assert_msg(worst < ROUNDTRIP_TOL, "worst round-trip error %g rad", worst);
}
END_TEST

/* Unlike the mirror ball, the angular map stays exact right up to the rim (atan2 and sin(pi
 * rho) keep absolute precision; 1e-15 is the floor of measuring the angle).  Catches acos(x)
 * for theta (error ~1e-16 / eps rad at eps from +x or -x). */
START_TEST(test_angular_roundtrip_holds_next_to_the_rim_and_the_centre)
{
    for (int k = 1; k <= 12; k++) {
        double eps = pow(10.0, -k);
        for (int side = 0; side < 4; side++) {
            double t = side * M_PI / 2 + 0.3;
            vec3 behind = vec3_make(-cos(eps), sin(eps) * cos(t), sin(eps) * sin(t));
            vec3 front = vec3_make(cos(eps), sin(eps) * cos(t), sin(eps) * sin(t));
            double a = vec3_angle(to_dir(to_uv(behind)), behind);
            ck_assert_msg(a < 1e-14, "%g rad from -x: error %g rad", eps, a);
            a = vec3_angle(to_dir(to_uv(front)), front);
            ck_assert_msg(a < 1e-15, "%g rad from +x: error %g rad", eps, a);
        }
    }
}
END_TEST

/* The rim is singular: every rim point is -x; -x itself gives the top rim point; directions
 * approaching -x from a side approach the rim point on that side.  Catches 0/0 at y = z = 0. */
START_TEST(test_angular_rim_is_the_direction_behind_the_probe)
{
    const uv2 rim[] = {{1, 0.5}, {0, 0.5}, {0.5, 0}, {0.5, 1}};
    for (int k = 0; k < 4; k++) ck_dir_near(to_dir(rim[k]), vec3_make(-1, 0, 0), 1e-15);
    for (int k = 0; k < 360; k++) {
        double t = k * M_PI / 180;
        ck_dir_near(to_dir((uv2){0.5 + 0.5 * cos(t), 0.5 - 0.5 * sin(t)}), vec3_make(-1, 0, 0),
                        1e-14);
    }
    uv2 uv = to_uv(vec3_make(-1, 0, 0));
    ck_assert_double_eq(uv.u, 0.5);
    ck_assert_double_eq(uv.v, 0.0);
    uv = to_uv(vec3_make(-1e-300, -0.0, 0.0));
    ck_assert_double_eq(uv.u, 0.5);
    ck_assert_double_eq(uv.v, 0.0);
    uv = to_uv(vec3_make(-1, -1e-9, 0)); /* from -y: the left rim point */
    ck_assert_near(uv.u, 0.0, 1e-9);
    ck_assert_near(uv.v, 0.5, 1e-9);
    uv = to_uv(vec3_make(-1, 0, -1e-9)); /* from -z: the bottom */
    ck_assert_near(uv.u, 0.5, 1e-9);
    ck_assert_near(uv.v, 1.0, 1e-9);
}
END_TEST

/* Outside the disc there is no direction.  Catches a missing disc test. */
START_TEST(test_angular_points_outside_the_disc_have_no_direction)
{
    const uv2 out[] = {{0, 0},          {1, 1},     {0, 1},     {0.9, 0.9},     {0.5, -1e-9},
                       {1 + 1e-9, 0.5}, {NAN, 0.5}, {0.5, NAN}, {INFINITY, 0.5}};
    for (size_t k = 0; k < sizeof out / sizeof out[0]; k++) {
        vec3 d = {7, 7, 7};
        ck_assert_int_eq(angular_uv_to_dir(out[k], &d), -1);
        ck_assert_double_eq(d.x, 7);
    }
}
END_TEST

/* Catches a missing validity check. */
START_TEST(test_angular_rejects_zero_infinite_and_nan_directions)
{
    const vec3 bad[] = {{0, 0, 0}, {-0.0, 0, -0.0}, {NAN, 0, 1}, {0, NAN, 0}, {-INFINITY, 0, 0}};
    image probe = {1, 1, (float[]){1, 1, 1}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        uv2 uv = {-5, -5};
        ck_assert_int_eq(angular_dir_to_uv(bad[k], &uv), -1);
        ck_assert_double_eq(uv.u, -5);
        ck_assert(rgb_is_black(angular_lookup_bilinear(&probe, bad[k])));
    }
}
END_TEST

/* Only the direction matters.  Catches a formula that assumes |d| = 1. */
START_TEST(test_angular_ignores_the_length_of_the_direction)
{
    const double scales[] = {7.25, 1e-300, 1e300, DBL_MAX / 2};
    rng r;
    rng_seed(&r, 7, 19);
    for (int k = 0; k < 1000; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        uv2 want = to_uv(d);
        for (size_t s = 0; s < sizeof scales / sizeof scales[0]; s++) {
            uv2 uv = to_uv(vec3_scale(d, scales[s]));
            ck_assert_near(uv.u, want.u, 1e-14);
            ck_assert_near(uv.v, want.v, 1e-14);
        }
    }
}
END_TEST

/* At texel centres the lookup returns the texel; +x reads the image centre.  Catches a
 * half-texel offset, a flipped axis, and wrapping instead of clamping at the edges. */
START_TEST(test_angular_lookup_reads_texel_centres)
{
    const int n = 9;
    image probe = {0};
    ck_assert_int_eq(image_alloc(&probe, n, n, NULL), 0);
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) image_set(&probe, x, y, rgb_gray(x + 100 * y));
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            vec3 d;
            if (angular_uv_to_dir((uv2){(x + 0.5) / n, (y + 0.5) / n}, &d)) continue;
            ck_assert_near(angular_lookup_bilinear(&probe, d).r, x + 100 * y, 1e-6);
        }
    ck_assert_near(angular_lookup_bilinear(&probe, vec3_make(1, 0, 0)).r, 4 + 400, 1e-12);
    ck_assert(angular_lookup_bilinear(&probe, vec3_make(1, 0, 1)).r < 400); /* +z: above */
    ck_assert(angular_lookup_bilinear(&probe, vec3_make(1, 1, 0)).r > 404); /* +y: right */
    /* beyond the outermost texel centres (on row 4's centre, v = 1/2) the lookup clamps to the
     * edge column (angular.h), not blended with the opposite edge as a wrapping lookup would */
    vec3 d;
    ck_assert_int_eq(angular_uv_to_dir((uv2){1 - 0.25 / n, 0.5}, &d), 0);
    ck_assert_near(angular_lookup_bilinear(&probe, d).r, 8 + 400, 1e-6);
    ck_assert_int_eq(angular_uv_to_dir((uv2){0.25 / n, 0.5}, &d), 0);
    ck_assert_near(angular_lookup_bilinear(&probe, d).r, 0 + 400, 1e-6);
    image_free(&probe);
}
END_TEST

Suite *angular_suite(void)
{
    Suite *s = suite_create("angular");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_angular_orientation_centre_is_back_at_the_camera_and_up_is_z);
    tcase_add_test(tc, test_angular_distance_from_centre_is_proportional_to_angle);
    tcase_add_test(tc, test_angular_shares_the_mirror_ball_frame);
    tcase_add_test(tc, test_angular_roundtrip_is_exact_for_random_directions);
    tcase_add_test(tc, test_angular_roundtrip_holds_next_to_the_rim_and_the_centre);
    tcase_add_test(tc, test_angular_rim_is_the_direction_behind_the_probe);
    tcase_add_test(tc, test_angular_points_outside_the_disc_have_no_direction);
    tcase_add_test(tc, test_angular_rejects_zero_infinite_and_nan_directions);
    tcase_add_test(tc, test_angular_ignores_the_length_of_the_direction);
    tcase_add_test(tc, test_angular_lookup_reads_texel_centres);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(angular_suite)
