/* test_gradetest.c - the noise-aware grading test (gradetest.h) against renders made by a tiny
 * "student" estimator: the irradiance-like integral L_o(n) = integral of rho/pi L(w) max(n.w, 0) dw
 * for a diffuse surface whose normal n varies over the image, lit by a smooth sky.  The correct
 * estimator (cosine sampling) with another seed must pass; the classic student bugs must fail:
 *   - a missing 1/pi in the diffuse BRDF,
 *   - a pdf off by sin theta (theta sampled uniformly, the Jacobian forgotten),
 *   - Russian roulette without dividing by the survival probability,
 *   - the cosine term forgotten. */
#include "unit.h"

#include <string.h>

#include "envtex/envmaps/genenv.h"
#include "envtex/render/gradetest.h"
#include "envtex/envmaps/latlong.h"
#include "envtex/core/rng.h"
#include "envtex/core/sampling.h"

enum bug { CORRECT, NO_INV_PI, PDF_WITHOUT_SINTHETA, RR_NOT_DIVIDED, NO_COSINE };

#define W   24
#define H   24
#define SPP 64

static image sky;

static void setup(void)
{
    genenv_params p = genenv_defaults();
    p.width = 64;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_SKY, &p, &sky, &err), 0);
}

static void teardown(void) { image_free(&sky); }

/* the normal of pixel (x, y): a hemisphere of normals seen from above, like a ball's */
static vec3 pixel_normal(int x, int y)
{
    double a = (x + 0.5) / W * 2 - 1, b = (y + 0.5) / H * 2 - 1;
    double r2 = fmin(a * a + b * b, 0.95);
    return vec3_normalize(vec3_make(a, b, sqrt(1 - r2)));
}

/* one sample of the estimator, with the bug */
static double sample(vec3 n, enum bug bug, rng *g)
{
    const double rho = 0.7;
    double xi1 = rng_uniform(g), xi2 = rng_uniform(g);
    vec3 l;
    double pdf;
    if (bug == PDF_WITHOUT_SINTHETA) {
        double theta = xi1 * M_PI / 2, phi = 2 * M_PI * xi2; /* uniform in (theta, phi) */
        l = vec3_make(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
        pdf = 1 / (M_PI * M_PI); /* 1 / (2 pi * pi/2): the 1 / sin theta is missing */
    } else {
        l = sampling_cosine_hemisphere(xi1, xi2);
        pdf = sampling_cosine_hemisphere_pdf(l.z);
    }
    vec3 w = sampling_to_world(l, n);
    double cos_t = vec3_dot(w, n);
    if (cos_t <= 0 || !(pdf > 0)) return 0;
    double L = rgb_avg(latlong_lookup_bilinear(&sky, w));
    double f = bug == NO_INV_PI ? rho : rho / M_PI;
    double v = f * L * (bug == NO_COSINE ? 1 : cos_t) / pdf;
    if (bug == RR_NOT_DIVIDED) {
        const double q = 0.8; /* survive with q ... and forget to divide by it */
        if (!(rng_uniform(g) < q)) return 0;
    }
    return v;
}

/* mean image and variance of the mean, as `envtex render --variance` makes them */
static void render(enum bug bug, uint64_t seed, image *img, image *var)
{
    error err = {0};
    ck_assert_int_eq(image_alloc(img, W, H, &err), 0);
    if (var) ck_assert_int_eq(image_alloc(var, W, H, &err), 0);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            rng g;
            rng_seed(&g, seed, (uint64_t)(y * W + x));
            double s = 0, s2 = 0;
            for (int k = 0; k < SPP; k++) {
                double v = sample(pixel_normal(x, y), bug, &g);
                s += v;
                s2 += v * v;
            }
            double mean = s / SPP, svar = (s2 - SPP * mean * mean) / (SPP - 1);
            image_set(img, x, y, rgb_gray(mean));
            if (var) image_set(var, x, y, rgb_gray(fmax(0.0, svar) / SPP));
        }
}

static gradetest_result grade(enum bug bug, uint64_t seed)
{
    image ref, var, img;
    render(CORRECT, 1, &ref, &var);
    render(bug, seed, &img, NULL);
    gradetest_params p = gradetest_defaults();
    gradetest_result r;
    error err = {0};
    ck_assert_int_eq(gradetest_run(&img, &ref, &var, &p, &r, NULL, &err), 0);
    image_free(&ref);
    image_free(&var);
    image_free(&img);
    return r;
}

