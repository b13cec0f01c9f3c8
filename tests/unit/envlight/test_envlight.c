/* test_envlight.c - the environment as a light (include/envtex/envlight/envlight.h).
 *
 * Every sampling mode (uniform, cdf, cdf-sintheta; binary search and alias tables) on the maps
 * the lecture's corner cases reduce to (one lit texel, constant, 1 x 1, 3 x 2, a sun 10^6 times
 * the sky, light only in the pole rows) is tested against its own pdf with a chi-square test
 * over equal solid-angle bins (sphchisq.h, cut at the texel edges so the expected counts are
 * exact).  Then the numerics the issue lists: an all-black map falls back to uniform, zero rows
 * and columns are never chosen, xi at 0, 1 - 2^-24 and 1 stay in range, bad texels are counted
 * and dark, a 4096 x 2048 table is normalized, pdf = L / |L| for the cdf mode, the envmap's
 * rotation is respected, a translation or uniform scale changes nothing and a non-uniform scale
 * is refused.  Median cut's strata: test_mediancut.c.
 */
#include "envtex/envlight/envlight.h"
#include "envtex/core/sampling.h"

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "chisq.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/envmaps/latlong.h"
#include "envtex/core/rng.h"
#include "sphchisq.h"
#include "unit.h"

#define N_SAMPLES      100000L /* per chi-square test */
#define N_U            16
#define N_PHI          32
#define PDF_REL_TOL    1e-5 /* a sample's pdf against envlight_pdf (issue 4) */
#define CANCEL_REL_TOL 1e-9 /* pdf |L| = L_avg: one division and a sum in double */

/* ---- the maps ---------------------------------------------------------------------------------
 */
enum { M_ONE_HOT, M_CONSTANT, M_1X1, M_3X2, M_SUN, M_POLES, M_COUNT };
static const char *const map_name[M_COUNT] = {"one-hot", "constant", "1 x 1",
                                              "3 x 2",   "sun 10^6", "pole rows"};

static void fill(image *im, int w, int h)
{
    error err = {0};
    ck_assert_int_eq(image_alloc(im, w, h, &err), 0);
}

static void set_gray(image *im, int c, int r, double v) { image_set(im, c, r, rgb_gray(v)); }

/* A 64 x 32 sun map, the sun 10^3 times the sky: the small map of the rotation and median-cut
 * tests. */
static void small_sun_map(image *im)
{
    genenv_params gp = genenv_defaults();
    gp.width = 64;
    gp.sun_ratio = 1e3;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_SUN, &gp, im, &err), 0);
}

