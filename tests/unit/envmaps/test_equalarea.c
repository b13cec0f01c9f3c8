/* test_equalarea.c - the equal-area map: orientation, round trips, poles, seam, equal texels. */
#include "envtex/envmaps/equalarea.h"
#include "envtex/core/rng.h"
#include "envtex/core/sampling.h"
#include "unit.h"

#include <float.h>

#define RANDOM_DIRECTIONS 1000000
#define ROUNDTRIP_TOL     1e-6 /* radians; the brief's bound (doubles give ~1e-15) */

static uv2 to_uv(vec3 d)
{
    uv2 uv = {NAN, NAN};
    ck_assert_int_eq(equalarea_dir_to_uv(d, &uv), 0);
    return uv;
}

/* Known answers: the zenith is the top row, the nadir the bottom, phi grows to the right.
 * Catches v measured upwards, theta used instead of cos theta, a phi offset. */
START_TEST(test_equalarea_orientation_has_the_zenith_at_the_top_and_phi_to_the_right)
{
    ck_assert_double_eq(to_uv(vec3_make(0, 0, 1)).v, 0.0);
    ck_assert_double_eq(to_uv(vec3_make(0, 0, -1)).v, 1.0);
    ck_assert_double_eq(to_uv(vec3_make(1, 0, 0)).v, 0.5);
    ck_assert_double_eq(to_uv(vec3_make(1, 0, 0)).u, 0.0);
    ck_assert_near(to_uv(vec3_make(0, 1, 0)).u, 0.25, 1e-15);
    ck_assert_near(to_uv(vec3_make(-1, 0, 0)).u, 0.5, 1e-15);
    ck_assert_near(to_uv(vec3_make(0, -1, 0)).u, 0.75, 1e-15);
    /* theta = 60 degrees: z = 1/2, v = 1/4 (a lat-long map would put it at 1/3) */
    ck_assert_near(to_uv(vec3_make(sqrt(3.0) / 2, 0, 0.5)).v, 0.25, 1e-15);
    vec3 d = equalarea_uv_to_dir((uv2){0.25, 0.75}); /* phi = 90 deg, z = -1/2 */
    ck_assert_near(d.x, 0, 1e-15);
    ck_assert_near(d.y, sqrt(3.0) / 2, 1e-15);
    ck_assert_near(d.z, -0.5, 1e-15);
}
END_TEST

/* Catches any inconsistency between the two directions of the map. */
START_TEST(test_equalarea_roundtrip_is_exact_for_random_directions)
{
    rng r;
    rng_seed(&r, 168, 5);
    double worst = 0;
    int bad = 0; /* counted, not asserted, in the loop: Check writes a file on every assert */
    for (int k = 0; k < RANDOM_DIRECTIONS; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        uv2 uv;
        bad += equalarea_dir_to_uv(d, &uv) != 0;
        bad += !(uv.u >= 0 && uv.u < 1 && uv.v >= 0 && uv.v <= 1);
        double a = vec3_angle(equalarea_uv_to_dir(uv), d);
        if (!(a <= worst)) worst = a;
    }
    ck_assert_int_eq(bad, 0);
    ck_assert_msg(worst < ROUNDTRIP_TOL, "worst round-trip error %g rad", worst);
}
END_TEST

/* Near the zenith 1 - z cancels; the (x^2+y^2)/(1+z) form and 2 sqrt(v(1-v)) keep the angle
 * to full precision.  Near the nadir v is within ulps of 1, and the double v itself limits the
 * angle to 2 sqrt(ulp(1)/2) ~ 2.1e-8 rad (equalarea.h).  Catches v = (1 - z)/2 computed
 * directly (error ~1e-8 rad at theta = 1e-8 from the zenith) and sqrt(1 - z^2) in uv_to_dir. */
#define NADIR_RESOLUTION 2.2e-8 /* 2 sqrt(2^-53): one step of v next to v = 1, in radians */
START_TEST(test_equalarea_roundtrip_is_exact_next_to_the_poles)
{
    for (int k = 1; k <= 12; k++) {
        double theta = pow(10.0, -k);
        for (int pole = 0; pole < 2; pole++) {
            double t = pole ? M_PI - theta : theta;
            vec3 d = vec3_make(sin(t) * cos(1.0), sin(t) * sin(1.0), cos(t));
            double a = vec3_angle(equalarea_uv_to_dir(to_uv(d)), d);
            double tol = pole ? NADIR_RESOLUTION : 1e-15 + 1e-9 * theta;
            ck_assert_msg(a < tol, "theta %g: error %g rad", t, a);
        }
    }
}
END_TEST

/* uv -> direction -> uv on a grid that includes both seam columns and both pole rows. */
START_TEST(test_equalarea_uv_roundtrip_on_a_grid)
{
    for (int j = 1; j < 64; j++)
        for (int i = 0; i < 64; i++) {
            uv2 uv = {i / 64.0, j / 64.0};
            uv2 back = to_uv(equalarea_uv_to_dir(uv));
            ck_assert_near(back.u, uv.u, 1e-12);
            ck_assert_near(back.v, uv.v, 1e-12);
        }
}
END_TEST

