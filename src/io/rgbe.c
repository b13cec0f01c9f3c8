/* rgbe.c - Radiance .hdr (RGBE) read / write (see include/envtex/io/rgbe.h). */
#include "envtex/io/rgbe.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envtex/io/fileio.h"

/* Below this the brightest channel stores as black (e = 0): RGBE's smallest exponent is 2^-128,
 * and Radiance itself uses 1e-32 as its "black" cut-off. */
#define RGBE_BLACK 1e-32

/* The fewest bytes a scanline can take: one 4-byte pixel (flat) or the 4-byte RLE marker. */
#define RGBE_MIN_SCANLINE_BYTES 4L

void rgbe_to_float(const unsigned char in[4], float c[3])
{
    if (in[3] == 0) {
        c[0] = c[1] = c[2] = 0.0f;
        return;
    }
    double f = ldexp(1.0, (int)in[3] - (128 + 8));                 /* 2^(e - 128) / 256 */
    for (int k = 0; k < 3; k++) c[k] = (float)((in[k] + 0.5) * f); /* middle of the bin */
}

void rgbe_from_float(const float c[3], unsigned char out[4])
{
    double v[3];
    for (int k = 0; k < 3; k++) {
        double x = c[k];
        v[k] = isnan(x) || x < 0.0 ? 0.0 : x > FLT_MAX ? FLT_MAX : x;
    }
    double m = fmax(v[0], fmax(v[1], v[2]));
    if (m < RGBE_BLACK) {
        memset(out, 0, 4);
        return;
    }
    int e;
    double frac = frexp(m, &e); /* m = frac 2^e, frac in [0.5, 1) */
    if (e + 128 > 255) {        /* beyond the largest RGBE value */
        memset(out, 255, 4);
        return;
    }
    double scale = frac * 256.0 / m; /* = 2^(8 - e): the brightest mantissa lands in [128, 256) */
    for (int k = 0; k < 3; k++) {
        double q = v[k] * scale;
        out[k] = (unsigned char)(q >= 255.0 ? 255.0 : q);
    }
    out[3] = (unsigned char)(e + 128);
}

/* ---- reading ------------------------------------------------------------------------------- */

/* One scanline of w pixels into scan (4 bytes a pixel).  0 ok, -1 with a message. */
static int read_scanline(const unsigned char *d, size_t n, size_t *at, unsigned char *scan, long w,
                         long y, const char *path, error *err)
{
    size_t p = *at;
    if (w >= 8 && w <= 0x7fff && n - p >= 4 && d[p] == 2 && d[p + 1] == 2 && !(d[p + 2] & 0x80)) {
        /* new-style RLE: the four channels one after the other, each as runs and literals */
        long len = (long)d[p + 2] << 8 | d[p + 3];
        if (len != w)
            return error_set(err, path, 0, "scanline %ld: RLE length %ld, expected %ld", y, len, w);
        p += 4;
        for (int ch = 0; ch < 4; ch++) {
            long x = 0;
            while (x < w) {
                if (p >= n) goto truncated;
                long c = d[p++];
                if (c > 128) { /* a run: c - 128 copies of the next byte */
                    c -= 128;
                    if (c > w - x) goto overflow;
                    if (p >= n) goto truncated;
                    unsigned char v = d[p++];
                    for (long i = 0; i < c; i++) scan[4 * (x + i) + ch] = v;
                } else { /* a literal: c bytes */
                    if (c == 0)
                        return error_set(err, path, 0, "scanline %ld: zero-length RLE literal", y);
                    if (c > w - x) goto overflow;
                    if (n - p < (size_t)c) goto truncated;
                    for (long i = 0; i < c; i++) scan[4 * (x + i) + ch] = d[p + (size_t)i];
                    p += (size_t)c;
                }
                x += c;
            }
        }
    } else {
        /* flat pixels, possibly with old-style runs (1,1,1,count: repeat the previous pixel
         * count << shift times, shift growing by 8 for consecutive run markers) */
        long x = 0;
        int shift = 0;
        while (x < w) {
            if (n - p < 4) goto truncated;
            const unsigned char *q = d + p;
            p += 4;
            if (q[0] == 1 && q[1] == 1 && q[2] == 1) {
                if (x == 0)
                    return error_set(err, path, 0,
                                     "scanline %ld: old-style run with no pixel before it", y);
                if (shift > 16) goto overflow;
                long count = (long)q[3] << shift;
                if (count > w - x) goto overflow;
                for (long i = 0; i < count; i++) memcpy(scan + 4 * (x + i), scan + 4 * (x - 1), 4);
                x += count;
                shift += 8;
            } else {
                memcpy(scan + 4 * x, q, 4);
                x++;
                shift = 0;
            }
        }
    }
    *at = p;
    return 0;
truncated:
    return error_set(err, path, 0,
                     "truncated Radiance file: scanline %ld of the pixels is incomplete", y);
overflow:
    return error_set(err, path, 0, "corrupt Radiance file: a run overflows scanline %ld", y);
}

