/* test_prefiltered.c - `integrator prefiltered` (prefiltered.h) and its scene commands: a diffuse
 * or Phong sphere in a constant environment is (kd + ks n.r) L with either irradiance method;
 * mirrors and glass are the ray tracer's to the bit; the maps follow the envmap's transform;
 * lights are warned about, GGX and a non-rotation refused; one Phong map per shininess. */
#include "envtex/integrators/prefiltered.h"

#include <string.h>

#include "envtex/geometry/bvh.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/integrators/integrator.h"
#include "envtex/envmaps/latlong.h"
#include "envtex/render/render.h"
#include "envtex/scene/scene_load.h"
#include "unit.h"

#define HEAD "size 24 24\ncamera 0 0 4 0 0 0 0 1 0 30\n"

typedef struct warnings {
    int n;
    error last;
} warnings;

static void keep_warning(void *ctx, const error *w)
{
    warnings *ws = ctx;
    ws->n++;
    ws->last = *w;
}

/* scene_load_string without images: the envmap is set by set_env */
static int load(scene *sc, const char *text, warnings *ws, error *err)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    if (ws) {
        memset(ws, 0, sizeof *ws);
        o.warn = keep_warning;
        o.warn_ctx = ws;
    }
    return scene_load_string(text, "prefiltered.test", &o, sc, err);
}

static void load_ok(scene *sc, const char *text)
{
    error err = {0};
    if (load(sc, text, NULL, &err)) ck_abort_msg("scene: line %d: %s", err.line, err.msg);
}

static void set_env(scene *sc, genenv_kind kind, int width, double value)
{
    genenv_params p = genenv_defaults();
    p.width = width;
    p.value = value;
    p.sun_elevation_deg = 90; /* the sun map's sun at the zenith, envmap +z */
    p.sun_radius_deg = 5;
    p.sun_ratio = 1000;
    error err = {0};
    image_free(&sc->envmap.img);
    ck_assert_int_eq(genenv_make(kind, &p, &sc->envmap.img, &err), 0);
    sc->envmap.present = 1;
    if (!(sc->envmap.scale > 0)) sc->envmap.scale = 1;
}

static void render_ok(const scene *sc, image *out)
{
    render_opts o = render_defaults();
    render_stats st;
    error err = {0};
    if (render_scene(sc, &o, out, &st, &err)) ck_abort_msg("render: %s", err.msg);
}

/* an integrator on a scene, outside render_scene */
typedef struct rig {
    bvh b;
    integrator it;
} rig;

static int rig_init(rig *r, const scene *sc, error *err)
{
    if (bvh_build(&r->b, scene_prims(sc), NULL, err)) return -1;
    if (integrator_init(&r->it, sc, &r->b, NULL, err)) {
        bvh_free(&r->b);
        return -1;
    }
    return 0;
}

static void rig_free(rig *r)
{
    integrator_free(&r->it);
    bvh_free(&r->b);
}

START_TEST(test_the_scene_chooses_the_integrator_and_the_irradiance_method)
{
    scene sc;
    load_ok(&sc, HEAD "integrator prefiltered\n");
    ck_assert_int_eq(sc.integrator, INTEGRATOR_PREFILTERED);
    ck_assert_int_eq(sc.prefilter, IRRADIANCE_EXACT); /* the default */
    ck_assert_str_eq(scene_integrator_name(sc.integrator), "prefiltered");
    scene_free(&sc);
    load_ok(&sc, HEAD "prefilter sh9\nintegrator prefiltered\n");
    ck_assert_int_eq(sc.prefilter, IRRADIANCE_SH9);
    scene_free(&sc);
    load_ok(&sc, HEAD "prefilter sh9\nprefilter exact\n");
    ck_assert_int_eq(sc.prefilter, IRRADIANCE_EXACT);
    scene_free(&sc);
    error err = {0};
    ck_assert_int_eq(load(&sc, HEAD "prefilter sh10\n", NULL, &err), -1);
    ck_assert_int_eq(err.line, 3);
    ck_assert_ptr_nonnull(strstr(err.msg, "sh10"));
    ck_assert_int_eq(load(&sc, HEAD "prefilter\n", NULL, &err), -1);
    ck_assert_int_eq(load(&sc, HEAD "prefilter exact sh9\n", NULL, &err), -1);
}
END_TEST

