/* test_displacemap.c - displacement maps applied to a copy of the scene (displacemap.h). */
#include "envtex/displacemap.h"

#include <stdio.h>

#include "envtex/bvh.h"
#include "envtex/texshade.h"
#include "unit.h"

static scene load(const char *text)
{
    scene sc;
    error err = {0};
    ck_assert_msg(scene_load_string(text, NULL, NULL, &sc, &err) == 0, "%s", err.msg);
    return sc;
}

/* A constant texture: a checker whose two colours are the same grey v. */
#define CONST_TEX(v) "texture h checker 1  " v " " v " " v "  " v " " v " " v "\n"

START_TEST(test_scenes_without_displacement_need_none)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX("1")
                    "bumpmap h 1\nsphere 0 0 0 1\n");
    ck_assert(!displacemap_needed(&sc));
    scene_free(&sc);
}
END_TEST

START_TEST(test_displaced_sphere_vertices_lie_at_radius_plus_scale_times_height)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX("0.5")
                    "displacementmap h 0.2\nsphere 1 0 0 2\nnomaps\nsphere -3 0 0 0.5\n");
    ck_assert(displacemap_needed(&sc));
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, &out, &st, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(st.spheres, 1);
    ck_assert_int_eq(st.sphere_rate, DISPLACEMAP_SPHERE_RATE);
    long n = DISPLACEMAP_SPHERE_RATE;
    ck_assert_int_eq(out.n_triangles, 4 * n * (n - 1));
    ck_assert_int_eq(out.n_spheres, 1); /* the undisplaced sphere stays a sphere */
    ck_assert(out.spheres[0].radius == 0.5);
    for (long i = 0; i < out.n_triangles; i++)
        for (int k = 0; k < 3; k++) {
            /* radius 2 + 0.2 * 0.5 around the centre (1, 0, 0), in world and object space */
            double r = vec3_length(vec3_sub(out.triangles[i].p[k], vec3_make(1, 0, 0)));
            ck_assert_msg(fabs(r - 2.1) < 1e-12, "vertex at radius %g, want 2.1", r);
            ck_assert(fabs(vec3_length(vec3_sub(out.triangles[i].q[k], vec3_make(1, 0, 0))) - 2.1) < 1e-12);
            ck_assert(out.triangles[i].has_normals && out.triangles[i].has_st);
            /* a uniformly displaced sphere is still a sphere: normals radial */
            vec3 radial = vec3_normalize(vec3_sub(out.triangles[i].p[k], vec3_make(1, 0, 0)));
            ck_assert(vec3_dot(out.triangles[i].n[k], radial) > 0.999);
        }
    /* the caller's scene is untouched */
    ck_assert_int_eq(sc.n_spheres, 2);
    ck_assert_int_eq(sc.n_triangles, 0);
    ck_assert(out.materials == sc.materials); /* shared, not copied */
    displacemap_free(&out);
    scene_free(&sc);
}
END_TEST

START_TEST(test_displaced_triangle_moves_along_its_normal_and_keeps_object_corners)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX("0.5")
                    "displacementmap h 0.2\ntranslate 0 0 3\n"
                    "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 2\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert(displacemap_apply(&sc, 0, &out, &st, &err) == 0);
    long n = DISPLACEMAP_TRIANGLE_RATE;
    ck_assert_int_eq(out.n_triangles, n * n);
    for (long i = 0; i < out.n_triangles; i++)
        for (int k = 0; k < 3; k++) {
            const scene_triangle *t = &out.triangles[i];
            ck_assert(fabs(t->p[k].z - 3.1) < 1e-12);   /* z = 3 + 0.2 * 0.5 along +z */
            ck_assert(fabs(t->q[k].z) < 1e-12);         /* object space: before translate */
            ck_assert(fabs(t->q[k].x - t->p[k].x) < 1e-12 && fabs(t->q[k].y - t->p[k].y) < 1e-12);
            ck_assert(fabs(t->st[k].u - t->p[k].x) < 1e-12); /* default st = (b1, b2) */
        }
    displacemap_free(&out);
    scene_free(&sc);
}
END_TEST

/* A tent of two flat triangles (no normals) meeting at 90 degrees along the ridge
 * (0, 0, 1) - (0, 1, 1).  Displaced along their own geometric normals, the two copies of the
 * ridge would part by 2 * 0.1 * sin 45 = 0.14 (a crack through which the background shows);
 * along the corners' shared mean normal, (0, 0, 1) here, they stay together. */
