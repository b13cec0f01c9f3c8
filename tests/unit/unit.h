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
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "envtex/core/stepcheck.h"
#include "envtex/core/vec.h"

/* A failed step check (stepcheck.h) fails the test case that made it, with its message. */
static inline void unit_stepcheck_fail(const char *msg) { ck_abort_msg("envtex: %s", msg); }

/* Each test case's limit: CASE_TIMEOUT seconds (default 10) times Check's CK_TIMEOUT_MULTIPLIER
 * (1 in make test, 10 under the sanitizers), so that a case that hangs fails by its own name
 * instead of holding up its whole program.  Set before the suite's test cases are made (Check
 * reads CK_DEFAULT_TIMEOUT then). */
static inline double unit_case_timeout(void)
{
    const char *s = getenv("CASE_TIMEOUT");
    double t = s && *s ? strtod(s, NULL) : 10;
    return t > 0 && t < 1e6 ? t : 10; /* seconds, fractions too */
}
static inline void unit_set_case_timeout(void)
{
    char t[32];
    snprintf(t, sizeof t, "%g", unit_case_timeout());
    setenv("CK_DEFAULT_TIMEOUT", t, 1);
}
/* A test case that holds a slow case (docs/design-notes.md, "Test cases' limits"): three times
 * the limit. */
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

/* ---- comparisons, reported at the line of the check ---------------------------------------
 * Each failure names what was compared and gives got, want and the tolerance in decimal (17
 * significant digits), at the FILE:LINE of the macro's call, not of a helper:
 *     test_mipmap.c:88: uv.u: got 0.30000000000000004, want 0.5, tolerance 1e-06 (off by 0.2)
 * A helper that checks for its caller takes the caller's file and line and fails with
 * unit_fail_at (a macro wrapping the helper passes __FILE__ and __LINE__). */
#define unit_fail_at(file, line, ...) _ck_assert_failed(file, line, "Failed", __VA_ARGS__)

static inline void unit_near(const char *file, int line, const char *what, double got,
                             double want, double tol)
{
    if (!(fabs(got - want) <= tol)) /* NaN fails */
        unit_fail_at(file, line, "%s: got %.17g, want %.17g, tolerance %.3g (off by %.3g)", what,
                     got, want, tol, fabs(got - want));
}
/* three values against three, at most tol apart each (`unit`: "component", "channel") */
static inline void unit_triple_near(const char *file, int line, const char *what, const double g[3],
                                    const double w[3], double tol, const char *unit)
{
    double off = fmax(fabs(g[0] - w[0]), fmax(fabs(g[1] - w[1]), fabs(g[2] - w[2])));
    if (!(off <= tol) || !isfinite(g[0] + g[1] + g[2])) /* fmax would hide a NaN */
        unit_fail_at(file, line,
                     "%s: got (%.17g, %.17g, %.17g), want (%.17g, %.17g, %.17g), tolerance %.3g "
                     "per %s (off by %.3g)",
                     what, g[0], g[1], g[2], w[0], w[1], w[2], tol, unit, off);
}
static inline void unit_vec_near(const char *file, int line, const char *what, vec3 got,
                                 vec3 want, double tol)
{
    const double g[3] = {got.x, got.y, got.z}, w[3] = {want.x, want.y, want.z};
    unit_triple_near(file, line, what, g, w, tol, "component");
}
static inline void unit_rgb_near(const char *file, int line, const char *what, rgb got, rgb want,
                                 double tol)
{
    const double g[3] = {got.r, got.g, got.b}, w[3] = {want.r, want.g, want.b};
    unit_triple_near(file, line, what, g, w, tol, "channel");
}
static inline void unit_uv_near(const char *file, int line, const char *what, uv2 got, uv2 want,
                                double tol)
{
    double off = fmax(fabs(got.u - want.u), fabs(got.v - want.v));
    if (!(off <= tol))
        unit_fail_at(file, line,
                     "%s: got (%.17g, %.17g), want (%.17g, %.17g), tolerance %.3g (off by %.3g)",
                     what, got.u, got.v, want.u, want.v, tol, off);
}
/* directions: the angle between them, in radians */
static inline void unit_dir_near(const char *file, int line, const char *what, vec3 got,
                                 vec3 want, double tol)
{
    double angle = vec3_angle(got, want);
    if (!(angle <= tol))
        unit_fail_at(file, line,
                     "%s: got (%.17g, %.17g, %.17g), want (%.17g, %.17g, %.17g), tolerance %.3g "
                     "radians (off by %.3g)",
                     what, got.x, got.y, got.z, want.x, want.y, want.z, tol, angle);
}
#define ck_assert_near(got, want, tol)                                                             \
    unit_near(__FILE__, __LINE__, #got, (double)(got), (double)(want), (double)(tol))
#define ck_vec_near(got, want, tol) unit_vec_near(__FILE__, __LINE__, #got, got, want, tol)
#define ck_rgb_near(got, want, tol) unit_rgb_near(__FILE__, __LINE__, #got, got, want, tol)
#define ck_uv_near(got, want, tol)  unit_uv_near(__FILE__, __LINE__, #got, got, want, tol)
#define ck_dir_near(got, want, tol) unit_dir_near(__FILE__, __LINE__, #got, got, want, tol)

#endif
