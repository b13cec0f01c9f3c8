/* image.h - a linear RGB float image, the one in-memory picture every module shares
 * (HDR environment maps, textures, renders).  Lecture slide 10: "HDR images".
 *
 *     image im = {0};
 *     if (image_alloc(&im, 512, 256, &err)) return -1;   // zero filled
 *     image_px(&im, x, y)[0] = 1.0f;                      // red of pixel (x, y)
 *     image_free(&im);
 *
 * Layout: row-major, row 0 at the TOP, 3 floats (r, g, b) per pixel, linear (not sRGB).
 * Sizes are limited before anything is allocated: each side at most IMAGE_MAX_SIDE, the pixel
 * count at most IMAGE_MAX_PIXELS.  Readers of hostile files rely on image_check_size.
 */
#ifndef ENVTEX_IMAGE_H
#define ENVTEX_IMAGE_H

#include <stddef.h>

#include "envtex/core/error.h"
#include "envtex/core/vec.h"

#define IMAGE_MAX_SIDE 32768L
#define IMAGE_MAX_PIXELS (1L << 28)
/* The memory one pixel of an image takes: three floats (what a reader charges per texel). */
#define IMAGE_TEXEL_BYTES 12

typedef struct image {
    int w, h;  /* width and height in pixels; 0 x 0 for an empty image */
    float *px; /* w * h * 3 floats, owned; free with image_free */
} image;

/* 0 if 1 <= w, h <= IMAGE_MAX_SIDE and w * h <= IMAGE_MAX_PIXELS; otherwise -1 with a message
 * naming `file` (may be NULL).  Takes long so a hostile header cannot overflow before the check. */
int image_check_size(long w, long h, const char *file, error *err);

/* Allocate a zero-filled w x h image into *im (whose old contents are not freed). */
int image_alloc(image *im, int w, int h, error *err);

/* Free the pixels and reset *im to 0 x 0.  Safe on a zeroed or already freed image. */
void image_free(image *im);

/* Pointer to the 3 floats of pixel (x, y); x, y must be in range: not checked (it is on every
 * texel fetch), and x = w reads pixel (0, y + 1) without any sanitizer noticing. */
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
/* 1 if the three channels of the stored pixel at p (image_px) are all finite */
static inline int image_px_is_finite(const float *p) { return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]); }

/* Replace every NaN or infinite channel value by 0 (image_zero_nonfinite), or also every
 * negative one (image_zero_nonfinite_or_negative: radiance cannot be negative).  Returns how
 * many values were replaced.  Loaders call them once, so a bad texel can neither reach a
 * lookup nor bleed into its bilinear neighbours (0 x NaN is NaN). */
long image_zero_nonfinite(image *im);
long image_zero_nonfinite_or_negative(image *im);

/* Bilinear interpolation at continuous image coordinates uv in [0,1]^2: u to the right, v down,
 * texel (i, j) centred at ((i + 0.5) / W, (j + 0.5) / H).  Outside the texel centres the image
 * is extended by clamping (image_bilinear_clamp), or wrapped left-right across u = 0 = 1 and
 * clamped top-bottom (image_bilinear_wrap_u: the phi seam of lat-long, equal-area and
 * cylindrical maps).  uv must be finite. */
rgb image_bilinear_clamp(const image *im, uv2 uv);
rgb image_bilinear_wrap_u(const image *im, uv2 uv);

#endif
