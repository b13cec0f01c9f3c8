/* test_transform.c - 4x4 affine transforms as the scene format composes them (right
 * multiplication: the command written last applies first), inverses, and normals under
 * non-uniform scale (the inverse transpose). */
#include "envtex/core/transform.h"

#include <string.h>

#include "envtex/core/rng.h"
#include "unit.h"

/* Checks for long loops: every passing ck_assert costs a system call (Check records the last
 * passing line), which would dominate the run time; these report failures only. */
#define EXPECT(c)                                                                                  \
    do {                                                                                           \
        if (!(c)) ck_abort_msg("failed: %s", #c);                                                  \
    } while (0)
#define EXPECT_MSG(c, ...)                                                                         \
    do {                                                                                           \
        if (!(c)) ck_abort_msg(__VA_ARGS__);                                                       \
    } while (0)
#define EXPECT_INT_EQ(a, b)                                                                        \
    do {                                                                                           \
        long long a_ = (a), b_ = (b);                                                              \
        if (a_ != b_) ck_abort_msg("%s == %lld, %s == %lld", #a, a_, #b, b_);                      \
    } while (0)
#define EXPECT_NEAR(a, b, tol) unit_near(__FILE__, __LINE__, #a, (a), (b), (tol))

static double sym(rng *r) { return 2 * rng_uniform(r) - 1; } /* uniform in [-1, 1) */

/* A random affine matrix M = T R S H: translation up to 10, any rotation, non-uniform scale
 * with factors in [0.1, 10] (a mirror half the time), and a shear H. */
static mat4 random_affine(rng *r)
{
    double a = pow(10, sym(r)) * (rng_uniform(r) < 0.5 ? -1 : 1);
    mat4 h = mat4_identity();
    h.m[0][1] = 0.5 * sym(r); /* a shear no product of T, R, S gives */
    mat4 m = mat4_translate(vec3_make(10 * sym(r), 10 * sym(r), 10 * sym(r)));
    m = mat4_mul(m, mat4_rotate(vec3_make(sym(r), sym(r), sym(r) + 0.1), 360 * rng_uniform(r)));
    m = mat4_mul(m, mat4_scale(vec3_make(a, pow(10, sym(r)), pow(10, sym(r)))));
    return mat4_mul(m, h);
}

START_TEST(test_transform_rotate_90_about_z_maps_x_to_y)
{
    mat4 r = mat4_rotate(vec3_make(0, 0, 1), 90);
    ck_vec_near(mat4_dir(&r, vec3_make(1, 0, 0)), vec3_make(0, 1, 0), 1e-15);
    ck_vec_near(mat4_dir(&r, vec3_make(0, 1, 0)), vec3_make(-1, 0, 0), 1e-15);
    ck_vec_near(mat4_dir(&r, vec3_make(0, 0, 1)), vec3_make(0, 0, 1), 1e-15);
    /* the axis need not be unit length: (0,0,5) is the same axis */
    mat4 r5 = mat4_rotate(vec3_make(0, 0, 5), 90);
    ck_vec_near(mat4_dir(&r5, vec3_make(1, 0, 0)), vec3_make(0, 1, 0), 1e-15);
}
END_TEST

START_TEST(test_transform_rotate_is_right_handed_about_x_and_y)
{
    /* right hand rule: about x, y goes to z; about y, z goes to x */
    mat4 rx = mat4_rotate(vec3_make(1, 0, 0), 90), ry = mat4_rotate(vec3_make(0, 1, 0), 90);
    ck_vec_near(mat4_dir(&rx, vec3_make(0, 1, 0)), vec3_make(0, 0, 1), 1e-15);
    ck_vec_near(mat4_dir(&ry, vec3_make(0, 0, 1)), vec3_make(1, 0, 0), 1e-15);
    /* rotate 1 0 0 -90 (FORMAT.md): the envmap's +z becomes the world's +y */
    mat4 env = mat4_rotate(vec3_make(1, 0, 0), -90);
    ck_vec_near(mat4_dir(&env, vec3_make(0, 0, 1)), vec3_make(0, 1, 0), 1e-15);
    /* 120 degrees about (1,1,1) cycles the axes x -> y -> z */
    mat4 c = mat4_rotate(vec3_make(1, 1, 1), 120);
    ck_vec_near(mat4_dir(&c, vec3_make(1, 0, 0)), vec3_make(0, 1, 0), 1e-15);
    ck_vec_near(mat4_dir(&c, vec3_make(0, 1, 0)), vec3_make(0, 0, 1), 1e-15);
}
END_TEST

START_TEST(test_transform_right_multiplication_applies_the_last_command_first)
{
    /* "translate 0 1 0" then "rotate 0 0 1 90" in a file: M = T R, p' = T (R p) */
    mat4 m = mat4_identity();
    m = mat4_mul(m, mat4_translate(vec3_make(0, 1, 0)));
    m = mat4_mul(m, mat4_rotate(vec3_make(0, 0, 1), 90));
    ck_vec_near(mat4_point(&m, vec3_make(1, 0, 0)), vec3_make(0, 2, 0), 1e-15);
    /* the other order would give R (T p) = R (1,1,0) = (-1,1,0) */
    mat4 rt = mat4_mul(mat4_rotate(vec3_make(0, 0, 1), 90), mat4_translate(vec3_make(0, 1, 0)));
    ck_vec_near(mat4_point(&rt, vec3_make(1, 0, 0)), vec3_make(-1, 1, 0), 1e-15);
    /* directions ignore the translation */
    ck_vec_near(mat4_dir(&m, vec3_make(1, 0, 0)), vec3_make(0, 1, 0), 1e-15);
    /* scale then translate: scale applies to the translation written after it */
    mat4 st = mat4_mul(mat4_scale(vec3_make(2, 3, 4)), mat4_translate(vec3_make(1, 1, 1)));
    ck_vec_near(mat4_point(&st, vec3_make(0, 0, 0)), vec3_make(2, 3, 4), 1e-15);
}
END_TEST

START_TEST(test_transform_transpose_swaps_rows_and_columns)
{
    mat4 a;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) a.m[i][j] = 10 * i + j;
    mat4 t = mat4_transpose(a);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) EXPECT(t.m[i][j] == a.m[j][i]);
}
END_TEST

