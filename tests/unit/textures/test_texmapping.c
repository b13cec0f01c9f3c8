/* test_texmapping.c - the lecture's (s, t) mappings: known values, the phi seam and the poles,
 * cube faces, barycentric interpolation, seam-aware differentials and tangents. */
#include "envtex/textures/texmapping.h"

#include <string.h>

#include "unit.h"

#define uv_near(a, u, v, tol) ck_uv_near(a, ((uv2){u, v}), tol)

START_TEST(test_names_round_trip_and_unknown_names_are_refused)
{
    for (int k = TEXMAPPING_UV; k <= TEXMAPPING_CUBE; k++) {
        texmapping_kind got;
        ck_assert_int_eq(texmapping_parse(texmapping_name((texmapping_kind)k), &got), 0);
        ck_assert_int_eq(got, k);
    }
    texmapping_kind got;
    ck_assert_int_eq(texmapping_parse("Spherical", &got), -1);
    ck_assert_int_eq(texmapping_parse("", &got), -1);
}
END_TEST

START_TEST(test_planar_is_x_and_y)
{
    uv_near(texmapping_planar(vec3_make(0.25, -3, 7)), 0.25, -3, 0);
}
END_TEST

START_TEST(test_spherical_known_values_follow_the_envmap_frame)
{
    uv_near(texmapping_spherical(vec3_make(1, 0, 0)), 0, 0.5, 1e-15);    /* phi 0, equator */
    uv_near(texmapping_spherical(vec3_make(0, 1, 0)), 0.25, 0.5, 1e-15); /* phi pi/2 */
    uv_near(texmapping_spherical(vec3_make(-1, 0, 0)), 0.5, 0.5, 1e-15);
    uv_near(texmapping_spherical(vec3_make(0, -2, 0)), 0.75, 0.5, 1e-15); /* any radius */
    uv_near(texmapping_spherical(vec3_make(0, 0, 1)), 0, 1, 0);           /* north pole: top */
    uv_near(texmapping_spherical(vec3_make(0, 0, -1)), 0, 0, 0);
    double c = cos(M_PI / 4);
    uv_near(texmapping_spherical(vec3_make(c, 0, c)), 0, 0.75, 1e-15); /* theta 45 deg */
    /* any radius, however large or small: sqrt(x^2 + y^2) overflowed at 1e200 (t = 0.5) and
     * underflowed at 1e-200 (t = 1) where (1, 1, 1) / sqrt 3 gives t = 1 - acos(1/sqrt 3) / pi */
    double t3 = 1 - acos(1 / sqrt(3.0)) / M_PI;
    uv_near(texmapping_spherical(vec3_make(1e200, 1e200, 1e200)), 0.125, t3, 1e-15);
    uv_near(texmapping_spherical(vec3_make(1e-200, 1e-200, 1e-200)), 0.125, t3, 1e-15);
}
END_TEST

START_TEST(test_spherical_seam_stays_below_one_and_poles_give_no_nan)
{
    /* just below the seam (y -> 0-) s must approach 1 but never reach it (wraps to 0) */
    uv2 a = texmapping_spherical(vec3_make(1, -1e-300, 0));
    ck_assert(a.u >= 0 && a.u < 1);
    uv2 b = texmapping_spherical(vec3_make(1, -1e-9, 0));
    ck_assert(b.u > 0.999999 && b.u < 1);
    uv2 p = texmapping_spherical(vec3_make(0, 0, 5));
    ck_assert(isfinite(p.u) && isfinite(p.v));
    uv2 z = texmapping_spherical(vec3_make(0, 0, 0));
    uv_near(z, 0, 0.5, 0);
}
END_TEST

START_TEST(test_cylindrical_is_phi_and_height)
{
    uv_near(texmapping_cylindrical(vec3_make(0, 3, -2.5)), 0.25, -2.5, 1e-15);
    uv_near(texmapping_cylindrical(vec3_make(0, 0, 4)), 0, 4, 0); /* on the axis: s 0 */
}
END_TEST

START_TEST(test_cube_picks_the_largest_component_and_orients_faces_from_outside)
{
    static const struct {
        vec3 q;
        int face;
        double s, t;
    } cases[] = {
        {{2, 0, 0}, 0, 0.5, 0.5},        {{1, 0.5, 0.5}, 0, 0.75, 0.75},
        {{-1, 0.5, 0.5}, 1, 0.25, 0.75}, {{0.5, 1, 0.5}, 2, 0.25, 0.75},
        {{0.5, -1, 0.5}, 3, 0.75, 0.75}, {{0.5, 0.5, 1}, 4, 0.75, 0.75},
        {{0.5, 0.5, -1}, 5, 0.75, 0.25}, {{1, 1, 1}, 0, 1, 1}, /* a corner: x wins the tie */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int f = -1;
        uv2 st = texmapping_cube(cases[i].q, &f);
        ck_assert_msg(f == cases[i].face, "case %zu: face %d", i, f);
        uv_near(st, cases[i].s, cases[i].t, 1e-15);
    }
}
END_TEST

