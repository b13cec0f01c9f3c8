/* test_vec.c - the inline vector maths: cross / dot / reflect identities and the orthonormal
 * basis of Duff et al., including n = (0,0,-1) where the naive formula divides by zero. */
#include "envtex/core/vec.h"

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

/* A uniformly distributed unit vector (z uniform in [-1,1], phi uniform). */
static vec3 random_unit(rng *r)
{
    double z = 2 * rng_uniform(r) - 1, phi = 2 * M_PI * rng_uniform(r);
    double s = sqrt(fmax(0.0, 1 - z * z));
    return vec3_make(s * cos(phi), s * sin(phi), z);
}

#define assert_orthonormal(n, t, b, tol) orthonormal_at(__FILE__, __LINE__, n, t, b, tol)
static void orthonormal_at(const char *file, int line, vec3 n, vec3 t, vec3 b, double tol)
{
    unit_near(file, line, "|t|", vec3_length(t), 1, tol);
    unit_near(file, line, "|b|", vec3_length(b), 1, tol);
    unit_near(file, line, "t . b", vec3_dot(t, b), 0, tol);
    unit_near(file, line, "t . n", vec3_dot(t, n), 0, tol);
    unit_near(file, line, "b . n", vec3_dot(b, n), 0, tol);
    /* right-handed: t x b = n */
    unit_vec_near(file, line, "t x b (n)", vec3_cross(t, b), n, tol);
}

START_TEST(test_vec_cross_of_x_and_y_is_z_and_anticommutes)
{
    vec3 z = vec3_cross(vec3_make(1, 0, 0), vec3_make(0, 1, 0));
    EXPECT(z.x == 0 && z.y == 0 && z.z == 1);
    vec3 x = vec3_cross(vec3_make(0, 1, 0), vec3_make(0, 0, 1));
    EXPECT(x.x == 1 && x.y == 0 && x.z == 0);
    vec3 y = vec3_cross(vec3_make(0, 0, 1), vec3_make(1, 0, 0));
    EXPECT(y.x == 0 && y.y == 1 && y.z == 0);
    rng r;
    rng_seed(&r, 1, 0);
    for (int i = 0; i < 1000; i++) {
        vec3 a = vec3_scale(random_unit(&r), 3), b = random_unit(&r);
        vec3 c = vec3_cross(a, b), d = vec3_cross(b, a);
        EXPECT(c.x == -d.x && c.y == -d.y && c.z == -d.z);
        EXPECT_NEAR(vec3_dot(c, a), 0, 1e-14); /* perpendicular to both */
        EXPECT_NEAR(vec3_dot(c, b), 0, 1e-14);
        /* |a x b|^2 + (a.b)^2 = |a|^2 |b|^2 (Lagrange) */
        EXPECT_NEAR(vec3_length2(c) + pow(vec3_dot(a, b), 2), vec3_length2(a) * vec3_length2(b),
                    1e-13);
    }
}
END_TEST

START_TEST(test_vec_reflect_mirrors_about_the_normal_and_keeps_length)
{
    /* a ray going down onto the floor bounces up: (1,-1,0) -> (1,1,0) */
    vec3 r0 = vec3_reflect(vec3_make(1, -1, 0), vec3_make(0, 1, 0));
    EXPECT(r0.x == 1 && r0.y == 1 && r0.z == 0);
    rng r;
    rng_seed(&r, 2, 0);
    for (int i = 0; i < 1000; i++) {
        vec3 d = random_unit(&r), n = random_unit(&r);
        vec3 m = vec3_reflect(d, n);
        EXPECT_NEAR(vec3_length(m), 1, 1e-14);
        EXPECT_NEAR(vec3_dot(m, n), -vec3_dot(d, n), 1e-14); /* normal part flips */
        vec3 back = vec3_reflect(m, n);                      /* an involution */
        EXPECT_NEAR(back.x, d.x, 1e-14);
        EXPECT_NEAR(back.y, d.y, 1e-14);
        EXPECT_NEAR(back.z, d.z, 1e-14);
    }
}
END_TEST

