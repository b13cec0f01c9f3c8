/* mistake.c - a render with the kind of error a student's code makes, for the grading tests
 * (tests/grading): the noise-aware test must fail each of these while it passes honest noise.
 *     build/tools/mistake dark F IN.exr OUT.exr    every pixel times F (0.93: 7% too dark)
 *     build/tools/mistake half F IN.exr OUT.exr    the left half of the frame times F
 *     build/tools/mistake shift N IN.exr OUT.exr   the picture moved N pixels right (edge repeated)
 * OUT keeps IN's envtex attributes (exrfile.h): it claims the same sample count. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/io/exrfile.h"
#include "envtex/io/imageio.h"

static void edit(const char *what, double f, const image *in, image *out)
{
    for (int y = 0; y < in->h; y++)
        for (int x = 0; x < in->w; x++) {
            rgb c = image_get(in, x, y);
            if (!strcmp(what, "dark") || (!strcmp(what, "half") && x < in->w / 2))
                c = rgb_scale(c, f);
            if (!strcmp(what, "shift")) {
                int sx = x - (int)f;
                c = image_get(in, sx < 0 ? 0 : sx, y);
            }
            image_set(out, x, y, c);
        }
}

int main(int argc, char **argv)
{
    error err = {0};
    image in = {0}, out = {0};
    exrfile_attrs at;
    char *end = NULL;
    double f = argc == 5 ? strtod(argv[2], &end) : 0;
    if (argc != 5 || !end || *end ||
        (strcmp(argv[1], "dark") && strcmp(argv[1], "half") && strcmp(argv[1], "shift"))) {
        fprintf(stderr, "usage: mistake dark|half|shift F IN.exr OUT.exr\n");
        return 1;
    }
    int st = imageio_read(argv[3], &in, NULL, &err) || exrfile_read_attrs(argv[3], &at, &err) ||
             image_alloc(&out, in.w, in.h, &err);
    if (!st) {
        edit(argv[1], f, &in, &out);
        st = exrfile_write_attrs(argv[4], &out, 0, &at, &err);
    }
    if (st) error_print(&err, stderr);
    image_free(&in);
    image_free(&out);
    return st ? 1 : 0;
}