START_TEST(test_lights_in_a_prefiltered_scene_are_warned_about_at_the_first)
{
    scene sc;
    warnings ws;
    error err = {0};
    ck_assert_int_eq(load(&sc,
                          HEAD "integrator prefiltered\nsphere 0 0 0 1\n"
                               "quadLight 0 2 0 1 0 0 0 0 1 5 5 5\npoint 0 3 0 1 1 1\n",
                          &ws, &err),
                     0);
    ck_assert_int_eq(ws.n, 1);
    ck_assert_int_eq(ws.last.line, 5); /* the quad light, before the point light */
    ck_assert_ptr_nonnull(strstr(ws.last.msg, "'prefiltered' integrator"));
    scene_free(&sc);
    ck_assert_int_eq(load(&sc, HEAD "directional 0 1 0 1 1 1\nintegrator prefiltered\n", &ws, &err),
                     0);
    ck_assert_int_eq(ws.n, 1);
    ck_assert_int_eq(ws.last.line, 3);
    scene_free(&sc);
    ck_assert_int_eq(load(&sc, HEAD "integrator prefiltered\nsphere 0 0 0 1\n", &ws, &err), 0);
    ck_assert_int_eq(ws.n, 0);
    scene_free(&sc);
}
END_TEST

/* A lone sphere filling the middle of the picture, in a constant environment L = 2. */
#define FURNACE HEAD "integrator prefiltered\nambient 0.3 0.3 0.3\n"

START_TEST(test_a_diffuse_or_phong_sphere_in_a_constant_environment_is_kd_plus_ks_times_L)
{
    const char *methods[] = {"prefilter exact\n", "prefilter sh9\n"};
    for (int m = 0; m < 2; m++)
        for (int phong = 0; phong < 2; phong++) {
            char text[512];
            snprintf(text, sizeof text, FURNACE "%s%s sphere 0 0 0 1\n", methods[m],
                     phong ? "diffuse 0.3 0.2 0.1\nspecular 0.2 0.4 0.6\nshininess 30\n"
                           : "diffuse 0.6 0.4 0.2\n");
            scene sc;
            load_ok(&sc, text);
            set_env(&sc, GENENV_CONSTANT, 512, 2);
            image im;
            render_ok(&sc, &im);
            /* the centre pixels see the sphere head on: (kd + ks (n . r)) L with n . r ~ 1,
             * ambient ignored; a corner the environment itself */
            rgb c = image_get(&im, 12, 12),
                k = phong ? rgb_make(0.5, 0.6, 0.7) : rgb_make(0.6, 0.4, 0.2);
            /* (pixel 12's centre is half a pixel off the axis: n . r = 0.998) */
            ck_assert_double_eq_tol(c.r, 2 * k.r, 5e-3);
            ck_assert_double_eq_tol(c.g, 2 * k.g, 5e-3);
            ck_assert_double_eq_tol(c.b, 2 * k.b, 5e-3);
            ck_assert_double_eq_tol(image_get(&im, 0, 0).g, 2, 1e-6);
            image_free(&im);
            scene_free(&sc);
        }
}
END_TEST

START_TEST(test_a_phong_lobe_is_ks_times_the_cosine_at_its_axis_times_its_map)
{
    scene sc;
    load_ok(&sc,
            HEAD "integrator prefiltered\nspecular 0.5 0.25 1\nshininess 40\nsphere 0 0 0 1\n");
    set_env(&sc, GENENV_CONSTANT, 512, 2);
    rig r;
    error err = {0};
    ck_assert_int_eq(rig_init(&r, &sc, &err), 0);
    surface s;
    memset(&s, 0, sizeof s);
    brdf_surface_from_material(&s, &sc.materials[0]);
    s.n = s.ng = vec3_make(0, 0, 1);
    const double angles[] = {0, 30, 60, 85};
    for (int i = 0; i < 4; i++) {
        double a = angles[i] * M_PI / 180; /* the view's angle from n, which r makes too */
        vec3 view = vec3_make(sin(a), 0, cos(a));
        int reflect = 1;
        rgb c = prefiltered_shade(r.it.pf, &sc.materials[0], &s, view, &reflect);
        ck_assert_int_eq(reflect, 0); /* the lobe replaces the mirror bounce */
        /* a constant map's Phong map is 1: ks (n . r) L */
        ck_assert_double_eq_tol(c.r, 0.5 * cos(a) * 2, 2e-3);
        ck_assert_double_eq_tol(c.b, 1.0 * cos(a) * 2, 2e-3);
    }
    /* a mirror or glass surface: emission only, the ray tracer bounces */
    s.kind = BRDF_MIRROR;
    s.emission = rgb_gray(0.125);
    int reflect = 1;
    rgb c = prefiltered_shade(r.it.pf, &sc.materials[0], &s, vec3_make(0, 0, 1), &reflect);
    ck_assert_int_eq(reflect, 1);
    ck_assert_double_eq(c.g, 0.125);
    rig_free(&r);
    scene_free(&sc);
}
END_TEST

