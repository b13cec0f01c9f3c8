/* imageio.c - read and write images by file name (see include/envtex/io/imageio.h). */
#include "envtex/io/imageio.h"

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

#include "envtex/io/exrfile.h"
#include "envtex/io/infile.h"
#include "envtex/io/pfm.h"
#include "envtex/io/pngfile.h"
#include "envtex/io/rgbe.h"

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
    do n = read(fd, m, 8);
    while (n < 0 && errno == EINTR);
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
    return error_set(err, path, 0, "unknown image format (not OpenEXR, PNG, Radiance .hdr or PFM)");
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

/* imageio_write_as, with `at` in the header of an OpenEXR file (NULL: none) */
static int write_as(const char *path, imageio_format format, const image *im,
                    const tonemap_params *tm, const exrfile_attrs *at, error *err)
{
    switch (format != IMAGEIO_UNKNOWN ? format : format_of_extension(path)) {
    case IMAGEIO_EXR: return exrfile_write_attrs(path, im, 0, at, err);
    case IMAGEIO_PNG: return pngfile_write(path, im, tm, err);
    case IMAGEIO_PFM: return pfm_write(path, im, err);
    case IMAGEIO_RGBE: return rgbe_write(path, im, err);
    default:
        return error_set(err, path, 0,
                         "cannot tell the image format from the name; use .exr, .png, "
                         ".pfm or .hdr");
    }
}

int imageio_write_as(const char *path, imageio_format format, const image *im,
                     const tonemap_params *tm, error *err)
{
    return write_as(path, format, im, tm, NULL, err);
}

int imageio_write(const char *path, const image *im, const tonemap_params *tm, error *err)
{
    return imageio_write_as(path, IMAGEIO_UNKNOWN, im, tm, err);
}

/* ---- several files as one output ----------------------------------------------------------- */

int imageio_write_set(int n, const char *const *paths, const image *const *images,
                      const tonemap_params *const *tms, const imageio_format *formats, error *err)
{
    return imageio_write_set_attrs(n, paths, images, tms, formats, NULL, err);
}

int imageio_write_set_attrs(int n, const char *const *paths, const image *const *images,
                            const tonemap_params *const *tms, const imageio_format *formats,
                            const exrfile_attrs *at, error *err)
{
    assert(n >= 1 && n <= IMAGEIO_SET_MAX);
    imageio_format fmt[IMAGEIO_SET_MAX]; /* decided by the targets' names, not the temporaries' */
    for (int k = 0; k < n; k++)
        fmt[k] =
            formats && formats[k] != IMAGEIO_UNKNOWN ? formats[k] : format_of_extension(paths[k]);
    if (n == 1) /* atomic already */
        return write_as(paths[0], fmt[0], images[0], tms ? tms[0] : NULL, at, err);
    char part[IMAGEIO_SET_MAX][ERROR_FILE_MAX], tag[32];
    snprintf(tag, sizeof tag, ".partial-%ld", (long)getpid());
    for (int k = 0; k < n; k++) { /* "sky_px.exr" -> "sky_px.partial-PID.exr": same format */
        const char *x = extension(paths[k]);
        size_t stem = strlen(paths[k]) - strlen(x);
        int len = snprintf(part[k], sizeof part[k], "%.*s%s%s", (int)stem, paths[k], tag, x);
        if (len < 0 || (size_t)len >= sizeof part[k])
            return error_set(err, paths[k], 0, "path is too long");
        /* a folder in a target's place would fail its rename at the end: refuse it first */
        struct stat st;
        if (stat(paths[k], &st) == 0 && !S_ISREG(st.st_mode))
            return error_set(err, paths[k], 0, "cannot write an image here: %s",
                             S_ISDIR(st.st_mode) ? "it is a folder" : "it is not a regular file");
    }
    int done = 0;
    for (; done < n; done++)
        if (write_as(part[done], fmt[done], images[done], tms ? tms[done] : NULL, at, err)) break;
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
            return error_set(err, paths[k], 0,
                             "cannot rename the finished file into place: %s (%d of %d "
                             "files were already replaced, the rest left as they were)",
                             strerror(e), k, n);
        }
    return 0;
}
