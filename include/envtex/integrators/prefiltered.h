/* prefiltered.h - `integrator prefiltered` (slide 44 (Environment Maps); Miller & Hoffman 1984,
 * Ramamoorthi & Hanrahan 2001): the environment's light read from illumination maps.  Camera rays,
 * mirrors and glass are the ray tracer's; at any other (brdf phong) hit, with the maps bilinear in
 * the envmap frame:
 *     I = emission + kd irr(n) + ks (n . r) phong_S(r),   irr = E / pi, r the mirror direction
 * No shadows, other lights, `ambient` or `brdf ggx` (docs/design-notes.md).
 *
 *     prefiltered_init(&it->pf, &it->rt, mem, &err);  ...  prefiltered_free(it->pf);
 */
#ifndef ENVTEX_PREFILTERED_H
#define ENVTEX_PREFILTERED_H

#include "envtex/core/budget.h"
#include "envtex/integrators/brdf.h"
#include "envtex/envlight/prefilter.h"
#include "envtex/integrators/raytracer.h"

/* The irradiance map's width under `prefilter exact` (E is smooth). */
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
    double *phong_s;      /* the distinct exponents */
    image *phong;         /* their maps */
    int *phong_of;        /* per material of the scene: its map, or -1 */
    double build_seconds; /* CPU time of building the maps */
    budget *mem;          /* the run's budget, charged `charged` bytes for the maps */
    double charged;
} prefiltered;

/* Build the maps and make rt shade with them; *out allocated (prefiltered_free).  -1 with *err,
 * nothing allocated: `brdf ggx`, an envmap transform not a (scaled) rotation, a shininess over
 * PREFILTER_MAX_SHININESS, more than PREFILTERED_MAX_PHONG_MAPS distinct shininesses, a map too
 * costly (prefilter.h), maps over the budget `mem` (charged until prefiltered_free), out of
 * memory. */
int prefiltered_init(prefiltered **out, raytracer *rt, budget *mem, error *err);

/* Free the maps (NULL is fine). */
void prefiltered_free(prefiltered *pf);

/* raytracer_shade_fn (ctx: the prefiltered): I above; *reflect = 0 for a Phong surface. */
rgb prefiltered_shade(void *ctx, const material *m, const surface *s, vec3 view, int *reflect);

/* E(n) / pi times the envmap's scale at world normal n (non-zero); sh9: clamped to >= 0. */
rgb prefiltered_irradiance(const prefiltered *pf, vec3 n);

#endif
