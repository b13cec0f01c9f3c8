/* test_imageio.c - reading by magic bytes, writing by extension. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envtex/io/imageio.h"
#include "unit.h"

#include "testdir.h"

static void fill(image *im)
{
    error err = {0};
    ck_assert_int_eq(image_alloc(im, 12, 10, &err), 0);
    for (int i = 0; i < 12 * 10 * 3; i++) im->px[i] = (float)(i % 17) / 16.0f;
}

/* A w x h image of noise in [0, scale) (a linear congruential generator from `seed`): no
 * format compresses it much, so its files are about as large as its pixels. */
static void fill_noise(image *im, int w, int h, unsigned int seed, float scale)
{
    error err = {0};
    ck_assert_int_eq(image_alloc(im, w, h, &err), 0);
    for (int i = 0; i < w * h * 3; i++) {
        seed = seed * 1103515245u + 12345u;
        im->px[i] = (float)(seed >> 8) / 16777216.0f * scale;
    }
}

START_TEST(test_every_extension_writes_and_reads_back)
{
    make_dir();
    image im = {0};
    error err = {0};
    fill(&im);
    /* tolerance per format: exact floats; RGBE 1/256 of the pixel's brightest channel (1 here at
     * most); 8-bit sRGB about 1/255 near white in linear terms */
    const char *names[] = {"a.exr", "b.PFM", "c.hdr", "d.Png", "e.EXR"};
    double tol[] = {0.0, 0.0, 1.0 / 256.0, 0.01, 0.0};
    for (int f = 0; f < 5; f++) {
        ck_assert(imageio_can_write(names[f]));
        ck_assert_msg(imageio_write(in_dir(names[f]), &im, NULL, &err) == 0, "%s: %s", names[f],
                      err.msg);
        image back = {0};
        ck_assert_msg(imageio_read(in_dir(names[f]), &back, NULL, &err) == 0, "%s: %s", names[f],
                      err.msg);
        ck_assert_int_eq(back.w, 12);
        ck_assert_int_eq(back.h, 10);
        double worst = 0.0;
        for (int i = 0; i < 12 * 10 * 3; i++) worst = fmax(worst, fabs(back.px[i] - im.px[i]));
        ck_assert_msg(worst <= tol[f], "%s: error %g", names[f], worst);
        image_free(&back);
    }
    ck_assert_int_eq(count_files(".tmp."), 0);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_reading_goes_by_magic_bytes_not_the_name)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    fill(&im);
    ck_assert_int_eq(imageio_write(in_dir("x.pfm"), &im, NULL, &err), 0);
    ck_assert_int_eq(rename(in_dir("x.pfm"), in_dir("looks_like.png")), 0);
    ck_assert_msg(imageio_read(in_dir("looks_like.png"), &back, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(memcmp(back.px, im.px, sizeof(float) * 360), 0);
    image_free(&back);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_detect_names_the_format_by_magic_bytes_as_read_does)
{
    make_dir();
    image im = {0};
    error err = {0};
    fill(&im);
    const char *names[] = {"a.exr", "b.png", "c.hdr", "d.pfm"};
    const imageio_format want[] = {IMAGEIO_EXR, IMAGEIO_PNG, IMAGEIO_RGBE, IMAGEIO_PFM};
    for (int f = 0; f < 4; f++) {
        ck_assert_int_eq(imageio_write(in_dir(names[f]), &im, NULL, &err), 0);
        ck_assert_int_eq(imageio_detect(in_dir(names[f])), want[f]);
    }
    /* the name does not count */
    ck_assert_int_eq(rename(in_dir("b.png"), in_dir("png_named.exr")), 0);
    ck_assert_int_eq(imageio_detect(in_dir("png_named.exr")), IMAGEIO_PNG);
    FILE *f = fopen(in_dir("text.exr"), "wb");
    ck_assert_ptr_nonnull(f);
    fputs("hello", f);
    fclose(f);
    ck_assert_int_eq(imageio_detect(in_dir("text.exr")), IMAGEIO_UNKNOWN);
    ck_assert_int_eq(imageio_detect(in_dir("missing.exr")), IMAGEIO_UNKNOWN);
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_unknown_missing_empty_and_folder_inputs_are_clear_errors)
{
    make_dir();
    image im = {0};
    error err = {0};
    ck_assert_int_eq(imageio_read(in_dir("missing.exr"), &im, NULL, &err), -1);
    ck_assert_str_eq(err.msg, "cannot open: No such file or directory");
    ck_assert_str_eq(err.file, in_dir("missing.exr"));
    ck_assert_int_eq(imageio_read(dir, &im, NULL, &err), -1);
    ck_assert_str_eq(err.msg, "cannot open: it is a directory, not a regular file");
    write_bytes(in_dir("empty.exr"), "", 0);
    ck_assert_int_eq(imageio_read(in_dir("empty.exr"), &im, NULL, &err), -1);
    ck_assert_str_eq(err.msg, "file is empty");
    write_bytes(in_dir("gif.exr"), "GIF89a\1\0\1\0", 10);
    ck_assert_int_eq(imageio_read(in_dir("gif.exr"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "unknown image format"));
    write_bytes(in_dir("short"), "\x76\x2f", 2); /* half an EXR magic */
    ck_assert_int_eq(imageio_read(in_dir("short"), &im, NULL, &err), -1);
    ck_assert_ptr_null(im.px);
    remove_dir();
}
END_TEST

/* Every reader charges the memory budget before it allocates: the decoded image (12 bytes a
 * texel), which stays charged, and its scratch (the file's bytes, PNG's rows, OpenEXR's chunk
 * buffers), which it releases.  A budget one byte short of the peak refuses the file with one
 * message naming the file, the claim and the budget, and leaves nothing charged. */
START_TEST(test_every_reader_charges_the_budget_and_keeps_only_the_image_charged)
{
    make_dir();
    image im = {0};
    error err = {0};
    fill_noise(&im, 40, 30, 7u, 1.0f);
    const char *names[] = {"a.exr", "b.pfm", "c.hdr", "d.png"};
    for (int f = 0; f < 4; f++) {
        ck_assert_int_eq(imageio_write(in_dir(names[f]), &im, NULL, &err), 0);
        budget mem;
        budget_init(&mem, 1e9);
        image back = {0};
        ck_assert_msg(imageio_read(in_dir(names[f]), &back, &mem, &err) == 0, "%s: %s", names[f],
                      err.msg);
        ck_assert_msg(mem.used == 40 * 30 * IMAGE_TEXEL_BYTES, "%s: %g charged", names[f],
                      mem.used);
        ck_assert_msg(mem.peak > mem.used, "%s: no scratch charged (peak %g)", names[f], mem.peak);
        image_free(&back);
        double peak = mem.peak;
        budget_init(&mem, peak - 1);
        ck_assert_int_eq(imageio_read(in_dir(names[f]), &back, &mem, &err), -1);
        ck_assert_ptr_null(back.px);
        ck_assert_str_eq(err.file, in_dir(names[f]));
        ck_assert_msg(strstr(err.msg, "beyond the memory budget of"), "%s: %s", names[f], err.msg);
        ck_assert_msg(mem.used == 0, "%s: %g left charged", names[f], mem.used);
        budget_init(&mem, peak);
        ck_assert_msg(imageio_read(in_dir(names[f]), &back, &mem, &err) == 0, "%s: %s", names[f],
                      err.msg);
        image_free(&back);
    }
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_truncated_files_of_every_format_are_errors)
{
    make_dir();
    image im = {0};
    error err = {0};
    fill(&im);
    const char *names[] = {"t.exr", "t.pfm", "t.hdr", "t.png"};
    for (int f = 0; f < 4; f++) {
        ck_assert_int_eq(imageio_write(in_dir(names[f]), &im, NULL, &err), 0);
        size_t n;
        unsigned char *d = slurp(in_dir(names[f]), &n);
        size_t cuts[] = {3, 12, n / 2, n - 13};
        for (size_t i = 0; i < 4; i++) {
            write_bytes(in_dir("cut"), d, cuts[i]);
            image back = {0};
            ck_assert_msg(imageio_read(in_dir("cut"), &back, NULL, &err) == -1, "%s cut at %zu",
                          names[f], cuts[i]);
            ck_assert_ptr_null(back.px);
        }
        free(d);
    }
    image_free(&im);
    remove_dir();
}
END_TEST

START_TEST(test_unknown_extension_and_invalid_images_write_nothing)
{
    make_dir();
    image im = {0}, empty = {0};
    error err = {0};
    fill(&im);
    ck_assert(!imageio_can_write("out.jpg"));
    ck_assert(!imageio_can_write("out"));
    ck_assert(!imageio_can_write("dir.exr/out"));
    ck_assert_int_eq(imageio_write(in_dir("out.jpg"), &im, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, ".exr"));
    ck_assert_int_eq(imageio_write(in_dir("out.exr"), &empty, NULL, &err), -1);
    ck_assert_int_eq(count_files("out"), 0);
    image_free(&im);
    remove_dir();
}
END_TEST

/* imageio_write_as: the format given wins over the name (a scene's `output scene2` is a PNG,
 * read back by its magic bytes), alone and in a set, with no temporary left; IMAGEIO_UNKNOWN
 * goes by the extension as imageio_write does. */
START_TEST(test_write_as_a_named_format_whatever_the_name)
{
    make_dir();
    image im = {0}, back = {0};
    error err = {0};
    fill(&im);
    char p1[256], p2[256];
    snprintf(p1, sizeof p1, "%s", in_dir("scene2"));
    snprintf(p2, sizeof p2, "%s", in_dir("scene6.bmp"));
    ck_assert_msg(imageio_write_as(p1, IMAGEIO_PNG, &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(imageio_detect(p1), IMAGEIO_PNG);
    ck_assert_msg(imageio_read(p1, &back, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(back.w, im.w);
    image_free(&back);
    const char *paths[1] = {p2};
    const image *images[1] = {&im};
    const imageio_format fmt[1] = {IMAGEIO_PNG};
    ck_assert_msg(imageio_write_set(1, paths, images, NULL, fmt, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(imageio_detect(p2), IMAGEIO_PNG);
    ck_assert_int_eq(imageio_write_as(in_dir("x.jpg"), IMAGEIO_UNKNOWN, &im, NULL, &err), -1);
    ck_assert_int_eq(count_files("partial"), 0);
    ck_assert_int_eq(count_files(".tmp."), 0);
    image_free(&im);
    remove_dir();
}
END_TEST

/* A write that fails part-way (the disk fills up: here a file size limit of 2 KB, for an image
 * of 49 KB of noise that no format compresses below it) is an error naming the file, leaves the
 * old file byte-identical and removes its temporary file, in every format.  And again with an
 * 8 x 8 image and a limit of 100 bytes: the whole file fits in stdio's buffer, so for the
 * writers that use stdio (PFM, HDR, PNG) it is fclose's flush that fails, and a writer that
 * ignored fclose's result would commit a truncated file. */
START_TEST(test_a_write_that_fails_part_way_leaves_the_old_file_and_no_temporary)
{
    make_dir();
    image im = {0}, noise = {0};
    error err = {0};
    fill(&im);
    fill_noise(&noise, 64, 64, 12345, 4.0f);
    image small = {0};
    ck_assert_int_eq(image_alloc(&small, 8, 8, &err), 0);
    memcpy(small.px, noise.px, sizeof(float) * 8 * 8 * 3);
    const char *names[] = {"a.exr", "b.pfm", "c.hdr", "d.png"};
    for (int round = 0; round < 2; round++)
        for (int f = 0; f < 4; f++) {
            ck_assert_int_eq(imageio_write(in_dir(names[f]), &im, NULL, &err), 0);
            size_t n;
            unsigned char *before = slurp(in_dir(names[f]), &n);
            file_size_limit(round == 0 ? 2048 : 100);
            int rc = imageio_write(in_dir(names[f]), round == 0 ? &noise : &small, NULL, &err);
            file_size_unlimited();
            ck_assert_msg(rc == -1, "%s, round %d: a write over the size limit succeeded", names[f],
                          round);
            ck_assert_msg(strstr(err.file, names[f]) != NULL, "%s: error names '%s'", names[f],
                          err.file);
            ck_assert_msg(strstr(err.msg, "File too large") != NULL, "%s, round %d: %s", names[f],
                          round, err.msg);
            assert_unchanged(in_dir(names[f]), before, n);
        }
    image_free(&im);
    image_free(&noise);
    image_free(&small);
    remove_dir();
}
END_TEST

/* A set of images is one output: all written, or no target touched. */
START_TEST(test_a_set_of_images_is_written_all_or_none)
{
    make_dir();
    image small = {0}, big = {0};
    error err = {0};
    fill(&small);
    fill_noise(&big, 64, 64, 777, 1.0f);
    /* the old targets, to be kept byte for byte */
    ck_assert_int_eq(imageio_write(in_dir("a.pfm"), &small, NULL, &err), 0);
    ck_assert_int_eq(imageio_write(in_dir("b.exr"), &small, NULL, &err), 0);
    size_t na, nb;
    unsigned char *a0 = slurp(in_dir("a.pfm"), &na), *b0 = slurp(in_dir("b.exr"), &nb);
    /* the first (1.5 KB) fits under 4 KB, the second (49 KB of noise) does not */
    char pa[256], pb[256], pc[256]; /* in_dir's buffers rotate: keep the names */
    snprintf(pa, sizeof pa, "%s", in_dir("a.pfm"));
    snprintf(pb, sizeof pb, "%s", in_dir("b.exr"));
    snprintf(pc, sizeof pc, "%s", in_dir("c.png"));
    const char *paths[2] = {pa, pb};
    const image *images[2] = {&small, &big};
    file_size_limit(4096);
    int rc = imageio_write_set(2, paths, images, NULL, NULL, &err);
    file_size_unlimited();
    ck_assert_int_eq(rc, -1);
    ck_assert_str_eq(err.file, pb); /* the target, not its temporary */
    ck_assert_ptr_nonnull(strstr(err.msg, "File too large"));
    ck_assert_int_eq(count_files("partial"), 0);
    assert_unchanged(pa, a0, na);
    assert_unchanged(pb, b0, nb);
    /* a folder in a target's place: refused before anything is written */
    ck_assert_int_eq(mkdir(pc, 0700), 0);
    const char *paths2[2] = {pa, pc};
    ck_assert_int_eq(imageio_write_set(2, paths2, images, NULL, NULL, &err), -1);
    ck_assert_ptr_nonnull(strstr(err.msg, "it is a folder"));
    ck_assert_int_eq(count_files("partial"), 0);
    ck_assert_int_eq(rmdir(pc), 0);
    /* the good case: both replaced, read back */
    ck_assert_msg(imageio_write_set(2, paths, images, NULL, NULL, &err) == 0, "%s", err.msg);
    image back = {0};
    ck_assert_msg(imageio_read(pb, &back, NULL, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(memcmp(back.px, big.px, sizeof(float) * 64 * 64 * 3), 0);
    ck_assert_int_eq(count_files("partial"), 0);
    image_free(&back);
    image_free(&small);
    image_free(&big);
    remove_dir();
}
END_TEST

Suite *imageio_suite(void)
{
    Suite *s = suite_create("imageio");
    TCase *tc = tcase_create("imageio");
    tcase_add_test(tc, test_every_extension_writes_and_reads_back);
    tcase_add_test(tc, test_reading_goes_by_magic_bytes_not_the_name);
    tcase_add_test(tc, test_detect_names_the_format_by_magic_bytes_as_read_does);
    tcase_add_test(tc, test_unknown_missing_empty_and_folder_inputs_are_clear_errors);
    tcase_add_test(tc, test_a_write_that_fails_part_way_leaves_the_old_file_and_no_temporary);
    tcase_add_test(tc, test_a_set_of_images_is_written_all_or_none);
    tcase_add_test(tc, test_truncated_files_of_every_format_are_errors);
    tcase_add_test(tc, test_every_reader_charges_the_budget_and_keeps_only_the_image_charged);
    tcase_add_test(tc, test_unknown_extension_and_invalid_images_write_nothing);
    tcase_add_test(tc, test_write_as_a_named_format_whatever_the_name);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(imageio_suite)
