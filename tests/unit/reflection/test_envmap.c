/* test_envmap.c - the environment rays see when they leave the scene: the scene's `envmap`
 * transform (envmap frame -> world) and scale are applied, and no envmap means black. */
#include "envtex/reflection/envmap.h"
#include "envtex/scene/scene.h"

#include <string.h>

#include "envtex/envmaps/genenv.h"
#include "envtex/envmaps/latlong.h"
#include "unit.h"

/* A scene with only an envmap: `kind` made by genenv at 64 x 32, frame -> world `xf`. */
static void env_scene(scene *sc, genenv_kind kind, mat4 xf, double scale)
{
    memset(sc, 0, sizeof *sc);
    genenv_params p = genenv_defaults();
    p.width = 64;
    error err = {0};
    ck_assert_int_eq(genenv_make(kind, &p, &sc->envmap.img, &err), 0);
    sc->envmap.present = 1;
    sc->envmap.scale = scale;
    sc->envmap.xf = xf;
    ck_assert_int_eq(mat4_inverse(xf, &sc->envmap.inv), 0);
}

START_TEST(test_envmap_absent_is_black)
{
    scene sc;
    memset(&sc, 0, sizeof sc);
    envmap env;
    scene_environment(&sc, &env);
    ck_assert_int_eq(env.present, 0);
    ck_assert(rgb_is_black(envmap_radiance(&env, vec3_make(0, 0, 1))));
    ck_assert(rgb_is_black(envmap_radiance(&env, vec3_make(1, -2, 0.5))));
    /* "present" without pixels (a parser test's scene, load_images = 0) is black too */
    sc.envmap.present = 1;
    sc.envmap.scale = 1;
    sc.envmap.xf = sc.envmap.inv = mat4_identity();
    scene_environment(&sc, &env);
    ck_assert_int_eq(env.present, 0);
    ck_assert(rgb_is_black(envmap_radiance(&env, vec3_make(0, 0, 1))));
}
END_TEST

START_TEST(test_envmap_identity_transform_is_the_latlong_lookup)
{
    scene sc;
    env_scene(&sc, GENENV_SKY, mat4_identity(), 1);
    envmap env;
    scene_environment(&sc, &env);
    ck_assert_int_eq(env.present, 1);
    const vec3 dirs[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0.3, -0.8, 0.2}, {-1, -1, -1}};
    for (unsigned i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        rgb a = envmap_radiance(&env, dirs[i]),
            b = latlong_lookup_bilinear(&sc.envmap.img, dirs[i]);
        ck_rgb_near(a, b, 0);
        /* length does not matter */
        ck_rgb_near(envmap_radiance(&env, vec3_scale(dirs[i], 7.5)), a, 1e-12);
    }
    ck_assert(rgb_is_black(envmap_radiance(&env, vec3_make(0, 0, 0))));
    ck_assert(rgb_is_black(envmap_radiance(&env, vec3_make(NAN, 0, 1))));
    image_free(&sc.envmap.img);
}
END_TEST

START_TEST(test_envmap_scale_multiplies_the_radiance)
{
    scene a, b;
    env_scene(&a, GENENV_AXES, mat4_identity(), 1);
    env_scene(&b, GENENV_AXES, mat4_identity(), 2.5);
    envmap ea, eb;
    scene_environment(&a, &ea);
    scene_environment(&b, &eb);
    vec3 d = vec3_make(0.2, 0.5, -0.7);
    ck_rgb_near(envmap_radiance(&eb, d), rgb_scale(envmap_radiance(&ea, d), 2.5), 1e-15);
    image_free(&a.envmap.img);
    image_free(&b.envmap.img);
}
END_TEST

/* The scale applies to every representation, not only lat-long's fast path: the same image read
 * as an equal-area, cylindrical or angular map with scale 2.5. */
