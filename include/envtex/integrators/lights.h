/* lights.h - the scene's lights for next-event estimation (hw2-hw4; slide 16 (Environment Maps
 * Generally), NEE extended to envmaps): quad, point, directional and the environment (envlight.h),
 * shared.
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
 * (R: the scene's bounding radius).  A quad light emits on the side of ac x ab and is opaque
 * from both sides to every ray, so NEE and BRDF sampling agree.
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
    const envlight *env;       /* NULL: no environment light */
    int n;                     /* sc->n_lights, + 1 for the environment (last) */
    light_selection selection; /* sc->lightselection */
    distrib1d choose;          /* pick a light by power */
    double radius;
    double env_fraction; /* c in [0, 1]: lights_set_env_fraction (default 1) */
    /* the quad lights' own BVH: its quad j is sc->lights[quad_light[j]] (owned) */
    bvh quad_bvh;
    int *quad_light;
    int n_quads;
} lights;

typedef struct light_sample {
    vec3 wi;      /* unit direction from the shading point towards the light */
    rgb Li;       /* radiance, or for delta lights irradiance at normal incidence */
    double pdf;   /* per steradian, of this light's sampling; 0 for delta lights */
    int is_delta; /* point, directional, median-cut: no density, BRDF rays cannot reach it */
    ray shadow;   /* the visibility ray: blocked means no light */
} light_sample;

/* The lights of sc plus env (NULL: none), both borrowed (they must outlive ls); scene_radius is
 * R (<= 0: 1).  The quads' BVH is charged to `mem` (NULL: none).  0, or -1 with *err set (the
 * budget, memory); free with lights_free. */
int lights_build(lights *ls, const scene *sc, const envlight *env, double scene_radius, budget *mem,
                 error *err);
void lights_free(lights *ls);

/* Pick a light by power (xi in [0,1)): 1, *k and *prob = lights_pick_prob(k); 0 if there are
 * none, or the envmap was picked but not kept (lights_set_env_fraction). */
int lights_pick(const lights *ls, double xi, int *k, double *prob);
double lights_pick_prob(const lights *ls, int k);

/* The probability that one light sample is of light k: `all` 1 (c for the envmap), `power`
 * lights_pick_prob(k) (times c for the envmap).  A light sample estimates
 * f Li cos / (prob pdf_k); MIS weighs a BRDF ray against lightsamples x prob x pdf_k. */
double lights_selection_prob(const lights *ls, int k);

/* Keep a light sample of the envmap with probability c in [0, 1] (MIS only; lights_pick returns
 * 0 for a dropped one); its selection probability, hence its pdf in the MIS weights, is
 * multiplied by c, which keeps the estimate unbiased; c = 0 leaves it to BRDF sampling. */
void lights_set_env_fraction(lights *ls, double c);
static inline int lights_env_index(const lights *ls) { return ls->env ? ls->n - 1 : -1; }

/* Sample light k from p (geometric normal ng, for the shadow ray's offset) with xi1, xi2, xi3
 * in [0,1); `stratified`: (xi1, xi2) from a stratified grid (the envmap then inverts its CDF
 * even with alias tables).  0 if the sample carries nothing. */
int lights_sample(const lights *ls, int k, vec3 p, vec3 ng, double xi1, double xi2, double xi3,
                  int stratified, light_sample *out);

/* The BVH of sc's spheres, triangles and (for all integrators but `raytracer` and
 * `prefiltered`) quad lights: BVH_QUAD with h.prim = j is light quad_light[j].  sc is borrowed;
 * b is charged to `mem`.  0, or -1 with *err (bvh_build's reasons); free with bvh_free. */
int lights_scene_bvh(bvh *b, const scene *sc, budget *mem, error *err);

/* Nearest quad light hit by r with t in (r->tmin, r->tmax): 1, its index (into sc->lights) and
 * t.  Quads are two-sided for visibility. */
int lights_intersect_quad(const lights *ls, const ray *r, int *k, double *t);
/* Radiance leaving quad k towards -d (d: the ray's direction): L on the emitting side. */
rgb lights_quad_radiance(const lights *ls, int k, vec3 d);
/* pdf per steradian of lights_sample(k) producing the point at distance t along unit wi from p. */
double lights_quad_pdf(const lights *ls, int k, vec3 wi, double t);

#endif
