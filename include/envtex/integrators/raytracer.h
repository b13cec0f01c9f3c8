/* raytracer.h - `integrator raytracer`: the CSE 167 Whitted ray tracer with the lecture's
 * reflection map (slides 3-5): "Color += reflectivity * Color of reflected ray; directly use
 * envmap if miss geometry, otherwise recurse".
 *
 * At a hit with material (ambient A, emission E, diffuse kd, specular ks, shininess s):
 *   I = A + E + sum over point/directional lights of  V L / atten (kd max(N.L,0) + ks max(N.H,0)^s)
 *         + ks I(reflected ray)                          (brdf phong / ggx, up to maxdepth)
 * with each term clamped on its own, as the course writes it: a light below the horizon
 * (N.L < 0) still adds ks max(N.H,0)^s unless its shadow ray is blocked (a closed object blocks
 * it; an open floor lit from just below its plane shows the highlight, as in the course).
 * `brdf mirror` drops the highlight term (a perfect mirror shows a point light as a point of
 * zero size) and keeps ks I(reflected).  `brdf glass` replaces the specular part by
 *   F I(reflected) + (1 - F) I(refracted)  with exact Fresnel F and total internal reflection.
 * A ray that misses everything sees the envmap: camera rays always (the background), reflected
 * and refracted rays unless `envmiss black`.  Quad lights are for the sampling integrators and
 * are not seen by this one.  maxdepth -1 ("unlimited") stops at RAYTRACER_UNLIMITED_DEPTH.
 *
 *     raytracer rt; raytracer_init(&rt, sc, &accel);
 *     rgb c = raytracer_trace(&rt, camera_ray(&cam, x, y));
 */
#ifndef ENVTEX_RAYTRACER_H
#define ENVTEX_RAYTRACER_H

#include "envtex/geometry/bvh.h"
#include "envtex/reflection/envmap.h"
#include "envtex/scene/scene.h"

#define RAYTRACER_UNLIMITED_DEPTH 64
/* A branch whose weight (product of reflectances) falls below this contributes less than 1e-3
 * even under a sun of radiance 1e6, so it is not traced (Hall & Greenberg's adaptive depth). */
#define RAYTRACER_MIN_WEIGHT 1e-9

/* Local shading in place of the Whitted terms A + E + lights at a hit whose normal-facing
 * surface is s (brdf.h), seen from direction view: returns that radiance, and sets *reflect to
 * 0 when a non-glass surface's ks is no mirror to recurse into.  `integrator prefiltered` sets
 * it (prefiltered.h); mirror and glass bounces stay the ray tracer's. */
struct surface;
typedef rgb (*raytracer_shade_fn)(void *ctx, const material *m, const struct surface *s, vec3 view,
                                  int *reflect);

typedef struct raytracer {
    const scene *sc;
    const bvh *accel;
    envmap env;
    int maxdepth;        /* resolved: -1 becomes RAYTRACER_UNLIMITED_DEPTH */
    long long rays;      /* rays traced, shadow rays included */
    raytracer_shade_fn shade; /* NULL (raytracer_init): the Whitted terms */
    void *shade_ctx;
} raytracer;

void raytracer_init(raytracer *rt, const scene *sc, const bvh *accel);

/* Radiance along a camera ray (depth 0). */
rgb raytracer_trace(raytracer *rt, ray r);

/* The same with the camera ray's differentials (raydiff.h; NULL or has = 0: none): texture
 * maps are filtered over the footprint, and mirror reflection and refraction carry it on. */
rgb raytracer_trace_diff(raytracer *rt, ray r, const ray_diff *rd);

#endif