START_TEST(test_mirrors_and_glass_are_the_ray_tracers_to_the_bit)
{
    const char *body = "ambient 0 0 0\nbrdf mirror\nspecular 0.9 0.8 0.7\nsphere -0.6 0 0 0.5\n"
                       "brdf glass\nior 1.5\nsphere 0.6 0 0 0.5\n";
    char a[512], b[512];
    snprintf(a, sizeof a, HEAD "integrator raytracer\n%s", body);
    snprintf(b, sizeof b, HEAD "integrator prefiltered\n%s", body);
    scene sa, sb;
    load_ok(&sa, a);
    load_ok(&sb, b);
    set_env(&sa, GENENV_SUN, 64, 1);
    set_env(&sb, GENENV_SUN, 64, 1);
    image ia, ib;
    render_ok(&sa, &ia);
    render_ok(&sb, &ib);
    ck_assert(memcmp(ia.px, ib.px, 3 * sizeof(float) * ia.w * ia.h) == 0);
    image_free(&ia);
    image_free(&ib);
    scene_free(&sa);
    scene_free(&sb);
}
END_TEST

START_TEST(test_the_maps_follow_the_envmaps_transform)
{
    /* the sun at envmap +z; `rotate 1 0 0 -90` turns it to world +y */
    for (int m = 0; m < 2; m++) {
        scene sc;
        load_ok(&sc, m ? HEAD
                         "integrator prefiltered\nprefilter sh9\npushTransform\nrotate 1 0 0 -90\n"
                         "envmap x.exr\npopTransform\ndiffuse 1 1 1\nsphere 0 0 0 1\n"
                       : HEAD "integrator prefiltered\npushTransform\nrotate 1 0 0 -90\n"
                              "envmap x.exr\npopTransform\ndiffuse 1 1 1\nsphere 0 0 0 1\n");
        set_env(&sc, GENENV_SUN, 128, 1);
        rig r;
        error err = {0};
        ck_assert_int_eq(rig_init(&r, &sc, &err), 0);
        const prefiltered *pf = r.it.pf;
        ck_assert_ptr_nonnull(pf);
        rgb up = prefiltered_irradiance(pf, vec3_make(0, 1, 0));
        rgb z = prefiltered_irradiance(pf, vec3_make(0, 0, 1)),
            down = prefiltered_irradiance(pf, vec3_make(0, -1, 0));
        ck_assert(up.g > 3 * z.g && z.g > down.g);
        /* and exactly the map made in the envmap's frame, at the turned normal */
        convert_env env = envmap_view(&r.it.rt.env);
        image ref = {0};
        prefilter_sh9 sh;
        ck_assert_int_eq(
            m ? prefilter_sh9_project(&env, &sh, &err) ||
                    prefilter_irradiance_sh9(&sh, PREFILTERED_IRRADIANCE_WIDTH, &ref, &err)
              : prefilter_irradiance_exact(&env, PREFILTERED_IRRADIANCE_WIDTH, &ref, &err),
            0);
        const vec3 world[] = {{0.3, 0.9, -0.2}, {-0.7, 0.1, 0.7}, {0, 0, -1}};
        for (int i = 0; i < 3; i++) {
            vec3 n = vec3_normalize(world[i]), e = mat4_dir(&sc.envmap.inv, n);
            rgb got = prefiltered_irradiance(pf, n);
            rgb want = m ? rgb_scale(prefilter_sh9_irradiance(&sh, vec3_normalize(e)), 1 / M_PI)
                         : latlong_lookup_bilinear(&ref, e);
            ck_assert_double_eq_tol(got.g, want.g, 1e-9 + 1e-6 * want.g);
        }
        image_free(&ref);
        rig_free(&r);
        scene_free(&sc);
    }
}
END_TEST

