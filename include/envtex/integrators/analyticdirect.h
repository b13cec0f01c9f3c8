/* analyticdirect.h - `integrator analyticdirect` (CSE 168 hw2): the exact, unshadowed direct
 * light of quad lights on diffuse surfaces, from the irradiance of a polygon (Lambert; Arvo):
 *   Phi(p) = 1/2 sum_i theta_i Gamma_i,  theta_i = angle between (v_i - p) and (v_{i+1} - p),
 *   Gamma_i = unit normal of the plane through p, v_i, v_{i+1}
 *   L = Le + kd / pi * L_light * (Phi(p) . n)        (no visibility, as in the course)
 * Phi . n is the integral of n . w over the polygon's solid angle, so it equals the irradiance
 * (the integral of max(n . w, 0)) only for the part of the light above p's horizon: the light
 * is first clipped to the half-space (v - p) . n >= 0.  A point on the back side of the light
 * (the side ac x ab does not point to) receives nothing from it.
 *
 *     const scene_light *l = &sc->lights[k];              // a LIGHT_QUAD
 *     double E = analyticdirect_irradiance(l, p, n);      // per unit radiance, unit n
 *     rgb Lo = rgb_scale(rgb_mul(kd, l->color), E / M_PI); // kd / pi L (Phi . n)
 */
#ifndef ENVTEX_ANALYTICDIRECT_H
#define ENVTEX_ANALYTICDIRECT_H

#include "envtex/integrators/integrator.h"

rgb analyticdirect_radiance(integrator *it, ray r, rng *g);
/* ... with the camera ray's differentials rd (NULL: none): the footprint that filters the hit's
 * texture maps (texshade.h), as in the other integrators. */
rgb analyticdirect_radiance_diff(integrator *it, ray r, const ray_diff *rd, rng *g);

/* The irradiance vector Phi(p) of the whole parallelogram of quad light l, for p in front of it
 * (unclipped: Phi . n counts the part below p's horizon negatively). */
vec3 analyticdirect_irradiance_vector(const scene_light *l, vec3 p);

/* The irradiance at p, normal n (unit), per unit radiance of quad light l: the integral of
 * max(n . w, 0) over the light's solid angle, i.e. Phi . n of the light clipped to p's upper
 * half-space; 0 if p is not on the emitting side.  In [0, pi]. */
double analyticdirect_irradiance(const scene_light *l, vec3 p, vec3 n);

#endif
