/* test_mediancut.c - Debevec's median cut (include/envtex/envlight/mediancut.h), through the
 * light that uses it (`envsampling mediancut N`, envlight.h): the strata cover the map once and
 * carry its power, the cuts follow energy and angle, each point light sits at its stratum's
 * energy centroid, and the shadow rays are jittered over the whole stratum.
 */
#include "envtex/envlight/mediancut.h"
#include "envtex/envlight/envlight.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/core/rng.h"
#include "envtex/core/sampling.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/envmaps/latlong.h"
#include "unit.h"

#define POWER_REL_TOL 1e-9 /* median-cut powers against a sum in double */

static void fill(image *im, int w, int h)
{
    error err = {0};
    ck_assert_int_eq(image_alloc(im, w, h, &err), 0);
}

static void set_gray(image *im, int c, int r, double v) { image_set(im, c, r, rgb_gray(v)); }

/* A 64 x 32 sun map, the sun 10^3 times the sky. */
static void small_sun_map(image *im)
{
    genenv_params gp = genenv_defaults();
    gp.width = 64;
    gp.sun_ratio = 1e3;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_SUN, &gp, im, &err), 0);
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

/* the median-cut light of env with n point lights */
static void build(envlight *el, const envmap *env, int n)
{
    error err = {0};
    if (envlight_build(el, env, ENVSAMPLING_MEDIANCUT, ENVSAMPLER_BINARY, n, NULL, &err))
        ck_abort_msg("envlight_build: %s", err.msg);
}

/* the texel of world direction w */
static void texel_of(const envlight *el, vec3 w, int *c, int *r)
{
    uv2 uv;
    ck_require(latlong_dir_to_uv(mat4_dir(&el->env->to_env, w), &uv) == 0);
    *c = (int)(uv.u * el->w);
    *r = (int)(uv.v * el->h);
    if (*c >= el->w) *c = el->w - 1;
    if (*r >= el->h) *r = el->h - 1;
}

/* N strata cover the map exactly once, their powers sum to the map's power per channel, picks
 * follow power, the shadow ray's jitter stays inside the stratum (through a rotation) */
START_TEST(test_mediancut_strata_partition_the_map_and_its_power)
{
    const int ns[] = {1, 10, 64};
    image im;
    small_sun_map(&im);
    envmap env = env_of(&im, 2, mat4_rotate(vec3_make(0.3, 1, 0.2), 40));
    static int cover[64 * 32];
    double want[3] = {0, 0, 0};
    for (int r = 0; r < 32; r++)
        for (int c = 0; c < 64; c++)
            for (int k = 0; k < 3; k++)
                want[k] += 2.0 * image_px(&im, c, r)[k] * latlong_texel_solid_angle(r, 64, 32);
    for (int t = 0; t < 3; t++) {
        envlight el;
        build(&el, &env, ns[t]);
        ck_assert_int_eq(el.n_points, ns[t]);
        memset(cover, 0, sizeof cover);
        double got[3] = {0, 0, 0}, avg_sum = 0;
        for (int k = 0; k < el.n_points; k++) {
            const mediancut_point *pt = &el.points[k];
            for (int c = pt->c0; c < pt->c1; c++)
                for (int r = pt->r0; r < pt->r1; r++) cover[r * 64 + c]++;
            got[0] += pt->power.r;
            got[1] += pt->power.g;
            got[2] += pt->power.b;
            avg_sum += rgb_avg(pt->power);
        }
        int miscovered = 0;
        for (int i = 0; i < 64 * 32; i++) miscovered += cover[i] != 1;
        ck_assert_msg(miscovered == 0, "N = %d: %d texels not covered exactly once", ns[t],
                      miscovered);
        ck_assert(fabs(got[0] - want[0]) < POWER_REL_TOL * want[0]);
        ck_assert(fabs(got[1] - want[1]) < POWER_REL_TOL * want[1]);
        ck_assert(fabs(got[2] - want[2]) < POWER_REL_TOL * want[2]);
        /* picks: probability power_avg / sum; the shadow direction jittered inside the stratum */
        rng g;
        rng_seed(&g, 31, (uint64_t)t);
        int bad = 0;
        for (int i = 0; i < 5000; i++) {
            int k, c, r;
            vec3 sd;
            double prob;
            ck_require(envlight_mediancut_pick(&el, rng_uniform(&g), rng_uniform(&g),
                                               rng_uniform(&g), &k, &sd, &prob));
            bad += fabs(prob - rgb_avg(el.points[k].power) / avg_sum) > 1e-12;
            texel_of(&el, sd, &c, &r);
            const mediancut_point *pt = &el.points[k];
            bad += c < pt->c0 || c >= pt->c1 || r < pt->r0 || r >= pt->r1;
        }
        ck_assert_int_eq(bad, 0);
        envlight_free(&el);
    }
    image_free(&im);
}
END_TEST

