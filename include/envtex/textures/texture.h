/* texture.h - a texture object and its filtered evaluation: image textures (an image, a wrap
 * mode and, when a filter needs it, its mip pyramid), the 2D checkerboard, and the solid
 * (3D, procedural) textures of Perlin noise.  Lecture "Environment, Texture Maps", slides
 * 25-46: "naive texture mapping aliases badly", bilinear magnification, mip-mapped trilinear
 * minification, EWA, procedural and solid textures, textures that drive BRDF parameters and
 * bump maps.  Knows nothing of scenes: a query says where, and how large the pixel is there.
 *
 *     texture tx;
 *     texture_init_image(&tx, &img, WRAP_REPEAT);       // img must outlive tx
 *     if (texture_prepare(&tx, TEXFILTER_TRILINEAR, &mem, &err)) return -1;  // builds the pyramid
 *     texture_query q = {0};
 *     q.st = st; q.dst_dx = dx; q.dst_dy = dy; q.filter = TEXFILTER_TRILINEAR;
 *     rgb kd = texture_eval(&tx, &q);
 *     texture_free(&tx);
 *
 * Kinds and their parameters (docs/scene-format.md spells them in the scene file):
 *   image       (s, t) as texlookup.h: from the bottom-left, t up; the wrap mode decides what
 *               lies outside [0, 1]^2.
 *   checker     2D, in (s, t): `frequency` squares per unit of s and of t; colour c0 where
 *               floor(f s) + floor(f t) is even (the square at the origin), c1 where odd.
 *   perlin      solid: v = 0.5 + 0.5 noise(scale P)
 *   fbm         solid: v = 0.5 + 0.5 fbm(scale P, octaves, lacunarity 2, gain 0.5)
 *   turbulence  solid: v = turbulence(scale P, octaves, 2, 0.5)
 *   marble      solid: v = 0.5 + 0.5 sin(frequency x + amplitude turbulence(x, octaves)), x = scale P
 *   wood        solid: v = frac(rings r + amplitude noise(x)), r = distance of x = scale P from
 *               its y axis (perlin_wood)
 *   Solid textures are evaluated at the OBJECT-space point P (so they move with the object) and
 *   return (1 - v) c0 + v c1 with v clamped to [0, 1].
 *
 * Filters (texture_filter) and what each does without differentials (all derivatives zero):
 *   nearest    image: the texel containing (s, t); checker, solids: the point value.
 *   bilinear   image: texlookup_bilinear; checker, solids: the point value.
 *   trilinear  image: mip level from the footprint width w = sqrt(|dst/dx| |dst/dy|) in
 *              texels (each axis as (ds W, dt H): the side of the square of the footprint's
 *              area when the axes are perpendicular, their geometric mean always; a non-square
 *              image's s and t texels differ in texture units),
 *              mipmap_lookup_trilinear; checker: the exact box-filtered value over the box
 *              max(|ds/dx|, |ds/dy|) wide in s (likewise t); solids: octaves band-limited by
 *              the footprint max(|dP/dx|, |dP/dy|) (perlin.h's filtered sums).
 *   ewa        image: mipmap_lookup_ewa with both derivative vectors; checker and solids: as
 *              trilinear.
 *   Fallback: zero derivatives mean "no footprint known" (for example after a diffuse bounce):
 *   trilinear and EWA then read level 0 bilinearly, the checker and solids are point sampled.
 *   That is the sharpest answer, never a blur; a renderer that wants less aliasing there must
 *   supply a footprint (for example from the path's spread angle).
 *
 * Evaluation is pure and allocation free; texture_prepare allocates (the pyramid), once.
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

/* Parameters of the solid textures.  Fields a kind does not use are still checked
 * (texture_init_solid's ranges), so zero them; they are otherwise ignored. */
typedef struct texture_solid_params {
    double scale;     /* > 0: P is multiplied by it, so features are 1 / scale object units wide */
    int octaves;      /* fbm, turbulence, marble: 1 .. PERLIN_MAX_OCTAVES */
    double frequency; /* marble: radians of vein phase per unit of scale P along x */
    double amplitude; /* marble: radians per unit of turbulence; wood: ring wobble, in rings */
    double rings;     /* wood: rings per unit of radius (of scale P) */
    rgb c0, c1;       /* colours at v = 0 and v = 1 */
} texture_solid_params;

typedef struct texture {
    texture_kind kind;
    /* image */
    const image *img; /* referenced, not owned: the caller keeps it alive and unchanged */
    wrap_mode wrap;
    mipmap mip;       /* built by texture_prepare for trilinear / EWA; owned */
    int has_mip;
    /* checker */
    double frequency; /* squares per unit of s and t, > 0 */
    rgb c0, c1;
    /* solids */
    texture_solid_params solid;
} texture;

/* Where and how to evaluate.  A zero-initialized query is valid (st = 0, no differentials,
 * nearest).  Spaces: st is texture space; p and its derivatives are the object space of the
 * surface (the one solid textures live in). */
