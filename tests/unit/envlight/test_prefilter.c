/* test_prefilter.c - illumination maps with analytic answers: R&H's basis and its constants, a
 * map that is one basis function gives that coefficient alone, a constant map gives E / pi = 1
 * and a Phong map of 1, one bright texel gives the clamped cosine and its lobe; the fast exact
 * sums equal the plain ones; SH9 irradiance equals the exact one on a map of bands 0-2. */
#include "envtex/envlight/prefilter.h"

#include <stdlib.h>
#include <string.h>

#include "envtex/envmaps/cubemap.h"
#include "envtex/envmaps/cylindrical.h"
#include "envtex/envmaps/equalarea.h"
#include "envtex/envmaps/latlong.h"
#include "envtex/envmaps/mirrorball.h"
#include "envtex/core/rng.h"
#include "unit.h"

/* Checks for long loops: report failures only (a passing ck_assert costs a system call). */
#define EXPECT_NEAR(a, b, tol) unit_near(__FILE__, __LINE__, #a, (a), (b), (tol))

typedef rgb (*env_fn)(vec3 d, const void *ctx);

/* A map of kind `kind` (lat-long, equal-area or cylindrical: w x w/2; cube: w x w faces; mirror
 * ball: w x w) whose texels hold f at their centres (a mirror ball's texels whose centre is
 * past the rim: f at the rim's direction, -x, where prefilter.h takes them). */
static void make_map(convert_map *m, convert_kind kind, int w, env_fn f, const void *ctx)
{
    error err = {0};
    memset(m, 0, sizeof *m);
    m->kind = kind;
    if (kind == CONVERT_CUBE) {
        ck_assert_int_eq(cubemap_alloc(&m->cube, w, &err), 0);
        for (int face = 0; face < CUBEMAP_FACES; face++)
            for (int r = 0; r < w; r++)
                for (int c = 0; c < w; c++) {
                    vec3 d = cubemap_face_to_dir(face, (uv2){(c + 0.5) / w, (r + 0.5) / w});
                    image_set(&m->cube.face[face], c, r, f(d, ctx));
                }
        return;
    }
    int h = kind == CONVERT_MIRRORBALL ? w : w / 2;
    ck_assert_int_eq(image_alloc(&m->img, w, h, &err), 0);
    if (kind == CONVERT_CYLINDRICAL) m->max_height = convert_cylindrical_height(w, h);
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) {
            uv2 uv = {(c + 0.5) / w, (r + 0.5) / h};
            vec3 d;
            if (kind == CONVERT_LATLONG)
                d = latlong_uv_to_dir(uv);
            else if (kind == CONVERT_EQUALAREA)
                d = equalarea_uv_to_dir(uv);
            else if (kind == CONVERT_CYLINDRICAL)
                ck_assert_int_eq(cylindrical_uv_to_dir(uv, m->max_height, &d), 0);
            else if (mirrorball_uv_to_dir(uv, &d))
                d = vec3_make(-1, 0, 0); /* past the rim: -x */
            image_set(&m->img, c, r, f(d, ctx));
        }
}

static rgb constant_fn(vec3 d, const void *ctx)
{
    (void)d;
    return rgb_gray(*(const double *)ctx);
}

/* sum_k w[k][ch] Y_k(d): a map made of basis functions */
static rgb basis_fn(vec3 d, const void *ctx)
{
    const double(*w)[3] = ctx;
    double Y[PREFILTER_SH9];
    prefilter_sh9_basis(vec3_normalize(d), Y);
    rgb sum = rgb_gray(0);
    for (int k = 0; k < PREFILTER_SH9; k++)
        sum = rgb_add(sum, rgb_scale(rgb_make(w[k][0], w[k][1], w[k][2]), Y[k]));
    return sum;
}

static prefilter_sh9 project(const convert_map *m)
{
    convert_env env = convert_view(m);
    prefilter_sh9 sh;
    error err = {0};
    ck_assert_msg(prefilter_sh9_project(&env, &sh, &err) == 0, "%s", err.msg);
    return sh;
}

static void random_map(convert_map *m, int w, int h, uint64_t seed)
{
    error err = {0};
    rng g;
    rng_seed(&g, seed, 0);
    memset(m, 0, sizeof *m);
    ck_assert_int_eq(image_alloc(&m->img, w, h, &err), 0);
    for (int r = 0; r < h; r++)
        for (int c = 0; c < w; c++) {
            double sun = rng_uniform(&g) < 0.01 ? 1000 : 1; /* a few bright texels */
            image_set(&m->img, c, r,
                      rgb_make(sun * rng_uniform(&g), rng_uniform(&g), 0.5 * rng_uniform(&g)));
        }
}

