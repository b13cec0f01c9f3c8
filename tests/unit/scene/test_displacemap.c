/* test_displacemap.c - displacement maps applied to a copy of the scene (displacemap.h). */
#include "envtex/scene/displacemap.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envtex/geometry/bvh.h"
#include "envtex/io/pfm.h"
#include "envtex/integrators/texshade.h"
#include "envtex/scene/scene_load.h"
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
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "1") "bumpmap h 1\nsphere 0 0 0 1\n");
    ck_assert(!displacemap_needed(&sc));
    scene_free(&sc);
}
END_TEST

START_TEST(test_displaced_sphere_vertices_lie_at_radius_plus_scale_times_height)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "0.5") "displacementmap h 0.2\nsphere 1 0 0 2\nnomaps\nsphere -3 0 0 0.5\n");
    ck_assert(displacemap_needed(&sc));
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
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
            ck_assert(fabs(vec3_length(vec3_sub(out.triangles[i].q[k], vec3_make(1, 0, 0))) - 2.1) <
                      1e-12);
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
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "0.5") "displacementmap h 0.2\ntranslate 0 0 3\n"
               "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 2\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert(displacemap_needed(&sc)); /* a displaced triangle alone needs it too */
    ck_assert(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0);
    long n = DISPLACEMAP_TRIANGLE_RATE;
    ck_assert_int_eq(out.n_triangles, n * n);
    for (long i = 0; i < out.n_triangles; i++)
        for (int k = 0; k < 3; k++) {
            const triangle *t = &out.triangles[i];
            ck_assert(fabs(t->p[k].z - 3.1) < 1e-12); /* z = 3 + 0.2 * 0.5 along +z */
            ck_assert(fabs(t->q[k].z) < 1e-12);       /* object space: before translate */
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
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "0.5") "displacementmap h 0.2\n"
               "vertex -1 0 0\nvertex 0 0 1\nvertex 0 1 1\nvertex 1 0 0\n"
               "tri 0 1 2\ntri 1 3 2\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
    long n = DISPLACEMAP_TRIANGLE_RATE, shared = 0;
    ck_assert_int_eq(out.n_triangles, 2 * n * n);
    for (long a = 0; a < n * n; a++)             /* the first triangle's patch */
        for (long b = n * n; b < 2 * n * n; b++) /* the second's */
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    const triangle *ta = &out.triangles[a], *tb = &out.triangles[b];
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
                                               vec3_make(-1 - 0.1 / sqrt(2), 0, 0.1 / sqrt(2)))) <
                          1e-12);
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
    ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
    long n = DISPLACEMAP_TRIANGLE_RATE, shared = 0;
    double worst = 0;
    for (long a = 0; a < n * n; a++)
        for (long b = n * n; b < 2 * n * n; b++)
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    const triangle *ta = &out.triangles[a], *tb = &out.triangles[b];
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

/* Two patches whose shared edge has no exact coordinates (under a rotation), with a solid
 * texture and with a planar mapping: both read their heights at the object point, which each
 * must get exactly as the other does along the edge, or the displaced vertices differ in their
 * last bits, the weld misses them, and each side keeps a one-sided normal (a crease of up to
 * 74 degrees).  Catches q recovered from the world point by a least-squares solve per patch
 * (84 of the 95 edge corners missed the weld with fbm). */
START_TEST(test_patches_with_a_solid_texture_share_their_edge_bit_for_bit)
{
    const char *maps[2] = {"texture h fbm 3.7 3  0 0 0  1 1 1\n",
                           "texture h checker 7.3  0 0 0  1 1 1\ntexmapping planar\n"};
    for (int k = 0; k < 2; k++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n%sdisplacementmap h 0.2\n"
                 "vertex 0.1 0.2 0.3\nvertex 1.3 0.1 0.7\nvertex 0.7 1.9 0.2\nvertex 1.7 1.3 1.1\n"
                 "rotate 0.3 1 0.2 37\ntri 0 1 2\ntri 2 1 3\n",
                 maps[k]);
        scene sc = load(text), out;
        displacemap_stats st;
        error err = {0};
        ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
        long n = (long)st.triangle_rate * st.triangle_rate, equal = 0, near = 0;
        double worst = 0;
        for (long a = 0; a < n; a++)
            for (long b = n; b < 2 * n; b++)
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++) {
                        const triangle *ta = &out.triangles[a], *tb = &out.triangles[b];
                        double d = vec3_length(vec3_sub(ta->p[i], tb->p[j]));
                        if (d == 0) {
                            equal++;
                            worst = fmax(worst, vec3_angle(ta->n[i], tb->n[j]));
                        } else if (d < 1e-9) {
                            near++;
                        }
                    }
        ck_assert_msg(near == 0, "map %d: %ld edge corners within 1e-9 but not equal (%ld equal)",
                      k, near, equal);
        ck_assert_msg(equal > st.triangle_rate, "map %d: only %ld shared corners", k, equal);
        ck_assert_msg(worst < 1e-9, "map %d: normals on the edge differ by %g degrees", k,
                      worst * 180 / M_PI);
        displacemap_free(&out);
        scene_free(&sc);
    }
}
END_TEST