START_TEST(test_cube_faces_are_right_handed_seen_from_outside)
{
    /* right x up must point out of the cube: catches a mirrored face */
    for (int f = 0; f < 6; f++) {
        vec3 c = vec3_make(f < 2 ? (f == 0 ? 1 : -1) : 0,
                           f == 2   ? 1
                           : f == 3 ? -1
                                    : 0,
                           f == 4   ? 1
                           : f == 5 ? -1
                                    : 0);
        uv2 o = texmapping_cube_face(c, f);
        uv_near(o, 0.5, 0.5, 0);
        /* numerically: a point moved a little along s and along t */
        vec3 e1, e2;
        vec3_basis(c, &e1, &e2);
        uv2 a = texmapping_cube_face(vec3_madd(c, e1, 1e-3), f);
        uv2 b = texmapping_cube_face(vec3_madd(c, e2, 1e-3), f);
        /* the 2D Jacobian's determinant has the sign of (e1 x e2).c = +1 when right x up = c */
        double det = (a.u - 0.5) * (b.v - 0.5) - (b.u - 0.5) * (a.v - 0.5);
        ck_assert_msg(det > 0, "face %d is mirrored", f);
    }
    uv_near(texmapping_cube_face(vec3_make(0, 1, 1), 0), 0.5, 0.5, 0); /* a = 0 guard */
}
END_TEST

START_TEST(test_uv_interpolation_hits_vertices_edges_and_degenerate_triangles)
{
    const uv2 st[3] = {{0, 0}, {1, 0}, {0.5, 2}};
    uv_near(texmapping_uv_interpolate(st, 0, 0), 0, 0, 0);
    uv_near(texmapping_uv_interpolate(st, 1, 0), 1, 0, 0);
    uv_near(texmapping_uv_interpolate(st, 0, 1), 0.5, 2, 0);
    uv_near(texmapping_uv_interpolate(st, 0.5, 0.5), 0.75, 1, 1e-15); /* edge midpoint */
    uv_near(texmapping_uv_interpolate(st, 1.0 / 3, 1.0 / 3), 0.5, 2.0 / 3, 1e-15);
    const uv2 same[3] = {{0.3, 0.7}, {0.3, 0.7}, {0.3, 0.7}};
    uv_near(texmapping_uv_interpolate(same, 0.2, 0.3), 0.3, 0.7, 1e-15);
}
END_TEST

START_TEST(test_wrap_delta_lands_in_the_half_open_interval)
{
    ck_assert_double_eq(texmapping_wrap_delta(0.5), 0.5);
    ck_assert_double_eq(texmapping_wrap_delta(-0.5), 0.5);
    ck_assert_near(texmapping_wrap_delta(0.97), -0.03, 1e-15);
    ck_assert_near(texmapping_wrap_delta(-0.97), 0.03, 1e-15);
    ck_assert_double_eq(texmapping_wrap_delta(3.25), 0.25);
    ck_assert_double_eq(texmapping_wrap_delta(NAN), 0);
    ck_assert_double_eq(texmapping_wrap_delta(INFINITY), 0);
    /* at and past 2^52 every double is a whole number of turns: 0, never 1 (d - 0.5 rounded to
     * even there: an audit found 2^52 + 1 giving 1); just below, halves still land on +0.5 */
    const double whole[] = {0x1p52 + 1, 0x1p53 - 1, -(0x1p52 + 1), 0x1p52 + 3, 1e300};
    for (int k = 0; k < 5; k++) ck_assert_double_eq(texmapping_wrap_delta(whole[k]), 0);
    ck_assert_double_eq(texmapping_wrap_delta(0x1p51 + 0.5), 0.5);
    ck_assert_double_eq(texmapping_wrap_delta(-0x1p51 - 0.5), 0.5);
}
END_TEST

START_TEST(test_differentials_across_the_phi_seam_are_small_not_one)
{
    /* a point just below the seam, stepping across it */
    vec3 q = vec3_make(1, -1e-4, 0), d = vec3_make(0, 2e-4, 0);
    uv2 dx, dy;
    texmapping_differentials(TEXMAPPING_SPHERICAL, q, d, vec3_make(0, 0, 1e-4), &dx, &dy);
    ck_assert_near(dx.u, 2e-4 / (2 * M_PI), 1e-9); /* d phi / 2 pi, not ~ -1 */
    ck_assert_near(dx.v, 0, 1e-12);
    ck_assert_near(dy.v, 1e-4 / M_PI, 1e-9);
    texmapping_differentials(TEXMAPPING_CYLINDRICAL, q, d, vec3_make(0, 0, 1e-4), &dx, &dy);
    ck_assert_near(dx.u, 2e-4 / (2 * M_PI), 1e-9);
    ck_assert_near(dy.v, 1e-4, 1e-15);
}
END_TEST