static double map_max(const image *a)
{
    double m = 0;
    for (long i = 0; i < 3L * a->w * a->h; i++) m = fmax(m, fabs(a->px[i]));
    return m;
}

/* max |a - b| over texels and channels (same sizes) */
static double max_diff(const image *a, const image *b)
{
    ck_assert_int_eq(a->w, b->w);
    ck_assert_int_eq(a->h, b->h);
    double m = 0;
    for (long i = 0; i < 3L * a->w * a->h; i++) m = fmax(m, fabs((double)a->px[i] - b->px[i]));
    return m;
}

/* ---- the basis ----------------------------------------------------------------------------- */

START_TEST(test_sh9_basis_is_ramamoorthi_and_hanrahans_real_basis)
{
    /* the constants (6 digits) and the closed forms, at a few unit directions */
    const vec3 dirs[] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0.48, -0.6, 0.64}, {-0.36, 0.48, -0.8}};
    for (unsigned i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        vec3 d = dirs[i];
        double x = d.x, y = d.y, z = d.z, Y[PREFILTER_SH9];
        prefilter_sh9_basis(d, Y);
        const double want[PREFILTER_SH9] = {0.282095,
                                            0.488603 * y,
                                            0.488603 * z,
                                            0.488603 * x,
                                            1.092548 * x * y,
                                            1.092548 * y * z,
                                            0.315392 * (3 * z * z - 1),
                                            1.092548 * x * z,
                                            0.546274 * (x * x - y * y)};
        for (int k = 0; k < PREFILTER_SH9; k++) EXPECT_NEAR(Y[k], want[k], 1e-6);
        EXPECT_NEAR(Y[0], 0.5 / sqrt(M_PI), 1e-16);
        EXPECT_NEAR(Y[6], sqrt(5 / (16 * M_PI)) * (3 * z * z - 1), 1e-15);
        EXPECT_NEAR(Y[8], sqrt(15 / (16 * M_PI)) * (x * x - y * y), 1e-15);
    }
    /* the order (0,0) (1,-1) (1,0) (1,1) (2,-2) (2,-1) (2,0) (2,1) (2,2) */
    const int l[] = {0, 1, 1, 1, 2, 2, 2, 2, 2}, m[] = {0, -1, 0, 1, -2, -1, 0, 1, 2};
    for (int k = 0; k < PREFILTER_SH9; k++) {
        ck_assert_int_eq(prefilter_sh9_l(k), l[k]);
        ck_assert_int_eq(prefilter_sh9_m(k), m[k]);
    }
}
END_TEST

/* The sums are the midpoint rule over texels: exact in phi for these trigonometric polynomials
 * (degree <= 4 in phi, W > 4 columns), second order in theta: the worst coefficient of a
 * basis-function map is off by 1.6e-3 at 64 x 32, 4.0e-4 at 128 x 64, 1.0e-4 at 256 x 128
 * (measured); allowed 2e-4 at 256 x 128. */
#define SH_DISCRETE_TOL 2e-4

START_TEST(test_a_map_that_is_one_basis_function_gives_that_coefficient_alone)
{
    for (int j = 0; j < PREFILTER_SH9; j++) {
        double w[PREFILTER_SH9][3] = {{0}};
        w[j][0] = 1, w[j][1] = 2, w[j][2] = -0.5; /* three channels, three weights */
        convert_map m;
        make_map(&m, CONVERT_LATLONG, 256, basis_fn, w);
        prefilter_sh9 sh = project(&m);
        for (int k = 0; k < PREFILTER_SH9; k++)
            for (int ch = 0; ch < 3; ch++)
                EXPECT_NEAR(sh.L[k][ch], w[k][ch], SH_DISCRETE_TOL * fabs(w[j][ch]));
        convert_map_free(&m);
    }
}
END_TEST

