/* mipmap.h - the image pyramid for minification (Williams 1983): trilinear lookups with a
 * scalar footprint, and elliptical weighted average (EWA, Heckbert 1989, as in pbrt-v3's
 * MIPMap::EWA) for anisotropic footprints.  Lecture "Environment, Texture Maps", the
 * mip-mapping slides 36-39: "prefilter the texture at a pyramid of resolutions; pick the
 * level whose texels match the pixel's footprint; blend the two nearest levels".
 *
 *     mipmap m;
 *     if (mipmap_build(&m, &img, WRAP_REPEAT, &err)) return -1;  // img must outlive m
 *     rgb a = mipmap_lookup_trilinear(&m, st, 0.01);             // footprint: 1% of the texture
 *     rgb b = mipmap_lookup_ewa(&m, st, dst_dx, dst_dy);         // st's derivatives per pixel
 *     mipmap_free(&m);
 *
 * Coordinates, texel centres and wrap modes are texlookup.h's: (s, t) from the bottom-left,
 * t up; every level covers [0, 1]^2 once and uses the same wrap mode as its lookups.
 *
 * Levels.  Level 0 is the base image; level l+1 is max(1, floor(W_l / 2)) x max(1, floor(H_l / 2)),
 * down to 1 x 1, so there are 1 + floor(log2(max(W, H))) levels.  Sizes need not be powers of
 * two and no row or column is dropped: along each axis, destination texel x covers the source
 * interval [x r, (x+1) r], r = n_src / n_dst (2 for even sizes, a little above 2 for odd ones,
 * 3 for 3 -> 1), and takes the mean over that interval of the source's bilinear (tent)
 * reconstruction,
 *     dst[x] = (1/r) sum_j src[wrap(j)] * integral_{x r}^{(x+1) r} tent(u - (j + 1/2)) du,
 * tent(u) = max(0, 1 - |u|).  For r = 2 these are the weights (1, 7, 7, 1) / 16.  Because the
 * intervals tile [0, n_src] and each tent integrates to 1 there (its outer part wrapped by the
 * wrap mode), every level has exactly the mean of the one below (up to float storage).  The
 * outer taps read across the border through the wrap mode: with repeat a border texel of level
 * 1 takes a little of the opposite side; with clamp or mirror it does not.
 */
#ifndef ENVTEX_MIPMAP_H
#define ENVTEX_MIPMAP_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/textures/texlookup.h"
#include "envtex/core/vec.h"

/* IMAGE_MAX_SIDE = 2^15 gives at most 16 levels */
#define MIPMAP_MAX_LEVELS 16

/* EWA: the longest allowed ratio of the ellipse's major to minor axis.  Past it the minor axis
 * is lengthened (blurring a little more) so the work per lookup stays bounded (pbrt's default). */
#define MIPMAP_MAX_ANISOTROPY 8.0

/* EWA: Gaussian weight exp(-alpha r^2) - exp(-alpha) over the ellipse r^2 < 1, tabulated at
 * MIPMAP_EWA_LUT_SIZE points r^2 = i / (SIZE - 1) and read linearly interpolated, within 3.1e-5
 * of the formula (pbrt-v3's alpha = 2 and table size 128; pbrt reads entry floor(r^2 SIZE),
 * which is up to 1.6% off). */
#define MIPMAP_EWA_ALPHA 2.0
#define MIPMAP_EWA_LUT_SIZE 128

typedef struct mipmap {
    int nlevels;                     /* 1 .. MIPMAP_MAX_LEVELS */
    wrap_mode wrap;                  /* used to build every level and by every lookup */
    image level[MIPMAP_MAX_LEVELS];  /* level[0] is a shallow copy of the base: its pixels are
                                        the caller's; levels 1.. are owned */
    double ewa_weight[MIPMAP_EWA_LUT_SIZE]; /* weight at r^2 = i / (SIZE - 1) */
} mipmap;

