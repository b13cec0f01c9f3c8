/* test_lights.c - the light set of next-event estimation (include/envtex/lights.h): lights are
 * picked with probability proportional to the documented power estimates, a quad light's sample
 * pdf is lights_quad_pdf at the sampled point, and a quad emits on the side of ac x ab only. */
#include "envtex/lights.h"

#include <string.h>

#include "envtex/genenv.h"
#include "envtex/rng.h"
#include "unit.h"

#define PDF_REL_TOL 1e-6 /* the shadow ray starts 1e-9 off the surface: t is known to ~1e-9 */

/* y is up; the quad at height 2 has ab x ac = +y, so it emits DOWN (ac x ab), onto the floor
 * (FORMAT.md: the official scenes light a floor below a light whose ab x ac points up) */
static const char *scene_text =
    "size 8 8\n"
    "camera 0 1 5  0 0 0  0 1 0  45\n"
    "quadLight -0.5 2 -0.5  0 0 1  1 0 0  6 3 9\n"
    "quadLight 3 1 0  0 2 0  0 0 0.5  1 1 1\n"
    "point 0 3 0  2 4 6\n"
    "directional 0 1 0  0.5 0.5 0.5\n"
    "diffuse 0.5 0.5 0.5\n"
    "sphere 0 0.5 0 0.5\n";

static void load(scene *sc)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    error err = {0};
    if (scene_load_string(scene_text, "lights.test", &o, sc, &err)) ck_abort_msg("scene: line %d: %s", err.line, err.msg);
    ck_assert_int_eq(sc->n_lights, 4);
}

/* pick probability = power / total power with quad pi A L_avg, point 4 pi I_avg, directional
 * pi R^2 E_avg, envmap pi R^2 |L|; and lights_pick returns each k at that rate */
START_TEST(test_lights_pick_probability_is_proportional_to_power)
{
    scene sc;
    load(&sc);
    image im;
    genenv_params gp = genenv_defaults();
    gp.width = 32;
    gp.value = 0.25;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_CONSTANT, &gp, &im, &err), 0);
    envmap env;
    memset(&env, 0, sizeof env); /* a zeroed envmap is a lat-long one */
    env.present = 1;
    env.img = &im;
    env.scale = 2.0;
    env.to_env = mat4_identity();
    envlight el;
    ck_assert_int_eq(envlight_build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0, &err), 0);
    double R = 3.0;
    lights ls;
    ck_assert_int_eq(lights_build(&ls, &sc, &el, R, &err), 0);
    ck_assert_int_eq(ls.n, 5);
    ck_assert_int_eq(lights_env_index(&ls), 4);
    double pw[5] = {M_PI * 1.0 * 6.0,          /* 1 x 1 quad, L_avg = 6 */
                    M_PI * 1.0 * 1.0,          /* 2 x 0.5 quad, L_avg = 1 */
                    4 * M_PI * 4.0,            /* point, I_avg = 4 */
                    M_PI * R * R * 0.5,        /* directional, E_avg = 0.5 */
                    M_PI * R * R * 4 * M_PI * 0.5}; /* env: |L| = 4 pi x 0.25 x 2 */
    double total = 0;
    for (int k = 0; k < 5; k++) total += pw[k];
    long count[5] = {0};
    enum { N = 100000 };
    for (int i = 0; i < N; i++) {
        int k;
        double prob;
        ck_assert(lights_pick(&ls, (i + 0.5) / N, &k, &prob));
        ck_assert(k >= 0 && k < 5);
        count[k]++;
        ck_assert(prob == lights_pick_prob(&ls, k));
    }
    for (int k = 0; k < 5; k++) {
        ck_assert_msg(fabs(lights_pick_prob(&ls, k) - pw[k] / total) < 1e-12, "light %d: %g, want %g", k,
                      lights_pick_prob(&ls, k), pw[k] / total);
        ck_assert_msg(fabs((double)count[k] / N - pw[k] / total) < 2.0 / N, "light %d picked %ld times", k, count[k]);
    }
    /* MIS's envmap fraction c: the envmap is kept at c of its picks, with pick probability c P;
     * other lights are unchanged; c = 0 never samples it; an out-of-range c means 1 */
    const double fractions[] = {0.3, 0.0, 1.0};
    for (int f = 0; f < 3; f++) {
        double c = fractions[f];
        lights_set_env_fraction(&ls, c);
        long kept[5] = {0}, none = 0;
        for (int i = 0; i < N; i++) {
            int k;
            double prob;
            if (!lights_pick(&ls, (i + 0.5) / N, &k, &prob)) { none++; continue; }
            kept[k]++;
            ck_assert(prob == lights_pick_prob(&ls, k));
        }
        ck_assert_msg(fabs(lights_pick_prob(&ls, 4) - c * pw[4] / total) < 1e-12, "c %g: %g", c, lights_pick_prob(&ls, 4));
        ck_assert_msg(fabs((double)kept[4] / N - c * pw[4] / total) < 2.0 / N, "c %g: env kept %ld times", c, kept[4]);
        ck_assert_msg(fabs((double)none / N - (1 - c) * pw[4] / total) < 2.0 / N, "c %g: %ld skipped", c, none);
        for (int k = 0; k < 4; k++) ck_assert(fabs(lights_pick_prob(&ls, k) - pw[k] / total) < 1e-12);
    }
    lights_set_env_fraction(&ls, NAN);
    ck_assert(ls.env_fraction == 1);
    lights_set_env_fraction(&ls, 1.5);
    ck_assert(ls.env_fraction == 1);
    lights_free(&ls);
    /* without an environment the set is the scene's lights only */
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, R, &err), 0);
    ck_assert_int_eq(ls.n, 4);
    ck_assert_int_eq(lights_env_index(&ls), -1);
    lights_free(&ls);
    envlight_free(&el);
    image_free(&im);
    scene_free(&sc);
}
END_TEST