START_TEST(test_transform_inverse_of_random_affine_matrices_is_exact)
{
    rng r;
    rng_seed(&r, 11, 0);
    for (int n = 0; n < 2000; n++) {
        mat4 m = random_affine(&r), inv;
        EXPECT_INT_EQ(mat4_inverse(m, &inv), 0);
        mat4 p = mat4_mul(m, inv), q = mat4_mul(inv, m);
        /* condition number <= ~1e3 and entries <= ~1e2: rounding leaves ~1e-13 */
        double tol = 1e-12;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                EXPECT_NEAR(p.m[i][j], i == j, tol);
                EXPECT_NEAR(q.m[i][j], i == j, tol);
            }
        EXPECT(inv.m[3][0] == 0 && inv.m[3][1] == 0 && inv.m[3][2] == 0 && inv.m[3][3] == 1);
    }
}
END_TEST

START_TEST(test_transform_inverse_of_simple_matrices_is_within_1e_12)
{
    mat4 m = mat4_mul(
             mat4_translate(vec3_make(1, -2, 3)),
             mat4_mul(mat4_rotate(vec3_make(1, 2, 3), 37), mat4_scale(vec3_make(2, 0.5, 3)))),
         inv;
    EXPECT_INT_EQ(mat4_inverse(m, &inv), 0);
    mat4 p = mat4_mul(m, inv);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) EXPECT_NEAR(p.m[i][j], i == j, 1e-12);
    /* a pure translation inverts exactly */
    mat4 t = mat4_translate(vec3_make(5, 6, 7)), ti;
    EXPECT_INT_EQ(mat4_inverse(t, &ti), 0);
    EXPECT(ti.m[0][3] == -5 && ti.m[1][3] == -6 && ti.m[2][3] == -7);
}
END_TEST

START_TEST(test_transform_singular_matrix_returns_minus_one_and_leaves_out_untouched)
{
    mat4 sentinel;
    memset(&sentinel, 0, sizeof sentinel);
    sentinel.m[1][2] = 42;
    mat4 out = sentinel;
    /* scale 0 along y: the usual way a scene makes a singular transform */
    EXPECT_INT_EQ(mat4_inverse(mat4_scale(vec3_make(1, 0, 1)), &out), -1);
    ck_assert_mem_eq(&out, &sentinel, sizeof out);
    /* rank 2 without a zero on the diagonal: rows 0 and 1 equal */
    mat4 m = mat4_identity();
    m.m[0][0] = m.m[0][1] = m.m[1][0] = m.m[1][1] = 1;
    EXPECT_INT_EQ(mat4_inverse(m, &out), -1);
    ck_assert_mem_eq(&out, &sentinel, sizeof out);
    /* NaN is not invertible either */
    mat4 nan = mat4_identity();
    nan.m[0][0] = NAN;
    EXPECT_INT_EQ(mat4_inverse(nan, &out), -1);
    ck_assert_mem_eq(&out, &sentinel, sizeof out);
    /* nor is an infinite entry (its pivot is not 0, but 1 / Inf = 0 would leave NaN behind) */
    mat4 inf = mat4_identity();
    inf.m[1][1] = INFINITY;
    EXPECT_INT_EQ(mat4_inverse(inf, &out), -1);
    ck_assert_mem_eq(&out, &sentinel, sizeof out);
}
END_TEST