/* each point light lies inside its own stratum: the energy centroid in image coordinates, not
 * the 3D mean direction, which for a stratum wide in phi near a pole (a piece of a ring) lies
 * poleward of it, outside (it did: N = 64 on this map, stratum columns [32, 49) of row 5, point
 * in row 4) */
START_TEST(test_mediancut_points_lie_inside_their_strata)
{
    image im;
    small_sun_map(&im);
    envmap env = env_of(&im, 2, mat4_rotate(vec3_make(0.3, 1, 0.2), 40));
    const int ns[] = {1, 10, 64, 256};
    for (int t = 0; t < 4; t++) {
        envlight el;
        build(&el, &env, ns[t]);
        int outside = 0;
        for (int k = 0; k < el.n_points; k++) {
            const mediancut_point *pt = &el.points[k];
            int c, r;
            texel_of(&el, pt->dir, &c, &r);
            outside += c < pt->c0 || c >= pt->c1 || r < pt->r0 || r >= pt->r1;
        }
        ck_assert_msg(outside == 0, "N = %d: %d points outside their stratum", ns[t], outside);
        envlight_free(&el);
    }
    image_free(&im);
}
END_TEST

/* Each point light sits at its stratum's energy centroid, L dOmega weighted (Debevec 2005), in
 * image coordinates: u = sum e (c + 1/2) / (W sum e), v = sum e (r + 1/2) / (H sum e) with
 * e = L_avg(c, r) dOmega_r, dOmega_r = (cos(pi r / H) - cos(pi (r + 1) / H)) 2 pi / W computed
 * here from the texels, then turned by the envmap's rotation.  Catches the texels weighted by L
 * alone (strata spanning rows of different solid angle: points off by up to 0.06 in uv here). */
START_TEST(test_mediancut_points_sit_at_their_strata_energy_centroids)
{
    image im;
    small_sun_map(&im);
    const int ns[] = {10, 64, 256};
    const double s = 2; /* the envmap's scale, which cancels in the centroid */
    mat4 rot = mat4_rotate(vec3_make(0.3, 1, 0.2), 40);
    for (int t = 0; t < 3; t++) {
        envmap env = env_of(&im, s, rot);
        envlight el;
        build(&el, &env, ns[t]);
        int bad = 0, multirow = 0;
        double worst = 0;
        for (int k = 0; k < el.n_points; k++) {
            const mediancut_point *pt = &el.points[k];
            double su = 0, sv = 0, se = 0;
            for (int r = pt->r0; r < pt->r1; r++) {
                double om = (cos(M_PI * r / 32) - cos(M_PI * (r + 1) / 32)) * 2 * M_PI / 64;
                for (int c = pt->c0; c < pt->c1; c++) {
                    const float *px = image_px(&im, c, r);
                    double e = s * ((double)px[0] + px[1] + px[2]) / 3 * om;
                    su += e * (c + 0.5);
                    sv += e * (r + 0.5);
                    se += e;
                }
            }
            ck_assert(se > 0);
            uv2 want = {su / se / 64, sv / se / 32}, got;
            ck_assert_int_eq(latlong_dir_to_uv(mat4_dir(&el.env->to_env, pt->dir), &got), 0);
            double du = fabs(got.u - want.u), dv = fabs(got.v - want.v);
            worst = fmax(worst, fmax(du, dv));
            bad += !(du < 1e-9 && dv < 1e-9); /* sums in double: ~1e-15 */
            multirow += pt->r1 - pt->r0 > 1;
        }
        ck_assert_msg(multirow > 0, "N = %d: no stratum spans rows: the test cannot fail", ns[t]);
        ck_assert_msg(bad == 0,
                      "N = %d: %d of %d points off their L dOmega centroid (by up to %g in uv)",
                      ns[t], bad, el.n_points, worst);
        envlight_free(&el);
    }
    image_free(&im);
}
END_TEST