static void make_map(int which, image *im)
{
    error err = {0};
    switch (which) {
    case M_ONE_HOT:
        fill(im, 16, 8);
        set_gray(im, 5, 3, 2.0);
        break;
    case M_CONSTANT:
        fill(im, 16, 8);
        for (int r = 0; r < 8; r++)
            for (int c = 0; c < 16; c++) set_gray(im, c, r, 0.7);
        break;
    case M_1X1:
        fill(im, 1, 1);
        image_set(im, 0, 0, rgb_make(3, 1, 2));
        break;
    case M_3X2: {
        const double v[6] = {1.0, 0.0, 2.5, 0.5, 4.0, 1.5};
        fill(im, 3, 2);
        for (int k = 0; k < 6; k++) set_gray(im, k % 3, k / 3, v[k]);
        break;
    }
    case M_SUN: {
        genenv_params p = genenv_defaults();
        p.width = 64;
        p.sun_ratio = 1e6;
        p.sun_radius_deg = 3;
        ck_assert_int_eq(genenv_make(GENENV_SUN, &p, im, &err), 0);
        break;
    }
    default: /* only the first and the last row are lit */
        fill(im, 16, 8);
        for (int c = 0; c < 16; c++) {
            set_gray(im, c, 0, 1 + c % 3);
            set_gray(im, c, 7, c % 4 == 0 ? 0 : 2);
        }
        break;
    }
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

/* the texel of world direction w: what envlight.c must agree with */
static void texel_of(const envlight *el, vec3 w, int *c, int *r)
{
    uv2 uv;
    ck_require(latlong_dir_to_uv(mat4_dir(&el->env->to_env, w), &uv) == 0);
    *c = (int)(uv.u * el->w);
    *r = (int)(uv.v * el->h);
    if (*c >= el->w) *c = el->w - 1;
    if (*r >= el->h) *r = el->h - 1;
}

static double texel_avg(const image *im, int c, int r)
{
    const float *p = image_px(im, c, r);
    double s = 0;
    for (int k = 0; k < 3; k++) s += isfinite(p[k]) && p[k] > 0 ? p[k] : 0;
    return s / 3;
}

/* 1 if world direction w lies in a lit texel or on the edge of one (within EDGE_TOL of a texel
 * width): a sample at xi = 0 lies exactly on the edge of the texel it chose */
#define EDGE_TOL 1e-9
static int lit_or_on_lit_edge(const envlight *el, const image *im, vec3 w)
{
    uv2 uv;
    if (latlong_dir_to_uv(mat4_dir(&el->env->to_env, w), &uv)) return 0;
    double x = uv.u * el->w, y = uv.v * el->h;
    for (int i = -1; i <= 1; i += 2)
        for (int j = -1; j <= 1; j += 2) {
            int c = (int)floor(x + i * EDGE_TOL), r = (int)floor(y + j * EDGE_TOL);
            c = (c % el->w + el->w) % el->w; /* the phi seam wraps */
            if (r < 0 || r >= el->h) continue;
            if (texel_avg(im, c, r) > 0) return 1;
        }
    return 0;
}

/* ---- chi-square of every mode ------------------------------------------------------------------
 */
enum { C_UNIFORM, C_CDF_BINARY, C_CDF_ALIAS, C_SIN_BINARY, C_SIN_ALIAS, C_COUNT };
static const envsampling_mode cfg_mode[C_COUNT] = {ENVSAMPLING_UNIFORM, ENVSAMPLING_CDF,
                                                   ENVSAMPLING_CDF, ENVSAMPLING_CDF_SINTHETA,
                                                   ENVSAMPLING_CDF_SINTHETA};
static const envsampler_kind cfg_sampler[C_COUNT] = {
    ENVSAMPLER_BINARY, ENVSAMPLER_BINARY, ENVSAMPLER_ALIAS, ENVSAMPLER_BINARY, ENVSAMPLER_ALIAS};
static const char *const cfg_name[C_COUNT] = {"uniform", "cdf binary", "cdf alias",
                                              "cdf-sintheta binary", "cdf-sintheta alias"};
#define N_ROTATED     4
#define N_CHISQ_TESTS (M_COUNT * C_COUNT + N_ROTATED)

typedef struct frame_ctx {
    const envlight *el;
    mat4 to_world;
} frame_ctx;

/* pdf at a direction given in the envmap frame (the grid's frame) */
static double pdf_in_frame(void *ctx, vec3 d)
{
    const frame_ctx *f = ctx;
    return envlight_pdf(f->el, mat4_dir(&f->to_world, d));
}

/* chi-square of N_SAMPLES samples of *el binned in the envmap frame; also every sample's pdf
 * and L must be envlight_pdf and envlight_radiance at its direction */
static void check_chisq(const envlight *el, const char *what, uint64_t seed)
{
    static double prob[SPH_MAX_BINS + 1], tb[SPH_MAX_BREAKS], pb[SPH_MAX_BREAKS];
    static long obs[SPH_MAX_BINS + 1];
    ck_assert(el->h + 1 <= SPH_MAX_BREAKS && el->w + 1 <= SPH_MAX_BREAKS);
    for (int r = 0; r <= el->h; r++) tb[r] = M_PI * r / el->h; /* texel edges: theta = pi r / H */
    for (int c = 0; c <= el->w; c++) pb[c] = 2 * M_PI * c / el->w; /* phi = 2 pi c / W */
    sph_grid g = sph_grid_make(N_U, N_PHI);
    g.sub = 1;
    g.theta_breaks = tb;
    g.n_theta_breaks = el->h + 1;
    g.phi_breaks = pb;
    g.n_phi_breaks = el->w + 1;
    frame_ctx f = {el, mat4_transpose(el->env->to_env)};
    double total = sph_expected(&g, pdf_in_frame, &f, prob);
    ck_assert_msg(fabs(total - 1) < 1e-9, "%s: pdf integrates to %.12f", what, total);
    int nb = sph_n_bins(&g);
    for (int k = 0; k < nb; k++) obs[k] = 0;
    rng r;
    rng_seed(&r, seed, 11);
    long failed = 0, pdf_bad = 0, L_bad = 0;
    for (long i = 0; i < N_SAMPLES; i++) {
        envlight_sample_result s;
        if (!envlight_sample(el, rng_uniform(&r), rng_uniform(&r), &s)) {
            failed++;
            continue;
        }
        double p = envlight_pdf(el, s.wi);
        pdf_bad += !(fabs(s.pdf - p) <= PDF_REL_TOL * p) || !(s.pdf > 0);
        rgb L = envlight_radiance(el, s.wi);
        L_bad += L.r != s.L.r || L.g != s.L.g || L.b != s.L.b;
        obs[sph_bin(&g, mat4_dir(&el->env->to_env, s.wi))]++;
    }
    ck_assert_msg(failed == 0, "%s: %ld samples failed", what, failed);
    ck_assert_msg(pdf_bad == 0, "%s: %ld samples' pdf differs from envlight_pdf", what, pdf_bad);
    ck_assert_msg(L_bad == 0, "%s: %ld samples' L differs from envlight_radiance", what, L_bad);
    chisq_result res = chisq_test(obs, prob, nb, N_SAMPLES);
    ck_assert_msg(chisq_accept(&res, N_CHISQ_TESTS), "%s: X^2 = %g, dof %d, p = %g, stray %ld",
                  what, res.stat, res.dof, res.p, res.stray);
}

START_TEST(test_envlight_every_mode_fits_its_pdf_on_every_map)
{
    int map = _i / C_COUNT, cfg = _i % C_COUNT;
    image im;
    make_map(map, &im);
    envmap env = env_of(&im, 1, mat4_identity());
    envlight el;
    build(&el, &env, cfg_mode[cfg], cfg_sampler[cfg], 0);
    char what[128];
    snprintf(what, sizeof what, "%s map, %s", map_name[map], cfg_name[cfg]);
    check_chisq(&el, what, 1000 + (uint64_t)_i);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* the same with the envmap rotated: bins in the envmap frame, directions mapped through to_env */
START_TEST(test_envlight_rotated_map_fits_its_pdf)
{
    int map = _i < 2 ? M_ONE_HOT : M_SUN, cfg = _i % 2 ? C_CDF_ALIAS : C_SIN_BINARY;
    image im;
    make_map(map, &im);
    envmap env = env_of(&im, 1.5, mat4_rotate(vec3_make(1, 2, -0.5), 71));
    envlight el;
    build(&el, &env, cfg_mode[cfg], cfg_sampler[cfg], 0);
    char what[128];
    snprintf(what, sizeof what, "rotated %s map, %s", map_name[map], cfg_name[cfg]);
    check_chisq(&el, what, 2000 + (uint64_t)_i);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* a rotated one-hot map: every sample, taken back to the envmap frame, is in the lit texel, and
 * is NOT there in the world frame (the rotation was applied, not ignored); the pdf follows */
START_TEST(test_envlight_rotation_moves_samples_and_pdf_with_the_map)
{
    image im;
    make_map(M_ONE_HOT, &im);
    envmap env = env_of(&im, 1, mat4_rotate(vec3_make(0, 1, 0), 90));
    envlight el;
    build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0);
    rng r;
    rng_seed(&r, 3, 0);
    int outside = 0, unrotated = 0;
    for (int i = 0; i < 2000; i++) {
        envlight_sample_result s;
        ck_assert(envlight_sample(&el, rng_uniform(&r), rng_uniform(&r), &s));
        int c, rr;
        texel_of(&el, s.wi, &c, &rr);
        outside += c != 5 || rr != 3;
        uv2 uv;
        latlong_dir_to_uv(s.wi, &uv);
        unrotated += (int)(uv.u * 16) == 5 && (int)(uv.v * 8) == 3;
    }
    ck_assert_int_eq(outside, 0);
    ck_assert_int_eq(unrotated, 0);
    /* the pdf of the lit texel's centre, seen in the world */
    mat4 to_world = mat4_transpose(env.to_env);
    vec3 centre = mat4_dir(&to_world, latlong_uv_to_dir((uv2){5.5 / 16, 3.5 / 8}));
    double om = latlong_texel_solid_angle(3, 16, 8);
    ck_assert_near(envlight_pdf(&el, centre) * om, 1, 1e-12);
    ck_assert(envlight_pdf(&el, latlong_uv_to_dir((uv2){5.5 / 16, 3.5 / 8})) == 0);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

static int same_rgb(rgb a, rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

/* Directions see only the linear part of the envmap's transform: a translation (the envmap is at
 * infinity) and a uniform scale change nothing, so the envlight built with them samples the same
 * world directions, with the same pdf and L, as the one built with the rotation alone (they were
 * refused as "not a rotation", so the path tracer would not render a scene the ray tracer
 * renders).  Uniform sampling, which only looks the map up, takes any transform. */
START_TEST(test_envlight_translation_and_uniform_scale_sample_as_the_rotation_alone)
{
    image im;
    small_sun_map(&im);
    mat4 rot = mat4_rotate(vec3_make(0.3, 1, 0.2), 40);
    /* envmap frame -> world: translate(1, -2, 3) rotate scale(2.5); to_env is its inverse */
    mat4 xf = mat4_mul(mat4_translate(vec3_make(1, -2, 3)),
                       mat4_mul(rot, mat4_scale(vec3_make(2.5, 2.5, 2.5))));
    mat4 inv_rot, inv_xf;
    ck_assert_int_eq(mat4_inverse(rot, &inv_rot), 0);
    ck_assert_int_eq(mat4_inverse(xf, &inv_xf), 0);
    envmap er = env_of(&im, 1, inv_rot), ex = env_of(&im, 1, inv_xf);
    const envsampling_mode modes[] = {ENVSAMPLING_CDF, ENVSAMPLING_CDF_SINTHETA,
                                      ENVSAMPLING_MEDIANCUT, ENVSAMPLING_UNIFORM};
    long bad = 0;
    for (int m = 0; m < 4; m++) {
        envlight a, b;
        build(&a, &er, modes[m], ENVSAMPLER_ALIAS, 16);
        build(&b, &ex, modes[m], ENVSAMPLER_ALIAS, 16);
        rng g;
        rng_seed(&g, 41, (uint64_t)m);
        for (int i = 0; i < 2000; i++) {
            double x1 = rng_uniform(&g), x2 = rng_uniform(&g), x3 = rng_uniform(&g);
            if (modes[m] == ENVSAMPLING_MEDIANCUT) {
                int ka, kb;
                vec3 da, db;
                double pa, pb;
                ck_assert(envlight_mediancut_pick(&a, x1, x2, x3, &ka, &da, &pa));
                ck_assert(envlight_mediancut_pick(&b, x1, x2, x3, &kb, &db, &pb));
                bad += ka != kb || pa != pb || vec3_length(vec3_sub(da, db)) > 1e-12 ||
                       vec3_length(vec3_sub(a.points[ka].dir, b.points[kb].dir)) > 1e-12;
                continue;
            }
            envlight_sample_result sa, sb;
            ck_require(envlight_sample(&a, x1, x2, &sa));
            ck_require(envlight_sample(&b, x1, x2, &sb));
            vec3 w =
                sampling_uniform_sphere(x3, rng_uniform(&g)); /* any direction, for the lookups */
            bad +=
                vec3_length(vec3_sub(sa.wi, sb.wi)) > 1e-12 || fabs(sa.pdf / sb.pdf - 1) > 1e-12 ||
                !same_rgb(sa.L, sb.L) ||
                !(fabs(envlight_pdf(&a, w) - envlight_pdf(&b, w)) <= 1e-12 * envlight_pdf(&a, w)) ||
                !same_rgb(envlight_radiance(&a, w), envlight_radiance(&b, w));
        }
        envlight_free(&a);
        envlight_free(&b);
    }
    ck_assert_msg(bad == 0, "%ld samples or lookups differ from the rotation alone", bad);
    /* uniform sampling under a non-uniform scale: the light is what the envmap frame holds in
     * the direction the transform gives, as for the background */
    mat4 sq = mat4_scale(vec3_make(1, 1, 0.25));
    envmap es = env_of(&im, 1, sq);
    envlight u;
    build(&u, &es, ENVSAMPLING_UNIFORM, ENVSAMPLER_BINARY, 0);
    rng g;
    rng_seed(&g, 43, 0);
    for (int i = 0; i < 500; i++) {
        vec3 w = sampling_uniform_sphere(rng_uniform(&g), rng_uniform(&g));
        bad += !same_rgb(envlight_radiance(&u, w), latlong_lookup_nearest(&im, mat4_dir(&sq, w)));
    }
    ck_assert_msg(bad == 0, "%ld uniform-mode lookups through a non-uniform scale are off", bad);
    envlight_free(&u);
    image_free(&im);
}
END_TEST

/* a transform with a scale (or shear) cannot be sampled: refused with a message.  The tolerance
 * is relative to the overall scale: a tiny transform (1e-4, 1e-4, 2e-4) distorts as much as
 * (1, 1, 2), though A A^T is within 1e-6 of s^2 I in absolute terms. */
START_TEST(test_envlight_non_rotation_transform_is_refused)
{
    image im;
    make_map(M_CONSTANT, &im);
    mat4 bad[3] = {mat4_scale(vec3_make(2, 1, 1)),
                   mat4_mul(mat4_rotate(vec3_make(0, 0, 1), 30), mat4_scale(vec3_make(1, 1, 0.5))),
                   mat4_scale(vec3_make(1e-4, 1e-4, 2e-4))};
    for (int i = 0; i < 3; i++) {
        envmap env = env_of(&im, 1, bad[i]);
        envlight el;
        error err = {0};
        ck_assert_int_eq(
            envlight_build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0, NULL, &err), -1);
        ck_assert_msg(strstr(err.msg, "rotation") != NULL, "message: %s", err.msg);
        envlight_free(&el); /* safe after a failure */
    }
    image_free(&im);
}
END_TEST

/* ---- numerics -----------------------------------------------------------------------------------
 */

/* an all-black map falls back to uniform sampling (fell_back = 1), in every mode */
START_TEST(test_envlight_all_black_map_falls_back_to_uniform)
{
    image im;
    fill(&im, 16, 8);
    envmap env = env_of(&im, 1, mat4_identity());
    envsampling_mode modes[3] = {ENVSAMPLING_CDF, ENVSAMPLING_CDF_SINTHETA, ENVSAMPLING_UNIFORM};
    for (int m = 0; m < 3; m++) {
        envlight el;
        build(&el, &env, modes[m], ENVSAMPLER_ALIAS, 0);
        ck_assert_int_eq(el.fell_back, 1);
        ck_assert_int_eq(el.mode, ENVSAMPLING_UNIFORM);
        ck_assert(el.power == 0);
        envlight_sample_result s;
        ck_assert(envlight_sample(&el, 0.3, 0.8, &s));
        ck_assert_near(s.pdf, 1 / (4 * M_PI), 1e-15);
        ck_assert(rgb_is_black(s.L));
        envlight_free(&el);
    }
    envlight el;
    build(&el, &env, ENVSAMPLING_MEDIANCUT, ENVSAMPLER_BINARY, 8);
    ck_assert_int_eq(el.fell_back, 1);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* a map with whole zero rows and columns (and scattered zero texels): over random and swept
 * inputs, xi exactly 0, 1 - 2^-24, the largest double below 1, and exactly 1, the sampled texel
 * is always in range and lit, in both CDF modes with both samplers */
START_TEST(test_envlight_zero_texels_and_edge_xi_are_never_sampled)
{
    image im;
    fill(&im, 24, 12);
    rng r;
    rng_seed(&r, 17, 0);
    for (int y = 0; y < 12; y++)
        for (int x = 0; x < 24; x++) {
            int zero_line =
                y == 0 || y == 5 || y == 11 || x == 0 || x == 7 || x == 23 || rng_uniform(&r) < 0.2;
            set_gray(&im, x, y, zero_line ? 0 : 0.1 + rng_uniform(&r));
        }
    envmap env = env_of(&im, 1, mat4_identity());
    const double edge[] = {0.0, 0x1p-24, 0.5, 1 - 0x1p-24, 0x1.fffffffffffffp-1, 1.0};
    int n_edge = (int)(sizeof edge / sizeof edge[0]);
    long bad = 0;
    for (int cfg = C_CDF_BINARY; cfg < C_COUNT; cfg++) {
        envlight el;
        build(&el, &env, cfg_mode[cfg], cfg_sampler[cfg], 0);
        for (int i = 0; i < 20000 + n_edge * n_edge; i++) {
            double xi1, xi2;
            if (i < n_edge * n_edge) {
                xi1 = edge[i % n_edge];
                xi2 = edge[i / n_edge];
            } else {
                xi1 = rng_uniform(&r);
                xi2 = rng_uniform(&r);
            }
            for (int force = 0; force < 2; force++) {
                envlight_sample_result s;
                if (!(force ? envlight_sample_stratified(&el, xi1, xi2, &s)
                            : envlight_sample(&el, xi1, xi2, &s))) {
                    bad++;
                    continue;
                }
                bad += !lit_or_on_lit_edge(&el, &im, s.wi);
                bad +=
                    !(s.pdf > 0) || !isfinite(s.pdf) || rgb_is_black(s.L) || !vec3_is_finite(s.wi);
            }
        }
        envlight_free(&el);
    }
    ck_assert_msg(bad == 0, "%ld samples out of range or on a zero texel", bad);
    image_free(&im);
}
END_TEST

/* A sample's direction must be a unit vector to the last few ulps and lie in the one lit
 * column, on maps 1 to 2000 columns wide; and on a constant map, where phi is known, it must be
 * that phi to a few ulps (phi = 2 pi (c + rc) / w, not e.g. the column's centre). */
#define UNIT_TOL 1e-15
#define PHI_TOL  1e-14 /* radians: a few ulps of 2 pi */
START_TEST(test_envlight_sampled_phi_is_unit_and_in_its_column)
{
    const int widths[] = {1, 2, 3, 7, 255, 256, 257, 2000};
    rng g;
    rng_seed(&g, 23, 0);
    double worst = 0;
    long outside = 0;
    for (size_t k = 0; k < sizeof widths / sizeof widths[0]; k++) {
        int w = widths[k], h = w > 1 ? w / 2 : 1, lit = w / 3;
        image im;
        fill(&im, w, h);
        for (int r = 0; r < h; r++) set_gray(&im, lit, r, 1.0 + r);
        envmap env = env_of(&im, 1, mat4_identity());
        for (int cfg = C_CDF_BINARY; cfg < C_COUNT; cfg++) {
            envlight el;
            build(&el, &env, cfg_mode[cfg], cfg_sampler[cfg], 0);
            for (int i = 0; i < 20000; i++) {
                double xi1 = i < 3 ? 0.5 * i : rng_uniform(&g); /* 0, 1/2, 1 and random */
                envlight_sample_result s;
                ck_require(envlight_sample(&el, xi1, rng_uniform(&g), &s));
                double e = fabs(vec3_dot(s.wi, s.wi) - 1);
                worst = e > worst ? e : worst;
                uv2 uv;
                ck_require(latlong_dir_to_uv(s.wi, &uv) == 0);
                double x = uv.u * w; /* in [lit, lit + 1], or at the seam 0 = w for column 0 */
                int in = (x > lit - EDGE_TOL && x < lit + 1 + EDGE_TOL) ||
                         (lit == 0 && x > w - EDGE_TOL);
                outside += !in;
            }
            envlight_free(&el);
        }
        image_free(&im);
    }
    ck_assert_msg(worst <= UNIT_TOL, "| |wi|^2 - 1 | up to %.3g", worst);
    ck_assert_msg(outside == 0, "%ld samples outside the lit column", outside);
    /* a constant one-row map a power of two wide (up to 256, in the weights' rounding): every
     * column equally likely and the CDF exact to an ulp, so phi = 2 pi (c + rc) / w = 2 pi xi1,
     * and the table's phi must be that angle (atan2 of the sample).  Wider, the CDF's rounding,
     * times w in the remapped value, reaches ~1e-13 */
    const int pow2[] = {1, 2, 4, 256};
    double worst_phi = 0;
    for (size_t k = 0; k < sizeof pow2 / sizeof pow2[0]; k++) {
        int w = pow2[k];
        image im;
        fill(&im, w, 1);
        for (int c = 0; c < w; c++) set_gray(&im, c, 0, 0.5);
        envmap env = env_of(&im, 1, mat4_identity());
        for (int cfg = C_CDF_BINARY; cfg < C_COUNT; cfg++) {
            envlight el;
            build(&el, &env, cfg_mode[cfg], cfg_sampler[cfg], 0);
            for (int i = 0; i < 20000; i++) {
                double xi1 = rng_uniform(&g);
                envlight_sample_result s;
                ck_require(envlight_sample(&el, xi1, rng_uniform(&g), &s));
                double phi = atan2(s.wi.y, s.wi.x), want = 2 * M_PI * xi1;
                if (phi < 0) phi += 2 * M_PI;
                double e = fabs(phi - want);
                e = e < 2 * M_PI - e ? e : 2 * M_PI - e; /* 0 and 2 pi are one angle */
                worst_phi = e > worst_phi ? e : worst_phi;
            }
            envlight_free(&el);
        }
        image_free(&im);
    }
    ck_assert_msg(worst_phi <= PHI_TOL, "phi off 2 pi xi by up to %.3g", worst_phi);
}
END_TEST

/* The last column at xi1 -> 1: its remapped rc is within an ulp of 1, so c + rc rounds to w.
 * With only the last column lit (p = 1, so rc is 1 - 2^-53), the sample is a unit vector in
 * that column, at its phi = 2 pi edge. */
START_TEST(test_envlight_last_column_at_xi_one_stays_in_its_column)
{
    const int widths[] = {2, 3, 7, 257, 2000};
    const double xi1s[] = {1.0, 0x1.fffffffffffffp-1, 1 - 0x1p-40};
    long bad = 0;
    for (size_t k = 0; k < sizeof widths / sizeof widths[0]; k++) {
        int w = widths[k], h = w / 2 > 0 ? w / 2 : 1;
        image im;
        fill(&im, w, h);
        for (int r = 0; r < h; r++) set_gray(&im, w - 1, r, 1.0);
        envmap env = env_of(&im, 1, mat4_identity());
        for (int cfg = C_CDF_BINARY; cfg < C_COUNT; cfg++) {
            envlight el;
            build(&el, &env, cfg_mode[cfg], cfg_sampler[cfg], 0);
            for (size_t i = 0; i < sizeof xi1s / sizeof xi1s[0]; i++) {
                envlight_sample_result s;
                ck_assert(envlight_sample(&el, xi1s[i], 0.3, &s));
                uv2 uv;
                ck_assert_int_eq(latlong_dir_to_uv(s.wi, &uv), 0);
                double x = uv.u * w; /* in [w - 1, w], or 0 at the seam */
                bad += !(fabs(vec3_dot(s.wi, s.wi) - 1) <= UNIT_TOL) ||
                       !(x > w - 1 - EDGE_TOL || x < EDGE_TOL);
            }
            envlight_free(&el);
        }
        image_free(&im);
    }
    ck_assert_msg(bad == 0, "%ld samples at xi1 -> 1 are not unit or not in the last column", bad);
}
END_TEST

/* NaN, +-Inf and negative channels are counted and used as 0: radiance 0 there (that channel),
 * never sampled when the whole texel is bad, not part of the power */
START_TEST(test_envlight_bad_texels_are_counted_dark_and_never_sampled)
{
    image im;
    make_map(M_CONSTANT, &im);
    float *p;
    p = image_px(&im, 2, 2);
    p[0] = p[1] = p[2] = NAN; /* 3 bad channels */
    p = image_px(&im, 9, 4);
    p[0] = INFINITY;
    p[1] = -INFINITY;
    p[2] = -1; /* 3 */
    p = image_px(&im, 12, 6);
    p[1] = NAN; /* 1: red and blue still 0.7 */
    p = image_px(&im, 5, 1);
    p[0] = p[1] = 0;
    p[2] = -0.0f; /* black, not bad: 0 */
    envmap env = env_of(&im, 1, mat4_identity());
    for (int cfg = C_UNIFORM; cfg < C_COUNT; cfg++) {
        envlight el;
        build(&el, &env, cfg_mode[cfg], cfg_sampler[cfg], 0);
        ck_assert_int_eq(el.n_bad, 7);
        rgb L1 = envlight_radiance(&el, latlong_uv_to_dir((uv2){2.5 / 16, 2.5 / 8}));
        rgb L2 = envlight_radiance(&el, latlong_uv_to_dir((uv2){9.5 / 16, 4.5 / 8}));
        rgb L3 = envlight_radiance(&el, latlong_uv_to_dir((uv2){12.5 / 16, 6.5 / 8}));
        ck_assert(rgb_is_black(L1) && rgb_is_black(L2));
        ck_assert(L3.g == 0 && fabs(L3.r - 0.7) < 1e-6 && fabs(L3.b - 0.7) < 1e-6);
        /* power: 128 texels of 0.7 minus the two dark ones and a third of the half-dark one */
        double want = 0;
        for (int y = 0; y < 8; y++)
            for (int x = 0; x < 16; x++)
                want += texel_avg(&im, x, y) * latlong_texel_solid_angle(y, 16, 8);
        ck_assert_msg(fabs(el.power - want) < 1e-9 * want, "power %.12g, want %.12g", el.power,
                      want);
        if (cfg != C_UNIFORM) {
            rng r;
            rng_seed(&r, 23, (uint64_t)cfg);
            long hit = 0;
            for (int i = 0; i < 50000; i++) {
                envlight_sample_result s;
                ck_require(envlight_sample(&el, rng_uniform(&r), rng_uniform(&r), &s));
                int c, rr;
                texel_of(&el, s.wi, &c, &rr);
                hit += (c == 2 && rr == 2) || (c == 9 && rr == 4);
                hit += !rgb_is_finite(s.L) || !isfinite(s.pdf);
            }
            ck_assert_msg(hit == 0, "%s: %ld samples on a bad texel", cfg_name[cfg], hit);
        }
        envlight_free(&el);
    }
    image_free(&im);
}
END_TEST

/* cdf-sintheta: xi_inner = 0 in a lit top row puts theta exactly at 0, where sin theta = 0:
 * the sample must still succeed with a finite pdf (the header: "never [fails] for a valid
 * table"; it once returned 0 with pdf 0 there) */
START_TEST(test_envlight_sintheta_sample_on_the_pole_edge_succeeds)
{
    image im;
    make_map(M_POLES, &im);
    envmap env = env_of(&im, 1, mat4_identity());
    const double edge[] = {0.0, 0.3, 1 - 0x1p-24, 1.0};
    int bad = 0;
    for (int sa = 0; sa < 2; sa++) {
        envlight el;
        build(&el, &env, ENVSAMPLING_CDF_SINTHETA, sa ? ENVSAMPLER_ALIAS : ENVSAMPLER_BINARY, 0);
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                envlight_sample_result s;
                int ok = envlight_sample_stratified(&el, edge[i], edge[j], &s);
                bad += !ok || !(s.pdf > 0) || !isfinite(s.pdf) || rgb_is_black(s.L);
            }
        envlight_free(&el);
    }
    ck_assert_msg(bad == 0, "%d edge samples failed", bad);
    image_free(&im);
}
END_TEST

/* a 4096 x 2048 table: built, and its pmf sums to 1 within 1e-6; |L| is the double sum */
START_TEST(test_envlight_large_table_is_normalized)
{
    enum { W = 4096, H = 2048 };
    image im;
    fill(&im, W, H);
    uint32_t x = 12345; /* a cheap xorshift pattern with a bright spot and zero bands */
    for (size_t i = 0; i < (size_t)W * H; i++) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        float v = (float)(x >> 8) * 0x1p-24f;
        im.px[3 * i] = im.px[3 * i + 1] = im.px[3 * i + 2] = (i / W) % 97 == 0 ? 0 : v;
    }
    for (int y = 600; y < 604; y++)
        for (int c = 1000; c < 1004; c++) set_gray(&im, c, y, 1e5);
    envmap env = env_of(&im, 1, mat4_identity());
    envlight el;
    build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0);
    double sum = 0, power = 0;
    for (int c = 0; c < W; c++)
        for (int r = 0; r < H; r++) sum += distrib2d_pmf(&el.table, c, r);
    for (int r = 0; r < H; r++) {
        double om = latlong_texel_solid_angle(r, W, H), row = 0;
        for (int c = 0; c < W; c++) row += texel_avg(&im, c, r);
        power += row * om;
    }
    ck_assert_msg(fabs(sum - 1) < 1e-6, "pmf sums to 1 + %g", sum - 1);
    ck_assert_msg(fabs(el.power - power) < 1e-9 * power, "power %.15g, want %.15g", el.power,
                  power);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* the cdf mode's pdf cancels the light: pdf(w) |L| = L_avg(w) at random directions, with a
 * scale; and cdf-sintheta's pdf is p(c, r) W H / (2 pi^2 sin theta) with p from the sin weights */
START_TEST(test_envlight_cdf_pdf_is_radiance_over_power)
{
    image im;
    make_map(M_SUN, &im);
    envmap env = env_of(&im, 2.5, mat4_rotate(vec3_make(1, 0, 0), -90));
    envlight el, es;
    build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_ALIAS, 0);
    build(&es, &env, ENVSAMPLING_CDF_SINTHETA, ENVSAMPLER_BINARY, 0);
    double wsum = 0; /* sum of L_avg sin(theta_centre): the sin-theta table's total */
    for (int r = 0; r < im.h; r++)
        for (int c = 0; c < im.w; c++)
            wsum += 2.5 * texel_avg(&im, c, r) * sin(M_PI * (r + 0.5) / im.h);
    rng g;
    rng_seed(&g, 29, 0);
    long bad = 0, bad_sin = 0;
    for (int i = 0; i < 20000; i++) {
        double z = 1 - 2 * rng_uniform(&g), ph = 2 * M_PI * rng_uniform(&g),
               st = sqrt(fmax(0, 1 - z * z));
        vec3 w = vec3_make(st * cos(ph), st * sin(ph), z);
        double La = rgb_avg(envlight_radiance(&el, w)), p = envlight_pdf(&el, w) * el.power;
        bad += !(fabs(p - La) <= CANCEL_REL_TOL * La) && !(La == 0 && p == 0);
        int c, r;
        texel_of(&es, w, &c, &r);
        vec3 d = mat4_dir(&env.to_env, w);
        double sin_t = sqrt(d.x * d.x + d.y * d.y) / vec3_length(d);
        double want = 2.5 * texel_avg(&im, c, r) * sin(M_PI * (r + 0.5) / im.h) / wsum * im.w *
                      im.h / (2 * M_PI * M_PI * sin_t);
        double got = envlight_pdf(&es, w);
        bad_sin += !(fabs(got - want) <= 1e-6 * want) && !(want == 0 && got == 0);
    }
    ck_assert_msg(bad == 0, "%ld directions where pdf |L| != L_avg", bad);
    ck_assert_msg(bad_sin == 0, "%ld directions where the sin-theta pdf is off", bad_sin);
    envlight_free(&el);
    envlight_free(&es);
    image_free(&im);
}
END_TEST

/* kappa = E[L^2] / E[L]^2 over uniform directions: 1 for a constant map, 2 for a map lit on
 * one hemisphere only (E[L^2] = L^2 / 2, E[L]^2 = L^2 / 4), huge for the sun; and
 * envlight_radiance_pdf is envlight_radiance and envlight_pdf in one lookup, in every mode */
START_TEST(test_envlight_kappa_and_the_combined_lookup)
{
    image im;
    make_map(M_CONSTANT, &im);
    envmap env = env_of(&im, 1, mat4_identity());
    envlight el;
    build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0);
    ck_assert_msg(fabs(el.kappa - 1) < 1e-12, "constant map: kappa %.15g", el.kappa);
    envlight_free(&el);
    image_free(&im);
    /* upper hemisphere 3, lower 0: rows split exactly at the equator (an even height) */
    ck_assert_int_eq(image_alloc(&im, 16, 8, &(error){0}), 0);
    for (int r = 0; r < 8; r++)
        for (int c = 0; c < 16; c++) image_set(&im, c, r, rgb_gray(r < 4 ? 3 : 0));
    env = env_of(&im, 1, mat4_identity());
    build(&el, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0);
    ck_assert_msg(fabs(el.kappa - 2) < 1e-12, "half-lit map: kappa %.15g", el.kappa);
    envlight_free(&el);
    image_free(&im);
    make_map(M_SUN, &im);
    env = env_of(&im, 2, mat4_rotate(vec3_make(1, 0, 0), -90));
    for (int mode = ENVSAMPLING_UNIFORM; mode <= ENVSAMPLING_CDF_SINTHETA; mode++) {
        build(&el, &env, (envsampling_mode)mode, ENVSAMPLER_BINARY, 0);
        ck_assert_msg(el.kappa > 100, "sun map: kappa %g", el.kappa);
        rng g;
        rng_seed(&g, 31, (uint64_t)mode);
        for (int i = 0; i < 5000; i++) {
            vec3 w = sampling_uniform_sphere(rng_uniform(&g), rng_uniform(&g));
            double pdf;
            rgb L = envlight_radiance_pdf(&el, w, &pdf), L1 = envlight_radiance(&el, w);
            ck_require(L.r == L1.r && L.g == L1.g && L.b == L1.b);
            ck_require_msg(pdf == envlight_pdf(&el, w), "mode %d: %g vs %g", mode, pdf,
                           envlight_pdf(&el, w));
        }
        envlight_free(&el);
    }
    image_free(&im);
}
END_TEST