/* Next header line [*at, end of line) into line (cut to its size); -1 when no newline is left. */
static int next_line(const unsigned char *d, size_t n, size_t *at, char *line, size_t cap)
{
    const unsigned char *nl = memchr(d + *at, '\n', n - *at);
    if (!nl) return -1;
    size_t len = (size_t)(nl - (d + *at));
    size_t keep = len < cap - 1 ? len : cap - 1;
    memcpy(line, d + *at, keep);
    line[keep] = '\0';
    while (keep > 0 && (line[keep - 1] == '\r' || line[keep - 1] == ' ' || line[keep - 1] == '\t'))
        line[--keep] = '\0';
    *at += len + 1;
    return 0;
}

/* The text header of the n bytes at d: "#?", the variables up to an empty line (FORMAT must be
 * 32-bit_rle_rgbe), the resolution "-Y H +X W".  0 with *at after it, or -1 with *err. */
static int read_header(const unsigned char *d, size_t n, size_t *at, long *w, long *h,
                       const char *path, error *err)
{
    char line[256];
    if (n < 2 || d[0] != '#' || d[1] != '?')
        return error_set(err, path, 0, "not a Radiance file (it must start with #?)");
    if (next_line(d, n, at, line, sizeof line)) goto truncated;
    for (;;) { /* variables up to the empty line */
        if (next_line(d, n, at, line, sizeof line)) goto truncated;
        if (!line[0]) break;
        if (!strncmp(line, "FORMAT=", 7) && strcmp(line + 7, "32-bit_rle_rgbe") != 0)
            return error_set(err, path, 0,
                             "Radiance format \"%s\" is not supported (only 32-bit_rle_rgbe)",
                             line + 7);
    }
    if (next_line(d, n, at, line, sizeof line)) goto truncated;
    char ya[8], xa[8];
    int used = 0;
    if (sscanf(line, "%7s %ld %7s %ld%n", ya, h, xa, w, &used) != 4 || line[used] != '\0')
        return error_set(err, path, 0, "bad Radiance resolution line \"%s\"", line);
    if (strcmp(ya, "-Y") != 0 || strcmp(xa, "+X") != 0)
        return error_set(err, path, 0,
                         "Radiance orientation \"%s ... %s\" is not supported (only -Y H +X W)", ya,
                         xa);
    return 0;
truncated:
    return error_set(err, path, 0, "truncated Radiance header");
}

