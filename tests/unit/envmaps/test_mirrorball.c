/* test_mirrorball.c - mirror-ball probes: orientation, reflection law, round trips, the rim. */
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
    ck_assert_int_eq(mirrorball_dir_to_uv(d, &uv), 0);
    return uv;
}

static vec3 to_dir(uv2 uv)
{
    vec3 d = {NAN, NAN, NAN};
    ck_assert_int_eq(mirrorball_uv_to_dir(uv, &d), 0);
    return d;
}

/* Known answers: the centre reflects straight back at the camera (+x), up is +z, right is +y,
 * the circle rho = 1/sqrt 2 is the horizon of the camera's hemisphere, the rim is -x.
 * Catches a mirrored image (right = -y), v measured upwards, the wrong view axis. */
START_TEST(test_mirrorball_orientation_centre_is_back_at_the_camera_and_up_is_z)
{
    const double q = 0.5 * sqrt(0.5); /* rho = 1/sqrt 2 is a distance of q in u or v */
    ck_dir_near(to_dir((uv2){0.5, 0.5}), vec3_make(1, 0, 0), 1e-15);
    ck_dir_near(to_dir((uv2){0.5 + q, 0.5}), vec3_make(0, 1, 0), 1e-15);  /* right: +y */
    ck_dir_near(to_dir((uv2){0.5 - q, 0.5}), vec3_make(0, -1, 0), 1e-15); /* left: -y */
    ck_dir_near(to_dir((uv2){0.5, 0.5 - q}), vec3_make(0, 0, 1), 1e-15);  /* up: +z */
    ck_dir_near(to_dir((uv2){0.5, 0.5 + q}), vec3_make(0, 0, -1), 1e-15); /* down: -z */
    uv2 uv = to_uv(vec3_make(1, 0, 0));
    ck_assert_double_eq(uv.u, 0.5);
    ck_assert_double_eq(uv.v, 0.5);
    uv = to_uv(vec3_make(0, 0, 1));
    ck_assert_near(uv.u, 0.5, 1e-15);
    ck_assert_near(uv.v, 0.5 - q, 1e-15);
    uv = to_uv(vec3_make(0, 1, 0));
    ck_assert_near(uv.u, 0.5 + q, 1e-15);
    ck_assert_near(uv.v, 0.5, 1e-15);
}
END_TEST

/* The law of reflection, checked without the module's formula: at every image point the
 * sphere's normal n = (sqrt(1 - a^2 - b^2), a, b) makes equal angles with V = +x and with the
 * direction returned, and the three are coplanar.  Catches r = n-based formulas that are not a
 * mirror reflection (e.g. r = 2 n - V without the n.V, or the angular map's law). */
START_TEST(test_mirrorball_directions_obey_the_law_of_reflection)
{
    rng r;
    rng_seed(&r, 11, 12);
    const vec3 view = {1, 0, 0};
    int tested = 0;
    for (int k = 0; k < 20000; k++) {
        uv2 uv = {rng_uniform(&r), rng_uniform(&r)};
        double a = 2 * uv.u - 1, b = 1 - 2 * uv.v;
        vec3 d;
        if (mirrorball_uv_to_dir(uv, &d)) {
            ck_assert(a * a + b * b > 1);
            continue;
        }
        if (a * a + b * b > 0.99) continue; /* the rim is singular: n.V -> 0 */
        tested++;
        vec3 n = vec3_make(sqrt(1 - a * a - b * b), a, b);
        ck_assert_near(vec3_length(d), 1.0, 1e-14);
        ck_assert_near(vec3_angle(n, view), vec3_angle(n, d), 1e-12);
        ck_assert_near(vec3_dot(vec3_cross(n, view), d), 0.0, 1e-12);
    }
    ck_assert_int_gt(tested, 10000);
}
END_TEST

/* Catches any inconsistency between the two directions of the map.  Random directions never
 * come within 1e-9 rad of the singular -x (probability ~1e-19), so no exclusion is needed;
 * the rim itself is tested below. */
START_TEST(test_mirrorball_roundtrip_is_exact_for_random_directions)
{
    rng r;
    rng_seed(&r, 168, 13);
    double worst = 0;
    int bad = 0; /* counted, not asserted, in the loop: Check writes a file on every assert */
    for (int k = 0; k < RANDOM_DIRECTIONS; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        uv2 uv;
        vec3 back = {NAN, NAN, NAN};
        bad += mirrorball_dir_to_uv(d, &uv) != 0;
        bad += mirrorball_uv_to_dir(uv, &back) != 0;
        double a = vec3_angle(back, d);
        if (!(a <= worst)) worst = a;
    }
    ck_assert_int_eq(bad, 0);
    ck_assert_msg(worst < ROUNDTRIP_TOL, "worst round-trip error %g rad", worst);
}
END_TEST

