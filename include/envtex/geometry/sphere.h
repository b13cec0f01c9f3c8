/* sphere.h - ray-sphere intersection under any affine transform (an ellipsoid when scaled):
 * the ray in object space, the hit and its normal (inverse transpose) back; world in and out.
 *
 *     if (sphere_intersect(&sc->spheres[i], &r, &t)) sphere_hit(&sc->spheres[i], &r, t, &h);
 */
#ifndef ENVTEX_SPHERE_H
#define ENVTEX_SPHERE_H

#include "envtex/geometry/ray.h"
#include "envtex/core/transform.h"

/* `sphere x y z r` under the current transform. */
typedef struct sphere {
    vec3 center; /* object space, as written */
    double radius;
    mat4 xf, inv;      /* object -> world and its inverse */
    int untransformed; /* 1: xf = inv = the identity, skipped; 0 (always correct): use them */
    int material;      /* index into scene.materials */
} sphere;

/* Nearest world-ray t in (r->tmin, r->tmax) on the transformed sphere: 1 and *t, or 0. */
int sphere_intersect(const sphere *s, const ray *r, double *t);

/* h->p and h->ng = h->ns (unit, outward, world) of the hit at t; h->bary = (0, 0) (texture
 * coordinates come from the object-space point: texshade.h).  The point is o + t d moved onto
 * the sphere along its radius, so it is a few ulps off the surface however far the ray came. */
void sphere_hit(const sphere *s, const ray *r, double t, hit *h);

/* World axis-aligned bounds: the transformed corners of the object box. */
void sphere_bounds(const sphere *s, vec3 *lo, vec3 *hi);

#endif
