/* test_infile.c - inputs are regular files, opened without blocking, and known by identity. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include "envtex/io/infile.h"
#include "unit.h"

static char dir[64];
static char pathbuf[8][256];
static int npath;

/* dir/name (a few kept at once) */
static const char *in_dir(const char *name)
{
    char *p = pathbuf[npath++ % 8];
    snprintf(p, 256, "%s/%s", dir, name);
    return p;
}

static void make_dir(void)
{
    strcpy(dir, "/tmp/envtex_infile_XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
    FILE *f = fopen(in_dir("a.obj"), "w");
    ck_assert_ptr_nonnull(f);
    fputs("v 0 0 0\n", f);
    fclose(f);
}

static void remove_dir(void)
{
    const char *names[] = {"a.obj", "b.obj", "link.obj", "fifo", "sock", "loop1", "loop2", "sub"};
    for (int i = 0; i < 8; i++) {
        unlink(in_dir(names[i]));
        rmdir(in_dir(names[i]));
    }
    ck_assert_int_eq(rmdir(dir), 0);
}

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* infile_open(path) fails, at once, with a message containing `what` */
static void refused(const char *path, const char *what)
{
    error err = {0};
    double t0 = seconds();
    ck_assert_int_eq(infile_open(path, NULL, &err), -1);
    ck_assert_msg(seconds() - t0 < 2.0, "%s: blocked", path);
    ck_assert_str_eq(err.file, path);
    ck_assert_msg(strstr(err.msg, what) != NULL, "%s: '%s' does not say '%s'", path, err.msg, what);
}

START_TEST(test_a_regular_file_opens_with_its_identity_whatever_its_name)
{
    make_dir();
    error err = {0};
    infile_id a, dot, linked, other;
    int fd = infile_open(in_dir("a.obj"), &a, &err);
    ck_assert_msg(fd >= 0, "%s", err.msg);
    char c;
    ck_assert_int_eq(read(fd, &c, 1), 1); /* readable, and blocking again (O_NONBLOCK cleared) */
    ck_assert_int_eq(fcntl(fd, F_GETFL) & O_NONBLOCK, 0);
    close(fd);
    char spelled[300];
    snprintf(spelled, sizeof spelled, "%s/./././a.obj", dir);
    ck_assert_int_eq(infile_identify(spelled, &dot), 0);
    ck_assert_int_eq(link(in_dir("a.obj"), in_dir("link.obj")), 0);
    ck_assert_int_eq(infile_identify(in_dir("link.obj"), &linked), 0);
    FILE *f = fopen(in_dir("b.obj"), "w");
    fclose(f);
    ck_assert_int_eq(infile_identify(in_dir("b.obj"), &other), 0);
    ck_assert(infile_same(a, dot));
    ck_assert(infile_same(a, linked));
    ck_assert(!infile_same(a, other));
    ck_assert_int_eq(infile_identify(in_dir("missing"), &other), -1);
    remove_dir();
}
END_TEST

START_TEST(test_anything_but_a_regular_file_is_refused_with_what_it_is)
{
    make_dir();
    ck_assert_int_eq(mkfifo(in_dir("fifo"), 0600), 0);
    refused(in_dir("fifo"),
            "cannot open: it is a FIFO, not a regular file"); /* no writer: no block */
    ck_assert_int_eq(mkdir(in_dir("sub"), 0700), 0);
    refused(in_dir("sub"), "cannot open: it is a directory, not a regular file");
    if (access("/dev/zero", R_OK) == 0)
        refused("/dev/zero", "cannot open: it is a character device");
    if (access("/dev/urandom", R_OK) == 0)
        refused("/dev/urandom", "cannot open: it is a character device");
    int s = socket(AF_UNIX, SOCK_STREAM, 0);
    struct sockaddr_un addr = {.sun_family = AF_UNIX};
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", in_dir("sock"));
    ck_assert_int_eq(bind(s, (struct sockaddr *)&addr, sizeof addr), 0);
    refused(in_dir("sock"), "cannot open: it is a socket, not a regular file");
    close(s);
    ck_assert_int_eq(symlink("loop2", in_dir("loop1")), 0);
    ck_assert_int_eq(symlink("loop1", in_dir("loop2")), 0);
    refused(in_dir("loop1"), "cannot open: a loop of symbolic links");
    refused(in_dir("missing"), "cannot open: No such file or directory");
    error err = {0};
    ck_assert_ptr_null(infile_fopen(in_dir("fifo"), NULL, &err));
    ck_assert_ptr_nonnull(strstr(err.msg, "a FIFO"));
    remove_dir();
}
END_TEST

/* A scene may come from a pipe: a FIFO nobody writes to opens at once and reads as empty. */
START_TEST(test_a_stream_may_be_a_pipe_and_a_silent_fifo_reads_as_empty)
{
    make_dir();
    ck_assert_int_eq(mkfifo(in_dir("fifo"), 0600), 0);
    error err = {0};
    double t0 = seconds();
    int fd = infile_open_stream(in_dir("fifo"), NULL, &err);
    ck_assert_msg(fd >= 0, "%s", err.msg);
    char c;
    ck_assert_int_eq(read(fd, &c, 1), 0);
    ck_assert(seconds() - t0 < 2.0);
    close(fd);
    ck_assert_int_eq(infile_open_stream(dir, NULL, &err), -1);
    ck_assert_str_eq(err.msg, "cannot open: it is a directory, not a regular file or a pipe");
    fd = infile_open_stream(in_dir("a.obj"), NULL, &err);
    ck_assert_int_ge(fd, 0);
    close(fd);
    remove_dir();
}
END_TEST

START_TEST(test_the_input_list_holds_each_file_once_and_finds_the_one_an_output_replaces)
{
    make_dir();
    infile_list l = {0};
    error err = {0};
    ck_assert_int_eq(link(in_dir("a.obj"), in_dir("link.obj")), 0);
    char spelled[300];
    snprintf(spelled, sizeof spelled, "%s/./a.obj", dir);
    ck_assert_int_eq(infile_list_add(&l, in_dir("a.obj"), &err), 0);
    ck_assert_int_eq(infile_list_add(&l, spelled, &err), 0);            /* the same file */
    ck_assert_int_eq(infile_list_add(&l, in_dir("link.obj"), &err), 0); /* the same file */
    ck_assert_int_eq(infile_list_add(&l, in_dir("missing"), &err), 0);  /* nothing to protect */
    ck_assert_int_eq(l.n, 1);
    ck_assert_str_eq(l.at[0].path, in_dir("a.obj"));
    ck_assert_str_eq(infile_list_clash(&l, spelled), in_dir("a.obj"));
    ck_assert_str_eq(infile_list_clash(&l, in_dir("link.obj")), in_dir("a.obj"));
    ck_assert_ptr_null(infile_list_clash(&l, in_dir("b.obj"))); /* does not exist yet */
    FILE *f = fopen(in_dir("b.obj"), "w");
    fclose(f);
    ck_assert_ptr_null(infile_list_clash(&l, in_dir("b.obj"))); /* another file */
    infile_list_free(&l);
    ck_assert_int_eq(l.n, 0);
    remove_dir();
}
END_TEST

static Suite *infile_suite(void)
{
    Suite *s = suite_create("infile");
    TCase *tc = tcase_create("infile");
    tcase_add_test(tc, test_a_regular_file_opens_with_its_identity_whatever_its_name);
    tcase_add_test(tc, test_anything_but_a_regular_file_is_refused_with_what_it_is);
    tcase_add_test(tc, test_a_stream_may_be_a_pipe_and_a_silent_fifo_reads_as_empty);
    tcase_add_test(tc,
                   test_the_input_list_holds_each_file_once_and_finds_the_one_an_output_replaces);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(infile_suite)
