/* test_genenv.c - procedural environments: sizes, exact constants, the axes map's colours at
 * known directions, and the sun: its disc carries sun_ratio times the sky's mean radiance over
 * its solid angle, in the direction asked for. */
#include "envtex/envmaps/genenv.h"

#include <string.h>

#include "envtex/envmaps/latlong.h"
#include "unit.h"

static image make(genenv_kind kind, const genenv_params *p)
{
    image im;
    error err = {0};
    if (genenv_make(kind, p, &im, &err)) ck_abort_msg("genenv: %s", err.msg);
    return im;
}

START_TEST(test_genenv_maps_are_two_to_one)
{
    genenv_params p = genenv_defaults();
    const int widths[] = {1, 2, 3, 64, 513};
    for (unsigned i = 0; i < sizeof widths / sizeof widths[0]; i++) {
        p.width = widths[i];
        image im = make(GENENV_SKY, &p);
        ck_assert_int_eq(im.w, widths[i]);
        ck_assert_int_eq(im.h, widths[i] / 2 > 0 ? widths[i] / 2 : 1);
        image_free(&im);
    }
    p = genenv_defaults();
    image im = make(GENENV_CONSTANT, &p);
    ck_assert_int_eq(im.w, 512); /* the documented default */
    ck_assert_int_eq(im.h, 256);
    image_free(&im);
}
END_TEST

START_TEST(test_genenv_constant_is_exact_everywhere)
{
    genenv_params p = genenv_defaults();
    p.width = 32;
    p.value = 0.3;
    image im = make(GENENV_CONSTANT, &p);
    for (int i = 0; i < 32 * 16 * 3; i++) ck_assert(im.px[i] == (float)0.3);
    image_free(&im);
    p.value = 0; /* zero is allowed: a black world */
    im = make(GENENV_CONSTANT, &p);
    for (int i = 0; i < 32 * 16 * 3; i++) ck_assert(im.px[i] == 0);
    image_free(&im);
}
END_TEST

START_TEST(test_genenv_axes_colours_name_their_directions)
{
    genenv_params p = genenv_defaults();
    p.width = 256;
    image im = make(GENENV_AXES, &p);
    /* (d + 1) / 2: +x red, +y green, +z blue (nearest lookup: within half a texel) */
    const struct {
        vec3 d;
        rgb c;
    } cases[] = {{{1, 0, 0}, {1, 0.5, 0.5}},  {{0, 1, 0}, {0.5, 1, 0.5}},
                 {{-1, 0, 0}, {0, 0.5, 0.5}}, {{0, -1, 0}, {0.5, 0, 0.5}},
                 {{0, 0, 1}, {0.5, 0.5, 1}},  {{0, 0, -1}, {0.5, 0.5, 0}}};
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        rgb c = latlong_lookup_nearest(&im, cases[i].d);
        ck_assert_msg(fabs(c.r - cases[i].c.r) < 0.02 && fabs(c.g - cases[i].c.g) < 0.02 &&
                          fabs(c.b - cases[i].c.b) < 0.02,
                      "direction %u: (%g, %g, %g)", i, c.r, c.g, c.b);
    }
    /* every texel is exactly (d + 1) / 2 of its centre direction (float rounding) */
    for (int y = 0; y < im.h; y++)
        for (int x = 0; x < im.w; x++) {
            vec3 d = latlong_uv_to_dir((uv2){(x + 0.5) / im.w, (y + 0.5) / im.h});
            rgb c = image_get(&im, x, y);
            if (!(fabs(c.r - (d.x + 1) / 2) < 1e-7 && fabs(c.g - (d.y + 1) / 2) < 1e-7 &&
                  fabs(c.b - (d.z + 1) / 2) < 1e-7))
                ck_abort_msg("texel (%d, %d) is not (d + 1) / 2", x, y);
        }
    image_free(&im);
}
END_TEST

START_TEST(test_genenv_sky_is_blue_above_and_dim_below)
{
    genenv_params p = genenv_defaults();
    p.width = 64;
    image im = make(GENENV_SKY, &p);
    rgb zen = latlong_lookup_nearest(&im, vec3_make(0, 0, 1)),
        nad = latlong_lookup_nearest(&im, vec3_make(0, 0, -1));
    ck_assert(zen.b > zen.r);
    ck_assert(rgb_avg(nad) < rgb_avg(zen));
    for (int i = 0; i < im.w * im.h * 3; i++) ck_assert(isfinite(im.px[i]) && im.px[i] > 0);
    image_free(&im);
}
END_TEST

