/* image.c - linear RGB float images (see include/envtex/core/image.h). */
#include "envtex/core/image.h"

#include <math.h>
#include <stdlib.h>

#include "envtex/core/stepcheck.h"

int image_check_size(long w, long h, const char *file, error *err)
{
    if (w < 1 || h < 1)
        return error_set(err, file, 0, "image size %ld x %ld is empty or negative", w, h);
    if (w > IMAGE_MAX_SIDE || h > IMAGE_MAX_SIDE)
        return error_set(err, file, 0, "image size %ld x %ld is over the limit of %ld per side", w,
                         h, IMAGE_MAX_SIDE);
    if (w * h > IMAGE_MAX_PIXELS) /* both <= 2^15, so the product fits in a long */
        return error_set(err, file, 0, "image size %ld x %ld is over the limit of 2^28 pixels", w,
                         h);
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

/* The four texels around uv and the weights (ax, ay) of the right and bottom ones. */
static rgb bilinear(const image *im, uv2 uv, int wrap_u)
{
    int w = im->w, h = im->h;
    double x = uv.u * w - 0.5, y = uv.v * h - 0.5; /* texel centres at integers */
    double x0 = floor(x), y0 = floor(y);
    double ax = x - x0, ay = y - y0;
    int i0 = (int)x0, j0 = (int)y0, i1 = i0 + 1, j1 = j0 + 1;
    /* STEP(bilinear): the four texels around uv for a bilinear lookup, slide 38 (Texture Map
     * Filtering): "interpolate (bilinear) between texel values": the columns wrap across the seam
     * when wrap_u (a lat-long map, slide 9 (Environment Map Representations)) and clamp otherwise;
     * the rows clamp (image.h) */
    /* STUB: (void)wrap_u;
     * i0 = i1 = (int)fmin(fmax(uv.u * w, 0), w - 1);
     * j0 = j1 = (int)fmin(fmax(uv.v * h, 0), h - 1); */
    if (wrap_u) {
        if (i0 < 0) i0 += w;
        if (i0 >= w) i0 -= w;
        if (i1 >= w) i1 -= w;
    } else {
        if (i0 < 0) i0 = 0;
        if (i1 > w - 1) i1 = w - 1;
        if (i0 > w - 1) i0 = w - 1;
    }
    if (j0 < 0) j0 = 0;
    if (j1 > h - 1) j1 = h - 1;
    if (j0 > h - 1) j0 = h - 1;
    /* END STEP(bilinear) */
    if (__builtin_expect(((unsigned)i0 >= (unsigned)w) | ((unsigned)i1 >= (unsigned)w) |
                             ((unsigned)j0 >= (unsigned)h) | ((unsigned)j1 >= (unsigned)h),
                         0)) { /* one branch; then which of the four */
        STEPCHECK_INDEX(i0, w, "bilinear", "column");
        STEPCHECK_INDEX(i1, w, "bilinear", "column");
        STEPCHECK_INDEX(j0, h, "bilinear", "row");
        STEPCHECK_INDEX(j1, h, "bilinear", "row");
    }
    rgb c00 = image_get(im, i0, j0), c10 = image_get(im, i1, j0);
    rgb c01 = image_get(im, i0, j1), c11 = image_get(im, i1, j1);
    /* L = (1-ax)(1-ay) c00 + ax (1-ay) c10 + (1-ax) ay c01 + ax ay c11 */
    rgb top = rgb_add(rgb_scale(c00, 1 - ax), rgb_scale(c10, ax));
    rgb bottom = rgb_add(rgb_scale(c01, 1 - ax), rgb_scale(c11, ax));
    return rgb_add(rgb_scale(top, 1 - ay), rgb_scale(bottom, ay));
}

rgb image_bilinear_clamp(const image *im, uv2 uv) { return bilinear(im, uv, 0); }

rgb image_bilinear_wrap_u(const image *im, uv2 uv) { return bilinear(im, uv, 1); }

long image_zero_nonfinite(image *im)
{
    long n = 0;
    size_t count = (size_t)im->w * (size_t)im->h * 3;
    for (size_t i = 0; i < count; i++)
        if (!isfinite(im->px[i])) {
            im->px[i] = 0.0f;
            n++;
        }
    return n;
}

long image_zero_nonfinite_or_negative(image *im)
{
    long n = 0;
    size_t count = (size_t)im->w * (size_t)im->h * 3;
    for (size_t i = 0; i < count; i++)
        if (!(im->px[i] >= 0.0f) || isinf(im->px[i])) { /* NaN fails >= */
            im->px[i] = 0.0f;
            n++;
        }
    return n;
}
