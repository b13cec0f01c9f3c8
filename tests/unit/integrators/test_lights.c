/* test_lights.c - the light set of next-event estimation (include/envtex/integrators/lights.h): lights are
 * picked with probability proportional to the documented power estimates, a quad light's sample
 * pdf is lights_quad_pdf at the sampled point, and a quad emits on the side of ac x ab only. */
#include "envtex/integrators/lights.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/envmaps/genenv.h"
#include "envtex/core/rng.h"
#include "envtex/geometry/triangle.h"
#include "envtex/scene/scene_load.h"
#include "unit.h"

#define PDF_REL_TOL 1e-6 /* the shadow ray starts 1e-9 off the surface: t is known to ~1e-9 */

/* y is up; the quad at height 2 has ab x ac = +y, so it emits DOWN (ac x ab), onto the floor
 * (FORMAT.md: the official scenes light a floor below a light whose ab x ac points up) */
static const char *scene_text = "size 8 8\n"
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
    if (scene_load_string(scene_text, "lights.test", &o, sc, &err))
        ck_abort_msg("scene: line %d: %s", err.line, err.msg);
    ck_assert_int_eq(sc->n_lights, 4);
}

/* im as a lat-long environment (world frame) of radiance scale x its texels */
static envmap latlong_env(const image *im, double scale)
{
    envmap env;
    memset(&env, 0, sizeof env); /* a zeroed envmap is a lat-long one */
    env.present = 1;
    env.img = im;
    env.scale = scale;
    env.to_env = mat4_identity();
    return env;
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
    envmap env = latlong_env(&im, 2.0);
    envlight el;
    ck_assert_int_eq(envlight_build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0, NULL, &err),
                     0);
    double R = 3.0;
    lights ls;
    ck_assert_int_eq(lights_build(&ls, &sc, &el, R, NULL, &err), 0);
    ck_assert_int_eq(ls.n, 5);
    ck_assert_int_eq(lights_env_index(&ls), 4);
    double pw[5] = {M_PI * 1.0 * 6.0,               /* 1 x 1 quad, L_avg = 6 */
                    M_PI * 1.0 * 1.0,               /* 2 x 0.5 quad, L_avg = 1 */
                    4 * M_PI * 4.0,                 /* point, I_avg = 4 */
                    M_PI * R * R * 0.5,             /* directional, E_avg = 0.5 */
                    M_PI * R * R * 4 * M_PI * 0.5}; /* env: |L| = 4 pi x 0.25 x 2 */
    double total = 0;
    for (int k = 0; k < 5; k++) total += pw[k];
    long count[5] = {0};
    enum { N = 100000 };
    for (int i = 0; i < N; i++) {
        int k;
        double prob;
        ck_require(lights_pick(&ls, (i + 0.5) / N, &k, &prob));
        ck_require(k >= 0 && k < 5);
        count[k]++;
        ck_require(prob == lights_pick_prob(&ls, k));
    }
    for (int k = 0; k < 5; k++) {
        ck_assert_msg(fabs(lights_pick_prob(&ls, k) - pw[k] / total) < 1e-12,
                      "light %d: %.17g, want %.17g", k, lights_pick_prob(&ls, k), pw[k] / total);
        ck_assert_msg(fabs((double)count[k] / N - pw[k] / total) < 2.0 / N,
                      "light %d picked %ld times", k, count[k]);
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
            if (!lights_pick(&ls, (i + 0.5) / N, &k, &prob)) {
                none++;
                continue;
            }
            kept[k]++;
            ck_require(prob == lights_pick_prob(&ls, k));
        }
        ck_assert_msg(fabs(lights_pick_prob(&ls, 4) - c * pw[4] / total) < 1e-12, "c %g: %g", c,
                      lights_pick_prob(&ls, 4));
        ck_assert_msg(fabs((double)kept[4] / N - c * pw[4] / total) < 2.0 / N,
                      "c %g: env kept %ld times", c, kept[4]);
        ck_assert_msg(fabs((double)none / N - (1 - c) * pw[4] / total) < 2.0 / N,
                      "c %g: %ld skipped", c, none);
        for (int k = 0; k < 4; k++)
            ck_assert(fabs(lights_pick_prob(&ls, k) - pw[k] / total) < 1e-12);
    }
    lights_set_env_fraction(&ls, NAN);
    ck_assert(ls.env_fraction == 1);
    lights_set_env_fraction(&ls, 1.5);
    ck_assert(ls.env_fraction == 1);
    lights_free(&ls);
    /* without an environment the set is the scene's lights only */
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, R, NULL, &err), 0);
    ck_assert_int_eq(ls.n, 4);
    ck_assert_int_eq(lights_env_index(&ls), -1);
    lights_free(&ls);
    envlight_free(&el);
    image_free(&im);
    scene_free(&sc);
}
END_TEST

