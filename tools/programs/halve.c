/* halve.c - halve a lat-long map's resolution with a 2 x 2 box filter, written as half-float
 * ZIP EXR.  How data/envmaps/courtyard.exr was made from ../shared/hdri/courtyard.exr:
 *     build/tools/halve ../shared/hdri/courtyard.exr data/envmaps/courtyard.exr
 * (A 2 x 2 average of a lat-long map is not solid-angle exact near the poles; for shipping a
 * smaller copy of a photograph that is fine.) */
#include <stdio.h>

#include "envtex/io/exrfile.h"
#include "envtex/io/imageio.h"

int main(int argc, char **argv)
{
    error err = {0};
    image in = {0}, out = {0};
    if (argc != 3) {
        fprintf(stderr, "usage: halve IN OUT.exr\n");
        return 1;
    }
    if (imageio_read(argv[1], &in, NULL, &err) || image_alloc(&out, in.w / 2, in.h / 2, &err)) {
        error_print(&err, stderr);
        return 1;
    }
    for (int y = 0; y < out.h; y++)
        for (int x = 0; x < out.w; x++) {
            rgb s = rgb_add(
                rgb_add(image_get(&in, 2 * x, 2 * y), image_get(&in, 2 * x + 1, 2 * y)),
                rgb_add(image_get(&in, 2 * x, 2 * y + 1), image_get(&in, 2 * x + 1, 2 * y + 1)));
            image_set(&out, x, y, rgb_scale(s, 0.25));
        }
    int st = exrfile_write(argv[2], &out, 1, &err);
    if (st) error_print(&err, stderr);
    image_free(&in);
    image_free(&out);
    return st ? 1 : 0;
}
