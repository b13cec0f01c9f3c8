/* raytracer.h - `integrator raytracer`: the CSE 167 Whitted ray tracer with the reflection map
 * (slide 5 (Using Environment for Reflection Map)): "Color += reflectivity * Color of reflected
 * ray; directly use envmap if miss geometry, otherwise recurse".
 *
 *     raytracer rt; raytracer_init(&rt, sc, &accel);
 *     rgb c = raytracer_trace(&rt, camera_ray(&cam, x, y));
 *
 * At a hit: I = A + E + sum over point / directional lights of V L / atten (kd max(N.L, 0) +
 * ks max(N.H, 0)^s) + ks I(reflected), each term clamped on its own as the course does; mirror:
 * no highlight; glass: F I(reflected) + (1 - F) I(refracted), exact Fresnel.  A miss sees the
 * envmap (bounced rays unless `envmiss black`); quad lights are not seen.  docs/design-notes.md.
 */
#ifndef ENVTEX_RAYTRACER_H
#define ENVTEX_RAYTRACER_H

#include "envtex/geometry/bvh.h"
#include "envtex/reflection/envmap.h"
#include "envtex/scene/scene.h"

#define RAYTRACER_UNLIMITED_DEPTH 64
/* A branch weighing less than this is not traced (adaptive depth: < 1e-3 under a 1e6 sun) */
#define RAYTRACER_MIN_WEIGHT 1e-9

/* Local shading in place of A + E + lights at surface s seen from view; *reflect = 0: no ks
 * bounce (not for glass).  Set by `integrator prefiltered`. */
struct surface;
typedef rgb (*raytracer_shade_fn)(void *ctx, const material *m, const struct surface *s, vec3 view,
                                  int *reflect);

typedef struct raytracer {
    const scene *sc;
    const bvh *accel;
    envmap env;
    int maxdepth;             /* resolved: -1 becomes RAYTRACER_UNLIMITED_DEPTH */
    long long rays;           /* rays traced, shadow rays included */
    raytracer_shade_fn shade; /* NULL (raytracer_init): the Whitted terms */
    void *shade_ctx;
} raytracer;

void raytracer_init(raytracer *rt, const scene *sc, const bvh *accel);

/* Radiance along a camera ray (depth 0). */
rgb raytracer_trace(raytracer *rt, ray r);

/* The same from the camera ray's closest hit, found already: got (BVH_MISS or BVH_SURFACE: the
 * ray tracer's BVH holds no quad lights) and *h as bvh_intersect returns and fills them, with
 * the ray's differentials rd (NULL or has = 0: none), carried by mirrors and glass. */
rgb raytracer_trace_hit(raytracer *rt, ray r, const ray_diff *rd, int got, const hit *h);

#endif
