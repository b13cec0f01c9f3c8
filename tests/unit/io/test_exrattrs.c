/* test_exrattrs.c - the envtex attributes set on and read from an OpenEXRCore context. */
#include <openexr.h>
#include <stdio.h>
#include <string.h>

#include "envtex/io/exrattrs.h"
#include "testdir.h"
#include "unit.h"

/* OpenEXRCore's messages are expected here: keep them off the test's output. */
static void quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt, (void)code, (void)msg;
}

/* A write context on a scratch file with one scanline part, its header not yet written. */
static exr_context_t start(const char *path, int *part)
{
    exr_context_t ctx = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet;
    ck_assert_int_eq(exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init), EXR_ERR_SUCCESS);
    ck_assert_int_eq(exr_add_part(ctx, "rgb", EXR_STORAGE_SCANLINE, part), EXR_ERR_SUCCESS);
    return ctx;
}

START_TEST(test_set_attributes_read_back_and_unknown_fields_are_not_written)
{
    make_dir();
    int part = 0;
    exr_context_t ctx = start(in_dir("a.exr"), &part);
    exrfile_attrs at = {.spp = 96, .has_seed = 1, .seed = 18446744073709551615ull};
    snprintf(at.scene, sizeof at.scene, "data/scenes/sphere.test");
    ck_assert_int_eq(exrattrs_set(ctx, part, &at), EXR_ERR_SUCCESS);
    exrfile_attrs got = {0};
    error err = {0};
    ck_assert_msg(exrattrs_get(ctx, &got, "a.exr", &err) == 0, "%s", err.msg);
    ck_assert_int_eq(got.spp, 96);
    ck_assert_int_eq(got.has_seed, 1);
    ck_assert(got.seed == 18446744073709551615ull);
    ck_assert_str_eq(got.scene, "data/scenes/sphere.test");
    ck_assert_str_eq(got.integrator, ""); /* empty: not written */
    int32_t len = 0;
    const char *str = NULL;
    ck_assert_int_eq(exr_attr_get_string(ctx, part, "envtex:integrator", &len, &str),
                     EXR_ERR_NO_ATTR_BY_NAME);
    ck_assert_int_eq(exrattrs_set(ctx, part, NULL), EXR_ERR_SUCCESS);
    exr_finish(&ctx);
    remove_dir();
}
END_TEST

START_TEST(test_attributes_of_the_wrong_kind_are_errors_naming_the_file)
{
    make_dir();
    int part = 0;
    exrfile_attrs got = {0};
    error err = {0};
    exr_context_t ctx = start(in_dir("b.exr"), &part);
    ck_assert_int_eq(exr_attr_set_int(ctx, part, "envtex:spp", 0), EXR_ERR_SUCCESS);
    ck_assert_int_eq(exrattrs_get(ctx, &got, "b.exr", &err), -1);
    ck_assert_str_eq(err.file, "b.exr");
    ck_assert_ptr_nonnull(strstr(err.msg, "envtex:spp"));
    exr_finish(&ctx);
    ctx = start(in_dir("c.exr"), &part);
    ck_assert_int_eq(exr_attr_set_string(ctx, part, "envtex:seed", "-3"), EXR_ERR_SUCCESS);
    ck_assert_int_eq(exrattrs_get(ctx, &got, "c.exr", &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "envtex:seed"));
    exr_finish(&ctx);
    ctx = start(in_dir("d.exr"), &part);
    ck_assert_int_eq(exr_attr_set_int(ctx, part, "envtex:scene", 3), EXR_ERR_SUCCESS);
    ck_assert_int_eq(exrattrs_get(ctx, &got, "d.exr", &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "not a string"));
    exr_finish(&ctx);
    remove_dir();
}
END_TEST

Suite *exrattrs_suite(void)
{
    Suite *s = suite_create("exrattrs");
    TCase *tc = tcase_create("exrattrs");
    tcase_add_test(tc, test_set_attributes_read_back_and_unknown_fields_are_not_written);
    tcase_add_test(tc, test_attributes_of_the_wrong_kind_are_errors_naming_the_file);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(exrattrs_suite)
