/* test_sis.c - structured importance sampling (include/envtex/envlight/sis.h).
 *
 * Known answers: the layer thresholds of a polar cap at i sigma (sigma by solid angle, in closed
 * form); the samples of two bright patches as floor(N Gamma_R / Gamma_4pi); every texel in
 * exactly one stratum, its nearest sample's; the lights' power summing to the map's; the
 * farthest-point radius within 2x of a brute-force k-center optimum; near-equal solid angles on
 * a constant map; shadow rays inside their stratum; the budget charged first.
 */
#include "envtex/envlight/sis.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/core/rng.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/envmaps/latlong.h"
#include "unit.h"

#define POWER_REL_TOL 1e-9  /* the lights' power against one sum in double */
#define SIGMA_REL_TOL 1e-9  /* sigma of a cap against its closed form (texel edges are exact) */
#define ANGLE_TOL     1e-12 /* ties between dot products of unit vectors */

static double *constant_lum(int w, int h, double v)
{
    double *lum = malloc((size_t)w * h * sizeof *lum);
    ck_assert_ptr_nonnull(lum);
    for (int i = 0; i < w * h; i++) lum[i] = v;
    return lum;
}

static void stratify(const double *lum, int w, int h, int n, sis_strata *s)
{
    error err = {0};
    if (sis_stratify(lum, w, h, n, NULL, s, &err)) ck_abort_msg("sis_stratify: %s", err.msg);
}

static vec3 texel_dir(int t, int w, int h)
{
    return latlong_uv_to_dir((uv2){(t % w + 0.5) / w, (t / w + 0.5) / h});
}

/* A cap of L = 1 over the rows above theta = pi / 4 (a quarter of the rows), 0.2 elsewhere: the
 * cap's share of the sphere is p = (1 - cos(pi / 4)) / 2, so sigma = 0.8 sqrt(p (1 - p)) =
 * 0.8 sin(pi / 4) / 2 = 0.8 / sqrt(8), and L_max / sigma = 3.54: thresholds 0, sigma, 2 sigma,
 * 3 sigma.  (Weighting texels alike instead of by solid angle would give p = 1/4.) */
START_TEST(test_sis_layer_thresholds_are_multiples_of_sigma)
{
    int w = 64, h = 32;
    double *lum = constant_lum(w, h, 0.2);
    for (int i = 0; i < w * h / 4; i++) lum[i] = 1;
    sis_strata s;
    stratify(lum, w, h, 16, &s);
    double sigma = 0.8 / sqrt(8.0);
    ck_assert_msg(fabs(s.sigma - sigma) <= SIGMA_REL_TOL * sigma, "sigma %.12g, want %.12g",
                  s.sigma, sigma);
    ck_assert_int_eq(s.n_layers, 4);
    for (int i = 0; i < 4; i++) ck_assert_near(s.threshold[i], i * s.sigma, 1e-15);
    ck_assert_int_eq(s.regions[0], 1);
    for (int i = 1; i < 4; i++) ck_assert_int_eq(s.regions[i], 1); /* the cap, joined at the pole */
    sis_strata_free(&s);
    /* a constant map has sigma 0: one layer, the whole map */
    for (int i = 0; i < w * h; i++) lum[i] = 3;
    stratify(lum, w, h, 16, &s);
    ck_assert(s.sigma < 1e-12 && s.n_layers == 1 && s.layer_total[0] == 16);
    sis_strata_free(&s);
    free(lum);
}
END_TEST

/* Two uniform patches on a dim sky, each a region of every layer up to its value: a patch R
 * holds floor(N Gamma_R / Gamma_4pi) samples, Gamma = E Omega^(1/4), E = sum L dw, Omega = sum
 * dw (fewer than their texels, and neither N Gamma / Gamma_4pi is within 0.1 of a whole number). */
