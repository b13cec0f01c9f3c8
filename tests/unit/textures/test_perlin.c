/* test_perlin.c - Improved Noise against Perlin's own numbers and an independent transcription of
 * his reference Java code; fbm, turbulence and their band-limited versions. */
#include "envtex/textures/perlin.h"

#include <stdint.h>

#include "unit.h"

/* ---- an independent reference: Perlin's Java ImprovedNoise, transcribed line by line, in long
 * double, with the lattice cell taken as (long long)floor(x) & 255 as Java's (int) would for
 * |x| < 2^31 (and correctly beyond, where Java's int would overflow). */
static const int ref_permutation[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103,
    30,  69,  142, 8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,
    197, 62,  94,  252, 219, 203, 117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174,
    20,  125, 136, 171, 168, 68,  175, 74,  165, 71,  134, 139, 48,  27,  166, 77,  146, 158, 231,
    83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,  55,  46,  245, 40,  244, 102, 143,
    54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,  18,  169, 200, 196,
    135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250, 124,
    123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,
    182, 189, 28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101,
    155, 167, 43,  172, 9,   129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185,
    112, 104, 218, 246, 97,  228, 251, 34,  242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,
    51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,  181, 199, 106, 157, 184, 84,  204, 176,
    115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114, 67,  29,  24,  72,  243,
    141, 128, 195, 78,  66,  215, 61,  156, 180};

static int ref_p(int i) { return ref_permutation[i & 255]; } /* p[i] = p[i + 256] */
static long double ref_fade(long double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
static long double ref_lerp(long double t, long double a, long double b) { return a + t * (b - a); }
static long double ref_grad(int hash, long double x, long double y, long double z)
{
    int h = hash & 15;
    long double u = h < 8 ? x : y, v = h < 4 ? y : h == 12 || h == 14 ? x : z;
    return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}
static double ref_noise(double xd, double yd, double zd)
{
    long double x = xd, y = yd, z = zd;
    int X = (int)((long long)floorl(x) & 255), Y = (int)((long long)floorl(y) & 255),
        Z = (int)((long long)floorl(z) & 255);
    x -= floorl(x);
    y -= floorl(y);
    z -= floorl(z);
    long double u = ref_fade(x), v = ref_fade(y), w = ref_fade(z);
    int A = ref_p(X) + Y, AA = ref_p(A) + Z, AB = ref_p(A + 1) + Z, B = ref_p(X + 1) + Y,
        BA = ref_p(B) + Z, BB = ref_p(B + 1) + Z;
    return (double)ref_lerp(
        w,
        ref_lerp(
            v, ref_lerp(u, ref_grad(ref_p(AA), x, y, z), ref_grad(ref_p(BA), x - 1, y, z)),
            ref_lerp(u, ref_grad(ref_p(AB), x, y - 1, z), ref_grad(ref_p(BB), x - 1, y - 1, z))),
        ref_lerp(v,
                 ref_lerp(u, ref_grad(ref_p(AA + 1), x, y, z - 1),
                          ref_grad(ref_p(BA + 1), x - 1, y, z - 1)),
                 ref_lerp(u, ref_grad(ref_p(AB + 1), x, y - 1, z - 1),
                          ref_grad(ref_p(BB + 1), x - 1, y - 1, z - 1))));
}

/* xorshift64: a fixed-seed stream of points, so the tests are deterministic (each test starts
 * the stream afresh, forked or not: see rng_restart) */
#define RNG_SEED 88172645463325252ULL
static uint64_t rng_state = RNG_SEED;
static void rng_restart(void) { rng_state = RNG_SEED; }
static double rng_uniform(double lo, double hi)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return lo + (hi - lo) * (double)(rng_state >> 11) * 0x1p-53;
}

/* Agreement with the reference: the two differ only by rounding (double vs long double). */
#define REF_TOL 1e-9

/* perlin_noise at (x, y, z) agrees with the reference; a failure names the point */
#define assert_matches_reference(x, y, z)                                                          \
    do {                                                                                           \
        double px_ = (x), py_ = (y), pz_ = (z), n_ = perlin_noise(px_, py_, pz_),                  \
               r_ = ref_noise(px_, py_, pz_);                                                      \
        ck_assert_msg(fabs(n_ - r_) <= REF_TOL,                                                    \
                      "perlin_noise(%.17g, %.17g, %.17g) = %.17g, Perlin's reference %.17g", px_,  \
                      py_, pz_, n_, r_);                                                           \
    } while (0)

