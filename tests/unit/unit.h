/* unit.h - the few lines every Check unit-test program shares.
 *
 * Each tests/unit/test_NAME.c builds into its own program: it defines `Suite *NAME_suite(void)`
 * and ends with UNIT_MAIN(NAME_suite).  Exit status 0 when every test passes, and 1 when one
 * fails or when none ran at all (CK_RUN_SUITE, CK_RUN_CASE or CK_INCLUDE_TAGS in the
 * environment can select nothing: a program that checked nothing has not passed).  A failed
 * step check (stepcheck.h) fails the running test case with its message.
 */
#ifndef ENVTEX_UNIT_H
#define ENVTEX_UNIT_H

#include <check.h>
#include <stdio.h>
#include <stdlib.h>

#include "envtex/core/stepcheck.h"

/* A failed step check (stepcheck.h) fails the test case that made it, with its message. */
static inline void unit_stepcheck_fail(const char *msg) { ck_abort_msg("envtex: %s", msg); }

/* Each test case's limit: CASE_TIMEOUT seconds (default 10) times Check's CK_TIMEOUT_MULTIPLIER
 * (1 in make test, 10 under the sanitizers), so that a case that hangs fails by its own name
 * instead of holding up its whole program.  Set before the suite's test cases are made (Check
 * reads CK_DEFAULT_TIMEOUT then). */
static inline int unit_case_timeout(void)
{
    const char *s = getenv("CASE_TIMEOUT");
    int t = s && *s ? atoi(s) : 10;
    return t > 0 ? t : 10;
}
static inline void unit_set_case_timeout(void)
{
    char t[16];
    snprintf(t, sizeof t, "%d", unit_case_timeout());
    setenv("CK_DEFAULT_TIMEOUT", t, 1);
}
/* A test case that takes over half a second at -O2 (5 s at -O0): three times the limit. */
static inline void unit_slow(TCase *tc) { tcase_set_timeout(tc, 3.0 * unit_case_timeout()); }

#define UNIT_MAIN(suite_fn)                                                                        \
    int main(void)                                                                                 \
    {                                                                                              \
        stepcheck_set_handler(unit_stepcheck_fail);                                                \
        unit_set_case_timeout();                                                                   \
        SRunner *sr = srunner_create(suite_fn());                                                  \
        srunner_run_all(sr, CK_NORMAL);                                                            \
        int failed = srunner_ntests_failed(sr), ran = srunner_ntests_run(sr);                      \
        srunner_free(sr);                                                                          \
        if (ran == 0) fprintf(stderr, "no test ran (CK_RUN_SUITE, CK_RUN_CASE?)\n");               \
        return failed || ran == 0 ? EXIT_FAILURE : EXIT_SUCCESS;                                   \
    }

/* Assertions for hot loops: ck_require(expr) and ck_require_msg(expr, fmt, ...) fail as
 * ck_assert and ck_assert_msg do, but a passing one costs nothing: Check records the file and
 * line of every passing ck_assert (a write() each), which in a loop of a million samples is most
 * of a test's time. */
#define ck_require(expr)                                                                           \
    do {                                                                                           \
        if (!(expr)) ck_abort_msg("Assertion '%s' failed", #expr);                                 \
    } while (0)
#define ck_require_msg(expr, ...)                                                                  \
    do {                                                                                           \
        if (!(expr)) ck_abort_msg(__VA_ARGS__);                                                    \
    } while (0)

/* |a - b| <= tol, with the values in the failure message */
#define ck_assert_near(a, b, tol) ck_assert_double_eq_tol((double)(a), (double)(b), (double)(tol))

#endif
