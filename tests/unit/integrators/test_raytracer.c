/* test_raytracer.c - the Whitted integrator with reflection maps (raytracer.h): orientation of
 * a mirror ball against the `axes` environment, envmiss black, maxdepth, Blinn-Phong lighting
 * with attenuation worked out by hand, shadows, and a glass ball that conserves energy. */
#include "envtex/integrators/raytracer.h"

#include <string.h>

#include "envtex/geometry/camera.h"
#include "envtex/envmaps/genenv.h"
#include "envtex/geometry/sphere.h"
#include "envtex/scene/scene_load.h"
#include "unit.h"

/* Parse `text` (no images are read). */
static void load(scene *sc, const char *text)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    error err = {0};
    if (scene_load_string(text, "test", &o, sc, &err))
        ck_abort_msg("scene: line %d: %s", err.line, err.msg);
}

/* Give the scene an environment made by genenv (envmap frame = world frame, scale 1). */
static void set_env(scene *sc, genenv_kind kind, double value)
{
    genenv_params p = genenv_defaults();
    p.width = 256;
    p.value = value;
    error err = {0};
    image_free(&sc->envmap.img);
    ck_assert_int_eq(genenv_make(kind, &p, &sc->envmap.img, &err), 0);
    sc->envmap.present = 1;
    sc->envmap.scale = 1;
    sc->envmap.xf = sc->envmap.inv = mat4_identity();
}

/* Everything needed to trace camera rays through one scene. */
typedef struct fixture {
    scene sc;
    bvh accel;
    raytracer rt;
    camera cam;
} fixture;

static void fixture_start(fixture *f)
{
    error err = {0};
    ck_assert_int_eq(bvh_build(&f->accel, scene_prims(&f->sc), NULL, &err), 0);
    raytracer_init(&f->rt, &f->sc, &f->accel);
    camera_init(&f->cam, f->sc.eye, f->sc.center, f->sc.up, f->sc.fovy, f->sc.width, f->sc.height);
}

static void fixture_end(fixture *f)
{
    bvh_free(&f->accel);
    scene_free(&f->sc);
}

/* Radiance through the centre of pixel (x, y). */
static rgb pixel(fixture *f, int x, int y)
{
    return raytracer_trace(&f->rt, camera_ray(&f->cam, x + 0.5, y + 0.5));
}

/* The orientation scene: world z up, camera on -y looking at a mirror ball at the origin. */
static const char *mirror_ball = "size 65 65\n"
                                 "camera 0 -5 0  0 0 0  0 0 1  40\n"
                                 "ambient 0 0 0\n"
                                 "brdf mirror\n"
                                 "specular 1 1 1\n"
                                 "sphere 0 0 0 1\n";

START_TEST(test_raytracer_mirror_ball_reflects_the_axes_environment_the_right_way_round)
{
    fixture f;
    load(&f.sc, mirror_ball);
    set_env(&f.sc, GENENV_AXES, 1);
    fixture_start(&f);
    /* the centre pixel reflects straight back to the camera, towards -y: (0.5, 0, 0.5) */
    ck_rgb_near(pixel(&f, 32, 32), rgb_make(0.5, 0, 0.5), 0.01);
    /* right of centre the ball reflects towards +x (red), above centre towards +z (blue) */
    rgb right = pixel(&f, 44, 32), left = pixel(&f, 20, 32), up = pixel(&f, 32, 20),
        down = pixel(&f, 32, 44);
    ck_assert_msg(right.r > 0.7 && left.r < 0.3, "phi runs the wrong way: right %g, left %g",
                  right.r, left.r);
    ck_assert_msg(up.b > 0.7 && down.b < 0.3, "the map is upside down: up %g, down %g", up.b,
                  down.b);
    ck_assert_near(right.b, 0.5, 0.01);
    ck_assert_near(up.r, 0.5, 0.01);
    /* background along the view (+y) is green; the left edge looks a little towards -x */
    rgb bg = pixel(&f, 0, 32);
    ck_assert(bg.g > 0.95 && bg.r < 0.5);
    fixture_end(&f);
}
END_TEST

