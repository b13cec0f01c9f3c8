/* test_pfm.c - Portable Float Map reading and writing. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envtex/io/imageio.h"
#include "envtex/io/pfm.h"
#include "unit.h"

#include "testdir.h"

static void little_float(unsigned char *p, float v)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    for (int i = 0; i < 4; i++) p[i] = (unsigned char)(u >> (8 * i));
}

/* Write `header` then the n floats v little endian (the pixels as a PFM with scale -1 stores
 * them) to path. */
static void write_pfm_bytes(const char *path, const char *header, const float *v, int n)
{
    size_t h = strlen(header);
    unsigned char d[256];
    ck_assert_uint_le(h + 4 * (size_t)n, sizeof d);
    memcpy(d, header, h);
    for (int i = 0; i < n; i++) little_float(d + h + 4 * i, v[i]);
    write_bytes(path, d, h + 4 * (size_t)n);
}

START_TEST(test_pfm_roundtrip_is_bit_exact_including_nan_and_inf)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 5, 3, &err), 0);
    for (int i = 0; i < 45; i++)
        im.px[i] = (float)(i - 20) * 0.123f * powf(10.0f, (float)(i % 7 - 3));
    im.px[4] = NAN;
    im.px[7] = INFINITY;
    im.px[8] = -0.0f;
    ck_assert_int_eq(pfm_write(in_dir("a.pfm"), &im, &err), 0);
    ck_assert_msg(pfm_read(in_dir("a.pfm"), &back, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(back.w, 5);
    ck_assert_int_eq(back.h, 3);
    ck_assert_int_eq(memcmp(im.px, back.px, sizeof(float) * 45), 0);
    ck_assert_int_eq(count_files(".tmp."), 0);
    image_free(&im);
    image_free(&back);
    remove_dir();
}
END_TEST

START_TEST(test_pfm_rows_are_stored_bottom_to_top)
{
    make_dir();
    /* 1 x 2 colour, little endian: the first stored row is the BOTTOM one */
    float v[6] = {1, 2, 3, 4, 5, 6};
    write_pfm_bytes(in_dir("rows.pfm"), "PF\n1 2\n-1.0\n", v, 6);
    image im = {0};
    error err = {0};
    ck_assert_msg(pfm_read(in_dir("rows.pfm"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(image_px(&im, 0, 0)[0] == 4.0f); /* top row = last stored */
    ck_assert(image_px(&im, 0, 1)[2] == 3.0f);
    image_free(&im);
    remove_dir();
}
END_TEST

/* A header with Windows line ends ("PF\r\n2 1\r\n-1.0\r\n") ends in one "\r\n": the pixels start
 * after the "\n" (read from the "\n", every float came out shifted by a byte: garbage, no error).
 * A header ending in a lone "\r" whose first pixel byte is 0x0A still reads that byte as a pixel.
 */
START_TEST(test_pfm_header_with_crlf_line_ends)
{
    make_dir();
    float v[6] = {1, 2, 3, 4, 5, 6};
    write_pfm_bytes(in_dir("crlf.pfm"), "PF\r\n2 1\r\n-1.0\r\n", v, 6);
    image im = {0};
    error err = {0};
    ck_assert_msg(pfm_read(in_dir("crlf.pfm"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(im.w, 2);
    for (int i = 0; i < 6; i++)
        ck_assert_msg(im.px[i] == v[i], "px[%d] = %g, want %g", i, im.px[i], v[i]);
    image_free(&im);

    /* lone "\r", grey, first float 0x3F80000A little endian: its first byte is the 0x0A */
    uint32_t bits = 0x3F80000Au;
    float g[2] = {0, 2.0f};
    memcpy(&g[0], &bits, 4);
    write_pfm_bytes(in_dir("cr.pfm"), "Pf\r2 1\r-1.0\r", g, 2);
    size_t n;
    unsigned char *e = slurp(in_dir("cr.pfm"), &n);
    ck_assert_int_eq(e[12], 0x0A);
    free(e);
    float first = g[0];
    ck_assert_msg(pfm_read(in_dir("cr.pfm"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == first && im.px[3] == 2.0f);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_big_endian_grey_pfm_is_replicated)
{
    make_dir();
    unsigned char d[11 + 8];
    memcpy(d, "Pf\n2 1\n1.0\n", 11);
    float v[2] = {1.2345678f, -2.0f}; /* 0x3F9E0651: four different bytes, so any byte order */
    for (int i = 0; i < 2; i++) {     /* but big endian's (most significant first) reads wrong */
        uint32_t u;
        memcpy(&u, &v[i], 4);
        for (int k = 0; k < 4; k++) d[11 + 4 * i + k] = (unsigned char)(u >> (24 - 8 * k));
    }
    write_bytes(in_dir("g.pfm"), d, sizeof d);
    image im = {0};
    error err = {0};
    ck_assert_msg(imageio_read(in_dir("g.pfm"), &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert(im.px[0] == 1.2345678f && im.px[1] == 1.2345678f && im.px[2] == 1.2345678f);
    ck_assert(im.px[3] == -2.0f && im.px[5] == -2.0f);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_absurd_pfm_size_is_refused_before_allocation)
{
    make_dir();
    const char *h = "PF\n100000 100000\n-1.0\n";
    write_bytes(in_dir("big.pfm"), h, strlen(h));
    image im = {0};
    error err = {0};
    ck_assert_int_eq(pfm_read(in_dir("big.pfm"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "over the limit"));
    ck_assert_ptr_null(im.px);
    const char *z = "PF\n2 2\n0\n";
    write_bytes(in_dir("zero.pfm"), z, strlen(z));
    ck_assert_int_eq(pfm_read(in_dir("zero.pfm"), &im, NULL, &err),
                     -1); /* scale 0: no byte order */
    const char *m = "P6\n2 2\n255\n";
    write_bytes(in_dir("ppm.pfm"), m, strlen(m));
    ck_assert_int_eq(pfm_read(in_dir("ppm.pfm"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "not a PFM"));
    remove_dir();
}
END_TEST

/* Header tokens that are not what they claim: each refused with its message, before any
 * pixel is read. */
START_TEST(test_malformed_pfm_header_tokens_are_refused)
{
    make_dir();
    char longscale[128];
    snprintf(longscale, sizeof longscale, "PF\n1 1\n-1.%0*d\n", 70, 0); /* a 73-byte scale token */
    static const struct {
        const char *head, *msg;
    } cases[] = {
        {"PF\n1 1\n-1.0x\n", "bad PFM scale \"-1.0x\""},
        {"PF\n4 -1\n-1.0\n", "bad PFM size \"4 -1\""},
        {"PF\n4 1x\n-1.0\n", "bad PFM size \"4 1x\""},
        /* far past a long: refused as a size, not wrapped around into a small one */
        {"PF\n18446744073709551617 1\n-1.0\n", "bad PFM size \"18446744073709551617 1\""},
        {NULL, "truncated PFM header"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *h = cases[i].head ? cases[i].head : longscale;
        unsigned char d[256] = {0};
        size_t n = strlen(h);
        memcpy(d, h, n);
        write_bytes(in_dir("h.pfm"), d, n + 12); /* room for one pixel */
        image im = {0};
        error err = {0};
        ck_assert_msg(pfm_read(in_dir("h.pfm"), &im, NULL, &err) == -1, "no error for %s", h);
        ck_assert_msg(strstr(err.msg, cases[i].msg) != NULL, "'%s' for %s", err.msg, h);
        ck_assert_ptr_null(im.px);
    }
    remove_dir();
}
END_TEST

START_TEST(test_truncated_pfm_is_an_error_at_every_offset)
{
    make_dir();
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 4, 4, &err), 0);
    ck_assert_int_eq(pfm_write(in_dir("full.pfm"), &im, &err), 0);
    size_t n;
    unsigned char *d = slurp(in_dir("full.pfm"), &n);
    /* 11: the file ends right after the scale token, with no white space to end the header */
    size_t cuts[] = {0, 1, 2, 5, 9, 10, 11, 12, n / 2, n - 1};
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
        write_bytes(in_dir("cut.pfm"), d, cuts[i]);
        image back = {0};
        ck_assert_msg(pfm_read(in_dir("cut.pfm"), &back, NULL, &err) == -1, "cut at %zu", cuts[i]);
        ck_assert_ptr_null(back.px);
    }
    free(d);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_failed_pfm_write_leaves_the_old_file_byte_identical)
{
    make_dir();
    image im = {0}, empty = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 3, 2, &err), 0);
    im.px[0] = 7.0f;
    ck_assert_int_eq(pfm_write(in_dir("keep.pfm"), &im, &err), 0);
    size_t nb;
    unsigned char *before = slurp(in_dir("keep.pfm"), &nb);
    ck_assert_int_eq(pfm_write(in_dir("keep.pfm"), &empty, &err), -1);
    ck_assert_int_eq(pfm_write(in_dir("missing/keep.pfm"), &im, &err), -1);
    assert_unchanged(in_dir("keep.pfm"), before, nb);
    image_free(&im);
    remove_dir();
}
END_TEST

Suite *pfm_suite(void)
{
    Suite *s = suite_create("pfm");
    TCase *tc = tcase_create("pfm");
    tcase_add_test(tc, test_pfm_roundtrip_is_bit_exact_including_nan_and_inf);
    tcase_add_test(tc, test_pfm_rows_are_stored_bottom_to_top);
    tcase_add_test(tc, test_pfm_header_with_crlf_line_ends);
    tcase_add_test(tc, test_big_endian_grey_pfm_is_replicated);
    tcase_add_test(tc, test_absurd_pfm_size_is_refused_before_allocation);
    tcase_add_test(tc, test_malformed_pfm_header_tokens_are_refused);
    tcase_add_test(tc, test_truncated_pfm_is_an_error_at_every_offset);
    tcase_add_test(tc, test_failed_pfm_write_leaves_the_old_file_byte_identical);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(pfm_suite)