/* Solid-angle weighted sum of the average channel: sum L dw over the sphere. */
static double power(const image *im)
{
    double s = 0;
    for (int y = 0; y < im->h; y++) {
        double dw = latlong_texel_solid_angle(y, im->w, im->h);
        for (int x = 0; x < im->w; x++) s += rgb_avg(image_get(im, x, y)) * dw;
    }
    return s;
}

START_TEST(test_genenv_sun_disc_carries_sun_ratio_times_the_sky_mean)
{
    genenv_params p = genenv_defaults();
    p.width = 512;
    p.sun_ratio = 1e4;
    p.sun_radius_deg = 1.5; /* wide enough that some texels lie wholly inside the disc */
    image sky = make(GENENV_SKY, &p), sun = make(GENENV_SUN, &p);
    double mean = power(&sky) / (4 * M_PI);
    /* the disc's extra power over the sky is (L_sun - L_sky) times its solid angle */
    double cap = 2 * M_PI * (1 - cos(p.sun_radius_deg * M_PI / 180));
    double extra = power(&sun) - power(&sky);
    ck_assert_msg(fabs(extra / cap / mean / p.sun_ratio - 1) < 0.1,
                  "disc mean = %g x the sky mean, want %g", extra / cap / mean, p.sun_ratio);
    /* fully covered texels hold exactly L_sun = ratio x mean (float rounding) */
    float peak = 0;
    for (int i = 0; i < sun.w * sun.h * 3; i++) peak = fmaxf(peak, sun.px[i]);
    ck_assert_near(peak / (p.sun_ratio * mean), 1, 1e-5);
    image_free(&sky);
    image_free(&sun);
}
END_TEST

START_TEST(test_genenv_sun_power_points_at_the_requested_direction)
{
    const double pos[][2] = {{35, 60}, {10, 200}, {80, -30}};
    for (int k = 0; k < 3; k++) {
        genenv_params p = genenv_defaults();
        p.width = 512;
        p.sun_elevation_deg = pos[k][0];
        p.sun_azimuth_deg = pos[k][1];
        image sky = make(GENENV_SKY, &p), sun = make(GENENV_SUN, &p);
        /* power-weighted mean direction of the disc (sun minus sky) */
        vec3 m = vec3_make(0, 0, 0);
        for (int y = 0; y < sun.h; y++) {
            double dw = latlong_texel_solid_angle(y, sun.w, sun.h);
            for (int x = 0; x < sun.w; x++) {
                double e = rgb_avg(image_get(&sun, x, y)) - rgb_avg(image_get(&sky, x, y));
                if (e == 0) continue;
                vec3 d = latlong_uv_to_dir((uv2){(x + 0.5) / sun.w, (y + 0.5) / sun.h});
                m = vec3_madd(m, d, e * dw);
            }
        }
        double el = pos[k][0] * M_PI / 180, az = pos[k][1] * M_PI / 180;
        vec3 want = vec3_make(cos(el) * cos(az), cos(el) * sin(az), sin(el));
        double ang = acos(fmin(1, vec3_dot(vec3_normalize(m), want))) * 180 / M_PI;
        ck_assert_msg(ang < 0.2, "sun %d: power centred %g degrees from the requested direction", k,
                      ang);
        image_free(&sky);
        image_free(&sun);
    }
}
END_TEST