START_TEST(test_raytracer_every_mirror_ball_pixel_shows_the_reflected_direction)
{
    /* the whole picture against the analytic answer: colour = (r + 1) / 2 with r the mirror
     * direction at the hit point of a unit ball (bilinear error on a 256 x 128 map < 0.005) */
    fixture f;
    load(&f.sc, mirror_ball);
    set_env(&f.sc, GENENV_AXES, 1);
    fixture_start(&f);
    int on_ball = 0;
    for (int y = 0; y < 65; y++)
        for (int x = 0; x < 65; x++) {
            ray r = camera_ray(&f.cam, x + 0.5, y + 0.5);
            double t;
            vec3 dir = r.d;
            if (sphere_intersect(&f.sc.spheres[0], &r, &t)) {
                vec3 n = vec3_madd(r.o, r.d, t); /* unit ball at the origin: n = p */
                dir = vec3_reflect(r.d, n);
                on_ball++;
            }
            rgb want = rgb_make((dir.x + 1) / 2, (dir.y + 1) / 2, (dir.z + 1) / 2);
            rgb got = pixel(&f, x, y);
            if (!(fabs(got.r - want.r) < 0.005 && fabs(got.g - want.g) < 0.005 &&
                  fabs(got.b - want.b) < 0.005))
                ck_abort_msg("pixel (%d, %d): (%g, %g, %g), want (%g, %g, %g)", x, y, got.r, got.g,
                             got.b, want.r, want.g, want.b);
        }
    ck_assert_int_gt(on_ball, 500);
    fixture_end(&f);
}
END_TEST

START_TEST(test_raytracer_envmiss_black_darkens_reflections_but_not_the_background)
{
    fixture a, b;
    load(&a.sc, mirror_ball);
    char text[1024];
    snprintf(text, sizeof text, "%senvmiss black\n", mirror_ball);
    load(&b.sc, text);
    set_env(&a.sc, GENENV_AXES, 1);
    set_env(&b.sc, GENENV_AXES, 1);
    fixture_start(&a);
    fixture_start(&b);
    ck_assert(rgb_is_black(pixel(&b, 32, 32)));
    ck_assert(rgb_is_black(pixel(&b, 44, 32)));
    ck_assert(!rgb_is_black(pixel(&a, 32, 32)));
    ck_rgb_near(pixel(&b, 0, 0), pixel(&a, 0, 0), 0); /* camera rays still see the envmap */
    fixture_end(&a);
    fixture_end(&b);
}
END_TEST

START_TEST(test_raytracer_maxdepth_0_shows_no_reflection)
{
    fixture f;
    char text[1024];
    snprintf(text, sizeof text, "%smaxdepth 0\n", mirror_ball);
    load(&f.sc, text);
    set_env(&f.sc, GENENV_AXES, 1);
    fixture_start(&f);
    ck_assert(rgb_is_black(pixel(&f, 32, 32))); /* ambient 0, emission 0, no reflection */
    ck_assert(!rgb_is_black(pixel(&f, 0, 0)));  /* the background is not a reflection */
    fixture_end(&f);
}
END_TEST

/* Two parallel mirrors facing each other, 2 apart, the camera between them looking at one at
 * normal incidence: the centre ray bounces forever, collecting the emission E once per surface,
 * weighted by ks^k, until maxdepth: I = E (1 + ks + ... + ks^maxdepth). */
static const char *facing_mirrors =
    "size 33 33\n"
    "camera 0 0 0  0 0 -1  0 1 0  90\n"
    "ambient 0 0 0\n"
    "brdf mirror\n"
    "specular 0.5 0.5 0.5\n"
    "emission 0.1 0.2 0.4\n"
    "vertex -2 -2 -1\nvertex 2 -2 -1\nvertex 2 2 -1\nvertex -2 2 -1\n"
    "vertex -2 -2 1\nvertex 2 -2 1\nvertex 2 2 1\nvertex -2 2 1\n"
    "tri 0 1 2\ntri 0 2 3\ntri 4 6 5\ntri 4 7 6\n";

START_TEST(test_raytracer_facing_mirrors_sum_emission_over_exactly_maxdepth_bounces)
{
    const int depths[] = {0, 1, 5, 12};
    for (unsigned i = 0; i < sizeof depths / sizeof depths[0]; i++) {
        fixture f;
        char text[2048];
        snprintf(text, sizeof text, "%smaxdepth %d\n", facing_mirrors, depths[i]);
        load(&f.sc, text);
        set_env(&f.sc, GENENV_CONSTANT, 1);
        fixture_start(&f);
        double sum = (1 - pow(0.5, depths[i] + 1)) / (1 - 0.5); /* 1 + ks + ... + ks^maxdepth */
        ck_rgb_near(pixel(&f, 16, 16), rgb_make(0.1 * sum, 0.2 * sum, 0.4 * sum), 1e-12);
        fixture_end(&f);
    }
}
END_TEST