int rgbe_read(const char *path, image *out, budget *mem, error *err)
{
    out->w = out->h = 0;
    out->px = NULL;
    unsigned char *d = NULL, *scan = NULL;
    size_t n = 0, at = 0;
    int rc = -1;
    image im = {0};
    double image_bytes = 0; /* charged: the image (not its scanline buffer, 128 KB at most) */
    if (fileio_read_all(path, &d, &n, mem, err)) return -1;
    long h, w;
    if (read_header(d, n, &at, &w, &h, path, err)) goto done;
    if (image_check_size(w, h, path, err)) goto done;
    /* Every scanline takes at least RGBE_MIN_SCANLINE_BYTES (a pixel, or the RLE marker), so
     * the file size bounds the height before the image is allocated: a 100-byte file that
     * claims 16384 x 16384 is refused here instead of costing 3 GB. */
    if ((size_t)h > (n - at) / RGBE_MIN_SCANLINE_BYTES) {
        error_set(err, path, 0,
                  "truncated Radiance file: %ld scanlines need at least %ld bytes, the file has "
                  "%zu after its header",
                  h, h * RGBE_MIN_SCANLINE_BYTES, n - at);
        goto done;
    }
    /* That check bounds the height, not the memory: old-style runs repeat a pixel up to 255 << 16
     * times, so a 32768-pixel scanline fits in 12 bytes and a 96 KB file claims 3 GB.  The
     * decoded size is charged from the header before anything is allocated. */
    if (budget_charge(mem, (double)w * h * IMAGE_TEXEL_BYTES, path, 0, err,
                      "%ld x %ld texels x %d bytes", w, h, IMAGE_TEXEL_BYTES))
        goto done;
    image_bytes = (double)w * h * IMAGE_TEXEL_BYTES;
    if (image_alloc(&im, (int)w, (int)h, err)) {
        error_prefix(err, "%s", path);
        goto done;
    }
    scan = malloc((size_t)w * 4);
    if (!scan) {
        error_set(err, path, 0, "out of memory");
        goto done;
    }
    for (long y = 0; y < h; y++) {
        if (read_scanline(d, n, &at, scan, w, y, path, err)) goto done;
        float *dst = image_px(&im, 0, (int)y);
        for (long x = 0; x < w; x++) rgbe_to_float(scan + 4 * x, dst + 3 * x);
    }
    *out = im;
    im.px = NULL;
    rc = 0;
done:
    free(d);
    free(scan);
    budget_release(mem, (double)n + 1);       /* the file's bytes (fileio_read_all) */
    if (rc) budget_release(mem, image_bytes); /* and the image, freed */
    image_free(&im);
    return rc;
}

/* ---- writing ------------------------------------------------------------------------------- */

/* RLE-encode one channel (bytes v[0], v[4], v[8] ... of w pixels) into dst; returns the byte
 * count (at most w + w / 128 + 1).  Runs of 4 or more equal bytes become (128 + count, byte)
 * with count <= 127; everything else goes into literals (count, bytes...) of at most 128. */
static size_t rle_channel(const unsigned char *v, long w, unsigned char *dst)
{
    size_t o = 0;
    long x = 0;
    while (x < w) {
        long run = 1;
        while (x + run < w && run < 127 && v[4 * (x + run)] == v[4 * x]) run++;
        if (run >= 4) {
            dst[o++] = (unsigned char)(128 + run);
            dst[o++] = v[4 * x];
            x += run;
            continue;
        }
        long start = x, len = 0;
        while (x < w && len < 128) {
            long r = 1;
            while (x + r < w && r < 4 && v[4 * (x + r)] == v[4 * x]) r++;
            if (r >= 4) break; /* a run starts here: end the literal */
            x++;
            len++;
        }
        dst[o++] = (unsigned char)len;
        for (long i = 0; i < len; i++) dst[o++] = v[4 * (start + i)];
    }
    return o;
}

static int write_rgbe(const char *path, const image *im, int rle, error *err)
{
    if (!im || !im->px || image_check_size(im->w, im->h, path, err))
        return error_set(err, path, 0, "cannot write an empty or invalid image");
    if (im->w < 8 || im->w > 0x7fff) rle = 0; /* new-style RLE is undefined outside [8, 32767] */
    char tmp[ERROR_FILE_MAX];
    FILE *f = fileio_tmp_fopen(path, tmp, err);
    if (!f) return -1;
    size_t w = (size_t)im->w;
    unsigned char *scan = malloc(4 * w), *packed = malloc(4 * (w + w / 128 + 2) + 4);
    int oom = !scan || !packed;
    int ok =
        !oom && fprintf(f, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n", im->h, im->w) > 0;
    for (int y = 0; ok && y < im->h; y++) {
        const float *src = image_px(im, 0, y);
        for (size_t x = 0; x < w; x++) rgbe_from_float(src + 3 * x, scan + 4 * x);
        if (!rle) {
            ok = fwrite(scan, 4, w, f) == w;
            continue;
        }
        size_t o = 0;
        packed[o++] = 2;
        packed[o++] = 2;
        packed[o++] = (unsigned char)(w >> 8);
        packed[o++] = (unsigned char)(w & 0xff);
        for (int ch = 0; ch < 4; ch++) o += rle_channel(scan + ch, (long)w, packed + o);
        ok = fwrite(packed, 1, o, f) == o;
    }
    int e = errno;
    free(scan);
    free(packed);
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

int rgbe_write(const char *path, const image *im, error *err)
{
    return write_rgbe(path, im, 1, err);
}

int rgbe_write_flat(const char *path, const image *im, error *err)
{
    return write_rgbe(path, im, 0, err);
}
