/* test_budget.c - the memory budget: charges within the limit pass, a charge beyond it is
 * refused with one message that names the file, the claim and the budget, and nothing is charged;
 * sizes are printed and parsed as a person writes them. */
#include <math.h>
#include <string.h>

#include "envtex/core/budget.h"
#include "unit.h"

#define MiB (1024.0 * 1024.0)
#define GiB (1024.0 * MiB)

START_TEST(test_charges_within_the_limit_pass_and_are_released)
{
    budget b;
    budget_init(&b, 100);
    error err = {0};
    ck_assert_int_eq(budget_charge(&b, 60, "a.png", 0, &err, "a"), 0);
    ck_assert_int_eq(budget_charge(&b, 40, "a.png", 0, &err, "b"), 0); /* exactly the limit */
    ck_assert(b.used == 100);
    budget_release(&b, 30);
    ck_assert(b.used == 70);
    ck_assert(b.peak == 100);
    budget_release(&b, 1000); /* more than was charged: never below 0 */
    ck_assert(b.used == 0);
    ck_assert_str_eq(err.msg, "");
}
END_TEST

START_TEST(test_a_charge_beyond_the_limit_is_refused_with_the_file_claim_and_budget)
{
    budget b;
    budget_init(&b, 2 * GiB);
    error err = {0};
    ck_assert_int_eq(budget_charge(&b, 16384.0 * 16384 * 15, "bomb.png", 0, &err,
                                   "%d x %d texels x %d bytes", 16384, 16384, 15),
                     -1);
    ck_assert_str_eq(err.file, "bomb.png");
    ck_assert_int_eq(err.line, 0);
    ck_assert_str_eq(
        err.msg, "16384 x 16384 texels x 15 bytes = 3.75 GiB, beyond the memory budget of 2 GiB "
                 "(envtex --memory-budget SIZE sets it)");
    ck_assert(b.used == 0); /* nothing charged */
    /* with something in use, the message says how much, and the line is kept */
    ck_assert_int_eq(budget_charge(&b, 1.5 * GiB, "s.test", 0, &err, "x"), 0);
    ck_assert_int_eq(
        budget_charge(&b, 0.75 * GiB, "s.test", 9, &err, "room for %d more triangles", 3), -1);
    ck_assert_int_eq(err.line, 9);
    ck_assert_str_eq(
        err.msg,
        "room for 3 more triangles = 768 MiB, beyond the memory budget of 2 GiB (1.5 GiB of "
        "it in use; envtex --memory-budget SIZE sets it)");
    ck_assert(b.used == 1.5 * GiB);
}
END_TEST

START_TEST(test_no_budget_refuses_nothing_and_bad_sizes_are_refused)
{
    error err = {0};
    ck_assert_int_eq(budget_charge(NULL, 1e300, "x", 0, &err, "anything"), 0);
    budget_release(NULL, 5); /* safe */
    budget b;
    budget_init(&b, 1e18);
    ck_assert_int_eq(budget_charge(&b, NAN, "x", 0, &err, "nan"), -1);
    ck_assert_int_eq(budget_charge(&b, INFINITY, "x", 0, &err, "inf"), -1);
    ck_assert_int_eq(budget_charge(&b, -1, "x", 0, &err, "negative"), -1);
    ck_assert(b.used == 0);
}
END_TEST

START_TEST(test_sizes_print_with_three_significant_digits)
{
    struct {
        double bytes;
        const char *text;
    } cases[] = {
        {0, "0 bytes"},           {512, "512 bytes"},    {1023, "1023 bytes"},
        {1024, "1 KiB"},          {12 * 1024, "12 KiB"}, {1.5 * MiB, "1.5 MiB"},
        {3.75 * GiB, "3.75 GiB"}, {2 * GiB, "2 GiB"},    {100.25 * MiB, "100 MiB"},
        {1024 * GiB, "1 TiB"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char buf[32];
        budget_format(cases[i].bytes, buf, sizeof buf);
        ck_assert_msg(!strcmp(buf, cases[i].text), "%g: '%s', expected '%s'", cases[i].bytes, buf,
                      cases[i].text);
    }
}
END_TEST

START_TEST(test_sizes_parse_with_binary_suffixes_and_nothing_else)
{
    struct {
        const char *text;
        double bytes;
    } good[] = {
        {"65536", 65536},      {"512M", 512 * MiB}, {"4G", 4 * GiB},    {"2g", 2 * GiB},
        {"1.5GiB", 1.5 * GiB}, {"10KB", 10240},     {"1T", 1024 * GiB}, {"100B", 100},
    };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        double v = 0;
        ck_assert_msg(budget_parse(good[i].text, &v) == 0 && v == good[i].bytes, "'%s': %g",
                      good[i].text, v);
    }
    const char *bad[] = {"",    "0",   "-1",  "1e9", "0x10", "4X", "G",
                         "4Gi", "nan", "inf", "4 G", "0.5",  ".",  NULL};
    for (int i = 0; i < (int)(sizeof bad / sizeof bad[0]); i++) {
        double v = -7;
        ck_assert_msg(budget_parse(bad[i], &v) == -1 && v == -7, "'%s' parsed as %g",
                      bad[i] ? bad[i] : "NULL", v);
    }
}
END_TEST

static Suite *budget_suite(void)
{
    Suite *s = suite_create("budget");
    TCase *tc = tcase_create("budget");
    tcase_add_test(tc, test_charges_within_the_limit_pass_and_are_released);
    tcase_add_test(tc, test_a_charge_beyond_the_limit_is_refused_with_the_file_claim_and_budget);
    tcase_add_test(tc, test_no_budget_refuses_nothing_and_bad_sizes_are_refused);
    tcase_add_test(tc, test_sizes_print_with_three_significant_digits);
    tcase_add_test(tc, test_sizes_parse_with_binary_suffixes_and_nothing_else);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(budget_suite)