START_TEST(test_transform_normal_stays_perpendicular_under_nonuniform_scale)
{
    rng r;
    rng_seed(&r, 12, 0);
    for (int n = 0; n < 2000; n++) {
        mat4 m = random_affine(&r), inv;
        EXPECT_INT_EQ(mat4_inverse(m, &inv), 0);
        vec3 nrm = vec3_normalize(vec3_make(sym(&r), sym(&r), sym(&r)));
        vec3 t0, t1;
        vec3_basis(nrm, &t0, &t1); /* two tangents of the surface */
        vec3 nw = vec3_normalize(mat4_normal(&inv, nrm));
        vec3 a = vec3_normalize(mat4_dir(&m, t0)), b = vec3_normalize(mat4_dir(&m, t1));
        EXPECT_NEAR(vec3_dot(nw, a), 0, 1e-9);
        EXPECT_NEAR(vec3_dot(nw, b), 0, 1e-9);
    }
    /* the known case: scale (2,1,1) turns the 45-degree normal (1,1,0) towards y: (1/2, 1, 0) */
    mat4 s = mat4_scale(vec3_make(2, 1, 1)), si;
    EXPECT_INT_EQ(mat4_inverse(s, &si), 0);
    vec3 n = mat4_normal(&si, vec3_make(1, 1, 0));
    ck_vec_near(n, vec3_make(0.5, 1, 0), 1e-15);
    /* the plain matrix would have given (2,1,0), which is not perpendicular */
    vec3 wrong = mat4_dir(&s, vec3_make(1, 1, 0));
    EXPECT(fabs(vec3_dot(vec3_normalize(wrong),
                         vec3_normalize(mat4_dir(&s, vec3_make(1, -1, 0))))) > 0.1);
}
END_TEST

/* det of the linear part is the volume factor: (M e1 x M e2) . M e3 = det(M) (e1 x e2) . e3
 * for any vectors, and its sign says whether M mirrors (the scene parser keeps triangles
 * counter-clockwise with it).  Catches a wrong cofactor sign or a translation column used. */
START_TEST(test_transform_det3_is_the_volume_factor_and_negative_for_mirrors)
{
    rng r;
    rng_seed(&r, 13, 0);
    for (int n = 0; n < 2000; n++) {
        mat4 m = random_affine(&r);
        vec3 e1 = vec3_make(sym(&r), sym(&r), sym(&r)), e2 = vec3_make(sym(&r), sym(&r), sym(&r));
        vec3 e3 = vec3_make(sym(&r), sym(&r), sym(&r));
        double before = vec3_dot(vec3_cross(e1, e2), e3);
        double after = vec3_dot(vec3_cross(mat4_dir(&m, e1), mat4_dir(&m, e2)), mat4_dir(&m, e3));
        double det = mat4_det3(&m);
        EXPECT_NEAR(after, det * before, 1e-9 * fmax(1, fabs(det)));
    }
    mat4 t = mat4_translate(vec3_make(5, 6, 7));
    EXPECT_NEAR(mat4_det3(&t), 1, 0);
    mat4 s = mat4_scale(vec3_make(-1, 2, 3));
    EXPECT_NEAR(mat4_det3(&s), -6, 0);
    mat4 rm = mat4_rotate(vec3_make(1, 2, 3), 77);
    EXPECT_NEAR(mat4_det3(&rm), 1, 1e-15);
}
END_TEST

/* Only the axis's direction counts: (1, 2, 3) scaled by 10^-300 .. 10^300 gives the same
 * rotation.  Catches a length from sqrt(x^2 + y^2 + z^2): it overflowed for 1e200 (axis 0, so
 * R = cos(t) I: `rotate 1e200 0 0 90` collapsed the object to a point) and lost bits for 1e-160
 * (subnormal squares: an error of 1e-5). */
START_TEST(test_transform_rotate_depends_only_on_the_axis_direction)
{
    mat4 ref = mat4_rotate(vec3_make(1, 2, 3), 77);
    for (int e = -300; e <= 300; e += 10) {
        double k = pow(10, e);
        mat4 r = mat4_rotate(vec3_make(k, 2 * k, 3 * k), 77);
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
                EXPECT_MSG(fabs(r.m[i][j] - ref.m[i][j]) <= 1e-15,
                           "axis scale 1e%d: m[%d][%d] = %.17g, expected %.17g", e, i, j, r.m[i][j],
                           ref.m[i][j]);
    }
}
END_TEST

Suite *transform_suite(void)
{
    Suite *s = suite_create("transform");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_transform_rotate_90_about_z_maps_x_to_y);
    tcase_add_test(tc, test_transform_rotate_is_right_handed_about_x_and_y);
    tcase_add_test(tc, test_transform_right_multiplication_applies_the_last_command_first);
    tcase_add_test(tc, test_transform_transpose_swaps_rows_and_columns);
    tcase_add_test(tc, test_transform_inverse_of_random_affine_matrices_is_exact);
    tcase_add_test(tc, test_transform_inverse_of_simple_matrices_is_within_1e_12);
    tcase_add_test(tc, test_transform_singular_matrix_returns_minus_one_and_leaves_out_untouched);
    tcase_add_test(tc, test_transform_normal_stays_perpendicular_under_nonuniform_scale);
    tcase_add_test(tc, test_transform_det3_is_the_volume_factor_and_negative_for_mirrors);
    tcase_add_test(tc, test_transform_rotate_depends_only_on_the_axis_direction);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(transform_suite)