START_TEST(test_gradetest_passes_a_correct_render_with_other_seeds)
{
    for (uint64_t seed = 2; seed < 7; seed++) {
        gradetest_result r = grade(CORRECT, seed);
        ck_assert_msg(r.pass, "seed %lu: %s (failed %ld, Z %.2f)", (unsigned long)seed, r.why,
                      r.failed, r.mean_z);
    }
}
END_TEST

START_TEST(test_gradetest_fails_a_missing_one_over_pi)
{
    gradetest_result r = grade(NO_INV_PI, 2);
    ck_assert_msg(!r.pass, "a missing 1/pi passed (failed %ld, Z %.2f)", r.failed, r.mean_z);
}
END_TEST

START_TEST(test_gradetest_fails_a_pdf_off_by_sin_theta)
{
    gradetest_result r = grade(PDF_WITHOUT_SINTHETA, 2);
    ck_assert_msg(!r.pass, "a pdf without sin theta passed (failed %ld, Z %.2f)", r.failed,
                  r.mean_z);
}
END_TEST

START_TEST(test_gradetest_fails_russian_roulette_without_division)
{
    gradetest_result r = grade(RR_NOT_DIVIDED, 2);
    ck_assert_msg(!r.pass, "roulette without 1/q passed (failed %ld, Z %.2f)", r.failed, r.mean_z);
}
END_TEST

START_TEST(test_gradetest_fails_a_forgotten_cosine)
{
    gradetest_result r = grade(NO_COSINE, 2);
    ck_assert_msg(!r.pass, "a forgotten cosine passed (failed %ld, Z %.2f)", r.failed, r.mean_z);
}
END_TEST

START_TEST(test_gradetest_fails_nan_pixels_and_refuses_mismatched_sizes)
{
    image ref, var, img, small;
    render(CORRECT, 1, &ref, &var);
    render(CORRECT, 2, &img, NULL);
    image_set(&img, 3, 3, rgb_gray(NAN));
    gradetest_params p = gradetest_defaults();
    gradetest_result r;
    error err = {0};
    ck_assert_int_eq(gradetest_run(&img, &ref, &var, &p, &r, NULL, &err), 0);
    ck_assert(!r.pass);
    ck_assert_int_eq(r.nonfinite, 1);
    ck_assert_int_eq(image_alloc(&small, 2, 2, &err), 0);
    ck_assert_int_eq(gradetest_run(&small, &ref, &var, &p, &r, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "sizes differ"));
    image_free(&ref);
    image_free(&var);
    image_free(&img);
    image_free(&small);
}
END_TEST

START_TEST(test_gradetest_z_threshold_inverts_the_normal_tail)
{
    ck_assert_near(gradetest_z_for_alpha(0.05), 1.959964, 1e-5);
    ck_assert_near(gradetest_z_for_alpha(0.01), 2.575829, 1e-5);
    ck_assert_near(erfc(gradetest_z_for_alpha(1e-7) / sqrt(2.0)), 1e-7, 1e-12);
}
END_TEST

/* ---- the statistic itself, on synthetic images with known numbers ------------------------
 * The renders above catch gross bugs by every route at once (many pixels, the image total); the
 * tests below pin each documented term of gradetest.h on its own, so that a grader who relies on
 * its false-alarm rate relies on the formula the header gives. */

enum { SW = 10, SH = 10 }; /* N = 100 pixels */

/* ref = r and var = v everywhere, img = ref */
static void synthetic(double r, double v, image *img, image *ref, image *var)
{
    error err = {0};
    ck_assert_int_eq(image_alloc(img, SW, SH, &err), 0);
    ck_assert_int_eq(image_alloc(ref, SW, SH, &err), 0);
    ck_assert_int_eq(image_alloc(var, SW, SH, &err), 0);
    for (int y = 0; y < SH; y++)
        for (int x = 0; x < SW; x++) {
            image_set(img, x, y, rgb_gray(r));
            image_set(ref, x, y, rgb_gray(r));
            image_set(var, x, y, rgb_gray(v));
        }
}

static void free3(image *a, image *b, image *c)
{
    image_free(a);
    image_free(b);
    image_free(c);
}

static gradetest_result run_ok(const image *img, const image *ref, const image *var,
                               const gradetest_params *p, image *map)
{
    gradetest_result r;
    error err = {0};
    ck_assert_msg(gradetest_run(img, ref, var, p, &r, map, &err) == 0, "%s", err.msg);
    return r;
}

/* z = (img - ref) / sqrt(V (ref_spp / img_spp + 1) + floor^2), failing beyond Phi^-1(1 - alpha / 2N),
 * on both sides: a pixel just inside the threshold passes, one just outside fails, either way. */
