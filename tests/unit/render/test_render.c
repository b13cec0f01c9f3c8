/* test_render.c - the pixel loop: deterministic per seed, pixel centres at spp 1, jittered and
 * averaged samples above, every integrator runs, a bad spp refused, non-finite pixels counted. */
#include "envtex/render/render.h"

#include <string.h>

#include "envtex/geometry/bvh.h"
#include "envtex/geometry/camera.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/integrators/integrator.h"
#include "envtex/integrators/lights.h"
#include "envtex/core/rng.h"
#include "envtex/integrators/raytracer.h"
#include "envtex/scene/scene_load.h"
#include "unit.h"

static void load(scene *sc, const char *text)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    error err = {0};
    if (scene_load_string(text, "render.test", &o, sc, &err))
        ck_abort_msg("scene: line %d: %s", err.line, err.msg);
}

/* the scene's envmap: a 128 x 64 generated map (value: a constant map's radiance) */
static void set_env_value(scene *sc, genenv_kind kind, double value)
{
    genenv_params p = genenv_defaults();
    p.width = 128;
    p.value = value;
    error err = {0};
    image_free(&sc->envmap.img);
    ck_assert_int_eq(genenv_make(kind, &p, &sc->envmap.img, &err), 0);
    sc->envmap.present = 1;
    sc->envmap.scale = 1;
    sc->envmap.xf = sc->envmap.inv = mat4_identity();
}

static void set_env(scene *sc, genenv_kind kind)
{
    set_env_value(sc, kind, genenv_defaults().value);
}

/* A mirror ball and a diffuse ball under a light, in the axes environment: edges everywhere, so
 * jittered samples change pixels. */
static const char *balls = "size 24 16\n"
                           "camera 0 -5 1  0 0 0  0 0 1  45\n"
                           "directional 1 -1 2  0.8 0.8 0.8\n"
                           "ambient 0 0 0\n"
                           "brdf mirror\nspecular 0.9 0.9 0.9\nsphere -1 0 0 1\n"
                           "brdf phong\nspecular 0 0 0\ndiffuse 0.6 0.5 0.4\nsphere 1.2 0 0 0.8\n";

static int render(const scene *sc, int spp, uint64_t seed, image *out, render_stats *st)
{
    render_opts o = render_defaults();
    o.spp = spp;
    o.seed = seed;
    error err = {0};
    int rc = render_scene(sc, &o, out, st, &err);
    if (rc) ck_abort_msg("render: %s", err.msg);
    return rc;
}

START_TEST(test_render_same_seed_gives_bit_identical_images)
{
    scene sc;
    load(&sc, balls);
    set_env(&sc, GENENV_AXES);
    image a, b;
    render_stats sa, sb;
    render(&sc, 4, 1234, &a, &sa);
    render(&sc, 4, 1234, &b, &sb);
    ck_assert_int_eq(a.w, 24);
    ck_assert_int_eq(a.h, 16);
    ck_assert_mem_eq(a.px, b.px, sizeof(float) * 3 * 24 * 16);
    ck_assert_int_eq(sa.spp, 4);
    ck_assert_int_eq(sa.rays, sb.rays);
    ck_assert_int_gt(sa.rays, 24 * 16 * 4 - 1);
    ck_assert_int_eq(sa.nonfinite_pixels, 0);
    ck_assert_int_eq(sa.prims, 2);
    ck_assert_int_eq(sa.bvh_is_tree, 0);
    image_free(&a);
    image_free(&b);
    scene_free(&sc);
}
END_TEST

START_TEST(test_render_different_seeds_give_different_images)
{
    scene sc;
    load(&sc, balls);
    set_env(&sc, GENENV_AXES);
    image a, b;
    render_stats st;
    render(&sc, 4, 1, &a, &st);
    render(&sc, 4, 2, &b, &st);
    ck_assert(memcmp(a.px, b.px, sizeof(float) * 3 * 24 * 16) != 0);
    /* but they are the same picture: the mean differs little */
    double ma = 0, mb = 0;
    for (int i = 0; i < 24 * 16 * 3; i++) ma += a.px[i], mb += b.px[i];
    ck_assert_near(ma / (24 * 16 * 3), mb / (24 * 16 * 3), 0.02);
    image_free(&a);
    image_free(&b);
    scene_free(&sc);
}
END_TEST