START_TEST(test_triangles_without_normals_that_share_an_edge_are_displaced_without_a_crack)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX("0.5")
                    "displacementmap h 0.2\n"
                    "vertex -1 0 0\nvertex 0 0 1\nvertex 0 1 1\nvertex 1 0 0\n"
                    "tri 0 1 2\ntri 1 3 2\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, &out, &st, &err) == 0, "%s", err.msg);
    long n = DISPLACEMAP_TRIANGLE_RATE, shared = 0;
    ck_assert_int_eq(out.n_triangles, 2 * n * n);
    for (long a = 0; a < n * n; a++)          /* the first triangle's patch */
        for (long b = n * n; b < 2 * n * n; b++) /* the second's */
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    const scene_triangle *ta = &out.triangles[a], *tb = &out.triangles[b];
                    if (!(vec3_length(vec3_sub(ta->q[i], tb->q[j])) < 1e-12)) continue;
                    shared++; /* the same point of the ridge before displacement */
                    ck_assert_msg(vec3_length(vec3_sub(ta->p[i], tb->p[j])) < 1e-12,
                                  "the ridge point (%g %g %g) went to (%g %g %g) and (%g %g %g)",
                                  ta->q[i].x, ta->q[i].y, ta->q[i].z, ta->p[i].x, ta->p[i].y,
                                  ta->p[i].z, tb->p[j].x, tb->p[j].y, tb->p[j].z);
                    ck_assert(fabs(ta->p[i].z - 1.1) < 1e-12); /* up by 0.2 * 0.5 along +z */
                }
    ck_assert(shared > 0);
    /* the far corners, used by one triangle each, still move along their own normal */
    for (long t = 0; t < out.n_triangles; t++)
        for (int k = 0; k < 3; k++)
            if (vec3_length(vec3_sub(out.triangles[t].q[k], vec3_make(-1, 0, 0))) < 1e-12)
                ck_assert(vec3_length(vec3_sub(out.triangles[t].p[k],
                                               vec3_make(-1 - 0.1 / sqrt(2), 0, 0.1 / sqrt(2)))) < 1e-12);
    displacemap_free(&out);
    scene_free(&sc);
}
END_TEST

/* A flat quad of two triangles displaced by smooth noise: each patch alone would give the
 * vertices on the diagonal a one-sided normal (measured: up to 11 degrees apart on the two
 * sides), a crease in the shading along every edge of the original mesh.  Both sides must
 * agree, and an inner vertex keeps its area-weighted normal. */
START_TEST(test_normals_on_the_edge_between_two_patches_are_shared_not_one_sided)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n"
                    "texture h perlin 3  0 0 0  1 1 1\ndisplacementmap h 0.3\n"
                    "vertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n"
                    "tri 0 1 2\ntri 0 2 3\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, &out, &st, &err) == 0, "%s", err.msg);
    long n = DISPLACEMAP_TRIANGLE_RATE, shared = 0;
    double worst = 0;
    for (long a = 0; a < n * n; a++)
        for (long b = n * n; b < 2 * n * n; b++)
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    const scene_triangle *ta = &out.triangles[a], *tb = &out.triangles[b];
                    if (!(vec3_length(vec3_sub(ta->p[i], tb->p[j])) == 0)) continue;
                    shared++;
                    worst = fmax(worst, vec3_angle(ta->n[i], tb->n[j]));
                }
    ck_assert(shared > 0);
    ck_assert_msg(worst < 1e-9, "normals on the diagonal differ by %g degrees", worst * 180 / M_PI);
    /* an inner vertex of the first patch (six triangles around it): the normalized sum of
     * (b - a) x (c - a) over them */
    vec3 sum = {0, 0, 0}, nv = {0, 0, 0};
    for (long s0 = 0, around = 0; s0 < n * n && around != 6; s0++) {
        vec3 v = out.triangles[s0].p[0];
        sum = nv = vec3_make(0, 0, 0);
        around = 0;
        for (long t = 0; t < n * n; t++)
            for (int k = 0; k < 3; k++)
                if (vec3_length(vec3_sub(out.triangles[t].p[k], v)) == 0) {
                    const vec3 *p = out.triangles[t].p;
                    sum = vec3_add(sum, vec3_cross(vec3_sub(p[1], p[0]), vec3_sub(p[2], p[0])));
                    nv = out.triangles[t].n[k];
                    around++;
                }
    }
    ck_assert(vec3_angle(nv, vec3_normalize(sum)) < 1e-9);
    displacemap_free(&out);
    scene_free(&sc);
}
END_TEST

/* A displaced sphere under a mirroring transform (det < 0) stays counter-clockwise seen from
 * outside, as parsed triangles do (scene.h): every triangle's e1 x e2 points away from the
 * centre, else glass would refract its index the wrong way round. */
START_TEST(test_a_displaced_sphere_under_a_mirror_keeps_its_triangles_facing_out)
{
    static const char *const xf[] = {"", "scale -1 1 1\n", "scale -1 -1 -1\n", "rotate 0 1 0 30\nscale 1 -2 1\n"};
    for (int k = 0; k < 4; k++) {
        char text[512];
        snprintf(text, sizeof text, "size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX("0.5")
                 "displacementmap h 0.1\n%ssphere 0.5 0 0 1\n", xf[k]);
        scene sc = load(text), out;
        displacemap_stats st;
        error err = {0};
        ck_assert_msg(displacemap_apply(&sc, 0, &out, &st, &err) == 0, "%s", err.msg);
        vec3 c = mat4_point(&sc.spheres[0].xf, sc.spheres[0].center);
        long inward = 0;
        for (long i = 0; i < out.n_triangles; i++) {
            const scene_triangle *t = &out.triangles[i];
            vec3 ng = vec3_cross(vec3_sub(t->p[1], t->p[0]), vec3_sub(t->p[2], t->p[0]));
            vec3 mid = vec3_scale(vec3_add(vec3_add(t->p[0], t->p[1]), t->p[2]), 1.0 / 3);
            inward += vec3_dot(ng, vec3_sub(mid, c)) < 0;
        }
        ck_assert_msg(inward == 0, "transform %d: %ld of %ld triangles face the centre", k, inward, out.n_triangles);
        displacemap_free(&out);
        scene_free(&sc);
    }
}
END_TEST

