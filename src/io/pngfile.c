/* pngfile.c - PNG read / write through libpng (see include/envtex/io/pngfile.h).
 *
 * libpng reports errors by calling an error function that must not return: ours copies the
 * message and longjmps back to the setjmp in the function that called libpng.  Everything that
 * must be freed after such a jump lives in a struct owned by the CALLER of that function, so no
 * local variable of the setjmp function is relied on after the jump.
 */
#include "envtex/io/pngfile.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envtex/io/fileio.h"
#include "envtex/io/infile.h"

/* Deflate's largest expansion: a 258-byte match coded in 2 bits is 1032 : 1 (RFC 1951). */
#define PNG_MAX_INFLATE_RATIO 1032.0

typedef struct png_job {
    const char *path;
    FILE *f;
    png_structp png;
    png_infop info;
    unsigned char *bytes; /* decoded / encoded rows */
    png_bytep *rows;
    float *lut;           /* decode table (sRGB or a gAMA power law), 256 or 65536 entries */
    png_fixed_point gama; /* writing: gAMA's file gamma x 100000, or 0 for an sRGB chunk */
    image im;
    budget *mem;                   /* reading: the run's memory budget (may be NULL) */
    double image_bytes, row_bytes; /* reading: charged to it for the image and the decoded rows */
    char msg[256];                 /* libpng's message */
    int errnum;                    /* writing: errno of a failed fwrite or fflush, else 0 */
} png_job;

static void job_error(png_structp png, png_const_charp msg)
{
    png_job *job = png_get_error_ptr(png);
    snprintf(job->msg, sizeof job->msg, "%s", msg ? msg : "libpng error");
    png_longjmp(png, 1);
}

static void job_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

/* ---- reading ------------------------------------------------------------------------------- */

/* The file gamma of a PNG whose codes follow a power law, encoded = linear^file_gamma, or 0 for
 * sRGB.  libpng's rule: an sRGB or iCCP chunk wins over gAMA (libpng also reports a gAMA for an
 * sRGB chunk, so sRGB is asked first); a gAMA chunk alone is a power law; no colour information
 * at all is taken as sRGB.  libpng drops a gAMA outside [1/6250, 6250] (so 0 never comes
 * back); the g > 0 test guards the division 1 / file_gamma all the same. */
static double file_gamma_of(png_structp png, png_infop info)
{
    if (png_get_valid(png, info, PNG_INFO_sRGB) || png_get_valid(png, info, PNG_INFO_iCCP))
        return 0.0;
    double g = 0.0;
    if (!png_get_gAMA(png, info, &g) || !(g > 0.0)) return 0.0;
    return g;
}

