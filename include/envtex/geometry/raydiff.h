/* raydiff.h - ray differentials (Igehy 1999, "Tracing Ray Differentials"; pbrt section 10.1):
 * how much the hit point moves from one pixel to the next, so that a texture lookup knows the
 * footprint it must average over.  Lecture "Environment, Texture Maps", slides 25-46: "naive
 * texture mapping aliases badly" - a pixel that covers many texels must average them
 * (mip-mapping), and it needs its footprint to know how many.
 *
 *     ray_diff rd;
 *     ray r = camera_ray_differential(&cam, x + 0.5, y + 0.5, 1.0, &rd);   // camera.h
 *     ... hit at p with geometric normal ng ...
 *     vec3 dpdx, dpdy;
 *     if (raydiff_at_hit(&r, &rd, p, ng, &dpdx, &dpdy)) ... footprint dpdx, dpdy ...
 *     ray_diff out;   // through a perfect mirror at p (shading normal n, its change dndx, dndy)
 *     raydiff_reflect(&rd, dpdx, dpdy, wo, n, dndx, dndy, &out);
 *
 * Conventions.  Differentials are per pixel step: the neighbouring pixel's ray is
 * (o + dox, d + ddx).  Directions are UNIT vectors and ddx is the change of the unit direction.
 * All vectors are world space.  Normals n are on the side of wo (the direction back towards
 * the ray's origin), and dndx, dndy are the change of that same (unit) normal per pixel step.
 *
 * Where differentials stop.  After a diffuse or glossy bounce the outgoing direction is random,
 * not a smooth function of the pixel: there is no differential to carry, and the integrators
 * continue with rd.has = 0.  Texture filters then use their documented fallback (texture.h:
 * the full-resolution image read bilinearly, procedural textures point sampled): the sharpest
 * answer, never a blur.  Any aliasing it causes is averaged away by the path tracer's many
 * samples per pixel, which is also why pbrt does the same.
 *
 * Everything here is pure and allocation free.
 */
#ifndef ENVTEX_RAYDIFF_H
#define ENVTEX_RAYDIFF_H

#include "envtex/geometry/ray.h"

/* |n . (d + dd)| below this (the offset ray runs along the tangent plane, grazing) gives no
 * hit differential: the footprint would be unbounded.  1e-12 is far below any angle a pixel
 * can resolve, yet keeps 1 / x finite. */
#define RAYDIFF_MIN_COS 1e-12

/* The change of the hit point per pixel step: the offset rays (o + dox, d + ddx) and
 * (o + doy, d + ddy) intersected with the tangent plane at p (normal ng, any length > 0):
 *     t_x = n . (p - (o + dox)) / n . (d + ddx),    dp/dx = (o + dox) + t_x (d + ddx) - p
 * (pbrt's "intersect the offset rays with the tangent plane").  Returns 1, or 0 with both
 * outputs zero when rd is NULL or has no differentials, or an offset ray is parallel to the
 * plane (|n.(d + dd)| <= RAYDIFF_MIN_COS |n| |d + dd|), or a result is not finite. */
int raydiff_at_hit(const ray *r, const ray_diff *rd, vec3 p, vec3 ng, vec3 *dpdx, vec3 *dpdy);

/* Differentials of the mirror direction wi = -wo + 2 (wo . n) n leaving a hit:
 *     dwo = -dd (of the incoming ray),  d(wo . n) = dwo . n + wo . dn,
 *     dwi = -dwo + 2 ((wo . n) dn + d(wo . n) n),       do = dp
 * in = the incoming ray's differentials (in->has = 0 gives out->has = 0), dpdx, dpdy from
 * raydiff_at_hit, wo unit (towards the incoming ray's origin), n unit on wo's side. */
void raydiff_reflect(const ray_diff *in, vec3 dpdx, vec3 dpdy, vec3 wo, vec3 n, vec3 dndx,
                     vec3 dndy, ray_diff *out);

/* Differentials of the refracted direction wi = -eta wo + mu n (Snell), with eta = n_i / n_t
 * (the index on wo's side over the far side's: the INVERSE of fresnel.h's eta),
 * cos_i = wo . n, cos_t = |wi . n|, mu = eta cos_i - cos_t:
 *     dwi = -eta dwo + mu dn + dmu n,   dmu = (eta - eta^2 cos_i / cos_t) d(wo . n),   do = dp
 * wi is the refracted unit direction (fresnel_refract).  Returns 1, or 0 with out->has = 0 at
 * grazing transmission (cos_t <= RAYDIFF_MIN_COS) or without incoming differentials. */
int raydiff_refract(const ray_diff *in, vec3 dpdx, vec3 dpdy, vec3 wo, vec3 n, vec3 dndx,
                    vec3 dndy, double eta, vec3 wi, ray_diff *out);

#endif
