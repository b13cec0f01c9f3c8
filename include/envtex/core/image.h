/* image.h - the linear RGB float image every module shares: HDR maps, textures, renders
 * (slide 10 (High Dynamic Range): "HDR images").
 *
 *     if (image_alloc(&im, 512, 256, &err)) return -1;   // zero filled
 *     image_px(&im, x, y)[0] = 1.0f;                      // red of pixel (x, y)
 *
 * Row-major, row 0 at the TOP, 3 linear floats a pixel.  Sizes are checked before allocation.
 */
#ifndef ENVTEX_IMAGE_H
#define ENVTEX_IMAGE_H

#include <stddef.h>

#include "envtex/core/error.h"
#include "envtex/core/vec.h"

#define IMAGE_MAX_SIDE   32768L
#define IMAGE_MAX_PIXELS (1L << 28)
/* Bytes a pixel takes, as readers charge them. */
#define IMAGE_TEXEL_BYTES 12

typedef struct image {
    int w, h;  /* 0 x 0 when empty */
    float *px; /* w * h * 3 floats, owned: image_free */
} image;

/* 0 if 1 <= w, h <= IMAGE_MAX_SIDE and w h <= IMAGE_MAX_PIXELS (no overflow), else -1 with
 * a message naming `file` (may be NULL). */
int image_check_size(long w, long h, const char *file, error *err);

/* A zero-filled w x h image into *im (old contents not freed). */
int image_alloc(image *im, int w, int h, error *err);

/* Free; *im becomes 0 x 0.  Safe on a zeroed or freed image. */
void image_free(image *im);

/* The 3 floats of pixel (x, y), unchecked: x, y must be in range. */
static inline float *image_px(const image *im, int x, int y)
{
    return im->px + 3 * ((size_t)y * (size_t)im->w + (size_t)x);
}
static inline rgb image_get(const image *im, int x, int y)
{
    const float *p = image_px(im, x, y);
    return (rgb){p[0], p[1], p[2]};
}
static inline void image_set(image *im, int x, int y, rgb c)
{
    float *p = image_px(im, x, y);
    p[0] = (float)c.r;
    p[1] = (float)c.g;
    p[2] = (float)c.b;
}
/* 1 if the pixel at p has three finite channels */
static inline int image_px_is_finite(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* Every NaN or infinite (or also negative) channel value becomes 0; returns how many. */
long image_zero_nonfinite(image *im);
long image_zero_nonfinite_or_negative(image *im);

/* Bilinear at finite uv, texel (i, j) centred at ((i + 0.5) / W, (j + 0.5) / H), extended by
 * clamping, or wrapped across u = 0 = 1 and clamped in v (the phi seam). */
rgb image_bilinear_clamp(const image *im, uv2 uv);
rgb image_bilinear_wrap_u(const image *im, uv2 uv);

#endif
