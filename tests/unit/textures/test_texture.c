/* test_texture.c - texture objects: each filter on an image texture against the lookup it
 * stands for, the lazy pyramid, the checker's closed-form box filter, solid textures and their
 * band-limiting, the scalar view and the bump derivatives against known slopes. */
#include "envtex/textures/texture.h"

#include <string.h>

#include "envtex/textures/perlin.h"
#include "unit.h"

/* w x h image whose texel (i, j), j from the bottom, is (i, j, i + j) */
static image ramp(int w, int h)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, w, h, &err), 0);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) image_set(&im, i, h - 1 - j, rgb_make(i, j, i + j));
    return im;
}

START_TEST(test_names_round_trip)
{
    for (int f = TEXFILTER_NEAREST; f <= TEXFILTER_EWA; f++) {
        texture_filter got;
        ck_assert_int_eq(texture_filter_parse(texture_filter_name((texture_filter)f), &got), 0);
        ck_assert_int_eq(got, f);
    }
    for (int k = TEXTURE_CHECKER; k <= TEXTURE_WOOD; k++) {
        texture_kind got;
        ck_assert_int_eq(texture_kind_parse(texture_kind_name((texture_kind)k), &got), 0);
        ck_assert_int_eq(got, k);
    }
    texture_kind k;
    texture_filter f;
    ck_assert_int_eq(texture_kind_parse("image", &k), -1); /* images have no keyword */
    ck_assert_int_eq(texture_filter_parse("Trilinear", &f), -1);
}
END_TEST

START_TEST(test_image_filters_are_the_lookups_they_name)
{
    image im = ramp(8, 4);
    texture tx;
    error err = {0};
    texture_init_image(&tx, &im, WRAP_REPEAT);
    ck_assert(texture_needs_prepare(&tx, TEXFILTER_TRILINEAR));
    ck_assert(!texture_needs_prepare(&tx, TEXFILTER_BILINEAR));
    ck_assert_int_eq(texture_prepare(&tx, TEXFILTER_BILINEAR, NULL, &err), 0);
    ck_assert_int_eq(tx.has_mip, 0); /* no pyramid unless a filter needs it */
    ck_assert_int_eq(texture_prepare(&tx, TEXFILTER_EWA, NULL, &err), 0);
    ck_assert_int_eq(tx.has_mip, 1);
    ck_assert(!texture_needs_prepare(&tx, TEXFILTER_EWA));
    ck_assert(!texture_needs_prepare(&tx, TEXFILTER_TRILINEAR)); /* the same pyramid */
    const image *level1 = mipmap_level(&tx.mip, 1);
    ck_assert_int_eq(texture_prepare(&tx, TEXFILTER_TRILINEAR, NULL, &err), 0);
    ck_assert_ptr_eq(mipmap_level(&tx.mip, 1)->px, level1->px); /* the pyramid is not rebuilt */
    texture_query q;
    memset(&q, 0, sizeof q);
    q.st = (uv2){0.3, 0.55};
    q.filter = TEXFILTER_NEAREST;
    ck_rgb_near(texture_eval(&tx, &q), texlookup_nearest(&im, q.st, WRAP_REPEAT), 0);
    q.filter = TEXFILTER_BILINEAR;
    ck_rgb_near(texture_eval(&tx, &q), texlookup_bilinear(&im, q.st, WRAP_REPEAT), 0);
    /* no differentials: trilinear and EWA fall back to level 0 bilinear */
    q.filter = TEXFILTER_TRILINEAR;
    ck_rgb_near(texture_eval(&tx, &q), texlookup_bilinear(&im, q.st, WRAP_REPEAT), 1e-6);
    q.filter = TEXFILTER_EWA;
    ck_rgb_near(texture_eval(&tx, &q), texlookup_bilinear(&im, q.st, WRAP_REPEAT), 1e-6);
    /* a footprint of 1/4 x 1/16 of the texture: its area's side is 1/8 (8 texels * 1/8 = 1
     * texel): trilinear uses sqrt(|dst/dx| |dst/dy|), not the long axis (src/textures/texture.c) */
    q.filter = TEXFILTER_TRILINEAR;
    q.dst_dx = (uv2){0.25, 0};
    q.dst_dy = (uv2){0, 0.0625};
    ck_rgb_near(texture_eval(&tx, &q), mipmap_lookup_trilinear(&tx.mip, q.st, 0.125), 1e-15);
    q.filter = TEXFILTER_EWA;
    ck_rgb_near(texture_eval(&tx, &q), mipmap_lookup_ewa(&tx.mip, q.st, q.dst_dx, q.dst_dy), 0);
    texture_free(&tx);
    ck_assert_int_eq(tx.has_mip, 0);
    texture_free(&tx); /* safe twice */
    image_free(&im);
}
END_TEST