START_TEST(test_raytracer_unlimited_depth_stops_where_the_branch_weight_is_negligible)
{
    /* maxdepth -1: the facing mirrors' series runs until ks^k <= RAYTRACER_MIN_WEIGHT (or
     * RAYTRACER_UNLIMITED_DEPTH), so the centre pixel is E (1 + ks + ... + ks^K) */
    fixture f;
    char text[2048];
    snprintf(text, sizeof text, "%smaxdepth -1\n", facing_mirrors);
    load(&f.sc, text);
    fixture_start(&f);
    ck_assert_int_eq(f.rt.maxdepth, RAYTRACER_UNLIMITED_DEPTH);
    int K = 0;
    while (K < RAYTRACER_UNLIMITED_DEPTH && pow(0.5, K + 1) > RAYTRACER_MIN_WEIGHT) K++;
    double sum = (1 - pow(0.5, K + 1)) / (1 - 0.5);
    ck_rgb_near(pixel(&f, 16, 16), rgb_make(0.1 * sum, 0.2 * sum, 0.4 * sum), 1e-12);
    ck_assert_near(sum, 2, 1e-8); /* and that is the infinite series' value, 2, to 1e-8 */
    fixture_end(&f);
}
END_TEST

START_TEST(test_raytracer_envmiss_black_removes_the_escaping_light_between_mirrors)
{
    fixture a, b;
    char text[2048];
    snprintf(text, sizeof text, "%smaxdepth 20\n", facing_mirrors);
    load(&a.sc, text);
    snprintf(text, sizeof text, "%smaxdepth 20\nenvmiss black\n", facing_mirrors);
    load(&b.sc, text);
    set_env(&a.sc, GENENV_CONSTANT, 1);
    set_env(&b.sc, GENENV_CONSTANT, 1);
    fixture_start(&a);
    fixture_start(&b);
    int differ = 0;
    for (int y = 0; y < 33; y++)
        for (int x = 0; x < 33; x++) {
            rgb ca = pixel(&a, x, y), cb = pixel(&b, x, y);
            if (cb.r > ca.r + 1e-15)
                ck_abort_msg("black misses made pixel (%d, %d) brighter", x, y);
            /* an oblique ray escapes after k bounces: the envmap adds ks^k * 1 */
            if (ca.r > cb.r + 1e-6) differ++;
        }
    ck_assert_int_gt(differ, 100);
    /* the centre ray never escapes: both give the emission series */
    ck_rgb_near(pixel(&a, 16, 16), pixel(&b, 16, 16), 1e-15);
    fixture_end(&a);
    fixture_end(&b);
}
END_TEST

/* A diffuse and glossy ball at the origin seen from +z; the centre pixel hits (0,0,1) with
 * normal N = V = (0,0,1). */
static const char *lit_ball = "size 65 65\n"
                              "camera 0 0 5  0 0 0  0 1 0  30\n"
                              "attenuation 1 0.5 0.25\n"
                              "point 2 0 3  1 0.8 0.6\n"
                              "ambient 0.1 0.05 0.02\n"
                              "diffuse 0.5 0.4 0.3\n"
                              "specular 0.2 0.2 0.2\n"
                              "shininess 10\n"
                              "sphere 0 0 0 1\n";

START_TEST(test_raytracer_whitted_lighting_matches_the_hand_computation)
{
    fixture f;
    char text[2048];
    snprintf(text, sizeof text, "%sdirectional 0 0 1  0.3 0.3 0.3\n", lit_ball);
    load(&f.sc, text); /* no envmap: the reflected ray sees black */
    fixture_start(&f);
    /* point light: to = (2,0,2), d = 2 sqrt 2, L = (1,0,1)/sqrt 2, N.L = 1/sqrt 2,
     * atten = 1 + 0.5 d + 0.25 d^2 = 3 + sqrt 2, H = normalize(L + V) */
    double s2 = sqrt(2.0), ndotl = 1 / s2, atten = 3 + s2;
    vec3 hv = vec3_normalize(vec3_make(1 / s2, 0, 1 + 1 / s2));
    double spec = 0.2 * pow(hv.z, 10); /* ks (N.H)^s */
    rgb kd = rgb_make(0.5, 0.4, 0.3);
    rgb point = rgb_scale(
        rgb_mul(rgb_make(1, 0.8, 0.6), rgb_add(rgb_scale(kd, ndotl), rgb_gray(spec))), 1 / atten);
    /* directional light along the normal: N.L = N.H = 1, no attenuation */
    rgb dir = rgb_scale(rgb_add(kd, rgb_gray(0.2)), 0.3);
    rgb want = rgb_add(rgb_add(rgb_make(0.1, 0.05, 0.02), point), dir);
    ck_rgb_near(pixel(&f, 32, 32), want, 1e-12);
    fixture_end(&f);
}
END_TEST

