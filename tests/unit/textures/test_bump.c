/* test_bump.c - Blinn's bump mapping: a constant height changes nothing, a linear ramp gives
 * the analytic tilted normal, a curved height agrees with the finite-difference normal of the
 * displaced surface, left-handed frames, the geometric-side guard and degenerate tangents. */
#include "envtex/textures/bump.h"

#include "unit.h"

static const vec3 Z = {0, 0, 1};

START_TEST(test_a_constant_height_leaves_the_normal_unchanged)
{
    vec3 out;
    vec3 n = vec3_normalize(vec3_make(0.1, 0.2, 1));
    ck_assert_int_eq(bump_normal(n, Z, vec3_make(1, 0, 0), vec3_make(0, 1, 0), 0, 0, 5, &out), 0);
    ck_vec_near(out, n, 1e-15);
    ck_assert_int_eq(bump_normal(Z, Z, vec3_make(1, 0, 0), vec3_make(0, 1, 0), 3, 4, 0, &out), 0);
    ck_vec_near(out, Z, 0);
}
END_TEST

START_TEST(test_a_linear_ramp_tilts_the_normal_analytically)
{
    /* plane P = (2 s, 3 t, 0), height h = a s + b t, strength k: the displaced plane is
     * z = k (a x / 2 + b y / 3), whose normal is (-k a / 2, -k b / 3, 1) normalized */
    double a = 0.7, b = -1.3, k = 0.5;
    vec3 out;
    ck_assert_int_eq(bump_normal(Z, Z, vec3_make(2, 0, 0), vec3_make(0, 3, 0), a, b, k, &out), 0);
    ck_vec_near(out, vec3_normalize(vec3_make(-k * a / 2, -k * b / 3, 1)), 1e-15);
}
END_TEST

/* height on the plane: h(s, t) = sin(3 s) cos(2 t) */
static double height(double s, double t) { return sin(3 * s) * cos(2 * t); }

START_TEST(test_a_curved_height_matches_the_finite_difference_normal)
{
    /* a sheared plane P(s, t) = s u + t v with normal n; the displaced surface
     * Q = P + k h n; its normal dQ/ds x dQ/dt by central differences */
    vec3 u = vec3_make(1, 0.2, 0), v = vec3_make(0.3, 1, 0.1);
    vec3 n = vec3_normalize(vec3_cross(u, v));
    double k = 0.8, s = 0.4, t = -0.9, e = 1e-6;
    double hs = 3 * cos(3 * s) * cos(2 * t), ht = -2 * sin(3 * s) * sin(2 * t);
    vec3 out;
    ck_assert_int_eq(bump_normal(n, n, u, v, hs, ht, k, &out), 0);
#define Q(S, T) vec3_madd(vec3_add(vec3_scale(u, S), vec3_scale(v, T)), n, k *height(S, T))
    vec3 qs = vec3_scale(vec3_sub(Q(s + e, t), Q(s - e, t)), 0.5 / e);
    vec3 qt = vec3_scale(vec3_sub(Q(s, t + e), Q(s, t - e)), 0.5 / e);
#undef Q
    ck_vec_near(out, vec3_normalize(vec3_cross(qs, qt)), 1e-8);
}
END_TEST

START_TEST(test_a_left_handed_frame_still_bumps_towards_the_shading_side)
{
    /* swapping the tangents flips dP/ds x dP/dt; the result must match the right-handed case
     * with the roles of s and t swapped */
    vec3 a, b;
    ck_assert_int_eq(bump_normal(Z, Z, vec3_make(0, 1, 0), vec3_make(1, 0, 0), 0.3, 0.6, 1, &a), 0);
    ck_assert_int_eq(bump_normal(Z, Z, vec3_make(1, 0, 0), vec3_make(0, 1, 0), 0.6, 0.3, 1, &b), 0);
    ck_vec_near(a, b, 1e-15);
    ck_assert(a.z > 0);
}
END_TEST

