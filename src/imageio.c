/* imageio.c - read and write images by file name (see include/envtex/imageio.h). */
#include "envtex/imageio.h"

#include <assert.h>
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envtex/exrfile.h"
#include "envtex/infile.h"
#include "envtex/pfm.h"
#include "envtex/pngfile.h"
#include "envtex/rgbe.h"

/* ---- atomic writes ------------------------------------------------------------------------- */

int imageio_tmp_open(const char *path, char *tmp_path, error *err)
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
    if (fchmod(fd, 0666 & ~mask) != 0) { /* not fatal: the file is merely private */ }
    return fd;
}

FILE *imageio_tmp_fopen(const char *path, char *tmp_path, error *err)
{
    int fd = imageio_tmp_open(path, tmp_path, err);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, "wb");
    if (!f) {
        int e = errno;
        close(fd);
        imageio_tmp_abandon(tmp_path);
        tmp_path[0] = '\0';
        error_set(err, path, 0, "cannot write: %s", strerror(e));
    }
    return f;
}

int imageio_tmp_commit(const char *tmp_path, const char *path, error *err)
{
    if (rename(tmp_path, path) != 0) {
        int e = errno;
        unlink(tmp_path);
        return error_set(err, path, 0, "cannot replace the file: %s", strerror(e));
    }
    return 0;
}

void imageio_tmp_abandon(const char *tmp_path)
{
    if (tmp_path && tmp_path[0]) unlink(tmp_path);
}

/* ---- whole files --------------------------------------------------------------------------- */

int imageio_read_all(const char *path, unsigned char **data, size_t *size, budget *mem, error *err)
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

/* ---- by magic / by extension --------------------------------------------------------------- */

/* The format named by a file's first n (<= 8) bytes m. */
static imageio_format format_of_magic(const unsigned char *m, size_t n)
{
    if (n >= 4 && memcmp(m, EXRFILE_MAGIC, 4) == 0) return IMAGEIO_EXR;
    if (n >= 8 && memcmp(m, PNGFILE_MAGIC, 8) == 0) return IMAGEIO_PNG;
    if (n >= 2 && m[0] == '#' && m[1] == '?') return IMAGEIO_RGBE;
    if (n >= 2 && m[0] == 'P' && (m[1] == 'F' || m[1] == 'f')) return IMAGEIO_PFM;
    return IMAGEIO_UNKNOWN;
}

/* The first bytes (up to 8) of the regular file at path into m: their count, or -1 with *err. */
static int read_magic(const char *path, unsigned char m[8], error *err)
{
    int fd = infile_open(path, NULL, err);
    if (fd < 0) return -1;
    ssize_t n;
    do n = read(fd, m, 8); while (n < 0 && errno == EINTR);
    int e = errno;
    close(fd);
    if (n < 0) return error_set(err, path, 0, "cannot read: %s", strerror(e));
    return (int)n;
}

int imageio_read(const char *path, image *out, budget *mem, error *err)
{
    out->w = out->h = 0;
    out->px = NULL;
    unsigned char m[8] = {0};
    int n = read_magic(path, m, err);
    if (n < 0) return -1;
    if (n == 0) return error_set(err, path, 0, "file is empty");

    switch (format_of_magic(m, (size_t)n)) {
    case IMAGEIO_EXR: return exrfile_read(path, out, mem, err);
    case IMAGEIO_PNG: return pngfile_read(path, out, mem, err);
    case IMAGEIO_RGBE: return rgbe_read(path, out, mem, err);
    case IMAGEIO_PFM: return pfm_read(path, out, mem, err);
    case IMAGEIO_UNKNOWN: break;
    }
    return error_set(err, path, 0,
                     "unknown image format (not OpenEXR, PNG, Radiance .hdr or PFM)");
}

imageio_format imageio_detect(const char *path)
{
    unsigned char m[8] = {0};
    int n = read_magic(path, m, NULL);
    return n > 0 ? format_of_magic(m, (size_t)n) : IMAGEIO_UNKNOWN;
}

/* ".ext" of path, "" if none (a dot in a folder name does not count) */
static const char *extension(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) ? dot : "";
}

