/* analyticdirect.h - `integrator analyticdirect` (CSE 168 hw2): the exact, unshadowed direct
 * light of quad lights on diffuse surfaces, from the irradiance of a polygon (Lambert; Arvo):
 *   Phi(p) = 1/2 sum_i theta_i Gamma_i,  theta_i = angle between (v_i - p) and (v_{i+1} - p),
 *   Gamma_i = unit normal of the plane through p, v_i, v_{i+1}
 *   L = Le + kd / pi * L_light * (Phi(p) . n)        (no visibility, as in the course)
 */
#ifndef ENVTEX_ANALYTICDIRECT_H
#define ENVTEX_ANALYTICDIRECT_H

#include "envtex/integrator.h"

rgb analyticdirect_radiance(integrator *it, ray r, rng *g);

/* The irradiance vector Phi(p) of the parallelogram of quad light l, for p in front of it. */
vec3 analyticdirect_irradiance_vector(const scene_light *l, vec3 p);

#endif
