/* test_misfraction.c - how often MIS samples the map (include/envtex/envlight/misfraction.h):
 * the variance model against closed forms on a constant map, its choices on a sky and a sun,
 * and the fraction it returns minimizes the variance x time it reports.
 */
#include "envtex/envlight/misfraction.h"

#include <string.h>

#include "envtex/envmaps/genenv.h"
#include "unit.h"

/* A 64 x 32 map with a sun 10^6 times the sky, 3 degrees in radius. */
static void sun_map(image *im)
{
    genenv_params p = genenv_defaults();
    p.width = 64;
    p.sun_ratio = 1e6;
    p.sun_radius_deg = 3;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_SUN, &p, im, &err), 0);
}

static envmap env_of(const image *im, double scale, mat4 to_env)
{
    envmap e;
    memset(&e, 0, sizeof e);
    e.present = 1;
    e.img = im;
    e.scale = scale;
    e.to_env = to_env;
    return e;
}

static void build(envlight *el, const envmap *env, envsampling_mode mode, envsampler_kind sampler,
                  int n)
{
    error err = {0};
    if (envlight_build(el, env, mode, sampler, n, NULL, &err))
        ck_abort_msg("envlight_build: %s", err.msg);
}

/* misfraction_choose's model against closed forms, and its choices.  Constant map L, a
 * normal n: g = L cos / pi on the upper hemisphere, I = L, p_light = 1 / (4 pi), so with
 * x = cos theta and the mixture p_m = (x / pi + c / (4 pi)) / (1 + c):
 *     S / I^2 = (1 + c) 2 pi int_0^1 (x / pi)^2 / (x / pi + c / (4 pi)) dx
 *             = 8 (1 + c) / c int_0^1 x^2 / (4x / c + 1) dx,
 * which is 1 at c = 0 (no variance), 1.402347 at c = 1 (V = 0.201174) and 1.227977 at
 * c = 1/2 (V = 0.151985).  The generated sky gets c = 0 (cosine sampling already follows it,
 * and light samples below the horizon are wasted), the sun map c = 1, and V falls with c under the
 * sun (V ~ 1/c there). */
START_TEST(test_misfraction_model_meets_its_closed_forms)
{
    image im;
    ck_assert_int_eq(image_alloc(&im, 128, 64, &(error){0}), 0);
    for (int r = 0; r < 64; r++)
        for (int c = 0; c < 128; c++) image_set(&im, c, r, rgb_gray(0.7));
    envmap env = env_of(&im, 1, mat4_identity());
    envlight el;
    build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_ALIAS, 0);
    double v[MISFRACTION_COUNT];
    ck_assert(misfraction_choose(&el, 0.6, v) == 0);
    ck_assert_msg(v[0] < 1e-3, "cosine sampling of a constant map: V %g", v[0]);
    ck_assert_msg(fabs(v[5] / 0.151985 - 1) < 0.01, "c = 1/2: V %g, closed form 0.151985", v[5]);
    ck_assert_msg(fabs(v[7] / 0.201174 - 1) < 0.01, "c = 1: V %g, closed form 0.201174", v[7]);
    envlight_free(&el);
    image_free(&im);
    genenv_params p = genenv_defaults();
    p.width = 256;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_SKY, &p, &im, &err), 0);
    env = env_of(&im, 1, mat4_identity());
    build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_ALIAS, 0);
    ck_assert_msg(misfraction_choose(&el, 0.6, v) == 0, "sky: c %g",
                  misfraction_choose(&el, 0.6, NULL));
    envlight_free(&el);
    image_free(&im);
    sun_map(&im);
    env = env_of(&im, 2, mat4_rotate(vec3_make(1, 0, 0), -90));
    build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_ALIAS, 0);
    ck_assert(misfraction_choose(&el, 0.6, v) == 1);
    for (int i = 1; i < MISFRACTION_COUNT; i++)
        ck_assert_msg(v[i] < v[i - 1], "sun: V[%d] %g >= V[%d] %g", i, v[i], i - 1, v[i - 1]);
    ck_assert_msg(v[0] > 10 * v[7], "sun: cosine sampling alone V %g, with c = 1 %g", v[0], v[7]);
    envlight_free(&el);
    build(&el, &env, ENVSAMPLING_UNIFORM, ENVSAMPLER_ALIAS, 0);
    ck_assert(misfraction_choose(&el, 0.6, NULL) == 1); /* not the cdf mode: unchanged */
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* misfraction_choose returns the c that minimizes V(c) (1 + light_cost c), its variance x time
 * (misfraction.h), whatever light_cost is: on the sun map (V falls like 1/c) a free light sample
 * or the integrator's 0.6 gives c = 1, a light sample 100 or 10^4 times a BRDF sample's cost a
 * smaller c.  Checked against the V it reports, so the model itself is not under test here. */
START_TEST(test_misfraction_minimizes_variance_times_time)
{
    static const double fractions[MISFRACTION_COUNT] = {0,    1.0 / 32, 1.0 / 16, 1.0 / 8,
                                                        0.25, 0.5,      0.75,     1};
    const double costs[] = {0, 0.6, 100, 1e4};
    image im;
    sun_map(&im);
    envmap env = env_of(&im, 1, mat4_identity());
    envlight el;
    build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0);
    for (size_t k = 0; k < sizeof costs / sizeof costs[0]; k++) {
        double v[MISFRACTION_COUNT], best = INFINITY, got_cost = NAN;
        double c = misfraction_choose(&el, costs[k], v);
        for (int i = 0; i < MISFRACTION_COUNT; i++) {
            double cost = v[i] * (1 + costs[k] * fractions[i]);
            best = fmin(best, cost);
            if (fractions[i] == c) got_cost = cost;
        }
        ck_assert_msg(got_cost <= best * (1 + 1e-9),
                      "light_cost %g: c = %g costs %g, the least is %g", costs[k], c, got_cost,
                      best);
        ck_assert_msg(costs[k] < 100 ? c == 1 : c < 1, "light_cost %g: c = %g", costs[k], c);
    }
    envlight_free(&el);
    image_free(&im);
}
END_TEST

Suite *misfraction_suite(void)
{
    Suite *s = suite_create("misfraction");
    TCase *tc = tcase_create("model");
    tcase_add_test(tc, test_misfraction_model_meets_its_closed_forms);
    tcase_add_test(tc, test_misfraction_minimizes_variance_times_time);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(misfraction_suite)