/* Behind the ball 1 + r_x cancels; the (r_y^2 + r_z^2)/(1 - r_x) form keeps the angle.
 * At 1e-6 rad from -x the error must stay ~1e-16 / 1e-6.  Catches normalize(r + V) computed
 * directly (error ~1e-10 rad there, and 0.5 rad at 1e-9). */
START_TEST(test_mirrorball_roundtrip_holds_close_to_the_rim)
{
    for (int k = 1; k <= 7; k++) {
        double eps = pow(10.0, -k); /* angle from -x */
        for (int side = 0; side < 4; side++) {
            double t = side * M_PI / 2 + 0.3;
            vec3 d = vec3_make(-cos(eps), sin(eps) * cos(t), sin(eps) * sin(t));
            double a = vec3_angle(to_dir(to_uv(d)), d);
            ck_assert_msg(a < 1e-15 / eps + 1e-15, "%g rad from -x: error %g rad", eps, a);
        }
    }
}
END_TEST

/* The rim is singular: every rim point is -x; -x itself gives the top rim point; directions
 * approaching -x from a side approach the rim point on that side.  Catches NaN from 0/0 at
 * r = -V and a rim point that is not on the disc's edge. */
START_TEST(test_mirrorball_rim_is_the_direction_behind_the_ball)
{
    const uv2 rim[] = {{1, 0.5}, {0, 0.5}, {0.5, 0}, {0.5, 1}};
    for (int k = 0; k < 4; k++) ck_dir_near(to_dir(rim[k]), vec3_make(-1, 0, 0), 0.0);
    for (int k = 0; k < 360; k++) { /* rim points made with cos / sin, rounding and all */
        double t = k * M_PI / 180;
        vec3 d = to_dir((uv2){0.5 + 0.5 * cos(t), 0.5 - 0.5 * sin(t)});
        ck_dir_near(d, vec3_make(-1, 0, 0), 1e-7); /* 1 - rho^2 ~ 1e-16: angle ~ 2e-8 */
    }
    uv2 uv = to_uv(vec3_make(-1, 0, 0));
    ck_assert_double_eq(uv.u, 0.5);
    ck_assert_double_eq(uv.v, 0.0);
    uv = to_uv(vec3_make(-3, -0.0, 0.0));
    ck_assert_double_eq(uv.u, 0.5);
    ck_assert_double_eq(uv.v, 0.0);
    uv = to_uv(vec3_make(-1, -1e-9, 0)); /* from -y: the left rim point */
    ck_assert_near(uv.u, 0.0, 1e-12);
    ck_assert_near(uv.v, 0.5, 1e-12);
    uv = to_uv(vec3_make(-1, 0, -1e-9)); /* from -z: the bottom */
    ck_assert_near(uv.u, 0.5, 1e-12);
    ck_assert_near(uv.v, 1.0, 1e-12);
}
END_TEST

/* Outside the ball there is no direction.  Catches a missing disc test (sqrt of a negative). */
START_TEST(test_mirrorball_points_outside_the_ball_have_no_direction)
{
    const uv2 out[] = {{0, 0},          {1, 1},     {0, 1},     {0.9, 0.9},     {0.5, -1e-9},
                       {1 + 1e-9, 0.5}, {NAN, 0.5}, {0.5, NAN}, {INFINITY, 0.5}};
    for (size_t k = 0; k < sizeof out / sizeof out[0]; k++) {
        vec3 d = {7, 7, 7};
        ck_assert_int_eq(mirrorball_uv_to_dir(out[k], &d), -1);
        ck_assert_double_eq(d.x, 7);
    }
}
END_TEST

/* Catches a missing validity check. */
START_TEST(test_mirrorball_rejects_zero_infinite_and_nan_directions)
{
    const vec3 bad[] = {{0, 0, 0}, {-0.0, 0, -0.0}, {NAN, 0, 1}, {0, NAN, 0}, {-INFINITY, 0, 0}};
    image probe = {1, 1, (float[]){1, 1, 1}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        uv2 uv = {-5, -5};
        ck_assert_int_eq(mirrorball_dir_to_uv(bad[k], &uv), -1);
        ck_assert_double_eq(uv.u, -5);
        ck_assert(rgb_is_black(mirrorball_lookup_bilinear(&probe, bad[k])));
    }
}
END_TEST

