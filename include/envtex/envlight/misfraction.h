/* misfraction.h - how often multiple importance sampling should sample the environment map
 * (lecture slide 23: MIS of the light and the BRDF): the fraction c of the map's picks that draw
 * a light sample (lights.h), chosen to minimize variance x time for a model surface under this
 * map (`envsamplefraction auto`).
 *
 *     envlight el;                                   // built with ENVSAMPLING_CDF (envlight.h)
 *     double v[MISFRACTION_COUNT];
 *     double c = misfraction_choose(&el, 0.6, v);    // one of the fractions; v[i] = V(c_i)
 *
 * The model: diffuse surfaces (albedo 1) facing 64 normals spread over the sphere, lit by the
 * map reduced to at most MISFRACTION_GRID_W x _H cells of mean radiance; per vertex one cosine
 * (BRDF) sample plus, with probability c, one cdf light sample, combined as 1 + c samples of the
 * mixture p_m = (p_brdf + c p_light) / (1 + c) (what the balance heuristic approaches):
 *     relative variance V(c) = (integral g^2 / p_m / I^2 - 1) / (1 + c),  g = L cos+ / pi,
 * averaged over the normals, and time per vertex 1 + light_cost c.
 */
#ifndef ENVTEX_MISFRACTION_H
#define ENVTEX_MISFRACTION_H

#include "envtex/envlight/envlight.h"

#define MISFRACTION_GRID_W 64
#define MISFRACTION_GRID_H 32
#define MISFRACTION_COUNT 8 /* the fractions tried: 0, 1/32, 1/16, 1/8, 1/4, 1/2, 3/4, 1 */

/* The fraction c that minimizes V(c) (1 + light_cost c) for el's map, a light sample costing
 * light_cost of a BRDF sample's ray and shading.  A constant map gives c = 0 (cosine sampling has
 * no variance there); a sun gives c = 1 (V grows like 1/c).  For the cdf modes (cdf-sintheta's
 * pdf is modelled as the cdf's); uniform, median cut and a black map return 1.  rel_var_out, if
 * given, receives V for each c (MISFRACTION_COUNT values; zeros where the model does not apply).
 * el must have been built by envlight_build (it needs the power).  Reads every texel once,
 * allocates nothing. */
double misfraction_choose(const envlight *el, double light_cost, double *rel_var_out);

#endif