START_TEST(test_gradetest_pixel_z_uses_both_variances_scaled_by_the_spp_ratio)
{
    image img, ref, var;
    synthetic(1.0, 0.01, &img, &ref, &var);
    gradetest_params p = gradetest_defaults();
    p.img_spp = 16;
    p.ref_spp = 64;   /* var_img = 4 V */
    p.global_z = 1e9; /* the image total is tested below */
    double thr = gradetest_z_for_alpha(p.alpha / (SW * SH));
    double floor_sd = p.rel_floor * 1.0;
    double sd = sqrt(0.01 * (4 + 1) + floor_sd * floor_sd);
    const double side[2] = {1, -1};
    for (int k = 0; k < 2; k++) {
        image_set(&img, 4, 6, rgb_gray(1.0 + side[k] * 0.999 * thr * sd));
        gradetest_result r = run_ok(&img, &ref, &var, &p, NULL);
        ck_assert_msg(r.failed == 0, "side %g: |z| just below the threshold failed", side[k]);
        ck_assert_near(r.z_threshold, thr, 1e-12);
        image_set(&img, 4, 6, rgb_gray(1.0 + side[k] * 1.001 * thr * sd));
        r = run_ok(&img, &ref, &var, &p, NULL);
        ck_assert_msg(r.failed == 1, "side %g: |z| just above the threshold passed", side[k]);
    }
    free3(&img, &ref, &var);
}
END_TEST

/* A VAR of var_spp samples (the image's own --variance, not the reference's): V var_spp is the
 * variance of one sample, so var of (img - ref) = V (var_spp / img_spp + var_spp / ref_spp). */
START_TEST(test_gradetest_variance_of_another_render_is_scaled_by_its_own_spp)
{
    image img, ref, var;
    synthetic(1.0, 0.01, &img, &ref, &var);
    gradetest_params p = gradetest_defaults();
    p.img_spp = 64;
    p.ref_spp = 1024;
    p.var_spp = 64; /* VAR is the image's: var_img = V, var_ref = V / 16 */
    p.global_z = 1e9;
    double thr = gradetest_z_for_alpha(p.alpha / (SW * SH));
    double floor_sd = p.rel_floor * 1.0;
    double sd = sqrt(0.01 * (1 + 1.0 / 16) + floor_sd * floor_sd);
    image_set(&img, 3, 5, rgb_gray(1.0 + 0.999 * thr * sd));
    ck_assert_int_eq(run_ok(&img, &ref, &var, &p, NULL).failed, 0);
    image_set(&img, 3, 5, rgb_gray(1.0 + 1.001 * thr * sd));
    ck_assert_int_eq(run_ok(&img, &ref, &var, &p, NULL).failed, 1);
    /* var_spp 0 is the reference's: V (1024 / 64 + 1), far wider, so the same pixel passes */
    p.var_spp = 0;
    ck_assert_int_eq(run_ok(&img, &ref, &var, &p, NULL).failed, 0);
    p.var_spp = -1;
    gradetest_result r;
    error err = {0};
    ck_assert_int_eq(gradetest_run(&img, &ref, &var, &p, &r, NULL, &err), -1);
    free3(&img, &ref, &var);
}
END_TEST

/* Where the variance is 0 (a constant background) only the floor rel_floor max(|ref|, 1e-3)
 * stands between float rounding and a failure, including where the reference is black. */
START_TEST(test_gradetest_zero_variance_pixels_get_the_relative_floor)
{
    const double refs[2] = {2.0, 0.0};
    for (int k = 0; k < 2; k++) {
        image img, ref, var;
        synthetic(refs[k], 0.0, &img, &ref, &var);
        gradetest_params p = gradetest_defaults();
        p.global_z = 1e9;
        double thr = gradetest_z_for_alpha(p.alpha / (SW * SH));
        double floor_sd = p.rel_floor * fmax(refs[k], 1e-3); /* sqrt(2) V = 0 */
        image_set(&img, 2, 2, rgb_gray(refs[k] + 0.99 * thr * floor_sd));
        gradetest_result r = run_ok(&img, &ref, &var, &p, NULL);
        ck_assert_msg(r.failed == 0, "ref %g: within the floor failed", refs[k]);
        image_set(&img, 2, 2, rgb_gray(refs[k] + 1.01 * thr * floor_sd));
        r = run_ok(&img, &ref, &var, &p, NULL);
        ck_assert_msg(r.failed == 1, "ref %g: beyond the floor passed", refs[k]);
        free3(&img, &ref, &var);
    }
}
END_TEST

