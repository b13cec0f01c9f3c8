/* test_pngfile.c - PNG reading (every colour type; sRGB decoded, or a gAMA chunk's power law)
 * and writing. */
#include <dirent.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envtex/io/imageio.h"
#include "envtex/io/pngfile.h"
#include "envtex/io/tonemap.h"
#include "unit.h"

#include "testdir.h"

/* Write a PNG with libpng directly: rows of raw samples (big endian for 16 bit).  `srgb`: sRGB,
 * gAMA and cHRM chunks, as many tools write them (png_set_sRGB_gAMA_and_cHRM); else a lone gAMA
 * chunk of `file_gamma` if it is > 0; else no colour chunk. */
static void write_tagged_png(const char *path, int w, int h, int type, int depth, int interlace,
                             const unsigned char *data, size_t rowbytes, int srgb,
                             double file_gamma)
{
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    ck_assert(!setjmp(png_jmpbuf(png)));
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, type, interlace,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (type == PNG_COLOR_TYPE_PALETTE) {
        png_color pal[2] = {{255, 0, 0}, {0, 0, 255}};
        png_set_PLTE(png, info, pal, 2);
    }
    if (srgb)
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    else if (file_gamma > 0)
        png_set_gAMA(png, info, file_gamma);
    png_write_info(png, info);
    png_bytep rows[64];
    for (int y = 0; y < h; y++) rows[y] = (png_bytep)data + (size_t)y * rowbytes;
    png_write_image(png, rows);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    fclose(f);
}

/* The same with no colour chunks at all. */
static void write_raw_png(const char *path, int w, int h, int type, int depth, int interlace,
                          const unsigned char *data, size_t rowbytes)
{
    write_tagged_png(path, w, h, type, depth, interlace, data, rowbytes, 0, 0.0);
}

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* The data of the first chunk of this type in the PNG bytes d[0..n), or NULL. */
static const unsigned char *find_chunk(const unsigned char *d, size_t n, const char type[4])
{
    for (size_t p = 8; p + 8 <= n; p += 12 + be32(d + p))
        if (memcmp(d + p + 4, type, 4) == 0) return d + p + 8;
    return NULL;
}

static float dec8(int v) { return (float)tonemap_srgb_decode(v / 255.0); }

/* A test image: values in [0,1], so nothing is clamped and every one comes back. */
static void fill_ramp(image *im)
{
    for (int i = 0; i < im->w * im->h * 3; i++) im->px[i] = (float)((i * 37) % 101) / 100.0f;
}