START_TEST(test_rates_are_halved_until_the_budget_fits_and_an_impossible_budget_fails)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX("1")
                    "displacementmap h 0.1\nsphere 0 0 0 1\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    /* rate 96: 36480 triangles; 48: 9024 fits 10000 */
    ck_assert(displacemap_apply(&sc, 10000, &out, &st, &err) == 0);
    ck_assert_int_eq(st.sphere_rate, 48);
    ck_assert_int_eq(out.n_triangles, 4 * 48 * 47);
    displacemap_free(&out);
    /* the lowest rate, 2, still needs 8 triangles */
    ck_assert(displacemap_apply(&sc, 7, &out, &st, &err) == -1);
    ck_assert(strstr(err.msg, "lowest rates") != NULL);
    ck_assert(out.triangles == NULL && out.spheres == NULL);
    scene_free(&sc);
}
END_TEST

/* (s, t) where a ray from (x, 10, z) straight down (-y) hits sc, as texshade sees it */
static uv2 st_seen_from_above(const scene *sc, double x, double z)
{
    bvh b;
    error err = {0};
    ck_assert_msg(bvh_build(&b, sc, &err) == 0, "%s", err.msg);
    ray r = {vec3_make(x, 10, z), vec3_make(0, -1, 0), 0, INFINITY};
    hit h;
    ck_assert(bvh_intersect(&b, sc, &r, &h));
    surface s;
    memset(&s, 0, sizeof s); /* no differentials */
    texshade_point tp;
    texshade_point_at(sc, &h, &s, &tp);
    bvh_free(&b);
    return tp.st;
}

/* A sphere's `texmapping` maps the unit direction (P_object - c) / R; its displaced copy is
 * triangles, and must show the texture where the sphere did, for every mapping (a zero height
 * moves nothing: only the tessellation differs, by its chord error, < 1e-3 here).  Off the
 * origin, with a radius other than 1 and under a transform, mapping the triangles' object
 * points instead put planar, cylindrical, spherical and cube textures elsewhere. */
START_TEST(test_a_displaced_sphere_keeps_its_texture_mapping)
{
    static const char *const mappings[] = {"uv", "planar", "cylindrical", "spherical", "cube"};
    for (int k = 0; k < 5; k++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX("0")
                 "texture c checker 4  1 0 0  0 1 0\n"
                 "texmapping %s\ndiffusemap c\ndisplacementmap h 0.3\n"
                 "translate 0.2 -0.4 0.3\nscale 1.2 0.8 1.1\nsphere 1 0.5 -0.3 1.5\n",
                 mappings[k]);
        scene sc = load(text), out;
        displacemap_stats st;
        error err = {0};
        ck_assert_msg(displacemap_apply(&sc, 0, &out, &st, &err) == 0, "%s", err.msg);
        /* rays near the top of the ellipsoid, world centre (1.4, 0, 0): object directions
         * near +y, away from the spherical seam and inside the cube's +y face */
        for (int i = 0; i < 9; i++) {
            double x = 1.4 + 0.4 * (i % 3 - 1), z = 0.4 * (i / 3 - 1);
            uv2 want = st_seen_from_above(&sc, x, z), got = st_seen_from_above(&out, x, z);
            ck_assert_msg(fabs(got.u - want.u) < 2e-3 && fabs(got.v - want.v) < 2e-3,
                          "texmapping %s at (%g, %g): displaced copy reads (%g, %g), the sphere "
                          "(%g, %g)", mappings[k], x, z, got.u, got.v, want.u, want.v);
        }
        displacemap_free(&out);
        scene_free(&sc);
    }
}
END_TEST

Suite *displacemap_suite(void)
{
    Suite *s = suite_create("displacemap");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_scenes_without_displacement_need_none);
    tcase_add_test(tc, test_displaced_sphere_vertices_lie_at_radius_plus_scale_times_height);
    tcase_add_test(tc, test_displaced_triangle_moves_along_its_normal_and_keeps_object_corners);
    tcase_add_test(tc, test_triangles_without_normals_that_share_an_edge_are_displaced_without_a_crack);
    tcase_add_test(tc, test_normals_on_the_edge_between_two_patches_are_shared_not_one_sided);
    tcase_add_test(tc, test_a_displaced_sphere_under_a_mirror_keeps_its_triangles_facing_out);
    tcase_add_test(tc, test_rates_are_halved_until_the_budget_fits_and_an_impossible_budget_fails);
    tcase_add_test(tc, test_a_displaced_sphere_keeps_its_texture_mapping);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(displacemap_suite)