/* Poles: phi is undefined, we return u = 0; atan2(+-0, -0) would give pi, so x = -0 tests
 * the special case.  Catches u = 0.5 at a pole and NaN from sqrt of a negative 1 - z^2. */
START_TEST(test_equalarea_poles_map_to_u_zero_and_the_end_rows)
{
    const vec3 poles[] = {{0, 0, 1}, {-0.0, 0, 1}, {-0.0, -0.0, 2}, {0, 0, -1}, {-0.0, 0.0, -3}};
    for (size_t k = 0; k < sizeof poles / sizeof poles[0]; k++) {
        uv2 uv = to_uv(poles[k]);
        ck_assert_double_eq(uv.u, 0.0);
        ck_assert_double_eq(uv.v, poles[k].z > 0 ? 0.0 : 1.0);
    }
    for (int i = 0; i < 8; i++) {
        vec3 n = equalarea_uv_to_dir((uv2){i / 8.0, 0.0}),
             s = equalarea_uv_to_dir((uv2){i / 8.0, 1.0});
        ck_assert_double_eq(n.z, 1.0);
        ck_assert_double_eq(s.z, -1.0);
        ck_assert_double_eq(vec3_length(n), 1.0);
    }
    /* v outside [0, 1] is clamped, not NaN */
    vec3 d = equalarea_uv_to_dir((uv2){0.3, -0.25});
    ck_assert_double_eq(d.z, 1.0);
    d = equalarea_uv_to_dir((uv2){0.3, 7.0});
    ck_assert_double_eq(d.z, -1.0);
}
END_TEST

/* The seam phi = 0 = 2 pi: y = +0, y = -0 and y = -tiny all give u = +0, never 1 and never -0.
 * Catches u = 1 (a column index W, read out of bounds) and -0 leaking out. */
START_TEST(test_equalarea_phi_seam_is_u_zero_from_both_sides)
{
    const vec3 seam[] = {{1, 0, 0}, {1, -0.0, 0}, {1, -1e-300, 0.5}, {2, -0x1p-1074, -1}};
    for (size_t k = 0; k < sizeof seam / sizeof seam[0]; k++) {
        uv2 uv = to_uv(seam[k]);
        ck_assert_double_eq(uv.u, 0.0);
        ck_assert(!signbit(uv.u));
    }
    /* just above the seam: u just below 1 */
    uv2 uv = to_uv(vec3_make(1, -1e-9, 0));
    ck_assert(uv.u < 1.0 && uv.u > 1.0 - 1e-9);
}
END_TEST

/* Catches a missing validity check (NaN coordinates, division by zero). */
START_TEST(test_equalarea_rejects_zero_infinite_and_nan_directions)
{
    const vec3 bad[] = {{0, 0, 0}, {-0.0, -0.0, -0.0}, {NAN, 0, 1}, {0, 0, NAN}, {0, INFINITY, 0}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        uv2 uv = {-5, -5};
        ck_assert_int_eq(equalarea_dir_to_uv(bad[k], &uv), -1);
        ck_assert_double_eq(uv.u, -5);
        ck_assert(
            rgb_is_black(equalarea_lookup_bilinear(&(image){1, 1, (float[]){1, 1, 1}}, bad[k])));
    }
}
END_TEST

/* Only the direction matters.  Catches x^2 + y^2 overflowing (1e300) or underflowing (1e-300)
 * when the vector is not normalized first. */
START_TEST(test_equalarea_ignores_the_length_of_the_direction)
{
    const double scales[] = {7.25, 1e-300, 1e300, DBL_MAX / 2};
    rng r;
    rng_seed(&r, 7, 6);
    for (int k = 0; k < 1000; k++) {
        vec3 d = sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r));
        uv2 want = to_uv(d);
        for (size_t s = 0; s < sizeof scales / sizeof scales[0]; s++) {
            uv2 uv = to_uv(vec3_scale(d, scales[s]));
            ck_assert_near(uv.u, want.u, 1e-15);
            ck_assert_near(uv.v, want.v, 1e-15);
        }
    }
}
END_TEST

/* Every texel covers 4 pi / (W H), computed from the corners of each texel the map itself
 * gives: (phi1 - phi0)(z0 - z1).  Catches rows uniform in theta instead of cos theta. */
START_TEST(test_equalarea_every_texel_has_the_same_solid_angle)
{
    const int w = 16, h = 8;
    double want = equalarea_texel_solid_angle(w, h);
    ck_assert_near(want, 4 * M_PI / 128, 1e-15);
    double total = 0;
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) {
            vec3 a = equalarea_uv_to_dir((uv2){(double)c / w, (double)r / h});
            vec3 b = equalarea_uv_to_dir((uv2){(c + 1.0) / w, (r + 1.0) / h});
            double omega = (2 * M_PI / w) * (a.z - b.z); /* d(omega) = d(phi) d(z) */
            ck_assert_near(omega, want, 1e-14);
            total += omega;
        }
    ck_assert_near(total, 4 * M_PI, 1e-12);
}
END_TEST