/* The pyramid is charged before it is built (mipmap_cost_of), the building scratch released; a
 * budget one byte short refuses and leaves nothing. */
START_TEST(test_the_pyramid_is_charged_before_it_is_built)
{
    image im = ramp(8, 4);
    texture tx;
    error err = {0};
    mipmap_cost c = mipmap_cost_of(8, 4);
    /* levels 4x2, 2x1, 1x1: 11 texels of 12 bytes; scratch 4 x 4 doubles */
    ck_assert(c.levels == 11 * 12.0 && c.scratch >= 4 * 4 * 3 * 8.0);
    budget mem;
    budget_init(&mem, c.levels + c.scratch - 1);
    texture_init_image(&tx, &im, WRAP_REPEAT);
    ck_assert_int_eq(texture_prepare(&tx, TEXFILTER_TRILINEAR, &mem, &err), -1);
    ck_assert_msg(strstr(err.msg, "a mip pyramid of 8 x 4 texels = "), "%s", err.msg);
    ck_assert(mem.used == 0 && !tx.has_mip);
    budget_init(&mem, c.levels + c.scratch);
    ck_assert_int_eq(texture_prepare(&tx, TEXFILTER_EWA, &mem, &err), 0); /* the levels */
    ck_assert(mem.used == c.levels && mem.peak == c.levels + c.scratch);
    ck_assert_int_eq(texture_prepare(&tx, TEXFILTER_TRILINEAR, &mem, &err), 0); /* nothing more */
    ck_assert(mem.used == c.levels);
    texture_free(&tx);
    image_free(&im);
}
END_TEST

START_TEST(test_checker_point_values_follow_the_parity_of_the_squares)
{
    texture tx;
    error err = {0};
    ck_assert_int_eq(texture_init_checker(&tx, rgb_gray(0), rgb_gray(1), 4, &err), 0);
    texture_query q;
    memset(&q, 0, sizeof q);
    q.st = (uv2){0.1, 0.1}; /* square (0, 0): c0 */
    ck_rgb_near(texture_eval(&tx, &q), rgb_gray(0), 0);
    q.st = (uv2){0.3, 0.1}; /* square (1, 0): c1 */
    ck_rgb_near(texture_eval(&tx, &q), rgb_gray(1), 0);
    q.st = (uv2){0.3, 0.3}; /* (1, 1): c0 */
    ck_rgb_near(texture_eval(&tx, &q), rgb_gray(0), 0);
    q.st = (uv2){-0.1, 0.1}; /* (-1, 0): c1 (negative coordinates keep the pattern) */
    ck_rgb_near(texture_eval(&tx, &q), rgb_gray(1), 0);
    /* on a square's edge: floor(f s) of the square it starts, f s = 1 is square 1 (c1), f s = 2
     * square 2 (c0), f s = -1 square -1 (c1) */
    q.st = (uv2){0.25, 0.1};
    ck_rgb_near(texture_eval(&tx, &q), rgb_gray(1), 0);
    q.st = (uv2){0.5, 0.1};
    ck_rgb_near(texture_eval(&tx, &q), rgb_gray(0), 0);
    q.st = (uv2){-0.25, 0.1};
    ck_rgb_near(texture_eval(&tx, &q), rgb_gray(1), 0);
    q.st = (uv2){0.1, 0.25};
    ck_rgb_near(texture_eval(&tx, &q), rgb_gray(1), 0);
    ck_assert_int_eq(texture_init_checker(&tx, rgb_gray(0), rgb_gray(1), 0, &err), -1);
    ck_assert_int_eq(texture_init_checker(&tx, rgb_gray(0), rgb_gray(1), NAN, &err), -1);
    ck_assert_int_eq(texture_init_checker(&tx, rgb_gray(0), rgb_gray(1), INFINITY, &err), -1);
}
END_TEST