START_TEST(test_noise_reproduces_perlins_published_value)
{
    /* Perlin's Java ImprovedNoise.noise(3.14, 42, 7) prints 0.13691995878400012 */
    ck_assert_near(perlin_noise(3.14, 42, 7), 0.13691995878400012, 1e-15);
    ck_assert_near(ref_noise(3.14, 42, 7), 0.13691995878400012, 1e-15);
}
END_TEST

START_TEST(test_noise_is_zero_at_every_integer_lattice_point)
{
    const double c[] = {0,    1,       -1,       7,      -13,         255,   256,
                        -256, 1000000, -1000000, 0x1p31, -0x1p31 - 1, 0x1p40};
    int n = (int)(sizeof c / sizeof c[0]);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) ck_assert(perlin_noise(c[i], c[j], c[(i + j) % n]) == 0.0);
}
END_TEST

START_TEST(test_noise_matches_the_reference_transcription_near_the_origin_and_negative)
{
    for (int i = 0; i < 5000; i++) {
        double x = rng_uniform(-300, 300), y = rng_uniform(-300, 300), z = rng_uniform(-300, 300);
        assert_matches_reference(x, y, z);
    }
    /* small negative coordinates, where truncation instead of floor picks the wrong cell */
    assert_matches_reference(-0.25, -0.5, -0.75);
    assert_matches_reference(-3.14, -42, -7);
    ck_assert(fabs(perlin_noise(-0.25, -0.5, -0.75)) > 1e-3); /* not trivially 0 */
}
END_TEST

START_TEST(test_noise_matches_the_reference_at_a_million_and_past_int_range)
{
    const double centres[] = {1e6, -1e6, 0x1p31, -0x1p31, 3e9, -3e9};
    for (int c = 0; c < 6; c++)
        for (int i = 0; i < 500; i++) {
            double x = centres[c] + rng_uniform(-2, 2), y = centres[5 - c] + rng_uniform(-2, 2);
            double z = rng_uniform(-2, 2) - centres[c];
            ck_assert(isfinite(perlin_noise(x, y, z)));
            assert_matches_reference(x, y, z);
        }
}
END_TEST

START_TEST(test_noise_is_finite_for_huge_coordinates_and_zero_for_non_finite_ones)
{
    ck_assert(isfinite(perlin_noise(1e15 + 0.5, -1e18, 1e300)));
    ck_assert(isfinite(perlin_noise(-1e300, 0.5, 0.25)));
    ck_assert(isfinite(perlin_noise(1e6 + 0.123456, -1e6 - 0.654321, 1e6 + 0.5)));
    ck_assert(perlin_noise(INFINITY, 0.5, 0.5) == 0.0);
    ck_assert(perlin_noise(0.5, -INFINITY, 0.5) == 0.0);
    ck_assert(perlin_noise(0.5, 0.5, NAN) == 0.0);
}
END_TEST

START_TEST(test_noise_is_continuous_across_cell_boundaries)
{
    /* The gradient of the noise is below 4, so points d either side of a cell wall differ by
     * less than 8 d; a wrong cell on either side (truncation instead of floor, a bad wrap at
     * 256 or at 2^31) jumps by orders of magnitude more. */
    const double walls[] = {0, 1, -1, -2, 255, 256, -256, 1e6, -1e6, 0x1p31, -0x1p31};
    for (int k = 0; k < 11; k++) {
        double b = walls[k];
        double d = fmax(1e-9, 4 * (nextafter(fabs(b), INFINITY) - fabs(b))); /* a few ulps */
        for (int i = 0; i < 50; i++) {
            double y = rng_uniform(-10, 10), z = rng_uniform(-10, 10);
            ck_assert_near(perlin_noise(b - d, y, z), perlin_noise(b + d, y, z), 8 * d);
            ck_assert_near(perlin_noise(y, b - d, z), perlin_noise(y, b + d, z), 8 * d);
            ck_assert_near(perlin_noise(z, y, b - d), perlin_noise(z, y, b + d), 8 * d);
        }
    }
}
END_TEST

