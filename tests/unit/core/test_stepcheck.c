/* test_stepcheck.c - the checks on an index or a coordinate a lecture step made: silent in range,
 * and out of range one message that names the function, the value, the range and the step. */
#include "envtex/core/stepcheck.h"

#include <math.h>
#include <setjmp.h>
#include <string.h>

#include "unit.h"

/* A handler that keeps the message and jumps back into the test (it must not return). */
static char got[256];
static jmp_buf back;
static void keep(const char *msg)
{
    snprintf(got, sizeof got, "%s", msg);
    longjmp(back, 1);
}

/* 1 if the check in `body` failed, its message in got */
#define FAILS(body)                                                                                \
    (got[0] = '\0', stepcheck_set_handler(keep),                                                   \
     setjmp(back) ? (stepcheck_set_handler(NULL), 1) : ((body), stepcheck_set_handler(NULL), 0))

static void index_check(int i, int n) { STEPCHECK_INDEX(i, n, "latlong", "column"); }
static void coord_check(double x) { STEPCHECK_COORD(x, 0.0, 1.0, "cubemap", "s"); }

START_TEST(test_stepcheck_index_passes_every_index_in_range)
{
    for (volatile int i = 0; i < 256; i++) /* volatile: kept across the longjmp */
        ck_assert_msg(!FAILS(index_check(i, 256)), "%d: %s", (int)i, got);
}
END_TEST

START_TEST(test_stepcheck_index_names_the_function_the_index_the_range_and_the_step)
{
    ck_assert(FAILS(index_check(-3, 256)));
    ck_assert_str_eq(got, "index_check: column -3 is outside [0, 255]: the latlong step's code "
                          "made it");
    ck_assert(FAILS(index_check(256, 256))); /* one past the end */
    ck_assert_str_eq(got, "index_check: column 256 is outside [0, 255]: the latlong step's code "
                          "made it");
    ck_assert(FAILS(index_check(-2147483647 - 1, 256)));
}
END_TEST

START_TEST(test_stepcheck_coord_passes_the_closed_interval_and_refuses_nan)
{
    ck_assert(!FAILS(coord_check(0.0)));
    ck_assert(!FAILS(coord_check(1.0)));
    ck_assert(!FAILS(coord_check(0.5)));
    ck_assert(FAILS(coord_check(-0.25)));
    ck_assert_str_eq(got, "coord_check: s = -0.25 is outside [0, 1]: the cubemap step's code "
                          "made it");
    ck_assert(FAILS(coord_check(nextafter(1.0, 2.0))));
    ck_assert(FAILS(coord_check(NAN)));
    ck_assert(FAILS(coord_check(INFINITY)));
}
END_TEST

/* Without a handler the process stops with status 1 (the command line's), not a crash. */
START_TEST(test_stepcheck_without_a_handler_exits_with_status_1)
{
    stepcheck_set_handler(NULL);
    index_check(-1, 4);
}
END_TEST

Suite *stepcheck_suite(void)
{
    Suite *s = suite_create("stepcheck");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_stepcheck_index_passes_every_index_in_range);
    tcase_add_test(tc, test_stepcheck_index_names_the_function_the_index_the_range_and_the_step);
    tcase_add_test(tc, test_stepcheck_coord_passes_the_closed_interval_and_refuses_nan);
    tcase_add_exit_test(tc, test_stepcheck_without_a_handler_exits_with_status_1, 1);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(stepcheck_suite)
