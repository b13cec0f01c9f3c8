/* test_displacemap.c - displacement maps applied to a copy of the scene (displacemap.h). */
#include "envtex/displacemap.h"
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

Suite *displacemap_suite(void)
{
    Suite *s = suite_create("displacemap");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_scenes_without_displacement_need_none);
    tcase_add_test(tc, test_displaced_sphere_vertices_lie_at_radius_plus_scale_times_height);
    tcase_add_test(tc, test_displaced_triangle_moves_along_its_normal_and_keeps_object_corners);
    tcase_add_test(tc, test_rates_are_halved_until_the_budget_fits_and_an_impossible_budget_fails);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(displacemap_suite)
