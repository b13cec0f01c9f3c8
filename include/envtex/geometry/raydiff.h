/* raydiff.h - ray differentials (Igehy 1999; pbrt 10.1): how far the hit point moves from one
 * pixel to the next, the footprint a texture filter needs (slides 26-46 (Texture Mapping)).
 *
 *     if (raydiff_at_hit(&r, &rd, p, ng, &dpdx, &dpdy)) ...  // rd: camera_ray_differential
 *
 * Per pixel step, world space; ddx is the change of the unit direction.  n is unit, on wo's
 * side (wo unit, towards the ray's origin); dndx, dndy its change.  Pure, allocation free.
 */
#ifndef ENVTEX_RAYDIFF_H
#define ENVTEX_RAYDIFF_H

#include "envtex/geometry/ray.h"

/* |cos| below which an offset ray grazes the plane: no differential. */
#define RAYDIFF_MIN_COS 1e-12

/* dp/dx = (o + dox) + t_x (d + ddx) - p on the tangent plane at p (ng any length > 0), and
 * dp/dy.  1, or 0 with both zero if rd is NULL or has none, a ray grazes, or not finite. */
int raydiff_at_hit(const ray *r, const ray_diff *rd, vec3 p, vec3 ng, vec3 *dpdx, vec3 *dpdy);

/* Of the mirror wi = -wo + 2 (wo . n) n: do = dp, dwo = -dd,
 * dwi = -dwo + 2 ((wo . n) dn + (dwo . n + wo . dn) n).  in->has = 0 gives out->has = 0. */
void raydiff_reflect(const ray_diff *in, vec3 dpdx, vec3 dpdy, vec3 wo, vec3 n, vec3 dndx,
                     vec3 dndy, ray_diff *out);

/* Of the refracted unit wi = -eta wo + mu n, eta = n_i / n_t (fresnel.h's INVERSE),
 * mu = eta cos_i - cos_t: dwi = -eta dwo + mu dn + dmu n, dmu = (eta - eta^2 cos_i / cos_t)
 * d(wo . n).  1, or 0 with out->has = 0 if cos_t <= RAYDIFF_MIN_COS or in->has = 0. */
int raydiff_refract(const ray_diff *in, vec3 dpdx, vec3 dpdy, vec3 wo, vec3 n, vec3 dndx, vec3 dndy,
                    double eta, vec3 wi, ray_diff *out);

#endif