/* nearest and bilinear point-sample the checker whatever the footprint (texture.h): only
 * trilinear and EWA box-filter it. */
START_TEST(test_checker_is_point_sampled_by_nearest_and_bilinear)
{
    texture tx;
    error err = {0};
    ck_assert_int_eq(texture_init_checker(&tx, rgb_gray(0), rgb_gray(1), 4, &err), 0);
    texture_query q;
    memset(&q, 0, sizeof q);
    q.st = (uv2){0.3, 0.1};
    q.dst_dx = (uv2){10, 0};
    q.dst_dy = (uv2){0, 10};
    const texture_filter point[2] = {TEXFILTER_NEAREST, TEXFILTER_BILINEAR};
    for (int k = 0; k < 2; k++) {
        q.filter = point[k];
        ck_rgb_near(texture_eval(&tx, &q), rgb_gray(1), 0);
    }
    q.filter = TEXFILTER_TRILINEAR;
    ck_assert(fabs(texture_eval(&tx, &q).r - 0.5) < 0.05);
}
END_TEST

START_TEST(test_checker_box_filter_matches_a_brute_force_average)
{
    texture tx;
    error err = {0};
    ck_assert_int_eq(texture_init_checker(&tx, rgb_gray(0), rgb_gray(1), 3, &err), 0);
    const double pts[][4] = {{0.31, 0.47, 0.05, 0.02},
                             {0.1, 0.9, 0.4, 0.4},
                             {-0.7, 2.2, 0.9, 0.01},
                             {0.5, 0.5, 3.0, 5.0}};
    for (int k = 0; k < 4; k++) {
        texture_query q;
        memset(&q, 0, sizeof q);
        q.st = (uv2){pts[k][0], pts[k][1]};
        q.dst_dx = (uv2){pts[k][2], 0};
        q.dst_dy = (uv2){0, pts[k][3]};
        q.filter = TEXFILTER_TRILINEAR;
        double got = texture_eval(&tx, &q).r;
        /* brute force: the mean over the box [s +- w/2] x [t +- h/2] on a fine grid */
        const int n = 600;
        double sum = 0;
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                texture_query p = q;
                p.filter = TEXFILTER_NEAREST;
                p.st.u += pts[k][2] * ((i + 0.5) / n - 0.5);
                p.st.v += pts[k][3] * ((j + 0.5) / n - 0.5);
                sum += texture_eval(&tx, &p).r;
            }
        ck_assert_msg(fabs(got - sum / (n * n)) < 4e-3, "case %d: %g vs %g", k, got, sum / (n * n));
    }
}
END_TEST

START_TEST(test_checker_filter_converges_to_the_mean_far_away)
{
    texture tx;
    error err = {0};
    ck_assert_int_eq(texture_init_checker(&tx, rgb_gray(0.2), rgb_gray(1), 8, &err), 0);
    texture_query q;
    memset(&q, 0, sizeof q);
    q.st = (uv2){0.123, 0.456};
    q.dst_dx = (uv2){100, 0};
    q.dst_dy = (uv2){0, 100};
    q.filter = TEXFILTER_EWA;
    ck_assert_near(texture_eval(&tx, &q).r, 0.6, 1e-3);
}
END_TEST

