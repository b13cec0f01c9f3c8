/* image.c - linear RGB float images (see include/envtex/image.h). */
#include "envtex/image.h"

#include <stdlib.h>

int image_check_size(long w, long h, const char *file, error *err)
{
    if (w < 1 || h < 1)
        return error_set(err, file, 0, "image size %ld x %ld is empty or negative", w, h);
    if (w > IMAGE_MAX_SIDE || h > IMAGE_MAX_SIDE)
        return error_set(err, file, 0, "image size %ld x %ld is over the limit of %ld per side", w,
                         h, IMAGE_MAX_SIDE);
    if (w * h > IMAGE_MAX_PIXELS) /* both <= 2^15, so the product fits in a long */
        return error_set(err, file, 0, "image size %ld x %ld is over the limit of 2^28 pixels", w, h);
    return 0;
}

int image_alloc(image *im, int w, int h, error *err)
{
    im->w = im->h = 0;
    im->px = NULL;
    if (image_check_size(w, h, NULL, err)) return -1;
    float *px = calloc((size_t)w * (size_t)h * 3, sizeof *px);
    if (!px) return error_set(err, NULL, 0, "out of memory for a %d x %d image", w, h);
    im->w = w;
    im->h = h;
    im->px = px;
    return 0;
}

void image_free(image *im)
{
    if (!im) return;
    free(im->px);
    im->px = NULL;
    im->w = im->h = 0;
}