START_TEST(test_differentials_at_a_pole_are_bounded)
{
    uv2 dx, dy;
    texmapping_differentials(TEXMAPPING_SPHERICAL, vec3_make(0, 0, 1), vec3_make(1e-3, 0, 0),
                             vec3_make(0, 1e-3, 0), &dx, &dy);
    ck_assert(fabs(dx.u) <= 0.5 && fabs(dy.u) <= 0.5);
    ck_assert(isfinite(dx.v) && isfinite(dy.v));
    ck_assert_near(dy.u, 0.25, 1e-12); /* phi from 0 to pi/2: a quarter turn */
}
END_TEST

START_TEST(test_cube_differentials_match_finite_differences_on_the_face)
{
    vec3 q = vec3_make(0.3, -0.2, 1.0), d = vec3_make(1e-7, 2e-7, -1e-7);
    uv2 dx, dy;
    texmapping_differentials(TEXMAPPING_CUBE, q, d, vec3_make(0, 0, 0), &dx, &dy);
    uv2 a = texmapping_cube_face(q, 4), b = texmapping_cube_face(vec3_add(q, d), 4);
    ck_assert_near(dx.u, b.u - a.u, 1e-13);
    ck_assert_near(dx.v, b.v - a.v, 1e-13);
    uv_near(dy, 0, 0, 0);
    /* near an edge the step crosses to another face: the differential stays on q's face */
    q = vec3_make(1.0, 0.999999, 0.2);
    texmapping_differentials(TEXMAPPING_CUBE, q, vec3_make(0, 1e-5, 0), vec3_make(0, 0, 0), &dx,
                             &dy);
    ck_assert_near(dx.u, 0.5e-5, 1e-12);
}
END_TEST

START_TEST(test_tangents_invert_the_mapping_jacobian)
{
    /* on the unit sphere at the equator, phi = 90 deg: dq/ds = 2 pi * (-1, 0, 0) direction,
     * dq/dt = pi * (0, 0, 1) (t grows towards the north pole) */
    vec3 q = vec3_make(0, 1, 0), dqs, dqt;
    ck_assert_int_eq(texmapping_tangents(TEXMAPPING_SPHERICAL, q, q, &dqs, &dqt), 0);
    ck_assert_near(dqs.x, -2 * M_PI, 1e-6);
    ck_assert_near(dqs.y, 0, 1e-6);
    ck_assert_near(dqs.z, 0, 1e-6);
    ck_assert_near(dqt.z, M_PI, 1e-6);
    /* planar: (1, 0, 0) and (0, 1, 0) */
    ck_assert_int_eq(
        texmapping_tangents(TEXMAPPING_PLANAR, vec3_make(3, 4, 0), vec3_make(0, 0, 1), &dqs, &dqt),
        0);
    ck_assert_near(dqs.x, 1, 1e-9);
    ck_assert_near(dqt.y, 1, 1e-9);
    ck_assert_near(dqs.y, 0, 1e-9);
    /* at the seam the tangents are the same as just beside it (no wrap blow-up) */
    ck_assert_int_eq(texmapping_tangents(TEXMAPPING_SPHERICAL, vec3_make(1, 0, 0),
                                         vec3_make(1, 0, 0), &dqs, &dqt),
                     0);
    ck_assert_near(dqs.y, 2 * M_PI, 1e-6);
    /* planar seen edge-on: singular, a basis is returned */
    ck_assert_int_eq(
        texmapping_tangents(TEXMAPPING_PLANAR, vec3_make(0, 0, 0), vec3_make(1, 0, 0), &dqs, &dqt),
        -1);
    ck_assert_near(vec3_length(dqs), 1, 1e-12);
}
END_TEST