START_TEST(test_a_huge_bump_stays_on_the_geometric_side)
{
    vec3 out;
    /* ng tilted away from n: a strong slope would push n' below the surface */
    vec3 ng = vec3_normalize(vec3_make(0.5, 0, 1));
    ck_assert_int_eq(bump_normal(Z, ng, vec3_make(1, 0, 0), vec3_make(0, 1, 0), 1e6, 0, 1, &out),
                     0);
    ck_assert_msg(vec3_dot(out, ng) >= BUMP_MIN_COS * (1 - 1e-9), "n'.ng = %g", vec3_dot(out, ng));
    ck_assert_near(vec3_length(out), 1, 1e-12);
}
END_TEST

/* The guard's target is n'.ng = BUMP_MIN_COS exactly (bump.h), not merely at least it, and it
 * acts on every n' below that cosine, including the ones still a hair above the surface
 * (0 <= n'.ng < BUMP_MIN_COS).  n = z, tangents x and y: a slope K in s gives n' along (-K, 0, 1),
 * whose cosine with ng = (0.5, 0, 1) / |.| is (1 - K / 2) / (|n'| |ng|), about 5e-4 at K = 1.9975
 * and about -0.45 at K = 1e6.  Catches the guard tested as n'.ng < 0 and a tilt that forgets the
 * tangential part's length |t| (it would land at n'.ng = 1.1e-3 for the steep slope). */
START_TEST(test_a_bump_below_the_minimum_cosine_is_tilted_to_exactly_it)
{
    vec3 ng = vec3_normalize(vec3_make(0.5, 0, 1));
    const double slopes[] = {1.9975, 1e6};
    for (int i = 0; i < 2; i++) {
        vec3 out, plain = vec3_normalize(vec3_make(-slopes[i], 0, 1));
        double c0 = vec3_dot(plain, ng);
        ck_assert(c0 < BUMP_MIN_COS); /* the guard must act */
        ck_assert_int_eq(
            bump_normal(Z, ng, vec3_make(1, 0, 0), vec3_make(0, 1, 0), slopes[i], 0, 1, &out), 0);
        ck_assert_near(vec3_dot(out, ng), BUMP_MIN_COS, 1e-12);
        ck_assert_near(vec3_length(out), 1, 1e-12);
        /* tilted along ng only: the tangential part keeps its direction (y component stays 0,
         * and it points the way the unguarded n' leans) */
        vec3 t = vec3_madd(out, ng, -vec3_dot(out, ng)), t0 = vec3_madd(plain, ng, -c0);
        ck_assert_near(vec3_dot(vec3_normalize(t), vec3_normalize(t0)), 1, 1e-12);
    }
    ck_assert(vec3_dot(vec3_normalize(vec3_make(-1.9975, 0, 1)), ng) > 0); /* still above: a hair */
}
END_TEST

START_TEST(test_degenerate_tangents_and_nan_give_the_normal_back)
{
    vec3 out;
    ck_assert_int_eq(bump_normal(Z, Z, vec3_make(1, 0, 0), vec3_make(2, 0, 0), 1, 1, 1, &out), -1);
    ck_vec_near(out, Z, 0);
    ck_assert_int_eq(bump_normal(Z, Z, vec3_make(1, 0, 0), vec3_make(0, 1, 0), NAN, 1, 1, &out),
                     -1);
    ck_vec_near(out, Z, 0);
    ck_assert_int_eq(bump_normal(Z, Z, vec3_make(0, 0, 0), vec3_make(0, 1, 0), 1, 1, 1, &out), -1);
}
END_TEST

Suite *bump_suite(void)
{
    Suite *s = suite_create("bump");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_a_constant_height_leaves_the_normal_unchanged);
    tcase_add_test(tc, test_a_linear_ramp_tilts_the_normal_analytically);
    tcase_add_test(tc, test_a_curved_height_matches_the_finite_difference_normal);
    tcase_add_test(tc, test_a_left_handed_frame_still_bumps_towards_the_shading_side);
    tcase_add_test(tc, test_a_huge_bump_stays_on_the_geometric_side);
    tcase_add_test(tc, test_a_bump_below_the_minimum_cosine_is_tilted_to_exactly_it);
    tcase_add_test(tc, test_degenerate_tangents_and_nan_give_the_normal_back);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(bump_suite)