START_TEST(test_sis_region_sample_counts_follow_the_metric)
{
    int w = 64, h = 32, n = 64;
    double *lum = constant_lum(w, h, 0.05);
    const int c0[2] = {8, 40}, r0[2] = {10, 14}, side[2] = {4, 6};
    const double value[2] = {57, 25};
    double e_tot = 0, om_tot = 0, e[2] = {0}, om[2] = {0};
    for (int p = 0; p < 2; p++)
        for (int r = r0[p]; r < r0[p] + side[p]; r++)
            for (int c = c0[p]; c < c0[p] + side[p]; c++) lum[r * w + c] = value[p];
    for (int t = 0; t < w * h; t++) {
        double o = latlong_texel_solid_angle(t / w, w, h);
        e_tot += lum[t] * o;
        om_tot += o;
        for (int p = 0; p < 2; p++) {
            int c = t % w, r = t / w;
            if (c >= c0[p] && c < c0[p] + side[p] && r >= r0[p] && r < r0[p] + side[p]) {
                e[p] += lum[t] * o;
                om[p] += o;
            }
        }
    }
    int want[2];
    for (int p = 0; p < 2; p++) {
        double x = n * e[p] * pow(om[p], 0.25) / (e_tot * pow(om_tot, 0.25));
        ck_assert_msg(fabs(x - floor(x + 0.5)) > 0.1, "patch %d: %g too near a whole number", p, x);
        want[p] = (int)floor(x); /* the rounding: floor */
    }
    sis_strata s;
    stratify(lum, w, h, n, &s);
    ck_assert_int_eq(s.n, n);
    ck_assert_int_eq(s.regions[1], 2);
    ck_assert_int_eq(s.layer_total[1], want[0] + want[1]);
    ck_assert_int_eq(s.layer_total[0], n);
    int got[2] = {0, 0};
    for (int k = 0; k < s.n; k++) {
        int c = s.seed[k] % w, r = s.seed[k] / w;
        for (int p = 0; p < 2; p++)
            got[p] += c >= c0[p] && c < c0[p] + side[p] && r >= r0[p] && r < r0[p] + side[p] &&
                      s.seed_layer[k] > 0;
    }
    ck_assert_msg(got[0] == want[0] && got[1] == want[1], "patch samples %d, %d; want %d, %d",
                  got[0], got[1], want[0], want[1]);
    int new_sum = 0;
    for (int i = 0; i < s.n_layers; i++) new_sum += s.layer_new[i];
    ck_assert_int_eq(new_sum, n);
    sis_strata_free(&s);
    free(lum);
}
END_TEST

/* Every texel lies in exactly one stratum, in [0, n), and it is its nearest sample's (angle);
 * each sample lies in its own stratum. */
START_TEST(test_sis_every_texel_lies_in_the_stratum_of_its_nearest_sample)
{
    image im = {0};
    genenv_params gp = genenv_defaults();
    gp.width = 48;
    gp.sun_ratio = 1e3;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_SUN, &gp, &im, &err), 0);
    double *lum = sis_luminance(&im, 1);
    ck_assert_ptr_nonnull(lum);
    const int ns[3] = {1, 7, 40};
    for (int q = 0; q < 3; q++) {
        sis_strata s;
        stratify(lum, im.w, im.h, ns[q], &s);
        ck_assert_int_eq(s.n, ns[q]);
        for (int k = 0; k < s.n; k++) ck_assert_int_eq(s.label[s.seed[k]], k);
        for (int t = 0; t < im.w * im.h; t++) {
            int l = s.label[t];
            ck_require_msg(l >= 0 && l < s.n, "texel %d: stratum %d of %d", t, l, s.n);
            vec3 d = texel_dir(t, im.w, im.h);
            double mine = vec3_dot(d, texel_dir(s.seed[l], im.w, im.h));
            for (int k = 0; k < s.n; k++)
                ck_require_msg(vec3_dot(d, texel_dir(s.seed[k], im.w, im.h)) <= mine + ANGLE_TOL,
                               "texel %d: sample %d is nearer than its own %d", t, k, l);
        }
        sis_strata_free(&s);
    }
    free(lum);
    image_free(&im);
}
END_TEST

