/* fileio.c - atomic writes and whole-file reads (see include/envtex/io/fileio.h). */
#include "envtex/io/fileio.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envtex/io/infile.h"

/* ---- atomic writes ------------------------------------------------------------------------- */

int fileio_tmp_open(const char *path, char *tmp_path, error *err)
{
    /* "PATH.tmp.XXXXXX": same folder as the target, so rename() never crosses file systems */
    int n = snprintf(tmp_path, ERROR_FILE_MAX, "%s.tmp.XXXXXX", path);
    if (n < 0 || n >= ERROR_FILE_MAX) {
        tmp_path[0] = '\0';
        return error_set(err, path, 0, "path is too long");
    }
    /* rename() would put the image in place of a folder's entry or a device: refuse first */
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        tmp_path[0] = '\0';
        return error_set(err, path, 0, "cannot write an image here: %s",
                         S_ISDIR(st.st_mode) ? "it is a folder" : "it is not a regular file");
    }
    int fd = mkstemp(tmp_path);
    if (fd < 0) {
        int e = errno;
        tmp_path[0] = '\0';
        return error_set(err, path, 0, "cannot create a file here: %s", strerror(e));
    }
    /* mkstemp makes the file 0600; give it the mode a plain fopen would (0666 less umask) */
    mode_t mask = umask(0);
    umask(mask);
    if (fchmod(fd, 0666 & ~mask) != 0) { /* not fatal: the file is merely private */
    }
    return fd;
}

FILE *fileio_tmp_fopen(const char *path, char *tmp_path, error *err)
{
    int fd = fileio_tmp_open(path, tmp_path, err);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, "wb");
    if (!f) {
        int e = errno;
        close(fd);
        fileio_tmp_abandon(tmp_path);
        tmp_path[0] = '\0';
        error_set(err, path, 0, "cannot write: %s", strerror(e));
    }
    return f;
}

int fileio_tmp_commit(const char *tmp_path, const char *path, error *err)
{
    if (rename(tmp_path, path) != 0) {
        int e = errno;
        unlink(tmp_path);
        return error_set(err, path, 0, "cannot replace the file: %s", strerror(e));
    }
    return 0;
}

void fileio_tmp_abandon(const char *tmp_path)
{
    if (tmp_path && tmp_path[0]) unlink(tmp_path);
}

/* ---- whole files --------------------------------------------------------------------------- */

int fileio_read_all(const char *path, unsigned char **data, size_t *size, budget *mem, error *err)
{
    *data = NULL;
    *size = 0;
    int fd = infile_open(path, NULL, err);
    if (fd < 0) return -1;
    struct stat st;
    if (fstat(fd, &st) != 0 || (uint64_t)st.st_size > (uint64_t)SIZE_MAX - 1) {
        int e = errno;
        close(fd);
        return error_set(err, path, 0, "cannot read: %s", strerror(e));
    }
    size_t n = (size_t)st.st_size, done = 0;
    if (budget_charge(mem, (double)n + 1, path, 0, err, "reading the %zu-byte file", n)) {
        close(fd);
        return -1;
    }
    unsigned char *buf = malloc(n + 1); /* +1: never malloc(0), and room for a terminating 0 */
    if (!buf) {
        close(fd);
        budget_release(mem, (double)n + 1);
        return error_set(err, path, 0, "out of memory reading %zu bytes", n);
    }
    while (done < n) {
        ssize_t got = read(fd, buf + done, n - done);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            int e = errno;
            free(buf);
            close(fd);
            budget_release(mem, (double)n + 1);
            return error_set(err, path, 0, "read error: %s", strerror(e));
        }
        if (got == 0) break; /* the file shrank: read what is there */
        done += (size_t)got;
    }
    close(fd);
    budget_release(mem, (double)(n - done)); /* charged: the bytes read, + 1 */
    buf[done] = 0;
    *data = buf;
    *size = done;
    return 0;
}
