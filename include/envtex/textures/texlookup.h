/* texlookup.h - reading an image as a texture: texture coordinates, wrap modes, nearest and
 * bilinear lookups.  Lecture "Environment, Texture Maps", the texture-mapping part of slides
 * 25-46: texture coordinates per vertex, "tiling" (repeat / clamp / mirror), magnification by
 * bilinear interpolation.  Knows nothing of scenes: it maps (s, t) to a colour.
 *
 *     rgb c = texlookup_bilinear(&img, (uv2){s, t}, WRAP_REPEAT);
 *     wrap_mode w;
 *     if (texlookup_wrap_parse("mirror", &w)) ...;     // scene files name the modes
 *
 * Conventions (the same as OpenGL and the OBJ `vt` record):
 *   - (s, t) = (st.u, st.v); s runs left to right, t runs BOTTOM to TOP.  (0, 0) is the
 *     bottom-left corner of the image, (1, 1) the top-right; [0, 1]^2 covers the image once.
 *     The image itself stores row 0 at the top (image.h), so t = 1 is row 0's top edge.
 *   - Texel (i, j) - column i from the left, j counted from the BOTTOM row - covers
 *     [i/W, (i+1)/W] x [j/H, (j+1)/H]; its centre is ((i + 0.5)/W, (j + 0.5)/H).
 *     Image row = H - 1 - j.
 *   - A wrap mode decides which texel an index outside [0, n) reads.  It is applied to texel
 *     indices (after the floor), so it also decides the neighbours bilinear blends at a border.
 *
 * Every lookup is pure and allocation free; any finite coordinate is safe (up to 1e9 and far
 * beyond: indices are wrapped in double before any conversion to int).
 */
#ifndef ENVTEX_TEXLOOKUP_H
#define ENVTEX_TEXLOOKUP_H

#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* What lies outside [0, 1] (texel indices outside [0, n)), for an index i and n texels:
 *   WRAP_REPEAT  tiles:                      i mod n              ... n-2 n-1 | 0 1 ... n-1 | 0 1 ...
 *   WRAP_CLAMP   extends the border texels:  min(max(i, 0), n-1)  ...  0  0  | 0 1 ... n-1 | n-1 ...
 *   WRAP_MIRROR  reflects, border repeated:  period 2n            ...  1  0  | 0 1 ... n-1 | n-1 n-2 ...
 *               (OpenGL's GL_MIRRORED_REPEAT) */
typedef enum wrap_mode { WRAP_REPEAT = 0, WRAP_CLAMP = 1, WRAP_MIRROR = 2 } wrap_mode;

/* Index i (any int, however far outside and negative) wrapped into [0, n).  n >= 1 (assert).
 * Never overflows: the mirror period 2n is computed in long long. */
int texlookup_wrap(int i, int n, wrap_mode wrap);

/* floor(x) wrapped into [0, n), for any double x: the wrap is done in double (exact: fmod) before
 * the conversion to int, so |x| up to 1e9 * n and beyond is safe.  NaN reads index 0; +-infinity
 * reads the border (clamp) or index 0 (repeat, mirror). */
int texlookup_wrap_floor(double x, int n, wrap_mode wrap);

/* "repeat", "clamp" or "mirror" (the scene-file spellings) into *out: 0, or -1 if unknown. */
int texlookup_wrap_parse(const char *name, wrap_mode *out);

/* The name texlookup_wrap_parse accepts for `wrap` (a static string). */
const char *texlookup_wrap_name(wrap_mode wrap);

/* Texel (i, j), j counted from the BOTTOM row, with both indices wrapped.  im non-empty. */
static inline rgb texlookup_texel(const image *im, int i, int j, wrap_mode wrap)
{
    int x = texlookup_wrap(i, im->w, wrap), y = texlookup_wrap(j, im->h, wrap);
    return image_get(im, x, im->h - 1 - y);
}

/* Nearest-texel ("point sampled") lookup: the texel whose square contains (s, t), i.e.
 * (floor(s W), floor(t H)) wrapped.  im non-empty.  A texel's square is half-open
 * [i/W, (i+1)/W): s = 1 exactly reads column 0 with repeat and column W-1 with clamp. */
rgb texlookup_nearest(const image *im, uv2 st, wrap_mode wrap);

/* Bilinear lookup: texel centres at ((i + 0.5)/W, (j + 0.5)/H) return their texel exactly (up
 * to rounding of s W); between centres the four nearest texels (wrapped) are blended,
 *     c = (1-fx)(1-fy) c00 + fx (1-fy) c10 + (1-fx) fy c01 + fx fy c11,
 *     x = s W - 1/2, i0 = floor(x), fx = x - i0   (likewise y, j0, fy from t H).
 * So with clamp the outer half texel is constant; with repeat it blends with the opposite side.
 * im non-empty.  A non-finite coordinate reads a border texel with weight 1 (never NaN from
 * the weights). */
rgb texlookup_bilinear(const image *im, uv2 st, wrap_mode wrap);

/* Past this magnitude a coordinate's floor is wrapped in double, below it as an int: 2^30
 * leaves room for the + 1 of a bilinear neighbour without reaching INT_MAX. */
#define TEXLOOKUP_INT_SAFE 0x1p30

/* floor(x) for |x| < TEXLOOKUP_INT_SAFE: truncate toward zero, then step down for a negative
 * non-integer (exact: x is compared with the integer it truncates to) */
static inline int texlookup_fast_floor(double x)
{
    int i = (int)x;
    return i - (x < (double)i);
}

/* One axis of a bilinear lookup: the two texels blended and the weight of the second. */
typedef struct texlookup_axis {
    int i0, i1; /* floor(x) and floor(x) + 1, wrapped into [0, n) */
    double f;   /* x - floor(x) in [0, 1]: i1's weight (0 for a non-finite x).  It rounds to
                 * exactly 1 for x just below an integer (x = -1e-17: i0 = -1 wrapped, f = 1),
                 * which reads i1 alone, the texel at that integer: still the right blend */
} texlookup_axis;

texlookup_axis texlookup_bilinear_axis_far(double x, int n, wrap_mode wrap);

/* One axis of a bilinear lookup over n texels (for lookups on other layouts), x = s n - 1/2 (texel centres at integers); a non-finite x reads a border
 * texel with weight 1.  Inline for the common cases, both texels inside or a tiled
 * power-of-two texture; the rest (other wraps, huge or non-finite x) is
 * texlookup_bilinear_axis_far. */
static inline texlookup_axis texlookup_bilinear_axis(double x, int n, wrap_mode wrap)
{
    if (fabs(x) < TEXLOOKUP_INT_SAFE) { /* false for NaN and infinities */
        int k = texlookup_fast_floor(x);
        if (k >= 0 && k + 1 < n) return (texlookup_axis){k, k + 1, x - k};
        if (wrap == WRAP_REPEAT && (n & (n - 1)) == 0) /* a tiled power-of-two texture: */
            return (texlookup_axis){k & (n - 1), (k + 1) & (n - 1), x - k}; /* k mod n, two's complement */
    }
    return texlookup_bilinear_axis_far(x, n, wrap);
}

#endif
