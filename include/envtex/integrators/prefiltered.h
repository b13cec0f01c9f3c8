/* prefiltered.h - `integrator prefiltered`: the environment's light read from illumination maps
 * instead of integrated (slide 44; Miller & Hoffman 1984, Ramamoorthi & Hanrahan 2001).  Camera
 * rays, mirrors and glass are the ray tracer's; at any other hit
 *     I = emission + kd x irr(n) + ks x (n . r) phong_S(r)     (brdf phong, shininess S)
 * irr = E / pi at the shading normal, phong_S the Phong-lobe map at the view's mirror direction
 * r, both in the envmap frame, bilinear, times its scale.  No shadows, no other lights or
 * `ambient` (the scene warns), no `brdf ggx`; black maps under `envmiss black` or no envmap.
 * Why (n . r) and the error: docs/illumination-maps.md and docs/design-notes.md.
 *
 *     raytracer_init(&it->rt, sc, accel); prefiltered_init(&it->pf, &it->rt, &err);
 *     rgb L = raytracer_trace(&it->rt, camera_ray(&cam, x, y));  ...  prefiltered_free(it->pf);
 */
#ifndef ENVTEX_PREFILTERED_H
#define ENVTEX_PREFILTERED_H

#include "envtex/integrators/brdf.h"
#include "envtex/envlight/prefilter.h"
#include "envtex/integrators/raytracer.h"

/* The irradiance map's width under `prefilter exact` (E is smooth). */
#define PREFILTERED_IRRADIANCE_WIDTH 128

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
} prefiltered;

/* Build the maps (the exact irradiance map or sh9's 9 coefficients; a Phong map per distinct
 * shininess) and make rt shade with them.  *out is allocated (prefiltered_free).  -1 with *err,
 * nothing allocated: `brdf ggx`, an envmap transform not a rotation (times a uniform scale), a
 * shininess over PREFILTER_MAX_SHININESS, a map too costly (prefilter.h), out of memory. */
int prefiltered_init(prefiltered **out, raytracer *rt, error *err);

/* Free the maps (NULL is fine). */
void prefiltered_free(prefiltered *pf);

/* raytracer_shade_fn (ctx: the prefiltered): I above; *reflect = 0 for a Phong surface. */
rgb prefiltered_shade(void *ctx, const material *m, const surface *s, vec3 view, int *reflect);

/* E(n) / pi times the envmap's scale at world normal n (non-zero); sh9: clamped to >= 0. */
rgb prefiltered_irradiance(const prefiltered *pf, vec3 n);

#endif
