/* test_sampling.c - direction samplers and their pdfs (include/envtex/core/sampling.h).
 *
 * Each sampler is tested against its own pdf with a Pearson chi-square test over equal solid
 * angle bins in (cos theta, phi) (sphchisq.h): expected counts are the pdf integrated over each
 * bin, so a sampler whose warp does not produce the density its pdf claims fails.  The pdfs are
 * checked to integrate to 1, the warps at the ends of [0, 1) to give unit directions in the right
 * hemisphere, and sampling_to_world to be a rotation taking +z to n.
 */
#include "envtex/core/sampling.h"

#include <stddef.h>
#include <stdint.h>

#include "chisq.h"
#include "envtex/core/rng.h"
#include "sphchisq.h"
#include "unit.h"

#define N_SAMPLES 200000L /* per chi-square test: a 3% error in a 1% bin is ~4 sigma */
#define N_U       16      /* bins in cos theta ... */
#define N_PHI     32      /* ... and in phi: 512 bins of equal solid angle */
/* integral of a pdf: the quadrature is good to ~1e-5 on the sharpest lobe (GGX alpha 0.05); a
 * wrong constant, (s+2) for (s+1), is off by > 1e-3 */
#define NORM_TOL 1e-4
#define GL_SUB                                                                                     \
    12                 /* Gauss-Legendre sub-intervals per bin: the top bin spans 29 degrees
                           * of theta and a GGX alpha = 0.05 lobe only ~3 */
#define UNIT_TOL 1e-12 /* |w| - 1 of a warped direction: a few roundings */

/* the chi-square tests of this program, for the Bonferroni correction (chisq.h) */
enum { N_PHONG = 4, N_GGX = 4 };
static const double phong_s[N_PHONG] = {1, 10, 50, 200};
static const double ggx_alpha[N_GGX] = {0.05, 0.2, 0.5, 1.0};
#define N_CHISQ_TESTS (4 + N_PHONG + N_GGX) /* sphere, hemisphere, cosine, tilted cosine */

typedef enum which { W_SPHERE, W_HEMI, W_COSINE, W_COSINE_TILTED, W_PHONG, W_GGX } which;

typedef struct sampler {
    which kind;
    double param;
    vec3 n;
} sampler;

static vec3 draw(const sampler *s, double xi1, double xi2)
{
    switch (s->kind) {
    case W_SPHERE: return sampling_uniform_sphere(xi1, xi2);
    case W_HEMI: return sampling_uniform_hemisphere(xi1, xi2);
    case W_COSINE: return sampling_cosine_hemisphere(xi1, xi2);
    case W_COSINE_TILTED: return sampling_to_world(sampling_cosine_hemisphere(xi1, xi2), s->n);
    case W_PHONG: return sampling_phong_lobe(s->param, xi1, xi2);
    default: return sampling_ggx_half(s->param, xi1, xi2);
    }
}

static double pdf_of(void *ctx, vec3 w)
{
    const sampler *s = ctx;
    switch (s->kind) {
    case W_SPHERE: return sampling_uniform_sphere_pdf();
    case W_HEMI: return sampling_uniform_hemisphere_pdf(w.z);
    case W_COSINE: return sampling_cosine_hemisphere_pdf(w.z);
    case W_COSINE_TILTED: return sampling_cosine_hemisphere_pdf(vec3_dot(w, s->n));
    case W_PHONG: return sampling_phong_lobe_pdf(s->param, w.z);
    default: return sampling_ggx_d(s->param, w.z) * w.z; /* pdf_h = D(h) cos(theta_h) */
    }
}

static const char *name_of(which k)
{
    static const char *names[] = {
        "uniform sphere", "uniform hemisphere", "cosine", "tilted cosine", "phong", "ggx"};
    return names[k];
}

/* chi-square of N_SAMPLES draws against the pdf; also the pdf's integral must be 1 */
static void check_sampler(const sampler *s, uint64_t seed)
{
    static double prob[SPH_MAX_BINS + 1];
    static long obs[SPH_MAX_BINS + 1];
    sph_grid g = sph_grid_make(N_U, N_PHI);
    g.sub = GL_SUB;
    double total = sph_expected(&g, pdf_of, (void *)s, prob);
    ck_assert_msg(fabs(total - 1) < NORM_TOL, "%s (%g): pdf integrates to %.9f", name_of(s->kind),
                  s->param, total);
    int nb = sph_n_bins(&g);
    for (int k = 0; k < nb; k++) obs[k] = 0;
    rng r;
    rng_seed(&r, seed, 1);
    long not_unit = 0;
    for (long i = 0; i < N_SAMPLES; i++) {
        vec3 w = draw(s, rng_uniform(&r), rng_uniform(&r));
        not_unit += !(fabs(vec3_length(w) - 1) < UNIT_TOL);
        obs[sph_bin(&g, w)]++;
    }
    ck_assert_msg(not_unit == 0, "%s: %ld directions are not unit", name_of(s->kind), not_unit);
    chisq_result res = chisq_test(obs, prob, nb, N_SAMPLES);
    ck_assert_msg(chisq_accept(&res, N_CHISQ_TESTS), "%s (%g): X^2 = %g, dof %d, p = %g, stray %ld",
                  name_of(s->kind), s->param, res.stat, res.dof, res.p, res.stray);
}