START_TEST(test_render_spp_1_traces_through_pixel_centres)
{
    scene sc;
    load(&sc, balls);
    set_env(&sc, GENENV_AXES);
    image img, img2;
    render_stats st;
    render(&sc, 1, 99, &img, &st);
    render(&sc, 1, 7, &img2, &st); /* no randomness at all at spp 1 */
    ck_assert_mem_eq(img.px, img2.px, sizeof(float) * 3 * 24 * 16);
    bvh accel;
    error err = {0};
    ck_assert_int_eq(bvh_build(&accel, scene_prims(&sc), NULL, &err), 0);
    raytracer rt;
    raytracer_init(&rt, &sc, &accel);
    camera cam;
    camera_init(&cam, sc.eye, sc.center, sc.up, sc.fovy, sc.width, sc.height);
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 24; x++) {
            rgb want = raytracer_trace(&rt, camera_ray(&cam, x + 0.5, y + 0.5));
            rgb got = image_get(&img, x, y);
            ck_assert_msg(got.r == (float)want.r && got.g == (float)want.g &&
                              got.b == (float)want.b,
                          "pixel (%d, %d) is not the pixel-centre ray", x, y);
        }
    bvh_free(&accel);
    image_free(&img);
    image_free(&img2);
    scene_free(&sc);
}
END_TEST

START_TEST(test_render_spp_0_takes_the_scenes_spp)
{
    scene sc;
    char text[1024];
    snprintf(text, sizeof text, "%sspp 3\n", balls);
    load(&sc, text);
    image img;
    render_stats st;
    render(&sc, 0, 5, &img, &st);
    ck_assert_int_eq(st.spp, 3);
    image_free(&img);
    render(&sc, 2, 5, &img, &st); /* the option overrides the scene */
    ck_assert_int_eq(st.spp, 2);
    image_free(&img);
    scene_free(&sc);
}
END_TEST

START_TEST(test_render_of_a_constant_environment_is_that_constant)
{
    /* an empty scene in a constant environment: every sample sees L, so every pixel is L
     * whatever the jitter (tests the box filter's 1 / spp) */
    scene sc;
    load(&sc, "size 8 6\ncamera 0 0 0  1 0 0  0 0 1  60\n");
    genenv_params p = genenv_defaults();
    p.width = 16;
    p.value = 0.625;
    error err = {0};
    ck_assert_int_eq(genenv_make(GENENV_CONSTANT, &p, &sc.envmap.img, &err), 0);
    sc.envmap.present = 1;
    sc.envmap.scale = 2;
    sc.envmap.xf = sc.envmap.inv = mat4_identity();
    image img;
    render_stats st;
    render(&sc, 5, 3, &img, &st);
    for (int i = 0; i < 8 * 6 * 3; i++)
        ck_assert_msg(img.px[i] == 1.25f, "px[%d] = %g", i, img.px[i]);
    ck_assert_int_eq(st.prims, 0);
    image_free(&img);
    scene_free(&sc);
}
END_TEST

START_TEST(test_render_runs_every_integrator_and_a_black_map_stays_finite)
{
    /* every integrator renders the balls (no envmap, no lights: black but finite pixels) */
    const char *names[] = {"raytracer", "analyticdirect", "direct", "pathtracer"};
    for (int i = 0; i < 4; i++) {
        scene sc;
        char text[1024];
        snprintf(text, sizeof text, "%sintegrator %s\nnexteventestimation mis\n", balls, names[i]);
        load(&sc, text);
        image img;
        render_stats st;
        error err = {0};
        ck_assert_msg(render_scene(&sc, NULL, &img, &st, &err) == 0, "%s: %s", names[i], err.msg);
        ck_assert_int_eq(st.nonfinite_pixels, 0);
        ck_assert_int_eq(img.w, sc.width);
        image_free(&img);
        scene_free(&sc);
    }
}
END_TEST

