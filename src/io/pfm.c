/* pfm.c - Portable Float Map read / write (see include/envtex/io/pfm.h). */
#include "envtex/io/pfm.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envtex/io/fileio.h"

/* Skip white space, then read a token of at most 63 characters; returns its length (0 at end). */
static size_t next_token(const unsigned char *d, size_t n, size_t *at, char tok[64])
{
    while (*at < n && isspace(d[*at])) (*at)++;
    size_t len = 0;
    while (*at < n && !isspace(d[*at]) && len < 63) tok[len++] = (char)d[(*at)++];
    tok[len] = '\0';
    return len;
}

/* A whole decimal integer token, or -1. */
static long parse_long(const char *t)
{
    if (!*t) return -1;
    long v = 0;
    for (; *t; t++) {
        if (*t < '0' || *t > '9' || v > 1000000000L) return -1;
        v = v * 10 + (*t - '0');
    }
    return v;
}

/* The 32 bits at p in the file's byte order. */
static uint32_t load_u32(const unsigned char *p, int little)
{
    if (little)
        return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    return (uint32_t)p[3] | (uint32_t)p[2] << 8 | (uint32_t)p[1] << 16 | (uint32_t)p[0] << 24;
}

/* The file's floats at p (rows bottom to top, `chans` a pixel) into the allocated *im. */
static void decode_pixels(const unsigned char *p, int little, int chans, image *im)
{
    for (long row = 0; row < im->h; row++) {
        float *dst = image_px(im, 0, (int)(im->h - 1 - row)); /* file rows go bottom to top */
        for (long x = 0; x < im->w; x++) {
            float v[3];
            for (int k = 0; k < chans; k++, p += 4) {
                uint32_t u = load_u32(p, little);
                memcpy(&v[k], &u, 4);
            }
            if (chans == 1) v[1] = v[2] = v[0];
            memcpy(dst + 3 * x, v, sizeof v);
        }
    }
}

int pfm_read(const char *path, image *out, budget *mem, error *err)
{
    out->w = out->h = 0;
    out->px = NULL;
    unsigned char *d = NULL;
    size_t n = 0, at = 2;
    int rc = -1;
    image im = {0};
    double charged = 0; /* the image's bytes, once charged */
    if (fileio_read_all(path, &d, &n, mem, err)) return -1;
    if (n < 2 || d[0] != 'P' || (d[1] != 'F' && d[1] != 'f')) {
        error_set(err, path, 0, "not a PFM file (it must start with PF or Pf)");
        goto done;
    }
    int chans = d[1] == 'F' ? 3 : 1;
    char tw[64], th[64], ts[64];
    if (!next_token(d, n, &at, tw) || !next_token(d, n, &at, th) || !next_token(d, n, &at, ts)) {
        error_set(err, path, 0, "truncated PFM header");
        goto done;
    }
    long w = parse_long(tw), h = parse_long(th);
    if (w < 0 || h < 0) {
        error_set(err, path, 0, "bad PFM size \"%s %s\"", tw, th);
        goto done;
    }
    char *end;
    double scale = strtod(ts, &end);
    if (*end || scale == 0.0 || isnan(scale)) {
        error_set(err, path, 0,
                  "bad PFM scale \"%s\" (its sign gives the byte order; 0 is not allowed)", ts);
        goto done;
    }
    if (at >= n || !isspace(d[at])) {
        error_set(err, path, 0, "truncated PFM header");
        goto done;
    }
    at++; /* exactly one white-space character ends the header */
    if (image_check_size(w, h, path, err)) goto done;
    size_t count = (size_t)w * (size_t)h * (size_t)chans; /* floats in the file */
    /* A header written with Windows line ends ends in "\r\n": one line end, not "\r" followed
     * by a first pixel byte of 0x0A (read that way every float would be shifted by a byte).  The
     * file's size tells the two apart: after a lone "\r" the pixels leave no byte to spare. */
    if (d[at - 1] == '\r' && at < n && d[at] == '\n' && n - (at + 1) >= count * 4) at++;
    if (n - at < count * 4) {
        error_set(err, path, 0, "truncated PFM: %zu bytes of pixels, %zu expected", n - at,
                  count * 4);
        goto done;
    }
    if (budget_charge(mem, (double)w * h * IMAGE_TEXEL_BYTES, path, 0, err,
                      "%ld x %ld texels x %d bytes", w, h, IMAGE_TEXEL_BYTES))
        goto done;
    charged = (double)w * h * IMAGE_TEXEL_BYTES;
    if (image_alloc(&im, (int)w, (int)h, err)) {
        error_prefix(err, "%s", path);
        goto done;
    }
    decode_pixels(d + at, scale < 0, chans, &im);
    *out = im;
    im.px = NULL;
    rc = 0;
done:
    free(d);
    budget_release(mem, (double)n + 1); /* the file's bytes (fileio_read_all) */
    if (rc) budget_release(mem, charged);
    image_free(&im);
    return rc;
}

int pfm_write(const char *path, const image *im, error *err)
{
    if (!im || !im->px || image_check_size(im->w, im->h, path, err))
        return error_set(err, path, 0, "cannot write an empty or invalid image");
    char tmp[ERROR_FILE_MAX];
    FILE *f = fileio_tmp_fopen(path, tmp, err);
    if (!f) return -1;
    size_t rowbytes = (size_t)im->w * 3 * 4;
    unsigned char *row = malloc(rowbytes);
    int oom = row == NULL;
    int ok = !oom && fprintf(f, "PF\n%d %d\n-1.0\n", im->w, im->h) > 0;
    for (int y = im->h - 1; ok && y >= 0; y--) { /* bottom row first */
        const float *src = image_px(im, 0, y);
        for (size_t i = 0; i < (size_t)im->w * 3; i++) {
            uint32_t u;
            memcpy(&u, &src[i], 4);
            row[4 * i] = (unsigned char)u; /* little endian, whatever the host is */
            row[4 * i + 1] = (unsigned char)(u >> 8);
            row[4 * i + 2] = (unsigned char)(u >> 16);
            row[4 * i + 3] = (unsigned char)(u >> 24);
        }
        ok = fwrite(row, 1, rowbytes, f) == rowbytes;
    }
    int e = errno;
    free(row);
    if (fclose(f) != 0 && ok) {
        ok = 0;
        e = errno;
    }
    if (!ok) {
        fileio_tmp_abandon(tmp);
        return error_set(err, path, 0, "cannot write: %s", oom ? "out of memory" : strerror(e));
    }
    return fileio_tmp_commit(tmp, path, err);
}