/* radiance is the nearest texel, scaled (piecewise constant, so light and BRDF sampling see the
 * same function) */
START_TEST(test_envlight_radiance_is_the_scaled_texel)
{
    image im;
    make_map(M_3X2, &im);
    envmap env = env_of(&im, 3, mat4_identity());
    envlight el;
    build(&el, &env, ENVSAMPLING_UNIFORM, ENVSAMPLER_BINARY, 0);
    int bad = 0;
    for (int r = 0; r < 2; r++)
        for (int c = 0; c < 3; c++)
            for (int j = 0; j < 9; j++) {
                uv2 uv = {(c + 0.05 + 0.1 * j) / 3, (r + 0.95 - 0.1 * j) / 2};
                rgb L = envlight_radiance(&el, latlong_uv_to_dir(uv));
                bad += fabs(L.g - 3 * image_px(&im, c, r)[1]) > 1e-12;
            }
    ck_assert_int_eq(bad, 0);
    /* the lookup-only light (envlight_build_lookup) reads the same radiance and draws the same
     * uniform samples, without a pass over the texels: no power */
    envlight lk;
    error err = {0};
    ck_assert_int_eq(envlight_build_lookup(&lk, &env, NULL, &err), 0);
    ck_assert(lk.mode == ENVSAMPLING_UNIFORM && lk.power == 0 && lk.kappa == 0);
    for (int j = 0; j < 200; j++) {
        vec3 d = latlong_uv_to_dir((uv2){(j * 0.618034) - floor(j * 0.618034), (j + 0.5) / 200});
        rgb a = envlight_radiance(&el, d), b = envlight_radiance(&lk, d);
        ck_assert(same_rgb(a, b));
        envlight_sample_result sa, sb;
        double x1 = (j + 0.25) / 200, x2 = (j * 0.414214) - floor(j * 0.414214);
        ck_assert(envlight_sample(&el, x1, x2, &sa) && envlight_sample(&lk, x1, x2, &sb));
        ck_assert(same_rgb(sa.L, sb.L) && sa.pdf == sb.pdf && sa.wi.x == sb.wi.x &&
                  sa.wi.y == sb.wi.y && sa.wi.z == sb.wi.z);
    }
    envlight_free(&lk);
    envlight_free(&el);
    image_free(&im);
}
END_TEST