static int warnings_seen;
static error last_warning;
static void keep_warning(void *ctx, const error *w)
{
    ck_assert_ptr_eq(ctx, &warnings_seen);
    warnings_seen++;
    last_warning = *w;
}

/* The issue: "an all-zero map falls back to uniform with a warning".  The warning comes once,
 * through render_opts.warn, at the `envmap` line, whenever the scene samples the map by its
 * values; not when it asked for uniform directions, nor when nothing samples the map, nor for a
 * map that is not black. */
START_TEST(test_render_warns_once_when_a_black_envmap_falls_back)
{
    static const struct {
        const char *lines;
        double value;
        int warns;
        const char *words;
    } cases[] = {
        {"integrator direct\n", 0, 1,
         "'envsampling cdf' has nothing to importance sample and samples uniform"},
        {"integrator direct\nenvsampling cdf-sintheta\n", 0, 1,
         "'envsampling cdf-sintheta' has nothing"},
        {"integrator direct\nenvsampling mediancut 4\n", 0, 1,
         "'envsampling mediancut' has no energy to divide"},
        {"integrator pathtracer\nnexteventestimation mis\n", 0, 1, "envmap black.exr is black"},
        {"integrator direct\nenvsampling uniform\n", 0, 0, NULL}, /* asked for uniform */
        {"integrator pathtracer\n", 0, 0, NULL},                  /* NEE off: looked up only */
        {"integrator raytracer\n", 0, 0, NULL},
        {"integrator direct\n", 0.5, 0, NULL}, /* not black */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        scene sc;
        char text[512];
        snprintf(text, sizeof text,
                 "size 4 4\ncamera 0 0 4  0 0 0  0 1 0  45\nenvmap black.exr\n%s"
                 "diffuse 0.5 0.5 0.5\nsphere 0 0 0 1\n",
                 cases[i].lines);
        load(&sc, text);
        set_env_value(&sc, GENENV_CONSTANT, cases[i].value);
        render_opts o = render_defaults();
        error err = {0};
        o.warn = keep_warning;
        o.warn_ctx = &warnings_seen;
        warnings_seen = 0;
        image img;
        render_stats st;
        ck_assert_msg(render_scene(&sc, &o, &img, &st, &err) == 0, "case %zu: %s", i, err.msg);
        ck_assert_msg(warnings_seen == cases[i].warns, "case %zu: %d warnings, want %d", i,
                      warnings_seen, cases[i].warns);
        if (cases[i].warns) {
            ck_assert_str_eq(last_warning.file, "render.test");
            ck_assert_int_eq(last_warning.line, 3); /* the envmap line */
            ck_assert_msg(strstr(last_warning.msg, cases[i].words), "case %zu: %s", i,
                          last_warning.msg);
        }
        image_free(&img);
        scene_free(&sc);
    }
}
END_TEST

START_TEST(test_render_refuses_an_out_of_range_spp_naming_the_scene)
{
    scene sc;
    load(&sc, balls);
    render_opts o = render_defaults();
    o.spp = SCENE_MAX_SPP + 1;
    image img;
    memset(&img, 0x55, sizeof img);
    render_stats st;
    error err = {0};
    ck_assert_int_eq(render_scene(&sc, &o, &img, &st, &err), -1);
    ck_assert_str_eq(err.file, "render.test");
    ck_assert_ptr_nonnull(strstr(err.msg, "spp"));
    ck_assert_ptr_null(img.px); /* nothing to free */
    ck_assert_int_eq(img.w, 0);
    scene_free(&sc);
}
END_TEST

/* The pixel loop against its own definition, replayed sample by sample: pixel (x, y) seeds its
 * generator with stream y W + x; each of the spp samples draws its jitter (jx, jy) and traces
 * the camera ray through (x + jx, y + jy) with differentials scaled by max(1 / sqrt(spp), 1/8);
 * the pixel is the mean and the variance image the variance of that mean,
 * sum (v - mean)^2 / ((spp - 1) spp).  A receding checker filtered by its footprint (emission
 * map, raytracer) makes both the differentials' scale and the jitter change the values: spp 16
 * (scale 1/4) and spp 256 (the floor 1/8, where 1/16 would be less). */