/* The largest angle from a texel to its sample, over every k-subset of an 8 x 4 map's texels:
 * the k-center optimum that the farthest-point rule must be within 2x of. */
static double best_radius(int w, int h, int k)
{
    int t_n = w * h, idx[8];
    double best = M_PI;
    for (int i = 0; i < k; i++) idx[i] = i;
    for (;;) {
        double radius = 0;
        for (int t = 0; t < t_n; t++) {
            double near = -2;
            for (int i = 0; i < k; i++)
                near = fmax(near, vec3_dot(texel_dir(t, w, h), texel_dir(idx[i], w, h)));
            radius = fmax(radius, acos(fmin(1.0, near)));
        }
        best = fmin(best, radius);
        int i = k - 1; /* the next k-subset in lexicographic order */
        while (i >= 0 && idx[i] == t_n - k + i) i--;
        if (i < 0) return best;
        idx[i]++;
        for (int j = i + 1; j < k; j++) idx[j] = idx[j - 1] + 1;
    }
}

START_TEST(test_sis_farthest_point_radius_is_within_twice_the_optimum)
{
    int w = 8, h = 4;
    double *lum = constant_lum(w, h, 1);
    for (int k = 2; k <= 4; k++) {
        sis_strata s;
        stratify(lum, w, h, k, &s);
        double opt = best_radius(w, h, k);
        ck_assert_msg(s.radius >= opt - ANGLE_TOL && s.radius <= 2 * opt + ANGLE_TOL,
                      "k = %d: radius %.6f, optimum %.6f", k, s.radius, opt);
        sis_strata_free(&s);
    }
    free(lum);
}
END_TEST

/* A constant map: one layer, all samples by the farthest-point rule, and strata of near-equal
 * solid angle (4 pi / N each on average, none beyond 2.5 times another) */
START_TEST(test_sis_constant_map_gives_strata_of_near_equal_solid_angle)
{
    int w = 128, h = 64, n = 32;
    double *lum = constant_lum(w, h, 1);
    sis_strata s;
    stratify(lum, w, h, n, &s);
    double om[32] = {0}, lo = 1e9, hi = 0;
    for (int t = 0; t < w * h; t++) om[s.label[t]] += latlong_texel_solid_angle(t / w, w, h);
    for (int k = 0; k < n; k++) {
        lo = fmin(lo, om[k]);
        hi = fmax(hi, om[k]);
    }
    ck_assert_msg(hi <= 2.5 * lo, "stratum solid angles from %.4f to %.4f sr (4 pi / N = %.4f)", lo,
                  hi, 4 * M_PI / n);
    sis_strata_free(&s);
    free(lum);
}
END_TEST

static envmap env_of(const image *im, double scale)
{
    envmap e;
    memset(&e, 0, sizeof e);
    e.present = 1;
    e.img = im;
    e.scale = scale;
    e.to_env = mat4_identity();
    return e;
}

static void sun_map(image *im, int width)
{
    genenv_params gp = genenv_defaults();
    gp.width = width;
    gp.sun_ratio = 1e4;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_SUN, &gp, im, &err), 0);
}

/* The lights carry the map's power: sum over lights of sum L dw over the stratum equals sum
 * over texels of L dw, channel by channel, to 1e-9 relative, for several N. */