START_TEST(test_sh9_of_a_combination_of_basis_functions_recovers_it_in_every_representation)
{
    double w[PREFILTER_SH9][3];
    rng g;
    rng_seed(&g, 5, 0);
    for (int k = 0; k < PREFILTER_SH9; k++)
        for (int ch = 0; ch < 3; ch++) w[k][ch] = 2 * rng_uniform(&g) - 1;
    /* lat-long, equal-area and cylindrical are rows; a cube and a mirror ball are texel lists
     * (the cylinder holds only +-57.5 degrees and the mirror ball's rim is coarse: not here) */
    const convert_kind kinds[] = {CONVERT_LATLONG, CONVERT_EQUALAREA, CONVERT_CUBE};
    const int widths[] = {256, 256, 96};
    for (int i = 0; i < 3; i++) {
        convert_map m;
        make_map(&m, kinds[i], widths[i], basis_fn, w);
        prefilter_sh9 sh = project(&m);
        for (int k = 0; k < PREFILTER_SH9; k++)
            for (int ch = 0; ch < 3; ch++) EXPECT_NEAR(sh.L[k][ch], w[k][ch], 3 * SH_DISCRETE_TOL);
        convert_map_free(&m);
    }
}
END_TEST

START_TEST(test_a_constant_map_has_L00_two_sqrt_pi_and_nothing_else)
{
    const convert_kind kinds[] = {CONVERT_LATLONG, CONVERT_EQUALAREA, CONVERT_CUBE,
                                  CONVERT_MIRRORBALL};
    double one = 1;
    for (int i = 0; i < 4; i++) {
        convert_map m;
        make_map(&m, kinds[i], kinds[i] == CONVERT_CUBE ? 32 : 128, constant_fn, &one);
        prefilter_sh9 sh = project(&m);
        /* L00 = integral of Y00 = 4 pi / (2 sqrt pi); the solid angles sum to 4 pi exactly, so
         * this is exact but for rounding, whatever the representation (mirror ball: its rim
         * texels, pulled onto the rim, too) */
        EXPECT_NEAR(sh.L[0][1], 2 * sqrt(M_PI), 1e-6);
        for (int k = 1; k < 4; k++)
            EXPECT_NEAR(sh.L[k][0], 0, kinds[i] == CONVERT_MIRRORBALL ? 0.02 : 1e-12);
        convert_map_free(&m);
    }
}
END_TEST

/* A constant map projects exactly: L00 = 2 sqrt(pi) and the 8 others 0, to rounding, at 16 x 8
 * as at 256 x 128, lat-long and equal-area.  Catches a projection that evaluates Y_lm at texel
 * centres (the midpoint rule): a 16 x 8 lat-long map then had L20 = 0.053 (1.5% of L00). */
START_TEST(test_a_constant_map_projects_exactly_whatever_its_size)
{
    const convert_kind kinds[] = {CONVERT_LATLONG, CONVERT_EQUALAREA};
    const int widths[] = {16, 64, 256};
    double one = 1;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 3; j++) {
            convert_map m;
            make_map(&m, kinds[i], widths[j], constant_fn, &one);
            prefilter_sh9 sh = project(&m);
            EXPECT_NEAR(sh.L[0][1], 2 * sqrt(M_PI), 1e-13);
            for (int k = 1; k < PREFILTER_SH9; k++)
                for (int ch = 0; ch < 3; ch++) EXPECT_NEAR(sh.L[k][ch], 0, 1e-13);
            convert_map_free(&m);
        }
}
END_TEST

/* The integral of Y_lm over [z0, z1] x [p0, p1] in (z = cos theta, phi), by the midpoint rule
 * on n x n cells: an independent answer, converging as 1 / n^2. */
static void quadrature(double z0, double z1, double p0, double p1, int n, double out[9])
{
    double y[PREFILTER_SH9];
    for (int k = 0; k < PREFILTER_SH9; k++) out[k] = 0;
    double cell = (z1 - z0) / n * (p1 - p0) / n;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double z = z0 + (z1 - z0) * (i + 0.5) / n, p = p0 + (p1 - p0) * (j + 0.5) / n;
            double st = sqrt(1 - z * z);
            prefilter_sh9_basis(vec3_make(st * cos(p), st * sin(p), z), y);
            for (int k = 0; k < PREFILTER_SH9; k++) out[k] += y[k] * cell;
        }
}

/* One bright texel of a 16 x 8 lat-long map - at the pole, at the horizon, at the phi seam -
 * projects to L times the integral of each Y_lm over the texel's rectangle in (cos theta,
 * phi), the map as the light sees it: within 1e-5 of L dOmega of a 400 x 400 midpoint
 * quadrature (whose own error is ~1e-6).  Catches the midpoint rule over the whole texel (off
 * by up to 0.1 L dOmega at this size) and a row or column integral of the wrong sign or order. */