/* One bright texel at the zenith: SH9 gives about L dOmega (1/4 + x/2 + 5 (3x^2 - 1) / 32),
 * below 0 around x = -0.53 (test_prefilter); the integrator's light is SH9's clamped at 0. */
START_TEST(test_sh9_irradiance_is_never_negative_behind_a_point_source)
{
    scene sc;
    load_ok(&sc, HEAD "integrator prefiltered\nprefilter sh9\ndiffuse 1 1 1\nsphere 0 0 0 1\n");
    error err = {0};
    ck_assert_int_eq(image_alloc(&sc.envmap.img, 64, 32, &err), 0);
    image_set(&sc.envmap.img, 0, 0, rgb_gray(1000));
    sc.envmap.present = 1;
    rig r;
    ck_assert_int_eq(rig_init(&r, &sc, &err), 0);
    convert_env env = envmap_view(&r.it.rt.env);
    prefilter_sh9 sh;
    ck_assert_int_eq(prefilter_sh9_project(&env, &sh, &err), 0);
    vec3 w = latlong_uv_to_dir((uv2){0.5 / 64, 0.5 / 32});
    int below = 0;
    for (int i = 0; i <= 20; i++) {
        double x = -1 + i / 10.0; /* n . w */
        vec3 t = vec3_normalize(vec3_cross(w, vec3_make(1, 0, 0)));
        vec3 n = vec3_add(vec3_scale(w, x), vec3_scale(t, sqrt(fmax(0, 1 - x * x))));
        double raw = prefilter_sh9_irradiance(&sh, mat4_dir(&sc.envmap.inv, n)).g / M_PI;
        double want = fmax(0, raw);
        below += raw < 0;
        ck_assert_double_eq_tol(prefiltered_irradiance(r.it.pf, n).g, want, 1e-9 + 1e-9 * want);
    }
    ck_assert_int_gt(below, 0); /* the polynomial did go below 0 */
    rig_free(&r);
    scene_free(&sc);
}
END_TEST

START_TEST(test_ggx_and_an_envmap_that_is_not_turned_are_refused)
{
    scene sc;
    rig r;
    error err = {0};
    load_ok(&sc, HEAD "integrator prefiltered\nbrdf ggx\nroughness 0.3\nsphere 0 0 0 1\n");
    set_env(&sc, GENENV_SKY, 32, 1);
    ck_assert_int_eq(rig_init(&r, &sc, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "'brdf ggx'"));
    scene_free(&sc);
    load_ok(&sc,
            HEAD "integrator prefiltered\npushTransform\nscale 1 1 3\nenvmap x.exr\npopTransform\n"
                 "diffuse 1 1 1\nsphere 0 0 0 1\n");
    set_env(&sc, GENENV_SKY, 32, 1);
    ck_assert_int_eq(rig_init(&r, &sc, &err), -1);
    ck_assert_int_eq(err.line, 6); /* the envmap line */
    ck_assert_ptr_nonnull(strstr(err.msg, "not a rotation"));
    scene_free(&sc);
    /* a rotation times a uniform scale is fine */
    load_ok(&sc, HEAD
            "integrator prefiltered\npushTransform\nscale 2 2 2\nrotate 0 0 1 30\nenvmap x.exr\n"
            "popTransform\ndiffuse 1 1 1\nsphere 0 0 0 1\n");
    set_env(&sc, GENENV_SKY, 32, 1);
    ck_assert_int_eq(rig_init(&r, &sc, &err), 0);
    rig_free(&r);
    scene_free(&sc);
}
END_TEST

START_TEST(test_without_the_envmaps_light_only_emission_and_mirrors_remain)
{
    const char *texts[] = {
        HEAD "integrator prefiltered\nenvmiss black\n"
             "diffuse 1 1 1\nemission 0.25 0 0\nsphere 0 0 0 1\n",
        HEAD "integrator prefiltered\ndiffuse 1 1 1\nemission 0.25 0 0\nsphere 0 0 0 1\n"};
    for (int i = 0; i < 2; i++) {
        scene sc;
        load_ok(&sc, texts[i]);
        if (i == 0) set_env(&sc, GENENV_CONSTANT, 32, 3);
        image im;
        render_ok(&sc, &im);
        rgb c = image_get(&im, 12, 12);
        ck_assert_double_eq_tol(c.r, 0.25, 1e-9);
        ck_assert_double_eq_tol(c.g, 0, 1e-12);
        if (i == 0) ck_assert_double_eq_tol(image_get(&im, 0, 0).g, 3, 1e-6); /* the background */
        image_free(&im);
        scene_free(&sc);
    }
}
END_TEST