START_TEST(test_noise_stays_in_its_bound_and_uses_the_range)
{
    double lo = 0, hi = 0;
    for (int i = 0; i < 30000; i++) {
        double n = perlin_noise(rng_uniform(0, 256), rng_uniform(0, 256), rng_uniform(0, 256));
        ck_assert(fabs(n) <= PERLIN_NOISE_BOUND);
        lo = fmin(lo, n);
        hi = fmax(hi, n);
    }
    ck_assert(lo < -0.8 && hi > 0.8); /* not accidentally scaled down */
}
END_TEST

START_TEST(test_noise_has_period_256)
{
    for (int i = 0; i < 200; i++) {
        double x = rng_uniform(-5, 5), y = rng_uniform(-5, 5), z = rng_uniform(-5, 5);
        double n = perlin_noise(x, y, z);
        ck_assert_near(perlin_noise(x + 256, y, z), n, 1e-12);
        ck_assert_near(perlin_noise(x, y - 256, z), n, 1e-12);
        ck_assert_near(perlin_noise(x, y, z + 512), n, 1e-12);
    }
}
END_TEST

START_TEST(test_mean_abs_constant_matches_a_fresh_measurement)
{
    double sum = 0;
    const int n = 50000; /* standard error of the mean about 7e-4 */
    for (int i = 0; i < n; i++)
        sum += fabs(perlin_noise(rng_uniform(0, 256), rng_uniform(0, 256), rng_uniform(0, 256)));
    ck_assert_near(sum / n, PERLIN_MEAN_ABS, 3e-3);
}
END_TEST

START_TEST(test_fbm_and_turbulence_sum_scaled_octaves)
{
    vec3 p = {0.3, -1.7, 2.45};
    double fbm = 0, turb = 0, amp = 1, f = 1;
    for (int i = 0; i < 5; i++, amp *= 0.6, f *= 2.1) {
        double n = perlin_noise(p.x * f, p.y * f, p.z * f);
        fbm += amp * n;
        turb += amp * fabs(n);
    }
    ck_assert_near(perlin_fbm(p, 5, 2.1, 0.6), fbm, 1e-14);
    ck_assert_near(perlin_turbulence(p, 5, 2.1, 0.6), turb, 1e-14);
    ck_assert(perlin_fbm(p, 1, 2.0, 0.5) == perlin_noise(p.x, p.y, p.z));
}
END_TEST

START_TEST(test_octave_counts_out_of_range_are_clamped)
{
    vec3 p = {0.3, 0.6, 0.9};
    ck_assert(perlin_fbm(p, 0, 2, 0.5) == 0.0);
    ck_assert(perlin_fbm(p, -5, 2, 0.5) == 0.0);
    ck_assert(perlin_turbulence(p, -5, 2, 0.5) == 0.0);
    ck_assert(perlin_fbm(p, 1 << 30, 2, 0.5) == perlin_fbm(p, PERLIN_MAX_OCTAVES, 2, 0.5));
}
END_TEST

START_TEST(test_filtered_fbm_with_zero_footprint_is_fbm)
{
    for (int i = 0; i < 100; i++) {
        vec3 p = {rng_uniform(-9, 9), rng_uniform(-9, 9), rng_uniform(-9, 9)};
        ck_assert(perlin_fbm_filtered(p, 0.0, 6, 2, 0.5) == perlin_fbm(p, 6, 2, 0.5));
        ck_assert(perlin_fbm_filtered(p, -1.0, 6, 2, 0.5) == perlin_fbm(p, 6, 2, 0.5));
        ck_assert(perlin_fbm_filtered(p, NAN, 6, 2, 0.5) == perlin_fbm(p, 6, 2, 0.5));
        /* a footprint far below the finest octave's lattice (2^-5 / 2) changes nothing */
        ck_assert(perlin_fbm_filtered(p, 0.01, 6, 2, 0.5) == perlin_fbm(p, 6, 2, 0.5));
    }
}
END_TEST

START_TEST(test_filtered_fbm_fades_the_octaves_past_nyquist_by_smoothstep)
{
    /* w = 0.3, lacunarity 2: f w = 0.3 (kept), 0.6 (faded), 1.2, 2.4 (gone) */
    vec3 p = {0.37, 1.21, -0.58};
    double t = (2 * 0.3 - 0.5) * 2, a1 = 1 - t * t * (3 - 2 * t);
    double n0 = perlin_noise(p.x, p.y, p.z), n1 = perlin_noise(2 * p.x, 2 * p.y, 2 * p.z);
    ck_assert_near(perlin_fbm_filtered(p, 0.3, 4, 2, 0.5), n0 + 0.5 * a1 * n1, 1e-14);
    double m = PERLIN_MEAN_ABS;
    ck_assert_near(perlin_turbulence_filtered(p, 0.3, 4, 2, 0.5),
                   fabs(n0) + 0.5 * (a1 * fabs(n1) + (1 - a1) * m) + 0.25 * m + 0.125 * m, 1e-14);
}
END_TEST