/* A displaced sphere under a mirroring transform (det < 0) stays counter-clockwise seen from
 * outside, as parsed triangles do (scene.h): every triangle's e1 x e2 points away from the
 * centre, else glass would refract its index the wrong way round. */
START_TEST(test_a_displaced_sphere_under_a_mirror_keeps_its_triangles_facing_out)
{
    static const char *const xf[] = {"", "scale -1 1 1\n", "scale -1 -1 -1\n",
                                     "rotate 0 1 0 30\nscale 1 -2 1\n"};
    for (int k = 0; k < 4; k++) {
        char text[512];
        snprintf(text, sizeof text,
                 "size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
                     "0.5") "displacementmap h 0.1\n%ssphere 0.5 0 0 1\n",
                 xf[k]);
        scene sc = load(text), out;
        displacemap_stats st;
        error err = {0};
        ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
        vec3 c = mat4_point(&sc.spheres[0].xf, sc.spheres[0].center);
        long inward = 0;
        for (long i = 0; i < out.n_triangles; i++) {
            const triangle *t = &out.triangles[i];
            vec3 ng = vec3_cross(vec3_sub(t->p[1], t->p[0]), vec3_sub(t->p[2], t->p[0]));
            vec3 mid = vec3_scale(vec3_add(vec3_add(t->p[0], t->p[1]), t->p[2]), 1.0 / 3);
            inward += vec3_dot(ng, vec3_sub(mid, c)) < 0;
        }
        ck_assert_msg(inward == 0, "transform %d: %ld of %ld triangles face the centre", k, inward,
                      out.n_triangles);
        displacemap_free(&out);
        scene_free(&sc);
    }
}
END_TEST

START_TEST(test_rates_are_halved_until_the_budget_fits_and_an_impossible_budget_fails)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "1") "displacementmap h 0.1\nsphere 0 0 0 1\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    /* rate 96: 36480 triangles; 48: 9024 fits 10000 */
    ck_assert(displacemap_apply(&sc, 10000, NULL, &out, &st, &err) == 0);
    ck_assert_int_eq(st.sphere_rate, 48);
    ck_assert_int_eq(out.n_triangles, 4 * 48 * 47);
    displacemap_free(&out);
    /* the lowest rate, 2, still needs 8 triangles */
    ck_assert(displacemap_apply(&sc, 7, NULL, &out, &st, &err) == -1);
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
    ck_assert_msg(bvh_build(&b, scene_prims(sc), NULL, &err) == 0, "%s", err.msg);
    ray r = {vec3_make(x, 10, z), vec3_make(0, -1, 0), 0, INFINITY};
    hit h;
    ck_assert(bvh_intersect(&b, &r, &h));
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
                 "size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
                     "0") "texture c checker 4  1 0 0  0 1 0\n"
                          "texmapping %s\ndiffusemap c\ndisplacementmap h 0.3\n"
                          "translate 0.2 -0.4 0.3\nscale 1.2 0.8 1.1\nsphere 1 0.5 -0.3 1.5\n",
                 mappings[k]);
        scene sc = load(text), out;
        displacemap_stats st;
        error err = {0};
        ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
        /* rays near the top of the ellipsoid, world centre (1.4, 0, 0): object directions
         * near +y, away from the spherical seam and inside the cube's +y face */
        for (int i = 0; i < 9; i++) {
            double x = 1.4 + 0.4 * (i % 3 - 1), z = 0.4 * (i / 3 - 1);
            uv2 want = st_seen_from_above(&sc, x, z), got = st_seen_from_above(&out, x, z);
            ck_assert_msg(fabs(got.u - want.u) < 2e-3 && fabs(got.v - want.v) < 2e-3,
                          "texmapping %s at (%g, %g): displaced copy reads (%g, %g), the sphere "
                          "(%g, %g)",
                          mappings[k], x, z, got.u, got.v, want.u, want.v);
        }
        displacemap_free(&out);
        scene_free(&sc);
    }
}
END_TEST