START_TEST(test_solid_parameters_are_checked)
{
    texture tx;
    error err = {0};
    texture_solid_params sp = {.scale = 1, .octaves = 4, .c0 = {0, 0, 0}, .c1 = {1, 1, 1}};
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_FBM, &sp, &err), 0);
    sp.octaves = 0;
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_FBM, &sp, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "octaves"));
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_PERLIN, &sp, &err), 0); /* not used */
    sp.scale = 0;
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_PERLIN, &sp, &err), -1);
    sp.scale = INFINITY;
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_PERLIN, &sp, &err), -1);
    sp.scale = 1;
    sp.rings = -1;
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_WOOD, &sp, &err), -1);
    sp.rings = 0;
    sp.octaves = PERLIN_MAX_OCTAVES;
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_TURBULENCE, &sp, &err), 0);
    sp.octaves = PERLIN_MAX_OCTAVES + 1;
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_TURBULENCE, &sp, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "octaves"));
}
END_TEST

/* Between no fading and the mean, wood's rings fade by the smoothstep of the documented band,
 * a = smoothstep(1/2, 1, rings w): at rings w = 0.625, a = 3 (1/4)^2 - 2 (1/4)^3 = 0.15625 and
 * v = (1 - a) v_point + a / 2. */
START_TEST(test_wood_fades_by_a_smoothstep_of_the_footprint)
{
    texture_solid_params sp = {
        .scale = 1, .octaves = 1, .rings = 6, .amplitude = 0.7, .c0 = {0, 0, 0}, .c1 = {1, 1, 1}};
    texture tx;
    error err = {0};
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_WOOD, &sp, &err), 0);
    texture_query q;
    memset(&q, 0, sizeof q);
    q.p = vec3_make(0.41, 0.2, -0.33);
    q.filter = TEXFILTER_TRILINEAR;
    double v0 = texture_eval(&tx, &q).r; /* no footprint: the point value */
    q.dp_dx = vec3_make(0.625 / 6, 0, 0);
    double a = 0.15625;
    ck_assert_near(texture_eval(&tx, &q).r, (1 - a) * v0 + 0.5 * a, 1e-12);
}
END_TEST

START_TEST(test_solids_without_footprint_are_the_perlin_functions)
{
    texture_solid_params sp = {.scale = 2,
                               .octaves = 5,
                               .frequency = 4,
                               .amplitude = 3,
                               .rings = 6,
                               .c0 = {0, 0, 0},
                               .c1 = {1, 1, 1}};
    vec3 p = vec3_make(0.37, -1.21, 2.5), x = vec3_scale(p, 2);
    double expect[5];
    expect[0] = 0.5 + 0.5 * perlin_noise(x.x, x.y, x.z);
    expect[1] = 0.5 + 0.5 * perlin_fbm(x, 5, 2, 0.5);
    expect[2] = perlin_turbulence(x, 5, 2, 0.5);
    expect[3] = perlin_marble(x, 4, 3, 5);
    expect[4] = perlin_wood(x, 6, 3);
    for (int k = 0; k < 5; k++) {
        texture tx;
        error err = {0};
        ck_assert_int_eq(texture_init_solid(&tx, (texture_kind)(TEXTURE_PERLIN + k), &sp, &err), 0);
        texture_query q;
        memset(&q, 0, sizeof q);
        q.p = p;
        q.filter = TEXFILTER_TRILINEAR; /* no dP: unfiltered */
        double e = expect[k] < 0 ? 0 : expect[k] > 1 ? 1 : expect[k];
        ck_assert_msg(fabs(texture_eval(&tx, &q).g - e) < 1e-12, "%s", texture_kind_name(tx.kind));
    }
}
END_TEST