START_TEST(test_sampling_uniform_sphere_fits_its_pdf)
{
    sampler s = {W_SPHERE, 0, {0, 0, 1}};
    check_sampler(&s, 1);
}
END_TEST

START_TEST(test_sampling_uniform_hemisphere_fits_its_pdf)
{
    sampler s = {W_HEMI, 0, {0, 0, 1}};
    check_sampler(&s, 2);
}
END_TEST

START_TEST(test_sampling_cosine_hemisphere_fits_its_pdf)
{
    sampler s = {W_COSINE, 0, {0, 0, 1}};
    check_sampler(&s, 3);
}
END_TEST

/* the same through sampling_to_world with a normal far from the axes: catches a basis that is
 * not orthonormal or maps +z elsewhere */
START_TEST(test_sampling_cosine_around_a_tilted_normal_fits_its_pdf)
{
    sampler s = {W_COSINE_TILTED, 0, vec3_normalize(vec3_make(0.3, -0.5, -0.81))};
    check_sampler(&s, 4);
}
END_TEST

START_TEST(test_sampling_phong_lobe_fits_its_pdf)
{
    sampler s = {W_PHONG, phong_s[_i], {0, 0, 1}};
    check_sampler(&s, 10 + (uint64_t)_i);
}
END_TEST

START_TEST(test_sampling_ggx_half_vector_fits_d_cos)
{
    sampler s = {W_GGX, ggx_alpha[_i], {0, 0, 1}};
    check_sampler(&s, 20 + (uint64_t)_i);
}
END_TEST

/* xi = 0, the largest values rng_uniform gives, the largest double below 1, and exactly 1 (the
 * clamp): every warp still gives a finite unit direction, in the upper hemisphere where it must */
START_TEST(test_sampling_edge_random_numbers_give_unit_directions_in_the_right_hemisphere)
{
    const double xs[] = {0.0, 0x1p-32, 0.5, 1 - 0x1p-24, 1 - 0x1p-32, 0x1.fffffffffffffp-1, 1.0};
    int n = (int)(sizeof xs / sizeof xs[0]), bad = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            vec3 w[6] = {
                sampling_uniform_sphere(xs[i], xs[j]),    sampling_uniform_hemisphere(xs[i], xs[j]),
                sampling_cosine_hemisphere(xs[i], xs[j]), sampling_phong_lobe(30, xs[i], xs[j]),
                sampling_ggx_half(0.3, xs[i], xs[j]),     sampling_ggx_half(1.0, xs[i], xs[j])};
            for (int k = 0; k < 6; k++) {
                bad += !vec3_is_finite(w[k]) || !(fabs(vec3_length(w[k]) - 1) < UNIT_TOL);
                bad += k > 0 && !(w[k].z >= 0);
            }
        }
    ck_assert_int_eq(bad, 0);
}
END_TEST

/* the pdfs are 0 where their sampler never goes (below the hemisphere / lobe) */
START_TEST(test_sampling_pdfs_vanish_below_their_hemisphere)
{
    ck_assert(sampling_uniform_hemisphere_pdf(-0.1) == 0);
    ck_assert(sampling_cosine_hemisphere_pdf(-0.1) == 0);
    ck_assert(sampling_cosine_hemisphere_pdf(0) == 0);
    ck_assert(sampling_phong_lobe_pdf(10, -0.2) == 0);
    ck_assert(sampling_ggx_d(0.3, -0.2) == 0);
    ck_assert(sampling_ggx_d(0.3, 0) == 0);
    ck_assert_near(sampling_uniform_sphere_pdf(), 1 / (4 * M_PI), 1e-15);
    ck_assert_near(sampling_uniform_hemisphere_pdf(0.3), 1 / (2 * M_PI), 1e-15);
}
END_TEST