START_TEST(test_render_replays_as_documented_mean_variance_and_differential_scale)
{
    scene sc;
    load(&sc, "size 6 5\ncamera 0 1 3  0 0 -4  0 1 0  50\nambient 0 0 0\ndiffuse 0 0 0\n"
              "texture c checker 2  0 0 0  1 0.5 0.25\nemissionmap c\ntexfilter trilinear\n"
              "vertextex -8 0 4  0 0\nvertextex 8 0 4  8 0\nvertextex 8 0 -40  8 22\nvertextex -8 "
              "0 -40  0 22\n"
              "tritex 0 1 2\ntritex 0 2 3\n");
    const int spps[2] = {16, 256};
    for (int k = 0; k < 2; k++) {
        int spp = spps[k];
        image img, var;
        render_opts o = render_defaults();
        o.spp = spp;
        o.seed = 5;
        o.variance = &var;
        render_stats st;
        error err = {0};
        ck_assert_msg(render_scene(&sc, &o, &img, &st, &err) == 0, "%s", err.msg);
        bvh accel;
        integrator it;
        ck_assert_int_eq(bvh_build(&accel, scene_prims(&sc), NULL, &err), 0);
        ck_assert_int_eq(integrator_init(&it, &sc, &accel, NULL, &err), 0);
        camera cam;
        camera_init(&cam, sc.eye, sc.center, sc.up, sc.fovy, sc.width, sc.height);
        double scale = fmax(1 / sqrt((double)spp), 0.125);
        double spread = 0;
        for (int y = 0; y < sc.height; y++)
            for (int x = 0; x < sc.width; x++) {
                rng g;
                rng_seed(&g, 5, (uint64_t)y * (uint64_t)sc.width + (uint64_t)x);
                double v[256], mean = 0;
                for (int s = 0; s < spp; s++) {
                    double jx = rng_uniform(&g), jy = rng_uniform(&g);
                    ray_diff rd;
                    ray r = camera_ray_differential(&cam, x + jx, y + jy, scale, &rd);
                    v[s] = render_radiance_diff(&it, r, &rd, &g).g;
                    mean += v[s];
                }
                mean /= spp;
                double ss = 0;
                for (int s = 0; s < spp; s++) ss += (v[s] - mean) * (v[s] - mean);
                double want_var = ss / ((double)(spp - 1) * spp);
                double got = image_get(&img, x, y).g, got_var = image_get(&var, x, y).g;
                ck_assert_msg(fabs(got - mean) <= 1e-6 * fmax(mean, 1e-3),
                              "spp %d, pixel (%d, %d): %.9g, replayed %.9g", spp, x, y, got, mean);
                ck_assert_msg(fabs(got_var - want_var) <= 1e-5 * want_var + 1e-12,
                              "spp %d, pixel (%d, %d): variance %.9g, replayed %.9g", spp, x, y,
                              got_var, want_var);
                spread = fmax(spread, want_var);
            }
        ck_assert_msg(spread > 1e-4, "spp %d: no pixel varies: the test sees no jitter", spp);
        integrator_free(&it);
        bvh_free(&accel);
        image_free(&img);
        image_free(&var);
    }
    scene_free(&sc);
}
END_TEST

/* A size and an spp each in range whose product of camera samples is over 2^34 is refused
 * before anything is allocated or traced. */
/* The tiles' packets change no pixel: a scene with a BVH tree (more than BVH_MIN_PRIMS spheres
 * and triangles), 19 x 11 pixels (the tiles of the last column and row cut short), spp 3,
 * replayed pixel by pixel through render_radiance with each pixel's own stream and Welford's
 * update, must give the same floats, bit for bit, in the image and the variance: for the path
 * tracer (next-event estimation, a quad light in the BVH) and the ray tracer (a mirror). */