START_TEST(test_genenv_rejects_bad_parameters)
{
    error err = {0};
    image im;
    genenv_params p = genenv_defaults();
    p.width = 0;
    ck_assert_int_eq(genenv_make(GENENV_SKY, &p, &im, &err), -1);
    ck_assert_ptr_null(im.px);
    p.width = 70000;
    ck_assert_int_eq(genenv_make(GENENV_SKY, &p, &im, &err), -1);
    p = genenv_defaults();
    p.value = -1;
    ck_assert_int_eq(genenv_make(GENENV_CONSTANT, &p, &im, &err), -1);
    p.value = NAN;
    ck_assert_int_eq(genenv_make(GENENV_CONSTANT, &p, &im, &err), -1);
    p.value = INFINITY;
    ck_assert_int_eq(genenv_make(GENENV_CONSTANT, &p, &im, &err), -1);
    p = genenv_defaults();
    p.sun_ratio = 0;
    ck_assert_int_eq(genenv_make(GENENV_SUN, &p, &im, &err), -1);
    p = genenv_defaults();
    p.sun_radius_deg = 0;
    ck_assert_int_eq(genenv_make(GENENV_SUN, &p, &im, &err), -1);
    p.sun_radius_deg = NAN;
    ck_assert_int_eq(genenv_make(GENENV_SUN, &p, &im, &err), -1);
    p.sun_radius_deg = 90; /* (0, 90): a sun of half the sky or more is not a sun */
    ck_assert_int_eq(genenv_make(GENENV_SUN, &p, &im, &err), -1);
    p.sun_radius_deg = 89.9;
    ck_assert_int_eq(genenv_make(GENENV_SUN, &p, &im, &err), 0);
    image_free(&im);
    p = genenv_defaults();
    p.sun_elevation_deg = INFINITY;
    ck_assert_int_eq(genenv_make(GENENV_SUN, &p, &im, &err), -1);
    ck_assert_ptr_null(im.px);
    /* an elevation past the zenith or nadir is a sun on the other side: refused, not folded */
    const double bad_el[] = {90.000001, -90.000001, 100, -180, 1e300, NAN};
    for (int k = 0; k < (int)(sizeof bad_el / sizeof bad_el[0]); k++) {
        p.sun_elevation_deg = bad_el[k];
        ck_assert_msg(genenv_make(GENENV_SUN, &p, &im, &err) == -1, "elevation %g accepted",
                      bad_el[k]);
        ck_assert_ptr_null(im.px);
    }
    ck_assert_str_eq(err.msg, "sun elevation must be in [-90, 90] degrees");
    const double ok_el[] = {90, -90, 0};
    for (int k = 0; k < 3; k++) {
        p.sun_elevation_deg = ok_el[k];
        ck_assert_msg(genenv_make(GENENV_SUN, &p, &im, &err) == 0, "elevation %g: %s", ok_el[k],
                      err.msg);
        image_free(&im);
    }
    p = genenv_defaults();
    p.sun_azimuth_deg = -INFINITY;
    ck_assert_int_eq(genenv_make(GENENV_SUN, &p, &im, &err), -1);
    p.sun_azimuth_deg = -725; /* any finite azimuth: it goes round */
    ck_assert_int_eq(genenv_make(GENENV_SUN, &p, &im, &err), 0);
    image_free(&im);
}
END_TEST

START_TEST(test_genenv_kind_parse_knows_the_four_names)
{
    genenv_kind k = GENENV_SKY;
    ck_assert_int_eq(genenv_kind_parse("constant", &k), 0);
    ck_assert_int_eq(k, GENENV_CONSTANT);
    ck_assert_int_eq(genenv_kind_parse("sun", &k), 0);
    ck_assert_int_eq(k, GENENV_SUN);
    ck_assert_int_eq(genenv_kind_parse("axes", &k), 0);
    ck_assert_int_eq(k, GENENV_AXES);
    ck_assert_int_eq(genenv_kind_parse("sky", &k), 0);
    ck_assert_int_eq(k, GENENV_SKY);
    ck_assert_int_eq(genenv_kind_parse("Sky", &k), -1);
    ck_assert_int_eq(genenv_kind_parse("", &k), -1);
    ck_assert_int_eq(k, GENENV_SKY); /* untouched on failure */
}
END_TEST

Suite *genenv_suite(void)
{
    Suite *s = suite_create("genenv");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_genenv_maps_are_two_to_one);
    tcase_add_test(tc, test_genenv_constant_is_exact_everywhere);
    tcase_add_test(tc, test_genenv_axes_colours_name_their_directions);
    tcase_add_test(tc, test_genenv_sky_is_blue_above_and_dim_below);
    tcase_add_test(tc, test_genenv_sun_disc_carries_sun_ratio_times_the_sky_mean);
    tcase_add_test(tc, test_genenv_sun_power_points_at_the_requested_direction);
    tcase_add_test(tc, test_genenv_rejects_bad_parameters);
    tcase_add_test(tc, test_genenv_kind_parse_knows_the_four_names);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(genenv_suite)