/* The budget is on the whole scene at the rates used (displacemap.h): a budget of exactly the
 * count fits without halving; an undisplaced triangle counts one; the rates stop at 2 and 1
 * (the triangle rate stays 1 while the sphere's is still being halved).  Catches the count of
 * a sphere taken as 4 N^2, ">=" for ">", the undisplaced triangles left out of the count (the
 * copy would overrun its array) and a triangle rate halved to 0. */
START_TEST(test_the_budget_counts_the_whole_scene_exactly)
{
    scene out;
    displacemap_stats st;
    error err = {0};
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "1") "displacementmap h 0.1\nsphere 0 0 0 1\n");
    ck_assert_msg(displacemap_apply(&sc, 4 * 48 * 47, NULL, &out, &st, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(st.sphere_rate, 48);
    displacemap_free(&out);
    scene_free(&sc);
    /* a displaced sphere, a displaced triangle and a plain one: 8 + 1 + 1 at rates 2 and 1 */
    sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "1") "displacementmap h 0.1\nsphere 0 0 0 1\n"
             "vertex 0 0 3\nvertex 1 0 3\nvertex 0 1 3\ntri 0 1 2\nnomaps\ntri 0 1 2\n");
    ck_assert_msg(displacemap_apply(&sc, 10, NULL, &out, &st, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(st.sphere_rate, 2);
    ck_assert_int_eq(st.triangle_rate, 1);
    ck_assert_int_eq(out.n_triangles, 10);
    displacemap_free(&out);
    ck_assert(displacemap_apply(&sc, 9, NULL, &out, &st, &err) == -1);
    scene_free(&sc);
}
END_TEST

/* A triangle with vertex normals (trinormal) moves along them, interpolated (displacemap.h,
 * displace.h): the corners along their own normals, (0, 0, 1), (0.6, 0, 0.8), (0, 0.6, 0.8),
 * each point along normalize(b0 n0 + b1 n1 + b2 n2).  Catches the welded normals of triangles
 * without normals used for it too. */
START_TEST(test_a_triangle_with_vertex_normals_moves_along_them)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "0.5") "displacementmap h 0.2\nvertexnormal 0 0 0  0 0 1\nvertexnormal 1 0 0  0.6 0 0.8\n"
               "vertexnormal 0 1 0  0 0.6 0.8\ntrinormal 0 1 2\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
    const vec3 n0 = {0, 0, 1}, n1 = {0.6, 0, 0.8}, n2 = {0, 0.6, 0.8};
    for (long i = 0; i < out.n_triangles; i++)
        for (int k = 0; k < 3; k++) {
            vec3 q = out.triangles[i].q[k]; /* the point before displacement: b1 = x, b2 = y */
            vec3 n = vec3_normalize(vec3_add(
                vec3_add(vec3_scale(n0, 1 - q.x - q.y), vec3_scale(n1, q.x)), vec3_scale(n2, q.y)));
            vec3 want = vec3_madd(q, n, 0.1); /* 0.2 * 0.5 */
            ck_assert_msg(vec3_length(vec3_sub(out.triangles[i].p[k], want)) < 1e-12,
                          "(%g %g %g) went to (%g %g %g)", q.x, q.y, q.z, out.triangles[i].p[k].x,
                          out.triangles[i].p[k].y, out.triangles[i].p[k].z);
        }
    displacemap_free(&out);
    scene_free(&sc);
}
END_TEST

/* A hard edge of a trinormal mesh stays hard (displacemap.h): a tent whose two faces carry
 * their own face normals at the ridge, not displaced (height 0), keeps each face's normal on
 * its side of the ridge; only an edge with the same normal before displacement on both sides
 * is welded.  Catches the border corners grouped by position alone. */