/* with alias tables, envlight_sample_stratified gives exactly the binary search's samples,
 * which are monotone in xi1 (the column, phi): stratified inputs stay stratified */
START_TEST(test_envlight_stratified_sampling_keeps_strata_with_alias_tables)
{
    image im;
    make_map(M_SUN, &im);
    envmap env = env_of(&im, 1, mat4_identity());
    envlight eb, ea;
    build(&eb, &env, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0);
    build(&ea, &env, ENVSAMPLING_CDF, ENVSAMPLER_ALIAS, 0);
    int differ = 0, not_monotone = 0, alias_differs = 0;
    double last_phi = -1;
    for (int i = 0; i < 4096; i++) {
        double xi1 = (i + 0.5) / 4096, xi2 = 0.37;
        envlight_sample_result a, b, c;
        ck_assert(envlight_sample(&eb, xi1, xi2, &b));
        ck_assert(envlight_sample_stratified(&ea, xi1, xi2, &a));
        ck_assert(envlight_sample(&ea, xi1, xi2, &c));
        differ += a.wi.x != b.wi.x || a.wi.y != b.wi.y || a.wi.z != b.wi.z;
        alias_differs += c.wi.x != b.wi.x || c.wi.y != b.wi.y;
        double phi = atan2(b.wi.y, b.wi.x);
        if (phi < 0) phi += 2 * M_PI;
        not_monotone += phi < last_phi - 1e-12;
        last_phi = phi;
    }
    ck_assert_int_eq(differ, 0);
    ck_assert_int_eq(not_monotone, 0);
    ck_assert(alias_differs > 0); /* the alias path really is another mapping */
    envlight_free(&eb);
    envlight_free(&ea);
    image_free(&im);
}
END_TEST