START_TEST(test_triangle_tangents_and_differentials_agree_with_a_known_plane)
{
    /* P = (2 s, 3 t, 0): dP/ds = (2, 0, 0), dP/dt = (0, 3, 0) */
    const vec3 p[3] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
    const uv2 st[3] = {{0, 0}, {1, 0}, {0, 1}};
    vec3 ds, dt;
    ck_assert_int_eq(texmapping_triangle_tangents(p, st, &ds, &dt), 0);
    ck_assert_near(ds.x, 2, 1e-15);
    ck_assert_near(dt.y, 3, 1e-15);
    uv2 dx, dy;
    ck_assert_int_eq(texmapping_triangle_differentials(p, st, vec3_make(0.2, 0, 0.7),
                                                       vec3_make(0, 0.3, 0), &dx, &dy),
                     0);
    uv_near(dx, 0.1, 0, 1e-15); /* the part along the normal (z) is dropped */
    uv_near(dy, 0, 0.1, 1e-15);
    /* degenerate st: a basis of the plane and -1 */
    const uv2 flat[3] = {{0, 0}, {1, 1}, {2, 2}};
    ck_assert_int_eq(texmapping_triangle_tangents(p, flat, &ds, &dt), -1);
    ck_assert_near(fabs(vec3_dot(vec3_cross(ds, dt), vec3_make(0, 0, 1))), 1, 1e-12);
    /* zero-area triangle: no differentials, guarded */
    const vec3 line[3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    ck_assert_int_eq(texmapping_triangle_differentials(line, st, vec3_make(1, 0, 0),
                                                       vec3_make(0, 1, 0), &dx, &dy),
                     -1);
    uv_near(dx, 0, 0, 0);
    ck_assert_int_eq(texmapping_triangle_tangents(line, st, &ds, &dt), -1);
    /* the thresholds are relative: a tiny st patch (extents 1e-7, det 1e-14) is not degenerate,
     * its tangents are 1e7 times as long; a sliver whose |e1 x e2|^2 is ~1e-14 of |e1|^2 |e2|^2
     * has no differentials though its det is far from 0 in absolute terms */
    /* a general triangle (edges not orthogonal, no st coordinate shared by two vertices) with
     * st an affine function of P: s = 0.3 x + 0.1 y + 0.2, t = -0.2 x + 0.4 y + 0.5, so
     * dst = (0.3 dx + 0.1 dy, -0.2 dx + 0.4 dy) for any dP in the plane */
    const vec3 pg[3] = {{0, 0, 0}, {2, 1.5, 0}, {0.5, 3, 0}};
    uv2 sg[3];
    for (int k = 0; k < 3; k++)
        sg[k] = (uv2){0.3 * pg[k].x + 0.1 * pg[k].y + 0.2, -0.2 * pg[k].x + 0.4 * pg[k].y + 0.5};
    ck_assert_int_eq(texmapping_triangle_differentials(pg, sg, vec3_make(0.2, 0.1, 0.7),
                                                       vec3_make(0, 0.3, 0), &dx, &dy),
                     0);
    uv_near(dx, 0.07, 0.0, 1e-15);
    uv_near(dy, 0.03, 0.12, 1e-15);
    const uv2 tiny[3] = {{0.5, 0.5}, {0.5 + 1e-7, 0.5}, {0.5, 0.5 + 1e-7}};
    ck_assert_int_eq(texmapping_triangle_tangents(p, tiny, &ds, &dt), 0);
    ck_assert_near(ds.x / 2e7, 1, 1e-6);
    ck_assert_near(dt.y / 3e7, 1, 1e-6);
    const vec3 sliver[3] = {{0, 0, 0}, {1, 0, 0}, {2, 1e-7, 0}};
    ck_assert_int_eq(texmapping_triangle_differentials(sliver, st, vec3_make(1, 0, 0),
                                                       vec3_make(0, 1, 0), &dx, &dy),
                     -1);
}
END_TEST

Suite *texmapping_suite(void)
{
    Suite *s = suite_create("texmapping");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_names_round_trip_and_unknown_names_are_refused);
    tcase_add_test(tc, test_planar_is_x_and_y);
    tcase_add_test(tc, test_spherical_known_values_follow_the_envmap_frame);
    tcase_add_test(tc, test_spherical_seam_stays_below_one_and_poles_give_no_nan);
    tcase_add_test(tc, test_cylindrical_is_phi_and_height);
    tcase_add_test(tc, test_cube_picks_the_largest_component_and_orients_faces_from_outside);
    tcase_add_test(tc, test_cube_faces_are_right_handed_seen_from_outside);
    tcase_add_test(tc, test_uv_interpolation_hits_vertices_edges_and_degenerate_triangles);
    tcase_add_test(tc, test_wrap_delta_lands_in_the_half_open_interval);
    tcase_add_test(tc, test_differentials_across_the_phi_seam_are_small_not_one);
    tcase_add_test(tc, test_differentials_at_a_pole_are_bounded);
    tcase_add_test(tc, test_cube_differentials_match_finite_differences_on_the_face);
    tcase_add_test(tc, test_tangents_invert_the_mapping_jacobian);
    tcase_add_test(tc, test_triangle_tangents_and_differentials_agree_with_a_known_plane);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(texmapping_suite)
