/* test_obj.c - the OBJ reader: every corner form, fan triangulation, negative indices, missing
 * vt / vn, skipped statements, and each error at its FILE:LINE before anything grows. */
#include "envtex/io/obj.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "unit.h"

static void load_ok(const char *text, obj_mesh *m)
{
    error err = {0};
    int rc = obj_load_string(text, "m.obj", 0, m, NULL, &err);
    ck_assert_msg(rc == 0, "unexpected error: %s:%d: %s", err.file, err.line, err.msg);
}

static void load_fails(const char *text, long max, int line, const char *what)
{
    obj_mesh m;
    error err = {0};
    ck_assert_msg(obj_load_string(text, "m.obj", max, &m, NULL, &err) == -1, "no error for:\n%s",
                  text);
    ck_assert_str_eq(err.file, "m.obj");
    ck_assert_msg(err.line == line, "line %d, expected %d: %s", err.line, line, err.msg);
    ck_assert_msg(strstr(err.msg, what) != NULL, "'%s' lacks \"%s\"", err.msg, what);
    ck_assert_ptr_null(m.v);
    ck_assert_ptr_null(m.tris);
}

#define QUAD "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"

START_TEST(test_every_corner_form_is_read)
{
    obj_mesh m;
    load_ok(QUAD "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n"
                 "f 1 2 3\nf 1/1 2/2 3/3\nf 1//1 2//1 3//1\nf 1/1/1 2/2/1 3/3/1\n",
            &m);
    ck_assert_int_eq(m.n_v, 4);
    ck_assert_int_eq(m.n_vt, 3);
    ck_assert_int_eq(m.n_vn, 1);
    ck_assert_int_eq(m.n_tris, 4);
    for (int t = 0; t < 4; t++)
        for (int k = 0; k < 3; k++) ck_assert_int_eq(m.tris[t].v[k], k);
    ck_assert_int_eq(m.tris[0].vt[0], -1);
    ck_assert_int_eq(m.tris[0].vn[2], -1);
    ck_assert_int_eq(m.tris[1].vt[2], 2);
    ck_assert_int_eq(m.tris[1].vn[0], -1);
    ck_assert_int_eq(m.tris[2].vt[0], -1);
    ck_assert_int_eq(m.tris[2].vn[1], 0);
    ck_assert_int_eq(m.tris[3].vt[1], 1);
    ck_assert_int_eq(m.tris[3].vn[1], 0);
    ck_assert_double_eq(m.vt[2].u, 1);
    ck_assert_double_eq(m.vt[2].v, 1);
    obj_free(&m);
    obj_free(&m);
}
END_TEST

START_TEST(test_polygons_are_fanned_from_their_first_corner)
{
    obj_mesh m;
    load_ok(QUAD "v 0.5 2 0\nf 1 2 3 5 4\n", &m);
    ck_assert_int_eq(m.n_tris, 3);
    const long expect[3][3] = {{0, 1, 2}, {0, 2, 4}, {0, 4, 3}};
    for (int t = 0; t < 3; t++)
        for (int k = 0; k < 3; k++) ck_assert_int_eq(m.tris[t].v[k], expect[t][k]);
    obj_free(&m);
}
END_TEST

START_TEST(test_negative_indices_count_back_from_the_last_record_so_far)
{
    obj_mesh m;
    load_ok(QUAD "vt 0 0\nvt 0.5 0.5\nf -4/-2 -3/-1 -2/-1\nv 9 9 9\nf -1 -2 -3\n", &m);
    ck_assert_int_eq(m.tris[0].v[0], 0);
    ck_assert_int_eq(m.tris[0].v[2], 2);
    ck_assert_int_eq(m.tris[0].vt[0], 0);
    ck_assert_int_eq(m.tris[0].vt[1], 1);
    ck_assert_int_eq(m.tris[1].v[0], 4); /* -1 now means the fifth vertex */
    ck_assert_int_eq(m.tris[1].v[2], 2);
    obj_free(&m);
}
END_TEST

START_TEST(test_optional_numbers_comments_and_other_statements_are_tolerated)
{
    obj_mesh m;
    load_ok("# a comment\r\nmtllib a.mtl\r\no thing\r\nv 1 2 3 1\r\nv 0 0 0 0.5 0.5 0.5\r\n"
            "v 1 1 1\r\nvt 0.25\r\ng group\r\ns off\r\nusemtl red\r\n\r\n  f 1/1 2/1 3/1 # c\r\n",
            &m);
    ck_assert_int_eq(m.n_v, 3);
    ck_assert_double_eq(m.v[0].z, 3);
    ck_assert_double_eq(m.vt[0].u, 0.25);
    ck_assert_double_eq(m.vt[0].v, 0);
    ck_assert_int_eq(m.n_tris, 1);
    ck_assert_int_eq(m.n_ignored, 5);
    ck_assert_str_eq(m.first_ignored, "mtllib");
    ck_assert_int_eq(m.first_ignored_line, 2);
    obj_free(&m);
}
END_TEST