/* the poles read the first and the last row: v = theta / pi is exactly 1 at the south pole
 * (0, 0, -1), which the row index floor(v H) must clamp to H - 1.  The map's memory goes on past
 * its last row with a bright sentinel row, so an unclamped index reads it (deterministically,
 * without a sanitizer); radiance, pdf and the combined lookup must all see the last row. */
START_TEST(test_envlight_south_pole_reads_the_last_row)
{
    enum { W = 3, H = 2 };
    static float px[3 * W * (H + 1)];
    for (int i = 0; i < 3 * W * (H + 1); i++) /* texel k is 0.25 (k + 1); then the sentinel row */
        px[i] = i < 3 * W * H ? 0.25f * (float)(1 + i / 3) : 1000.0f;
    image im = {W, H, px};
    envmap env = env_of(&im, 1, mat4_identity());
    const envsampling_mode modes[2] = {ENVSAMPLING_CDF, ENVSAMPLING_UNIFORM};
    for (int m = 0; m < 2; m++) {
        envlight el;
        build(&el, &env, modes[m], ENVSAMPLER_BINARY, 0);
        const vec3 pole[2] = {{0, 0, 1}, {0, 0, -1}};
        for (int k = 0; k < 2; k++) {
            double want = image_px(&im, 0, k * (H - 1))[1]; /* phi = 0 at the poles: column 0 */
            rgb L = envlight_radiance(&el, pole[k]);
            ck_assert_msg(L.g == want, "pole %d: L = %g, want the texel of row %d, %g", k, L.g,
                          k * (H - 1), want);
            double pdf;
            L = envlight_radiance_pdf(&el, pole[k], &pdf);
            ck_assert(L.g == want);
            double want_pdf = modes[m] == ENVSAMPLING_CDF ? want / el.power : 1 / (4 * M_PI);
            double got = envlight_pdf(&el, pole[k]);
            ck_assert_msg(fabs(got - want_pdf) <= 1e-12 * want_pdf &&
                              fabs(pdf - want_pdf) <= 1e-12 * want_pdf,
                          "pole %d: pdf %g and %g, want %g", k, got, pdf, want_pdf);
        }
        envlight_free(&el);
    }
}
END_TEST