START_TEST(test_filtered_fbm_is_its_mean_when_the_footprint_exceeds_every_octave)
{
    vec3 p = {0.37, 1.21, -0.58};
    ck_assert(perlin_fbm_filtered(p, 1.0, 6, 2, 0.5) == 0.0);
    ck_assert(perlin_fbm_filtered(p, 1e9, 6, 2, 0.5) == 0.0);
    double mean = PERLIN_MEAN_ABS * (1 - pow(0.5, 6)) / (1 - 0.5); /* sum_i 0.5^i E|n| */
    ck_assert_near(perlin_turbulence_filtered(p, 5.0, 6, 2, 0.5), mean, 1e-14);
}
END_TEST

START_TEST(test_filtered_fbm_is_continuous_in_the_footprint)
{
    /* Each octave's weight has slope at most 3 f_i per unit footprint, so a step dw moves the
     * sum by at most 6 octaves * 3 * PERLIN_NOISE_BOUND * dw (gain 1/2 cancels lacunarity 2);
     * dropping octave i abruptly (a pop) near w = 1 / f_i would jump by 2^-i |n_i|, about 30
     * times more.  Footprints step geometrically from 2^-7 to 2 (every octave fades in there). */
    const double ratio = exp2(2e-3);
    vec3 pts[3] = {{0.37, 1.21, -0.58}, {-4.1, 0.2, 7.7}, {12.6, -3.3, 0.9}};
    for (int k = 0; k < 3; k++) {
        double w = 0x1p-7;
        double prev = perlin_fbm_filtered(pts[k], w, 6, 2, 0.5);
        double prev_t = perlin_turbulence_filtered(pts[k], w, 6, 2, 0.5);
        for (; w < 2.0; w *= ratio) {
            double next = w * ratio, limit = 6 * 3 * PERLIN_NOISE_BOUND * (next - w) * 1.01;
            double v = perlin_fbm_filtered(pts[k], next, 6, 2, 0.5);
            double vt = perlin_turbulence_filtered(pts[k], next, 6, 2, 0.5);
            ck_assert_msg(fabs(v - prev) <= limit, "fbm jumps by %g at footprint %g", v - prev,
                          next);
            ck_assert_msg(fabs(vt - prev_t) <= limit, "turbulence jumps by %g at %g", vt - prev_t,
                          next);
            prev = v;
            prev_t = vt;
        }
    }
}
END_TEST

START_TEST(test_marble_and_wood_follow_their_formulas_and_stay_in_range)
{
    for (int i = 0; i < 2000; i++) {
        vec3 p = {rng_uniform(-50, 50), rng_uniform(-50, 50), rng_uniform(-50, 50)};
        double m = perlin_marble(p, 4, 8, 6), w = perlin_wood(p, 8, 0.5);
        ck_assert(m >= 0 && m <= 1);
        ck_assert(w >= 0 && w < 1);
        double turb = perlin_turbulence(p, 6, 2, 0.5);
        ck_assert_near(m, 0.5 + 0.5 * sin(4 * p.x + 8 * turb), 1e-12);
        double v = 8 * sqrt(p.x * p.x + p.z * p.z) + 0.5 * perlin_noise(p.x, p.y, p.z);
        ck_assert_near(w, v - floor(v), 1e-12);
    }
    /* without noise the rings are exact circles about the y axis */
    ck_assert_near(perlin_wood(vec3_make(0.3, 5, 0.4), 2, 0), 0.0, 1e-12); /* 2 * 0.5 = 1 */
    ck_assert_near(perlin_wood(vec3_make(0, -9, 0.3), 5, 0), 0.5, 1e-12);
    ck_assert_near(perlin_marble(vec3_make(M_PI / 8, 3, 3), 4, 0, 6), 1.0, 1e-12);
    /* a ring fraction that rounds up to 1 is kept below 1, and next to its true value
     * v - floor(v) = 1 - 1e-17 (not wrapped round to 0, the far end of the ring) */
    double f = perlin_wood(vec3_make(0, 0, -1e-17), -1, 0);
    ck_assert(f < 1.0);
    ck_assert_near(f, 1.0, 1e-15);
}
END_TEST