/* lights_selection_prob, the probability that one light sample is of light k: under
 * `lightselection all` (the default) 1 for every light and c for the envmap, whatever their
 * powers; under `power` the pick probability (c P for the envmap), lights_pick_prob. */
START_TEST(test_lights_selection_probability_follows_the_selection)
{
    for (int mode = 0; mode < 2; mode++) {
        scene sc;
        load(&sc);
        sc.lightselection = mode ? LIGHTSELECTION_POWER : LIGHTSELECTION_ALL;
        image im;
        genenv_params gp = genenv_defaults();
        gp.width = 32;
        error err = {0};
        ck_assert_int_eq(genenv_make(GENENV_CONSTANT, &gp, &im, &err), 0);
        envmap env = latlong_env(&im, 1.0);
        envlight el;
        ck_assert_int_eq(
            envlight_build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0, NULL, &err), 0);
        lights ls;
        ck_assert_int_eq(lights_build(&ls, &sc, &el, 3.0, NULL, &err), 0);
        const double fractions[] = {1.0, 0.3, 0.0};
        double p_env = lights_pick_prob(&ls, 4); /* P(pick the envmap) at c = 1 */
        for (int f = 0; f < 3; f++) {
            lights_set_env_fraction(&ls, fractions[f]);
            double sum = 0;
            for (int k = 0; k < ls.n; k++) {
                double p = lights_selection_prob(&ls, k), want = mode     ? lights_pick_prob(&ls, k)
                                                                 : k == 4 ? fractions[f]
                                                                          : 1.0;
                ck_assert_msg(p == want, "%s, c %g, light %d: %.17g, want %.17g",
                              mode ? "power" : "all", fractions[f], k, p, want);
                sum += p;
            }
            double want_sum = mode ? 1 - (1 - fractions[f]) * p_env : 4 + fractions[f];
            ck_assert_msg(fabs(sum - want_sum) < 1e-12, "%s, c %g: probabilities sum to %.17g",
                          mode ? "power" : "all", fractions[f], sum);
        }
        lights_free(&ls);
        envlight_free(&el);
        image_free(&im);
        scene_free(&sc);
    }
}
END_TEST

/* Powers that do not fit a double, though every number in the scene does: two point lights of
 * intensity 1e307 and 2e307 (4 pi I overflows their sum, and at 1.7e308 each power is +Inf),
 * and a quad light of area 1e308 (pi A L overflows).  Only the ratios matter: 1/3 and 2/3, and the huge quad wins
 * over a point light of intensity 1.  Catches weights taken as the raw powers (the build
 * failed with "the sum of the 2 weights overflows a double", or chose uniformly). */
