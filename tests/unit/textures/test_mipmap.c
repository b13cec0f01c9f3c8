/* test_mipmap.c - pyramid sizes and means for non-power-of-two images, wrap modes at every
 * level's border, level selection, trilinear continuity, EWA known answers. */
#include "envtex/textures/mipmap.h"

#include <stdint.h>
#include <string.h>

#include "unit.h"

static const wrap_mode all_modes[3] = {WRAP_REPEAT, WRAP_CLAMP, WRAP_MIRROR};

static uint64_t rng_state = 0x9E3779B97F4A7C15ULL;
static double rng_uniform(double lo, double hi)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return lo + (hi - lo) * (double)(rng_state >> 11) * 0x1p-53;
}

static image new_image(int w, int h)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, w, h, &err), 0);
    return im;
}

static image random_image(int w, int h)
{
    image im = new_image(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            image_set(&im, x, y,
                      rgb_make(rng_uniform(0.1, 1), rng_uniform(0, 5), rng_uniform(0, 0.01)));
    return im;
}

/* texel (i, j) (j from the bottom) = 1 where (i / cell + j / cell) is odd, else 0 */
static image checker_image(int w, int h, int cell)
{
    image im = new_image(w, h);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            image_set(&im, i, h - 1 - j, rgb_gray((i / cell + j / cell) % 2));
    return im;
}

static mipmap build(const image *im, wrap_mode wrap)
{
    mipmap m;
    error err = {0};
    ck_assert_int_eq(mipmap_build(&m, im, wrap, &err), 0);
    return m;
}

static rgb image_mean(const image *im)
{
    double s[3] = {0, 0, 0};
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) {
            rgb c = image_get(im, x, y);
            s[0] += c.r;
            s[1] += c.g;
            s[2] += c.b;
        }
    double n = (double)im->w * im->h;
    return rgb_make(s[0] / n, s[1] / n, s[2] / n);
}