/* GGX with alpha = 0 is the mirror limit, alpha = SAMPLING_GGX_ALPHA_MIN: at the axis D is the
 * finite peak 1 / (pi alpha^2), also for a cosine that rounded to 1 + 2^-52, and off the axis
 * next to nothing.  Catches alpha = 0 kept as 0 (D = 0 everywhere: a smooth GGX ball renders
 * black) and a cosine above 1 not clamped (1 - c^2 < 0 outweighs alpha^2 c^2: D = 0 or
 * negative at the peak, the lost samples of a mirror-like lobe). */
START_TEST(test_sampling_ggx_d_with_zero_roughness_is_the_mirror_limit)
{
    double a = SAMPLING_GGX_ALPHA_MIN, peak = 1 / (M_PI * a * a);
    ck_assert_double_eq_tol(sampling_ggx_d(0, 1), peak, 1e-12 * peak);
    ck_assert_double_eq_tol(sampling_ggx_d(0, 1 + 0x1p-52), peak, 1e-12 * peak);
    ck_assert_double_eq_tol(sampling_ggx_d(1e-300, 1 + 0x1p-52), peak, 1e-12 * peak);
    ck_assert_double_eq_tol(sampling_ggx_d(1e-9, 1 + 0x1p-52), peak, 1e-12 * peak);
    ck_assert(sampling_ggx_d(0, 0.5) >= 0 && sampling_ggx_d(0, 0.5) < 1e-15);
    ck_assert(sampling_ggx_d(0, NAN) == 0);
    /* D integrates to 1 over projected area: D(alpha, 1) = 1 / (pi alpha^2) at the peak */
    ck_assert_near(sampling_ggx_d(0.5, 1) * M_PI * 0.25, 1, 1e-12);
}
END_TEST

/* The Phong lobe pdf at its axis with a cosine that rounded above 1 (r.wi of two unit vectors
 * can be 1 + 2^-52) is the peak (s + 1) / (2 pi), for a huge shininess too.  Catches the cosine
 * not clamped to <= 1: (1 + 2^-52)^1e18 = Inf, and at s = 1e15 a peak 1.25 times too high. */
START_TEST(test_sampling_phong_pdf_treats_a_cosine_rounded_above_one_as_the_axis)
{
    const double shin[] = {10, 1e15, 1e18, 1e300};
    for (int i = 0; i < 4; i++) {
        double s = shin[i], peak = (s + 1) / (2 * M_PI);
        ck_assert_near(sampling_phong_lobe_pdf(s, 1.0), peak, 1e-15 * peak);
        ck_assert_near(sampling_phong_lobe_pdf(s, 1 + 0x1p-52), peak, 1e-15 * peak);
    }
}
END_TEST

/* Every roughness the parser accepts (any finite alpha >= 0) gives a finite D and unit half
 * vectors in the upper hemisphere, at the peak, off it and near the horizon.  Catches alpha^2
 * overflowing (alpha > 1e154: D = Inf / Inf) and D's peak 1 / (pi alpha^2) overflowing (alpha
 * below ~1e-81, where (alpha^2)^2 underflows, and below 1e-154). */
START_TEST(test_sampling_ggx_is_finite_for_every_roughness_the_parser_accepts)
{
    const double alphas[] = {0,     4.9e-324, 1e-300, 1e-160, 1e-100,
                             1e-20, 1e-9,     0.3,    1e10,   1e30,
                             1e154, 1e155,    1e200,  1e300,  1.7976931348623157e308};
    const double cosines[] = {1.0, 1 - 0x1p-53, 0.9, 0.5, 1e-8, 1e-160, 4.9e-324};
    const double xs[] = {0.0, 0x1p-53, 0x1p-32, 0.5, 1 - 0x1p-32, 0x1.fffffffffffffp-1};
    int bad = 0;
    for (int i = 0; i < (int)(sizeof alphas / sizeof alphas[0]); i++) {
        double a = alphas[i];
        for (int k = 0; k < (int)(sizeof cosines / sizeof cosines[0]); k++) {
            double d = sampling_ggx_d(a, cosines[k]);
            bad += !(isfinite(d) && d >= 0);
        }
        for (int k = 0; k < (int)(sizeof xs / sizeof xs[0]); k++) {
            vec3 h = sampling_ggx_half(a, xs[k], 0.3);
            bad += !vec3_is_finite(h) || !(fabs(vec3_length(h) - 1) < UNIT_TOL) || !(h.z >= 0);
            bad += !isfinite(sampling_ggx_d(a, h.z) * h.z); /* the half vector's pdf */
        }
    }
    ck_assert_int_eq(bad, 0);
}
END_TEST