START_TEST(test_one_phong_map_per_distinct_shininess)
{
    scene sc;
    load_ok(&sc,
            HEAD "integrator prefiltered\nspecular 0.5 0.5 0.5\nshininess 10\nsphere -1 0 0 0.4\n"
                 "diffuse 0.2 0.2 0.2\nsphere 0 0 0 0.4\nshininess 50\nsphere 1 0 0 0.4\n"
                 "specular 0 0 0\nshininess 7\nsphere 0 1 0 0.4\n");
    set_env(&sc, GENENV_SKY, 64, 1);
    rig r;
    error err = {0};
    ck_assert_int_eq(rig_init(&r, &sc, &err), 0);
    const prefiltered *pf = r.it.pf;
    ck_assert_int_eq(pf->n_phong, 2); /* 10 and 50: the last sphere has no specular part */
    ck_assert_int_eq(pf->phong[0].w, prefilter_phong_width(10));
    ck_assert_int_eq(pf->phong[1].w, prefilter_phong_width(50));
    ck_assert_int_eq(pf->phong_of[0], pf->phong_of[1]);
    ck_assert_int_eq(pf->phong_of[sc.n_materials - 1], -1);
    rig_free(&r);
    scene_free(&sc);
}
END_TEST

START_TEST(test_sh9_and_exact_agree_on_a_smooth_sky)
{
    image im[2];
    for (int m = 0; m < 2; m++) {
        scene sc;
        load_ok(&sc,
                m ? HEAD
                    "integrator prefiltered\nprefilter sh9\ndiffuse 0.8 0.8 0.8\nsphere 0 0 0 1\n"
                  : HEAD "integrator prefiltered\ndiffuse 0.8 0.8 0.8\nsphere 0 0 0 1\n");
        set_env(&sc, GENENV_SKY, 256, 1);
        render_ok(&sc, &im[m]);
        scene_free(&sc);
    }
    /* the sky is smooth: 9 coefficients hold its irradiance within 3% of the peak */
    double peak = 0, worst = 0;
    for (long i = 0; i < 3L * im[0].w * im[0].h; i++) {
        peak = fmax(peak, im[0].px[i]);
        worst = fmax(worst, fabs(im[0].px[i] - im[1].px[i]));
    }
    ck_assert_msg(worst <= 0.03 * peak, "sh9 differs from exact by %g of the peak", worst / peak);
    ck_assert(worst > 0); /* and they are two methods */
    image_free(&im[0]);
    image_free(&im[1]);
}
END_TEST

Suite *prefiltered_suite(void)
{
    Suite *s = suite_create("prefiltered");
    TCase *tc = tcase_create("core");
    unit_slow(tc); /* a slow case (unit.h) */
    tcase_add_test(tc, test_the_scene_chooses_the_integrator_and_the_irradiance_method);
    tcase_add_test(tc, test_lights_in_a_prefiltered_scene_are_warned_about_at_the_first);
    tcase_add_test(tc,
                   test_a_diffuse_or_phong_sphere_in_a_constant_environment_is_kd_plus_ks_times_L);
    tcase_add_test(tc, test_a_phong_lobe_is_ks_times_the_cosine_at_its_axis_times_its_map);
    tcase_add_test(tc, test_mirrors_and_glass_are_the_ray_tracers_to_the_bit);
    tcase_add_test(tc, test_the_maps_follow_the_envmaps_transform);
    tcase_add_test(tc, test_sh9_irradiance_is_never_negative_behind_a_point_source);
    tcase_add_test(tc, test_ggx_and_an_envmap_that_is_not_turned_are_refused);
    tcase_add_test(tc, test_without_the_envmaps_light_only_emission_and_mirrors_remain);
    tcase_add_test(tc, test_one_phong_map_per_distinct_shininess);
    tcase_add_test(tc, test_sh9_and_exact_agree_on_a_smooth_sky);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(prefiltered_suite)
