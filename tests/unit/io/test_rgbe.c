/* test_rgbe.c - Radiance .hdr (RGBE) reading and writing. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envtex/io/imageio.h"
#include "envtex/io/rgbe.h"
#include "unit.h"

#include "testdir.h"

/* the length of the header rgbe_write writes (clang warns about an array used only in sizeof) */
enum { HEADER_LEN = sizeof "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" - 1 };

static void fill(image *im, int w, int h)
{
    error err = {0};
    ck_assert_int_eq(image_alloc(im, w, h, &err), 0);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *p = image_px(im, x, y);
            p[0] = (float)(x / 4) * 0.3f + 0.01f; /* runs of 4 equal values: RLE runs */
            p[1] = (float)y * 100.0f + 0.5f;
            p[2] = (float)((x * 7 + y) % 11) * 1e-3f;
        }
}

/* RGBE keeps 8 bits of the brightest channel: every channel is within 1/256 of it (the
 * mantissa bin is 1/128..1/256 of the value wide, decoded at its middle). */
static double worst_error(const image *a, const image *b)
{
    double worst = 0.0;
    for (size_t i = 0; i < (size_t)a->w * a->h; i++) {
        const float *p = a->px + 3 * i, *q = b->px + 3 * i;
        double m = fmax(p[0], fmax(p[1], p[2]));
        for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(p[k] - q[k]) / m);
    }
    return worst;
}