START_TEST(test_levels_halve_rounding_down_to_one_by_one)
{
    const int sizes[][2] = {{5, 3}, {1, 7}, {1, 1}, {8, 8}, {1000, 3}, {2, 1}};
    const int want_levels[] = {3, 3, 1, 4, 10, 2};
    for (int k = 0; k < 6; k++) {
        image im = new_image(sizes[k][0], sizes[k][1]);
        mipmap m = build(&im, WRAP_REPEAT);
        ck_assert_int_eq(mipmap_levels(&m), want_levels[k]);
        int w = sizes[k][0], h = sizes[k][1];
        for (int l = 0; l < mipmap_levels(&m); l++) {
            ck_assert_int_eq(mipmap_level(&m, l)->w, w);
            ck_assert_int_eq(mipmap_level(&m, l)->h, h);
            w = w / 2 > 1 ? w / 2 : 1;
            h = h / 2 > 1 ? h / 2 : 1;
        }
        ck_assert(mipmap_level(&m, mipmap_levels(&m) - 1)->w == 1);
        ck_assert(mipmap_level(&m, mipmap_levels(&m) - 1)->h == 1);
        mipmap_free(&m);
        image_free(&im);
    }
    /* 5x3 -> 2x1 -> 1x1 spelled out */
    image im = new_image(5, 3);
    mipmap m = build(&im, WRAP_CLAMP);
    ck_assert(mipmap_level(&m, 1)->w == 2 && mipmap_level(&m, 1)->h == 1);
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

START_TEST(test_level_zero_references_the_base_and_free_leaves_it_alone)
{
    image im = random_image(6, 5);
    mipmap m = build(&im, WRAP_REPEAT);
    ck_assert(mipmap_level(&m, 0)->px == im.px);
    mipmap_free(&m);
    mipmap_free(&m); /* twice is safe */
    ck_assert(im.px != NULL);
    im.px[0] = 0.5f; /* still ours (AddressSanitizer would catch a use after free) */
    image_free(&im);
}
END_TEST

START_TEST(test_every_level_keeps_the_mean_for_odd_and_even_sizes)
{
    const int sizes[][2] = {{37, 23}, {5, 3}, {1, 7}, {16, 9}, {3, 3}, {64, 1}};
    for (int k = 0; k < 6; k++)
        for (int md = 0; md < 3; md++) {
            image im = random_image(sizes[k][0], sizes[k][1]);
            mipmap m = build(&im, all_modes[md]);
            rgb mean = image_mean(&im);
            for (int l = 1; l < mipmap_levels(&m); l++) {
                rgb ml = image_mean(mipmap_level(&m, l));
                ck_assert_near(ml.r, mean.r, 1e-6 * mean.r);
                ck_assert_near(ml.g, mean.g, 1e-6 * mean.g);
                ck_assert_near(ml.b, mean.b, 1e-6 * mean.b);
            }
            mipmap_free(&m);
            image_free(&im);
        }
}
END_TEST

START_TEST(test_odd_sizes_keep_the_last_column_and_row)
{
    /* only the last column (of 5) and the top row (of 3) are lit: a filter that drops the odd
     * one out would leave level 1 black */
    image im = new_image(5, 3);
    for (int y = 0; y < 3; y++) image_set(&im, 4, y, rgb_gray(1));
    image im2 = new_image(5, 3);
    for (int x = 0; x < 5; x++) image_set(&im2, x, 0, rgb_gray(1));
    mipmap m = build(&im, WRAP_CLAMP), m2 = build(&im2, WRAP_CLAMP);
    ck_assert(image_get(mipmap_level(&m, 1), 1, 0).r > 0.3);
    ck_assert(image_get(mipmap_level(&m2, 1), 0, 0).r > 0.3);
    ck_assert_near(image_mean(mipmap_level(&m, 1)).r, 0.2, 1e-7);
    ck_assert_near(image_mean(mipmap_level(&m2, 1)).r, 1.0 / 3, 1e-7);
    mipmap_free(&m);
    mipmap_free(&m2);
    image_free(&im);
    image_free(&im2);
}
END_TEST

START_TEST(test_even_sizes_use_the_weights_one_seven_seven_one_over_sixteen)
{
    image im = new_image(4, 1); /* an impulse at column 1 */
    image_set(&im, 1, 0, rgb_gray(1));
    mipmap m = build(&im, WRAP_CLAMP);
    ck_assert_near(image_get(mipmap_level(&m, 1), 0, 0).r, 7.0 / 16, 1e-7);
    ck_assert_near(image_get(mipmap_level(&m, 1), 1, 0).r, 1.0 / 16, 1e-7);
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

START_TEST(test_repeat_blends_the_opposite_border_at_every_level_and_clamp_does_not)
{
    /* red left column, blue right column, black between */
    image im = new_image(16, 4);
    for (int y = 0; y < 4; y++) {
        image_set(&im, 0, y, rgb_make(1, 0, 0));
        image_set(&im, 15, y, rgb_make(0, 0, 1));
    }
    mipmap rep = build(&im, WRAP_REPEAT), cla = build(&im, WRAP_CLAMP),
           mir = build(&im, WRAP_MIRROR);
    for (int l = 1; l < mipmap_levels(&rep); l++) {
        const image *r = mipmap_level(&rep, l);
        if (r->w < 2) break;
        rgb left = image_get(r, 0, 0), right = image_get(r, r->w - 1, 0);
        ck_assert_msg(left.b > 0 && right.r > 0, "repeat level %d: no wrap-around", l);
    }
    for (int l = 1; l <= 2; l++) { /* up to 4 x 1: the halves stay apart */
        const image *c = mipmap_level(&cla, l), *mi = mipmap_level(&mir, l);
        ck_assert_msg(image_get(c, 0, 0).b == 0 && image_get(c, c->w - 1, 0).r == 0,
                      "clamp level %d bleeds across the border", l);
        ck_assert_msg(image_get(mi, 0, 0).b == 0 && image_get(mi, mi->w - 1, 0).r == 0,
                      "mirror level %d bleeds across the border", l);
        ck_assert(image_get(c, 0, 0).r > 0 && image_get(c, c->w - 1, 0).b > 0);
    }
    mipmap_free(&rep);
    mipmap_free(&cla);
    mipmap_free(&mir);
    image_free(&im);
}
END_TEST

START_TEST(test_level_for_footprint_is_log2_of_the_width_in_texels)
{
    image im = new_image(8, 8); /* levels 0..3 */
    mipmap m = build(&im, WRAP_REPEAT);
    ck_assert(mipmap_level_for_footprint(&m, 1.0) == 0.0);
    ck_assert(mipmap_level_for_footprint(&m, 4.0) == 2.0);
    ck_assert(mipmap_level_for_footprint(&m, 2.0) == 1.0);
    ck_assert_near(mipmap_level_for_footprint(&m, 3.0), log2(3.0), 1e-15);
    ck_assert(mipmap_level_for_footprint(&m, 0.25) == 0.0);
    ck_assert(mipmap_level_for_footprint(&m, 0.0) == 0.0);
    ck_assert(mipmap_level_for_footprint(&m, -5.0) == 0.0);
    ck_assert(mipmap_level_for_footprint(&m, NAN) == 0.0);
    ck_assert(mipmap_level_for_footprint(&m, 64.0) == 3.0);
    ck_assert(mipmap_level_for_footprint(&m, INFINITY) == 3.0);
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

START_TEST(test_trilinear_below_one_texel_is_bilinear_on_the_base)
{
    image im = random_image(13, 6);
    for (int md = 0; md < 3; md++) {
        mipmap m = build(&im, all_modes[md]);
        for (int k = 0; k < 200; k++) {
            uv2 st = {rng_uniform(-2, 3), rng_uniform(-2, 3)};
            rgb want = texlookup_bilinear(&im, st, all_modes[md]);
            rgb a = mipmap_lookup_trilinear(&m, st, 0.0),
                b = mipmap_lookup_trilinear(&m, st, 1.0 / 13);
            /* trilinear blends in float (mipmap.h): a few float ulps of texels in [0, 1) */
            ck_rgb_near(a, want, 1e-6);
            ck_rgb_near(b, want, 1e-6);
        }
        mipmap_free(&m);
    }
    image_free(&im);
}
END_TEST

/* Catches a footprint measured by the width instead of the longer side (mipmap.h: width in texels
 * = footprint_width * max(W, H)): on a TALL 4 x 16 image a footprint of 1/4 is 4 texels, level
 * 2 exactly (the 1 x 4 level, bilinear there); by the width it would be 1 texel, level 0. */
START_TEST(test_trilinear_measures_a_tall_images_footprint_by_its_longer_side)
{
    image im = random_image(4, 16);
    mipmap m = build(&im, WRAP_REPEAT);
    for (int k = 0; k < 50; k++) {
        uv2 st = {rng_uniform(0, 1), rng_uniform(0, 1)};
        ck_rgb_near(mipmap_lookup_trilinear(&m, st, 0.25),
                    texlookup_bilinear(mipmap_level(&m, 2), st, WRAP_REPEAT), 1e-6);
    }
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

START_TEST(test_trilinear_blends_the_two_nearest_levels_by_the_fraction)
{
    image im = random_image(32, 20);
    mipmap m = build(&im, WRAP_REPEAT);
    uv2 st = {0.3, 0.71};
    double fp = pow(2.0, 1.25) / 32; /* level 1.25 */
    rgb want = rgb_madd(rgb_scale(texlookup_bilinear(mipmap_level(&m, 1), st, WRAP_REPEAT), 0.75),
                        texlookup_bilinear(mipmap_level(&m, 2), st, WRAP_REPEAT), 0.25);
    ck_rgb_near(mipmap_lookup_trilinear(&m, st, fp), want, 1e-6); /* float arithmetic */
    /* huge footprint: the 1 x 1 level, the mean */
    ck_rgb_near(mipmap_lookup_trilinear(&m, st, 1e9), image_mean(&im), 1e-5);
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

/* The blend weight itself: on a 2 x 2 texture whose texel (0, 0) is 0 and whose 1 x 1 level is
 * 0.5, a lookup at that texel's centre is f / 2 exactly, f the footprint's fraction of a level:
 * f = log2(width in texels) (a level per doubling), not e.g. the width's fraction itself. */
START_TEST(test_trilinear_blend_weight_is_the_level_fraction)
{
    image im = new_image(2, 2);
    image_set(&im, 0, 1, rgb_gray(0)); /* (0, 0) from the bottom */
    image_set(&im, 1, 1, rgb_gray(1));
    image_set(&im, 0, 0, rgb_gray(1));
    image_set(&im, 1, 0, rgb_gray(0));
    mipmap m = build(&im, WRAP_CLAMP);
    ck_assert_int_eq(mipmap_levels(&m), 2);
    ck_assert(image_get(mipmap_level(&m, 1), 0, 0).g == 0.5f);
    uv2 centre = {0.25, 0.25};
    for (int k = 1; k < 4000; k++) {
        /* texels in (1, 2): w4 = texels^4 in (1, 16), every mantissa and exponents 0 to 3 */
        double texels = k < 3000 ? 1 + k / 3000.0
                                 : exp2(0.25 * (4 - (k - 2999) * 1e-4)); /* up to 2^-1e-4 below 2 */
        double f = 2 * mipmap_lookup_trilinear(&m, centre, texels / 2).g;
        double want = log2(texels);
        if (!(fabs(f - want) <= 1e-12))
            ck_abort_msg("footprint %.12g texels: f = %.9g, log2 = %.9g", texels, f, want);
    }
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

START_TEST(test_trilinear_is_continuous_in_the_footprint)
{
    /* Steps of 1e-3 in log2(footprint) move the level by 1e-3, so the colour by at most 1e-3
     * times the largest difference between levels (< 5 in g, < 1 in r here); switching levels
     * without the blend jumps by that whole difference. */
    image im = random_image(40, 24);
    for (int md = 0; md < 3; md++) {
        mipmap m = build(&im, all_modes[md]);
        for (int k = 0; k < 3; k++) {
            uv2 st = {rng_uniform(0, 1), rng_uniform(0, 1)};
            rgb prev = mipmap_lookup_trilinear(&m, st, 0.5 / 40);
            for (double e = log2(0.5 / 40); e < 1.0; e += 1e-3) {
                rgb c = mipmap_lookup_trilinear(&m, st, exp2(e));
                ck_assert_msg(fabs(c.g - prev.g) < 5.1e-3 && fabs(c.r - prev.r) < 1.1e-3,
                              "jump at footprint %g: %g -> %g", exp2(e), prev.g, c.g);
                prev = c;
            }
            /* right across the switch from level 0 to level 1 (1 texel) */
            rgb lo = mipmap_lookup_trilinear(&m, st, (1 - 1e-9) / 40);
            rgb hi = mipmap_lookup_trilinear(&m, st, (1 + 1e-9) / 40);
            ck_rgb_near(lo, hi, 1e-7);
        }
        mipmap_free(&m);
    }
    image_free(&im);
}
END_TEST

START_TEST(test_ewa_of_a_constant_texture_is_the_constant)
{
    image im = new_image(23, 9);
    for (int y = 0; y < 9; y++)
        for (int x = 0; x < 23; x++) image_set(&im, x, y, rgb_make(0.25, 2.0, 0.125));
    for (int md = 0; md < 3; md++) {
        mipmap m = build(&im, all_modes[md]);
        for (int k = 0; k < 300; k++) {
            uv2 st = {rng_uniform(-1.5, 2.5), rng_uniform(-1.5, 2.5)};
            double s = exp2(rng_uniform(-12, 2));
            uv2 dx = {s * rng_uniform(-1, 1), s * rng_uniform(-1, 1)};
            uv2 dy = {s * rng_uniform(-1, 1) * 0.05, s * rng_uniform(-1, 1)};
            ck_rgb_near(mipmap_lookup_ewa(&m, st, dx, dy), rgb_make(0.25, 2.0, 0.125), 1e-6);
        }
        mipmap_free(&m);
    }
    image_free(&im);
}
END_TEST

START_TEST(test_ewa_with_zero_footprint_is_bilinear_on_the_base)
{
    image im = random_image(11, 7);
    for (int md = 0; md < 3; md++) {
        mipmap m = build(&im, all_modes[md]);
        for (int k = 0; k < 100; k++) {
            uv2 st = {rng_uniform(-1, 2), rng_uniform(-1, 2)};
            rgb a = mipmap_lookup_ewa(&m, st, (uv2){0, 0}, (uv2){0, 0});
            rgb b = texlookup_bilinear(&im, st, all_modes[md]);
            ck_assert(a.r == b.r && a.g == b.g && a.b == b.b);
        }
        mipmap_free(&m);
    }
    image_free(&im);
}
END_TEST

START_TEST(test_ewa_with_a_tiny_footprint_is_bilinear_on_a_ramp_at_texel_centres)
{
    /* value = 3 i + 5 j: the symmetric Gaussian around a texel centre averages a linear function
     * to its centre value, as bilinear does */
    image im = new_image(16, 12);
    for (int j = 0; j < 12; j++)
        for (int i = 0; i < 16; i++) image_set(&im, i, 11 - j, rgb_make(3 * i + 5 * j, i, j));
    mipmap m = build(&im, WRAP_CLAMP);
    for (int j = 3; j < 9; j++)
        for (int i = 3; i < 13; i++) {
            uv2 st = {(i + 0.5) / 16, (j + 0.5) / 12};
            rgb e = mipmap_lookup_ewa(&m, st, (uv2){1e-4, 0}, (uv2){0, 1e-4});
            ck_rgb_near(e, rgb_make(3 * i + 5 * j, i, j), 1e-9);
        }
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

START_TEST(test_ewa_weights_are_the_documented_gaussian)
{
    /* value = i: with a tiny footprint the ellipse is the unit disc around st (in texels);
     * 0.3 texel right of the centre of column 3, the texels of columns 3 and 4 in its row lie
     * at r^2 = 0.09 and 0.49 (the rows above and below at r^2 > 1), so the lookup is their
     * average with weights exp(-2 r^2) - exp(-2).  Reading the table at floor(128 r^2)
     * (pbrt's index) misses by 3.6e-4. */
    image im = new_image(8, 8);
    for (int j = 0; j < 8; j++)
        for (int i = 0; i < 8; i++) image_set(&im, i, j, rgb_make(i, 1, 0));
    mipmap m = build(&im, WRAP_CLAMP);
    double e2 = exp(-MIPMAP_EWA_ALPHA);
    double w3 = exp(-MIPMAP_EWA_ALPHA * 0.09) - e2, w4 = exp(-MIPMAP_EWA_ALPHA * 0.49) - e2;
    double want = (3 * w3 + 4 * w4) / (w3 + w4);
    for (int j = 1; j < 7; j++) {
        uv2 st = {3.8 / 8, (j + 0.5) / 8}; /* x = 3.8 * 8 / 8 - 0.5 = 3.3 texels */
        rgb e = mipmap_lookup_ewa(&m, st, (uv2){1e-9, 0}, (uv2){0, 1e-9});
        ck_assert_near(e.r, want, 2e-5);
        ck_assert_near(e.g, 1.0, 1e-12);
    }
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

START_TEST(test_ewa_of_a_checkerboard_with_a_large_footprint_is_its_average)
{
    image fine = checker_image(64, 64, 1), coarse = checker_image(64, 64, 8);
    for (int md = 0; md < 3; md++) {
        mipmap a = build(&fine, all_modes[md]), b = build(&coarse, all_modes[md]);
        for (int k = 0; k < 20; k++) {
            /* away from the border, where clamp and mirror make a checker's filtered value
             * differ from 1/2 */
            uv2 st = {rng_uniform(0.3, 0.7), rng_uniform(0.3, 0.7)};
            /* footprint wider than the texture: the 1 x 1 level */
            ck_assert_near(mipmap_lookup_ewa(&b, st, (uv2){3, 0}, (uv2){0, 2}).r, 0.5, 1e-6);
            ck_assert_near(mipmap_lookup_ewa(&b, st, (uv2){INFINITY, 0}, (uv2){0, 2}).r, 0.5, 1e-6);
            ck_assert_near(mipmap_lookup_ewa(&b, st, (uv2){NAN, 0}, (uv2){0, 2}).r, 0.5, 1e-6);
            /* a 1-texel checker is gone (exactly 1/2) from level 1 up: 4 texels, level 2 */
            ck_assert_near(
                mipmap_lookup_ewa(&a, st, (uv2){4.0 / 64, 1.0 / 64}, (uv2){-1.0 / 64, 4.0 / 64}).r,
                0.5, 1e-6);
        }
        mipmap_free(&a);
        mipmap_free(&b);
    }
    image_free(&fine);
    image_free(&coarse);
}
END_TEST

START_TEST(test_ewa_filters_along_the_major_axis_only)
{
    /* stripes across x (alternating columns) and across y (alternating rows) */
    image cols = new_image(64, 64), rows = new_image(64, 64);
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            image_set(&cols, x, y, rgb_gray(x % 2));
            image_set(&rows, x, y, rgb_gray(y % 2));
        }
    mipmap mc = build(&cols, WRAP_REPEAT), mr = build(&rows, WRAP_REPEAT);
    /* 4 texels along s, half a texel along t: a ratio of 8, the largest kept as given */
    uv2 dx = {4.0 / 64, 0}, dy = {0, 0.5 / 64};
    for (int k = 0; k < 10; k++) {
        /* texel centres in texture row 30 = image row 33, which is lit */
        uv2 st = {(20 + k + 0.5) / 64, (30 + 0.5) / 64};
        /* across the stripes: averaged */
        ck_assert_near(mipmap_lookup_ewa(&mc, st, dx, dy).r, 0.5, 0.05);
        /* along the stripes: the lit row stays bright */
        ck_assert(mipmap_lookup_ewa(&mr, st, dx, dy).r > 0.85);
        /* while an isotropic footprint as wide as the major axis would average it away */
        ck_assert_near(mipmap_lookup_ewa(&mr, st, dx, (uv2){0, 4.0 / 64}).r, 0.5, 0.05);
    }
    mipmap_free(&mc);
    mipmap_free(&mr);
    image_free(&cols);
    image_free(&rows);
}
END_TEST

START_TEST(test_ewa_clamps_the_anisotropy)
{
    image im = random_image(32, 32);
    mipmap m = build(&im, WRAP_REPEAT);
    uv2 st = {0.4, 0.6}, major = {0.5, 0};
    /* a line footprint (minor 0) and one at exactly the largest ratio agree */
    rgb line = mipmap_lookup_ewa(&m, st, major, (uv2){0, 0});
    rgb capped = mipmap_lookup_ewa(&m, st, major, (uv2){0, 0.5 / MIPMAP_MAX_ANISOTROPY});
    ck_rgb_near(line, capped, 1e-12);
    /* so does a needle of ratio 1000 */
    rgb needle = mipmap_lookup_ewa(&m, st, major, (uv2){0, 0.5 / 1000});
    ck_rgb_near(needle, capped, 1e-12);
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

START_TEST(test_ewa_far_coordinates_read_like_near_ones)
{
    image im = random_image(8, 8);
    uv2 dx = {0.05, 0}, dy = {0, 0.03}; /* axis aligned: clamp's far result is exact */
    mipmap rep = build(&im, WRAP_REPEAT), cla = build(&im, WRAP_CLAMP),
           mir = build(&im, WRAP_MIRROR);
    ck_rgb_near(mipmap_lookup_ewa(&rep, (uv2){0.3 + 1e6, 0.6 - 1e6}, dx, dy),
                mipmap_lookup_ewa(&rep, (uv2){0.3, 0.6}, dx, dy), 1e-6);
    /* mirror's period is 2 (2n texels): s = 0.3 + an odd number of units is the mirrored 1.3 (far:
     * 4000001 units are 3.2e7 texels, past the 2^24 where reduce_coordinate steps in) */
    ck_rgb_near(mipmap_lookup_ewa(&mir, (uv2){0.3 + 4000001.0, 0.6}, dx, dy),
                mipmap_lookup_ewa(&mir, (uv2){1.3, 0.6}, dx, dy), 1e-6);
    ck_rgb_near(mipmap_lookup_ewa(&cla, (uv2){-1e9, 0.6}, dx, dy),
                mipmap_lookup_ewa(&cla, (uv2){-3.0, 0.6}, dx, dy), 1e-9);
    ck_rgb_near(mipmap_lookup_ewa(&cla, (uv2){0.4, 1e12}, dx, dy),
                mipmap_lookup_ewa(&cla, (uv2){0.4, 4.0}, dx, dy), 1e-9);
    /* past 2^53 texels, on a 3-texel (NPOT) texture: the far lookup reads what the lookup at the
     * exactly reduced coordinate reads (fmod; x - n floor(x / n) is not exact there and read a
     * neighbouring texel, 0 where 10 was right: an audit's probe, s = 32600230925411192) */
    image strip = new_image(3, 1);
    for (int i = 0; i < 3; i++) image_set(&strip, i, 0, rgb_gray(10.0 * i));
    uv2 small = {0.2 / 3, 0}, none = {0, 0}; /* 0.2 texel: a round ellipse of about a texel */
    for (wrap_mode w = WRAP_REPEAT; w <= WRAP_MIRROR; w++) {
        if (w == WRAP_CLAMP) continue;
        mipmap m3 = build(&strip, w);
        double period = w == WRAP_MIRROR ? 6 : 3;
        const double far[] = {32600230925411192.0, 1e17 + 8, -3.3e16 - 4, 7.7e18};
        for (int k = 0; k < 4; k++) {
            double x = far[k] * 3 - 0.5, r = fmod(x, period); /* the texel coordinate, reduced */
            if (r < 0) r += period;
            uv2 st = {far[k], 0.5}, near = {(r + 0.5) / 3, 0.5};
            ck_rgb_near(mipmap_lookup_ewa(&m3, st, small, none),
                        mipmap_lookup_ewa(&m3, near, small, none), 1e-3);
        }
        mipmap_free(&m3);
    }
    image_free(&strip);
    ck_assert(rgb_is_finite(mipmap_lookup_ewa(&rep, (uv2){NAN, 0.5}, dx, dy)));
    ck_assert(rgb_is_finite(mipmap_lookup_ewa(&cla, (uv2){INFINITY, 0.5}, dx, dy)));
    ck_assert(rgb_is_finite(mipmap_lookup_trilinear(&cla, (uv2){INFINITY, NAN}, 0.1)));
    mipmap_free(&rep);
    mipmap_free(&cla);
    mipmap_free(&mir);
    image_free(&im);
}
END_TEST

/* Catches an EWA ellipse of the wrong size or shape: the filter is the ellipse x^T S^-1 x < 1 with
 * S = J J^T + I (J the footprint's axes in texels, I the texel's own reconstruction).  A single
 * lit texel on black, read with axes of 4 and 1 texels (level 0: the minor axis is 1 texel):
 * S has the axes' directions with variances 17 and 2, so the texel counts (> 0) at 4.05 texels
 * along the major axis and 1.38 across it (r^2 = 0.965, 0.952) and not at all (exactly 0) at
 * 4.5 and 1.6 (r^2 = 1.19, 1.28); axis-aligned and turned by 45 degrees (where S has a cross
 * term).  A bounding box of half the ellipse's extent, a lost "+ 1" (variances 16 or 1: r^2 =
 * 1.03, 1.90) or a wrong det S would move these edges. */
START_TEST(test_ewa_ellipse_is_the_footprint_plus_one_texel)
{
    enum { N = 32, I0 = 16, J0 = 16 };
    image im = new_image(N, N);
    image_set(&im, I0, N - 1 - J0, rgb_gray(1)); /* texel (I0, J0), J0 from the bottom */
    mipmap m = build(&im, WRAP_CLAMP);
    for (int turned = 0; turned < 2; turned++) {
        double c = turned ? sqrt(0.5) : 1, sn = turned ? sqrt(0.5) : 0; /* major axis (c, sn) */
        uv2 d0 = {4 * c / N, 4 * sn / N}, d1 = {-sn / N, c / N};
        const double along[4] = {4.05, 4.5, 0, 0}, across[4] = {0, 0, 1.38, 1.6};
        for (int k = 0; k < 4; k++) {
            /* the lit texel's offset from the lookup point, in texels */
            double ox = along[k] * c - across[k] * sn, oy = along[k] * sn + across[k] * c;
            uv2 st = {(I0 + 0.5 - ox) / N, (J0 + 0.5 - oy) / N};
            double v = mipmap_lookup_ewa(&m, st, d0, d1).g;
            int inside = k % 2 == 0;
            ck_assert_msg(inside ? v > 0 : v == 0, "%s, %g along and %g across: %g",
                          turned ? "turned" : "aligned", along[k], across[k], v);
        }
    }
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

/* Catches EWA switching levels without the blend (or blending only part of the way): as the
 * footprint grows by steps of 1e-3 in log2, from half a texel to 8 texels, the colour moves
 * smoothly (measured: at most 0.016 in g, whose texels span [0, 5); the LUT's steps), while a
 * level switched without the blend jumps by half the difference between two levels or more
 * (0.28 here). */
START_TEST(test_ewa_is_continuous_in_the_footprint)
{
    image im = random_image(40, 24);
    mipmap m = build(&im, WRAP_REPEAT);
    double worst = 0;
    for (int k = 0; k < 3; k++) {
        uv2 st = {rng_uniform(0, 1), rng_uniform(0, 1)}, dx = {0.5 / 40, 0}, dy = {0, 0.5 / 24};
        rgb prev = mipmap_lookup_ewa(&m, st, dx, dy);
        for (double e = -1 + 1e-3; e < 3.0; e += 1e-3) {
            double r = exp2(e); /* the footprint in texels, each way */
            rgb c = mipmap_lookup_ewa(&m, st, (uv2){r / 40, 0}, (uv2){0, r / 24});
            worst = fmax(worst, fabs(c.g - prev.g));
            prev = c;
        }
    }
    ck_assert_msg(worst < 0.05, "the colour jumps by %g between footprints 1e-3 apart in log2",
                  worst);
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

START_TEST(test_build_rejects_an_empty_image_and_an_unknown_wrap_mode)
{
    mipmap m;
    error err = {0};
    image empty = {0};
    ck_assert_int_eq(mipmap_build(&m, &empty, WRAP_REPEAT, &err), -1);
    ck_assert(strstr(err.msg, "empty") != NULL);
    mipmap_free(&m);
    image im = new_image(2, 2);
    memset(&err, 0, sizeof err);
    ck_assert_int_eq(mipmap_build(&m, &im, (wrap_mode)7, &err), -1);
    ck_assert(strstr(err.msg, "wrap") != NULL);
    mipmap_free(&m);
    image_free(&im);
}
END_TEST

/* A footprint says how many texels it covers, whatever the image's aspect ratio: every level
 * halves both sides, so EWA measures its axes in texels, (ds W, dt H).  Two images of stripes
 * 4 rows wide, 64 x 64 and 64 x 16, read around the same texel with the same footprint in
 * texels (2 across, 1 up, the minor axis one texel: level 0) give the same answer.  In texture
 * units the 64 x 16 image's minor axis once measured 2 of the longer side's texels: level 1,
 * blurrier stripes. */
START_TEST(test_ewa_measures_a_non_square_images_footprint_in_texels)
{
    image sq = new_image(64, 64), wide = new_image(64, 16);
    for (int j = 0; j < 64; j++)
        for (int i = 0; i < 64; i++) {
            image_set(&sq, i, j, rgb_gray((j / 4) % 2));
            if (j < 16) image_set(&wide, i, j, rgb_gray((j / 4) % 2));
        }
    mipmap a, b;
    error err = {0};
    ck_assert_int_eq(mipmap_build(&a, &sq, WRAP_REPEAT, &err), 0);
    ck_assert_int_eq(mipmap_build(&b, &wide, WRAP_REPEAT, &err), 0);
    /* texel (20, 5) from the top of both, in a stripe of 1: the same texels around it */
    uv2 sta = {20.5 / 64, (64 - 5.5) / 64}, stb = {20.5 / 64, (16 - 5.5) / 16};
    rgb ca = mipmap_lookup_ewa(&a, sta, (uv2){2.0 / 64, 0}, (uv2){0, 1.0 / 64});
    rgb cb = mipmap_lookup_ewa(&b, stb, (uv2){2.0 / 64, 0}, (uv2){0, 1.0 / 16});
    ck_assert_msg(ca.r > 0.75, "the square image's level 0 shows the stripe: %g", ca.r);
    ck_assert_msg(fabs(ca.r - cb.r) < 1e-6, "64 x 64 gives %.9g, 64 x 16 %.9g", ca.r, cb.r);
    /* the same axes given the other way round (dst/dx along t): each axis's t by H, not W */
    rgb sa = mipmap_lookup_ewa(&a, sta, (uv2){0, 1.0 / 64}, (uv2){2.0 / 64, 0});
    rgb sb = mipmap_lookup_ewa(&b, stb, (uv2){0, 1.0 / 16}, (uv2){2.0 / 64, 0});
    ck_assert_msg(fabs(sa.r - ca.r) < 1e-6 && fabs(sb.r - cb.r) < 1e-6,
                  "axes swapped: %.9g and %.9g", sa.r, sb.r);
    mipmap_free(&a);
    mipmap_free(&b);
    image_free(&sq);
    image_free(&wide);
}
END_TEST

Suite *mipmap_suite(void)
{
    Suite *s = suite_create("mipmap");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_levels_halve_rounding_down_to_one_by_one);
    tcase_add_test(tc, test_level_zero_references_the_base_and_free_leaves_it_alone);
    tcase_add_test(tc, test_every_level_keeps_the_mean_for_odd_and_even_sizes);
    tcase_add_test(tc, test_odd_sizes_keep_the_last_column_and_row);
    tcase_add_test(tc, test_even_sizes_use_the_weights_one_seven_seven_one_over_sixteen);
    tcase_add_test(tc, test_repeat_blends_the_opposite_border_at_every_level_and_clamp_does_not);
    tcase_add_test(tc, test_level_for_footprint_is_log2_of_the_width_in_texels);
    tcase_add_test(tc, test_trilinear_below_one_texel_is_bilinear_on_the_base);
    tcase_add_test(tc, test_trilinear_measures_a_tall_images_footprint_by_its_longer_side);
    tcase_add_test(tc, test_trilinear_blends_the_two_nearest_levels_by_the_fraction);
    tcase_add_test(tc, test_trilinear_blend_weight_is_the_level_fraction);
    tcase_add_test(tc, test_trilinear_is_continuous_in_the_footprint);
    tcase_add_test(tc, test_ewa_of_a_constant_texture_is_the_constant);
    tcase_add_test(tc, test_ewa_with_zero_footprint_is_bilinear_on_the_base);
    tcase_add_test(tc, test_ewa_with_a_tiny_footprint_is_bilinear_on_a_ramp_at_texel_centres);
    tcase_add_test(tc, test_ewa_weights_are_the_documented_gaussian);
    tcase_add_test(tc, test_ewa_of_a_checkerboard_with_a_large_footprint_is_its_average);
    tcase_add_test(tc, test_ewa_filters_along_the_major_axis_only);
    tcase_add_test(tc, test_ewa_clamps_the_anisotropy);
    tcase_add_test(tc, test_ewa_measures_a_non_square_images_footprint_in_texels);
    tcase_add_test(tc, test_ewa_far_coordinates_read_like_near_ones);
    tcase_add_test(tc, test_ewa_ellipse_is_the_footprint_plus_one_texel);
    tcase_add_test(tc, test_ewa_is_continuous_in_the_footprint);
    tcase_add_test(tc, test_build_rejects_an_empty_image_and_an_unknown_wrap_mode);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(mipmap_suite)