START_TEST(test_raytracer_shadowed_point_is_ambient_only)
{
    fixture f;
    char text[2048];
    /* a small ball halfway between the shading point (0,0,1) and the light (2,0,3) */
    snprintf(text, sizeof text, "%ssphere 1 0 2 0.3\n", lit_ball);
    load(&f.sc, text);
    fixture_start(&f);
    ck_rgb_near(pixel(&f, 32, 32), rgb_make(0.1, 0.05, 0.02), 0);
    fixture_end(&f);
    /* without the blocker the same pixel is lit */
    load(&f.sc, lit_ball);
    fixture_start(&f);
    ck_assert(pixel(&f, 32, 32).r > 0.2);
    fixture_end(&f);
}
END_TEST

START_TEST(test_raytracer_light_behind_the_surface_adds_nothing)
{
    fixture f;
    load(&f.sc,
         "size 65 65\ncamera 0 0 5  0 0 0  0 1 0  30\n"
         "directional 0 0 -1  1 1 1\npoint 0 0 -3  1 1 1\n"
         "ambient 0.1 0.2 0.3\ndiffuse 1 1 1\nspecular 1 1 1\nshininess 1\nsphere 0 0 0 1\n");
    fixture_start(&f);
    ck_rgb_near(pixel(&f, 32, 32), rgb_make(0.1, 0.2, 0.3), 0);
    fixture_end(&f);
}
END_TEST

/* FORMAT.md's Whitted sum clamps each term on its own: kd max(N.L, 0) + ks max(N.H, 0)^s.  An
 * open floor (two triangles, normal +y) under a directional light 0.1 below its plane, seen from
 * above: N.L < 0, so no diffuse, but N.H > 0 and the course shows the highlight (nothing blocks
 * the shadow ray: the floor has no underside).  Catches a light skipped at N.L <= 0. */
START_TEST(test_raytracer_a_light_just_below_an_open_floor_still_gives_the_courses_highlight)
{
    fixture f;
    load(&f.sc, "size 9 9\ncamera 0 3 3  0 0 0  0 1 0  45\n"
                "directional 1 -0.1 0  1 1 1\n"
                "ambient 0 0 0\ndiffuse 0.5 0.5 0.5\nspecular 0.5 0.5 0.5\nshininess 1\n"
                "vertex -2 0 -2\nvertex 2 0 -2\nvertex 2 0 2\nvertex -2 0 2\n"
                "tri 0 2 1\ntri 0 3 2\n");
    fixture_start(&f);
    /* the centre pixel sees the origin: V = (0, 1, 1) / sqrt 2, L = (1, -0.1, 0) / |...| */
    vec3 l = vec3_normalize(vec3_make(1, -0.1, 0)), v = vec3_normalize(vec3_make(0, 1, 1));
    double ndoth = vec3_normalize(vec3_add(l, v)).y;
    ck_assert(ndoth > 0.1);
    ck_rgb_near(pixel(&f, 4, 4), rgb_gray(0.5 * ndoth), 1e-12); /* ks (N.H)^1, no kd term */
    fixture_end(&f);
}
END_TEST

/* ... but each term is clamped on its own: where N.H < 0 too (the light far below the floor) the
 * highlight is 0, not (N.H)^s of a negative N.H (positive for an even s). */
START_TEST(test_raytracer_no_highlight_where_n_dot_h_is_negative)
{
    fixture f;
    load(&f.sc, "size 9 9\ncamera 0 3 3  0 0 0  0 1 0  45\n"
                "directional 1 -3 0  1 1 1\n"
                "ambient 0 0 0\ndiffuse 0.5 0.5 0.5\nspecular 0.5 0.5 0.5\nshininess 2\n"
                "vertex -2 0 -2\nvertex 2 0 -2\nvertex 2 0 2\nvertex -2 0 2\n"
                "tri 0 2 1\ntri 0 3 2\n");
    fixture_start(&f);
    vec3 l = vec3_normalize(vec3_make(1, -3, 0)), v = vec3_normalize(vec3_make(0, 1, 1));
    ck_assert(vec3_normalize(vec3_add(l, v)).y < -0.1);
    ck_rgb_near(pixel(&f, 4, 4), rgb_gray(0), 0);
    fixture_end(&f);
}
END_TEST

