/* mipmap.h - the image pyramid (Williams 1983): trilinear lookups for a scalar footprint, EWA
 * (Heckbert 1989) for an anisotropic one.  Slides 39-40 (Mip Maps): pick the level that matches the
 * footprint, blend the two nearest.
 *
 *     if (mipmap_build(&m, &img, WRAP_REPEAT, &err)) return -1;  // img must outlive m
 *     rgb c = mipmap_lookup_trilinear(&m, st, 0.01);             // 1% of the texture wide
 *
 * (s, t) and wraps as texlookup.h.  Level l+1 is max(1, W_l / 2) x max(1, H_l / 2), rounded
 * down, to 1 x 1; each keeps the mean of the one below (docs/texture-mapping.md, section 11).
 */
#ifndef ENVTEX_MIPMAP_H
#define ENVTEX_MIPMAP_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/textures/texlookup.h"
#include "envtex/core/vec.h"

#define MIPMAP_MAX_LEVELS 16 /* IMAGE_MAX_SIDE = 2^15 */

/* EWA: the largest major / minor axis ratio (bounded work) */
#define MIPMAP_MAX_ANISOTROPY 8.0

/* EWA: weight exp(-alpha r^2) - exp(-alpha) inside r^2 < 1, a table read linearly */
#define MIPMAP_EWA_ALPHA    2.0
#define MIPMAP_EWA_LUT_SIZE 128

typedef struct mipmap {
    int nlevels;                            /* 1 .. MIPMAP_MAX_LEVELS */
    wrap_mode wrap;                         /* used to build every level and by every lookup */
    image level[MIPMAP_MAX_LEVELS];         /* [0]: the caller's base (shallow); 1..: owned */
    double ewa_weight[MIPMAP_EWA_LUT_SIZE]; /* weight at r^2 = i / (SIZE - 1) */
} mipmap;

/* The pyramid of `base` (non-empty) for `wrap`; level 0 shares base->px, which must stay
 * unchanged until mipmap_free.  0, or -1 with *err (empty base, bad wrap, out of memory) and
 * nothing to free. */
int mipmap_build(mipmap *m, const image *base, wrap_mode wrap, error *err);

/* Bytes a w x h base's pyramid keeps (levels 1..) and needs while building. */
typedef struct mipmap_cost {
    double levels, scratch; /* bytes */
} mipmap_cost;
mipmap_cost mipmap_cost_of(int w, int h);

/* Free the owned levels, zero *m (not the base).  Safe on a zeroed, failed or freed mipmap. */
void mipmap_free(mipmap *m);

/* Number of levels, 1 + floor(log2(max(W, H))). */
int mipmap_levels(const mipmap *m);

/* Level l, 0 <= l < mipmap_levels (assert); not to be freed. */
const image *mipmap_level(const mipmap *m, int l);

/* log2(width_in_texels) clamped to [0, levels - 1]; width <= 1 or NaN: 0. */
double mipmap_level_for_footprint(const mipmap *m, double width_in_texels);

/* Trilinear, footprint_width in texture units of the longer side.  L = level for footprint_width
 * max(W, H), l = floor(L), f = L - l:  c = (1 - f) bilinear(l, st) + f bilinear(l + 1, st). */
rgb mipmap_lookup_trilinear(const mipmap *m, uv2 st, double footprint_width);

/* EWA over the footprint's axes dst_dx, dst_dy (change of st per pixel), in level-0 texels,
 * the minor one at least major / MIPMAP_MAX_ANISOTROPY; the minor's level and the next blended
 * as trilinear.  Zero axes: bilinear on level 0; NaN, infinite or texture-wide: its mean. */
rgb mipmap_lookup_ewa(const mipmap *m, uv2 st, uv2 dst_dx, uv2 dst_dy);

#endif
