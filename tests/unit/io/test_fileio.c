/* test_fileio.c - atomic temporary files and whole-file reads. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envtex/io/fileio.h"
#include "unit.h"

#include "testdir.h"

START_TEST(test_temporary_files_live_beside_the_target_and_commit_by_rename)
{
    make_dir();
    char tmp[ERROR_FILE_MAX];
    error err = {0};
    int fd = fileio_tmp_open(in_dir("t.bin"), tmp, &err);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(strncmp(tmp, in_dir("t.bin.tmp."), strlen(in_dir("t.bin.tmp."))), 0);
    ck_assert_int_eq((int)write(fd, "abc", 3), 3);
    ck_assert_int_eq(close(fd), 0);
    struct stat st;
    ck_assert_int_eq(stat(tmp, &st), 0);
    mode_t mask = umask(0);
    umask(mask);
    ck_assert_int_eq((int)(st.st_mode & 0777), (int)(0666 & ~mask)); /* not mkstemp's 0600 */
    ck_assert_int_eq(fileio_tmp_commit(tmp, in_dir("t.bin"), &err), 0);
    size_t n;
    unsigned char *d = slurp(in_dir("t.bin"), &n);
    ck_assert_uint_eq(n, 3);
    free(d);
    fd = fileio_tmp_open(in_dir("t.bin"), tmp, &err);
    ck_assert_int_ge(fd, 0);
    close(fd);
    fileio_tmp_abandon(tmp);
    ck_assert_int_eq(count_files(".tmp."), 0);
    ck_assert_int_eq(fileio_tmp_open(in_dir("no/t.bin"), tmp, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "No such file or directory"));
    char longpath[ERROR_FILE_MAX + 10];
    memset(longpath, 'a', sizeof longpath - 1);
    longpath[sizeof longpath - 1] = '\0';
    ck_assert_int_eq(fileio_tmp_open(longpath, tmp, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "too long"));
    remove_dir();
}
END_TEST

/* A whole file comes back byte for byte with a 0 after it, charged size + 1 to the budget; a
 * budget one byte short refuses it and charges nothing; a folder is refused by name. */
START_TEST(test_read_all_returns_the_bytes_and_charges_them)
{
    make_dir();
    FILE *f = fopen(in_dir("d.bin"), "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite("hello", 1, 5, f), 5);
    ck_assert_int_eq(fclose(f), 0);
    budget mem;
    budget_init(&mem, 6);
    error err = {0};
    unsigned char *d;
    size_t n;
    ck_assert_int_eq(fileio_read_all(in_dir("d.bin"), &d, &n, &mem, &err), 0);
    ck_assert_uint_eq(n, 5);
    ck_assert(memcmp(d, "hello", 6) == 0); /* the 0 after the bytes */
    ck_assert(mem.used == 6);
    free(d);
    budget_init(&mem, 5);
    ck_assert_int_eq(fileio_read_all(in_dir("d.bin"), &d, &n, &mem, &err), -1);
    ck_assert(mem.used == 0 && d == NULL);
    ck_assert_int_eq(fileio_read_all(dir, &d, &n, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "not a regular file"));
    remove_dir();
}
END_TEST

Suite *fileio_suite(void)
{
    Suite *s = suite_create("fileio");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_temporary_files_live_beside_the_target_and_commit_by_rename);
    tcase_add_test(tc, test_read_all_returns_the_bytes_and_charges_them);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(fileio_suite)
