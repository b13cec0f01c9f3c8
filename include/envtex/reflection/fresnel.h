/* fresnel.h - reflection and refraction at a smooth dielectric (slide 5 (Using Environment for
 * Reflection Map): mirror reflection "and refraction" to an environment map).
 *
 *     double F = fresnel_dielectric(cos_i, eta);   // fraction reflected
 *     vec3 t; if (fresnel_refract(d, n, eta, &t)) ... else total internal reflection
 *
 * eta = n_t / n_i: the index on the far side over the index on the ray's side.
 */
#ifndef ENVTEX_FRESNEL_H
#define ENVTEX_FRESNEL_H

#include "envtex/core/vec.h"

/* Exact unpolarized reflectance, cos_i in [0, 1] measured on the incident side: 1 under total
 * internal reflection, else F = (r_s^2 + r_p^2) / 2. */
double fresnel_dielectric(double cos_i, double eta);

/* Refract unit d at unit n (incident side, d.n < 0), sin_t = sin_i / eta: 1 and the unit
 * refracted direction in *t, or 0 under total internal reflection. */
int fresnel_refract(vec3 d, vec3 n, double eta, vec3 *t);

#endif