/* Marble's phase frequency * x + amplitude * turbulence overflows for parameters the parser
 * accepts (frequency 1e200 at x = 1e200, frequency 1.8e308 at x = 2, amplitude 1.8e308 times a
 * turbulence above 1, 0 * Inf at an infinite x), and sin(Inf) and sin(NaN) are NaN.  The veins
 * are then far finer than the doubles can place: marble is their mean, exactly 0.5.  Finite
 * phases keep the formula (sin(1e200 * 0.3) is noise, but finite).  Catches the phase passed to
 * sin unchecked (NaN). */
START_TEST(test_marble_is_its_mean_where_its_phase_overflows)
{
    const double big = 1.7976931348623157e308;
    ck_assert(perlin_marble(vec3_make(1e200, 0.3, 0.2), 1e200, 0, 6) == 0.5);
    ck_assert(perlin_marble(vec3_make(-1e200, 0.3, 0.2), 1e200, 8, 6) == 0.5);
    ck_assert(perlin_marble(vec3_make(2, 0.3, 0.2), big, 8, 6) == 0.5);
    ck_assert(perlin_marble(vec3_make(INFINITY, 0.3, 0.2), 0, 8, 6) == 0.5); /* 0 * Inf */
    ck_assert(perlin_marble(vec3_make(2, 0.3, 0.2), big, -big, 30) == 0.5);  /* Inf, or Inf - Inf */
    int overflowed = 0;
    for (int i = 0; i < 2000; i++) {
        vec3 p = {rng_uniform(-50, 50), rng_uniform(-50, 50), rng_uniform(-50, 50)};
        double turb = perlin_turbulence(p, 6, 2, 0.5), m = perlin_marble(p, 4, big, 6);
        if (isfinite(4 * p.x + big * turb)) {
            ck_assert_near(m, 0.5 + 0.5 * sin(4 * p.x + big * turb), 1e-12);
        } else {
            overflowed++;
            ck_assert(m == 0.5);
        }
        m = perlin_marble(p, 1e200, 8, 6);
        ck_assert(isfinite(m) && m >= 0 && m <= 1);
    }
    ck_assert_int_gt(overflowed, 0); /* the loop reached amplitude * turbulence = Inf */
}
END_TEST

Suite *perlin_suite(void)
{
    Suite *s = suite_create("perlin");
    TCase *tc = tcase_create("core");
    tcase_add_checked_fixture(tc, rng_restart, NULL);
    tcase_add_test(tc, test_noise_reproduces_perlins_published_value);
    tcase_add_test(tc, test_noise_is_zero_at_every_integer_lattice_point);
    tcase_add_test(tc, test_noise_matches_the_reference_transcription_near_the_origin_and_negative);
    tcase_add_test(tc, test_noise_matches_the_reference_at_a_million_and_past_int_range);
    tcase_add_test(tc, test_noise_is_finite_for_huge_coordinates_and_zero_for_non_finite_ones);
    tcase_add_test(tc, test_noise_is_continuous_across_cell_boundaries);
    tcase_add_test(tc, test_noise_stays_in_its_bound_and_uses_the_range);
    tcase_add_test(tc, test_noise_has_period_256);
    tcase_add_test(tc, test_mean_abs_constant_matches_a_fresh_measurement);
    tcase_add_test(tc, test_fbm_and_turbulence_sum_scaled_octaves);
    tcase_add_test(tc, test_octave_counts_out_of_range_are_clamped);
    tcase_add_test(tc, test_filtered_fbm_with_zero_footprint_is_fbm);
    tcase_add_test(tc, test_filtered_fbm_fades_the_octaves_past_nyquist_by_smoothstep);
    tcase_add_test(tc, test_filtered_fbm_is_its_mean_when_the_footprint_exceeds_every_octave);
    tcase_add_test(tc, test_filtered_fbm_is_continuous_in_the_footprint);
    tcase_add_test(tc, test_marble_and_wood_follow_their_formulas_and_stay_in_range);
    tcase_add_test(tc, test_marble_is_its_mean_where_its_phase_overflows);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(perlin_suite)
