/* prefiltered.h - `integrator prefiltered`: the environment's light read from illumination maps
 * instead of integrated (lecture slide 44, Miller & Hoffman 1984; Ramamoorthi & Hanrahan 2001;
 * docs/illumination-maps.md).  Camera rays, mirrors and glass are the ray tracer's
 * (raytracer.h: a mirror adds ks x its reflected ray, glass its Fresnel-weighted reflected and
 * refracted rays, a ray that leaves sees the envmap); at any other hit
 *
 *     I = emission + kd x irr(n) + ks x (n . r) phong_S(r)     (brdf phong; S its shininess)
 *
 * irr(n) = E(n) / pi, the irradiance map, at the shading normal n; phong_S(r) the Phong-lobe map
 * of exponent S (prefilter.h) at r, the mirror direction of the view; both turned into the
 * envmap frame (envmap_to_frame), looked up bilinearly and times the envmap's scale.  The
 * cosine is the course BRDF's: f = ks (S + 2) / (2 pi) (r . wi)^S meets n . wi in the rendering
 * equation, and n . wi = (n . r)(r . wi) + (a part across r), so the glossy term is ks (n . r)
 * times the normalized lobe of exponent S + 1 over L (for which the map of S stands), plus a
 * part that vanishes where L is symmetric about r, less what the horizon cuts off.  The maps
 * see the environment alone: no shadows and no light from other objects, the classic
 * approximation, exact for a lone convex object under the irradiance map (docs/
 * illumination-maps.md measures the glossy term's error).  Point, directional and quad
 * lights are ignored (the scene warns), `ambient` too; mirror and glass have no diffuse term,
 * as in the path tracer; `brdf ggx` is refused.  With `envmiss black`, or no envmap, the maps
 * are black.
 *
 * Built once per render, in memory: the exact irradiance map, PREFILTERED_IRRADIANCE_WIDTH wide
 * (`prefilter exact`, the default), or R&H's quadratic form of the 9 coefficients evaluated at
 * each n (`prefilter sh9`); one Phong map per distinct shininess of a Phong material with a
 * specular part, prefilter_phong_width(S) wide.
 *
 *     (integrator.c) raytracer_init(&it->rt, sc, accel); prefiltered_init(&it->pf, &it->rt, mem, &err);
 *     rgb L = raytracer_trace(&it->rt, camera_ray(&cam, x, y));  ...  prefiltered_free(it->pf);
 */
#ifndef ENVTEX_PREFILTERED_H
#define ENVTEX_PREFILTERED_H

#include "envtex/core/budget.h"
#include "envtex/integrators/brdf.h"
#include "envtex/envlight/prefilter.h"
#include "envtex/integrators/raytracer.h"

/* The irradiance map's width under `prefilter exact` (E is smooth: docs/illumination-maps.md). */
#define PREFILTERED_IRRADIANCE_WIDTH 128
/* At most this many distinct Phong exponents a scene (one map each, each up to a few seconds). */
#define PREFILTERED_MAX_PHONG_MAPS 16

typedef struct prefiltered {
    const envmap *env;         /* the ray tracer's (its transform and scale) */
    const material *materials; /* the scene's, which phong_of follows */
    int lit;                   /* 0: no envmap, or `envmiss black`: the maps are black */
    irradiance_method method;
    image irradiance;          /* exact: E / pi, envmap frame */
    prefilter_sh9_quadratic q; /* sh9: E(n) = (n, 1)^T M (n, 1) */
    int n_phong;
    double *phong_s;           /* the distinct exponents */
    image *phong;              /* their maps */
    int *phong_of;             /* per material of the scene: its map, or -1 */
    double build_seconds;      /* CPU time of building the maps */
    budget *mem;               /* the run's budget, charged `charged` bytes for the maps */
    double charged;
} prefiltered;

/* Build the maps for rt's scene and environment and make rt shade with them (rt->shade).
 * *out is allocated (free with prefiltered_free).  Fails, with nothing allocated and the
 * message naming the scene (the `envmap` line for its transform): a `brdf ggx` material, an
 * envmap transform that is not a rotation (times a uniform scale), a shininess over
 * PREFILTER_MAX_SHININESS, more than PREFILTERED_MAX_PHONG_MAPS distinct shininesses, a map too
 * costly to make (prefilter.h), maps over the budget `mem` (charged until prefiltered_free),
 * out of memory. */
int prefiltered_init(prefiltered **out, raytracer *rt, budget *mem, error *err);

/* Free the maps (NULL is fine). */
void prefiltered_free(prefiltered *pf);

/* raytracer_shade_fn: the local radiance above at the normal-facing surface s seen from view
 * (world), *reflect = 0 for a Phong surface (its lobe replaces the ray tracer's mirror bounce).
 * ctx is the prefiltered. */
rgb prefiltered_shade(void *ctx, const material *m, const surface *s, vec3 view, int *reflect);

/* E(n) / pi times the envmap's scale at world normal n (any non-zero length); under sh9 each
 * channel at least 0 (the quadratic form rings below 0 behind a bright source; the maps of
 * prefilter.h keep its values). */
rgb prefiltered_irradiance(const prefiltered *pf, vec3 n);

#endif
