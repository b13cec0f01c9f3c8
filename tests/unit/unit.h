/* unit.h - the few lines every Check unit-test program shares.
 *
 * Each tests/unit/test_NAME.c builds into its own program: it defines `Suite *NAME_suite(void)`
 * and ends with UNIT_MAIN(NAME_suite).  Exit status 0 when every test passes.
 */
#ifndef ENVTEX_UNIT_H
#define ENVTEX_UNIT_H

#include <check.h>
#include <stdlib.h>

#define UNIT_MAIN(suite_fn)                                                       \
    int main(void)                                                                \
    {                                                                             \
        SRunner *sr = srunner_create(suite_fn());                                 \
        srunner_run_all(sr, CK_NORMAL);                                           \
        int failed = srunner_ntests_failed(sr);                                   \
        srunner_free(sr);                                                         \
        return failed ? EXIT_FAILURE : EXIT_SUCCESS;                              \
    }

/* |a - b| <= tol, with the values in the failure message */
#define ck_assert_near(a, b, tol) ck_assert_double_eq_tol((double)(a), (double)(b), (double)(tol))

#endif