/* Independent of the formulas: uniform random directions fall into the texels of a 8 x 4 map
 * equally often (chi-square, 31 degrees of freedom; 70 is beyond p = 1e-4).  A lat-long row
 * layout gives chi-square in the tens of thousands. */
START_TEST(test_equalarea_texels_receive_equal_shares_of_uniform_directions)
{
    enum { W = 8, H = 4, N = 400000 };
    long count[W * H] = {0};
    rng r;
    rng_seed(&r, 2024, 7);
    for (int k = 0; k < N; k++) {
        uv2 uv;
        equalarea_dir_to_uv(sampling_uniform_sphere(rng_uniform(&r), rng_uniform(&r)), &uv);
        int c = (int)(uv.u * W), row = (int)(uv.v * H);
        if (row == H) row = H - 1; /* v = 1 exactly belongs to the last row */
        count[row * W + c]++;
    }
    double expect = (double)N / (W * H), chi2 = 0;
    for (int k = 0; k < W * H; k++) chi2 += (count[k] - expect) * (count[k] - expect) / expect;
    ck_assert_msg(chi2 < 70, "chi-square %g with 31 degrees of freedom", chi2);
}
END_TEST

/* Guard of the division: no texels, no solid angle (not infinity). */
START_TEST(test_equalarea_texel_solid_angle_of_an_empty_map_is_zero)
{
    ck_assert_double_eq(equalarea_texel_solid_angle(0, 5), 0.0);
    ck_assert_double_eq(equalarea_texel_solid_angle(4, -1), 0.0);
    ck_assert_near(equalarea_texel_solid_angle(1, 1), 4 * M_PI, 1e-15);
}
END_TEST

/* Texel (c, r) = c + 10 r.  At texel centres the lookup returns the texel; exactly on the seam
 * it is the mean of the first and last columns; at the poles it clamps to the end row.
 * Catches a half-texel offset and clamping (instead of wrapping) at the seam. */
START_TEST(test_equalarea_lookup_wraps_the_seam_and_hits_texel_centres)
{
    const int w = 8, h = 4;
    image map = {0};
    ck_assert_int_eq(image_alloc(&map, w, h, NULL), 0);
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) image_set(&map, c, r, rgb_gray(c + 10 * r));
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) {
            vec3 d = equalarea_uv_to_dir((uv2){(c + 0.5) / w, (r + 0.5) / h});
            ck_assert_near(equalarea_lookup_bilinear(&map, d).r, c + 10 * r, 1e-9);
        }
    for (int r = 0; r < h; r++) {
        vec3 d = equalarea_uv_to_dir((uv2){0.0, (r + 0.5) / h}); /* on the seam, y = 0 */
        ck_assert_near(equalarea_lookup_bilinear(&map, d).r, (0 + 7) / 2.0 + 10 * r, 1e-9);
        d.y = -0.0;
        ck_assert_near(equalarea_lookup_bilinear(&map, d).r, (0 + 7) / 2.0 + 10 * r, 1e-9);
    }
    /* zenith: u = 0 (seam), row 0 clamped; nadir: last row */
    ck_assert_near(equalarea_lookup_bilinear(&map, vec3_make(0, 0, 1)).r, 3.5, 1e-12);
    ck_assert_near(equalarea_lookup_bilinear(&map, vec3_make(0, 0, -1)).r, 3.5 + 30, 1e-12);
    image_free(&map);
}
END_TEST

Suite *equalarea_suite(void)
{
    Suite *s = suite_create("equalarea");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_equalarea_orientation_has_the_zenith_at_the_top_and_phi_to_the_right);
    tcase_add_test(tc, test_equalarea_roundtrip_is_exact_for_random_directions);
    tcase_add_test(tc, test_equalarea_roundtrip_is_exact_next_to_the_poles);
    tcase_add_test(tc, test_equalarea_uv_roundtrip_on_a_grid);
    tcase_add_test(tc, test_equalarea_poles_map_to_u_zero_and_the_end_rows);
    tcase_add_test(tc, test_equalarea_phi_seam_is_u_zero_from_both_sides);
    tcase_add_test(tc, test_equalarea_rejects_zero_infinite_and_nan_directions);
    tcase_add_test(tc, test_equalarea_ignores_the_length_of_the_direction);
    tcase_add_test(tc, test_equalarea_every_texel_has_the_same_solid_angle);
    tcase_add_test(tc, test_equalarea_texels_receive_equal_shares_of_uniform_directions);
    tcase_add_test(tc, test_equalarea_texel_solid_angle_of_an_empty_map_is_zero);
    tcase_add_test(tc, test_equalarea_lookup_wraps_the_seam_and_hits_texel_centres);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(equalarea_suite)
