/* texture.h - a texture and its filtered evaluation: images (with their mip pyramid), the
 * checkerboard and Perlin's solid textures (slides 26-46 (Texture Mapping)).
 *
 *     texture_init_image(&tx, &img, WRAP_REPEAT);       // img must outlive tx
 *     if (texture_prepare(&tx, TEXFILTER_TRILINEAR, &mem, &err)) return -1;
 *     texture_query q = {.st = st, .dst_dx = dx, .dst_dy = dy, .filter = TEXFILTER_TRILINEAR};
 *     rgb kd = texture_eval(&tx, &q);
 *     texture_free(&tx);
 *
 * Solids are evaluated at the object-space point: (1 - v) c0 + v c1, v in [0, 1] (perlin.h).
 * The checker is c0 where floor(f s) + floor(f t) is even.  Evaluation is pure and allocation
 * free.  Details: docs/texture-mapping.md, section 11.
 */
#ifndef ENVTEX_TEXTURE_H
#define ENVTEX_TEXTURE_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/textures/mipmap.h"
#include "envtex/textures/texlookup.h"
#include "envtex/core/vec.h"

typedef enum texture_kind {
    TEXTURE_IMAGE,
    TEXTURE_CHECKER,
    TEXTURE_PERLIN,
    TEXTURE_FBM,
    TEXTURE_TURBULENCE,
    TEXTURE_MARBLE,
    TEXTURE_WOOD
} texture_kind;

typedef enum texture_filter {
    TEXFILTER_NEAREST,
    TEXFILTER_BILINEAR,
    TEXFILTER_TRILINEAR, /* the scene's default */
    TEXFILTER_EWA
} texture_filter;

/* The solids' parameters; zero those a kind does not use (they are checked). */
typedef struct texture_solid_params {
    double scale;     /* > 0: the noise of scale P */
    int octaves;      /* fbm, turbulence, marble: 1 .. PERLIN_MAX_OCTAVES */
    double frequency; /* marble: radians per unit of scale P along x */
    double amplitude; /* marble: radians per unit of turbulence; wood: rings */
    double rings;     /* wood: rings per unit of radius */
    rgb c0, c1;       /* colours at v = 0 and v = 1 */
} texture_solid_params;

typedef struct texture {
    texture_kind kind;
    /* image */
    const image *img; /* the caller's, kept alive and unchanged */
    wrap_mode wrap;
    mipmap mip; /* owned, built by texture_prepare */
    int has_mip;
    /* checker */
    double frequency; /* squares per unit of s and t, > 0 */
    rgb c0, c1;
    /* solids */
    texture_solid_params solid;
} texture;

/* Where and how to evaluate (zeroed: valid, nearest, no footprint); p is in object space. */
typedef struct texture_query {
    uv2 st;             /* texture coordinates (image, checker) */
    uv2 dst_dx, dst_dy; /* change of st per pixel step in x and y */
    vec3 p;             /* object-space point (solids) */
    vec3 dp_dx, dp_dy;  /* its change per pixel step */
    vec3 dp_ds, dp_dt;  /* tangents dP/ds, dP/dt (solids' bump); zero: no bump */
    texture_filter filter;
} texture_query;

/* Bump: an image's smallest half step, in texels */
#define TEXTURE_BUMP_MIN_TEXELS 0.5

/* Bump: the checker's and solids' smallest half step, in squares or noise cells */
#define TEXTURE_BUMP_MIN_FEATURE 1e-3

/* An image texture of img (non-empty, assert; kept unchanged until texture_free), no pyramid. */
void texture_init_image(texture *t, const image *img, wrap_mode wrap);

/* A checkerboard, `frequency` squares per unit of s and t: 0, or -1 with *err unless finite > 0. */
int texture_init_checker(texture *t, rgb c0, rgb c1, double frequency, error *err);

/* A solid texture (TEXTURE_PERLIN .. TEXTURE_WOOD): 0, or -1 with *err unless scale > 0,
 * octaves in [1, PERLIN_MAX_OCTAVES] (fbm, turbulence, marble), all finite, rings and
 * frequency >= 0. */
int texture_init_solid(texture *t, texture_kind kind, const texture_solid_params *sp, error *err);

/* Ready t for `filter`: an image's pyramid, built once for trilinear or EWA and charged to mem
 * first (NULL: no budget; the scratch is released).  0, or -1 with *err (budget, memory). */
int texture_prepare(texture *t, texture_filter filter, budget *mem, error *err);

/* Free the pyramid (not the image), zero t.  Safe on a zeroed texture. */
void texture_free(texture *t);

/* 1 if `filter` needs texture_prepare first (an image for trilinear or EWA, not yet built). */
int texture_needs_prepare(const texture *t, texture_filter filter);

/* The colour at q by q->filter: nearest, bilinear read a point; trilinear the mip level of
 * w = sqrt(|dst/dx| |dst/dy|) texels (checker: a box filter; solids: octaves band-limited by
 * max(|dP/dx|, |dP/dy|)); ewa mipmap_lookup_ewa (others as trilinear).  Zero derivatives:
 * read at the point (images bilinearly).  Images prepared for trilinear or EWA (assert). */
rgb texture_eval(const texture *t, const texture_query *q);

/* The mean of the channels (bump, roughness and displacement maps). */
double texture_eval_scalar(const texture *t, const texture_query *q);

/* h = texture_eval_scalar(t, q) and dh/ds, dh/dt by central differences of the filtered
 * texture, (h(s + e) - h(s - e)) / 2e with e = max(0.5 (|ds/dx| + |ds/dy|), the minimum above)
 * (likewise t); solids step along q's dP/ds, dP/dt (zero: 0). */
void texture_height_derivs(const texture *t, const texture_query *q, double *h, double *dh_ds,
                           double *dh_dt);

/* "nearest", "bilinear", "trilinear" or "ewa" into *out: 0, or -1 if unknown. */
int texture_filter_parse(const char *name, texture_filter *out);
const char *texture_filter_name(texture_filter f); /* static string */

/* "checker", "perlin", "fbm", "turbulence", "marble" or "wood": 0, or -1. */
int texture_kind_parse(const char *name, texture_kind *out);
const char *texture_kind_name(texture_kind k); /* static string; "image" for TEXTURE_IMAGE */

#endif