START_TEST(test_render_by_tiles_is_the_pixel_by_pixel_replay_bit_for_bit)
{
    const char *heads[2] = {"integrator pathtracer\nnexteventestimation on\nspp 3\n"
                            "quadLight -1 -1 4  2 0 0  0 2 0  5 5 5\n",
                            "integrator raytracer\nspp 3\npoint 0 -2 4  6 6 6\n"};
    for (int k = 0; k < 2; k++) {
        char text[16384];
        int len = snprintf(
            text, sizeof text,
            "size 19 11\ncamera -4 -7 4  1 1 -0.5  0 0 1  30\n%sdiffuse 0.5 0.5 0.5\n", heads[k]);
        for (int i = 0; i < 48; i++) /* spheres in rows, every third a mirror */
            len += snprintf(text + len, sizeof text - (size_t)len, "%ssphere %g %g %g 0.3\n",
                            i % 3 ? "brdf phong\n" : "brdf mirror\nspecular 0.8 0.8 0.8\n",
                            -2.8 + 0.75 * (i % 8), -1.5 + 0.6 * (i / 8), 0.4 * (i % 3));
        len += snprintf(text + len, sizeof text - (size_t)len,
                        "brdf phong\nvertex -5 -5 -1\nvertex 5 -5 -1\nvertex 5 5 -1\n"
                        "vertex -5 5 -1\ntri 0 1 2\ntri 0 2 3\n");
        scene sc;
        load(&sc, text);
        image img, var;
        render_opts o = render_defaults();
        o.seed = 7;
        o.variance = &var;
        render_stats st;
        error err = {0};
        ck_assert_msg(render_scene(&sc, &o, &img, &st, &err) == 0, "%s", err.msg);
        ck_assert_int_eq(st.bvh_is_tree, 1);
        bvh accel;
        integrator it;
        ck_assert_int_eq(lights_scene_bvh(&accel, &sc, NULL, &err), 0);
        ck_assert_int_eq(integrator_init(&it, &sc, &accel, NULL, &err), 0);
        camera cam;
        camera_init(&cam, sc.eye, sc.center, sc.up, sc.fovy, sc.width, sc.height);
        int differ = 0;
        double spread = 0;
        for (int y = 0; y < sc.height; y++)
            for (int x = 0; x < sc.width; x++) {
                rng g;
                rng_seed(&g, 7, (uint64_t)y * (uint64_t)sc.width + (uint64_t)x);
                rgb mean = rgb_gray(0), m2 = rgb_gray(0);
                for (int s = 0; s < 3; s++) {
                    double jx = rng_uniform(&g), jy = rng_uniform(&g);
                    rgb v = render_radiance(&it, camera_ray(&cam, x + jx, y + jy), &g);
                    rgb d = rgb_make(v.r - mean.r, v.g - mean.g, v.b - mean.b);
                    mean = rgb_madd(mean, d, 1.0 / (s + 1));
                    m2 = rgb_add(m2, rgb_make(d.r * (v.r - mean.r), d.g * (v.g - mean.g),
                                              d.b * (v.b - mean.b)));
                }
                image replay = {0};
                ck_assert_int_eq(image_alloc(&replay, 2, 1, &err), 0);
                image_set(&replay, 0, 0, mean);
                image_set(&replay, 1, 0, rgb_scale(m2, 1.0 / 6));
                differ +=
                    memcmp(image_px(&replay, 0, 0), image_px(&img, x, y), 3 * sizeof(float)) ||
                    memcmp(image_px(&replay, 1, 0), image_px(&var, x, y), 3 * sizeof(float));
                spread = fmax(spread, m2.g);
                image_free(&replay);
            }
        ck_assert_msg(differ == 0, "%s: %d of %d pixels differ from the replay", heads[k], differ,
                      sc.width * sc.height);
        ck_assert_msg(spread > 0, "%s: no pixel varies: the test sees no jitter", heads[k]);
        integrator_free(&it);
        bvh_free(&accel);
        image_free(&img);
        image_free(&var);
        scene_free(&sc);
    }
}
END_TEST

