/* integrator.h - which renderer runs (`integrator raytracer|analyticdirect|direct|pathtracer`)
 * and the context they share, built once per render with only what the scene needs: environment
 * sampling tables exist only for integrators that sample lights (direct, and the path tracer
 * with next-event estimation); the light set (lights.h: the quads' BVH that every ray stops at,
 * the pick table) for every integrator but `raytracer`, which builds nothing.
 *
 *     integrator it;
 *     if (integrator_init(&it, sc, &accel, &mem, &err)) ...
 *     rgb L = render_radiance(&it, camera_ray(&cam, x, y), &r);   // render.h
 *     integrator_free(&it);
 *
 * The sampling integrators see the environment two ways (docs/environment-lighting.md): along
 * camera rays and chains of perfect mirror / glass bounces, where no other strategy competes,
 * it is looked up bilinearly (the smooth reflection map); after any other bounce it is the
 * piecewise-constant light of envlight.h, so that light sampling (whose pdf = L / |L| is
 * constant over a texel) and BRDF sampling estimate exactly the same integral.
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

/* The time of one envmap light sample (shadow ray, BRDF and pdfs) relative to one BRDF sample's
 * ray and shading, for `envsamplefraction auto` (envlight_mis_fraction).  Measured: MIS with
 * c = 1 took 1.2-1.8x the time of BRDF sampling alone at equal spp on the bench scenes
 * (docs/results, 2026-11). */
#define INTEGRATOR_MIS_LIGHT_COST 0.6

typedef struct integrator {
    const scene *sc;
    const bvh *accel;
    envmap env;
    envlight el;
    int has_envlight;   /* el built (the envmap lights the scene: looked up, maybe sampled); without
                         * samples_env only for lookups (envlight_build_lookup: no power) */
    int samples_env;    /* the integrator samples el as a light (direct, or pathtracer with NEE) */
    lights ls;
    int has_lights;     /* ls built */
    int maxdepth;       /* resolved: -1 becomes INTEGRATOR_UNLIMITED_DEPTH */
    raytracer rt;       /* integrator raytracer (and prefiltered, which shades its hits) */
    struct prefiltered *pf; /* integrator prefiltered: its maps (prefiltered.h) */
    long long rays;     /* rays traced by the sampling integrators */
    double build_seconds;
    double env_fraction;  /* the envmap's sampling fraction in use (lights.h), 1 if not MIS */
    nee_mode nee;         /* the path tracer's next-event estimation as run: the scene's, or off
                           * when no light can be sampled (no lights; or MIS whose only light is
                           * the envmap at fraction c = 0, which is BRDF sampling alone: the same
                           * estimator without a light pick and a pdf lookup per vertex) */
} integrator;

/* Build what sc's integrator needs (the envmap's tables charged to `mem`, envlight.h; NULL: no
 * budget).  Returns 0, or -1 with *err set, an envmap problem at its `envmap` line. */
int integrator_init(integrator *it, const scene *sc, const bvh *accel, budget *mem, error *err);
void integrator_free(integrator *it);

/* ---- shared by the integrators ---------------------------------------------------------- */

typedef struct scene_hit {
    int kind;        /* 0: nothing, 1: geometry (h, s valid), 2: a quad light (light, t valid) */
    hit h;
    surface s;
    int light;
    double t;
} scene_hit;

/* Nearest of the geometry (BVH) and the quad lights along r; fills the shading surface with
 * normals turned towards the ray's origin. */
void integrator_intersect(integrator *it, const ray *r, scene_hit *out);

/* The same for a ray with differentials rd (NULL: none): the surface gets its footprint
 * (s.has_diff, dpdx, ...) and its texture maps are filtered over it (texshade.h). */
void integrator_intersect_diff(integrator *it, const ray *r, const ray_diff *rd, scene_hit *out);

/* 1 if the shadow ray is blocked by geometry or by a quad light (either side: lights are opaque
 * to every ray, so light sampling and BRDF sampling see the same visibility). */
int integrator_occluded(integrator *it, const ray *shadow);

/* `lightstratify on` with n light samples: the side m of the m x m grid of strata (the largest
 * m with m^2 <= n; samples past m^2 are not stratified); 0 when not stratifying. */
int integrator_strata(int n, int stratify);

/* Sample j of n with an m x m grid: (xi1, xi2) moved into stratum (j mod m, j / m) if j < m^2.
 * Returns 1 if the sample is stratified. */
int integrator_stratum(int j, int m, double *xi1, double *xi2);

/* One sample of light k seen from s: fills *l and *f_li_cos = f(wo, wi) Li cos(theta_i) and
 * returns 1, or returns 0 when it carries nothing (the light is behind the surface, the BRDF is
 * zero there, or the shadow ray is blocked).  The caller divides by the pdf and weights. */
int integrator_light_sample(integrator *it, const surface *s, vec3 wo, int k, double xi1, double xi2,
                            double xi3, int stratified, light_sample *l, rgb *f_li_cos);

/* power heuristic with beta = 2: w = (nf pf)^2 / ((nf pf)^2 + (ng pg)^2) */
static inline double integrator_power_heuristic(double nf, double pf, double ng, double pg)
{
    /* STEP(mis): Veach's power heuristic (beta = 2) for the sample of strategy f against g:
     * (nf pf)^2 / ((nf pf)^2 + (ng pg)^2); 0 when nf pf is 0 (or NaN), 1 when it is infinite
     * (a delta) (slide 23) */
    /* STUB: (void)nf; (void)pf; (void)ng; (void)pg;
     * return 0.5; */
    double f = nf * pf, g = ng * pg;
    if (!(f > 0)) return 0;
    if (isinf(f)) return 1;
    return f * f / (f * f + g * g);
    /* END STEP(mis) */
}

#endif
