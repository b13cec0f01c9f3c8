/* integrator.h - which renderer runs (`integrator ...`) and the context the integrators share,
 * built once per render with only what the scene needs.
 *
 *     if (integrator_init(&it, sc, &accel, &mem, &err)) ...
 *     rgb L = render_radiance(&it, camera_ray(&cam, x, y), &r);   // render.h
 *     integrator_free(&it);
 *
 * Camera rays and mirror / glass chains see the envmap bilinearly; other bounces see the
 * piecewise-constant light of envlight.h (docs/environment-lighting.md).
 */
#ifndef ENVTEX_INTEGRATOR_H
#define ENVTEX_INTEGRATOR_H

#include "envtex/integrators/brdf.h"
#include "envtex/geometry/bvh.h"
#include "envtex/envlight/envlight.h"
#include "envtex/reflection/envmap.h"
#include "envtex/integrators/lights.h"
#include "envtex/integrators/raytracer.h"
#include "envtex/core/rng.h"

/* maxdepth -1 ("unlimited", for Russian roulette) stops at this many bounces */
#define INTEGRATOR_UNLIMITED_DEPTH 1000

/* An envmap light sample's cost over a BRDF sample's, for `envsamplefraction auto`
 * (misfraction_choose; docs/design-notes.md) */
#define INTEGRATOR_MIS_LIGHT_COST 0.6

typedef struct integrator {
    const scene *sc;
    const bvh *accel;
    envmap env;
    envlight el;
    int has_envlight; /* el built; without samples_env for lookups only (no power) */
    int samples_env;  /* el is sampled as a light (direct, or pathtracer with NEE) */
    lights ls;
    int has_lights;         /* ls built */
    int maxdepth;           /* resolved: -1 becomes INTEGRATOR_UNLIMITED_DEPTH */
    raytracer rt;           /* integrator raytracer (and prefiltered, which shades its hits) */
    struct prefiltered *pf; /* integrator prefiltered: its maps (prefiltered.h) */
    long long rays;         /* rays traced by the sampling integrators */
    double build_seconds;
    double env_fraction; /* the envmap's sampling fraction in use (lights.h), 1 if not MIS */
    nee_mode nee;        /* as run: the scene's, or off when no light can be sampled (none, or
                           * MIS with the envmap alone at fraction 0) */
} integrator;

/* Build what sc's integrator needs, tables charged to mem (NULL: none).  0, or -1 with *err
 * (an envmap problem at its `envmap` line). */
int integrator_init(integrator *it, const scene *sc, const bvh *accel, budget *mem, error *err);
void integrator_free(integrator *it);

/* ---- shared by the integrators ---------------------------------------------------------- */

/* What a ray met first. */
typedef enum scene_hit_kind {
    SCENE_HIT_NOTHING,  /* the ray escaped: the environment */
    SCENE_HIT_GEOMETRY, /* h and s valid */
    SCENE_HIT_LIGHT     /* a quad light: light and t valid */
} scene_hit_kind;

typedef struct scene_hit {
    scene_hit_kind kind;
    hit h;
    surface s;
    int light;
    double t;
} scene_hit;

/* The nearest geometry or quad light along r; geometry's surface faces the ray's origin. */
void integrator_intersect(integrator *it, const ray *r, scene_hit *out);

/* The same with differentials rd (NULL: none): the surface's footprint filters its maps. */
void integrator_intersect_diff(integrator *it, const ray *r, const ray_diff *rd, scene_hit *out);

/* The rest of integrator_intersect_diff, for a ray whose closest hit bvh_intersect (or
 * bvh_intersect_packet) found already: got its return value, out->h the hit it filled. */
void integrator_scene_hit(integrator *it, const ray *r, const ray_diff *rd, int got,
                          scene_hit *out);

/* 1 if geometry or a quad light (opaque from both sides) blocks the shadow ray. */
int integrator_occluded(integrator *it, const ray *shadow);

/* The side m of the strata grid for n samples (largest m^2 <= n); 0 if not stratifying. */
int integrator_strata(int n, int stratify);

/* (xi1, xi2) moved into stratum (j mod m, j / m) if j < m^2: returns 1, else 0. */
int integrator_stratum(int j, int m, double *xi1, double *xi2);

/* One sample of light k from s: *l and *f_li_cos = f Li cos(theta_i), returns 1; 0 when it
 * carries nothing (behind, zero BRDF, blocked).  The caller divides by the pdf. */
int integrator_light_sample(integrator *it, const surface *s, vec3 wo, int k, double xi1,
                            double xi2, double xi3, int stratified, light_sample *l, rgb *f_li_cos);

/* power heuristic with beta = 2: w = (nf pf)^2 / ((nf pf)^2 + (ng pg)^2), for pdfs of any
 * size (their squares may underflow or overflow: w stays in [0, 1]) */
static inline double integrator_power_heuristic(double nf, double pf, double ng, double pg)
{
    /* STEP(mis): Veach's power heuristic (beta = 2; Veach 1997) weighting strategy f's sample
     * against g's, slide 22 (Sampling General 2D Distributions): "probability distribution also
     * enables MIS"; 0 when nf pf is 0 or NaN, 1 when it is infinite (a delta) */
    /* STUB: (void)nf; (void)pf; (void)ng; (void)pg;
     * return 0.5; */
    double f = nf * pf, g = ng * pg;
    if (!(f > 0)) return 0;
    if (isinf(f)) return 1;
    double r = g / f; /* by the ratio: f^2 and g^2 underflow below 1e-154 (0 / 0) */
    return 1 / (1 + r * r);
    /* END STEP(mis) */
}

#endif