START_TEST(test_solids_fade_to_their_mean_under_a_huge_footprint)
{
    texture_solid_params sp = {.scale = 1,
                               .octaves = 6,
                               .frequency = 4,
                               .amplitude = 3,
                               .rings = 6,
                               .c0 = {0, 0, 0},
                               .c1 = {1, 1, 1}};
    const double mean[5] = {0.5, 0.5, PERLIN_MEAN_ABS * (2 - 1.0 / 32) /* gains 1 .. 1/32 */, 0.5,
                            0.5};
    for (int k = 0; k < 5; k++) {
        texture tx;
        error err = {0};
        ck_assert_int_eq(texture_init_solid(&tx, (texture_kind)(TEXTURE_PERLIN + k), &sp, &err), 0);
        texture_query q;
        memset(&q, 0, sizeof q);
        q.p = vec3_make(3.3, 1.7, -0.4);
        q.dp_dx = vec3_make(1000, 0, 0);
        q.filter = TEXFILTER_TRILINEAR;
        double v = texture_eval(&tx, &q).r;
        double tol = 1e-12;
        ck_assert_msg(fabs(v - mean[k]) <= tol, "%s: %g", texture_kind_name(tx.kind), v);
        /* nearest and bilinear ignore the footprint: the point value, as without one (this
         * once evaluated nearest and checked nothing) */
        texture_query pq = q;
        pq.dp_dx = vec3_make(0, 0, 0);
        double point = texture_eval(&tx, &pq).r;
        ck_assert_msg(fabs(point - mean[k]) > 1e-6, "%s: the test point is at the mean",
                      texture_kind_name(tx.kind));
        const texture_filter unfiltered[2] = {TEXFILTER_NEAREST, TEXFILTER_BILINEAR};
        for (int f = 0; f < 2; f++) {
            q.filter = unfiltered[f];
            ck_assert_msg(texture_eval(&tx, &q).r == point, "%s, %s: %g, want the point value %g",
                          texture_kind_name(tx.kind), texture_filter_name(q.filter),
                          texture_eval(&tx, &q).r, point);
        }
    }
}
END_TEST

/* Every procedural texture the parser accepts (any finite scale, frequency, rings, amplitude
 * and octaves in range) stays in [c0, c1] at any finite point, point sampled and filtered,
 * small and huge footprints alike: scale P, frequency x, rings r and amplitude * noise may
 * overflow to infinities (1e200 * 1e200), and NaN must not come out of them.  Catches the
 * marble's phase reaching sin as Inf or NaN (unfiltered, and filtered, where the faded veins
 * are 0 * sin(Inf)); also guards wood's NaN-to-0 fraction and the checker's box filter. */
START_TEST(test_procedural_textures_stay_in_range_for_every_parameter_the_parser_accepts)
{
    const double big = 1.7976931348623157e308;
    const double scales[] = {1e-300, 1, 1e155, 1e200, big};
    const double params[] = {0, 4, 1e20, 1e200, big};
    const double amplitudes[] = {0, 8, -1e200, 1e200, big, -big};
    const vec3 points[] = {
        {0.3, -1.2, 0.7}, {1.5, 0.2, -0.1}, {-1e200, 3, 1e-300}, {big, -big, 0.5}};
    const double footprints[] = {0, 1e-3, 1, 1e300};
    int bad = 0, n = 0;
    for (int kind = TEXTURE_PERLIN; kind <= TEXTURE_WOOD; kind++)
        for (int si = 0; si < 5; si++)
            for (int pi = 0; pi < 5; pi++)
                for (int ai = 0; ai < 6; ai++) {
                    texture_solid_params sp = {.scale = scales[si],
                                               .octaves = 6,
                                               .frequency = params[pi],
                                               .amplitude = amplitudes[ai],
                                               .rings = params[pi],
                                               .c0 = {0, 0, 0},
                                               .c1 = {1, 1, 1}};
                    texture tx;
                    error err = {0};
                    ck_assert_int_eq(texture_init_solid(&tx, (texture_kind)kind, &sp, &err), 0);
                    for (int k = 0; k < 4; k++)
                        for (int f = 0; f < 4; f++) {
                            texture_query q;
                            memset(&q, 0, sizeof q);
                            q.p = points[k];
                            q.dp_dx = vec3_make(footprints[f], 0, 0);
                            q.filter = TEXFILTER_TRILINEAR;
                            double v = texture_eval(&tx, &q).r;
                            bad += !(v >= 0 && v <= 1);
                            n++;
                        }
                }
    for (int pi = 1; pi < 5; pi++) {
        texture tx;
        error err = {0};
        ck_assert_int_eq(texture_init_checker(&tx, rgb_gray(0), rgb_gray(1), params[pi], &err), 0);
        const uv2 sts[] = {{0.3, 0.7}, {1e200, -0.2}, {big, -big}};
        for (int k = 0; k < 3; k++)
            for (int f = 0; f < 4; f++) {
                texture_query q;
                memset(&q, 0, sizeof q);
                q.st = sts[k];
                q.dst_dx = (uv2){footprints[f], 0};
                q.dst_dy = (uv2){0, footprints[f]};
                q.filter = TEXFILTER_TRILINEAR;
                double v = texture_eval(&tx, &q).r;
                bad += !(v >= 0 && v <= 1);
                n++;
            }
    }
    ck_assert_msg(bad == 0, "%d of %d evaluations outside [0, 1] or NaN", bad, n);
}
END_TEST