START_TEST(test_one_texel_projects_to_its_exact_integrals)
{
    const int w = 16, h = 8, at[][2] = {{3, 0}, {5, 3}, {15, 4}, {0, 7}};
    for (int i = 0; i < 4; i++) {
        int tc = at[i][0], tr = at[i][1];
        convert_map m;
        error err = {0};
        memset(&m, 0, sizeof m);
        ck_assert_int_eq(image_alloc(&m.img, w, h, &err), 0);
        image_set(&m.img, tc, tr, rgb_make(2, 0, 0));
        prefilter_sh9 sh = project(&m);
        double want[PREFILTER_SH9], om = latlong_texel_solid_angle(tr, w, h);
        quadrature(cos(M_PI * (tr + 1) / h), cos(M_PI * tr / h), 2 * M_PI * tc / w,
                   2 * M_PI * (tc + 1) / w, 400, want);
        for (int k = 0; k < PREFILTER_SH9; k++)
            ck_assert_msg(fabs(sh.L[k][0] - 2 * want[k]) <= 1e-5 * 2 * om,
                          "texel (%d, %d) L[%d]: %.12g, quadrature %.12g", tc, tr, k, sh.L[k][0],
                          2 * want[k]);
        convert_map_free(&m);
    }
}
END_TEST

/* ---- irradiance ---------------------------------------------------------------------------- */

START_TEST(test_the_quadratic_form_is_the_sum_of_the_A_l_terms)
{
    prefilter_sh9 sh;
    rng g;
    rng_seed(&g, 9, 0);
    for (int k = 0; k < PREFILTER_SH9; k++)
        for (int ch = 0; ch < 3; ch++) sh.L[k][ch] = 2 * rng_uniform(&g) - 1;
    prefilter_sh9_quadratic q;
    prefilter_sh9_matrix(&sh, &q);
    for (int i = 0; i < 200; i++) {
        vec3 n = vec3_normalize(
            vec3_make(rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5));
        rgb a = prefilter_sh9_irradiance(&sh, n), b = prefilter_sh9_quadratic_eval(&q, n);
        EXPECT_NEAR(a.r, b.r, 1e-14);
        EXPECT_NEAR(a.g, b.g, 1e-14);
        EXPECT_NEAR(a.b, b.b, 1e-14);
    }
    /* and R&H's printed constants: c1 = 0.429043 ... c5 = 0.247708 */
    memset(&sh, 0, sizeof sh);
    sh.L[8][0] = 1; /* L22 */
    sh.L[3][1] = 1; /* L11 */
    sh.L[6][2] = 1; /* L20 */
    prefilter_sh9_matrix(&sh, &q);
    EXPECT_NEAR(q.m[0][0][0], 0.429043, 1e-6);
    EXPECT_NEAR(q.m[1][0][3], 0.511664, 1e-6);
    EXPECT_NEAR(q.m[2][2][2], 0.743125, 2e-6); /* their c3 = 3 c5 rounded: 0.7431239 exactly */
    EXPECT_NEAR(q.m[2][3][3], -0.247708, 1e-6);
    sh.L[0][0] = 1;
    prefilter_sh9_matrix(&sh, &q);
    EXPECT_NEAR(q.m[0][3][3], 0.886227, 1e-6);
}
END_TEST

START_TEST(test_a_constant_map_gives_E_over_pi_of_one_by_sh9_and_exactly)
{
    double two = 2;
    convert_map m;
    make_map(&m, CONVERT_LATLONG, 128, constant_fn, &two);
    convert_env env = convert_view(&m);
    prefilter_sh9 sh = project(&m);
    image a = {0}, b = {0};
    error err = {0};
    ck_assert_int_eq(prefilter_irradiance_sh9(&sh, 16, &a, &err), 0);
    ck_assert_int_eq(prefilter_irradiance_exact(&env, 16, &b, &err), 0);
    ck_assert_int_eq(a.w, 16);
    ck_assert_int_eq(a.h, 8);
    for (long i = 0; i < 3L * a.w * a.h; i++) {
        /* E = pi L: L00 = 2 sqrt(pi) L and A_0 Y00 L00 = pi L; the midpoint rule in theta
         * leaves L20 ~ 1e-4 L (measured 1.2e-4 at 128 x 64), the exact sum its own ~1e-4 */
        EXPECT_NEAR(a.px[i], 2, 2 * 5e-4);
        EXPECT_NEAR(b.px[i], 2, 2 * 5e-4);
    }
    image_free(&a);
    image_free(&b);
    convert_map_free(&m);
}
END_TEST

