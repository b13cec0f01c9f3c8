/* ray.h - rays and ray-surface hits, shared by the geometry and the integrators.
 *
 * A ray is o + t d, t in (tmin, tmax), t in units of |d|; hits are in world space.  A ray_diff
 * travels beside a ray: the neighbouring pixels' rays are (o + dox, d + ddx) and
 * (o + doy, d + ddy) (camera.h makes them, raydiff.h carries them).
 */
#ifndef ENVTEX_RAY_H
#define ENVTEX_RAY_H

#include "envtex/core/vec.h"

typedef struct ray {
    vec3 o, d;
    double tmin, tmax;
} ray;

typedef struct ray_diff {
    int has;       /* 1: valid; 0: none (after a diffuse bounce, shadow rays) */
    vec3 dox, ddx; /* change of o and of the UNIT d per pixel step in x */
    vec3 doy, ddy; /* ... in y (one row down) */
} ray_diff;

typedef struct hit {
    double t;      /* ray parameter of the hit */
    vec3 p;        /* world position */
    vec3 ng;       /* unit geometric normal, facing outward (not flipped towards the ray) */
    vec3 ns;       /* unit shading normal, same side as ng */
    uv2 bary;      /* triangle barycentrics (b1, b2) of corners 1, 2; sphere: (0, 0) */
    long prim;     /* index of the primitive in its scene array */
    int is_sphere; /* 1 sphere, 0 triangle */
    int material;  /* index into scene.materials */
} hit;

/* A leaving ray's origin moves along ng by ABS + REL max |p_i| (no "acne").  A hit point is
 * off its surface by at most sqrt(3) gamma(7) ~ 1.4e-15 times its triangle's largest corner
 * coordinate (pbrt-v4's bound for the barycentric point; a sphere's point, moved onto the
 * sphere, by less): REL = 2^-40 ~ 9.1e-13 is 670 times that, and ABS covers a triangle up to
 * 7e5 + 670 max |p_i| long.  Invisible at any scale: 1e-5 at 1e7, where 1e-9 gave 1e-2. */
#define RAY_OFFSET_REL 0x1p-40
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

/* A shadow ray from p to q, stopping RAY_SHADOW_SHORT (relative) short of q. */
#define RAY_SHADOW_SHORT 1e-7
static inline ray ray_spawn_to(vec3 p, vec3 ng, vec3 q)
{
    vec3 o = ray_offset(p, ng, vec3_sub(q, p));
    return (ray){o, vec3_sub(q, o), 0.0, 1.0 - RAY_SHADOW_SHORT};
}

#endif
