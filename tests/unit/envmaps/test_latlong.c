/* test_latlong.c - the lat-long map's convention (FORMAT.md, latlong.h): +x at u = 0, +y at
 * u = 0.25, zenith at v = 0; exact round trips; the phi seam; bilinear wrapping and pole
 * clamping; texel solid angles. */
#include "envtex/envmaps/latlong.h"

#include <string.h>

#include "envtex/core/rng.h"
#include "unit.h"

/* Checks for long loops: every passing ck_assert costs a system call (Check records the last
 * passing line), which would dominate the run time; these report failures only. */
#define EXPECT(c)                                                                                  \
    do {                                                                                           \
        if (!(c)) ck_abort_msg("failed: %s", #c);                                                  \
    } while (0)
#define EXPECT_MSG(c, ...)                                                                         \
    do {                                                                                           \
        if (!(c)) ck_abort_msg(__VA_ARGS__);                                                       \
    } while (0)
#define EXPECT_INT_EQ(a, b)                                                                        \
    do {                                                                                           \
        long long a_ = (a), b_ = (b);                                                              \
        if (a_ != b_) ck_abort_msg("%s == %lld, %s == %lld", #a, a_, #b, b_);                      \
    } while (0)
#define EXPECT_NEAR(a, b, tol) unit_near(__FILE__, __LINE__, #a, (a), (b), (tol))

static uv2 to_uv(vec3 d)
{
    uv2 uv = {-1, -1};
    EXPECT_INT_EQ(latlong_dir_to_uv(d, &uv), 0);
    return uv;
}

static image make_map(int w, int h)
{
    image im;
    error err = {0};
    EXPECT_INT_EQ(image_alloc(&im, w, h, &err), 0);
    return im;
}

START_TEST(test_latlong_axes_land_where_the_convention_says)
{
    uv2 uv = to_uv(vec3_make(1, 0, 0));
    EXPECT(uv.u == 0);
    EXPECT_NEAR(uv.v, 0.5, 1e-16);
    EXPECT_NEAR(to_uv(vec3_make(0, 1, 0)).u, 0.25, 1e-16);
    EXPECT_NEAR(to_uv(vec3_make(-1, 0, 0)).u, 0.5, 1e-16);
    EXPECT_NEAR(to_uv(vec3_make(0, -1, 0)).u, 0.75, 1e-16);
    EXPECT(to_uv(vec3_make(0, 0, 1)).v == 0);  /* zenith: top row */
    EXPECT(to_uv(vec3_make(0, 0, -1)).v == 1); /* nadir: bottom row */
    EXPECT(to_uv(vec3_make(0, 0, 1)).u == 0);  /* phi = 0 at the poles */
    /* ... also where x or y is -0 (a negated or rotated direction): atan2(0, -0) is pi and
     * atan2(-0, -0) is -pi, which would put the pole at u = 1/2 */
    EXPECT(to_uv(vec3_make(-0.0, 0, 1)).u == 0);
    EXPECT(to_uv(vec3_make(-0.0, -0.0, -1)).u == 0);
    EXPECT(to_uv(vec3_make(0, -0.0, 2)).u == 0);
    /* any length: (2, 2, 0) is phi = 45 degrees on the horizon */
    uv = to_uv(vec3_make(2, 2, 0));
    EXPECT_NEAR(uv.u, 0.125, 1e-16);
    EXPECT_NEAR(uv.v, 0.5, 1e-16);
    /* 45 degrees above the horizon towards -x */
    uv = to_uv(vec3_make(-1, 0, 1));
    EXPECT_NEAR(uv.u, 0.5, 1e-16);
    EXPECT_NEAR(uv.v, 0.25, 1e-16);
}
END_TEST

START_TEST(test_latlong_uv_to_dir_is_the_documented_formula)
{
    vec3 d = latlong_uv_to_dir((uv2){0.25, 0.5});
    EXPECT_NEAR(d.x, 0, 1e-15);
    EXPECT_NEAR(d.y, 1, 1e-15);
    EXPECT_NEAR(d.z, 0, 1e-15);
    d = latlong_uv_to_dir((uv2){0, 0});
    EXPECT(d.z == 1);
    d = latlong_uv_to_dir((uv2){0.6, 1});
    EXPECT(d.z == -1);
    /* column c's centre is at phi = 2 pi (c + 0.5) / W, row r's at theta = pi (r + 0.5) / H */
    const int w = 16, h = 8;
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) {
            vec3 e = latlong_uv_to_dir((uv2){(c + 0.5) / w, (r + 0.5) / h});
            double th = M_PI * (r + 0.5) / h, ph = 2 * M_PI * (c + 0.5) / w;
            EXPECT_NEAR(e.x, sin(th) * cos(ph), 1e-15);
            EXPECT_NEAR(e.y, sin(th) * sin(ph), 1e-15);
            EXPECT_NEAR(e.z, cos(th), 1e-15);
        }
}
END_TEST

START_TEST(test_latlong_roundtrip_is_exact_away_from_poles)
{
    rng g;
    rng_seed(&g, 51, 0);
    double worst = 0;
    for (int i = 0; i < 1000000; i++) {
        double z = 2 * rng_uniform(&g) - 1, phi = 2 * M_PI * rng_uniform(&g);
        if (fabs(z) > 0.999999) continue;
        double s = sqrt(1 - z * z);
        vec3 d = vec3_make(s * cos(phi), s * sin(phi), z);
        uv2 uv;
        EXPECT_INT_EQ(latlong_dir_to_uv(d, &uv), 0);
        EXPECT(uv.u >= 0 && uv.u < 1 && uv.v >= 0 && uv.v <= 1);
        worst = fmax(worst, vec3_angle(d, latlong_uv_to_dir(uv)));
    }
    EXPECT_MSG(worst < 1e-9, "worst round-trip error %g rad", worst);
}
END_TEST

START_TEST(test_latlong_roundtrip_is_exact_near_the_poles)
{
    /* acos(z) would lose everything here: z = cos(1e-8) rounds to 1 - 5e-17 ~ 1 */
    for (int k = 0; k < 16; k++) {
        double phi = 2 * M_PI * (k + 0.25) / 16;
        const double ths[] = {1e-8, 1e-12, M_PI - 1e-8};
        for (int j = 0; j < 3; j++) {
            double th = ths[j];
            vec3 d = vec3_make(sin(th) * cos(phi), sin(th) * sin(phi), cos(th));
            uv2 uv = to_uv(d);
            EXPECT_NEAR(uv.v * M_PI, th, 1e-15 * fmax(th, 1e-3));
            EXPECT_NEAR(uv.u, (k + 0.25) / 16, 1e-12);
            EXPECT(vec3_angle(d, latlong_uv_to_dir(uv)) < 1e-15);
        }
    }
}
END_TEST

START_TEST(test_latlong_seam_gives_u_in_0_to_1_never_1)
{
    const double ys[] = {-0.0, -1e-300, -1e-17, -1e-16, -5e-16, -1e-15, -1e-10};
    for (unsigned i = 0; i < sizeof ys / sizeof ys[0]; i++) {
        uv2 uv = to_uv(vec3_make(1, ys[i], 0.3));
        EXPECT_MSG(uv.u >= 0 && uv.u < 1, "y = %g gives u = %.17g", ys[i], uv.u);
        /* either 0 or just below 1: on the seam, never past it */
        EXPECT(uv.u == 0 || uv.u > 0.999999);
    }
    uv2 uv = to_uv(vec3_make(1, -1e-10, 0));
    EXPECT_NEAR(uv.u, 1 - 1e-10 / (2 * M_PI), 1e-16);
    /* and the nearest texel is then the last column or the first, never one past the end */
    image m = make_map(8, 4);
    for (int x = 0; x < 8; x++)
        for (int y = 0; y < 4; y++) image_set(&m, x, y, rgb_gray(x));
    for (unsigned i = 0; i < sizeof ys / sizeof ys[0]; i++) {
        double v = latlong_lookup_nearest(&m, vec3_make(1, ys[i], 0)).r;
        EXPECT(v == 0 || v == 7);
    }
    image_free(&m);
}
END_TEST

START_TEST(test_latlong_zero_and_nan_directions_are_rejected)
{
    uv2 uv = {7, 7};
    EXPECT_INT_EQ(latlong_dir_to_uv(vec3_make(0, 0, 0), &uv), -1);
    EXPECT_INT_EQ(latlong_dir_to_uv(vec3_make(-0.0, 0, -0.0), &uv), -1);
    EXPECT_INT_EQ(latlong_dir_to_uv(vec3_make(NAN, 0, 1), &uv), -1);
    EXPECT_INT_EQ(latlong_dir_to_uv(vec3_make(0, NAN, 1), &uv), -1);
    EXPECT_INT_EQ(latlong_dir_to_uv(vec3_make(0, 0, NAN), &uv), -1);
    EXPECT_INT_EQ(latlong_dir_to_uv(vec3_make(INFINITY, 0, 0), &uv), -1);
    EXPECT(uv.u == 7 && uv.v == 7); /* untouched */
    image m = make_map(4, 2);
    for (int i = 0; i < 4 * 2 * 3; i++) m.px[i] = 1;
    EXPECT(rgb_is_black(latlong_lookup_bilinear(&m, vec3_make(0, 0, 0))));
    EXPECT(rgb_is_black(latlong_lookup_bilinear(&m, vec3_make(NAN, 1, 0))));
    EXPECT(rgb_is_black(latlong_lookup_nearest(&m, vec3_make(0, 0, 0))));
    EXPECT(rgb_is_black(latlong_lookup_nearest(&m, vec3_make(1, 1, NAN))));
    image_free(&m);
}
END_TEST

START_TEST(test_latlong_accepts_directions_of_any_nonzero_length)
{
    /* the contract says any non-zero length: x^2 + y^2 must neither underflow nor overflow */
    uv2 uv = to_uv(vec3_make(1e-200, 1e-200, 0)); /* x^2 underflows to 0 */
    EXPECT_NEAR(uv.u, 0.125, 1e-15);
    EXPECT_NEAR(uv.v, 0.5, 1e-15);
    uv = to_uv(vec3_make(1e-200, 0, 1e-200));
    EXPECT_NEAR(uv.v, 0.25, 1e-15);
    uv = to_uv(vec3_make(1e300, 0, 1e300)); /* x^2 overflows to inf */
    EXPECT_NEAR(uv.v, 0.25, 1e-15);
    uv = to_uv(vec3_make(-3e-320, 0, 0)); /* a denormal */
    EXPECT_NEAR(uv.u, 0.5, 1e-15);
}
END_TEST

START_TEST(test_latlong_bilinear_wraps_across_the_phi_seam)
{
    /* first column 1, last column 3, the rest 10: at phi = 0 (+x) the seam lies halfway
     * between the two, so the lookup is exactly 2 */
    const int w = 8, h = 4;
    image m = make_map(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) image_set(&m, x, y, rgb_gray(x == 0 ? 1 : x == w - 1 ? 3 : 10));
    EXPECT(latlong_lookup_bilinear(&m, vec3_make(1, 0, 0)).g == 2);
    EXPECT(latlong_lookup_bilinear(&m, vec3_make(1, -0.0, 0.5)).g == 2);
    /* a quarter texel either side: 1.5 and 2.5 */
    double q = 2 * M_PI * 0.25 / w;
    EXPECT_NEAR(latlong_lookup_bilinear(&m, vec3_make(cos(q), sin(q), 0)).g, 1.5, 1e-12);
    EXPECT_NEAR(latlong_lookup_bilinear(&m, vec3_make(cos(q), -sin(q), 0)).g, 2.5, 1e-12);
    image_free(&m);
}
END_TEST

START_TEST(test_latlong_bilinear_clamps_at_the_poles)
{
    /* row r holds r + 1; the poles lie half a texel beyond the first and last row centres,
     * where the lookup must clamp (an out-of-range row is an ASan report) */
    const int w = 6, h = 3;
    image m = make_map(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) image_set(&m, x, y, rgb_make(y + 1, x, 0));
    EXPECT(latlong_lookup_bilinear(&m, vec3_make(0, 0, 1)).r == 1);
    EXPECT(latlong_lookup_bilinear(&m, vec3_make(0, 0, -1)).r == h);
    EXPECT(latlong_lookup_bilinear(&m, vec3_make(1e-9, 2e-9, 1)).r == 1);
    EXPECT(latlong_lookup_bilinear(&m, vec3_make(-1e-9, -2e-9, -1)).r == h);
    /* between the centres of rows 0 and 1 (theta = pi / h): the average */
    double th = M_PI / h;
    EXPECT_NEAR(latlong_lookup_bilinear(&m, vec3_make(sin(th), 0, cos(th))).r, 1.5, 1e-12);
    image_free(&m);
    /* a 1 x 1 map is constant, however it wraps and clamps */
    image one = make_map(1, 1);
    image_set(&one, 0, 0, rgb_make(4, 5, 6));
    rng g;
    rng_seed(&g, 52, 0);
    for (int i = 0; i < 1000; i++) {
        vec3 d = vec3_make(rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5);
        rgb c = latlong_lookup_bilinear(&one, d);
        EXPECT(c.r == 4 && c.g == 5 && c.b == 6);
    }
    image_free(&one);
}
END_TEST

START_TEST(test_latlong_lookups_at_texel_centres_return_the_texel)
{
    const int w = 12, h = 6;
    image m = make_map(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) image_set(&m, x, y, rgb_make(x, y, x * h + y));
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            vec3 d = latlong_uv_to_dir((uv2){(x + 0.5) / w, (y + 0.5) / h});
            rgb b = latlong_lookup_bilinear(&m, d), n = latlong_lookup_nearest(&m, d);
            EXPECT_NEAR(b.b, x * h + y, 1e-9);
            EXPECT(n.r == x && n.g == y);
            /* nearest anywhere inside the texel gives the texel */
            d = latlong_uv_to_dir((uv2){(x + 0.9) / w, (y + 0.1) / h});
            n = latlong_lookup_nearest(&m, d);
            EXPECT(n.r == x && n.g == y);
        }
    image_free(&m);
}
END_TEST