/* A point light's shadow ray ends at the light: a ball above the light does not shadow the floor
 * below it.  Floor point (0, 0, 0), light at (0, 1, 0) (N.L = 1, attenuation 1 0 0), kd 0.5. */
START_TEST(test_raytracer_an_object_beyond_a_point_light_casts_no_shadow)
{
    fixture f;
    load(&f.sc, "size 9 9\ncamera 0 3 3  0 0 0  0 1 0  45\n"
                "point 0 1 0  1 1 1\n"
                "ambient 0 0 0\ndiffuse 0.5 0.5 0.5\n"
                "vertex -2 0 -2\nvertex 2 0 -2\nvertex 2 0 2\nvertex -2 0 2\n"
                "tri 0 2 1\ntri 0 3 2\n"
                "sphere 0 3 0 1\n");
    fixture_start(&f);
    ck_rgb_near(pixel(&f, 4, 4), rgb_gray(0.5), 1e-12);
    fixture_end(&f);
}
END_TEST

/* A reflection is traced whenever ks has any channel above 0 (`specular 0 0.5 0`: its largest
 * channel), and it is ks times what the reflected ray sees: a ball in a constant environment of
 * 1 shows (0, 0.5, 0). */
START_TEST(test_raytracer_a_coloured_specular_reflects)
{
    fixture f;
    load(&f.sc, "size 9 9\ncamera 0 0 5  0 0 0  0 1 0  30\n"
                "ambient 0 0 0\ndiffuse 0 0 0\nspecular 0 0.5 0\nsphere 0 0 0 1\n");
    set_env(&f.sc, GENENV_CONSTANT, 1.0);
    fixture_start(&f);
    ck_rgb_near(pixel(&f, 4, 4), rgb_make(0, 0.5, 0), 1e-6);
    fixture_end(&f);
}
END_TEST

/* Rays from a point light aimed (to within 1e-9 rad) at the centre of a ball with a huge
 * shininess (1e18): N, L and V agree to rounding there, N.H rounds to 1 + 2^-52 for some of
 * them, and the highlight ks (N.H)^s must still be at most ks, so each ray's radiance is at most
 * ambient + (kd + ks) * colour.  Catches N.H not clamped to <= 1 ((1 + 2^-52)^1e18 = Inf). */
START_TEST(test_raytracer_blinn_phong_highlight_with_huge_shininess_never_exceeds_ks)
{
    fixture f;
    load(&f.sc, "size 9 9\ncamera 0 0 5  0 0 0  0 1 0  30\n"
                "point 0.3 -2.5 1.7  1 1 1\n"
                "ambient 0.1 0.1 0.1\ndiffuse 0.5 0.5 0.5\nspecular 1 1 1\nshininess 1e18\n"
                "sphere 0 0 0 1\n");
    fixture_start(&f);
    vec3 q = vec3_make(0.3, -2.5, 1.7), axis = vec3_normalize(vec3_neg(q));
    int bad = 0, lit = 0;
    for (int i = 0; i < 2000; i++) {
        /* a direction 1e-9 rad or less from the axis: the highlight's centre */
        double a = 1e-9 * ((i % 41) - 20) / 20, b = 1e-9 * ((i / 41) % 49 - 24) / 24;
        vec3 d = vec3_normalize(vec3_add(axis, vec3_make(a, b, 0.5 * a - b)));
        ray r = {q, d, 0.0, INFINITY};
        rgb c = raytracer_trace(&f.rt, r);
        bad += !(c.r <= 0.1 + 0.5 + 1 + 1e-9);
        lit += c.r > 1.5; /* the highlight is there: ks (N.H)^s = e^(-1e18 * 1e-18 / 2) at most */
    }
    ck_assert_int_eq(bad, 0);
    ck_assert_int_gt(lit, 1000);
    fixture_end(&f);
}
END_TEST

/* A glass ball in a constant environment L: every path ends in the environment, weighted by
 * Fresnel fractions that sum to one, so each pixel is L minus what is cut at maxdepth. */
