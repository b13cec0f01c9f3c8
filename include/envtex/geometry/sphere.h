/* sphere.h - ray-sphere intersection under any affine transform (a scaled sphere is an
 * ellipsoid), as the CSE 167 raytracer assignment does it: intersect the ray transformed into
 * object space, then bring the hit and its normal back (normal by the inverse transpose).
 *
 *     double t;
 *     if (sphere_intersect(&sc->spheres[i], &r, &t)) sphere_hit(&sc->spheres[i], &r, t, &h);
 */
#ifndef ENVTEX_SPHERE_H
#define ENVTEX_SPHERE_H

#include "envtex/geometry/ray.h"
#include "envtex/core/transform.h"

/* A sphere of the scene (`sphere x y z r` under the current transform: an ellipsoid when the
 * transform scales unevenly). */
typedef struct sphere {
    vec3 center;    /* object space, as written */
    double radius;
    mat4 xf, inv;   /* object -> world and its inverse (transform current at `sphere`) */
    int untransformed; /* 1: xf = inv = the identity (no transform at `sphere`, as most are),
                        * so a ray needs no transform into object space; 0: use xf and inv
                        * (always correct: a sphere built by hand may leave it 0) */
    int material;   /* index into scene.materials */
} sphere;

/* Nearest t in (r->tmin, r->tmax) where the ray meets the (transformed) sphere: 1 and *t, or 0.
 * t is the world ray's parameter (the object-space ray keeps it, since the map is affine).
 * A sphere read without a transform (s->untransformed) skips the two matrix products, with
 * the same t: the identity's products are exact (sphere_hit skips its three too).  One
 * exception: an origin with a -0 coordinate (the products make it +0) where o.d is exactly 0
 * picks the other of the two root formulas, and t can differ in its last bit. */
int sphere_intersect(const sphere *s, const ray *r, double *t);

/* Fill h->p and h->ng = h->ns (unit, outward, world space) for the hit at parameter t;
 * h->bary = (0, 0): a sphere has no barycentrics, and its texture coordinates come from the
 * object-space point through its texture mapping (texshade.h), which is paid for only where
 * a surface is shaded with a texture. */
void sphere_hit(const sphere *s, const ray *r, double t, hit *h);

/* World-space axis-aligned bounds of the transformed sphere (corners of the object box). */
void sphere_bounds(const sphere *s, vec3 *lo, vec3 *hi);

#endif