/* A pixel's V is the largest of its 3 x 3 neighbourhood: a pixel whose own variance came out 0
 * is tested with the neighbour's, whichever side that neighbour is on. */
START_TEST(test_gradetest_pixel_variance_is_the_neighbourhood_largest)
{
    const int nb[4][2] = {{0, -1}, {0, 1}, {-1, 0}, {1, 1}};
    for (int k = 0; k < 4; k++) {
        image img, ref, var;
        synthetic(1.0, 0.0, &img, &ref, &var);
        gradetest_params p = gradetest_defaults();
        p.global_z = 1e9;
        image_set(&var, 5 + nb[k][0], 5 + nb[k][1], rgb_gray(0.04));
        image_set(&img, 5, 5, rgb_gray(1.0 + 0.2)); /* z = 0.2 / sqrt(2 x 0.04) = 0.71 */
        gradetest_result r = run_ok(&img, &ref, &var, &p, NULL);
        ck_assert_msg(r.failed == 0, "neighbour (%d, %d): its variance was not used", nb[k][0],
                      nb[k][1]);
        free3(&img, &ref, &var);
    }
}
END_TEST

/* The image total, Z = sum (img - ref) / sqrt(sum (V_own (ratio + 1) + floor^2)), with each
 * pixel's OWN variance: a small bias everywhere fails it (and the render) although no pixel
 * fails; its sign is kept in mean_z, and |Z| = global_z exactly still passes. */
START_TEST(test_gradetest_image_total_catches_a_thin_bias_with_own_variances)
{
    image img, ref, var;
    synthetic(1.0, 0.0, &img, &ref, &var);
    gradetest_params p = gradetest_defaults();
    const double bias[2] = {0.08, -0.08};
    for (int k = 0; k < 2; k++) {
        double sum_d = 0, sum_v = 0, fl = p.rel_floor * 1.0;
        for (int y = 0; y < SH; y++)
            for (int x = 0; x < SW; x++) {
                double v = (x + y) % 2
                               ? 0.01
                               : 0.0025; /* a checker: each pixel's neighbourhood max is 0.01 */
                image_set(&var, x, y, rgb_gray(v));
                image_set(&img, x, y, rgb_gray(1.0 + bias[k]));
                sum_d += image_get(&img, x, y).r - 1.0; /* the stored floats */
                sum_v += image_get(&var, x, y).r * 2 + fl * fl;
            }
        gradetest_result r = run_ok(&img, &ref, &var, &p, NULL);
        ck_assert_int_eq(r.failed, 0); /* |z| = 0.08 / sqrt(0.02) = 0.57 per pixel; |Z| = 7.2 */
        ck_assert_near(r.mean_z, sum_d / sqrt(sum_v), 1e-9 * fabs(sum_d / sqrt(sum_v)));
        ck_assert_near(r.global_stat, fabs(sum_d / sqrt(sum_v)), 1e-9);
        ck_assert_msg(r.global_stat > p.global_z && !r.pass, "a bias of %g passed (Z %.2f)",
                      bias[k], r.mean_z);
        ck_assert_ptr_nonnull(strstr(r.why, "mean z"));
        gradetest_params q = p;
        q.global_z = r.global_stat; /* the bound itself passes */
        gradetest_result r2 = run_ok(&img, &ref, &var, &q, NULL);
        ck_assert_msg(r2.pass, "|Z| equal to global_z failed: %s", r2.why);
    }
    free3(&img, &ref, &var);
}
END_TEST

/* max_fail_fraction is inclusive; a NaN pixel counts among the failed ones and fails the render
 * whatever the fraction; the map marks too bright red, too dark blue, NaN magenta, the rest grey. */