START_TEST(test_render_refuses_too_many_camera_samples)
{
    scene sc;
    load(&sc, "size 8192 4096\ncamera 0 0 5  0 0 0  0 1 0  45\nsphere 0 0 0 1\n");
    render_opts o = render_defaults();
    o.spp = 1024; /* 2^13 x 2^12 x 2^10 = 2^35 */
    image img;
    render_stats st;
    error err = {0};
    ck_assert_int_eq(render_scene(&sc, &o, &img, &st, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "camera samples"));
    ck_assert_ptr_null(img.px);
    scene_free(&sc);
}
END_TEST

START_TEST(test_render_counts_nonfinite_pixels)
{
    /* an envmap with a NaN texel: the pixels whose lookups touch it are NaN, and counted */
    scene sc;
    load(&sc, "size 9 9\ncamera 0 0 0  1 0 0  0 0 1  30\n"); /* looking at +x: u = 0 */
    set_env(&sc, GENENV_CONSTANT);
    image *m = &sc.envmap.img;
    image_set(m, 0, m->h / 2, rgb_make(NAN, 0, 0)); /* just right of phi = 0, below the horizon */
    image img;
    render_stats st;
    render(&sc, 1, 0, &img, &st);
    long nan_pixels = 0;
    for (int y = 0; y < 9; y++)
        for (int x = 0; x < 9; x++) nan_pixels += !rgb_is_finite(image_get(&img, x, y));
    ck_assert_int_gt(nan_pixels, 0);
    ck_assert_int_lt(nan_pixels, 81);
    ck_assert_int_eq(st.nonfinite_pixels, nan_pixels);
    image_free(&img);
    /* and an all-NaN environment makes every pixel count */
    for (int i = 0; i < m->w * m->h * 3; i++) m->px[i] = NAN;
    render(&sc, 2, 0, &img, &st);
    ck_assert_int_eq(st.nonfinite_pixels, 81);
    image_free(&img);
    scene_free(&sc);
}
END_TEST

static int rows_seen;
static void count_rows(void *ctx, int done, int rows)
{
    ck_assert_int_eq(done, ++rows_seen);
    ck_assert_int_eq(rows, 16);
    ck_assert_ptr_eq(ctx, &rows_seen);
}

START_TEST(test_render_reports_progress_after_every_row)
{
    scene sc;
    load(&sc, balls);
    render_opts o = render_defaults();
    o.progress = count_rows;
    o.progress_ctx = &rows_seen;
    rows_seen = 0;
    image img;
    render_stats st;
    error err = {0};
    ck_assert_int_eq(render_scene(&sc, &o, &img, &st, &err), 0);
    ck_assert_int_eq(rows_seen, 16);
    image_free(&img);
    scene_free(&sc);
}
END_TEST

Suite *render_suite(void)
{
    Suite *s = suite_create("render");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_render_same_seed_gives_bit_identical_images);
    tcase_add_test(tc, test_render_different_seeds_give_different_images);
    tcase_add_test(tc, test_render_spp_1_traces_through_pixel_centres);
    tcase_add_test(tc, test_render_spp_0_takes_the_scenes_spp);
    tcase_add_test(tc, test_render_of_a_constant_environment_is_that_constant);
    tcase_add_test(tc, test_render_runs_every_integrator_and_a_black_map_stays_finite);
    tcase_add_test(tc, test_render_warns_once_when_a_black_envmap_falls_back);
    tcase_add_test(tc, test_render_refuses_an_out_of_range_spp_naming_the_scene);
    tcase_add_test(tc, test_render_counts_nonfinite_pixels);
    tcase_add_test(tc, test_render_replays_as_documented_mean_variance_and_differential_scale);
    tcase_add_test(tc, test_render_by_tiles_is_the_pixel_by_pixel_replay_bit_for_bit);
    tcase_add_test(tc, test_render_refuses_too_many_camera_samples);
    tcase_add_test(tc, test_render_reports_progress_after_every_row);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(render_suite)