START_TEST(test_envmap_scale_multiplies_every_representation)
{
    const convert_kind kinds[] = {CONVERT_EQUALAREA, CONVERT_CYLINDRICAL, CONVERT_ANGULAR,
                                  CONVERT_MIRRORBALL};
    for (int k = 0; k < 4; k++) {
        scene a, b;
        env_scene(&a, GENENV_SKY, mat4_identity(), 1);
        env_scene(&b, GENENV_SKY, mat4_identity(), 2.5);
        a.envmap.kind = b.envmap.kind = kinds[k];
        a.envmap.max_height = b.envmap.max_height = 1;
        envmap ea, eb;
        scene_environment(&a, &ea);
        scene_environment(&b, &eb);
        vec3 d = vec3_normalize(vec3_make(0.2, 0.5, 0.3));
        rgb la = envmap_radiance(&ea, d);
        ck_assert_msg(la.g > 0, "kind %d: black", (int)kinds[k]);
        ck_rgb_near(envmap_radiance(&eb, d), rgb_scale(la, 2.5), 1e-12);
        image_free(&a.envmap.img);
        image_free(&b.envmap.img);
    }
}
END_TEST

START_TEST(test_envmap_rotate_x_minus_90_puts_the_zenith_at_world_plus_y)
{
    /* `rotate 1 0 0 -90` before `envmap` (FORMAT.md): a y-up world gets the sky overhead */
    scene sc;
    env_scene(&sc, GENENV_AXES, mat4_rotate(vec3_make(1, 0, 0), -90), 1);
    envmap env;
    scene_environment(&sc, &env);
    /* axes map: colour = (d_env + 1) / 2, so the colour names the envmap-frame direction */
    rgb up = envmap_radiance(&env, vec3_make(0, 1, 0));
    /* (the nearest row centre is half a texel, pi / 64, from the pole: colours within 0.03) */
    ck_assert_msg(up.b > 0.99 && fabs(up.r - 0.5) < 0.03 && fabs(up.g - 0.5) < 0.03,
                  "world +y sees (%g, %g, %g), not the zenith", up.r, up.g, up.b);
    rgb down = envmap_radiance(&env, vec3_make(0, -1, 0));
    ck_assert(down.b < 0.05);
    /* world +z is the envmap's -y (R_x(-90) maps -y to +z): (0.5, 0, 0.5) on the horizon */
    ck_rgb_near(envmap_radiance(&env, vec3_make(0, 0, 1)), rgb_make(0.5, 0, 0.5), 0.01);
    /* world +x stays +x */
    ck_rgb_near(envmap_radiance(&env, vec3_make(1, 0, 0)), rgb_make(1, 0.5, 0.5), 0.01);
    /* the zenith row itself, by value: a map whose top row is 7 and the rest 1 */
    for (int y = 0; y < sc.envmap.img.h; y++)
        for (int x = 0; x < sc.envmap.img.w; x++)
            image_set(&sc.envmap.img, x, y, rgb_gray(y == 0 ? 7 : 1));
    ck_assert(envmap_radiance(&env, vec3_make(0, 1, 0)).r == 7);
    ck_assert(envmap_radiance(&env, vec3_make(0, 0, 1)).r == 1);
    image_free(&sc.envmap.img);
}
END_TEST

START_TEST(test_envmap_rotation_about_z_turns_the_map)
{
    /* rotate 0 0 1 90: the envmap's +x is the world's +y */
    scene sc;
    env_scene(&sc, GENENV_AXES, mat4_rotate(vec3_make(0, 0, 1), 90), 3);
    envmap env;
    scene_environment(&sc, &env);
    ck_rgb_near(envmap_radiance(&env, vec3_make(0, 1, 0)), rgb_scale(rgb_make(1, 0.5, 0.5), 3),
                    0.03);
    ck_rgb_near(envmap_radiance(&env, vec3_make(-1, 0, 0)), rgb_scale(rgb_make(0.5, 1, 0.5), 3),
                    0.03);
    image_free(&sc.envmap.img);
}
END_TEST

Suite *envmap_suite(void)
{
    Suite *s = suite_create("envmap");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_envmap_absent_is_black);
    tcase_add_test(tc, test_envmap_identity_transform_is_the_latlong_lookup);
    tcase_add_test(tc, test_envmap_scale_multiplies_the_radiance);
    tcase_add_test(tc, test_envmap_scale_multiplies_every_representation);
    tcase_add_test(tc, test_envmap_rotate_x_minus_90_puts_the_zenith_at_world_plus_y);
    tcase_add_test(tc, test_envmap_rotation_about_z_turns_the_map);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(envmap_suite)