START_TEST(test_lights_pick_probabilities_of_powers_past_the_largest_double)
{
    const char *texts[3] = {
        "size 8 8\ncamera 0 1 5  0 0 0  0 1 0  45\npoint 0 3 0  1e307 1e307 1e307\npoint 0 3 1  "
        "2e307 2e307 2e307\n",
        "size 8 8\ncamera 0 1 5  0 0 0  0 1 0  45\npoint 0 3 0  0.85e308 0.85e308 0.85e308\n"
        "point 0 3 1  1.7e308 1.7e308 1.7e308\n",
        "size 8 8\ncamera 0 1 5  0 0 0  0 1 0  45\nquadLight 0 3 0  1e154 0 0  0 0 1e154  1 1 1\n"
        "point 0 3 1  1 1 1\n"};
    for (int i = 0; i < 3; i++) {
        scene sc;
        scene_load_opts o = scene_load_defaults();
        o.load_images = 0;
        error err = {0};
        if (scene_load_string(texts[i], "huge.test", &o, &sc, &err))
            ck_abort_msg("scene %d: %s", i, err.msg);
        lights ls;
        ck_assert_msg(lights_build(&ls, &sc, NULL, 3, NULL, &err) == 0, "scene %d: %s", i, err.msg);
        double p0 = lights_pick_prob(&ls, 0), p1 = lights_pick_prob(&ls, 1);
        if (i < 2) {
            ck_assert_msg(fabs(p0 - 1.0 / 3) < 1e-12 && fabs(p1 - 2.0 / 3) < 1e-12,
                          "scene %d: %g %g", i, p0, p1);
        } else {
            ck_assert_msg(p0 == 1.0 && p1 == 0.0, "scene %d: %g %g", i, p0, p1);
        }
        lights_free(&ls);
        scene_free(&sc);
    }
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
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, NULL, &err), 0);
    vec3 p = vec3_make(0, 0, 0), ng = vec3_make(0, 1, 0);
    rng g;
    rng_seed(&g, 9, 0);
    int bad = 0;
    double sum = 0;
    enum { N = 40000 };
    for (int i = 0; i < N; i++) {
        light_sample s;
        ck_require(
            lights_sample(&ls, 0, p, ng, rng_uniform(&g), rng_uniform(&g), rng_uniform(&g), 0, &s));
        vec3 q = vec3_add(s.shadow.o, s.shadow.d); /* the shadow ray ends at the sampled point */
        double t = vec3_length(vec3_sub(q, p));
        double pq = lights_quad_pdf(&ls, 0, s.wi, t);
        bad += !(fabs(s.pdf - pq) <= PDF_REL_TOL * pq) || s.is_delta;
        bad += fabs(q.y - 2) > 1e-9 || fabs(q.x) > 0.5 + 1e-9 || fabs(q.z) > 0.5 + 1e-9;
        bad += s.Li.r != 6 || s.Li.g != 3 || s.Li.b != 9;
        sum += 1 / s.pdf;
    }
    ck_assert_int_eq(bad, 0);
    double a = 0.5, b = 0.5, d = 2,
           omega = 4 * asin(a * b / sqrt((a * a + d * d) * (b * b + d * d)));
    ck_assert_msg(fabs(sum / N - omega) < 2e-3 * omega, "mean 1/pdf %g, solid angle %g", sum / N,
                  omega);
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
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, NULL, &err), 0);
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
    ck_assert(
        !lights_sample(&ls, 0, vec3_make(0, 3, 0), vec3_make(0, -1, 0), 0.3, 0.6, 0.5, 0, &s));
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
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, NULL, &err), 0);
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

/* A point light is divided by c + l d + q d^2 at its distance d (FORMAT.md's attenuation), each
 * term counted: at d = 2 with attenuation 0.5 0.25 0.125 that is 0.5 + 0.5 + 0.5 = 1.5. */
START_TEST(test_lights_point_attenuation_uses_all_three_terms_at_the_distance)
{
    scene sc;
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    error err = {0};
    const char *text = "size 8 8\ncamera 0 1 5  0 0 0  0 1 0  45\n"
                       "attenuation 0.5 0.25 0.125\npoint 0 3 0  3 6 9\n";
    if (scene_load_string(text, "atten.test", &o, &sc, &err)) ck_abort_msg("scene: %s", err.msg);
    lights ls;
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, NULL, &err), 0);
    light_sample s;
    ck_assert(lights_sample(&ls, 0, vec3_make(0, 1, 0), vec3_make(0, 1, 0), 0.5, 0.5, 0.5, 0, &s));
    ck_assert_near(s.Li.r, 3 / 1.5, 1e-12);
    ck_assert_near(s.Li.b, 9 / 1.5, 1e-12);
    lights_free(&ls);
    scene_free(&sc);
}
END_TEST

