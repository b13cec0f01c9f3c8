/* test_simd.c - simd.h's lanes compute what the same float expression computes lane by lane:
 * min and max as a < b ? a : b and a > b ? a : b (so the second operand where either is NaN,
 * which the BVH's slab tests rely on), |a|, and the mask of a comparison's lanes.  Built twice:
 * as it is (SSE on x86-64) and as test_simd_generic (ENVTEX_NO_SSE: the lane-by-lane code that
 * other processors run). */
#include "envtex/core/simd.h"

#include <math.h>
#include <string.h>

#include "unit.h"

static const float special[] = {0.0f,     -0.0f,     1.0f, -1.0f, 0x1p-149f, -3.5f,
                                INFINITY, -INFINITY, NAN,  2.5f,  1e30f,     -1e-30f};
#define N_SPECIAL ((int)(sizeof special / sizeof special[0]))

static int same_bits(float a, float b) { return memcmp(&a, &b, sizeof a) == 0; }

START_TEST(test_simd_min_and_max_are_the_c_conditional_lane_by_lane)
{
    for (int i = 0; i < N_SPECIAL; i++)
        for (int j = 0; j < N_SPECIAL; j++) {
            float a = special[i], b = special[j];
            f4 va = {a, b, a, b}, vb = {b, a, a, b};
            f4 mn = f4_min(va, vb), mx = f4_max(va, vb);
            for (int l = 0; l < 4; l++) {
                float x = va[l], y = vb[l];
                ck_require_msg(same_bits(mn[l], x < y ? x : y), "min(%g, %g) lane %d", x, y, l);
                ck_require_msg(same_bits(mx[l], x > y ? x : y), "max(%g, %g) lane %d", x, y, l);
            }
        }
}
END_TEST

START_TEST(test_simd_abs_clears_only_the_sign)
{
    for (int i = 0; i + 3 < N_SPECIAL; i++) {
        f4 v = {special[i], special[i + 1], special[i + 2], special[i + 3]}, a = f4_abs(v);
        for (int l = 0; l < 4; l++) ck_require(same_bits(a[l], fabsf(v[l])) || isnan(v[l]));
    }
}
END_TEST

START_TEST(test_simd_mask_has_a_bit_for_each_true_lane)
{
    for (int m = 0; m < 16; m++) {
        f4 a = f4_set(0), b = {m & 1 ? 1.0f : -1.0f, m & 2 ? 1.0f : -1.0f, m & 4 ? 1.0f : NAN,
                               m & 8 ? INFINITY : -0.0f};
        ck_assert_int_eq(f4_mask(a < b), m);
        ck_assert_int_eq(f4_mask(a >= b), 15 & ~m & ~4); /* lane 2: 0 >= 1, 0 >= NaN: false */
    }
    ck_assert_int_eq(f4_mask(f4_set(1) == f4_set(1)), 15);
    ck_assert_int_eq(f4_mask(f4_set(1) != f4_set(1)), 0);
}
END_TEST

Suite *simd_suite(void)
{
    Suite *s = suite_create(SIMD_SSE ? "simd (SSE)" : "simd (lane by lane)");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_simd_min_and_max_are_the_c_conditional_lane_by_lane);
    tcase_add_test(tc, test_simd_abs_clears_only_the_sign);
    tcase_add_test(tc, test_simd_mask_has_a_bit_for_each_true_lane);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(simd_suite)
