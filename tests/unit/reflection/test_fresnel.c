/* test_fresnel.c - exact dielectric Fresnel reflectance and Snell refraction: known values at
 * normal and grazing incidence, total internal reflection beyond the critical angle, Snell's law
 * and unit length of the refracted ray, F in [0, 1]. */
#include "envtex/reflection/fresnel.h"

#include "envtex/core/rng.h"
#include "unit.h"

#define EXPECT_NEAR(a, b, tol) unit_near(__FILE__, __LINE__, #a, (a), (b), (tol))

START_TEST(test_fresnel_at_normal_incidence_is_f0)
{
    const double etas[] = {1.0, 1.33, 1.5, 2.4, 1 / 1.5};
    for (unsigned i = 0; i < sizeof etas / sizeof etas[0]; i++) {
        double e = etas[i], f0 = ((e - 1) / (e + 1)) * ((e - 1) / (e + 1));
        ck_assert_near(fresnel_dielectric(1.0, e), f0, 1e-15);
    }
    ck_assert_near(fresnel_dielectric(1.0, 1.5), 0.04, 1e-15); /* glass: 4 percent */
    /* no interface, no reflection: exact Fresnel gives 0, Schlick's approximation (1 - cos)^5 */
    ck_assert_msg(
        fresnel_dielectric(0.7, 1.0) == 0,
        "fresnel_dielectric(0.7, 1.0) = %g: with eta = 1 there is no interface, and the exact "
        "Fresnel term of fresnel.h is 0 (Schlick's approximation gives (1 - cos)^5 = 0.00243)",
        fresnel_dielectric(0.7, 1.0));
}
END_TEST

START_TEST(test_fresnel_goes_to_one_at_grazing_incidence)
{
    ck_assert_near(fresnel_dielectric(0.0, 1.5), 1, 1e-15);
    ck_assert(fresnel_dielectric(1e-3, 1.5) > 0.99);
    /* rising monotonically from normal to grazing (entering a denser medium) */
    double prev = fresnel_dielectric(1.0, 1.5);
    for (int i = 999; i >= 0; i--) {
        double f = fresnel_dielectric(i / 1000.0, 1.5);
        if (i < 900 && !(f > prev)) ck_abort_msg("F not increasing at cos_i = %g", i / 1000.0);
        prev = f;
    }
}
END_TEST

START_TEST(test_fresnel_matches_the_textbook_value_at_45_degrees)
{
    /* glass, 45 degrees: sin_t = sin 45 / 1.5; R_s, R_p from the Fresnel equations */
    double ci = cos(M_PI / 4), st = sin(M_PI / 4) / 1.5, ct = sqrt(1 - st * st);
    double rs = (ci - 1.5 * ct) / (ci + 1.5 * ct), rp = (1.5 * ci - ct) / (1.5 * ci + ct);
    ck_assert_near(fresnel_dielectric(ci, 1.5), 0.5 * (rs * rs + rp * rp), 1e-15);
    ck_assert_near(fresnel_dielectric(ci, 1.5), 0.0502, 1e-4); /* 5.0 percent, the tables' value */
    /* Brewster's angle tan(theta_B) = eta: R_p = 0, so F = R_s / 2 */
    double cb = cos(atan(1.5));
    double sb = sin(atan(1.5)) / 1.5, cbt = sqrt(1 - sb * sb);
    double rsb = (cb - 1.5 * cbt) / (cb + 1.5 * cbt);
    ck_assert_near(fresnel_dielectric(cb, 1.5), 0.5 * rsb * rsb, 1e-15);
}
END_TEST

START_TEST(test_fresnel_total_internal_reflection_beyond_the_critical_angle)
{
    /* inside glass: eta = 1 / 1.5; critical angle sin(theta_c) = 1 / 1.5 */
    double eta = 1 / 1.5, sc = 1 / 1.5, cc = sqrt(1 - sc * sc);
    ck_assert(fresnel_dielectric(cc - 1e-6, eta) == 1);
    ck_assert(fresnel_dielectric(0.1, eta) == 1);
    ck_assert(fresnel_dielectric(cc + 1e-3, eta) < 1);
    ck_assert_near(fresnel_dielectric(1.0, eta), 0.04, 1e-15); /* same 4 percent from inside */
    /* and refraction reports it */
    vec3 n = vec3_make(0, 0, 1), t;
    double s = sqrt(1 - (cc - 1e-6) * (cc - 1e-6));
    vec3 d = vec3_make(s, 0, -(cc - 1e-6));
    ck_assert_int_eq(fresnel_refract(d, n, eta, &t), 0);
    s = sqrt(1 - (cc + 1e-3) * (cc + 1e-3));
    d = vec3_make(s, 0, -(cc + 1e-3));
    ck_assert_int_eq(fresnel_refract(d, n, eta, &t), 1);
}
END_TEST