/* median cut through the light set: the light is the stratum's point (its centroid, its power
 * over the pick probability), but the shadow ray is jittered inside the stratum (slides 18-21 (Structured Importance Sampling)),
 * so it follows envlight_mediancut_pick's direction, not the centroid's. */
START_TEST(test_lights_median_cut_shadow_ray_is_jittered_in_the_stratum)
{
    scene sc;
    load(&sc);
    image im;
    genenv_params gp = genenv_defaults();
    gp.width = 64;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_SKY, &gp, &im, &err), 0);
    envmap env = latlong_env(&im, 1.0);
    envlight el;
    ck_assert_int_eq(
        envlight_build(&el, &env, ENVSAMPLING_MEDIANCUT, ENVSAMPLER_BINARY, 4, NULL, &err), 0);
    lights ls;
    ck_assert_int_eq(lights_build(&ls, &sc, &el, 3, NULL, &err), 0);
    int ke = lights_env_index(&ls);
    vec3 p = vec3_make(0, 1, 0), n = vec3_make(0, 1, 0);
    int moved = 0;
    for (int i = 0; i < 16; i++) {
        double xi = 0.3, xi1 = (i % 4 + 0.5) / 4, xi2 = (i / 4 + 0.5) / 4;
        light_sample s;
        int k;
        vec3 sd;
        double prob;
        ck_assert(lights_sample(&ls, ke, p, n, xi, xi1, xi2, 0, &s));
        ck_assert(envlight_mediancut_pick(&el, xi, xi1, xi2, &k, &sd, &prob));
        ck_assert(s.is_delta);
        ck_assert(vec3_dot(s.wi, el.points[k].dir) > 1 - 1e-12); /* shaded with the centroid */
        ck_assert_near(s.Li.g, el.points[k].power.g / prob,
                       1e-9 * s.Li.g); /* its power / P(pick) */
        ck_assert_msg(vec3_dot(vec3_normalize(s.shadow.d), sd) > 1 - 1e-12,
                      "shadow ray %d is not the jittered one", i);
        moved += vec3_dot(sd, s.wi) < 1 - 1e-6;
    }
    ck_assert_int_gt(moved, 8); /* the jitter does move it off the centroid */
    lights_free(&ls);
    envlight_free(&el);
    image_free(&im);
    scene_free(&sc);
}
END_TEST

/* A scene of n_quads random quad lights (random sizes and orientations in a 10-unit cube), each
 * after two point lights, so that quad j is sc->lights[3 j + 2]. */
static void load_many_quads(scene *sc, int n_quads, uint64_t seed)
{
    size_t cap = 256 + (size_t)n_quads * 200;
    char *text = malloc(cap);
    ck_assert_ptr_nonnull(text);
    int len = snprintf(text, cap, "size 8 8\ncamera 0 0 20  0 0 0  0 1 0  45\n");
    rng g;
    rng_seed(&g, seed, 0);
    for (int j = 0; j < n_quads; j++) {
        double v[9];
        for (int i = 0; i < 3; i++) v[i] = 10 * rng_uniform(&g) - 5;
        for (int i = 3; i < 9; i++) v[i] = 2 * rng_uniform(&g) - 1;
        len += snprintf(text + len, cap - (size_t)len,
                        "point 0 %d 0  1 1 1\ndirectional 1 %d 1  1 1 1\n"
                        "quadLight %.6f %.6f %.6f  %.6f %.6f %.6f  %.6f %.6f %.6f  1 1 1\n",
                        j, j + 1, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]);
    }
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    error err = {0};
    if (scene_load_string(text, "quads.test", &o, sc, &err))
        ck_abort_msg("scene: line %d: %s", err.line, err.msg);
    free(text);
    ck_assert_int_eq(sc->n_lights, 3 * n_quads);
}

/* The nearest quad by testing every light, as the lecture's loop does (the reference). */
static int nearest_quad_by_testing_all(const scene *sc, const ray *r, int *k, double *t_out)
{
    int found = 0;
    ray rr = *r;
    for (int i = 0; i < sc->n_lights; i++) {
        const scene_light *l = &sc->lights[i];
        if (l->kind != LIGHT_QUAD) continue;
        vec3 a = l->pos, b = vec3_add(a, l->ab), c = vec3_add(b, l->ac), d = vec3_add(a, l->ac);
        double t, b1, b2;
        if (triangle_intersect(a, b, c, &rr, &t, &b1, &b2) ||
            triangle_intersect(a, c, d, &rr, &t, &b1, &b2)) {
            found = 1;
            *k = i;
            *t_out = t;
            rr.tmax = t;
        }
    }
    return found;
}