static int read_body(png_job *job, error *err)
{
    if (setjmp(png_jmpbuf(job->png)))
        return error_set(err, job->path, 0, "corrupt or truncated PNG: %s", job->msg);
    png_init_io(job->png, job->f);
    png_read_info(job->png, job->info);
    png_uint_32 w, h;
    int depth, type, interlace;
    png_get_IHDR(job->png, job->info, &w, &h, &depth, &type, &interlace, NULL, NULL);
    if (image_check_size((long)w, (long)h, job->path, err)) return -1; /* before any pixel memory */
    /* The pixels are deflated, and deflate expands at most PNG_MAX_INFLATE_RATIO times, so the
     * file size bounds the size a PNG can truly have: a 100-byte file that claims 16384 x 16384
     * is refused before 3 GB are allocated.  raw = h (1 + ceil(w channels depth / 8)), the
     * filtered rows of a non-interlaced image (an interlaced one has more). */
    struct stat st;
    double raw =
        (double)h * (1.0 + ceil((double)w * png_get_channels(job->png, job->info) * depth / 8.0));
    if (fstat(fileno(job->f), &st) == 0 && raw > PNG_MAX_INFLATE_RATIO * (double)st.st_size)
        return error_set(err, job->path, 0,
                         "corrupt or truncated PNG: %u x %u pixels need %.0f bytes of image data, "
                         "more than a %lld-byte file can hold",
                         (unsigned)w, (unsigned)h, raw, (long long)st.st_size);

    /* every layout to 8- or 16-bit RGB */
    if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(job->png);
    if (type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(job->png);
    png_set_strip_alpha(job->png); /* alpha, and the alpha a palette's tRNS expands to */
    if (type == PNG_COLOR_TYPE_GRAY || type == PNG_COLOR_TYPE_GRAY_ALPHA)
        png_set_gray_to_rgb(job->png);
    if (interlace != PNG_INTERLACE_NONE) png_set_interlace_handling(job->png);
    png_read_update_info(job->png, job->info);
    int bytes_per = png_get_bit_depth(job->png, job->info) == 16 ? 2 : 1;
    size_t rowbytes = png_get_rowbytes(job->png, job->info);
    if (png_get_channels(job->png, job->info) != 3 || rowbytes != (size_t)w * 3 * (size_t)bytes_per)
        return error_set(err, job->path, 0, "unexpected PNG layout after conversion");

    /* decoded, a pixel takes 12 bytes of float RGB and 3 or 6 of libpng's rows: a 32 KB 1-bit
     * grey file of 16384 x 16384 claims 3.75 GiB (the deflate bound above allows it) */
    int texel = IMAGE_TEXEL_BYTES + 3 * bytes_per;
    if (budget_charge(job->mem, (double)w * h * texel, job->path, 0, err,
                      "%u x %u texels x %d bytes", (unsigned)w, (unsigned)h, texel))
        return -1;
    job->image_bytes = (double)w * h * IMAGE_TEXEL_BYTES;
    job->row_bytes = (double)w * h * 3 * bytes_per;
    if (image_alloc(&job->im, (int)w, (int)h, err)) return error_prefix(err, "%s", job->path);
    job->bytes = malloc(rowbytes * h);
    job->rows = malloc(sizeof *job->rows * h);
    size_t levels = bytes_per == 2 ? 65536 : 256;
    job->lut = malloc(sizeof *job->lut * levels);
    if (!job->bytes || !job->rows || !job->lut)
        return error_set(err, job->path, 0, "out of memory for a %u x %u PNG", (unsigned)w,
                         (unsigned)h);
    double file_gamma = file_gamma_of(job->png, job->info);
    for (size_t i = 0; i < levels; i++) { /* code = i / max code */
        double code = (double)i / (double)(levels - 1);
        job->lut[i] =
            (float)(file_gamma > 0.0 ? pow(code, 1.0 / file_gamma) /* linear = code^(1/g) */
                                     : tonemap_srgb_decode(code));
    }
    for (png_uint_32 y = 0; y < h; y++) job->rows[y] = job->bytes + rowbytes * y;
    png_read_image(job->png, job->rows);
    png_read_end(job->png, NULL);

    size_t count = (size_t)w * h * 3;
    float *dst = job->im.px;
    if (bytes_per == 1) {
        for (size_t i = 0; i < count; i++) dst[i] = job->lut[job->bytes[i]];
    } else {
        for (size_t i = 0; i < count; i++) /* 16-bit samples are big endian */
            dst[i] = job->lut[(size_t)job->bytes[2 * i] << 8 | job->bytes[2 * i + 1]];
    }
    return 0;
}

int pngfile_read(const char *path, image *out, budget *mem, error *err)
{
    out->w = out->h = 0;
    out->px = NULL;
    png_job job = {.path = path, .mem = mem};
    int rc = -1;
    unsigned char sig[8];
    job.f = infile_fopen(path, NULL, err);
    if (!job.f) return -1;
    size_t got = fread(sig, 1, sizeof sig, job.f);
    if (got == 0 && ferror(job.f)) { /* e.g. a folder: EISDIR */
        error_set(err, path, 0, "cannot open: %s", strerror(errno));
        goto done;
    }
    if (got != sizeof sig || png_sig_cmp(sig, 0, sizeof sig)) {
        error_set(err, path, 0, "not a PNG file");
        goto done;
    }
    job.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &job, job_error, job_warning);
    if (job.png) job.info = png_create_info_struct(job.png);
    if (!job.png || !job.info) {
        error_set(err, path, 0, "out of memory starting libpng");
        goto done;
    }
    png_set_sig_bytes(job.png, sizeof sig);
    if (read_body(&job, err)) goto done;
    *out = job.im;
    job.im.px = NULL;
    rc = 0;
done:
    if (job.png) png_destroy_read_struct(&job.png, job.info ? &job.info : NULL, NULL);
    fclose(job.f);
    free(job.bytes);
    free(job.rows);
    free(job.lut);
    image_free(&job.im);
    budget_release(mem, job.row_bytes + (rc ? job.image_bytes : 0)); /* what was freed */
    return rc;
}

/* ---- writing ------------------------------------------------------------------------------- */

/* libpng's own write function reports a failed fwrite as "Write Error" and nothing more; these
 * keep errno (a full disk: "No space left on device") for the message. */
static void job_write(png_structp png, png_bytep data, size_t n)
{
    png_job *job = png_get_io_ptr(png);
    if (fwrite(data, 1, n, job->f) != n) {
        job->errnum = errno ? errno : EIO;
        png_error(png, "write error");
    }
}

