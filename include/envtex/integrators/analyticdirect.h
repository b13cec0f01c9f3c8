/* analyticdirect.h - `integrator analyticdirect` (CSE 168 hw2): quad lights' exact, unshadowed
 * light on diffuse surfaces by the irradiance vector (Arvo):
 *   Phi(p) = 1/2 sum_i theta_i Gamma_i,   L = Le + kd / pi L_light (Phi(p) . n)
 * theta_i the angle between v_i - p and v_{i+1} - p, Gamma_i the unit normal of their plane.
 *
 *     double E = analyticdirect_irradiance(&sc->lights[k], p, n);  // Phi . n, clipped
 */
#ifndef ENVTEX_ANALYTICDIRECT_H
#define ENVTEX_ANALYTICDIRECT_H

#include "envtex/integrators/integrator.h"

/* Radiance along camera ray r from its first hit sh (integrator_intersect_diff's; its
 * differentials rd, NULL: none, filtered the hit's textures).  render_radiance calls it. */
rgb analyticdirect_radiance_hit(integrator *it, ray r, const ray_diff *rd, const scene_hit *sh,
                                rng *g);

/* Phi(p) of quad light l's whole parallelogram (unclipped: below p's horizon counts < 0). */
vec3 analyticdirect_irradiance_vector(const scene_light *l, vec3 p);

/* Irradiance per unit radiance in [0, pi] at p, unit normal n: Phi . n of light l clipped to
 * (v - p) . n >= 0; 0 behind the light (the side ac x ab does not point to). */
double analyticdirect_irradiance(const scene_light *l, vec3 p, vec3 n);

#endif