START_TEST(test_a_hard_edge_between_patches_stays_hard)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "0") "displacementmap h 0.2\n"
             "vertexnormal -1 0 0  -1 0 1\nvertexnormal 0 0 1  -1 0 1\nvertexnormal 0 1 1  -1 0 1\n"
             "vertexnormal 0 0 1  1 0 1\nvertexnormal 1 0 0  1 0 1\nvertexnormal 0 1 1  1 0 1\n"
             "trinormal 0 1 2\ntrinormal 3 4 5\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
    long n = DISPLACEMAP_TRIANGLE_RATE;
    ck_assert_int_eq(out.n_triangles, 2 * n * n);
    vec3 left = vec3_normalize(vec3_make(-1, 0, 1)), right = vec3_normalize(vec3_make(1, 0, 1));
    for (long i = 0; i < out.n_triangles; i++)
        for (int k = 0; k < 3; k++)
            ck_assert_msg(
                vec3_length(vec3_sub(out.triangles[i].n[k], i < n * n ? left : right)) < 1e-12,
                "triangle %ld corner %d: normal (%g %g %g)", i, k, out.triangles[i].n[k].x,
                out.triangles[i].n[k].y, out.triangles[i].n[k].z);
    displacemap_free(&out);
    scene_free(&sc);
}
END_TEST

/* A corner without a normal moves along the ANGLE-weighted mean of the unit geometric normals of
 * the DISPLACED triangles without normals at its position (displacemap.h).  Two displaced
 * triangles meet at the origin with angles 90 and 48 degrees there; a third, undisplaced one
 * (nomaps) shares their other corners and must not pull them.  Catches an unweighted mean and
 * undisplaced neighbours counted in it. */
START_TEST(test_a_corner_without_normals_moves_along_the_angle_weighted_mean_of_displaced_faces)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "0.5") "displacementmap h 0.2\n"
               "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 -1 0\nvertex 0.5 -1 1\n"
               "vertex 1 1 1\ntri 0 1 2\ntri 0 3 4\nnomaps\ntri 1 5 2\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
    /* the faces and their angles at the origin, by the documented formula */
    vec3 na = vec3_make(0, 0, 1), nb = vec3_normalize(vec3_make(-1, 0, 0.5));
    double aa = M_PI / 2, ab = vec3_angle(vec3_make(0, -1, 0), vec3_make(0.5, -1, 1));
    vec3 origin = vec3_normalize(vec3_madd(vec3_scale(na, aa), nb, ab));
    /* (1, 0, 0) and (0, 1, 0): only the first displaced face has them */
    long seen_origin = 0, seen_edge = 0, n = DISPLACEMAP_TRIANGLE_RATE;
    ck_assert_int_eq(out.n_triangles, 2 * n * n + 1);
    for (long i = 0; i < 2 * n * n; i++) /* the two displaced patches (the plain copy is last) */
        for (int k = 0; k < 3; k++) {
            vec3 q = out.triangles[i].q[k], p = out.triangles[i].p[k];
            if (vec3_length(q) == 0) {
                seen_origin++;
                ck_assert_msg(vec3_length(vec3_sub(p, vec3_scale(origin, 0.1))) < 1e-12,
                              "the shared corner went to (%g %g %g)", p.x, p.y, p.z);
            } else if (q.z == 0 && q.x + q.y == 1 && (q.x == 1 || q.y == 1)) {
                seen_edge++;
                ck_assert_msg(vec3_length(vec3_sub(p, vec3_madd(q, na, 0.1))) < 1e-12,
                              "(%g %g 0) went to (%g %g %g)", q.x, q.y, p.x, p.y, p.z);
            }
        }
    ck_assert(seen_origin > 0 && seen_edge > 0);
    displacemap_free(&out);
    scene_free(&sc);
}
END_TEST

/* A sphere's normals go to world space like the sphere's (by the inverse transpose): under
 * `scale 1 0.5 1` the displaced ellipsoid's normal at object point q is along (q.x, 2 q.y, q.z),
 * not q.  Catches the object-space normal copied as it is. */
START_TEST(test_a_displaced_sphere_under_a_scale_has_the_ellipsoids_normals)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "0.5") "displacementmap h 0.2\nscale 1 0.5 1\nsphere 0 0 0 1\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, NULL, &out, &st, &err) == 0, "%s", err.msg);
    for (long i = 0; i < out.n_triangles; i++)
        for (int k = 0; k < 3; k++) {
            vec3 q = out.triangles[i].q[k];
            vec3 want = vec3_normalize(vec3_make(q.x, 2 * q.y, q.z));
            ck_assert_msg(vec3_dot(out.triangles[i].n[k], want) > 0.999, "at (%g %g %g)", q.x, q.y,
                          q.z);
        }
    displacemap_free(&out);
    scene_free(&sc);
}
END_TEST

/* Solid textures on a displaced sphere see the object-space point centre + radius p
 * (displacemap.h): off the origin and with radius 1.5, every vertex lies at c + (R + SCALE h) u,
 * h the texture at c + R u.  The solid is marble without turbulence, 0.5 + 0.5 sin(2 x): smooth,
 * and independent of the noise (the perlin step's starter returns 0).  Catches the unit sphere's
 * p passed instead. */