typedef struct texture_query {
    uv2 st;              /* texture coordinates (image, checker) */
    uv2 dst_dx, dst_dy;  /* (ds/dx, dt/dx) and (ds/dy, dt/dy): change of st per pixel step */
    vec3 p;              /* object-space point (solids) */
    vec3 dp_dx, dp_dy;   /* its change per pixel step (solids' footprint) */
    vec3 dp_ds, dp_dt;   /* object-space surface tangents dP/ds, dP/dt (solids' bump
                            derivatives, texture_height_derivs); zero: no bump from solids */
    texture_filter filter;
} texture_query;

/* Bump derivatives: an image texture's central difference spans at least this many texels on
 * each side (half a texel: with bilinear reconstruction the slope is exact between centres). */
#define TEXTURE_BUMP_MIN_TEXELS 0.5

/* Bump derivatives of the checker and the solids: the smallest half step, as a fraction of one
 * feature (a square, or one noise lattice cell 1 / scale).  The checker is a step function,
 * so its bump is a ridge this wide at each edge when no footprint is known; the noise is
 * smooth, so 1e-3 of a cell gives its slope to ~1e-6. */
#define TEXTURE_BUMP_MIN_FEATURE 1e-3

/* An image texture reading `img` (non-empty, assert) with `wrap`.  References img: it must
 * stay allocated and unchanged until texture_free.  No pyramid yet (texture_prepare). */
void texture_init_image(texture *t, const image *img, wrap_mode wrap);

/* A checkerboard with `frequency` squares per unit of s and t.  Returns 0, or -1 with *err
 * set when frequency is not finite and > 0. */
int texture_init_checker(texture *t, rgb c0, rgb c1, double frequency, error *err);

/* A solid texture of `kind` (TEXTURE_PERLIN .. TEXTURE_WOOD).  Returns 0, or -1 with *err set
 * when a parameter is out of range: scale must be finite and > 0; octaves in
 * [1, PERLIN_MAX_OCTAVES] for fbm, turbulence, marble; frequency, amplitude and rings finite
 * (rings >= 0, frequency >= 0). */
int texture_init_solid(texture *t, texture_kind kind, const texture_solid_params *sp, error *err);

/* Get t ready for evaluations with `filter`: builds the mip pyramid of an image texture the
 * first time trilinear or EWA is asked for (once; later calls are free).  Other kinds and
 * filters need nothing.  What it builds is charged to `mem` first (budget.h, mipmap_cost_of;
 * NULL: no budget) and stays charged; the building scratch is released.  Returns 0, or -1 with
 * *err set (the budget, out of memory). */
int texture_prepare(texture *t, texture_filter filter, budget *mem, error *err);

/* Free what t owns (its pyramid; not the image) and zero it.  Safe on a zeroed texture. */
void texture_free(texture *t);

/* 1 if evaluating with `filter` needs texture_prepare first (an image texture filtered by
 * trilinear or EWA, without its pyramid yet). */
int texture_needs_prepare(const texture *t, texture_filter filter);

/* The texture's colour for query q, filtered by q->filter (see the table above).  An image
 * texture evaluated with trilinear or EWA must have been prepared for it (assert). */
rgb texture_eval(const texture *t, const texture_query *q);

/* The scalar value for bump, roughness and displacement maps: the mean of the three channels. */
double texture_eval_scalar(const texture *t, const texture_query *q);

/* Height h = texture_eval_scalar(t, q) and its derivatives along s and t, for bump mapping.
 *   image, checker: central differences in (s, t) with half steps
 *       es = max(0.5 (|ds/dx| + |ds/dy|), minimum), et likewise from dt,
 *     minimum = TEXTURE_BUMP_MIN_TEXELS / W (H for t) for images and TEXTURE_BUMP_MIN_FEATURE /
 *     frequency for the checker: dh/ds = (h(s + es) - h(s - es)) / (2 es).
 *   solids: central differences along the object-space tangents dP/ds, dP/dt of the query:
 *       dh/ds = (h(P + e dP/ds) - h(P - e dP/ds)) / (2 e),  e |dP/ds| = max(half the footprint
 *     0.5 (|dP/dx| + |dP/dy|), TEXTURE_BUMP_MIN_FEATURE / scale);  a zero tangent gives 0.
 * Every sample uses the query's filter and footprint, so the derivative is of the filtered
 * texture ("scaled to the footprint"): a distant bump map flattens instead of sparkling. */
void texture_height_derivs(const texture *t, const texture_query *q, double *h, double *dh_ds,
                           double *dh_dt);

/* "nearest", "bilinear", "trilinear" or "ewa" into *out: 0, or -1 if unknown. */
int texture_filter_parse(const char *name, texture_filter *out);
const char *texture_filter_name(texture_filter f); /* static string */

/* "checker", "perlin", "fbm", "turbulence", "marble" or "wood" into *out: 0, or -1 (images
 * have no keyword). */
int texture_kind_parse(const char *name, texture_kind *out);
const char *texture_kind_name(texture_kind k); /* static string; "image" for TEXTURE_IMAGE */

#endif