START_TEST(test_fresnel_refract_obeys_snell_and_stays_unit)
{
    rng g;
    rng_seed(&g, 61, 0);
    const double etas[] = {1.5, 1.33, 2.4, 1 / 1.5, 1.0};
    for (unsigned k = 0; k < sizeof etas / sizeof etas[0]; k++)
        for (int i = 0; i < 20000; i++) {
            /* random normal, random incident direction against it */
            double z = 2 * rng_uniform(&g) - 1, phi = 2 * M_PI * rng_uniform(&g),
                   sz = sqrt(1 - z * z);
            vec3 n = vec3_make(sz * cos(phi), sz * sin(phi), z);
            z = 2 * rng_uniform(&g) - 1, phi = 2 * M_PI * rng_uniform(&g), sz = sqrt(1 - z * z);
            vec3 d = vec3_make(sz * cos(phi), sz * sin(phi), z);
            if (vec3_dot(d, n) > 0) d = vec3_neg(d);
            if (vec3_dot(d, n) > -1e-6) continue;
            vec3 t;
            double cos_i = -vec3_dot(d, n), sin_i = sqrt(fmax(0, 1 - cos_i * cos_i));
            int ok = fresnel_refract(d, n, etas[k], &t);
            if (sin_i / etas[k] > 1 + 1e-12 && ok)
                ck_abort_msg("refracted beyond the critical angle");
            if (sin_i / etas[k] < 1 - 1e-12 && !ok)
                ck_abort_msg("no refraction below the critical angle");
            if (!ok) continue;
            EXPECT_NEAR(vec3_length(t), 1, 1e-14);
            double cos_t = -vec3_dot(t, n), sin_t = vec3_length(vec3_cross(t, n));
            if (!(cos_t > 0)) ck_abort_msg("refracted ray does not cross the surface");
            EXPECT_NEAR(sin_i, etas[k] * sin_t, 1e-12); /* Snell: sin_i = eta sin_t */
            /* coplanar with d and n */
            EXPECT_NEAR(vec3_dot(t, vec3_cross(d, n)), 0, 1e-12);
            /* F is a fraction */
            double f = fresnel_dielectric(cos_i, etas[k]);
            if (!(f >= 0 && f <= 1)) ck_abort_msg("F = %g out of [0, 1]", f);
        }
    /* eta = 1: straight through */
    vec3 t, d = vec3_normalize(vec3_make(1, 2, -3));
    ck_assert_int_eq(fresnel_refract(d, vec3_make(0, 0, 1), 1.0, &t), 1);
    ck_assert_near(t.x, d.x, 1e-15);
    ck_assert_near(t.z, d.z, 1e-15);
}
END_TEST

START_TEST(test_fresnel_is_a_fraction_even_for_out_of_range_cosines)
{
    /* cos_i outside [0, 1] (rounding in a caller's dot product) is clamped, never NaN */
    const double cs[] = {-0.5, -1e-17, 0, 1e-300, 0.5, 1, 1 + 1e-15, 2};
    const double etas[] = {1.5, 1 / 1.5, 1.0, 10};
    for (unsigned i = 0; i < sizeof cs / sizeof cs[0]; i++)
        for (unsigned k = 0; k < sizeof etas / sizeof etas[0]; k++) {
            double f = fresnel_dielectric(cs[i], etas[k]);
            ck_assert_msg(f >= 0 && f <= 1, "F(%g, %g) = %g", cs[i], etas[k], f);
        }
}
END_TEST

Suite *fresnel_suite(void)
{
    Suite *s = suite_create("fresnel");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_fresnel_at_normal_incidence_is_f0);
    tcase_add_test(tc, test_fresnel_goes_to_one_at_grazing_incidence);
    tcase_add_test(tc, test_fresnel_matches_the_textbook_value_at_45_degrees);
    tcase_add_test(tc, test_fresnel_total_internal_reflection_beyond_the_critical_angle);
    tcase_add_test(tc, test_fresnel_refract_obeys_snell_and_stays_unit);
    tcase_add_test(tc, test_fresnel_is_a_fraction_even_for_out_of_range_cosines);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(fresnel_suite)