/* the format imageio_write picks for path's extension; IMAGEIO_UNKNOWN for none it knows */
static imageio_format format_of_extension(const char *path)
{
    const char *x = extension(path);
    if (!strcasecmp(x, ".exr")) return IMAGEIO_EXR;
    if (!strcasecmp(x, ".png")) return IMAGEIO_PNG;
    if (!strcasecmp(x, ".pfm")) return IMAGEIO_PFM;
    if (!strcasecmp(x, ".hdr")) return IMAGEIO_RGBE;
    return IMAGEIO_UNKNOWN;
}

int imageio_can_write(const char *path) { return format_of_extension(path) != IMAGEIO_UNKNOWN; }

int imageio_write_as(const char *path, imageio_format format, const image *im, const tonemap_params *tm,
                     error *err)
{
    switch (format != IMAGEIO_UNKNOWN ? format : format_of_extension(path)) {
    case IMAGEIO_EXR: return exrfile_write(path, im, 0, err);
    case IMAGEIO_PNG: return pngfile_write(path, im, tm, err);
    case IMAGEIO_PFM: return pfm_write(path, im, err);
    case IMAGEIO_RGBE: return rgbe_write(path, im, err);
    default:
        return error_set(err, path, 0, "cannot tell the image format from the name; use .exr, .png, "
                                       ".pfm or .hdr");
    }
}

int imageio_write(const char *path, const image *im, const tonemap_params *tm, error *err)
{
    return imageio_write_as(path, IMAGEIO_UNKNOWN, im, tm, err);
}

/* ---- several files as one output ----------------------------------------------------------- */

int imageio_write_set(int n, const char *const *paths, const image *const *images,
                      const tonemap_params *const *tms, const imageio_format *formats, error *err)
{
    assert(n >= 1 && n <= IMAGEIO_SET_MAX);
    imageio_format fmt[IMAGEIO_SET_MAX]; /* decided by the targets' names, not the temporaries' */
    for (int k = 0; k < n; k++)
        fmt[k] = formats && formats[k] != IMAGEIO_UNKNOWN ? formats[k] : format_of_extension(paths[k]);
    if (n == 1) return imageio_write_as(paths[0], fmt[0], images[0], tms ? tms[0] : NULL, err); /* atomic already */
    char part[IMAGEIO_SET_MAX][ERROR_FILE_MAX], tag[32];
    snprintf(tag, sizeof tag, ".partial-%ld", (long)getpid());
    for (int k = 0; k < n; k++) { /* "sky_px.exr" -> "sky_px.partial-PID.exr": same format */
        const char *x = extension(paths[k]);
        size_t stem = strlen(paths[k]) - strlen(x);
        int len = snprintf(part[k], sizeof part[k], "%.*s%s%s", (int)stem, paths[k], tag, x);
        if (len < 0 || (size_t)len >= sizeof part[k]) return error_set(err, paths[k], 0, "path is too long");
        /* a folder in a target's place would fail its rename at the end: refuse it first */
        struct stat st;
        if (stat(paths[k], &st) == 0 && !S_ISREG(st.st_mode))
            return error_set(err, paths[k], 0, "cannot write an image here: %s",
                             S_ISDIR(st.st_mode) ? "it is a folder" : "it is not a regular file");
    }
    int done = 0;
    for (; done < n; done++)
        if (imageio_write_as(part[done], fmt[done], images[done], tms ? tms[done] : NULL, err)) break;
    if (done < n) {
        for (int k = 0; k < done; k++) unlink(part[k]);
        if (err) { /* name the target, not its temporary */
            char msg[ERROR_MSG_MAX];
            memcpy(msg, err->msg, sizeof msg);
            error_set(err, paths[done], 0, "%s", msg);
        }
        return -1;
    }
    for (int k = 0; k < n; k++)
        if (rename(part[k], paths[k]) != 0) {
            int e = errno;
            for (int j = k; j < n; j++) unlink(part[j]);
            return error_set(err, paths[k], 0, "cannot rename the finished file into place: %s (%d of %d "
                             "files were already replaced, the rest left as they were)", strerror(e), k, n);
        }
    return 0;
}