START_TEST(test_one_bright_texel_gives_its_clamped_cosine)
{
    const int w = 64, h = 32, tc = 41, tr = 9;
    convert_map m;
    error err = {0};
    memset(&m, 0, sizeof m);
    ck_assert_int_eq(image_alloc(&m.img, w, h, &err), 0);
    image_set(&m.img, tc, tr, rgb_make(1000, 10, 0));
    vec3 wt = latlong_uv_to_dir((uv2){(tc + 0.5) / w, (tr + 0.5) / h});
    double om = latlong_texel_solid_angle(tr, w, h);
    convert_env env = convert_view(&m);
    image e = {0};
    ck_assert_int_eq(prefilter_irradiance_exact(&env, 32, &e, &err), 0);
    for (int r = 0; r < e.h; r++)
        for (int c = 0; c < e.w; c++) {
            vec3 n = latlong_uv_to_dir((uv2){(c + 0.5) / e.w, (r + 0.5) / e.h});
            double want =
                1000 * om * fmax(0, vec3_dot(n, wt)) / M_PI; /* L dOmega max(0, n.w) / pi */
            EXPECT_NEAR(image_px(&e, c, r)[0], want, 1e-6 * want + 1e-12);
            EXPECT_NEAR(image_px(&e, c, r)[1], want / 100, 1e-6 * want / 100 + 1e-12);
            EXPECT_NEAR(image_px(&e, c, r)[2], 0, 0);
        }
    image_free(&e);
    convert_map_free(&m);
}
END_TEST

/* One small texel is nearly a point source: its coefficients are nearly L dOmega Y_lm(w_t), and
 * by the addition theorem SH9 gives L dOmega (A_0 / 4 pi + 3 A_1 / 4 pi x + 5 A_2 / 4 pi
 * P_2(x)), x = n . w_t: 1/4 + x/2 + 5 (3 x^2 - 1) / 32, the clamped cosine's bands 0-2, worst at
 * the terminator (x = 0: 3/32 = 9.4% of the peak, R&H's bound) and 6.25% at x = +-1.  To 2e-3:
 * the projection integrates the texel's 5.6 x 5.6 degrees (1e-3 from the point here). */
START_TEST(test_sh9_of_one_bright_texel_is_the_clamped_cosines_first_three_bands)
{
    const int w = 64, h = 32, tc = 10, tr = 20;
    convert_map m;
    error err = {0};
    memset(&m, 0, sizeof m);
    ck_assert_int_eq(image_alloc(&m.img, w, h, &err), 0);
    image_set(&m.img, tc, tr, rgb_gray(100));
    vec3 wt = latlong_uv_to_dir((uv2){(tc + 0.5) / w, (tr + 0.5) / h});
    double lw = 100 * latlong_texel_solid_angle(tr, w, h);
    prefilter_sh9 sh = project(&m);
    double worst = 0;
    for (int i = 0; i <= 200; i++) {
        double x = -1 + i / 100.0, y = sqrt(fmax(0, 1 - x * x));
        vec3 t = vec3_normalize(vec3_cross(wt, vec3_make(0, 0, 1))); /* any direction across wt */
        vec3 n = vec3_add(vec3_scale(wt, x), vec3_scale(t, y));
        double e = prefilter_sh9_irradiance(&sh, n).g / lw;
        EXPECT_NEAR(e, 0.25 + x / 2 + 5 * (3 * x * x - 1) / 32, 2e-3);
        worst = fmax(worst, fabs(e - fmax(0, x)));
    }
    EXPECT_NEAR(worst, 3.0 / 32, 2e-3);
    convert_map_free(&m);
}
END_TEST