/* Far too rough for the chi-square bins (the lobe lies within 1e-19 rad of the horizon), the
 * sampler must still draw from the lobe sampling_ggx_d describes, the one of alpha clamped to
 * SAMPLING_GGX_ALPHA_MAX: its CDF in tan^2, P(tan^2 theta_h <= T) = T / (alpha^2 + T), is xi1
 * at the sampled half vector.  Catches the sampler left unclamped while D is clamped (at
 * alpha = 1e30 the CDF is ~1 for every xi1: samples from another lobe than the pdf's). */
START_TEST(test_sampling_ggx_half_draws_from_the_lobe_d_describes_at_huge_roughness)
{
    const double alphas[] = {0x1p64, 1e30, 1e100, 1e200, 1.7976931348623157e308};
    double a2 = (double)SAMPLING_GGX_ALPHA_MAX * SAMPLING_GGX_ALPHA_MAX;
    for (int i = 0; i < 5; i++)
        for (int k = 1; k < 10; k++) {
            double xi1 = 0.1 * k;
            vec3 h = sampling_ggx_half(alphas[i], xi1, 0.3);
            double tan2 = (h.x * h.x + h.y * h.y) / (h.z * h.z);
            ck_assert_msg(fabs(tan2 / (a2 + tan2) - xi1) < 1e-9 * xi1, "alpha %g xi1 %g: CDF %.17g",
                          alphas[i], xi1, tan2 / (a2 + tan2));
        }
}
END_TEST

/* sampling_to_world is a rotation taking +z to n, for normals along and near every axis
 * (n = -z is where the branch-free basis changes sign) */
START_TEST(test_sampling_to_world_is_a_rotation_taking_z_to_n)
{
    vec3 ns[] = {{0, 0, 1},         {0, 0, -1},         {1, 0, 0},
                 {0, 1, 0},         {0, -1, 0},         {1e-9, 0, -1},
                 {-1e-9, 1e-9, -1}, {0.3, -0.5, -0.81}, {0.577, 0.577, 0.577}};
    int bad = 0;
    for (int i = 0; i < (int)(sizeof ns / sizeof ns[0]); i++) {
        vec3 n = vec3_normalize(ns[i]);
        vec3 x = sampling_to_world(vec3_make(1, 0, 0), n),
             y = sampling_to_world(vec3_make(0, 1, 0), n);
        vec3 z = sampling_to_world(vec3_make(0, 0, 1), n);
        bad += vec3_length(vec3_sub(z, n)) > 1e-12;
        bad += fabs(vec3_dot(x, y)) > 1e-12 || fabs(vec3_dot(x, z)) > 1e-12 ||
               fabs(vec3_dot(y, z)) > 1e-12;
        bad += fabs(vec3_length(x) - 1) > 1e-12 || fabs(vec3_length(y) - 1) > 1e-12;
        bad += vec3_dot(vec3_cross(x, y), z) < 0; /* right-handed: a rotation, not a reflection */
    }
    ck_assert_int_eq(bad, 0);
}
END_TEST

Suite *sampling_suite(void)
{
    Suite *s = suite_create("sampling");
    TCase *tc = tcase_create("chisq");
    tcase_add_test(tc, test_sampling_uniform_sphere_fits_its_pdf);
    tcase_add_test(tc, test_sampling_uniform_hemisphere_fits_its_pdf);
    tcase_add_test(tc, test_sampling_cosine_hemisphere_fits_its_pdf);
    tcase_add_test(tc, test_sampling_cosine_around_a_tilted_normal_fits_its_pdf);
    tcase_add_loop_test(tc, test_sampling_phong_lobe_fits_its_pdf, 0, N_PHONG);
    tcase_add_loop_test(tc, test_sampling_ggx_half_vector_fits_d_cos, 0, N_GGX);
    suite_add_tcase(s, tc);
    tc = tcase_create("edges");
    tcase_add_test(tc,
                   test_sampling_edge_random_numbers_give_unit_directions_in_the_right_hemisphere);
    tcase_add_test(tc, test_sampling_pdfs_vanish_below_their_hemisphere);
    tcase_add_test(tc, test_sampling_ggx_d_with_zero_roughness_is_the_mirror_limit);
    tcase_add_test(tc, test_sampling_phong_pdf_treats_a_cosine_rounded_above_one_as_the_axis);
    tcase_add_test(tc, test_sampling_ggx_is_finite_for_every_roughness_the_parser_accepts);
    tcase_add_test(tc, test_sampling_ggx_half_draws_from_the_lobe_d_describes_at_huge_roughness);
    tcase_add_test(tc, test_sampling_to_world_is_a_rotation_taking_z_to_n);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(sampling_suite)
