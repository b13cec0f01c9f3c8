/* test_exrfile.c - OpenEXR reading and writing through OpenEXRCore. */
#include <fcntl.h>
#include <math.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envtex/io/exrfile.h"
#include "envtex/io/pfm.h"
#include "envtex/io/imageio.h"
#include "testdir.h"
#include "unit.h"

/* The shared CC0 maps sit beside the repository (../shared/hdri, as tools/bench and
 * tools/programs/halve.c use them); tests run from the repository's root. */
#define COURTYARD "../shared/hdri/courtyard.exr"

/* A test picture with values over many decades, negatives, and a distinct value per pixel. */
static void fill_test_image(image *im, int w, int h)
{
    error err = {0};
    ck_assert_int_eq(image_alloc(im, w, h, &err), 0);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *p = image_px(im, x, y);
            p[0] = (float)(x + 1) * 0.37f;
            p[1] = (float)(y + 1) / 7.0f;
            p[2] = (float)((x * 31 + y * 17) % 23 - 11) * 0.013f * powf(10.0f, (float)(x % 5 - 2));
        }
}

static int count_tmp_files(void) { return count_files(".tmp."); }

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* Copy the first n bytes of src to dst. */
static void truncate_copy(const char *src, const char *dst, long n)
{
    FILE *f = fopen(src, "rb"), *g = fopen(dst, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_ptr_nonnull(g);
    char buf[4096];
    while (n > 0) { /* no ck_assert per byte: Check logs every assertion it runs */
        size_t want = n < (long)sizeof buf ? (size_t)n : sizeof buf;
        size_t got = fread(buf, 1, want, f);
        ck_assert_uint_eq(got, want);
        fwrite(buf, 1, got, g);
        n -= (long)got;
    }
    fclose(f);
    ck_assert_int_eq(fclose(g), 0);
}

/* ---- a test writer on OpenEXRCore directly, for layouts exrfile_write does not make ------ */

typedef struct tchan {
    const char *name;
    exr_pixel_type_t type; /* file type; data is float, or uint32 for EXR_PIXEL_UINT */
    const void *data;      /* data-window sized, planar, row-major */
} tchan;

/* When set, write_test_exr calls it on the part before writing the header (extra attributes). */
static exr_result_t (*test_header_hook)(exr_context_t ctx, int part);

static exr_result_t write_test_exr(const char *path, int tiled, exr_compression_t comp,
                                   exr_attr_box2i_t disp, exr_attr_box2i_t dw, const tchan *ch,
                                   int nch)
{
    exr_context_t ctx = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = NULL;
    exr_result_t r = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (r) return r;
    int part = 0;
    exr_attr_v2f_t center = {.x = 0.0f, .y = 0.0f};
    r = exr_add_part(ctx, "test", tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, &part);
    if (!r)
        r = exr_initialize_required_attr(ctx, part, &disp, &dw, 1.0f, &center, 1.0f,
                                         EXR_LINEORDER_INCREASING_Y, comp);
    if (!r && tiled)
        r = exr_set_tile_descriptor(ctx, part, 16, 16, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
    for (int c = 0; c < nch && !r; c++)
        r = exr_add_channel(ctx, part, ch[c].name, ch[c].type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (!r && test_header_hook) r = test_header_hook(ctx, part);
    if (!r) r = exr_write_header(ctx);
    int dww = dw.max.x - dw.min.x + 1, dwh = dw.max.y - dw.min.y + 1;
    int32_t lines = 16;
    if (!r && !tiled) r = exr_get_scanlines_per_chunk(ctx, part, &lines);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    int ready = 0;
    int ntx = tiled ? (dww + 15) / 16 : 1, nty = (dwh + lines - 1) / lines;
    for (int ty = 0; ty < nty && !r; ty++)
        for (int tx = 0; tx < ntx && !r; tx++) {
            exr_chunk_info_t ci;
            r = tiled ? exr_write_tile_chunk_info(ctx, part, tx, ty, 0, 0, &ci)
                      : exr_write_scanline_chunk_info(ctx, part, dw.min.y + ty * lines, &ci);
            if (!r)
                r = ready ? exr_encoding_update(ctx, part, &ci, &enc)
                          : exr_encoding_initialize(ctx, part, &ci, &enc);
            if (r) break;
            ready = 1;
            for (int c = 0; c < enc.channel_count; c++) {
                const tchan *t = NULL;
                for (int k = 0; k < nch; k++)
                    if (!strcmp(ch[k].name, enc.channels[c].channel_name)) t = &ch[k];
                size_t off = ((size_t)ty * (size_t)lines * (size_t)dww + (size_t)tx * 16) * 4;
                enc.channels[c].encode_from_ptr = (const uint8_t *)t->data + off;
                enc.channels[c].user_pixel_stride = 4;
                enc.channels[c].user_line_stride = 4 * dww;
                enc.channels[c].user_data_type =
                    t->type == EXR_PIXEL_UINT ? EXR_PIXEL_UINT : EXR_PIXEL_FLOAT;
                enc.channels[c].user_bytes_per_element = 4;
            }
            r = exr_encoding_choose_default_routines(ctx, part, &enc);
            if (!r) r = exr_encoding_run(ctx, part, &enc);
        }
    if (ready) exr_encoding_destroy(ctx, &enc);
    exr_result_t f = exr_finish(&ctx);
    return r ? r : f;
}

static exr_attr_box2i_t box(int x0, int y0, int x1, int y1)
{
    exr_attr_box2i_t b;
    b.min.x = x0;
    b.min.y = y0;
    b.max.x = x1;
    b.max.y = y1;
    return b;
}

/* planar float data w x h with value f(c, x, y) */
static float *planar(int w, int h, int c)
{
    float *d = malloc(sizeof *d * (size_t)w * (size_t)h);
    ck_assert_ptr_nonnull(d);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            d[y * w + x] = 0.25f * (float)(c + 1) + 0.01f * (float)x + 0.1f * (float)y;
    return d;
}

/* ---- tests ---------------------------------------------------------------------------------- */

START_TEST(test_float_exr_roundtrip_is_exact)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    fill_test_image(&im, 37, 19);
    ck_assert_int_eq(exrfile_write(in_dir("f.exr"), &im, 0, &err), 0);
    ck_assert_msg(exrfile_read(in_dir("f.exr"), &back, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(back.w, 37);
    ck_assert_int_eq(back.h, 19);
    ck_assert_int_eq(memcmp(im.px, back.px, sizeof(float) * 3 * 37 * 19), 0);
    ck_assert(!count_tmp_files());
    image_free(&im);
    image_free(&back);
    remove_dir();
}
END_TEST

/* A chunk that ZIP can barely not compress (a noisy path-traced render: tests/unit/data/
 * nearly_incompressible.pfm, its second 16-row chunk) is stored as is by OpenEXRCore 3.1, which
 * then wrote the ZIP-transformed bytes instead of the pixels (every reader got garbage); exrfile's
 * raw_guard puts the raw bytes back.  Purely random data does not show it (zlib then fails
 * outright and the library copies the pixels itself). */
START_TEST(test_barely_incompressible_exr_chunk_roundtrips_exactly)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    ck_assert_msg(pfm_read("tests/unit/data/nearly_incompressible.pfm", &im, NULL, &err) == 0, "%s",
                  err.msg);
    ck_assert_int_eq(exrfile_write(in_dir("noise.exr"), &im, 0, &err), 0);
    ck_assert_msg(exrfile_read(in_dir("noise.exr"), &back, NULL, &err) == 0, "%s", err.msg);
    long bad = 0;
    for (size_t i = 0; i < (size_t)im.w * im.h * 3; i++)
        bad += memcmp(&im.px[i], &back.px[i], sizeof(float)) != 0;
    ck_assert_msg(bad == 0, "%ld of %d values came back wrong", bad, im.w * im.h * 3);
    image_free(&im);
    image_free(&back);
    remove_dir();
}
END_TEST

START_TEST(test_half_exr_roundtrip_is_within_half_precision)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    fill_test_image(&im, 40, 33); /* more than one 16-line ZIP block */
    ck_assert_int_eq(exrfile_write(in_dir("h.exr"), &im, 1, &err), 0);
    ck_assert_msg(exrfile_read(in_dir("h.exr"), &back, NULL, &err) == 0, "%s", err.msg);
    for (size_t i = 0; i < 3 * 40 * 33; i++) {
        double v = im.px[i], b = back.px[i];
        /* half: 11 significant bits, so round-to-nearest is within 2^-11 relative for normal
         * values; below 2^-14 (subnormal) the step is 2^-24 absolute */
        ck_assert_msg(fabs(v - b) <= fabs(v) * 0x1p-11 + 0x1p-24, "%zu: %g vs %g", i, v, b);
    }
    ck_assert(memcmp(im.px, back.px, sizeof(float) * 3 * 40 * 33) != 0); /* it really is half */
    image_free(&im);
    image_free(&back);
    remove_dir();
}
END_TEST

START_TEST(test_courtyard_has_the_size_and_mean_its_readme_gives)
{
    if (access(COURTYARD, R_OK) != 0) return; /* shared HDRIs absent: nothing to check */
    image im = {0};
    error err = {0};
    ck_assert_msg(exrfile_read(COURTYARD, &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(im.w, 1024);
    ck_assert_int_eq(im.h, 512);
    double sum = 0.0;
    long nonfinite = 0;
    for (size_t i = 0; i < (size_t)3 * im.w * im.h; i++) {
        nonfinite += !isfinite(im.px[i]);
        sum += im.px[i];
    }
    ck_assert_int_eq(nonfinite, 0);
    ck_assert_near(sum / (3.0 * im.w * im.h), 0.56, 0.01);
    image_free(&im);
}
END_TEST

START_TEST(test_tiled_exr_with_partial_edge_tiles_reads)
{
    make_dir();
    int w = 37, h = 21; /* not multiples of the 16 x 16 tiles */
    float *r = planar(w, h, 0), *g = planar(w, h, 1), *b = planar(w, h, 2);
    tchan ch[3] = {{"R", EXR_PIXEL_HALF, r}, {"G", EXR_PIXEL_FLOAT, g}, {"B", EXR_PIXEL_HALF, b}};
    ck_assert_int_eq(write_test_exr(in_dir("t.exr"), 1, EXR_COMPRESSION_ZIP,
                                    box(0, 0, w - 1, h - 1), box(0, 0, w - 1, h - 1), ch, 3),
                     0);
    image im = {0};
    error err = {0};
    ck_assert_msg(imageio_read(in_dir("t.exr"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(im.w, w);
    ck_assert_int_eq(im.h, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *p = image_px(&im, x, y);
            ck_assert_near(p[0], r[y * w + x], r[y * w + x] * 0x1p-11);
            ck_assert(p[1] == g[y * w + x]); /* float channel: exact */
            ck_assert_near(p[2], b[y * w + x], b[y * w + x] * 0x1p-11);
        }
    image_free(&im);
    free(r);
    free(g);
    free(b);
    remove_dir();
}
END_TEST

START_TEST(test_every_compression_openexrcore_writes_reads_back)
{
    make_dir();
    static const exr_compression_t comps[] = {
        EXR_COMPRESSION_NONE, EXR_COMPRESSION_RLE,   EXR_COMPRESSION_ZIPS, EXR_COMPRESSION_ZIP,
        EXR_COMPRESSION_PIZ,  EXR_COMPRESSION_PXR24, EXR_COMPRESSION_B44,  EXR_COMPRESSION_B44A};
    int w = 40, h = 40;
    float *r = planar(w, h, 0), *g = planar(w, h, 1), *b = planar(w, h, 2);
    tchan ch[3] = {{"R", EXR_PIXEL_HALF, r}, {"G", EXR_PIXEL_HALF, g}, {"B", EXR_PIXEL_HALF, b}};
    for (size_t c = 0; c < sizeof comps / sizeof comps[0]; c++)
        for (int tiled = 0; tiled < 2; tiled++) {
            ck_assert_int_eq(write_test_exr(in_dir("c.exr"), tiled, comps[c],
                                            box(0, 0, w - 1, h - 1), box(0, 0, w - 1, h - 1), ch,
                                            3),
                             0);
            image im = {0};
            error err = {0};
            ck_assert_msg(exrfile_read(in_dir("c.exr"), &im, NULL, &err) == 0,
                          "compression %d tiled %d: %s", (int)comps[c], tiled, err.msg);
            /* lossless ones within half rounding; B44 is lossy (4x4 blocks, about 1%) */
            double tol = comps[c] == EXR_COMPRESSION_B44 || comps[c] == EXR_COMPRESSION_B44A
                             ? 2e-2
                             : 0x1p-11;
            double worst = 0.0; /* largest relative error of channel B */
            for (int y = 0; y < h; y++)
                for (int x = 0; x < w; x++)
                    worst = fmax(worst, fabs(image_px(&im, x, y)[2] - b[y * w + x]) / b[y * w + x]);
            ck_assert_msg(worst <= tol, "compression %d tiled %d: relative error %g", (int)comps[c],
                          tiled, worst);
            image_free(&im);
        }
    free(r);
    free(g);
    free(b);
    remove_dir();
}
END_TEST

START_TEST(test_y_only_exr_is_grey)
{
    make_dir();
    float *yv = planar(9, 5, 3);
    tchan ch[1] = {{"Y", EXR_PIXEL_HALF, yv}};
    ck_assert_int_eq(write_test_exr(in_dir("y.exr"), 0, EXR_COMPRESSION_ZIP, box(0, 0, 8, 4),
                                    box(0, 0, 8, 4), ch, 1),
                     0);
    image im = {0};
    error err = {0};
    ck_assert_msg(exrfile_read(in_dir("y.exr"), &im, NULL, &err) == 0, "%s", err.msg);
    for (int y = 0; y < 5; y++)
        for (int x = 0; x < 9; x++) {
            float *p = image_px(&im, x, y);
            ck_assert_near(p[0], yv[y * 9 + x], yv[y * 9 + x] * 0x1p-11);
            ck_assert(p[1] == p[0] && p[2] == p[0]);
        }
    image_free(&im);
    free(yv);
    remove_dir();
}
END_TEST

START_TEST(test_uint_channels_read_as_their_values)
{
    make_dir();
    uint32_t u[3][12];
    for (int c = 0; c < 3; c++)
        for (int i = 0; i < 12; i++) u[c][i] = (uint32_t)(c * 1000 + i * 7);
    tchan ch[3] = {
        {"R", EXR_PIXEL_UINT, u[0]}, {"G", EXR_PIXEL_UINT, u[1]}, {"B", EXR_PIXEL_UINT, u[2]}};
    ck_assert_int_eq(write_test_exr(in_dir("u.exr"), 0, EXR_COMPRESSION_NONE, box(0, 0, 3, 2),
                                    box(0, 0, 3, 2), ch, 3),
                     0);
    image im = {0};
    error err = {0};
    ck_assert_msg(exrfile_read(in_dir("u.exr"), &im, NULL, &err) == 0, "%s", err.msg);
    for (int i = 0; i < 12; i++)
        for (int c = 0; c < 3; c++) ck_assert(im.px[3 * i + c] == (float)u[c][i]);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_data_window_is_placed_in_the_display_window_and_the_rest_is_zero)
{
    make_dir();
    /* display 0..9 x 0..7; data window 6..12 x -2..3: overhangs right and top */
    int dww = 7, dwh = 6;
    float *r = planar(dww, dwh, 0), *g = planar(dww, dwh, 1), *b = planar(dww, dwh, 2);
    tchan ch[3] = {{"R", EXR_PIXEL_FLOAT, r}, {"G", EXR_PIXEL_FLOAT, g}, {"B", EXR_PIXEL_FLOAT, b}};
    ck_assert_int_eq(write_test_exr(in_dir("d.exr"), 0, EXR_COMPRESSION_ZIP, box(0, 0, 9, 7),
                                    box(6, -2, 12, 3), ch, 3),
                     0);
    image im = {0};
    error err = {0};
    ck_assert_msg(exrfile_read(in_dir("d.exr"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(im.w, 10);
    ck_assert_int_eq(im.h, 8);
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 10; x++) {
            int dx = x - 6, dy = y + 2; /* position in the data window */
            int inside = dx >= 0 && dx < dww && dy >= 0 && dy < dwh;
            float want = inside ? g[dy * dww + dx] : 0.0f;
            ck_assert_msg(image_px(&im, x, y)[1] == want, "(%d, %d)", x, y);
        }
    image_free(&im);
    /* the same data window overhanging the left and the bottom: x -3..3, y 4..9 */
    ck_assert_int_eq(write_test_exr(in_dir("d2.exr"), 0, EXR_COMPRESSION_ZIP, box(0, 0, 9, 7),
                                    box(-3, 4, 3, 9), ch, 3),
                     0);
    ck_assert_msg(exrfile_read(in_dir("d2.exr"), &im, NULL, &err) == 0, "%s", err.msg);
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 10; x++) {
            int dx = x + 3, dy = y - 4;
            int inside = dx >= 0 && dx < dww && dy >= 0 && dy < dwh;
            float want = inside ? g[dy * dww + dx] : 0.0f;
            ck_assert_msg(image_px(&im, x, y)[1] == want, "(%d, %d)", x, y);
        }
    image_free(&im);
    free(r);
    free(g);
    free(b);
    remove_dir();
}
END_TEST

START_TEST(test_one_layer_of_prefixed_channels_is_read_and_two_are_refused)
{
    make_dir();
    float *v = planar(4, 4, 0);
    tchan one[3] = {{"beauty.B", EXR_PIXEL_HALF, v},
                    {"beauty.G", EXR_PIXEL_HALF, v},
                    {"beauty.R", EXR_PIXEL_HALF, v}};
    ck_assert_int_eq(write_test_exr(in_dir("l.exr"), 0, EXR_COMPRESSION_ZIP, box(0, 0, 3, 3),
                                    box(0, 0, 3, 3), one, 3),
                     0);
    image im = {0};
    error err = {0};
    ck_assert_msg(exrfile_read(in_dir("l.exr"), &im, NULL, &err) == 0, "%s", err.msg);
    image_free(&im);
    tchan two[6] = {{"a.R", EXR_PIXEL_HALF, v}, {"a.G", EXR_PIXEL_HALF, v},
                    {"a.B", EXR_PIXEL_HALF, v}, {"b.R", EXR_PIXEL_HALF, v},
                    {"b.G", EXR_PIXEL_HALF, v}, {"b.B", EXR_PIXEL_HALF, v}};
    ck_assert_int_eq(write_test_exr(in_dir("l2.exr"), 0, EXR_COMPRESSION_ZIP, box(0, 0, 3, 3),
                                    box(0, 0, 3, 3), two, 6),
                     0);
    ck_assert_int_eq(exrfile_read(in_dir("l2.exr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "several layers"));
    ck_assert_ptr_null(im.px);
    tchan lower[3] = {{"r", EXR_PIXEL_HALF, v}, {"g", EXR_PIXEL_HALF, v}, {"b", EXR_PIXEL_HALF, v}};
    ck_assert_int_eq(write_test_exr(in_dir("lc.exr"), 0, EXR_COMPRESSION_ZIP, box(0, 0, 3, 3),
                                    box(0, 0, 3, 3), lower, 3),
                     0);
    ck_assert_int_eq(exrfile_read(in_dir("lc.exr"), &im, NULL, &err),
                     -1); /* names are case-sensitive */
    ck_assert_ptr_nonnull(strstr(err.msg, "no R, G, B or Y channels"));
    free(v);
    remove_dir();
}
END_TEST

/* Files envtex does not read are refused by name: deep pixels, luminance-chroma (Y, RY, BY). */
START_TEST(test_deep_and_luminance_chroma_exr_are_refused)
{
    make_dir();
    exr_context_t ctx = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    int part = 0;
    exr_result_t r = exr_start_write(&ctx, in_dir("deep.exr"), EXR_WRITE_FILE_DIRECTLY, &init);
    if (!r) r = exr_add_part(ctx, "deep", EXR_STORAGE_DEEP_SCANLINE, &part);
    if (!r) r = exr_initialize_required_attr_simple(ctx, part, 4, 4, EXR_COMPRESSION_NONE);
    if (!r)
        r = exr_add_channel(ctx, part, "R", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (!r) r = exr_write_header(ctx);
    for (int y = 0; y < 4 && !r; y++) { /* no samples in any pixel */
        exr_chunk_info_t ci;
        int32_t counts[4] = {0, 0, 0, 0};
        r = exr_write_scanline_chunk_info(ctx, part, y, &ci);
        if (!r) r = exr_write_deep_scanline_chunk(ctx, part, y, NULL, 0, 0, counts, sizeof counts);
    }
    exr_result_t f = exr_finish(&ctx);
    ck_assert_int_eq(r ? r : f, EXR_ERR_SUCCESS);
    image im = {0};
    error err = {0};
    ck_assert_int_eq(exrfile_read(in_dir("deep.exr"), &im, NULL, &err), -1);
    ck_assert_str_eq(err.msg, "deep OpenEXR images are not supported");
    ck_assert_ptr_null(im.px);

    float *v = planar(4, 4, 0);
    tchan yc[3] = {{"BY", EXR_PIXEL_HALF, v}, {"RY", EXR_PIXEL_HALF, v}, {"Y", EXR_PIXEL_HALF, v}};
    ck_assert_int_eq(write_test_exr(in_dir("yc.exr"), 0, EXR_COMPRESSION_ZIP, box(0, 0, 3, 3),
                                    box(0, 0, 3, 3), yc, 3),
                     0);
    ck_assert_int_eq(exrfile_read(in_dir("yc.exr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "luminance-chroma images (Y, RY, BY) are not supported"));
    ck_assert_ptr_null(im.px);
    free(v);
    remove_dir();
}
END_TEST

/* First index of the n bytes `pat` in d[0..len), or -1. */
static long find_bytes(const unsigned char *d, size_t len, const void *pat, size_t n)
{
    for (size_t i = 0; i + n <= len; i++)
        if (memcmp(d + i, pat, n) == 0) return (long)i;
    return -1;
}

/* Header claims the file cannot back, made by patching an uncompressed 8 x 8 file (one
 * scanline per chunk, 96 bytes each): each is refused with its own message before any pixel
 * is decoded. */
START_TEST(test_exr_header_claims_are_checked_before_decoding)
{
    make_dir();
    float *r = planar(8, 8, 0), *g = planar(8, 8, 1), *b = planar(8, 8, 2);
    tchan ch[3] = {{"B", EXR_PIXEL_FLOAT, b}, {"G", EXR_PIXEL_FLOAT, g}, {"R", EXR_PIXEL_FLOAT, r}};
    ck_assert_int_eq(write_test_exr(in_dir("n.exr"), 0, EXR_COMPRESSION_NONE, box(0, 0, 7, 7),
                                    box(0, 0, 7, 7), ch, 3),
                     0);
    size_t n;
    unsigned char *d = slurp(in_dir("n.exr"), &n);
    unsigned char *e = malloc(n);
    ck_assert_ptr_nonnull(e);
    image im = {0};
    error err = {0};
    ck_assert_msg(exrfile_read(in_dir("n.exr"), &im, NULL, &err) == 0, "%s", err.msg);
    image_free(&im);

    /* the channel list: "G\0", pixel type (4 bytes), pLinear and 3 reserved, xSampling, ySampling */
    long at = find_bytes(d, n, "chlist", 7);
    ck_assert_int_gt(at, 0);
    long gch = find_bytes(d + at, n - (size_t)at, "G\0", 2) + at;
    const int32_t two = 2;
    for (int k = 0; k < 2; k++) { /* x, then y sub-sampled */
        memcpy(e, d, n);
        memcpy(e + gch + 2 + 4 + 4 + 4 * k, &two, 4);
        write_bytes(in_dir("sub.exr"), e, n);
        ck_assert_int_eq(exrfile_read(in_dir("sub.exr"), &im, NULL, &err), -1);
        ck_assert_str_eq(err.msg, k == 0 ? "channel G is sub-sampled (2 x 1); not supported"
                                         : "channel G is sub-sampled (1 x 2); not supported");
    }

    /* a data window of 32768 x 16384 (2^29 pixels, each side allowed): over IMAGE_MAX_PIXELS */
    at = find_bytes(d, n, "dataWindow\0box2i\0", 17);
    ck_assert_int_gt(at, 0);
    const int32_t most[2] = {32767, 16383};
    memcpy(e, d, n);
    memcpy(e + at + 17 + 4 + 8, most, sizeof most); /* after the size field and min.x, min.y */
    write_bytes(in_dir("dw.exr"), e, n);
    ck_assert_int_eq(exrfile_read(in_dir("dw.exr"), &im, NULL, &err), -1);
    ck_assert_msg(strstr(err.msg, "data window: image size 32768 x 16384 is over the limit"), "%s",
                  err.msg);

    /* an uncompressed chunk whose leader says 48 bytes where its 8 pixels take 96: the chunks
     * hold 720 bytes, the pixels need 768 (compressed, up to 4096 times as many could be fine) */
    const int32_t leader[2] = {0, 96}, shorter[2] = {0, 48};
    long c0 = find_bytes(d, n, leader, sizeof leader);
    ck_assert_int_gt(c0, 0);
    memcpy(e, d, n);
    memcpy(e + c0, shorter, sizeof shorter);
    write_bytes(in_dir("short.exr"), e, n);
    ck_assert_int_eq(exrfile_read(in_dir("short.exr"), &im, NULL, &err), -1);
    ck_assert_msg(
        strstr(err.msg, "corrupt or truncated OpenEXR file: 8 x 8 pixels need 768 bytes, more than "
                        "its 720 bytes of chunks can hold"),
        "%s", err.msg);
    ck_assert_ptr_null(im.px);
    free(d);
    free(e);
    free(r);
    free(g);
    free(b);
    remove_dir();
}
END_TEST

/* Find the compression attribute's value byte in an EXR header: "compression\0compression\0"
 * then a 4-byte size (1) and the value. */
static long compression_byte(const unsigned char *d, size_t n)
{
    static const char key[] = "compression\0compression\0\1\0\0\0";
    for (size_t i = 0; i + sizeof key < n; i++)
        if (!memcmp(d + i, key, sizeof key - 1)) return (long)(i + sizeof key - 1);
    return -1;
}

START_TEST(test_dwa_files_are_refused_with_a_resave_hint)
{
    make_dir();
    image im = {0};
    error err = {0};
    fill_test_image(&im, 8, 8);
    ck_assert_int_eq(exrfile_write(in_dir("z.exr"), &im, 1, &err), 0);
    unsigned char *d;
    size_t n;
    ck_assert_int_eq(fileio_read_all(in_dir("z.exr"), &d, &n, NULL, &err), 0);
    long at = compression_byte(d, n);
    ck_assert_int_ge(at, 0);
    ck_assert_int_eq(d[at], EXR_COMPRESSION_ZIP);
    d[at] = EXR_COMPRESSION_DWAB; /* the header now claims DWAB */
    FILE *f = fopen(in_dir("dwab.exr"), "wb");
    ck_assert_uint_eq(fwrite(d, 1, n, f), n);
    fclose(f);
    free(d);
    image back = {0};
    ck_assert_int_eq(exrfile_read(in_dir("dwab.exr"), &back, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "cannot decode DWAA/DWAB"));
    ck_assert_ptr_nonnull(strstr(err.msg, "--compression zip"));
    ck_assert_str_eq(err.file, in_dir("dwab.exr"));
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_truncated_exr_is_an_error_at_every_offset)
{
    make_dir();
    image im = {0};
    error err = {0};
    fill_test_image(&im, 50, 40);
    ck_assert_int_eq(exrfile_write(in_dir("full.exr"), &im, 0, &err), 0);
    long size = file_size(in_dir("full.exr"));
    long offsets[] = {0, 1, 4, 8, 40, 150, 300, size / 3, size / 2, size - 100, size - 1};
    for (size_t i = 0; i < sizeof offsets / sizeof offsets[0]; i++) {
        if (offsets[i] < 0 || offsets[i] >= size) continue;
        truncate_copy(in_dir("full.exr"), in_dir("cut.exr"), offsets[i]);
        image back = {0};
        ck_assert_msg(exrfile_read(in_dir("cut.exr"), &back, NULL, &err) == -1, "cut at %ld read",
                      offsets[i]);
        ck_assert_ptr_null(back.px);
        ck_assert(err.msg[0] != '\0');
    }
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_corrupted_exr_bytes_never_crash)
{
    make_dir();
    image im = {0};
    error err = {0};
    fill_test_image(&im, 33, 35);
    ck_assert_int_eq(exrfile_write(in_dir("ok.exr"), &im, 1, &err), 0);
    unsigned char *d;
    size_t n;
    ck_assert_int_eq(fileio_read_all(in_dir("ok.exr"), &d, &n, NULL, &err), 0);
    unsigned s = 12345u; /* fixed seed: the same corruptions every run */
    for (int trial = 0; trial < 60; trial++) {
        unsigned char *c = malloc(n);
        memcpy(c, d, n);
        for (int k = 0; k < 4; k++) {
            s = s * 1103515245u + 12345u;
            c[(s >> 8) % n] ^= (unsigned char)(1u << (s % 8));
        }
        FILE *f = fopen(in_dir("bad.exr"), "wb");
        fwrite(c, 1, n, f);
        fclose(f);
        free(c);
        image back = {0};
        if (exrfile_read(in_dir("bad.exr"), &back, NULL, &err) ==
            0) { /* a flip in pixel data may still decode */
            ck_assert_int_eq(back.w, 33);
            image_free(&back);
        } else {
            ck_assert_ptr_null(back.px);
        }
    }
    free(d);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_missing_files_and_folders_are_clear_errors)
{
    image im = {0};
    error err = {0};
    ck_assert_int_eq(exrfile_read("/nonexistent/sky.exr", &im, NULL, &err), -1);
    ck_assert_str_eq(err.msg, "cannot open: No such file or directory");
    ck_assert_int_eq(exrfile_read("/tmp", &im, NULL, &err), -1);
    ck_assert_str_eq(err.msg, "cannot open: it is a directory, not a regular file");
}
END_TEST

START_TEST(test_failed_exr_write_leaves_the_old_file_byte_identical)
{
    make_dir();
    image im = {0}, empty = {0};
    error err = {0};
    fill_test_image(&im, 8, 8);
    ck_assert_int_eq(exrfile_write(in_dir("keep.exr"), &im, 0, &err), 0);
    unsigned char *before, *after;
    size_t nb, na;
    ck_assert_int_eq(fileio_read_all(in_dir("keep.exr"), &before, &nb, NULL, &err), 0);
    ck_assert_int_eq(exrfile_write(in_dir("keep.exr"), &empty, 0, &err), -1); /* invalid image */
    ck_assert_int_eq(exrfile_write(in_dir("no/such/folder.exr"), &im, 0, &err), -1);
    ck_assert_int_eq(fileio_read_all(in_dir("keep.exr"), &after, &na, NULL, &err), 0);
    ck_assert_uint_eq(na, nb);
    ck_assert_int_eq(memcmp(before, after, nb), 0);
    ck_assert(!count_tmp_files());
    free(before);
    free(after);
    image_free(&im);
    remove_dir();
}
END_TEST

/* ---- the envtex attributes: what a render records about itself ---------------------------- */

START_TEST(test_render_attributes_roundtrip_through_the_header)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    fill_test_image(&im, 13, 7);
    exrfile_attrs at = {.spp = 1024, .has_seed = 1, .seed = 0xfedcba9876543210ull};
    strcpy(at.integrator, "pathtracer");
    strcpy(at.scene, "data/scenes/lecture/mirror ball.test");
    ck_assert_msg(exrfile_write_attrs(in_dir("a.exr"), &im, 0, &at, &err) == 0, "%s", err.msg);
    exrfile_attrs got;
    memset(&got, 0x5a, sizeof got);
    ck_assert_msg(exrfile_read_attrs(in_dir("a.exr"), &got, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(got.spp, 1024);
    ck_assert_int_eq(got.has_seed, 1);
    ck_assert(got.seed == 0xfedcba9876543210ull); /* all 64 bits: a string, not an int */
    ck_assert_str_eq(got.integrator, "pathtracer");
    ck_assert_str_eq(got.scene, "data/scenes/lecture/mirror ball.test");
    /* the pixels are those exrfile_write writes */
    ck_assert_msg(exrfile_read(in_dir("a.exr"), &back, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(memcmp(back.px, im.px, sizeof(float) * 3 * 13 * 7), 0);
    image_free(&back);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_a_file_without_attributes_reads_them_as_unknown)
{
    make_dir();
    image im = {0};
    error err = {0};
    fill_test_image(&im, 4, 3);
    ck_assert_int_eq(exrfile_write(in_dir("plain.exr"), &im, 1, &err), 0);
    exrfile_attrs got;
    ck_assert_msg(exrfile_read_attrs(in_dir("plain.exr"), &got, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(got.spp, 0);
    ck_assert_int_eq(got.has_seed, 0);
    ck_assert_str_eq(got.integrator, "");
    ck_assert_str_eq(got.scene, "");
    /* only the known fields are written: spp alone */
    exrfile_attrs only = {.spp = 7};
    ck_assert_int_eq(exrfile_write_attrs(in_dir("spp.exr"), &im, 1, &only, &err), 0);
    ck_assert_int_eq(exrfile_read_attrs(in_dir("spp.exr"), &got, &err), 0);
    ck_assert_int_eq(got.spp, 7);
    ck_assert_int_eq(got.has_seed, 0);
    ck_assert_str_eq(got.scene, "");
    /* not an OpenEXR file: an error naming it */
    FILE *f = fopen(in_dir("not.exr"), "wb");
    ck_assert_ptr_nonnull(f);
    fputs("PF\n1 1\n-1\n", f);
    fclose(f);
    ck_assert_int_eq(exrfile_read_attrs(in_dir("not.exr"), &got, &err), -1);
    ck_assert_str_eq(err.file, in_dir("not.exr"));
    ck_assert_int_eq(got.spp, 0);
    image_free(&im);
    remove_dir();
}
END_TEST

static exr_result_t spp_as_float(exr_context_t ctx, int part)
{
    return exr_attr_set_float(ctx, part, "envtex:spp", 64.0f);
}
static exr_result_t spp_zero(exr_context_t ctx, int part)
{
    return exr_attr_set_int(ctx, part, "envtex:spp", 0);
}
static exr_result_t seed_not_a_number(exr_context_t ctx, int part)
{
    exr_result_t r = exr_attr_set_int(ctx, part, "envtex:spp", 16);
    return r ? r : exr_attr_set_string(ctx, part, "envtex:seed", "-3");
}

START_TEST(test_an_attribute_that_is_not_a_sample_count_is_refused)
{
    make_dir();
    float *v = planar(2, 2, 0);
    tchan ch[3] = {{"R", EXR_PIXEL_FLOAT, v}, {"G", EXR_PIXEL_FLOAT, v}, {"B", EXR_PIXEL_FLOAT, v}};
    exr_result_t (*hooks[3])(exr_context_t, int) = {spp_as_float, spp_zero, seed_not_a_number};
    const char *why[3] = {"not an int", "not a sample count", "not a whole number"};
    for (int k = 0; k < 3; k++) {
        test_header_hook = hooks[k];
        exr_result_t r = write_test_exr(in_dir("t.exr"), 0, EXR_COMPRESSION_NONE, box(0, 0, 1, 1),
                                        box(0, 0, 1, 1), ch, 3);
        test_header_hook = NULL;
        ck_assert_int_eq(r, 0);
        exrfile_attrs got;
        error err = {0};
        ck_assert_int_eq(exrfile_read_attrs(in_dir("t.exr"), &got, &err), -1);
        ck_assert_msg(strstr(err.msg, why[k]), "case %d: %s", k, err.msg);
        ck_assert_int_eq(got.spp, 0);
        image im = {0}; /* the pixels still read */
        ck_assert_msg(exrfile_read(in_dir("t.exr"), &im, NULL, &err) == 0, "%s", err.msg);
        image_free(&im);
    }
    free(v);
    remove_dir();
}
END_TEST

Suite *exrfile_suite(void)
{
    Suite *s = suite_create("exrfile");
    TCase *tc = tcase_create("exrfile");
    tcase_add_test(tc, test_float_exr_roundtrip_is_exact);
    tcase_add_test(tc, test_barely_incompressible_exr_chunk_roundtrips_exactly);
    tcase_add_test(tc, test_half_exr_roundtrip_is_within_half_precision);
    tcase_add_test(tc, test_courtyard_has_the_size_and_mean_its_readme_gives);
    tcase_add_test(tc, test_tiled_exr_with_partial_edge_tiles_reads);
    tcase_add_test(tc, test_every_compression_openexrcore_writes_reads_back);
    tcase_add_test(tc, test_y_only_exr_is_grey);
    tcase_add_test(tc, test_uint_channels_read_as_their_values);
    tcase_add_test(tc, test_data_window_is_placed_in_the_display_window_and_the_rest_is_zero);
    tcase_add_test(tc, test_one_layer_of_prefixed_channels_is_read_and_two_are_refused);
    tcase_add_test(tc, test_dwa_files_are_refused_with_a_resave_hint);
    tcase_add_test(tc, test_deep_and_luminance_chroma_exr_are_refused);
    tcase_add_test(tc, test_exr_header_claims_are_checked_before_decoding);
    tcase_add_test(tc, test_truncated_exr_is_an_error_at_every_offset);
    tcase_add_test(tc, test_corrupted_exr_bytes_never_crash);
    tcase_add_test(tc, test_missing_files_and_folders_are_clear_errors);
    tcase_add_test(tc, test_failed_exr_write_leaves_the_old_file_byte_identical);
    tcase_add_test(tc, test_render_attributes_roundtrip_through_the_header);
    tcase_add_test(tc, test_a_file_without_attributes_reads_them_as_unknown);
    tcase_add_test(tc, test_an_attribute_that_is_not_a_sample_count_is_refused);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(exrfile_suite)