START_TEST(test_scalar_is_the_channel_mean)
{
    texture tx;
    error err = {0};
    ck_assert_int_eq(texture_init_checker(&tx, rgb_make(0.3, 0.6, 0.9), rgb_gray(1), 1, &err), 0);
    texture_query q;
    memset(&q, 0, sizeof q);
    q.st = (uv2){0.5, 0.5};
    ck_assert_near(texture_eval_scalar(&tx, &q), 0.6, 1e-15);
}
END_TEST

START_TEST(test_height_derivs_of_an_image_ramp_are_its_slope)
{
    /* texel (i, j) = (i, j, i + j): channel mean = (2 i + 2 j) / 3, so with bilinear
     * reconstruction dh/ds = (2/3) W and dh/dt = (2/3) H between texel centres */
    image im = ramp(16, 8);
    texture tx;
    texture_init_image(&tx, &im, WRAP_CLAMP);
    texture_query q;
    memset(&q, 0, sizeof q);
    q.st = (uv2){0.4, 0.5};
    q.filter = TEXFILTER_BILINEAR;
    double h, hs, ht;
    texture_height_derivs(&tx, &q, &h, &hs, &ht);
    ck_assert_near(hs, 2.0 / 3 * 16, 1e-4);
    ck_assert_near(ht, 2.0 / 3 * 8, 1e-4);
    ck_assert_double_eq(h, texture_eval_scalar(&tx, &q));
    /* a footprint of 2 texels each side still measures the same slope on a ramp */
    q.dst_dx = (uv2){2.0 / 16, 0};
    q.dst_dy = (uv2){2.0 / 16, 0};
    texture_height_derivs(&tx, &q, &h, &hs, &ht);
    ck_assert_near(hs, 2.0 / 3 * 16, 1e-4);
    texture_free(&tx);
    image_free(&im);
}
END_TEST

START_TEST(test_height_derivs_of_a_solid_agree_with_a_fine_difference)
{
    texture_solid_params sp = {.scale = 1.5, .octaves = 3, .c0 = {0, 0, 0}, .c1 = {1, 1, 1}};
    texture tx;
    error err = {0};
    ck_assert_int_eq(texture_init_solid(&tx, TEXTURE_FBM, &sp, &err), 0);
    texture_query q;
    memset(&q, 0, sizeof q);
    q.p = vec3_make(0.3, 0.71, -0.2);
    q.dp_ds = vec3_make(2, 0, 0);
    q.dp_dt = vec3_make(0, 0, 0); /* no tangent: no derivative */
    q.filter = TEXFILTER_TRILINEAR;
    double h, hs, ht;
    texture_height_derivs(&tx, &q, &h, &hs, &ht);
    double e = 1e-7;
    texture_query a = q, b = q;
    a.p.x += 2 * e;
    b.p.x -= 2 * e;
    double ref = (texture_eval_scalar(&tx, &a) - texture_eval_scalar(&tx, &b)) / (2 * e);
    ck_assert_msg(fabs(hs - ref) < 1e-3 * (1 + fabs(ref)), "%g vs %g", hs, ref);
    ck_assert_double_eq(ht, 0);
}
END_TEST