/* lights_intersect_quad finds the same nearest quad (index into sc->lights) at the same t as
 * testing every light, with few quads (a plain loop) and with many (the quads' BVH), for rays
 * from outside and inside the cloud of quads, and with a finite tmax */
START_TEST(test_lights_intersect_quad_finds_the_nearest_quad_of_many)
{
    static const int counts[] = {1, 4, 5, 300};
    for (int c = 0; c < 4; c++) {
        scene sc;
        load_many_quads(&sc, counts[c], 7 + (uint64_t)c);
        lights ls;
        error err = {0};
        ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, NULL, &err), 0);
        ck_assert_int_eq(ls.n_quads, counts[c]);
        rng g;
        rng_seed(&g, 99, (uint64_t)c);
        int hits = 0;
        for (int i = 0; i < 4000; i++) {
            double s = i % 2 ? 4 : 12; /* inside the cube, or from around it */
            vec3 o = vec3_make(s * (2 * rng_uniform(&g) - 1), s * (2 * rng_uniform(&g) - 1),
                               s * (2 * rng_uniform(&g) - 1));
            /* towards a random point of a random quad (the nearest hit may be another one) */
            const scene_light *l = &sc.lights[3 * (int)(rng_uniform(&g) * counts[c]) + 2];
            vec3 q = vec3_add(l->pos, vec3_add(vec3_scale(l->ab, rng_uniform(&g)),
                                               vec3_scale(l->ac, rng_uniform(&g))));
            vec3 d = vec3_normalize(vec3_sub(q, o));
            ray r = {o, d, 0, i % 3 ? INFINITY : 6};
            int k0 = -1, k1 = -1;
            double t0 = 0, t1 = 0;
            int h0 = nearest_quad_by_testing_all(&sc, &r, &k0, &t0);
            int h1 = lights_intersect_quad(&ls, &r, &k1, &t1);
            ck_require(h1 == h0);
            if (h0) {
                ck_require(k1 == k0);
                ck_require(t1 == t0);
                hits++;
            }
        }
        ck_assert_int_gt(hits, 1000); /* the rays do meet the quads */
        lights_free(&ls);
        scene_free(&sc);
    }
}
END_TEST

/* lights_scene_bvh puts the quads into the scene's BVH for the integrators that see them, and
 * a BVH_QUAD there is the same nearest quad, at the same t, as testing every light finds (and
 * occludes as it does); the Whitted raytracer's BVH holds none */
START_TEST(test_lights_scene_bvh_holds_the_quads_and_finds_the_nearest)
{
    scene sc;
    load_many_quads(&sc, 300, 5);
    bvh b;
    error err = {0};
    ck_assert_int_eq(lights_scene_bvh(&b, &sc, NULL, &err), 0); /* integrator raytracer */
    ck_assert_int_eq(b.prims_of.n_quads, 0);
    bvh_free(&b);
    sc.integrator = INTEGRATOR_PATHTRACER;
    lights ls;
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, NULL, &err), 0);
    ck_assert_int_eq(lights_scene_bvh(&b, &sc, NULL, &err), 0);
    ck_assert_int_eq(b.prims_of.n_quads, 300);
    rng g;
    rng_seed(&g, 98, 0);
    int hits = 0;
    for (int i = 0; i < 4000; i++) {
        vec3 o = vec3_make(12 * (2 * rng_uniform(&g) - 1), 12 * (2 * rng_uniform(&g) - 1), 12);
        const scene_light *l = &sc.lights[3 * (int)(rng_uniform(&g) * 300) + 2];
        double u = rng_uniform(&g), v = rng_uniform(&g);
        vec3 q = vec3_add(l->pos, vec3_add(vec3_scale(l->ab, u), vec3_scale(l->ac, v)));
        ray r = {o, vec3_normalize(vec3_sub(q, o)), 0, i % 3 ? INFINITY : 14};
        int k0 = -1;
        double t0 = 0;
        int h0 = nearest_quad_by_testing_all(&sc, &r, &k0, &t0);
        hit h;
        ck_require((bvh_intersect(&b, &r, &h) == BVH_QUAD) == h0);
        ck_require(bvh_occluded(&b, &r) == h0);
        if (!h0) continue;
        if (!(ls.quad_light[h.prim] == k0 && h.t == t0))
            ck_abort_msg("ray %d: quad %d at t %.17g, testing all: %d at %.17g", i,
                         ls.quad_light[h.prim], h.t, k0, t0);
        hits++;
    }
    ck_assert_int_gt(hits, 1000);
    bvh_free(&b);
    lights_free(&ls);
    scene_free(&sc);
}
END_TEST