START_TEST(test_the_arc_sums_equal_the_plain_sum)
{
    /* widths that divide, do not divide, and are odd; lat-long, equal-area, cylindrical */
    const int sizes[][2] = {{64, 32}, {96, 48}, {33, 17}, {100, 50}};
    const convert_kind kinds[] = {CONVERT_LATLONG, CONVERT_EQUALAREA, CONVERT_CYLINDRICAL};
    for (int s = 0; s < 4; s++)
        for (int k = 0; k < 3; k++) {
            convert_map m;
            random_map(&m, sizes[s][0], sizes[s][1], 11 + s);
            m.kind = kinds[k];
            if (m.kind == CONVERT_CYLINDRICAL)
                m.max_height = convert_cylindrical_height(m.img.w, m.img.h);
            convert_env env = convert_view(&m);
            image a = {0}, b = {0};
            error err = {0};
            ck_assert_int_eq(prefilter_irradiance_arcs(&env, 16, &a, &err), 0);
            ck_assert_int_eq(prefilter_irradiance_brute(&env, 16, &b, &err), 0);
            double d = max_diff(&a, &b), top = map_max(&b);
            ck_assert_msg(d <= 1e-6 * top,
                          "%dx%d %s: arcs differ from the plain sum by %g (max %g)", sizes[s][0],
                          sizes[s][1], convert_kind_name(kinds[k]), d, top);
            image_free(&a);
            image_free(&b);
            convert_map_free(&m);
        }
    /* a kind without rows is not for the arc sums */
    convert_map m;
    double one = 1;
    make_map(&m, CONVERT_CUBE, 8, constant_fn, &one);
    convert_env env = convert_view(&m);
    image a = {0};
    error err = {0};
    ck_assert_int_eq(prefilter_irradiance_arcs(&env, 16, &a, &err), -1);
    ck_assert_ptr_null(a.px);
    convert_map_free(&m);
}
END_TEST

/* A map of bands 0-2 only: its irradiance is exactly what its 9 coefficients give, so SH9 and
 * the exact convolution agree to the discretisation (any wrong A_l, or basis constant, fails). */
START_TEST(test_sh9_irradiance_equals_the_exact_one_on_a_map_of_bands_0_to_2)
{
    double w[PREFILTER_SH9][3] = {{4, 5, 6}};
    rng g;
    rng_seed(&g, 3, 0);
    for (int k = 1; k < PREFILTER_SH9; k++)
        for (int ch = 0; ch < 3; ch++) w[k][ch] = 2 * rng_uniform(&g) - 1;
    convert_map m;
    make_map(&m, CONVERT_LATLONG, 256, basis_fn, w);
    convert_env env = convert_view(&m);
    prefilter_sh9 sh = project(&m);
    image a = {0}, b = {0};
    error err = {0};
    ck_assert_int_eq(prefilter_irradiance_sh9(&sh, 32, &a, &err), 0);
    ck_assert_int_eq(prefilter_irradiance_exact(&env, 32, &b, &err), 0);
    double d = max_diff(&a, &b), top = map_max(&b);
    ck_assert_msg(d <= 1e-3 * top, "SH9 and exact differ by %g of the peak", d / top);
    image_free(&a);
    image_free(&b);
    convert_map_free(&m);
}
END_TEST

/* ---- Phong lobes --------------------------------------------------------------------------- */

START_TEST(test_a_constant_map_gives_a_phong_map_of_one)
{
    const double s[] = {0, 1, 10, 100};
    double one = 1;
    convert_map m;
    make_map(&m, CONVERT_LATLONG, 512, constant_fn, &one);
    convert_env env = convert_view(&m);
    for (int i = 0; i < 4; i++) {
        image p = {0};
        error err = {0};
        ck_assert_int_eq(prefilter_phong(&env, s[i], 16, &p, &err), 0);
        /* the lobe's integral is 1; the midpoint rule over the lobe's texels, finer than it */
        for (long k = 0; k < 3L * p.w * p.h; k++) EXPECT_NEAR(p.px[k], 1, 2e-3);
        image_free(&p);
    }
    convert_map_free(&m);
}
END_TEST

START_TEST(test_one_bright_texel_gives_its_phong_lobe)
{
    const int w = 128, h = 64, tc = 100, tr = 40;
    const double s[] = {0, 3, 37.5, 400};
    convert_map m;
    error err = {0};
    memset(&m, 0, sizeof m);
    ck_assert_int_eq(image_alloc(&m.img, w, h, &err), 0);
    image_set(&m.img, tc, tr, rgb_gray(50));
    vec3 wt = latlong_uv_to_dir((uv2){(tc + 0.5) / w, (tr + 0.5) / h});
    double lw = 50 * latlong_texel_solid_angle(tr, w, h); /* L dOmega */
    convert_env env = convert_view(&m);
    for (int i = 0; i < 4; i++) {
        image p = {0};
        ck_assert_int_eq(prefilter_phong(&env, s[i], 64, &p, &err), 0);
        for (int r = 0; r < p.h; r++)
            for (int c = 0; c < p.w; c++) {
                vec3 rr = latlong_uv_to_dir((uv2){(c + 0.5) / p.w, (r + 0.5) / p.h});
                double t = vec3_dot(rr, wt);
                double want = t > 0 ? lw * (s[i] + 1) / (2 * M_PI) * pow(t, s[i]) : 0;
                /* what is left out is at most PREFILTER_PHONG_DROP x the mean radiance */
                double slack = PREFILTER_PHONG_DROP * lw / (4 * M_PI);
                EXPECT_NEAR(image_px(&p, c, r)[2], want, 1e-6 * want + slack);
            }
        image_free(&p);
    }
    convert_map_free(&m);
}
END_TEST