/* Trilinear's level comes from the footprint in texels, (ds W, dt H): every level halves both
 * sides.  A footprint one texel wide each way on a 64 x 16 one-texel checker is level 0 (the
 * texel itself at its centre), as on a square image; measured in texture units against the
 * longer side it once read 2 texels, level 1, the checker's grey.  Four texels each way is
 * level 2 on both. */
START_TEST(test_trilinear_measures_a_non_square_images_footprint_in_texels)
{
    int sizes[3][2] = {{64, 64}, {64, 16}, {16, 64}};
    for (int k = 0; k < 3; k++) {
        int w = sizes[k][0], h = sizes[k][1];
        image im = {0};
        error err = {0};
        ck_assert_int_eq(image_alloc(&im, w, h, &err), 0);
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) image_set(&im, i, j, rgb_gray((i + j) % 2));
        texture t;
        texture_init_image(&t, &im, WRAP_REPEAT);
        ck_assert_int_eq(texture_prepare(&t, TEXFILTER_TRILINEAR, NULL, &err), 0);
        texture_query q = {0};
        q.filter = TEXFILTER_TRILINEAR;
        q.st = (uv2){5.5 / w, (h - 2.5) / h}; /* the centre of texel (5, 2) from the top: 1 */
        q.dst_dx = (uv2){1.0 / w, 0};
        q.dst_dy = (uv2){0, 1.0 / h};
        double v = texture_eval_scalar(&t, &q);
        ck_assert_msg(fabs(v - 1.0) < 1e-6, "%d x %d, one texel each way: %.9g, want 1 (level 0)",
                      w, h, v);
        q.dst_dx = (uv2){4.0 / w, 0};
        q.dst_dy = (uv2){0, 4.0 / h};
        v = texture_eval_scalar(&t, &q);
        ck_assert_msg(fabs(v - 0.5) < 1e-6, "%d x %d, four texels each way: %.9g, want 0.5", w, h,
                      v);
        texture_free(&t);
        image_free(&im);
    }
}
END_TEST

Suite *texture_suite(void)
{
    Suite *s = suite_create("texture");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_names_round_trip);
    tcase_add_test(tc, test_image_filters_are_the_lookups_they_name);
    tcase_add_test(tc, test_the_pyramid_is_charged_before_it_is_built);
    tcase_add_test(tc, test_checker_point_values_follow_the_parity_of_the_squares);
    tcase_add_test(tc, test_checker_box_filter_matches_a_brute_force_average);
    tcase_add_test(tc, test_checker_is_point_sampled_by_nearest_and_bilinear);
    tcase_add_test(tc, test_wood_fades_by_a_smoothstep_of_the_footprint);
    tcase_add_test(tc, test_checker_filter_converges_to_the_mean_far_away);
    tcase_add_test(tc, test_solid_parameters_are_checked);
    tcase_add_test(tc, test_solids_without_footprint_are_the_perlin_functions);
    tcase_add_test(tc, test_solids_fade_to_their_mean_under_a_huge_footprint);
    tcase_add_test(tc,
                   test_procedural_textures_stay_in_range_for_every_parameter_the_parser_accepts);
    tcase_add_test(tc, test_scalar_is_the_channel_mean);
    tcase_add_test(tc, test_height_derivs_of_an_image_ramp_are_its_slope);
    tcase_add_test(tc, test_height_derivs_of_a_solid_agree_with_a_fine_difference);
    tcase_add_test(tc, test_trilinear_measures_a_non_square_images_footprint_in_texels);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(texture_suite)