/* A ray tests the quads along one path of a BVH, not every light: many quads get a tree of
 * depth O(log n) (SAH leaves of up to BVH_LEAF_MAX quads), a few a plain loop, and a scene
 * of point and directional lights nothing to test at all */
START_TEST(test_lights_quads_get_a_bvh_and_other_lights_none)
{
    scene sc;
    load_many_quads(&sc, 300, 3);
    lights ls;
    error err = {0};
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, NULL, &err), 0);
    ck_assert(ls.quad_bvh.is_tree);
    ck_assert_int_eq(ls.quad_bvh.n_prims, 300); /* one parallelogram a quad */
    ck_assert_int_le(ls.quad_bvh.depth, 24);    /* a balanced tree of 300 / 4 leaves: ~7 levels */
    lights_free(&ls);
    scene_free(&sc);

    load_many_quads(&sc, 4, 3);
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, NULL, &err), 0);
    ck_assert(!ls.quad_bvh.is_tree); /* 4 quads: at most BVH_MIN_PRIMS, tested in a loop */
    lights_free(&ls);
    scene_free(&sc);

    const char *points =
        "size 8 8\ncamera 0 0 5  0 0 0  0 1 0  45\npoint 0 3 0  1 1 1\ndirectional 0 1 0  1 1 1\n";
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    ck_assert_int_eq(scene_load_string(points, "points.test", &o, &sc, &err), 0);
    ck_assert_int_eq(lights_build(&ls, &sc, NULL, 3, NULL, &err), 0);
    ck_assert_int_eq(ls.n, 2);
    ck_assert_int_eq(ls.n_quads, 0);
    ck_assert_ptr_null(ls.quad_light);
    int k;
    double t;
    ray r = {vec3_make(0, 0, 0), vec3_make(0, 1, 0), 0, INFINITY};
    ck_assert(!lights_intersect_quad(&ls, &r, &k, &t));
    lights_free(&ls);
    scene_free(&sc);
}
END_TEST

Suite *lights_suite(void)
{
    Suite *s = suite_create("lights");
    TCase *tc = tcase_create("lights");
    tcase_add_test(tc, test_lights_pick_probability_is_proportional_to_power);
    tcase_add_test(tc, test_lights_selection_probability_follows_the_selection);
    tcase_add_test(tc, test_lights_pick_probabilities_of_powers_past_the_largest_double);
    tcase_add_test(tc, test_lights_quad_sample_pdf_matches_lights_quad_pdf);
    tcase_add_test(tc, test_lights_quad_emits_on_the_side_of_ac_cross_ab);
    tcase_add_test(tc, test_lights_delta_lights_give_intensity_over_attenuation);
    tcase_add_test(tc, test_lights_point_attenuation_uses_all_three_terms_at_the_distance);
    tcase_add_test(tc, test_lights_median_cut_shadow_ray_is_jittered_in_the_stratum);
    tcase_add_test(tc, test_lights_intersect_quad_finds_the_nearest_quad_of_many);
    tcase_add_test(tc, test_lights_quads_get_a_bvh_and_other_lights_none);
    tcase_add_test(tc, test_lights_scene_bvh_holds_the_quads_and_finds_the_nearest);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(lights_suite)
