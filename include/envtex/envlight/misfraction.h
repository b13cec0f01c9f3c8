/* misfraction.h - how often MIS (slide 22 (Sampling General 2D Distributions)) light-samples the
 * envmap (`envsamplefraction auto`): diffuse surfaces facing 64 normals, 1 + c samples of p_m =
 * (p_brdf + c p_light) / (1 + c):
 *     V(c) = (integral g^2 / p_m / I^2 - 1) / (1 + c),  g = L cos+ / pi,  time 1 + light_cost c
 *
 *     double v[MISFRACTION_COUNT], c = misfraction_choose(&el, 0.6, v);
 */
#ifndef ENVTEX_MISFRACTION_H
#define ENVTEX_MISFRACTION_H

#include "envtex/envlight/envlight.h"

#define MISFRACTION_GRID_W 64
#define MISFRACTION_GRID_H 32
#define MISFRACTION_COUNT  8 /* c: 0, 1/32, 1/16, 1/8, 1/4, 1/2, 3/4, 1 */

/* The c minimizing V(c) (1 + light_cost c) for a cdf-mode light from envlight_build, else 1;
 * rel_var_out (NULL or MISFRACTION_COUNT) gets each V.  Allocates nothing. */
double misfraction_choose(const envlight *el, double light_cost, double *rel_var_out);

#endif
