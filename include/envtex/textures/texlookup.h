/* texlookup.h - an image read as a texture: wrap modes, nearest and bilinear lookups (slide
 * 38 (Texture Map Filtering): tiling, magnification by bilinear interpolation).
 *
 *     rgb c = texlookup_bilinear(&img, (uv2){s, t}, WRAP_REPEAT);
 *
 * (s, t) as OpenGL and OBJ `vt`: (0, 0) bottom-left, t up, [0, 1]^2 the image once.  Texel
 * (i, j), j from the BOTTOM row (image row H - 1 - j), covers [i/W, (i+1)/W] x [j/H, (j+1)/H].
 * Pure, allocation free, safe for any finite coordinate (wrapped in double first).
 */
#ifndef ENVTEX_TEXLOOKUP_H
#define ENVTEX_TEXLOOKUP_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* Outside [0, n): repeat i mod n; clamp min(max(i, 0), n-1); mirror reflects with period 2n,
 * ... 1 0 | 0 1 ... n-1 | n-1 n-2 ... (GL_MIRRORED_REPEAT) */
typedef enum wrap_mode { WRAP_REPEAT = 0, WRAP_CLAMP = 1, WRAP_MIRROR = 2 } wrap_mode;

/* Any int i wrapped into [0, n), n >= 1 (assert); never overflows. */
int texlookup_wrap(int i, int n, wrap_mode wrap);

/* floor(x) wrapped into [0, n) for any double x (wrapped exactly in double); NaN: 0;
 * +-infinity: the border (clamp) or 0. */
int texlookup_wrap_floor(double x, int n, wrap_mode wrap);

/* "repeat", "clamp" or "mirror" into *out: 0, or -1 if unknown. */
int texlookup_wrap_parse(const char *name, wrap_mode *out);

/* The name of `wrap` (static). */
const char *texlookup_wrap_name(wrap_mode wrap);

/* Texel (i, j), j from the bottom, both wrapped.  im non-empty. */
static inline rgb texlookup_texel(const image *im, int i, int j, wrap_mode wrap)
{
    int x = texlookup_wrap(i, im->w, wrap), y = texlookup_wrap(j, im->h, wrap);
    return image_get(im, x, im->h - 1 - y);
}

/* Nearest texel: (floor(s W), floor(t H)) wrapped.  im non-empty. */
rgb texlookup_nearest(const image *im, uv2 st, wrap_mode wrap);

/* Bilinear: x = s W - 1/2, i0 = floor(x), fx = x - i0 (likewise y, j0, fy from t H),
 *     c = (1-fx)(1-fy) c00 + fx (1-fy) c10 + (1-fx) fy c01 + fx fy c11   (indices wrapped);
 * exact at texel centres.  im non-empty; a non-finite coordinate reads a border texel. */
rgb texlookup_bilinear(const image *im, uv2 st, wrap_mode wrap);

/* Below this |x|, floor(x) + 1 fits an int */
#define TEXLOOKUP_INT_SAFE 0x1p30

/* floor(x), exact, for |x| < TEXLOOKUP_INT_SAFE */
static inline int texlookup_fast_floor(double x)
{
    int i = (int)x;
    return i - (x < (double)i);
}

/* One axis of a bilinear lookup: the two texels blended and the weight of the second. */
typedef struct texlookup_axis {
    int i0, i1; /* floor(x) and floor(x) + 1, wrapped into [0, n) */
    double f;   /* x - floor(x) in [0, 1]: i1's weight (0 for a non-finite x) */
} texlookup_axis;

texlookup_axis texlookup_bilinear_axis_far(double x, int n, wrap_mode wrap);

/* One axis over n texels, x = s n - 1/2 (non-finite: a border texel); inline for texels inside
 * or a tiled power-of-two texture, else texlookup_bilinear_axis_far. */
static inline texlookup_axis texlookup_bilinear_axis(double x, int n, wrap_mode wrap)
{
    if (fabs(x) < TEXLOOKUP_INT_SAFE) { /* false for NaN and infinities */
        int k = texlookup_fast_floor(x);
        if (k >= 0 && k + 1 < n) return (texlookup_axis){k, k + 1, x - k};
        if (wrap == WRAP_REPEAT && (n & (n - 1)) == 0) /* a tiled power-of-two texture: */
            return (texlookup_axis){k & (n - 1), (k + 1) & (n - 1), x - k}; /* k mod n */
    }
    return texlookup_bilinear_axis_far(x, n, wrap);
}

#endif