/* Build the pyramid of `base` (non-empty) for lookups with `wrap`.  The mipmap REFERENCES the
 * base: its level 0 shares base->px, so the base must stay allocated and unchanged until
 * mipmap_free (which does not free it).  The other levels are allocated here and owned.
 * Returns 0, or -1 with *err set (empty base, unknown wrap mode, out of memory); on failure *m
 * holds nothing to free (mipmap_free is still safe). */
int mipmap_build(mipmap *m, const image *base, wrap_mode wrap, error *err);

/* What a pyramid of a w x h base costs, for a memory budget charged before it is built
 * (budget.h): `levels`, what mipmap_build keeps (levels 1 and up, 12 bytes a texel: about a
 * third of the base's bytes); `scratch`, the most it holds only while building (one level's
 * filtering buffer of doubles, 24 bytes a texel of a w/2 x h grid: about the base's bytes). */
typedef struct mipmap_cost {
    double levels, scratch; /* bytes */
} mipmap_cost;
mipmap_cost mipmap_cost_of(int w, int h);

/* Free the owned levels and reset *m (the base image is untouched).  Safe
 * on a zeroed, failed or already freed mipmap. */
void mipmap_free(mipmap *m);

/* Number of levels, 1 + floor(log2(max(W, H))). */
int mipmap_levels(const mipmap *m);

/* Level `l` (0 = the base), 0 <= l < mipmap_levels (assert).  Do not free it: levels 1.. are
 * owned by the mipmap, and level 0's pixels are the caller's base (mipmap_build). */
const image *mipmap_level(const mipmap *m, int l);

/* Continuous level for a footprint `width_in_texels` wide (in level-0 texels):
 * log2(width) clamped to [0, levels - 1].  1 texel -> 0, 4 texels -> 2; width <= 1 or NaN -> 0
 * (magnification: the base itself), +infinity -> levels - 1. */
double mipmap_level_for_footprint(const mipmap *m, double width_in_texels);

/* Trilinear lookup.  `footprint_width` is the footprint's width in TEXTURE units: the fraction
 * of the texture it spans, measured against the longer side (width_in_texels =
 * footprint_width * max(W, H)).  With level L = mipmap_level_for_footprint(width_in_texels),
 * l = floor(L), f = L - l:
 *     c = (1 - f) bilinear(level l, st) + f bilinear(level l + 1, st).
 * Continuous in footprint_width and in st; footprint <= 1 texel is a plain bilinear lookup of
 * the base.  Allocation free. */
rgb mipmap_lookup_trilinear(const mipmap *m, uv2 st, double footprint_width);

/* EWA lookup (pbrt-v3 MIPMap::EWA).  dst_dx, dst_dy: the change of (s, t) per pixel step in x
 * and y (texture units), i.e. the two axes of the pixel's footprint in texture space.
 *   - Axes are measured in level-0 texels, (ds W, dt H) (every level halves both sides, so a
 *     non-square image's texels, not its texture units, say how far up to go).  The longer is
 *     the major axis; if the minor axis is shorter than major / MIPMAP_MAX_ANISOTROPY it is
 *     lengthened to that (a zero minor axis becomes perpendicular to the major one).
 *   - Level L = log2(minor length in texels) clamped to [0, levels - 1] (for a square image,
 *     minor length in texture units * W); the two nearest levels are filtered and blended by
 *     the fraction of L, as in trilinear.
 *   - On a level, texels (i, j) whose centres lie in the ellipse r^2 < 1 of the footprint's
 *     covariance plus one texel^2 (so the filter never falls between texels) are averaged with
 *     weights exp(-alpha r^2) - exp(-alpha), normalised by their sum; indices wrap.
 * Both derivatives zero: exactly texlookup_bilinear on level 0.  A tiny footprint is a Gaussian
 * of about one texel around st, "bilinear-ish" (equal to bilinear on a linear ramp at texel
 * centres).  A footprint whose minor axis spans the whole texture (L at the top) reads the 1 x 1
 * level: the texture's mean.  A derivative that is NaN or infinite also gives the mean.
 * Work per lookup is bounded (at most about 33 x 33 texels per level); allocation free. */
rgb mipmap_lookup_ewa(const mipmap *m, uv2 st, uv2 dst_dx, uv2 dst_dy);

#endif