/* the shadow direction is uniform in (cos theta, phi) over its stratum: with one stratum, the
 * whole map, cos theta = 1 - 2 xi1 and phi = 2 pi xi2, which is sampling_uniform_sphere(xi1, xi2)
 * (a jitter over only part of the stratum, in either coordinate, would not be) */
START_TEST(test_mediancut_shadow_directions_cover_the_stratum)
{
    image im;
    small_sun_map(&im);
    envmap env = env_of(&im, 1, mat4_identity());
    envlight el;
    build(&el, &env, 1);
    ck_assert_int_eq(el.n_points, 1);
    rng g;
    rng_seed(&g, 47, 0);
    double worst = 0;
    for (int i = 0; i < 1000; i++) {
        double xi1 = i == 0 ? 0 : rng_uniform(&g), xi2 = i == 0 ? 0 : rng_uniform(&g), prob;
        int k;
        vec3 sd;
        ck_assert(envlight_mediancut_pick(&el, rng_uniform(&g), xi1, xi2, &k, &sd, &prob));
        worst = fmax(worst, vec3_length(vec3_sub(sd, sampling_uniform_sphere(xi1, xi2))));
    }
    ck_assert_msg(worst < 1e-12, "shadow directions off the uniform sphere's by up to %g", worst);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* on a constant map the strata carry about equal energy (median cut splits energy in halves) */
START_TEST(test_mediancut_strata_of_a_constant_map_have_equal_energy)
{
    image im;
    genenv_params gp = genenv_defaults();
    gp.width = 128;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_CONSTANT, &gp, &im, &err), 0);
    envmap env = env_of(&im, 1, mat4_identity());
    envlight el;
    build(&el, &env, 16);
    ck_assert_int_eq(el.n_points, 16);
    double lo = INFINITY, hi = 0;
    for (int k = 0; k < el.n_points; k++) {
        double e = rgb_avg(el.points[k].power);
        lo = fmin(lo, e);
        hi = fmax(hi, e);
    }
    /* a cut falls on a texel edge, so halves are equal only to a column or row of the region:
     * with 16 strata of ~512 texels each stays within 15% of the mean (measured: -14%, +9%;
     * a split of the longer side by area, ignoring energy, would be off by 2x) */
    double mean = 4 * M_PI / 16;
    ck_assert_msg(lo > 0.85 * mean && hi < 1.15 * mean, "strata energies from %g to %g (mean %g)",
                  lo, hi, mean);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* median cut splits a stratum across its longer side measured in angle, the phi side shortened
 * by sin theta (Debevec 2005).  A 64 x 32 map lit only in its two polar rows: the first cuts
 * give 4 strata of about 16 columns (15 to 17: a cut falls where the energy halves) x rows
 * [0, 2) holding all the light; each is ~16 * 2 pi / 64 * sin(pi / 32) = 0.15 rad long in phi
 * but 2 pi / 32 = 0.20 rad tall in theta, so it is cut across theta, into one-row strata.
 * Measuring phi without sin theta (0.15 rad as pi / 2) would cut it into strata two rows tall.
 * (The halves of the map, pi by pi, are a tie, cut either way: the test holds for both.)  With
 * 24 strata the one-row strata must be cut again, across phi (a stratum one texel tall but many
 * wide still splits), rather than the dark strata. */
