/* fresnel.h - reflection and refraction at a smooth dielectric (lecture slide 3-5: mirror
 * reflection "and refraction" to an environment map).
 *
 *     double F = fresnel_dielectric(cos_i, eta);   // fraction reflected
 *     vec3 t; if (fresnel_refract(d, n, eta, &t)) ... else total internal reflection
 *
 * eta = n_t / n_i: the index on the far side over the index on the ray's side.
 */
#ifndef ENVTEX_FRESNEL_H
#define ENVTEX_FRESNEL_H

#include "envtex/core/vec.h"

/* Exact unpolarized Fresnel reflectance for cos_i = cos of the angle between the incident ray
 * (reversed) and the normal on the incident side, in [0, 1].  Returns 1 under total internal
 * reflection.  F = (r_s^2 + r_p^2) / 2 with
 * r_s = (cos_i - eta cos_t) / (cos_i + eta cos_t), r_p = (eta cos_i - cos_t) / (eta cos_i + cos_t). */
double fresnel_dielectric(double cos_i, double eta);

/* Refract unit direction d at unit normal n (n on the incident side: d.n < 0) with
 * eta = n_t / n_i (Snell: sin_t = sin_i / eta).  Returns 1 and the unit refracted direction in
 * *t, or 0 under total internal reflection. */
int fresnel_refract(vec3 d, vec3 n, double eta, vec3 *t);

#endif
