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

#include "envtex/genenv.h"
#include "envtex/gradetest.h"
#include "envtex/latlong.h"
#include "envtex/rng.h"
#include "envtex/sampling.h"

enum bug { CORRECT, NO_INV_PI, PDF_WITHOUT_SINTHETA, RR_NOT_DIVIDED, NO_COSINE };

#define W 24
#define H 24
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
        ck_assert_msg(r.pass, "seed %lu: %s (failed %ld, Z %.2f)", (unsigned long)seed, r.why, r.failed, r.mean_z);
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
    ck_assert_msg(!r.pass, "a pdf without sin theta passed (failed %ld, Z %.2f)", r.failed, r.mean_z);
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

static Suite *gradetest_suite(void)
{
    Suite *s = suite_create("gradetest");
    TCase *tc = tcase_create("core");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 30);
    tcase_add_test(tc, test_gradetest_passes_a_correct_render_with_other_seeds);
    tcase_add_test(tc, test_gradetest_fails_a_missing_one_over_pi);
    tcase_add_test(tc, test_gradetest_fails_a_pdf_off_by_sin_theta);
    tcase_add_test(tc, test_gradetest_fails_russian_roulette_without_division);
    tcase_add_test(tc, test_gradetest_fails_a_forgotten_cosine);
    tcase_add_test(tc, test_gradetest_fails_nan_pixels_and_refuses_mismatched_sizes);
    tcase_add_test(tc, test_gradetest_z_threshold_inverts_the_normal_tail);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(gradetest_suite)
