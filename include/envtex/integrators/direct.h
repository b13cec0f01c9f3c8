/* direct.h - direct lighting by light sampling: `integrator direct` (CSE 168 hw2) and the path
 * tracer's next-event estimation.  At the first non-delta hit (mirrors and glass are followed):
 *   L = Le + sum over lights of (1/N) sum_j f(wo, wi_j) cos(theta_j) Li(wi_j) V / pdf(wi_j)
 * N = `lightsamples` (`lightstratify on`: on a grid), 1 for a point or directional light;
 * `lightselection power`: N samples in all, lights picked by power (lights.h).
 */
#ifndef ENVTEX_DIRECT_H
#define ENVTEX_DIRECT_H

#include "envtex/integrators/integrator.h"

/* Radiance along camera ray r from its first hit sh (integrator_intersect_diff's), the
 * differentials rd (NULL: none) carried by mirrors and glass.  render_radiance calls it. */
rgb direct_radiance_hit(integrator *it, ray r, const ray_diff *rd, const scene_hit *sh, rng *g);

/* The sum above without Le (0 at a mirror or glass, or without lights); each sample draws
 * four numbers from g: the selection's, then lights_sample's xi1, xi2, xi3. */
rgb direct_lighting(integrator *it, const surface *s, vec3 wo, rng *g);

/* The same, each sample weighted by the power heuristic against the scene's BRDF sampling. */
rgb direct_lighting_mis(integrator *it, const surface *s, vec3 wo, rng *g);

#endif