START_TEST(test_png_roundtrip_is_within_8bit_quantization)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 16, 9, &err), 0);
    fill_ramp(&im);
    ck_assert_int_eq(pngfile_write(in_dir("a.png"), &im, NULL, &err), 0);
    ck_assert_msg(pngfile_read(in_dir("a.png"), &back, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(back.w, 16);
    ck_assert_int_eq(back.h, 9);
    double worst = 0.0; /* in encoded units: rounding to 8 bits is within half a step */
    for (int i = 0; i < 16 * 9 * 3; i++)
        worst = fmax(worst, fabs(tonemap_srgb_encode(back.px[i]) - tonemap_srgb_encode(im.px[i])));
    ck_assert_double_le(worst, 0.5 / 255.0 + 1e-6);
    ck_assert_int_eq(count_files(".tmp."), 0);
    image_free(&im);
    image_free(&back);
    remove_dir();
}
END_TEST

START_TEST(test_png_is_labelled_with_the_curve_its_bytes_are_in)
{
    make_dir();
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 4, 4, &err), 0);
    fill_ramp(&im);
    size_t n;
    /* the default tone mapping encodes with the sRGB curve: an sRGB chunk, no gAMA */
    ck_assert_int_eq(pngfile_write(in_dir("s.png"), &im, NULL, &err), 0);
    unsigned char *d = slurp(in_dir("s.png"), &n);
    ck_assert_ptr_nonnull(find_chunk(d, n, "sRGB"));
    ck_assert_ptr_null(find_chunk(d, n, "gAMA"));
    free(d);
    /* gamma g encodes with c^(1/g): a gAMA chunk of 1/g (x 100000), no sRGB chunk */
    const double g[3] = {2.2, 1.0, 1.8};
    const uint32_t stored[3] = {45455, 100000, 55556};
    for (int k = 0; k < 3; k++) {
        tonemap_params tm = tonemap_defaults();
        tm.gamma = g[k];
        ck_assert_int_eq(pngfile_write(in_dir("g.png"), &im, &tm, &err), 0);
        d = slurp(in_dir("g.png"), &n);
        ck_assert_msg(find_chunk(d, n, "sRGB") == NULL, "gamma %g: an sRGB chunk", g[k]);
        const unsigned char *gama = find_chunk(d, n, "gAMA");
        ck_assert_msg(gama != NULL, "gamma %g: no gAMA chunk", g[k]);
        ck_assert_uint_eq(be32(gama), stored[k]);
        free(d);
    }
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_gamma_png_roundtrip_is_within_8bit_quantization)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 16, 9, &err), 0);
    fill_ramp(&im);
    const double g[3] = {2.2, 1.0, 1.8};
    for (int k = 0; k < 3; k++) {
        tonemap_params tm = tonemap_defaults();
        tm.gamma = g[k];
        ck_assert_int_eq(pngfile_write(in_dir("g.png"), &im, &tm, &err), 0);
        ck_assert_msg(pngfile_read(in_dir("g.png"), &back, NULL, &err) == 0, "%s", err.msg);
        /* in encoded units c^(1/g), rounding to 8 bits is within half a step; 1e-5 more for the
         * file gamma's 5 digits (0.45455, not 1/2.2) */
        double worst = 0.0;
        for (int i = 0; i < 16 * 9 * 3; i++)
            worst = fmax(worst, fabs(pow(back.px[i], 1.0 / g[k]) - pow(im.px[i], 1.0 / g[k])));
        ck_assert_msg(worst <= 0.5 / 255.0 + 1e-5, "gamma %g: worst %g", g[k], worst);
        image_free(&back);
    }
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_a_gamma_no_gama_chunk_can_hold_is_an_error_and_writes_nothing)
{
    make_dir();
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 2, 2, &err), 0);
    tonemap_params tm = tonemap_defaults();
    const double bad[2] = {0.99 / PNGFILE_GAMMA_MAX, 1.01 * PNGFILE_GAMMA_MAX};
    for (int k = 0; k < 2; k++) {
        tm.gamma = bad[k];
        ck_assert_int_eq(pngfile_write(in_dir("x.png"), &im, &tm, &err), -1);
        ck_assert_msg(strstr(err.msg, "gamma") && strstr(err.msg, "gAMA"), "%s", err.msg);
        ck_assert_str_eq(err.file, in_dir("x.png"));
        ck_assert_int_eq(count_files("x.png"), 0); /* neither the file nor a temporary */
    }
    uint8_t px[3] = {1, 2, 3};
    ck_assert_int_eq(pngfile_write_rgb8_gamma(in_dir("x.png"), 1, 1, px, 0.0, &err), -1);
    ck_assert_int_eq(pngfile_write_rgb8_gamma(in_dir("x.png"), 1, 1, px, NAN, &err), -1);
    ck_assert_int_eq(count_files("x.png"), 0);
    /* the two ends themselves are fine: 16 and 625000000 units of 1e-5 */
    const double ends[2] = {PNGFILE_GAMMA_MAX, 1.0 / PNGFILE_GAMMA_MAX};
    const uint32_t stored[2] = {16, 625000000};
    for (int k = 0; k < 2; k++) {
        ck_assert_msg(pngfile_write_rgb8_gamma(in_dir("x.png"), 1, 1, px, ends[k], &err) == 0, "%s",
                      err.msg);
        size_t n;
        unsigned char *d = slurp(in_dir("x.png"), &n);
        const unsigned char *gama = find_chunk(d, n, "gAMA");
        ck_assert_ptr_nonnull(gama);
        ck_assert_uint_eq(be32(gama), stored[k]);
        free(d);
    }
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_every_colour_type_decodes_to_linear_rgb)
{
    make_dir();
    image im = {0};
    error err = {0};
    /* grey 8: 0, 128, 255 */
    unsigned char g8[3] = {0, 128, 255};
    write_raw_png(in_dir("g8.png"), 3, 1, PNG_COLOR_TYPE_GRAY, 8, PNG_INTERLACE_NONE, g8, 3);
    ck_assert_msg(pngfile_read(in_dir("g8.png"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(im.px[3] == dec8(128) && im.px[4] == dec8(128) && im.px[5] == dec8(128));
    ck_assert(im.px[6] == 1.0f && im.px[0] == 0.0f);
    image_free(&im);
    /* grey 1 bit: 1 0 1 */
    unsigned char g1[1] = {0xA0};
    write_raw_png(in_dir("g1.png"), 3, 1, PNG_COLOR_TYPE_GRAY, 1, PNG_INTERLACE_NONE, g1, 1);
    ck_assert_msg(pngfile_read(in_dir("g1.png"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == 1.0f && im.px[3] == 0.0f && im.px[8] == 1.0f);
    image_free(&im);
    /* grey + alpha: alpha dropped */
    unsigned char ga[4] = {255, 0, 128, 255};
    write_raw_png(in_dir("ga.png"), 2, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 8, PNG_INTERLACE_NONE, ga, 4);
    ck_assert_msg(pngfile_read(in_dir("ga.png"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == 1.0f && im.px[3] == dec8(128));
    image_free(&im);
    /* RGBA 8 */
    unsigned char rgba[8] = {255, 0, 64, 7, 1, 2, 3, 255};
    write_raw_png(in_dir("rgba.png"), 2, 1, PNG_COLOR_TYPE_RGBA, 8, PNG_INTERLACE_NONE, rgba, 8);
    ck_assert_msg(pngfile_read(in_dir("rgba.png"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == 1.0f && im.px[1] == 0.0f && im.px[2] == dec8(64) && im.px[5] == dec8(3));
    image_free(&im);
    /* RGB 16: 65535 -> 1, 32768 -> decode(32768 / 65535) */
    unsigned char rgb16[6] = {0xff, 0xff, 0x80, 0x00, 0x00, 0x00};
    write_raw_png(in_dir("rgb16.png"), 1, 1, PNG_COLOR_TYPE_RGB, 16, PNG_INTERLACE_NONE, rgb16, 6);
    ck_assert_msg(pngfile_read(in_dir("rgb16.png"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == 1.0f && im.px[2] == 0.0f);
    ck_assert(im.px[1] == (float)tonemap_srgb_decode(32768.0 / 65535.0));
    image_free(&im);
    /* palette: index 1 is blue */
    unsigned char pal[2] = {1, 0};
    write_raw_png(in_dir("pal.png"), 2, 1, PNG_COLOR_TYPE_PALETTE, 8, PNG_INTERLACE_NONE, pal, 2);
    ck_assert_msg(pngfile_read(in_dir("pal.png"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == 0.0f && im.px[2] == 1.0f && im.px[3] == 1.0f && im.px[5] == 0.0f);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_a_gama_chunk_alone_means_a_power_law_and_srgb_wins_over_it)
{
    make_dir();
    image im = {0};
    error err = {0};
    unsigned char c8[6] = {0, 64, 128, 192, 255, 16};
    /* gAMA 1/2.2 alone: encoded = linear^(1/2.2), so linear = code^2.2 (the file holds 45455) */
    write_tagged_png(in_dir("g22.png"), 2, 1, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_NONE, c8, 6, 0,
                     1.0 / 2.2);
    ck_assert_msg(pngfile_read(in_dir("g22.png"), &im, NULL, &err) == 0, "%s", err.msg);
    for (int i = 0; i < 6; i++) ck_assert_near(im.px[i], pow(c8[i] / 255.0, 1.0 / 0.45455), 1e-6);
    ck_assert(im.px[4] == 1.0f && im.px[0] == 0.0f);
    image_free(&im);
    /* gAMA 1 alone, 16 bit: the codes are linear */
    unsigned char c16[6] = {0x80, 0x00, 0x40, 0x00, 0xff, 0xff};
    write_tagged_png(in_dir("g1.png"), 1, 1, PNG_COLOR_TYPE_RGB, 16, PNG_INTERLACE_NONE, c16, 6, 0,
                     1.0);
    ck_assert_msg(pngfile_read(in_dir("g1.png"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert_near(im.px[0], 32768.0 / 65535.0, 1e-6);
    ck_assert_near(im.px[1], 16384.0 / 65535.0, 1e-6);
    ck_assert(im.px[2] == 1.0f);
    image_free(&im);
    /* sRGB with gAMA 1/2.2 beside it: the sRGB curve, not the power law (they differ by more
     * by 0.003 to 0.009 at 16, 64, 128 and 192); and no colour chunk at all: sRGB too */
    write_tagged_png(in_dir("srgb.png"), 2, 1, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_NONE, c8, 6, 1,
                     0.0);
    size_t n;
    unsigned char *d = slurp(in_dir("srgb.png"), &n);
    ck_assert(find_chunk(d, n, "sRGB") && find_chunk(d, n, "gAMA"));
    free(d);
    write_raw_png(in_dir("none.png"), 2, 1, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_NONE, c8, 6);
    const char *names[] = {"srgb.png", "none.png"};
    for (int f = 0; f < 2; f++) {
        ck_assert_msg(pngfile_read(in_dir(names[f]), &im, NULL, &err) == 0, "%s", err.msg);
        for (int i = 0; i < 6; i++) ck_assert_msg(im.px[i] == dec8(c8[i]), "%s [%d]", names[f], i);
        image_free(&im);
    }
    remove_dir();
}
END_TEST

START_TEST(test_interlaced_png_reads_like_a_plain_one)
{
    make_dir();
    unsigned char d[20 * 20 * 3];
    for (size_t i = 0; i < sizeof d; i++) d[i] = (unsigned char)(i * 13);
    write_raw_png(in_dir("i.png"), 20, 20, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_ADAM7, d, 60);
    write_raw_png(in_dir("p.png"), 20, 20, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_NONE, d, 60);
    image a = {0}, b = {0};
    error err = {0};
    ck_assert_msg(pngfile_read(in_dir("i.png"), &a, NULL, &err) == 0, "%s", err.msg);
    ck_assert_msg(pngfile_read(in_dir("p.png"), &b, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(memcmp(a.px, b.px, sizeof(float) * 20 * 20 * 3), 0);
    ck_assert(image_px(&a, 19, 19)[2] == dec8(d[sizeof d - 1]));
    image_free(&a);
    image_free(&b);
    remove_dir();
}
END_TEST

/* CRC-32 of PNG chunks (ISO 3309), bit by bit: tests only. */
static uint32_t crc32_png(const unsigned char *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xffffffffu;
}

START_TEST(test_png_claiming_40000_by_40000_is_refused_before_allocation)
{
    make_dir();
    unsigned char px[3] = {1, 2, 3};
    write_raw_png(in_dir("one.png"), 1, 1, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_NONE, px, 3);
    size_t n;
    unsigned char *d = slurp(in_dir("one.png"), &n);
    /* IHDR: length at 8, "IHDR" at 12, width at 16, height at 20, CRC after 13 data bytes */
    ck_assert_int_eq(memcmp(d + 12, "IHDR", 4), 0);
    unsigned char big[4] = {0, 0, 0x9c, 0x40}; /* 40000 */
    memcpy(d + 16, big, 4);
    memcpy(d + 20, big, 4);
    uint32_t c = crc32_png(d + 12, 17);
    unsigned char cb[4] = {(unsigned char)(c >> 24), (unsigned char)(c >> 16),
                           (unsigned char)(c >> 8), (unsigned char)c};
    memcpy(d + 29, cb, 4);
    write_bytes(in_dir("big.png"), d, n);
    image im = {0};
    error err = {0};
    ck_assert_int_eq(pngfile_read(in_dir("big.png"), &im, NULL, &err), -1);
    ck_assert_msg(strstr(err.msg, "over the limit") != NULL, "%s", err.msg);
    ck_assert_ptr_null(im.px);
    free(d);
    remove_dir();
}
END_TEST

START_TEST(test_a_gama_outside_what_libpng_accepts_is_read_as_srgb)
{
    make_dir();
    unsigned char c8[3] = {16, 64, 192};
    write_tagged_png(in_dir("g.png"), 1, 1, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_NONE, c8, 3, 0,
                     1.0);
    size_t n;
    unsigned char *d = slurp(in_dir("g.png"), &n);
    /* gAMA follows IHDR (8 + 25 bytes): length at 33, "gAMA" at 37, value at 41, CRC at 45 */
    ck_assert_int_eq(memcmp(d + 37, "gAMA", 4), 0);
    const unsigned char bad[2][4] = {{0, 0, 0, 0}, {0, 0, 0, 15}}; /* 0 and 0.00015 < 1/6250 */
    for (int b = 0; b < 2; b++) {
        memcpy(d + 41, bad[b], 4);
        uint32_t c = crc32_png(d + 37, 8);
        unsigned char cb[4] = {(unsigned char)(c >> 24), (unsigned char)(c >> 16),
                               (unsigned char)(c >> 8), (unsigned char)c};
        memcpy(d + 45, cb, 4);
        write_bytes(in_dir("bad.png"), d, n);
        image im = {0};
        error err = {0};
        ck_assert_msg(pngfile_read(in_dir("bad.png"), &im, NULL, &err) == 0, "%s", err.msg);
        for (int i = 0; i < 3; i++) ck_assert_msg(im.px[i] == dec8(c8[i]), "gAMA %d [%d]", b, i);
        image_free(&im);
    }
    free(d);
    remove_dir();
}
END_TEST

START_TEST(test_truncated_and_corrupt_png_are_errors)
{
    make_dir();
    unsigned char d0[32 * 32 * 3];
    for (size_t i = 0; i < sizeof d0; i++) d0[i] = (unsigned char)((i * 7919) >> 3);
    write_raw_png(in_dir("full.png"), 32, 32, PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_NONE, d0, 96);
    size_t n;
    unsigned char *d = slurp(in_dir("full.png"), &n);
    error err = {0};
    size_t cuts[] = {0, 4, 8, 20, 33, 40, n / 2, n - 13, n - 1};
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
        write_bytes(in_dir("cut.png"), d, cuts[i]);
        image im = {0};
        int r = pngfile_read(in_dir("cut.png"), &im, NULL, &err);
        /* cutting only into the IEND chunk leaves every pixel readable; anything earlier fails */
        if (cuts[i] < n - 12) ck_assert_msg(r == -1, "cut at %zu of %zu read", cuts[i], n);
        if (r == -1) ck_assert_ptr_null(im.px);
        image_free(&im);
    }
    d[50] ^= 0x55; /* a flipped byte in the image data: CRC error */
    write_bytes(in_dir("flip.png"), d, n);
    image im = {0};
    ck_assert_int_eq(pngfile_read(in_dir("flip.png"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "PNG"));
    free(d);
    remove_dir();
}
END_TEST

/* pngfile_read called directly (imageio reads by magic and never sends it these): a file that
 * is only the start of a signature is not a PNG, and a folder is named as one. */
START_TEST(test_a_partial_signature_and_a_folder_are_refused_by_name)
{
    make_dir();
    write_bytes(in_dir("p4.png"), "\x89PNG", 4);
    image im = {0};
    error err = {0};
    ck_assert_int_eq(pngfile_read(in_dir("p4.png"), &im, NULL, &err), -1);
    ck_assert_str_eq(err.msg, "not a PNG file");
    ck_assert_int_eq(pngfile_read(dir, &im, NULL, &err), -1);
    ck_assert_msg(strstr(err.msg, "cannot open: it is a directory, not a regular file") != NULL,
                  "%s", err.msg);
    ck_assert_ptr_null(im.px);
    remove_dir();
}
END_TEST

START_TEST(test_failed_png_write_leaves_the_old_file_byte_identical)
{
    make_dir();
    image im = {0}, empty = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 4, 4, &err), 0);
    ck_assert_int_eq(pngfile_write(in_dir("keep.png"), &im, NULL, &err), 0);
    size_t nb;
    unsigned char *before = slurp(in_dir("keep.png"), &nb);
    ck_assert_int_eq(pngfile_write(in_dir("keep.png"), &empty, NULL, &err), -1);
    empty.w = 5; /* a size without pixels fails validation too */
    ck_assert_int_eq(pngfile_write(in_dir("keep.png"), &empty, NULL, &err), -1);
    ck_assert_int_eq(pngfile_write(in_dir("gone/keep.png"), &im, NULL, &err), -1);
    assert_unchanged(in_dir("keep.png"), before, nb);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_png_write_applies_the_tone_mapping_it_is_given)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 1, 1, &err), 0);
    im.px[0] = 0.25f; /* exposure +2 EV: 1.0, white */
    tonemap_params tm = tonemap_defaults();
    tm.exposure = 2.0;
    ck_assert_int_eq(pngfile_write(in_dir("e.png"), &im, &tm, &err), 0);
    ck_assert_int_eq(pngfile_read(in_dir("e.png"), &back, NULL, &err), 0);
    ck_assert(back.px[0] == 1.0f && back.px[1] == 0.0f);
    image_free(&im);
    image_free(&back);
    remove_dir();
}
END_TEST

Suite *pngfile_suite(void)
{
    Suite *s = suite_create("pngfile");
    TCase *tc = tcase_create("pngfile");
    tcase_add_test(tc, test_png_roundtrip_is_within_8bit_quantization);
    tcase_add_test(tc, test_png_is_labelled_with_the_curve_its_bytes_are_in);
    tcase_add_test(tc, test_gamma_png_roundtrip_is_within_8bit_quantization);
    tcase_add_test(tc, test_a_gamma_no_gama_chunk_can_hold_is_an_error_and_writes_nothing);
    tcase_add_test(tc, test_every_colour_type_decodes_to_linear_rgb);
    tcase_add_test(tc, test_a_gama_chunk_alone_means_a_power_law_and_srgb_wins_over_it);
    tcase_add_test(tc, test_interlaced_png_reads_like_a_plain_one);
    tcase_add_test(tc, test_png_claiming_40000_by_40000_is_refused_before_allocation);
    tcase_add_test(tc, test_a_gama_outside_what_libpng_accepts_is_read_as_srgb);
    tcase_add_test(tc, test_truncated_and_corrupt_png_are_errors);
    tcase_add_test(tc, test_a_partial_signature_and_a_folder_are_refused_by_name);
    tcase_add_test(tc, test_failed_png_write_leaves_the_old_file_byte_identical);
    tcase_add_test(tc, test_png_write_applies_the_tone_mapping_it_is_given);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(pngfile_suite)
