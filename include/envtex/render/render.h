/* render.h - from a scene to an image: builds what the scene needs (and nothing else), runs the
 * scene's integrator over every pixel, and reports what it built and what it cost.
 *
 *     render_opts o = render_defaults();
 *     o.seed = 7;
 *     image img; render_stats st;
 *     if (render_scene(sc, &o, &img, &st, &err)) ...
 *     ... image_free(&img);
 *
 * Deterministic: pixel (x, y) draws from random stream y * width + x of `seed`, so the image
 * depends only on the scene, spp and seed, and is bit-identical run to run on one build.
 * With spp = 1 the ray passes through the pixel centre; with spp > 1 each sample is jittered
 * uniformly within the pixel and the samples are averaged (a box filter).
 */
#ifndef ENVTEX_RENDER_H
#define ENVTEX_RENDER_H

#include <stdint.h>

#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/integrators/integrator.h"
#include "envtex/scene/scene.h"

typedef void (*render_progress_fn)(void *ctx, int rows_done, int rows);
typedef void (*render_start_fn)(void *ctx);

typedef struct render_opts {
    int spp;                   /* samples per pixel; 0: the scene's `spp` */
    uint64_t seed;             /* default 0 */
    render_progress_fn progress; /* called after each row (may be NULL) */
    void *progress_ctx;
    render_start_fn start;     /* called once, when every check that can refuse the render has
                                * passed and what it needs is built, before the first pixel (may
                                * be NULL).  A refused render never calls it: a caller prints the
                                * scene's warnings here, so a refused run prints its error alone */
    void *start_ctx;
    scene_warn_fn warn;        /* called for each warning of the render's own, before start (may
                                * be NULL: dropped).  One so far: an envmap that is black (no
                                * texel above 0) where the scene samples it by its values
                                * (`envsampling cdf`, `cdf-sintheta`, `mediancut`), which then
                                * falls back (envlight.h) */
    void *warn_ctx;
    budget *mem;               /* the run's memory budget (budget.h; NULL: none), charged before
                                * each structure is built: the displaced geometry, the BVH, the
                                * envmap's tables (the image and variance are not: SCENE_MAX_PIXELS
                                * bounds them) */
    image *variance;           /* if not NULL: receives the per-pixel variance of the mean,
                                * s^2 / spp with s^2 the unbiased sample variance of the pixel's
                                * samples (needs spp >= 2; allocated here, free with image_free) */
} render_opts;

typedef struct render_stats {
    double seconds;            /* wall-clock time of the pixel loop */
    double build_seconds;      /* time to build acceleration structures and tables */
    long long rays;            /* rays traced, shadow rays included */
    int spp;
    long nonfinite_pixels;     /* pixels with a NaN or Inf channel in the image as stored (float:
                                * a radiance above FLT_MAX is Inf there) (should be 0) */
    long nonfinite_variance;   /* the same, in opts->variance (0 without one) */
    /* what was built */
    long prims;
    int bvh_is_tree;
    int ray_differentials;     /* camera rays carried differentials (a map needs a footprint) */
    long bvh_nodes;
    int bvh_depth;
    int envlight_built;        /* environment sampling tables were built */
    int envlight_sampled;      /* the integrator samples the envmap as a light */
    int envlight_mode;         /* envsampling_mode used (cdf and cdf-sintheta become uniform on a
                                  black map; median cut keeps its mode, with equal strata) */
    double envlight_seconds;   /* time to build them */
    long envlight_bad_texels;  /* NaN / Inf / negative texel channels, treated as 0 */
    int envlight_fell_back;    /* the map was black: sampling fell back to uniform */
    int envlight_points;       /* median cut: point lights made */
    int envlight_w, envlight_h; /* the lat-long map sampled (resampled for other kinds) */
    double envlight_kappa;     /* E[L^2] / E[L]^2 of the map (envlight.h) */
    double env_fraction;       /* the envmap's sampling fraction under MIS (lights.h), else 1 */
    nee_mode nee;              /* the path tracer's next-event estimation as run (integrator.h) */
    int lights;                /* lights the sampling integrators choose among */
    long displaced_spheres, displaced_triangles; /* objects tessellated for displacement maps */
    long displaced_result;     /* triangles they became (with the untouched ones) */
    int displace_sphere_rate, displace_triangle_rate;
} render_stats;

render_opts render_defaults(void);

/* Render `sc` into *out (allocated here, width x height; free with image_free).  opts may be
 * NULL (render_defaults()); stats may not.  Returns 0, or -1 with *err set, naming the scene file:
 * spp out of [1, SCENE_MAX_SPP] or over SCENE_MAX_CAMERA_SAMPLES, a variance asked for at spp 1,
 * a displacement budget, BVH or envmap table that cannot be built or is beyond the memory
 * budget, out of memory.  On failure
 * *out (and opts->variance) hold nothing to free and opts->start was not called. */
int render_scene(const scene *sc, const render_opts *opts, image *out, render_stats *stats, error *err);

/* Radiance along a camera ray by the scene's integrator (`integrator raytracer|analyticdirect|
 * direct|pathtracer`), in the context `it` built for it (integrator.h). */
rgb render_radiance(integrator *it, ray r, rng *g);

/* The same with the camera ray's differentials (raydiff.h; NULL: none), which texture
 * filtering uses and perfect mirror / glass bounces carry on (docs/texture-mapping.md). */
rgb render_radiance_diff(integrator *it, ray r, const ray_diff *rd, rng *g);

#endif