START_TEST(test_rle_and_flat_roundtrips_are_within_rgbe_precision)
{
    make_dir();
    image im = {0}, rle = {0}, flat = {0};
    error err = {0};
    fill(&im, 300, 7);
    ck_assert_int_eq(rgbe_write(in_dir("r.hdr"), &im, &err), 0);
    ck_assert_int_eq(rgbe_write_flat(in_dir("f.hdr"), &im, &err), 0);
    ck_assert_msg(rgbe_read(in_dir("r.hdr"), &rle, NULL, &err) == 0, "%s", err.msg);
    ck_assert_msg(rgbe_read(in_dir("f.hdr"), &flat, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(memcmp(rle.px, flat.px, sizeof(float) * 3 * 300 * 7), 0); /* same pixels */
    ck_assert_double_le(worst_error(&im, &rle), 1.0 / 256.0);
    size_t nr, nf;
    free(slurp(in_dir("r.hdr"), &nr));
    free(slurp(in_dir("f.hdr"), &nf));
    ck_assert_uint_lt(nr, nf); /* the runs did compress */
    ck_assert_int_eq(count_files(".tmp."), 0);
    image_free(&im);
    image_free(&rle);
    image_free(&flat);
    remove_dir();
}
END_TEST

START_TEST(test_narrow_images_are_written_flat_and_read_back)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    fill(&im, 5, 3); /* below 8 pixels new-style RLE is undefined */
    ck_assert_int_eq(rgbe_write(in_dir("n.hdr"), &im, &err), 0);
    ck_assert_msg(imageio_read(in_dir("n.hdr"), &back, NULL, &err) == 0, "%s", err.msg);
    ck_assert_double_le(worst_error(&im, &back), 1.0 / 256.0);
    image_free(&im);
    image_free(&back);
    remove_dir();
}
END_TEST

START_TEST(test_rgbe_pixel_conversion_known_values)
{
    unsigned char b[4];
    float c[3];
    rgbe_from_float((float[3]){1.0f, 0.5f, 0.0f}, b);
    ck_assert_int_eq(b[0], 128); /* 1 = 0.5 * 2^1: mantissa 128/256, exponent 1 + 128 */
    ck_assert_int_eq(b[1], 64);
    ck_assert_int_eq(b[2], 0);
    ck_assert_int_eq(b[3], 129);
    rgbe_to_float(b, c);
    ck_assert(c[0] == 128.5f / 128.0f); /* (128 + 0.5) / 256 * 2 */
    rgbe_from_float((float[3]){-0.3f, 0.5f, 0.25f}, b);
    ck_assert_int_eq(b[0], 0); /* a negative channel beside positive ones stores as 0 */
    ck_assert_int_eq(b[1], 128);
    ck_assert_int_eq(b[2], 64);
    rgbe_from_float((float[3]){NAN, -1.0f, 0.0f}, b);
    ck_assert_int_eq(b[3], 0); /* NaN and negatives store as black */
    rgbe_to_float(b, c);
    ck_assert(c[0] == 0.0f && c[1] == 0.0f && c[2] == 0.0f);
    rgbe_from_float((float[3]){INFINITY, 1.0f, 1.0f}, b);
    ck_assert_int_eq(b[3], 255); /* +Inf: the largest value */
    rgbe_from_float((float[3]){1e-35f, 0.0f, 0.0f}, b);
    ck_assert_int_eq(b[3], 0); /* below RGBE_BLACK */
}
END_TEST

START_TEST(test_handmade_flat_file_with_comments_and_exposure_reads)
{
    make_dir();
    const char h[] = "#?RGBE\n# made by hand\nEXPOSURE=2.0\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 1\n";
    unsigned char d[sizeof h - 1 + 8];
    memcpy(d, h, sizeof h - 1);
    memcpy(d + sizeof h - 1,
           "\x80\x40\x00\x81"
           "\x00\x00\x00\x00",
           8);
    write_bytes(in_dir("hand.hdr"), d, sizeof d);
    image im = {0};
    error err = {0};
    ck_assert_msg(imageio_read(in_dir("hand.hdr"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(im.w, 1);
    ck_assert_int_eq(im.h, 2);
    ck_assert(im.px[0] == 128.5f / 128.0f && im.px[1] == 64.5f / 128.0f &&
              im.px[2] == 0.5f / 128.0f);
    ck_assert(im.px[3] == 0.0f); /* second row: e = 0 is black */
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_old_style_runs_repeat_the_previous_pixel)
{
    make_dir();
    const char h[] = "#?RADIANCE\n\n-Y 1 +X 6\n";
    unsigned char d[sizeof h - 1 + 12];
    memcpy(d, h, sizeof h - 1);
    memcpy(d + sizeof h - 1,
           "\x80\x80\x80\x81"
           "\x01\x01\x01\x04"
           "\x40\x40\x40\x81",
           12);
    write_bytes(in_dir("old.hdr"), d, sizeof d);
    image im = {0};
    error err = {0};
    ck_assert_msg(rgbe_read(in_dir("old.hdr"), &im, NULL, &err) == 0, "%s", err.msg);
    for (int x = 0; x < 5; x++) ck_assert(image_px(&im, x, 0)[1] == 128.5f / 128.0f);
    ck_assert(image_px(&im, 5, 0)[1] == 64.5f / 128.0f);
    image_free(&im);
    memcpy(d + sizeof h - 1 + 4, "\x01\x01\x01\x09", 4); /* a run of 9 in a 6-pixel scanline */
    write_bytes(in_dir("old2.hdr"), d, sizeof d);
    ck_assert_int_eq(rgbe_read(in_dir("old2.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "overflows"));
    remove_dir();
}
END_TEST

/* A file of one 8-pixel new-style RLE scanline whose first channel is `chan0` (n bytes); the
 * other three channels are a run of 8. */
static void write_rle8(const char *path, const unsigned char *chan0, size_t n)
{
    unsigned char d[256];
    size_t o = 0;
    const char h[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n";
    memcpy(d, h, sizeof h - 1);
    o += sizeof h - 1;
    memcpy(d + o, "\x02\x02\x00\x08", 4);
    o += 4;
    memcpy(d + o, chan0, n);
    o += n;
    for (int c = 0; c < 3; c++) {
        d[o++] = 128 + 8;
        d[o++] = c == 2 ? 129 : 10;
    }
    write_bytes(path, d, o);
}

START_TEST(test_hostile_rle_runs_that_overflow_the_scanline_are_errors)
{
    make_dir();
    image im = {0};
    error err = {0};
    write_rle8(in_dir("ok.hdr"), (const unsigned char *)"\x88\x20", 2); /* a run of 8: fine */
    ck_assert_msg(rgbe_read(in_dir("ok.hdr"), &im, NULL, &err) == 0, "%s", err.msg);
    image_free(&im);
    write_rle8(in_dir("run.hdr"), (const unsigned char *)"\xff\x20", 2); /* a run of 127 */
    ck_assert_int_eq(rgbe_read(in_dir("run.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "overflows"));
    write_rle8(in_dir("lit.hdr"), (const unsigned char *)"\x04\x01\x02\x03\x04\x80",
               6); /* 4 + 128 */
    ck_assert_int_eq(rgbe_read(in_dir("lit.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "overflows"));
    write_rle8(in_dir("lit9.hdr"),
               (const unsigned char *)"\x09\x01\x02\x03\x04\x05\x06\x07\x08\x09", 10);
    ck_assert_int_eq(rgbe_read(in_dir("lit9.hdr"), &im, NULL, &err), -1); /* one byte more than 8 */
    ck_assert_ptr_nonnull(strstr(err.msg, "overflows"));
    write_rle8(in_dir("zero.hdr"), (const unsigned char *)"\x00", 1);
    ck_assert_int_eq(rgbe_read(in_dir("zero.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "zero-length RLE literal"));
    ck_assert_ptr_null(im.px);
    remove_dir();
}
END_TEST

/* A literal of exactly 128 bytes (the count byte 128: a literal, not a run; runs are 129..255):
 * 300 pixels whose red mantissas count 128, 129, ..., 255 over and over are written as literals
 * of 128 and their red read back exactly (each decodes to the middle of its bin, which it was). */
START_TEST(test_rle_literals_of_128_bytes_roundtrip_exactly)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 300, 2, &err), 0);
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 300; x++)
            image_px(&im, x, y)[0] = (float)((128 + x % 128 + 0.5) / 256.0);
    ck_assert_int_eq(rgbe_write(in_dir("lit.hdr"), &im, &err), 0);
    ck_assert_msg(rgbe_read(in_dir("lit.hdr"), &back, NULL, &err) == 0, "%s", err.msg);
    for (int i = 0; i < 600; i++) /* red exactly; green and blue are 0, read as half a bin */
        ck_assert_msg(back.px[3 * i] == im.px[3 * i], "pixel %d: %.9g, want %.9g", i,
                      back.px[3 * i], im.px[3 * i]);
    image_free(&im);
    image_free(&back);
    remove_dir();
}
END_TEST

/* A new-style scanline whose RLE length is not the image width is an error, even when the runs
 * that follow would fill the width. */
START_TEST(test_rle_length_other_than_the_width_is_an_error)
{
    make_dir();
    unsigned char d[128];
    size_t o = 0;
    const char h[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n";
    memcpy(d, h, sizeof h - 1);
    o += sizeof h - 1;
    memcpy(d + o, "\x02\x02\x00\x09", 4); /* says 9 */
    o += 4;
    for (int c = 0; c < 4; c++) {
        d[o++] = 128 + 8; /* runs of 8: the width */
        d[o++] = c == 3 ? 129 : 10;
    }
    write_bytes(in_dir("len.hdr"), d, o);
    image im = {0};
    error err = {0};
    ck_assert_int_eq(rgbe_read(in_dir("len.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "RLE length 9"));
    ck_assert_ptr_null(im.px);
    remove_dir();
}
END_TEST

START_TEST(test_unsupported_headers_are_refused_with_a_reason)
{
    make_dir();
    image im = {0};
    error err = {0};
    const char *flip = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 2 +X 2\n";
    write_bytes(in_dir("flip.hdr"), flip, strlen(flip));
    ck_assert_int_eq(rgbe_read(in_dir("flip.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "only -Y H +X W"));
    const char *xyze = "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 2\n";
    write_bytes(in_dir("xyze.hdr"), xyze, strlen(xyze));
    ck_assert_int_eq(rgbe_read(in_dir("xyze.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "xyze"));
    const char *big = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 99999 +X 99999\n";
    write_bytes(in_dir("big.hdr"), big, strlen(big));
    ck_assert_int_eq(rgbe_read(in_dir("big.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "over the limit"));
    const char *junk = "#?RADIANCE\n\n-Y two +X 2\n";
    write_bytes(in_dir("junk.hdr"), junk, strlen(junk));
    ck_assert_int_eq(rgbe_read(in_dir("junk.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_null(im.px);
    remove_dir();
}
END_TEST

/* Read the n bytes d (after a "#?RADIANCE" header ending in the resolution line `res`) as an
 * .hdr file: 0 and *im, or -1 and err. */
static int read_bytes_hdr(const char *res, const void *px, size_t n, image *im, error *err)
{
    unsigned char d[2048];
    int h = snprintf((char *)d, sizeof d, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n%s\n", res);
    ck_assert(h > 0 && (size_t)h + n <= sizeof d);
    memcpy(d + h, px, n);
    write_bytes(in_dir("b.hdr"), d, (size_t)h + n);
    return rgbe_read(in_dir("b.hdr"), im, NULL, err);
}

/* What marks a scanline as new-style RLE: width 8 to 32767 and 2, 2, then a length whose high
 * bit is clear.  A flat pixel may begin with 2, 2 all the same (a dark red-green), and must be
 * read as a pixel. */
START_TEST(test_flat_pixels_that_begin_like_an_rle_marker_are_pixels)
{
    make_dir();
    image im = {0};
    error err = {0};
    unsigned char px[8 * 4];
    for (int i = 0; i < 8; i++) memcpy(px + 4 * i, "\x80\x40\x20\x81", 4);
    memcpy(px, "\x02\x02\x00\x88", 4); /* width 4: too narrow for RLE */
    ck_assert_msg(read_bytes_hdr("-Y 1 +X 4", px, 16, &im, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == 2.5f && im.px[2] == 0.5f); /* (m + 1/2) / 256 * 2^(136 - 128) */
    ck_assert(im.px[3] == 128.5f / 128.0f);
    image_free(&im);
    memcpy(px, "\x02\x02\x80\x88", 4); /* width 8, but the length's high bit is set */
    ck_assert_msg(read_bytes_hdr("-Y 1 +X 8", px, 32, &im, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == 2.5f && im.px[2] == 128.5f);
    ck_assert(im.px[21] == 128.5f / 128.0f);
    image_free(&im);
    remove_dir();
}
END_TEST

/* Old-style runs (1, 1, 1, n): each repeats the previous pixel n << shift times, the shift
 * growing by 8 for each consecutive marker and starting again after a pixel. */
START_TEST(test_old_style_run_counts_shift_by_8_and_restart)
{
    make_dir();
    image im = {0};
    error err = {0};
    /* 260 pixels: A, then 3 and 1 << 8 = 256 copies of it from two consecutive markers */
    ck_assert_msg(read_bytes_hdr("-Y 1 +X 260",
                                 "\x80\x80\x80\x81"
                                 "\x01\x01\x01\x03"
                                 "\x01\x01\x01\x01",
                                 12, &im, &err) == 0,
                  "%s", err.msg);
    for (int x = 0; x < 260; x++) ck_assert(image_px(&im, x, 0)[1] == 128.5f / 128.0f);
    image_free(&im);
    /* A, 2 copies, B, 2 copies: the second marker's shift is 0 again (a kept shift made 512) */
    ck_assert_msg(read_bytes_hdr("-Y 1 +X 6",
                                 "\x80\x80\x80\x81"
                                 "\x01\x01\x01\x02"
                                 "\x40\x40\x40\x81"
                                 "\x01\x01\x01\x02",
                                 16, &im, &err) == 0,
                  "%s", err.msg);
    ck_assert(image_px(&im, 2, 0)[1] == 128.5f / 128.0f &&
              image_px(&im, 5, 0)[1] == 64.5f / 128.0f);
    image_free(&im);
    /* a marker before any pixel, and a run one pixel too long */
    ck_assert_int_eq(read_bytes_hdr("-Y 1 +X 6",
                                    "\x01\x01\x01\x02"
                                    "\x80\x80\x80\x81",
                                    8, &im, &err),
                     -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "old-style run with no pixel before it"));
    ck_assert_int_eq(read_bytes_hdr("-Y 1 +X 6",
                                    "\x80\x80\x80\x81"
                                    "\x01\x01\x01\x06",
                                    8, &im, &err),
                     -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "overflows"));
    ck_assert_ptr_null(im.px);
    remove_dir();
}
END_TEST

/* A literal that runs past the end of the file is "truncated", not read from past the buffer. */
START_TEST(test_rle_literal_past_the_end_of_the_file_is_truncated)
{
    make_dir();
    image im = {0};
    error err = {0};
    ck_assert_int_eq(read_bytes_hdr("-Y 1 +X 8",
                                    "\x02\x02\x00\x08"
                                    "\x08\x01\x02\x03",
                                    8, &im, &err),
                     -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "truncated Radiance file: scanline 0"));
    ck_assert_ptr_null(im.px);
    remove_dir();
}
END_TEST

/* Header lines: trailing white space (and \r) is not part of a value; the magic, the resolution
 * line's tokens and its orientation are checked. */
START_TEST(test_header_lines_magic_and_resolution)
{
    make_dir();
    image im = {0};
    error err = {0};
    const char *ws =
        "#?RADIANCE \r\nFORMAT=32-bit_rle_rgbe \t\r\n\r\n-Y 1 +X 1 \r\n\x80\x80\x80\x81";
    write_bytes(in_dir("ws.hdr"), ws, strlen(ws));
    ck_assert_msg(rgbe_read(in_dir("ws.hdr"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == 128.5f / 128.0f);
    image_free(&im);
    const char *magic = "#!RADIANCE\n\n-Y 1 +X 1\n\x80\x80\x80\x81";
    write_bytes(in_dir("magic.hdr"), magic, strlen(magic));
    ck_assert_int_eq(rgbe_read(in_dir("magic.hdr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "not a Radiance file"));
    ck_assert_int_eq(read_bytes_hdr("-Y 1 +X 1 junk", "\x80\x80\x80\x81", 4, &im, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "bad Radiance resolution line \"-Y 1 +X 1 junk\""));
    ck_assert_int_eq(read_bytes_hdr("-Y 1 -X 1", "\x80\x80\x80\x81", 4, &im, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "only -Y H +X W"));
    ck_assert_ptr_null(im.px);
    remove_dir();
}
END_TEST

START_TEST(test_truncated_hdr_is_an_error_at_every_offset)
{
    make_dir();
    image im = {0};
    error err = {0};
    fill(&im, 40, 6);
    for (int flat = 0; flat < 2; flat++) {
        ck_assert_int_eq((flat ? rgbe_write_flat : rgbe_write)(in_dir("full.hdr"), &im, &err), 0);
        size_t n;
        unsigned char *d = slurp(in_dir("full.hdr"), &n);
        size_t cuts[] = {0, 2, 10, HEADER_LEN, HEADER_LEN + 4, n / 2, n - 1};
        for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
            write_bytes(in_dir("cut.hdr"), d, cuts[i]);
            image back = {0};
            ck_assert_msg(rgbe_read(in_dir("cut.hdr"), &back, NULL, &err) == -1,
                          "flat %d cut at %zu", flat, cuts[i]);
            ck_assert_ptr_null(back.px);
        }
        free(d);
    }
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_failed_hdr_write_leaves_the_old_file_byte_identical)
{
    make_dir();
    image im = {0}, empty = {0};
    error err = {0};
    fill(&im, 9, 2);
    ck_assert_int_eq(rgbe_write(in_dir("keep.hdr"), &im, &err), 0);
    size_t nb;
    unsigned char *before = slurp(in_dir("keep.hdr"), &nb);
    ck_assert_int_eq(rgbe_write(in_dir("keep.hdr"), &empty, &err), -1);
    ck_assert_int_eq(rgbe_write(in_dir("nope/keep.hdr"), &im, &err), -1);
    assert_unchanged(in_dir("keep.hdr"), before, nb);
    image_free(&im);
    remove_dir();
}
END_TEST

Suite *rgbe_suite(void)
{
    Suite *s = suite_create("rgbe");
    TCase *tc = tcase_create("rgbe");
    tcase_add_test(tc, test_rle_and_flat_roundtrips_are_within_rgbe_precision);
    tcase_add_test(tc, test_narrow_images_are_written_flat_and_read_back);
    tcase_add_test(tc, test_rgbe_pixel_conversion_known_values);
    tcase_add_test(tc, test_handmade_flat_file_with_comments_and_exposure_reads);
    tcase_add_test(tc, test_old_style_runs_repeat_the_previous_pixel);
    tcase_add_test(tc, test_hostile_rle_runs_that_overflow_the_scanline_are_errors);
    tcase_add_test(tc, test_rle_literals_of_128_bytes_roundtrip_exactly);
    tcase_add_test(tc, test_rle_length_other_than_the_width_is_an_error);
    tcase_add_test(tc, test_unsupported_headers_are_refused_with_a_reason);
    tcase_add_test(tc, test_flat_pixels_that_begin_like_an_rle_marker_are_pixels);
    tcase_add_test(tc, test_old_style_run_counts_shift_by_8_and_restart);
    tcase_add_test(tc, test_rle_literal_past_the_end_of_the_file_is_truncated);
    tcase_add_test(tc, test_header_lines_magic_and_resolution);
    tcase_add_test(tc, test_truncated_hdr_is_an_error_at_every_offset);
    tcase_add_test(tc, test_failed_hdr_write_leaves_the_old_file_byte_identical);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(rgbe_suite)