START_TEST(test_vec_normalize_leaves_zero_alone_and_makes_unit_length)
{
    vec3 z = vec3_normalize(vec3_make(0, 0, 0));
    EXPECT(z.x == 0 && z.y == 0 && z.z == 0);
    vec3 n = vec3_normalize(vec3_make(3, 0, 4));
    EXPECT_NEAR(n.x, 0.6, 1e-15);
    EXPECT_NEAR(n.z, 0.8, 1e-15);
    EXPECT(vec3_max_abs(vec3_make(-5, 2, 3)) == 5);
    EXPECT(!vec3_is_finite(vec3_make(0, NAN, 0)));
    EXPECT(!rgb_is_finite(rgb_make(0, 0, INFINITY)));
    EXPECT(vec3_get(vec3_make(1, 2, 3), 2) == 3);
}
END_TEST

START_TEST(test_vec_basis_is_orthonormal_for_many_normals)
{
    rng r;
    rng_seed(&r, 3, 0);
    for (int i = 0; i < 100000; i++) {
        vec3 n = random_unit(&r), t, b;
        vec3_basis(n, &t, &b);
        assert_orthonormal(n, t, b, 1e-12);
    }
}
END_TEST

START_TEST(test_vec_basis_is_orthonormal_at_and_near_the_south_pole)
{
    /* n.z = -1 is where 1 / (1 + n.z) of the original Frisvad formula blows up */
    const double eps[] = {0, 1e-300, 1e-30, 1e-16, 1e-12, 1e-8, 1e-4};
    for (unsigned i = 0; i < sizeof eps / sizeof eps[0]; i++)
        for (int k = 0; k < 8; k++) {
            double phi = k * M_PI / 4;
            double s = sin(eps[i]);
            vec3 ns[2] = {vec3_make(s * cos(phi), s * sin(phi), -cos(eps[i])),
                          vec3_make(s * cos(phi), s * sin(phi), cos(eps[i]))};
            for (int j = 0; j < 2; j++) {
                vec3 t, b;
                vec3_basis(ns[j], &t, &b);
                assert_orthonormal(ns[j], t, b, 1e-12);
            }
        }
    vec3 t, b;
    vec3_basis(vec3_make(0, 0, -0.0), &t, &b); /* not unit, but must stay finite */
    EXPECT(vec3_is_finite(t) && vec3_is_finite(b));
    vec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
    for (int i = 0; i < 4; i++) {
        vec3_basis(axes[i], &t, &b);
        assert_orthonormal(axes[i], t, b, 1e-15);
    }
}
END_TEST

START_TEST(test_rgb_helpers_work_channel_by_channel)
{
    rgb a = rgb_make(1, 2, 3), k = rgb_make(0.5, 0.25, 2);
    rgb m = rgb_mul(a, k);
    EXPECT(m.r == 0.5 && m.g == 0.5 && m.b == 6);
    rgb f = rgb_fma(a, k, a); /* a + k a */
    EXPECT(f.r == 1.5 && f.g == 2.5 && f.b == 9);
    EXPECT(rgb_avg(a) == 2 && rgb_max(a) == 3);
    EXPECT(rgb_is_black(rgb_gray(0)) && !rgb_is_black(rgb_make(0, 0, 1e-300)));
    EXPECT_NEAR(rgb_luminance(rgb_gray(1)), 1, 1e-15); /* weights sum to one */
}
END_TEST

Suite *vec_suite(void)
{
    Suite *s = suite_create("vec");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_vec_cross_of_x_and_y_is_z_and_anticommutes);
    tcase_add_test(tc, test_vec_reflect_mirrors_about_the_normal_and_keeps_length);
    tcase_add_test(tc, test_vec_normalize_leaves_zero_alone_and_makes_unit_length);
    tcase_add_test(tc, test_vec_basis_is_orthonormal_for_many_normals);
    tcase_add_test(tc, test_vec_basis_is_orthonormal_at_and_near_the_south_pole);
    tcase_add_test(tc, test_rgb_helpers_work_channel_by_channel);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(vec_suite)