/* Only the direction matters.  Catches a formula that assumes |d| = 1. */
START_TEST(test_mirrorball_ignores_the_length_of_the_direction)
{
    const double scales[] = {7.25, 1e-300, 1e300, DBL_MAX / 2};
    rng r;
    rng_seed(&r, 7, 14);
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

/* A mirror ball is an equal-area map: cos(angle from +x) = 1 - 2 rho^2.  Uniform random
 * directions must land uniformly over the disc: in 8 rings of equal area (rho^2 in [k/8,
 * (k+1)/8)) equally often (chi-square, 7 degrees of freedom; 30 is beyond p = 1e-4).
 * Catches the angular map's law (rho proportional to angle) and a wrong n. */
START_TEST(test_mirrorball_equal_image_areas_hold_equal_solid_angles)
{
    enum { RINGS = 8, N = 200000 };
    long count[RINGS] = {0};
    rng r;
    rng_seed(&r, 2024, 15);
    for (int k = 0; k < N; k++) {
        uv2 uv;
        mirrorball_dir_to_uv(sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r)), &uv);
        double a = 2 * uv.u - 1, b = 1 - 2 * uv.v;
        int ring = (int)((a * a + b * b) * RINGS);
        count[ring < RINGS ? ring : RINGS - 1]++;
    }
    double expect = (double)N / RINGS, chi2 = 0;
    for (int k = 0; k < RINGS; k++) chi2 += (count[k] - expect) * (count[k] - expect) / expect;
    ck_assert_msg(chi2 < 30, "chi-square %g with 7 degrees of freedom", chi2);
}
END_TEST

/* At texel centres the lookup returns the texel; +x reads the centre of the image.
 * Catches a half-texel offset and a flipped image axis. */
START_TEST(test_mirrorball_lookup_reads_texel_centres)
{
    const int n = 9;
    image probe = {0};
    ck_assert_int_eq(image_alloc(&probe, n, n, NULL), 0);
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) image_set(&probe, x, y, rgb_gray(x + 100 * y));
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            vec3 d;
            if (mirrorball_uv_to_dir((uv2){(x + 0.5) / n, (y + 0.5) / n}, &d)) continue;
            ck_assert_near(mirrorball_lookup_bilinear(&probe, d).r, x + 100 * y, 1e-6);
        }
    ck_assert_near(mirrorball_lookup_bilinear(&probe, vec3_make(1, 0, 0)).r, 4 + 400, 1e-12);
    /* +z is above the centre (smaller row), +y to its right (larger column) */
    ck_assert(mirrorball_lookup_bilinear(&probe, vec3_make(1, 0, 1)).r < 400);
    ck_assert(mirrorball_lookup_bilinear(&probe, vec3_make(1, 1, 0)).r > 404);
    /* beyond the outermost texel centres (on row 4's centre, v = 1/2) the lookup clamps to the
     * edge column (mirrorball.h), not blended with the opposite edge as a wrapping lookup would */
    vec3 d;
    ck_assert_int_eq(mirrorball_uv_to_dir((uv2){1 - 0.25 / n, 0.5}, &d), 0);
    ck_assert_near(mirrorball_lookup_bilinear(&probe, d).r, 8 + 400, 1e-6);
    ck_assert_int_eq(mirrorball_uv_to_dir((uv2){0.25 / n, 0.5}, &d), 0);
    ck_assert_near(mirrorball_lookup_bilinear(&probe, d).r, 0 + 400, 1e-6);
    image_free(&probe);
}
END_TEST

Suite *mirrorball_suite(void)
{
    Suite *s = suite_create("mirrorball");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_mirrorball_orientation_centre_is_back_at_the_camera_and_up_is_z);
    tcase_add_test(tc, test_mirrorball_directions_obey_the_law_of_reflection);
    tcase_add_test(tc, test_mirrorball_roundtrip_is_exact_for_random_directions);
    tcase_add_test(tc, test_mirrorball_roundtrip_holds_close_to_the_rim);
    tcase_add_test(tc, test_mirrorball_rim_is_the_direction_behind_the_ball);
    tcase_add_test(tc, test_mirrorball_points_outside_the_ball_have_no_direction);
    tcase_add_test(tc, test_mirrorball_rejects_zero_infinite_and_nan_directions);
    tcase_add_test(tc, test_mirrorball_ignores_the_length_of_the_direction);
    tcase_add_test(tc, test_mirrorball_equal_image_areas_hold_equal_solid_angles);
    tcase_add_test(tc, test_mirrorball_lookup_reads_texel_centres);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(mirrorball_suite)