/* The tables are charged to the budget before they are built: what stays (the cdf tables, the
 * median-cut points), and while building the texels' energy, released after.  A budget one byte
 * short refuses with one message naming the map; a black map, which falls back to uniform
 * directions, keeps no cdf table charged. */
START_TEST(test_envlight_tables_are_charged_before_they_are_built)
{
    const envsampling_mode modes[4] = {ENVSAMPLING_UNIFORM, ENVSAMPLING_CDF, ENVSAMPLING_CDF,
                                       ENVSAMPLING_MEDIANCUT};
    const envsampler_kind samplers[4] = {ENVSAMPLER_BINARY, ENVSAMPLER_BINARY, ENVSAMPLER_ALIAS,
                                         ENVSAMPLER_BINARY};
    image im = {0}, black = {0};
    make_map(M_ONE_HOT, &im);
    fill(&black, 16, 8);
    envmap env = env_of(&im, 1, mat4_identity()), dark = env_of(&black, 1, mat4_identity());
    double kept_cdf = 0;
    for (int k = 0; k < 4; k++) {
        error err = {0};
        envlight el;
        budget mem;
        budget_init(&mem, 1e9);
        ck_assert_int_eq(envlight_build(&el, &env, modes[k], samplers[k], 4, &mem, &err), 0);
        double used = mem.used, peak = mem.peak;
        ck_assert_msg(used > 0 && (k == 0 || peak > used), "mode %d: used %g, peak %g", k, used,
                      peak);
        if (k == 1) kept_cdf = used;
        if (k == 2)
            ck_assert(used > kept_cdf + 16 * 8 * sizeof(distrib_alias)); /* the alias cells */
        envlight_free(&el);
        budget_init(&mem, peak - 1);
        ck_assert_int_eq(envlight_build(&el, &env, modes[k], samplers[k], 4, &mem, &err), -1);
        ck_assert_msg(strstr(err.msg, "for a 16 x 8 lat-long map = ") &&
                          strstr(err.msg, "beyond the memory budget"),
                      "%s", err.msg);
        ck_assert(mem.used == 0);
    }
    error err = {0};
    envlight el;
    budget mem;
    budget_init(&mem, 1e9);
    ck_assert_int_eq(envlight_build(&el, &dark, ENVSAMPLING_CDF, ENVSAMPLER_BINARY, 0, &mem, &err),
                     0);
    ck_assert(el.fell_back && mem.used < kept_cdf - distrib2d_bytes(16, 8) / 2);
    envlight_free(&el);
    image_free(&im);
    image_free(&black);
}
END_TEST