static void job_flush(png_structp png)
{
    png_job *job = png_get_io_ptr(png);
    if (fflush(job->f) != 0) {
        job->errnum = errno ? errno : EIO;
        png_error(png, "write error");
    }
}

static int write_body(png_job *job, int w, int h, const uint8_t *rgb8, error *err)
{
    if (setjmp(png_jmpbuf(job->png))) {
        if (job->errnum) /* say why, as the other writers do */
            return error_set(err, job->path, 0, "cannot write: %s", strerror(job->errnum));
        return error_set(err, job->path, 0, "cannot write PNG: %s", job->msg);
    }
    png_set_write_fn(job->png, job, job_write, job_flush);
    png_set_IHDR(job->png, job->info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (job->gama > 0)
        png_set_gAMA_fixed(job->png, job->info, job->gama); /* power law alone */
    else
        png_set_sRGB(job->png, job->info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(job->png, job->info);
    for (int y = 0; y < h; y++) png_write_row(job->png, rgb8 + (size_t)y * (size_t)w * 3);
    png_write_end(job->png, NULL);
    return 0;
}

/* Write the bytes atomically with one colour chunk: gAMA of `gama` (the file gamma x 100000)
 * when gama > 0, else sRGB.  The public functions name the two cases. */
static int write_png(const char *path, png_fixed_point gama, int w, int h, const uint8_t *rgb8,
                     error *err)
{
    char tmp[ERROR_FILE_MAX];
    png_job job = {.path = path, .gama = gama};
    int rc = -1;
    job.f = fileio_tmp_fopen(path, tmp, err);
    if (!job.f) return -1;
    job.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &job, job_error, job_warning);
    if (job.png) job.info = png_create_info_struct(job.png);
    if (!job.png || !job.info) {
        error_set(err, path, 0, "out of memory starting libpng");
        goto done;
    }
    if (write_body(&job, w, h, rgb8, err)) goto done;
    rc = 0;
done:
    if (job.png) png_destroy_write_struct(&job.png, job.info ? &job.info : NULL);
    if (job.f && fclose(job.f) != 0 && rc == 0)
        rc = error_set(err, path, 0, "cannot write: %s", strerror(errno));
    if (rc != 0) {
        fileio_tmp_abandon(tmp);
        return -1;
    }
    return fileio_tmp_commit(tmp, path, err);
}

int pngfile_write_rgb8(const char *path, int w, int h, const uint8_t *rgb8, error *err)
{
    if (!rgb8 || image_check_size(w, h, path, err))
        return error_set(err, path, 0, "cannot write an empty or invalid image");
    return write_png(path, 0, w, h, rgb8, err); /* sRGB chunk */
}

int pngfile_write_rgb8_gamma(const char *path, int w, int h, const uint8_t *rgb8, double gamma,
                             error *err)
{
    if (!rgb8 || image_check_size(w, h, path, err))
        return error_set(err, path, 0, "cannot write an empty or invalid image");
    if (!(gamma >= 1.0 / PNGFILE_GAMMA_MAX && gamma <= PNGFILE_GAMMA_MAX))
        return error_set(err, path, 0,
                         "gamma %g cannot be recorded in a PNG (a gAMA chunk holds "
                         "gammas from 1/%g to %g)",
                         gamma, PNGFILE_GAMMA_MAX, PNGFILE_GAMMA_MAX);
    /* encoded = linear^(1/gamma): the file gamma is 1/gamma, stored x 100000 (2.2 -> 45455),
     * within [16, 625000000], which libpng accepts */
    png_fixed_point gama = (png_fixed_point)floor(100000.0 / gamma + 0.5);
    return write_png(path, gama, w, h, rgb8, err);
}

int pngfile_write(const char *path, const image *im, const tonemap_params *tm, error *err)
{
    if (!im || !im->px || image_check_size(im->w, im->h, path, err))
        return error_set(err, path, 0, "cannot write an empty or invalid image");
    tonemap_params def = tonemap_defaults();
    uint8_t *buf = malloc((size_t)im->w * (size_t)im->h * 3);
    if (!buf) return error_set(err, path, 0, "out of memory for a %d x %d PNG", im->w, im->h);
    const tonemap_params *t = tm ? tm : &def;
    tonemap_image(t, im, buf);
    /* label the file with the curve tonemap_image encoded with */
    int rc = t->gamma > 0.0 ? pngfile_write_rgb8_gamma(path, im->w, im->h, buf, t->gamma, err)
                            : pngfile_write_rgb8(path, im->w, im->h, buf, err);
    free(buf);
    return rc;
}