START_TEST(test_sis_light_powers_sum_to_the_map_power)
{
    image im = {0};
    sun_map(&im, 64);
    envmap env = env_of(&im, 0.7);
    rgb want = rgb_gray(0);
    for (int r = 0; r < im.h; r++)
        for (int c = 0; c < im.w; c++)
            want = rgb_madd(want, rgb_scale(image_get(&im, c, r), 0.7),
                            latlong_texel_solid_angle(r, im.w, im.h));
    const int ns[3] = {1, 16, 200};
    for (int q = 0; q < 3; q++) {
        envlight el;
        error err = {0};
        ck_assert_int_eq(sis_envlight_build(&el, &env, ENVSAMPLER_BINARY, ns[q], NULL, &err), 0);
        ck_assert_int_eq(el.n_points, ns[q]);
        rgb got = rgb_gray(0);
        double avg = 0;
        for (int k = 0; k < el.n_points; k++) got = rgb_add(got, el.points[k].power);
        for (int k = 0; k < el.n_points; k++) avg += rgb_avg(el.points[k].power);
        for (int k = 0; k < el.n_points; k++) { /* sis_pick chooses a light by its power */
            double p = rgb_avg(el.points[k].power) / avg;
            ck_assert_near(distrib1d_pmf(&el.point_choice, k), p, 1e-12);
        }
        double g[3] = {got.r, got.g, got.b}, x[3] = {want.r, want.g, want.b};
        for (int ch = 0; ch < 3; ch++)
            ck_assert_msg(fabs(g[ch] - x[ch]) <= POWER_REL_TOL * x[ch],
                          "N %d channel %d: %.15g, want %.15g", ns[q], ch, g[ch], x[ch]);
        envlight_free(&el);
    }
    image_free(&im);
}
END_TEST

/* A shadow ray towards light k leaves through a texel of stratum k, and texels are chosen by
 * energy: a stratum's brightest texel is hit about its share of the stratum's energy. */
START_TEST(test_sis_shadow_rays_stay_inside_their_stratum)
{
    image im = {0};
    sun_map(&im, 64);
    envmap env = env_of(&im, 1);
    envlight el;
    error err = {0};
    ck_assert_int_eq(sis_envlight_build(&el, &env, ENVSAMPLER_BINARY, 24, NULL, &err), 0);
    double *lum = sis_luminance(&im, 1);
    sis_strata s;
    stratify(lum, im.w, im.h, 24, &s);
    rng g;
    rng_seed(&g, 7, 0);
    for (int k = 0; k < el.n_points; k++) {
        int bright = -1, hits = 0, draws = 4000;
        double e_k = 0, e_b = 0;
        for (int t = 0; t < im.w * im.h; t++) {
            if (s.label[t] != k) continue;
            double e = lum[t] * latlong_texel_solid_angle(t / im.w, im.w, im.h);
            e_k += e;
            if (e > e_b) {
                e_b = e;
                bright = t;
            }
        }
        for (int i = 0; i < draws; i++) {
            vec3 d = sis_shadow_dir(&el, k, rng_uniform(&g), rng_uniform(&g));
            uv2 uv;
            ck_require(latlong_dir_to_uv(d, &uv) == 0);
            int c = (int)(uv.u * im.w), r = (int)(uv.v * im.h);
            int t = (r < im.h ? r : im.h - 1) * im.w + (c < im.w ? c : im.w - 1);
            ck_require_msg(s.label[t] == k, "light %d: a shadow ray through texel %d of stratum %d",
                           k, t, s.label[t]);
            hits += t == bright;
        }
        double p = e_b / e_k, se = sqrt(p * (1 - p) / draws);
        ck_assert_msg(fabs(hits / (double)draws - p) <= 5 * se + 1e-12,
                      "light %d: brightest texel hit %.4f, its energy share %.4f", k,
                      hits / (double)draws, p);
    }
    sis_strata_free(&s);
    free(lum);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* envlight's budget counts sis: a budget one byte below the peak refuses before building and
 * leaves nothing charged; sis_stratify charges its own budget the same way. */
START_TEST(test_sis_memory_is_charged_before_it_is_built)
{
    image im = {0};
    sun_map(&im, 64);
    envmap env = env_of(&im, 1);
    envlight el;
    error err = {0};
    budget mem;
    budget_init(&mem, 1e9);
    ck_assert_int_eq(sis_envlight_build(&el, &env, ENVSAMPLER_BINARY, 32, &mem, &err), 0);
    double peak = mem.peak, used = mem.used;
    ck_assert(peak > used && used >= sis_envlight_bytes(im.w, im.h, 32));
    envlight_free(&el);
    budget_init(&mem, peak - 1);
    ck_assert_int_eq(sis_envlight_build(&el, &env, ENVSAMPLER_BINARY, 32, &mem, &err), -1);
    ck_assert_msg(strstr(err.msg, "beyond the memory budget"), "%s", err.msg);
    ck_assert(mem.used == 0);
    double *lum = sis_luminance(&im, 1);
    sis_strata s;
    double need = sis_strata_bytes(im.w, im.h, 32) + sis_scratch_bytes(im.w, im.h, 32);
    budget_init(&mem, need - 1);
    ck_assert_int_eq(sis_stratify(lum, im.w, im.h, 32, &mem, &s, &err), -1);
    ck_assert(mem.used == 0 && s.label == NULL);
    budget_init(&mem, need);
    ck_assert_int_eq(sis_stratify(lum, im.w, im.h, 32, &mem, &s, &err), 0);
    ck_assert(mem.used == sis_strata_bytes(im.w, im.h, 32));
    sis_strata_free(&s);
    free(lum);
    image_free(&im);
}
END_TEST

/* A black map as a light falls back to uniform directions, as envlight_build's other modes do */
START_TEST(test_sis_black_map_light_falls_back_to_uniform)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 16, 8, &err), 0);
    envmap env = env_of(&im, 1);
    envlight el;
    ck_assert_int_eq(sis_envlight_build(&el, &env, ENVSAMPLER_BINARY, 8, NULL, &err), 0);
    ck_assert(el.fell_back && el.mode == ENVSAMPLING_UNIFORM && el.n_points == 0);
    int k;
    vec3 d;
    double prob;
    ck_assert_int_eq(sis_pick(&el, 0.5, 0.5, 0.5, &k, &d, &prob), 0);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* Refusals: a black map, N = 0, more strata than texels; each leaves the result empty. */