START_TEST(test_latlong_texel_solid_angles_sum_to_4_pi)
{
    const int sizes[][2] = {{1, 1}, {8, 4}, {512, 256}, {7, 13}, {4096, 2048}};
    for (unsigned k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        int w = sizes[k][0], h = sizes[k][1];
        double sum = 0;
        for (int r = 0; r < h; r++) {
            double a = latlong_texel_solid_angle(r, w, h);
            EXPECT(a > 0);
            EXPECT_NEAR(a, latlong_texel_solid_angle(h - 1 - r, w, h), 1e-15); /* symmetric */
            sum += a * w;
        }
        EXPECT_NEAR(sum, 4 * M_PI, 1e-12);
    }
    /* one row of a 2-row map is a hemisphere: 2 pi / w per texel */
    EXPECT_NEAR(latlong_texel_solid_angle(0, 4, 2), 2 * M_PI / 4, 1e-15);
}
END_TEST

Suite *latlong_suite(void)
{
    Suite *s = suite_create("latlong");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_latlong_axes_land_where_the_convention_says);
    tcase_add_test(tc, test_latlong_uv_to_dir_is_the_documented_formula);
    tcase_add_test(tc, test_latlong_roundtrip_is_exact_away_from_poles);
    tcase_add_test(tc, test_latlong_roundtrip_is_exact_near_the_poles);
    tcase_add_test(tc, test_latlong_seam_gives_u_in_0_to_1_never_1);
    tcase_add_test(tc, test_latlong_zero_and_nan_directions_are_rejected);
    tcase_add_test(tc, test_latlong_accepts_directions_of_any_nonzero_length);
    tcase_add_test(tc, test_latlong_bilinear_wraps_across_the_phi_seam);
    tcase_add_test(tc, test_latlong_bilinear_clamps_at_the_poles);
    tcase_add_test(tc, test_latlong_lookups_at_texel_centres_return_the_texel);
    tcase_add_test(tc, test_latlong_texel_solid_angles_sum_to_4_pi);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(latlong_suite)
