/* test_error.c - errors as values: error_set formats and keeps one line, error_prefix prepends,
 * error_print writes the one line main.c shows: "envtex: FILE:LINE: msg". */
#include "envtex/core/error.h"

#include <string.h>

#include "unit.h"

/* Run error_print into a string (tmpfile: portable, no GNU extensions). */
static void print_to(const error *err, char *buf, size_t n)
{
    FILE *f = tmpfile();
    ck_assert_ptr_nonnull(f);
    error_print(err, f);
    rewind(f);
    size_t got = fread(buf, 1, n - 1, f);
    buf[got] = '\0';
    fclose(f);
}

START_TEST(test_error_set_formats_and_returns_minus_one)
{
    error err = {0};
    ck_assert_int_eq(error_set(&err, "a.test", 7, "expected %d numbers, got '%s'", 3, "x"), -1);
    ck_assert_str_eq(err.file, "a.test");
    ck_assert_int_eq(err.line, 7);
    ck_assert_str_eq(err.msg, "expected 3 numbers, got 'x'");
}
END_TEST

START_TEST(test_error_set_with_null_file_leaves_file_empty)
{
    error err;
    memset(&err, 'x', sizeof err); /* garbage: error_set must overwrite every part */
    error_set(&err, NULL, 0, "bad");
    ck_assert_str_eq(err.file, "");
    ck_assert_int_eq(err.line, 0);
    ck_assert_str_eq(err.msg, "bad");
}
END_TEST

START_TEST(test_error_set_accepts_a_null_error)
{
    ck_assert_int_eq(error_set(NULL, "f", 1, "ignored %d", 1), -1);
    ck_assert_int_eq(error_prefix(NULL, "ignored"), -1);
}
END_TEST

START_TEST(test_error_set_replaces_newlines_by_spaces)
{
    error err = {0};
    error_set(&err, "f", 1, "one\ntwo\r\nthree%s", "\n");
    ck_assert_str_eq(err.msg, "one two  three ");
    ck_assert_ptr_null(strchr(err.msg, '\n'));
}
END_TEST

START_TEST(test_error_set_truncates_a_long_message_safely)
{
    char big[3 * ERROR_MSG_MAX];
    memset(big, 'a', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    error err = {0};
    error_set(&err, big, 1, "%s", big);
    ck_assert_uint_eq(strlen(err.msg), ERROR_MSG_MAX - 1);
    ck_assert_uint_eq(strlen(err.file), ERROR_FILE_MAX - 1);
}
END_TEST

START_TEST(test_error_prefix_prepends_and_keeps_file_and_line)
{
    error err = {0};
    error_set(&err, "sky.exr", 0, "truncated");
    ck_assert_int_eq(error_prefix(&err, "envmap '%s'", "sky.exr"), -1);
    ck_assert_str_eq(err.msg, "envmap 'sky.exr': truncated");
    ck_assert_str_eq(err.file, "sky.exr");
    ck_assert_int_eq(err.line, 0);
}
END_TEST

START_TEST(test_error_prefix_of_a_full_message_stays_terminated)
{
    error err = {0};
    char big[ERROR_MSG_MAX];
    memset(big, 'b', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    error_set(&err, "f", 2, "%s", big);
    error_prefix(&err, "head\nline");
    ck_assert_uint_eq(strlen(err.msg), ERROR_MSG_MAX - 1);
    ck_assert(strncmp(err.msg, "head line: bbb", 14) == 0);
    /* an over-long prefix is cut too, and still leaves ": " */
    error_prefix(&err, "%s", big);
    ck_assert_uint_lt(strlen(err.msg), ERROR_MSG_MAX);
}
END_TEST

START_TEST(test_error_print_writes_file_line_and_message)
{
    error err = {0};
    char out[4096];
    error_set(&err, "scenes/a.test", 12, "unknown command 'spere'");
    print_to(&err, out, sizeof out);
    ck_assert_str_eq(out, "envtex: scenes/a.test:12: unknown command 'spere'\n");
}
END_TEST

/* A file name may hold a newline (a scene named $'a\nb.test'): the report stays one line.
 * Catches a file name copied as it is (an audit's two-line error). */
START_TEST(test_error_print_keeps_a_file_name_with_a_newline_on_one_line)
{
    error err = {0};
    char out[4096];
    error_set(&err, "dir/a\nb\r.test", 2, "expected a number");
    print_to(&err, out, sizeof out);
    ck_assert_str_eq(out, "envtex: dir/a b .test:2: expected a number\n");
}
END_TEST

START_TEST(test_error_print_without_a_line_leaves_the_line_out)
{
    error err = {0};
    char out[4096];
    error_set(&err, "sky.exr", 0, "not an OpenEXR file");
    print_to(&err, out, sizeof out);
    ck_assert_str_eq(out, "envtex: sky.exr: not an OpenEXR file\n");
}
END_TEST

START_TEST(test_error_print_without_a_file_prints_the_message_only)
{
    error err = {0};
    char out[4096];
    error_set(&err, NULL, 5, "out of memory");
    print_to(&err, out, sizeof out);
    ck_assert_str_eq(out, "envtex: out of memory\n");
}
END_TEST

START_TEST(test_error_print_of_an_empty_error_says_unknown)
{
    error err = {0};
    char out[4096];
    print_to(&err, out, sizeof out);
    ck_assert_str_eq(out, "envtex: unknown error\n");
}
END_TEST

Suite *error_suite(void)
{
    Suite *s = suite_create("error");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_error_set_formats_and_returns_minus_one);
    tcase_add_test(tc, test_error_set_with_null_file_leaves_file_empty);
    tcase_add_test(tc, test_error_set_accepts_a_null_error);
    tcase_add_test(tc, test_error_set_replaces_newlines_by_spaces);
    tcase_add_test(tc, test_error_set_truncates_a_long_message_safely);
    tcase_add_test(tc, test_error_prefix_prepends_and_keeps_file_and_line);
    tcase_add_test(tc, test_error_prefix_of_a_full_message_stays_terminated);
    tcase_add_test(tc, test_error_print_writes_file_line_and_message);
    tcase_add_test(tc, test_error_print_without_a_line_leaves_the_line_out);
    tcase_add_test(tc, test_error_print_keeps_a_file_name_with_a_newline_on_one_line);
    tcase_add_test(tc, test_error_print_without_a_file_prints_the_message_only);
    tcase_add_test(tc, test_error_print_of_an_empty_error_says_unknown);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(error_suite)