START_TEST(test_sis_refuses_a_black_map_and_bad_counts)
{
    double *lum = constant_lum(8, 4, 0);
    sis_strata s;
    error err = {0};
    ck_assert_int_eq(sis_stratify(lum, 8, 4, 4, NULL, &s, &err), -1);
    ck_assert_msg(strstr(err.msg, "black"), "%s", err.msg);
    ck_assert(s.label == NULL && s.seed == NULL);
    lum[5] = 1;
    ck_assert_int_eq(sis_stratify(lum, 8, 4, 0, NULL, &s, &err), -1);
    ck_assert_int_eq(sis_stratify(lum, 8, 4, 33, NULL, &s, &err), -1);
    ck_assert_int_eq(sis_stratify(lum, 8, 4, 32, NULL, &s, &err), 0); /* a stratum a texel */
    for (int t = 0; t < 32; t++) ck_assert_int_eq(s.seed[s.label[t]], t);
    sis_strata_free(&s);
    free(lum);
}
END_TEST

Suite *sis_suite(void)
{
    Suite *s = suite_create("sis");
    TCase *tc = tcase_create("strata");
    tcase_add_test(tc, test_sis_layer_thresholds_are_multiples_of_sigma);
    tcase_add_test(tc, test_sis_region_sample_counts_follow_the_metric);
    tcase_add_test(tc, test_sis_every_texel_lies_in_the_stratum_of_its_nearest_sample);
    tcase_add_test(tc, test_sis_farthest_point_radius_is_within_twice_the_optimum);
    tcase_add_test(tc, test_sis_constant_map_gives_strata_of_near_equal_solid_angle);
    tcase_add_test(tc, test_sis_refuses_a_black_map_and_bad_counts);
    suite_add_tcase(s, tc);
    tc = tcase_create("lights");
    tcase_add_test(tc, test_sis_light_powers_sum_to_the_map_power);
    tcase_add_test(tc, test_sis_shadow_rays_stay_inside_their_stratum);
    tcase_add_test(tc, test_sis_memory_is_charged_before_it_is_built);
    tcase_add_test(tc, test_sis_black_map_light_falls_back_to_uniform);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(sis_suite)