START_TEST(test_a_utf8_byte_order_mark_at_the_start_is_skipped)
{
    obj_mesh m;
    load_ok("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &m);
    ck_assert_int_eq(m.n_v, 3); /* the first 'v' is a vertex, not an unknown statement */
    ck_assert_int_eq(m.n_tris, 1);
    ck_assert_int_eq(m.n_ignored, 0);
    obj_free(&m);
    /* the mark's line is still line 1 */
    load_fails("\xEF\xBB\xBFv 0 0 abc\n", 0, 1, "'abc'");
}
END_TEST

START_TEST(test_each_error_names_its_line)
{
    load_fails("v 0 0 abc\n", 0, 1, "'abc'");
    load_fails("v 0 0 nan\n", 0, 1, "finite");
    load_fails("v 0 0 1e999\n", 0, 1, "finite");
    load_fails("v 0 0\n", 0, 1, "takes 3");
    load_fails("vn 0 0 1 1\n", 0, 1, "at most 3");
    load_fails(QUAD "f 1 2\n", 0, 5, "at least 3");
    load_fails(QUAD "f 1 2 5\n", 0, 5, "index 5 of 'f' is out of range: 4 vertices");
    load_fails(QUAD "f 1 2 0\n", 0, 5, "index 0");
    load_fails(QUAD "f 1 2 -5\n", 0, 5, "index -5");
    load_fails(QUAD "f 1/1 2 3\n", 0, 5, "0 texture coordinates");
    load_fails(QUAD "f 1//1 2 3\n", 0, 5, "0 normals");
    load_fails(QUAD "f 1/ 2 3\n", 0, 5, "bad corner");
    load_fails(QUAD "f 1/1/1/1 2 3\n", 0, 5, "bad corner");
    load_fails(QUAD "f 1x 2 3\n", 0, 5, "bad index '1x'");
    load_fails(QUAD "f 99999999999999999999 2 3\n", 0, 5, "bad index");
}
END_TEST

START_TEST(test_limits_are_checked_before_the_arrays_grow)
{
    load_fails(QUAD, 3, 4, "more than 3 vertices");
    load_fails(QUAD "f 1 2 3 4 1 2 3\n", 4, 5, "more than 4 triangles");
    obj_mesh m;
    error err = {0};
    ck_assert_int_eq(obj_load_string(QUAD, "m.obj", 4, &m, NULL, &err), 0);
    obj_free(&m);
}
END_TEST

/* What each array grows by (its capacity doubles from 64) is charged before it grows; a refusal
 * names the line and the budget and leaves nothing charged. */
START_TEST(test_the_arrays_growth_is_charged_and_a_refusal_leaves_nothing_charged)
{
    obj_mesh m;
    error err = {0};
    budget mem;
    budget_init(&mem, 1e9);
    ck_assert_int_eq(obj_load_string(QUAD "f 1 2 3 4\n", "m.obj", 0, &m, &mem, &err), 0);
    ck_assert(m.bytes == 64.0 * sizeof(vec3) + 64.0 * sizeof(obj_triangle)); /* 4 v, 2 triangles */
    ck_assert(mem.used == m.bytes);
    obj_free(&m);
    char text[100 * 8 + 16] = "";
    for (int i = 0; i < 100; i++) strcat(text + 8 * (i > 0 ? i - 1 : 0), "v 0 0 0\n");
    budget_init(&mem, 1e9);
    ck_assert_int_eq(obj_load_string(text, "m.obj", 0, &m, &mem, &err), 0);
    ck_assert(m.bytes == 128.0 * sizeof(vec3)); /* 64, then 64 more */
    ck_assert(mem.used == m.bytes);
    obj_free(&m);
    budget_init(&mem, 2000);
    ck_assert_int_eq(obj_load_string(QUAD "f 1 2 3 4\n", "m.obj", 0, &m, &mem, &err), -1);
    ck_assert_str_eq(err.file, "m.obj");
    ck_assert_int_eq(err.line, 5); /* the face: 64 vertices fit (1.5 KiB), 64 triangles do not */
    ck_assert_str_eq(err.msg,
                     "room for 64 more triangles x 72 bytes = 4.5 KiB, beyond the memory budget of "
                     "1.95 KiB (1.5 KiB of it in use; envtex --memory-budget SIZE sets it)");
    ck_assert(mem.used == 0);
    ck_assert_ptr_null(m.v);
}
END_TEST

START_TEST(test_files_are_read_and_missing_ones_named)
{
    char path[] = "/tmp/test_obj_XXXXXX";
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    const char text[] = QUAD "f 1 2 3 4\n";
    ck_assert_int_eq(write(fd, text, sizeof text - 1), (long)sizeof text - 1);
    close(fd);
    obj_mesh m;
    error err = {0};
    ck_assert_int_eq(obj_load(path, 0, &m, NULL, &err), 0);
    ck_assert_int_eq(m.n_tris, 2);
    obj_free(&m);
    unlink(path);
    ck_assert_int_eq(obj_load(path, 0, &m, NULL, &err), -1);
    ck_assert_str_eq(err.file, path);
    ck_assert_ptr_nonnull(strstr(err.msg, "cannot open"));
}
END_TEST

Suite *obj_suite(void)
{
    Suite *s = suite_create("obj");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_every_corner_form_is_read);
    tcase_add_test(tc, test_polygons_are_fanned_from_their_first_corner);
    tcase_add_test(tc, test_negative_indices_count_back_from_the_last_record_so_far);
    tcase_add_test(tc, test_optional_numbers_comments_and_other_statements_are_tolerated);
    tcase_add_test(tc, test_a_utf8_byte_order_mark_at_the_start_is_skipped);
    tcase_add_test(tc, test_each_error_names_its_line);
    tcase_add_test(tc, test_limits_are_checked_before_the_arrays_grow);
    tcase_add_test(tc, test_the_arrays_growth_is_charged_and_a_refusal_leaves_nothing_charged);
    tcase_add_test(tc, test_files_are_read_and_missing_ones_named);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(obj_suite)
