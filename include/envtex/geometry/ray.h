/* ray.h - rays and ray-surface hits, shared by the geometry and the integrators.
 *
 * A ray is o + t d for t in (tmin, tmax); d need not be unit length, and t is in units of |d|.
 * A hit records where and what was hit, in world space.
 *
 * Ray differentials (Igehy 1999; pbrt's RayDifferential) travel BESIDE a ray, as a ray_diff:
 * how its origin and direction change from one pixel to the next, so that the rays of the
 * neighbouring pixels are (o + dox, d + ddx) and (o + doy, d + ddy).  has = 0 means "no
 * footprint known" (after a diffuse or glossy bounce, shadow rays, scenes without texture
 * maps).  camera_ray_differential makes them, raydiff.h carries them to hits and through
 * perfect mirrors and refraction; texture filtering turns them into a footprint.
 */
#ifndef ENVTEX_RAY_H
#define ENVTEX_RAY_H

#include "envtex/core/vec.h"

typedef struct ray {
    vec3 o, d;
    double tmin, tmax;
} ray;

typedef struct ray_diff {
    int has;             /* 1: the four vectors are valid; 0: no differentials */
    vec3 dox, ddx;       /* change of o and of the UNIT direction d per pixel step in x */
    vec3 doy, ddy;       /* ... per pixel step in y (one row down) */
} ray_diff;

typedef struct hit {
    double t;       /* ray parameter of the hit */
    vec3 p;         /* world position */
    vec3 ng;        /* unit geometric normal, facing outward (not flipped towards the ray) */
    vec3 ns;        /* unit shading normal (interpolated for trinormal), same side as ng */
    uv2 bary;       /* triangle barycentrics (b1, b2) of corners 1, 2; sphere: (0, 0) */
    long prim;      /* index of the primitive in its scene array */
    int is_sphere;  /* 1 sphere, 0 triangle */
    int material;   /* index into scene.materials */
} hit;

/* Offset for rays leaving a surface (avoids "acne", self-intersection): the origin moves along
 * the geometric normal by RAY_OFFSET_REL times the hit point's largest coordinate (plus an
 * absolute floor for points near the origin).  Double precision intersection errors are about
 * 1e-15 relative, so 1e-9 leaves six orders of margin yet is invisible at any scene scale. */
#define RAY_OFFSET_REL 1e-9
#define RAY_OFFSET_ABS 1e-9

/* p moved off the surface with normal ng towards the side of direction d. */
static inline vec3 ray_offset(vec3 p, vec3 ng, vec3 d)
{
    double eps = RAY_OFFSET_ABS + RAY_OFFSET_REL * vec3_max_abs(p);
    return vec3_madd(p, ng, vec3_dot(d, ng) >= 0 ? eps : -eps);
}

/* A ray leaving hit point p (normal ng) in direction d. */
static inline ray ray_spawn(vec3 p, vec3 ng, vec3 d)
{
    return (ray){ray_offset(p, ng, d), d, 0.0, INFINITY};
}

/* A shadow ray from p towards target point q: stops RAY_SHADOW_SHORT (relative) short of q. */
#define RAY_SHADOW_SHORT 1e-7
static inline ray ray_spawn_to(vec3 p, vec3 ng, vec3 q)
{
    vec3 o = ray_offset(p, ng, vec3_sub(q, p));
    return (ray){o, vec3_sub(q, o), 0.0, 1.0 - RAY_SHADOW_SHORT};
}

#endif