START_TEST(test_a_displaced_spheres_solid_texture_sees_the_object_point)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n"
                    "texture h marble 1 2 0 1  0 0 0  1 1 1\ntexfilter nearest\n"
                    "displacementmap h 0.3\nsphere 1 -2 0.5 1.5\n");
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 2000, NULL, &out, &st, &err) == 0, "%s", err.msg);
    const material *m = &sc.materials[sc.spheres[0].material];
    const texture *tex = scene_map(&sc, m->displacementmap);
    vec3 c = vec3_make(1, -2, 0.5);
    double lo = 1e9, hi = -1e9;
    for (long i = 0; i < out.n_triangles; i++)
        for (int k = 0; k < 3; k++) {
            vec3 d = vec3_sub(out.triangles[i].q[k], c), u = vec3_normalize(d);
            texture_query tq = {0};
            tq.p = vec3_madd(c, u, 1.5);
            tq.filter = m->texfilter;
            double h = texture_eval_scalar(tex, &tq);
            lo = fmin(lo, h);
            hi = fmax(hi, h);
            ck_assert_msg(fabs(vec3_length(d) - (1.5 + 0.3 * h)) < 1e-9, "radius %g, want %g",
                          vec3_length(d), 1.5 + 0.3 * h);
        }
    ck_assert(hi - lo > 0.1); /* the heights do vary */
    displacemap_free(&out);
    scene_free(&sc);
}
END_TEST

/* Texture coordinates of the heights under a point mapping (displacemap.h): a sphere's is its
 * texmapping of the UNIT direction u (not of the object point c + R u), a triangle's that of
 * its object-space point q (not the interpolated uv).  A smooth 4 x 4 image, read bilinearly,
 * planar mapping, off the origin.  Catches the sphere mapping its object point and the triangle
 * keeping its uv. */
START_TEST(test_heights_under_a_planar_mapping_read_the_documented_point)
{
    char dir[] = "/tmp/test_displacemap_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[256], text[1024];
    snprintf(path, sizeof path, "%s/h.pfm", dir);
    image img;
    error err = {0};
    ck_assert_int_eq(image_alloc(&img, 4, 4, &err), 0);
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++)
            for (int c = 0; c < 3; c++)
                img.px[3 * (4 * y + x) + c] = (float)(0.1 + 0.2 * x + 0.1 * y * (x % 3));
    ck_assert_int_eq(pfm_write(path, &img, &err), 0);
    image_free(&img);
    snprintf(text, sizeof text,
             "size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\ntexture h %s\n"
             "texfilter bilinear\ntexmapping planar\ndisplacementmap h 0.3\nsphere 1 -2 0.5 1.5\n"
             "translate 0 0 4\nvertex 0.2 0.3 0\nvertex 1.7 0.1 0\nvertex 0.4 1.2 0\ntri 0 1 2\n",
             path);
    scene sc = load(text), out;
    displacemap_stats st;
    ck_assert_msg(displacemap_apply(&sc, 3000, NULL, &out, &st, &err) == 0, "%s", err.msg);
    const material *m = &sc.materials[sc.spheres[0].material];
    const texture *tex = scene_map(&sc, m->displacementmap);
    vec3 c = vec3_make(1, -2, 0.5);
    long spheres = 0, tris = 0;
    double lo = 1e9, hi = -1e9;
    for (long i = 0; i < out.n_triangles; i++)
        for (int k = 0; k < 3; k++) {
            const triangle *t = &out.triangles[i];
            texture_query tq = {0};
            tq.filter = m->texfilter;
            if (t->st_mapped) { /* the sphere's: c + (R + SCALE h) u */
                vec3 d = vec3_sub(t->q[k], c);
                tq.st = texmapping_point(TEXMAPPING_PLANAR, vec3_normalize(d));
                double h = texture_eval_scalar(tex, &tq);
                ck_assert_msg(fabs(vec3_length(d) - (1.5 + 0.3 * h)) < 1e-9,
                              "sphere: radius %g, want %g", vec3_length(d), 1.5 + 0.3 * h);
                spheres++;
            } else { /* the triangle's: up from z = 4 by SCALE h */
                tq.st = texmapping_point(TEXMAPPING_PLANAR, t->q[k]);
                tq.p = t->q[k];
                double h = texture_eval_scalar(tex, &tq);
                ck_assert_msg(fabs(t->p[k].z - (4 + 0.3 * h)) < 1e-9, "triangle: z %g, want %g",
                              t->p[k].z, 4 + 0.3 * h);
                lo = fmin(lo, h);
                hi = fmax(hi, h);
                tris++;
            }
        }
    ck_assert(spheres > 0 && tris > 0 && hi - lo > 0.05);
    displacemap_free(&out);
    scene_free(&sc);
    remove(path);
    rmdir(dir);
}
END_TEST

