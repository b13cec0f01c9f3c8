/* testdir.h - a scratch folder per test, for the image-format tests: each test calls make_dir()
 * (a fresh mkdtemp folder), names files in it with in_dir(), and ends with remove_dir().
 * Header-only (static inline: a test that uses only some of them gets no unused warnings). */
#ifndef ENVTEX_TESTDIR_H
#define ENVTEX_TESTDIR_H

#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "envtex/io/fileio.h"
#include "envtex/io/imageio.h"
#include "unit.h"

static char dir[64];

static inline void make_dir(void)
{
    strcpy(dir, "/tmp/envtex_test_XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
}

static inline void remove_dir(void)
{
    DIR *d = opendir(dir);
    ck_assert_ptr_nonnull(d);
    char p[512];
    for (struct dirent *e; (e = readdir(d));) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        unlink(p);
    }
    closedir(d);
    ck_assert_int_eq(rmdir(dir), 0);
}

/* Entries of the test folder whose name contains `part` (".tmp." finds left-over temporaries). */
static inline int count_files(const char *part)
{
    DIR *d = opendir(dir);
    ck_assert_ptr_nonnull(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        if (e->d_name[0] != '.' && strstr(e->d_name, part)) n++;
    closedir(d);
    return n;
}

/* "dir/name" (one of 4 rotating buffers, so a call may take two or three of them) */
static inline const char *in_dir(const char *name)
{
    static char buf[4][256];
    static int i;
    i = (i + 1) % 4;
    snprintf(buf[i], sizeof buf[i], "%s/%s", dir, name);
    return buf[i];
}

static inline void write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(data, 1, n, f), n);
    ck_assert_int_eq(fclose(f), 0);
}

/* The whole file (caller frees). */
static inline unsigned char *slurp(const char *path, size_t *n)
{
    unsigned char *d = NULL;
    error err = {0};
    ck_assert_msg(fileio_read_all(path, &d, n, NULL, &err) == 0, "%s", err.msg);
    return d;
}

/* A write that failed left the file at `path` exactly as `before` (n bytes, read with slurp
 * before the write) and no temporary file beside it; frees `before`. */
static inline void assert_unchanged(const char *path, unsigned char *before, size_t n)
{
    size_t na;
    unsigned char *after = slurp(path, &na);
    ck_assert_uint_eq(na, n);
    ck_assert_int_eq(memcmp(before, after, n), 0);
    ck_assert_int_eq(count_files(".tmp."), 0);
    free(before);
    free(after);
}

/* A disk that fills up part-way through a file: until file_size_unlimited(), a write past
 * `bytes` fails with EFBIG (RLIMIT_FSIZE, with SIGXFSZ ignored so it is an error, not a kill).
 * For the writers' failure paths; Check runs each test in its own process, and the test
 * restores the limit anyway. */
static struct rlimit saved_fsize;
static inline void file_size_limit(rlim_t bytes)
{
    ck_assert_int_eq(getrlimit(RLIMIT_FSIZE, &saved_fsize), 0);
    signal(SIGXFSZ, SIG_IGN);
    struct rlimit r = saved_fsize;
    r.rlim_cur = bytes;
    ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &r), 0);
}

static inline void file_size_unlimited(void)
{
    ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &saved_fsize), 0);
    signal(SIGXFSZ, SIG_DFL);
}

#endif