static const char *glass_ball = "size 33 33\n"
                                "camera 0 0 5  0 0 0  0 1 0  30\n"
                                "maxdepth 12\n"
                                "ambient 0 0 0\n"
                                "brdf glass\n"
                                "ior 1.5\n"
                                "sphere 0 0 0 1\n";

START_TEST(test_raytracer_glass_ball_in_a_constant_environment_conserves_energy)
{
    fixture f;
    load(&f.sc, glass_ball);
    set_env(&f.sc, GENENV_CONSTANT, 0.75);
    fixture_start(&f);
    double L = 0.75; /* exactly representable as a float */
    /* through the centre: 0.04 L reflected + 0.96^2 L through, + 0.96 * 0.04 * ... inside */
    rgb c = pixel(&f, 16, 16);
    ck_rgb_near(c, rgb_gray(L), 1e-9);
    double sum = 0;
    int n = 0;
    for (int y = 0; y < 33; y++)
        for (int x = 0; x < 33; x++) {
            rgb p = pixel(&f, x, y);
            if (p.r > L * (1 + 1e-12) || p.g > L * (1 + 1e-12))
                ck_abort_msg("pixel (%d, %d) = %.17g exceeds the environment %g", x, y, p.r, L);
            ray r = camera_ray(&f.cam, x + 0.5, y + 0.5);
            double t;
            if (sphere_intersect(&f.sc.spheres[0], &r, &t)) {
                sum += p.r;
                n++;
            }
        }
    ck_assert_int_gt(n, 100);
    ck_assert_msg(sum / n > 0.99 * L, "glass ball loses energy: mean %g of %g", sum / n, L);
    fixture_end(&f);
}
END_TEST

START_TEST(test_raytracer_glass_ball_refracts_the_view_upside_down)
{
    /* a solid glass ball is a thick lens: behind it, the world appears flipped.  Looking
     * along -z through the centre region, a ray right of centre leaves the ball heading left. */
    fixture f;
    load(&f.sc, glass_ball);
    set_env(&f.sc, GENENV_AXES, 1);
    fixture_start(&f);
    rgb right = pixel(&f, 20, 16), left = pixel(&f, 12, 16);
    ck_assert_msg(right.r < 0.5 && left.r > 0.5, "right %g, left %g", right.r, left.r);
    rgb centre = pixel(&f, 16, 16); /* straight through: the -z side of the map, blue ~ 0 */
    ck_assert(centre.b < 0.1);
    fixture_end(&f);
}
END_TEST

Suite *raytracer_suite(void)
{
    Suite *s = suite_create("raytracer");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc,
                   test_raytracer_mirror_ball_reflects_the_axes_environment_the_right_way_round);
    tcase_add_test(tc, test_raytracer_every_mirror_ball_pixel_shows_the_reflected_direction);
    tcase_add_test(tc, test_raytracer_envmiss_black_darkens_reflections_but_not_the_background);
    tcase_add_test(tc, test_raytracer_maxdepth_0_shows_no_reflection);
    tcase_add_test(tc, test_raytracer_facing_mirrors_sum_emission_over_exactly_maxdepth_bounces);
    tcase_add_test(tc, test_raytracer_unlimited_depth_stops_where_the_branch_weight_is_negligible);
    tcase_add_test(tc, test_raytracer_envmiss_black_removes_the_escaping_light_between_mirrors);
    tcase_add_test(tc, test_raytracer_whitted_lighting_matches_the_hand_computation);
    tcase_add_test(tc, test_raytracer_shadowed_point_is_ambient_only);
    tcase_add_test(tc, test_raytracer_light_behind_the_surface_adds_nothing);
    tcase_add_test(
        tc, test_raytracer_a_light_just_below_an_open_floor_still_gives_the_courses_highlight);
    tcase_add_test(tc, test_raytracer_blinn_phong_highlight_with_huge_shininess_never_exceeds_ks);
    tcase_add_test(tc, test_raytracer_glass_ball_in_a_constant_environment_conserves_energy);
    tcase_add_test(tc, test_raytracer_glass_ball_refracts_the_view_upside_down);
    tcase_add_test(tc, test_raytracer_no_highlight_where_n_dot_h_is_negative);
    tcase_add_test(tc, test_raytracer_an_object_beyond_a_point_light_casts_no_shadow);
    tcase_add_test(tc, test_raytracer_a_coloured_specular_reflects);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(raytracer_suite)