START_TEST(test_the_fast_phong_sum_equals_the_plain_one_within_what_it_leaves_out)
{
    /* output widths that divide the input's (p = 1), share a factor (p = 2, 4) or none */
    const int sizes[][3] = {{64, 32, 16}, {96, 48, 64}, {100, 50, 16}, {33, 17, 8}};
    const double s[] = {0, 1, 7, 37.5, 500};
    for (int z = 0; z < 4; z++) {
        convert_map m;
        random_map(&m, sizes[z][0], sizes[z][1], 21 + z);
        convert_env env = convert_view(&m);
        rgb power = convert_power(&env);
        double mean = rgb_max(power) / (4 * M_PI);
        for (int i = 0; i < 5; i++) {
            image a = {0}, b = {0};
            error err = {0};
            ck_assert_int_eq(prefilter_phong(&env, s[i], sizes[z][2], &a, &err), 0);
            ck_assert_int_eq(prefilter_phong_brute(&env, s[i], sizes[z][2], &b, &err), 0);
            double d = max_diff(&a, &b), top = map_max(&b);
            ck_assert_msg(d <= 1e-6 * top + PREFILTER_PHONG_DROP * mean,
                          "%dx%d to %d, S = %g: the fast sum differs by %g (max %g)", sizes[z][0],
                          sizes[z][1], sizes[z][2], s[i], d, top);
            image_free(&a);
            image_free(&b);
        }
        convert_map_free(&m);
    }
}
END_TEST

START_TEST(test_the_phong_lobe_of_exponent_1_is_the_irradiance)
{
    /* (1 + 1) / (2 pi) max(0, r . w) = max(0, n . w) / pi: the two maps are one */
    convert_map m;
    random_map(&m, 80, 40, 7);
    convert_env env = convert_view(&m);
    image a = {0}, b = {0};
    error err = {0};
    ck_assert_int_eq(prefilter_phong(&env, 1, 32, &a, &err), 0);
    ck_assert_int_eq(prefilter_irradiance_exact(&env, 32, &b, &err), 0);
    ck_assert(max_diff(&a, &b) <= 1e-6 * map_max(&b));
    image_free(&a);
    image_free(&b);
    convert_map_free(&m);
}
END_TEST

START_TEST(test_exact_maps_of_cube_and_mirror_ball_inputs_agree_with_lat_long)
{
    /* one smooth environment in three representations: the exact maps agree to the inputs'
     * own discretisation (the texel lists are summed by the plain sum) */
    double w[PREFILTER_SH9][3] = {
        {3, 3, 3}, {0.5, 0, 0}, {0, 0.7, 0}, {0, 0, 0.4}, {0.3, 0.3, 0.3}};
    const convert_kind kinds[] = {CONVERT_CUBE, CONVERT_MIRRORBALL, CONVERT_LATLONG};
    const int widths[] = {48, 256, 256};
    image maps[3][2];
    for (int i = 0; i < 3; i++) {
        convert_map m;
        make_map(&m, kinds[i], widths[i], basis_fn, w);
        convert_env env = convert_view(&m);
        error err = {0};
        ck_assert_int_eq(prefilter_irradiance_exact(&env, 16, &maps[i][0], &err), 0);
        ck_assert_int_eq(prefilter_phong(&env, 20, 16, &maps[i][1], &err), 0);
        convert_map_free(&m);
    }
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double d = max_diff(&maps[i][j], &maps[2][j]), top = map_max(&maps[2][j]);
            ck_assert_msg(d <= 0.01 * top, "%s, %s: %g of the peak from lat-long",
                          convert_kind_name(kinds[i]), j ? "phong" : "irradiance", d / top);
        }
    for (int i = 0; i < 3; i++) image_free(&maps[i][0]), image_free(&maps[i][1]);
}
END_TEST

/* ---- arguments ------------------------------------------------------------------------------ */