Suite *envlight_suite(void)
{
    Suite *s = suite_create("envlight");
    TCase *tc = tcase_create("chisq");
    tcase_add_loop_test(tc, test_envlight_every_mode_fits_its_pdf_on_every_map, 0,
                        M_COUNT * C_COUNT);
    tcase_add_loop_test(tc, test_envlight_rotated_map_fits_its_pdf, 0, N_ROTATED);
    suite_add_tcase(s, tc);
    tc = tcase_create("numerics");
    tcase_add_test(tc, test_envlight_rotation_moves_samples_and_pdf_with_the_map);
    tcase_add_test(tc, test_envlight_kappa_and_the_combined_lookup);
    tcase_add_test(tc, test_envlight_tables_are_charged_before_they_are_built);
    tcase_add_test(tc, test_envlight_non_rotation_transform_is_refused);
    tcase_add_test(tc, test_envlight_translation_and_uniform_scale_sample_as_the_rotation_alone);
    tcase_add_test(tc, test_envlight_all_black_map_falls_back_to_uniform);
    tcase_add_test(tc, test_envlight_zero_texels_and_edge_xi_are_never_sampled);
    tcase_add_test(tc, test_envlight_sampled_phi_is_unit_and_in_its_column);
    tcase_add_test(tc, test_envlight_last_column_at_xi_one_stays_in_its_column);
    tcase_add_test(tc, test_envlight_bad_texels_are_counted_dark_and_never_sampled);
    tcase_add_test(tc, test_envlight_large_table_is_normalized);
    tcase_add_test(tc, test_envlight_cdf_pdf_is_radiance_over_power);
    tcase_add_test(tc, test_envlight_radiance_is_the_scaled_texel);
    tcase_add_test(tc, test_envlight_south_pole_reads_the_last_row);
    tcase_add_test(tc, test_envlight_stratified_sampling_keeps_strata_with_alias_tables);
    tcase_add_test(tc, test_envlight_sintheta_sample_on_the_pole_edge_succeeds);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(envlight_suite)