START_TEST(test_gradetest_failed_fraction_nan_pixels_and_the_map)
{
    image img, ref, var, map;
    synthetic(1.0, 0.01, &img, &ref, &var);
    gradetest_params p = gradetest_defaults();
    p.global_z = 1e9;
    image_set(&img, 1, 1, rgb_gray(1.0 + 10));
    image_set(&img, 8, 8, rgb_gray(1.0 - 10));
    p.max_fail_fraction = 2.0 / (SW * SH);
    gradetest_result r = run_ok(&img, &ref, &var, &p, &map);
    ck_assert_int_eq(r.failed, 2);
    ck_assert_msg(r.pass, "2 failed pixels of 100 with 2%% allowed: %s", r.why);
    rgb red = image_get(&map, 1, 1), blue = image_get(&map, 8, 8), grey = image_get(&map, 5, 5);
    ck_assert(red.r == 1 && red.g == 0 && red.b == 0);
    ck_assert(blue.r == 0 && blue.b == 1);
    ck_assert(grey.r == grey.g && grey.g == grey.b && grey.r > 0 && grey.r < 1);
    image_free(&map);
    p.max_fail_fraction = 1.999 / (SW * SH);
    ck_assert(!run_ok(&img, &ref, &var, &p, NULL).pass);

    image_set(&img, 8, 8, rgb_gray(NAN));
    p.max_fail_fraction = 0.5;
    r = run_ok(&img, &ref, &var, &p, &map);
    ck_assert_int_eq(r.nonfinite, 1);
    ck_assert_int_eq(r.failed, 2); /* the bright one and the NaN */
    ck_assert_near(r.failed_fraction, 0.02, 1e-15);
    ck_assert(!r.pass);
    rgb mag = image_get(&map, 8, 8);
    ck_assert(mag.r == 1 && mag.g == 0 && mag.b == 1);
    image_free(&map);
    free3(&img, &ref, &var);
}
END_TEST

/* What cannot be tested is an error, not a verdict: a variance image of another size, a sample
 * count <= 0, a negative variance. */
START_TEST(test_gradetest_refuses_what_it_cannot_test)
{
    image img, ref, var, small;
    synthetic(1.0, 0.01, &img, &ref, &var);
    gradetest_params p = gradetest_defaults();
    gradetest_result r;
    error err = {0};
    ck_assert_int_eq(image_alloc(&small, 3, SH, &err), 0);
    ck_assert_int_eq(gradetest_run(&img, &ref, &small, &p, &r, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "sizes differ"));
    p.img_spp = 0;
    ck_assert_int_eq(gradetest_run(&img, &ref, &var, &p, &r, NULL, &err), -1);
    p = gradetest_defaults();
    p.ref_spp = NAN;
    ck_assert_int_eq(gradetest_run(&img, &ref, &var, &p, &r, NULL, &err), -1);
    p = gradetest_defaults();
    image_set(&var, 7, 2, rgb_gray(-1e-6));
    ck_assert_int_eq(gradetest_run(&img, &ref, &var, &p, &r, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "(7, 2)"));
    image_free(&small);
    free3(&img, &ref, &var);
}
END_TEST

/* Phi^-1(1 - a/2) at the ends of its domain: a >= 1 needs no evidence (0), a <= 0 or NaN can
 * never be reached (the largest z, 40). */
START_TEST(test_gradetest_z_threshold_at_the_ends)
{
    ck_assert(gradetest_z_for_alpha(1) == 0);
    ck_assert(gradetest_z_for_alpha(3) == 0);
    ck_assert(gradetest_z_for_alpha(0) == 40);
    ck_assert(gradetest_z_for_alpha(-1) == 40);
    ck_assert(gradetest_z_for_alpha(NAN) == 40);
    ck_assert(gradetest_z_for_alpha(0.5) < gradetest_z_for_alpha(0.1));
}
END_TEST

static Suite *gradetest_suite(void)
{
    Suite *s = suite_create("gradetest");
    TCase *tc = tcase_create("core");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, test_gradetest_passes_a_correct_render_with_other_seeds);
    tcase_add_test(tc, test_gradetest_fails_a_missing_one_over_pi);
    tcase_add_test(tc, test_gradetest_fails_a_pdf_off_by_sin_theta);
    tcase_add_test(tc, test_gradetest_fails_russian_roulette_without_division);
    tcase_add_test(tc, test_gradetest_fails_a_forgotten_cosine);
    tcase_add_test(tc, test_gradetest_fails_nan_pixels_and_refuses_mismatched_sizes);
    tcase_add_test(tc, test_gradetest_z_threshold_inverts_the_normal_tail);
    tcase_add_test(tc, test_gradetest_pixel_z_uses_both_variances_scaled_by_the_spp_ratio);
    tcase_add_test(tc, test_gradetest_variance_of_another_render_is_scaled_by_its_own_spp);
    tcase_add_test(tc, test_gradetest_zero_variance_pixels_get_the_relative_floor);
    tcase_add_test(tc, test_gradetest_pixel_variance_is_the_neighbourhood_largest);
    tcase_add_test(tc, test_gradetest_image_total_catches_a_thin_bias_with_own_variances);
    tcase_add_test(tc, test_gradetest_failed_fraction_nan_pixels_and_the_map);
    tcase_add_test(tc, test_gradetest_refuses_what_it_cannot_test);
    tcase_add_test(tc, test_gradetest_z_threshold_at_the_ends);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(gradetest_suite)