START_TEST(test_mediancut_cuts_polar_strata_across_theta)
{
    image im;
    fill(&im, 64, 32);
    for (int c = 0; c < 64; c++) {
        set_gray(&im, c, 0, 1.0);
        set_gray(&im, c, 1, 1.0);
    }
    envmap env = env_of(&im, 1, mat4_identity());
    const int ns[2] = {12,
                       24}; /* 12: 4 dark strata, 8 lit; 24: the one-row strata cut across phi */
    for (int t = 0; t < 2; t++) {
        envlight el;
        build(&el, &env, ns[t]);
        ck_assert_int_eq(el.n_points, ns[t]);
        int lit = 0, tall = 0;
        for (int k = 0; k < el.n_points; k++) {
            const mediancut_point *pt = &el.points[k];
            if (!(rgb_avg(pt->power) > 0)) continue;
            lit++;
            tall += pt->r1 - pt->r0 != 1;
        }
        ck_assert_int_ge(lit, ns[t] - 4); /* lit strata are cut before dark ones (energy ~0) */
        ck_assert_msg(tall == 0, "N = %d: %d of the %d lit strata are more than one row tall",
                      ns[t], tall, lit);
        envlight_free(&el);
    }
    image_free(&im);
}
END_TEST

/* mediancut_build on its own: a 2 x 1 map of radiance 1 and 3 cut into 2 strata is its two
 * texels, each a point light at its centre (envmap frame) with power L dOmega, picked by power
 * (1/4, 3/4); the jitter at (1/2, 1/2) is the middle of the stratum in (cos theta, phi). */
START_TEST(test_mediancut_two_strata_of_a_two_texel_map_are_its_texels)
{
    image im;
    fill(&im, 2, 1);
    set_gray(&im, 0, 0, 1);
    set_gray(&im, 1, 0, 3);
    const double row_omega[1] = {2 * M_PI}, cos_edge[2] = {1, -1};
    const double energy[2] = {1 * row_omega[0], 3 * row_omega[0]};
    mediancut_map m = {&im, 1, energy, row_omega};
    mediancut_point *pts;
    int n;
    distrib1d choice;
    error err = {0};
    ck_assert_int_eq(mediancut_build(&m, 2, &pts, &n, &choice, &err), 0);
    ck_assert_int_eq(n, 2);
    for (int k = 0; k < 2; k++) { /* the strata in any order: c, the texel of stratum k */
        int c = pts[k].c0;
        ck_assert(pts[k].c1 == c + 1 && pts[k].r0 == 0 && pts[k].r1 == 1);
        ck_assert(fabs(pts[k].power.g - (1 + 2 * c) * 2 * M_PI) < 1e-12);
        vec3 want = latlong_uv_to_dir((uv2){0.25 + 0.5 * c, 0.5});
        ck_assert(vec3_length(vec3_sub(pts[k].dir, want)) < 1e-12);
        ck_assert(fabs(distrib1d_pmf(&choice, k) - 0.25 * (1 + 2 * c)) < 1e-12);
    }
    const mediancut_point *right = pts[0].c0 == 1 ? &pts[0] : &pts[1];
    vec3 d = mediancut_jitter(right, 2, cos_edge, 0.5, 0.5); /* cos theta 0, phi 3 pi / 2 */
    ck_assert_msg(vec3_length(vec3_sub(d, vec3_make(0, -1, 0))) < 1e-12, "jitter (%g, %g, %g)", d.x,
                  d.y, d.z);
    free(pts);
    distrib1d_free(&choice);
    image_free(&im);
}
END_TEST

Suite *mediancut_suite(void)
{
    Suite *s = suite_create("mediancut");
    TCase *tc = tcase_create("mediancut");
    tcase_add_test(tc, test_mediancut_two_strata_of_a_two_texel_map_are_its_texels);
    tcase_add_test(tc, test_mediancut_strata_partition_the_map_and_its_power);
    tcase_add_test(tc, test_mediancut_points_lie_inside_their_strata);
    tcase_add_test(tc, test_mediancut_points_sit_at_their_strata_energy_centroids);
    tcase_add_test(tc, test_mediancut_shadow_directions_cover_the_stratum);
    tcase_add_test(tc, test_mediancut_strata_of_a_constant_map_have_equal_energy);
    tcase_add_test(tc, test_mediancut_cuts_polar_strata_across_theta);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(mediancut_suite)
