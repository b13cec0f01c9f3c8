/* direct.h - direct lighting by light sampling: `integrator direct` (CSE 168 hw2) and the path
 * tracer's next-event estimation (hw3-hw4).  At the first non-delta hit:
 *   L = Le + sum over lights of (1/N) sum_j f(wo, wi_j) cos(theta_j) Li(wi_j) V / pdf(wi_j)
 * with N = `lightsamples` samples of each quad light and of the environment (sampled as
 * `envsampling` says; `lightstratify on`: each light's own sqrt(N) x sqrt(N) grid), N = 1 for a
 * point or directional light (a delta: more samples would all be the same).  That is the course's
 * `lightselection all`, the default; `lightselection power` (envtex's, for scenes of many lights)
 * takes N samples in all, each of one light picked by power and divided by that probability
 * (lights.h).  Perfect mirror and glass surfaces are followed (up to maxdepth bounces) to the
 * first surface that can be lit.
 */
#ifndef ENVTEX_DIRECT_H
#define ENVTEX_DIRECT_H

#include "envtex/integrators/integrator.h"

rgb direct_radiance(integrator *it, ray r, rng *g);
/* ... with the camera ray's differentials rd (NULL: none), carried through mirrors and glass. */
rgb direct_radiance_diff(integrator *it, ray r, const ray_diff *rd, rng *g);

/* Estimate of the direct light s reflects towards wo: the sum above without Le, by the scene's
 * `lightselection` (0 at a mirror or glass, or without lights).  Each light sample draws four
 * numbers from g: the selection's, then (xi1, xi2, xi3) of lights_sample. */
rgb direct_lighting(integrator *it, const surface *s, vec3 wo, rng *g);

/* The same with each light sample weighted by the power heuristic against one BRDF sample of the
 * scene's `importancesampling` (the path tracer's `nexteventestimation mis`, pathtracer.h). */
rgb direct_lighting_mis(integrator *it, const surface *s, vec3 wo, rng *g);

#endif