/* The memory budget lowers the rates as max_tris does: the displaced triangles, with their BVH,
 * must fit in what the budget still holds; they are charged.  Even the lowest rates beyond it:
 * one message naming the scene and the budget. */
START_TEST(test_the_memory_budget_lowers_the_rates_until_the_triangles_fit)
{
    scene sc = load("size 4 4\ncamera 0 0 5  0 0 0  0 1 0  40\n" CONST_TEX(
        "0.5") "displacementmap h 0.2\nsphere 0 0 0 1\n");
    snprintf(sc.path, sizeof sc.path, "d.test");
    double per_tri = sizeof(triangle) + bvh_bytes_per_prim();
    budget mem;
    budget_init(&mem, 9100 * per_tri); /* rate 96 makes 36480 triangles, 48 makes 9024 */
    scene out;
    displacemap_stats st;
    error err = {0};
    ck_assert_msg(displacemap_apply(&sc, 0, &mem, &out, &st, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(st.sphere_rate, 48);
    ck_assert_int_eq(out.n_triangles, 4 * 48 * 47);
    ck_assert(mem.used == 9024.0 * sizeof(triangle));
    displacemap_free(&out);
    budget_init(&mem, 10 * per_tri); /* rate 2 makes 8 */
    ck_assert_int_eq(displacemap_apply(&sc, 0, &mem, &out, &st, &err), 0);
    ck_assert_int_eq(st.sphere_rate, 2);
    displacemap_free(&out);
    budget_init(&mem, 7 * per_tri);
    ck_assert_int_eq(displacemap_apply(&sc, 0, &mem, &out, &st, &err), -1);
    ck_assert_str_eq(err.file, "d.test");
    ck_assert_msg(
        strstr(err.msg,
               "even at the lowest rates, displacement mapping's 8 triangles and their BVH x ") &&
            strstr(err.msg, "beyond the memory budget"),
        "%s", err.msg);
    ck_assert(mem.used == 0 && out.triangles == NULL);
    scene_free(&sc);
}
END_TEST

Suite *displacemap_suite(void)
{
    Suite *s = suite_create("displacemap");
    TCase *tc = tcase_create("core");
    unit_slow(tc); /* a slow case (unit.h) */
    tcase_add_test(tc, test_scenes_without_displacement_need_none);
    tcase_add_test(tc, test_the_memory_budget_lowers_the_rates_until_the_triangles_fit);
    tcase_add_test(tc, test_displaced_sphere_vertices_lie_at_radius_plus_scale_times_height);
    tcase_add_test(tc, test_displaced_triangle_moves_along_its_normal_and_keeps_object_corners);
    tcase_add_test(tc,
                   test_triangles_without_normals_that_share_an_edge_are_displaced_without_a_crack);
    tcase_add_test(tc, test_normals_on_the_edge_between_two_patches_are_shared_not_one_sided);
    tcase_add_test(tc, test_patches_with_a_solid_texture_share_their_edge_bit_for_bit);
    tcase_add_test(tc, test_a_displaced_sphere_under_a_mirror_keeps_its_triangles_facing_out);
    tcase_add_test(tc, test_rates_are_halved_until_the_budget_fits_and_an_impossible_budget_fails);
    tcase_add_test(tc, test_a_displaced_sphere_keeps_its_texture_mapping);
    tcase_add_test(tc, test_the_budget_counts_the_whole_scene_exactly);
    tcase_add_test(tc, test_a_triangle_with_vertex_normals_moves_along_them);
    tcase_add_test(tc, test_a_hard_edge_between_patches_stays_hard);
    tcase_add_test(
        tc, test_a_corner_without_normals_moves_along_the_angle_weighted_mean_of_displaced_faces);
    tcase_add_test(tc, test_a_displaced_sphere_under_a_scale_has_the_ellipsoids_normals);
    tcase_add_test(tc, test_a_displaced_spheres_solid_texture_sees_the_object_point);
    tcase_add_test(tc, test_heights_under_a_planar_mapping_read_the_documented_point);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(displacemap_suite)
