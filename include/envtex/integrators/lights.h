/* lights.h - the scene's lights for next-event estimation (CSE 168 hw2-hw4, lecture slide 17:
 * "extend next-event estimation to envmaps"): quad, point and directional lights and the
 * environment (envlight.h), one set the sampling integrators share.
 *
 *     lights ls;
 *     lights_build(&ls, sc, el, radius, &mem, &err);
 *     int k; double prob; lights_pick(&ls, xi, &k, &prob);     // lightselection power
 *     light_sample s;
 *     if (lights_sample(&ls, k, p, ng, xi1, xi2, xi3, stratified, &s)) ... trace s.shadow ...
 *
 * `lightselection` (direct.h): `all` samples every light (`lightsamples` each, one for a delta
 * light); `power` picks one light per sample with probability proportional to its power:
 *   quad: pi A L_avg;  point: 4 pi I_avg;  directional: pi R^2 E_avg;  envmap: pi R^2 |L|
 * (R: the radius of the scene's bounding sphere).  A quad light emits on the side of ac x ab
 * (FORMAT.md) and is opaque from both sides to every ray (camera, BRDF and shadow rays), so
 * NEE and BRDF sampling agree; the quads join the scene's BVH (lights_scene_bvh).
 */
#ifndef ENVTEX_LIGHTS_H
#define ENVTEX_LIGHTS_H

#include "envtex/geometry/bvh.h"
#include "envtex/envlight/distrib.h"
#include "envtex/envlight/envlight.h"
#include "envtex/geometry/ray.h"
#include "envtex/scene/scene.h"

typedef struct lights {
    const scene *sc;
    const envlight *env;  /* NULL: no environment light */
    int n;                /* sc->n_lights, plus 1 for the environment (last index) */
    light_selection selection; /* sc->lightselection */
    distrib1d choose;     /* pick a light by power */
    double radius;
    double env_fraction;  /* c in [0, 1]: lights_set_env_fraction (default 1) */
    /* a BVH over the quad lights alone; its quad j is light quad_light[j] (an index into
     * sc->lights; owned, NULL without quads), in the order of sc->lights */
    bvh quad_bvh;
    int *quad_light;
    int n_quads;
} lights;

typedef struct light_sample {
    vec3 wi;        /* unit direction from the shading point towards the light (shading) */
    rgb Li;         /* radiance (area and env lights) or, for delta lights, irradiance at normal
                     * incidence (intensity / attenuation, power of a median-cut stratum) */
    double pdf;     /* per steradian, of this light's sampling; 0 for delta lights */
    int is_delta;   /* point, directional, median-cut: no density, not reachable by BRDF rays */
    ray shadow;     /* the visibility ray: blocked means no light */
} light_sample;

/* The light set of sc plus the environment env (NULL: none), both referenced: they must outlive
 * ls.  scene_radius is R above (<= 0: 1).  The quads' triangles and BVH are charged to `mem`
 * first (budget.h; NULL: none).  Returns 0, or -1 with *err set (the budget, out of memory);
 * free with lights_free. */
int lights_build(lights *ls, const scene *sc, const envlight *env, double scene_radius, budget *mem,
                 error *err);
void lights_free(lights *ls);

/* Pick a light with probability proportional to its power (xi in [0,1)), envmap fraction c
 * included (below): 1, *k and *prob = lights_pick_prob(k); 0 if there are none, or when the
 * envmap was picked but not kept.  (`lightselection power`; any selection may call it.) */
int lights_pick(const lights *ls, double xi, int *k, double *prob);
double lights_pick_prob(const lights *ls, int k);

/* The probability that one light sample is a sample of light k in the selection in use:
 *   all:    c for the envmap, 1 for every other light (each has samples of its own);
 *   power:  lights_pick_prob(k) = P(pick k), times c for the envmap.
 * A light sample of k estimates f Li cos / (lights_selection_prob(k) pdf_k); MIS weighs a BRDF
 * ray that finds light k against lightsamples x lights_selection_prob(k) x pdf_k. */
double lights_selection_prob(const lights *ls, int k);

/* Keep a light sample of the envmap with probability c in [0, 1] (MIS only: with NEE alone the
 * skipped directions would be lost; lights_pick returns 0 for a dropped one).  The envmap's
 * selection probability, hence its pdf in the MIS weights, is multiplied by c on both sides,
 * so the estimate stays unbiased for any c; c = 0 leaves the envmap to BRDF sampling.  The
 * pathtracer's `envsamplefraction auto` takes c from misfraction_choose. */
void lights_set_env_fraction(lights *ls, double c);
static inline int lights_env_index(const lights *ls) { return ls->env ? ls->n - 1 : -1; }

/* Sample light k from shading point p (geometric normal ng, for the shadow ray's offset) with
 * (xi1, xi2) in [0,1)^2 and xi3 in [0,1) (median cut jitter).  `stratified`: (xi1, xi2) come
 * from a stratified grid (the envmap then inverts its CDF even with alias tables).  Returns 0
 * if the sample carries nothing. */
int lights_sample(const lights *ls, int k, vec3 p, vec3 ng, double xi1, double xi2, double xi3,
                  int stratified, light_sample *out);

/* The BVH of sc's spheres and triangles and, for an integrator that sees quad lights (all but
 * `raytracer` and `prefiltered`), its quad lights: bvh_intersect's BVH_QUAD with h.prim = j is
 * light quad_light[j] of lights_build (the j-th quadLight of sc->lights).  sc is borrowed (it
 * must outlive b); b is charged to `mem`.  Returns 0, or -1 with *err set (bvh_build's
 * reasons); free with bvh_free. */
int lights_scene_bvh(bvh *b, const scene *sc, budget *mem, error *err);

/* Nearest quad light hit by r with t in (r->tmin, r->tmax): 1, its index (into sc->lights) and
 * t.  Quads are two-sided for visibility; lights_quad_radiance tells the emitting side. */
int lights_intersect_quad(const lights *ls, const ray *r, int *k, double *t);
/* Radiance leaving quad k towards direction -d (d: the ray's direction): L on the emitting side. */
rgb lights_quad_radiance(const lights *ls, int k, vec3 d);
/* pdf per steradian of lights_sample(k) producing the point at distance t along unit wi from p. */
double lights_quad_pdf(const lights *ls, int k, vec3 wi, double t);

#endif