/* quad sampling: the sample's pdf is lights_quad_pdf(wi, t) at the sampled point, the point is
 * on the quad, Li is its radiance, and the estimate of the solid angle (mean of 1 / pdf) is the
 * quad's solid angle from a point straight below its centre (4 asin(a b / sqrt((a^2+d^2)(b^2+d^2)))
 * for a 2a x 2b rectangle at distance d) */
START_TEST(test_lights_quad_sample_pdf_matches_lights_quad_pdf)
{
    scene sc;
    load(&sc);
    lights ls;
    error err = {0};
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, &err), 0);
    vec3 p = vec3_make(0, 0, 0), ng = vec3_make(0, 1, 0);
    rng g;
    rng_seed(&g, 9, 0);
    int bad = 0;
    double sum = 0;
    enum { N = 40000 };
    for (int i = 0; i < N; i++) {
        light_sample s;
        ck_assert(lights_sample(&ls, 0, p, ng, rng_uniform(&g), rng_uniform(&g), rng_uniform(&g), 0, &s));
        vec3 q = vec3_add(s.shadow.o, s.shadow.d); /* the shadow ray ends at the sampled point */
        double t = vec3_length(vec3_sub(q, p));
        double pq = lights_quad_pdf(&ls, 0, s.wi, t);
        bad += !(fabs(s.pdf - pq) <= PDF_REL_TOL * pq) || s.is_delta;
        bad += fabs(q.y - 2) > 1e-9 || fabs(q.x) > 0.5 + 1e-9 || fabs(q.z) > 0.5 + 1e-9;
        bad += s.Li.r != 6 || s.Li.g != 3 || s.Li.b != 9;
        sum += 1 / s.pdf;
    }
    ck_assert_int_eq(bad, 0);
    double a = 0.5, b = 0.5, d = 2, omega = 4 * asin(a * b / sqrt((a * a + d * d) * (b * b + d * d)));
    ck_assert_msg(fabs(sum / N - omega) < 2e-3 * omega, "mean 1/pdf %g, solid angle %g", sum / N, omega);
    lights_free(&ls);
    scene_free(&sc);
}
END_TEST

/* the quad emits on the side of ac x ab (down here): seen from below it has radiance L, from
 * above none; a point above cannot sample it; rays hit it from both sides (visibility) */
START_TEST(test_lights_quad_emits_on_the_side_of_ac_cross_ab)
{
    scene sc;
    load(&sc);
    lights ls;
    error err = {0};
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, &err), 0);
    ray up = {vec3_make(0.1, 0, 0.1), vec3_make(0, 1, 0), 0, INFINITY};
    ray down = {vec3_make(0.1, 5, 0.1), vec3_make(0, -1, 0), 0, INFINITY};
    int k;
    double t;
    ck_assert(lights_intersect_quad(&ls, &up, &k, &t));
    ck_assert_int_eq(k, 0);
    ck_assert_near(t, 2, 1e-12);
    rgb below = lights_quad_radiance(&ls, 0, up.d);
    ck_assert(below.r == 6 && below.g == 3 && below.b == 9);
    ck_assert(lights_intersect_quad(&ls, &down, &k, &t));
    ck_assert_near(t, 3, 1e-12);
    ck_assert(rgb_is_black(lights_quad_radiance(&ls, 0, down.d)));
    light_sample s;
    ck_assert(!lights_sample(&ls, 0, vec3_make(0, 3, 0), vec3_make(0, -1, 0), 0.3, 0.6, 0.5, 0, &s));
    ck_assert(lights_quad_pdf(&ls, 0, vec3_make(0, -1, 0), 1) == 0);
    ck_assert(lights_quad_pdf(&ls, 0, vec3_make(0, 1, 0), 2) > 0);
    lights_free(&ls);
    scene_free(&sc);
}
END_TEST

/* point and directional lights: one delta sample, Li = I / attenuation and E; the shadow ray
 * towards the point light stops short of it */
START_TEST(test_lights_delta_lights_give_intensity_over_attenuation)
{
    scene sc;
    load(&sc);
    lights ls;
    error err = {0};
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, &err), 0);
    light_sample s;
    ck_assert(lights_sample(&ls, 2, vec3_make(0, 1, 0), vec3_make(0, 1, 0), 0.2, 0.2, 0.2, 0, &s));
    ck_assert(s.is_delta && s.pdf == 0);
    ck_assert(s.Li.r == 2 && s.Li.g == 4 && s.Li.b == 6); /* attenuation 1 0 0 */
    ck_assert_near(s.wi.y, 1, 1e-15);
    ck_assert(s.shadow.tmax < 1);
    ck_assert(lights_sample(&ls, 3, vec3_make(0, 1, 0), vec3_make(0, 1, 0), 0.2, 0.2, 0.2, 0, &s));
    ck_assert(s.is_delta && s.Li.r == 0.5 && s.wi.y == 1);
    lights_free(&ls);
    scene_free(&sc);
}
END_TEST

Suite *lights_suite(void)
{
    Suite *s = suite_create("lights");
    TCase *tc = tcase_create("lights");
    tcase_set_timeout(tc, 60); /* generous for sanitizer builds */
    tcase_add_test(tc, test_lights_pick_probability_is_proportional_to_power);
    tcase_add_test(tc, test_lights_quad_sample_pdf_matches_lights_quad_pdf);
    tcase_add_test(tc, test_lights_quad_emits_on_the_side_of_ac_cross_ab);
    tcase_add_test(tc, test_lights_delta_lights_give_intensity_over_attenuation);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(lights_suite)