START_TEST(test_widths_exponents_and_huge_work_are_refused_with_a_message)
{
    double one = 1;
    convert_map m;
    make_map(&m, CONVERT_LATLONG, 1024, constant_fn, &one);
    convert_env env = convert_view(&m);
    image out = {0};
    error err = {0};
    const long bad_w[] = {0, 1, 3, 63, -2, PREFILTER_MAX_WIDTH + 2};
    for (int i = 0; i < 6; i++) {
        ck_assert_int_eq(prefilter_check_width(bad_w[i], &err), -1);
        ck_assert_ptr_nonnull(strstr(err.msg, "even number from 2 to"));
        ck_assert_int_eq(prefilter_irradiance_exact(&env, (int)bad_w[i], &out, &err), -1);
        ck_assert_ptr_null(out.px);
    }
    ck_assert_int_eq(prefilter_check_width(2, &err), 0);
    ck_assert_int_eq(prefilter_check_width(PREFILTER_MAX_WIDTH, &err), 0);
    const double bad_s[] = {-1, NAN, INFINITY, 2 * PREFILTER_MAX_SHININESS};
    for (int i = 0; i < 4; i++) {
        ck_assert_int_eq(prefilter_phong(&env, bad_s[i], 16, &out, &err), -1);
        ck_assert_ptr_nonnull(strstr(err.msg, "Phong exponent"));
        ck_assert_ptr_null(out.px);
    }
    /* a Phong map of 8192 x 4096 from 1024 x 512 texels: refused before any work */
    ck_assert_int_eq(prefilter_phong(&env, 1, 8192, &out, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "over the limit"));
    ck_assert_ptr_null(out.px);
    convert_map_free(&m);
    /* an exact irradiance map of 4096 x 2048 from a cube of 32 x 32 faces: refused too */
    make_map(&m, CONVERT_CUBE, 32, constant_fn, &one);
    env = convert_view(&m);
    ck_assert_int_eq(prefilter_irradiance_exact(&env, 4096, &out, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "smaller --width"));
    ck_assert_ptr_null(out.px);
    convert_map_free(&m);
}
END_TEST

START_TEST(test_the_phong_width_grows_with_the_exponent)
{
    ck_assert_int_eq(prefilter_phong_width(0), 64);
    ck_assert_int_eq(prefilter_phong_width(10), 64);    /* 4 pi sqrt 10 = 40 */
    ck_assert_int_eq(prefilter_phong_width(100), 128);  /* 126 */
    ck_assert_int_eq(prefilter_phong_width(1000), 512); /* 397 */
    ck_assert_int_eq(prefilter_phong_width(1e6), 1024); /* the cap */
}
END_TEST

Suite *prefilter_suite(void)
{
    Suite *s = suite_create("prefilter");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_sh9_basis_is_ramamoorthi_and_hanrahans_real_basis);
    tcase_add_test(tc, test_a_map_that_is_one_basis_function_gives_that_coefficient_alone);
    tcase_add_test(
        tc, test_sh9_of_a_combination_of_basis_functions_recovers_it_in_every_representation);
    tcase_add_test(tc, test_a_constant_map_has_L00_two_sqrt_pi_and_nothing_else);
    tcase_add_test(tc, test_a_constant_map_projects_exactly_whatever_its_size);
    tcase_add_test(tc, test_one_texel_projects_to_its_exact_integrals);
    tcase_add_test(tc, test_the_quadratic_form_is_the_sum_of_the_A_l_terms);
    tcase_add_test(tc, test_a_constant_map_gives_E_over_pi_of_one_by_sh9_and_exactly);
    tcase_add_test(tc, test_one_bright_texel_gives_its_clamped_cosine);
    tcase_add_test(tc, test_sh9_of_one_bright_texel_is_the_clamped_cosines_first_three_bands);
    tcase_add_test(tc, test_the_arc_sums_equal_the_plain_sum);
    tcase_add_test(tc, test_sh9_irradiance_equals_the_exact_one_on_a_map_of_bands_0_to_2);
    tcase_add_test(tc, test_a_constant_map_gives_a_phong_map_of_one);
    tcase_add_test(tc, test_one_bright_texel_gives_its_phong_lobe);
    tcase_add_test(tc, test_the_fast_phong_sum_equals_the_plain_one_within_what_it_leaves_out);
    tcase_add_test(tc, test_the_phong_lobe_of_exponent_1_is_the_irradiance);
    tcase_add_test(tc, test_exact_maps_of_cube_and_mirror_ball_inputs_agree_with_lat_long);
    tcase_add_test(tc, test_widths_exponents_and_huge_work_are_refused_with_a_message);
    tcase_add_test(tc, test_the_phong_width_grows_with_the_exponent);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(prefilter_suite)
