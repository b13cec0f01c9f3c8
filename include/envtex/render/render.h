/* render.h - from a scene to an image: build what the scene needs (nothing else), run its
 * integrator over every pixel, report what was built and what it cost.
 *
 *     if (render_scene(sc, &opts, &img, &stats, &err)) ...   // opts = render_defaults()
 *
 * Deterministic: pixel (x, y) draws from stream y * width + x of `seed`.  spp = 1: the pixel
 * centre; more: jittered in the pixel and averaged (a box filter).
 */
#ifndef ENVTEX_RENDER_H
#define ENVTEX_RENDER_H

#include <stdint.h>

#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/integrators/integrator.h"
#include "envtex/scene/scene.h"

/* The pixels go a tile of RENDER_TILE x RENDER_TILE at a time, their camera rays one packet
 * (bvh_packet.h); progress is reported when a row of tiles is done. */
#define RENDER_TILE 8

typedef void (*render_progress_fn)(void *ctx, int rows_done, int rows);
typedef void (*render_start_fn)(void *ctx);

typedef struct render_opts {
    int spp;                     /* samples per pixel; 0: the scene's `spp` */
    uint64_t seed;               /* default 0 */
    render_progress_fn progress; /* called for each row, rows_done = 1, 2, ... h, the rows
                                  * of a row of tiles together when it is done (may be NULL) */
    void *progress_ctx;
    render_start_fn start; /* once everything is built, before the first pixel (may be
                                * NULL); never for a refused render */
    void *start_ctx;
    scene_warn_fn warn; /* the render's own warnings (a black sampled envmap), before
                                * start (NULL: dropped) */
    void *warn_ctx;
    budget *mem;     /* charged before the displaced geometry, BVH and envmap tables
                                * are built (NULL: none) */
    image *variance; /* not NULL: gets the variance of each pixel's mean (image_free) */
} render_opts;

typedef struct render_stats {
    double seconds;       /* wall-clock time of the pixel loop */
    double build_seconds; /* time to build acceleration structures and tables */
    long long rays;       /* rays traced, shadow rays included */
    int spp;
    long nonfinite_pixels;   /* pixels stored with a NaN or Inf channel (should be 0) */
    long nonfinite_variance; /* the same, in opts->variance (0 without one) */
    /* what was built */
    long prims;
    int bvh_is_tree;
    int ray_differentials; /* camera rays carried differentials (a map needs a footprint) */
    long bvh_nodes;
    int bvh_depth;
    int envlight_built;         /* environment sampling tables were built */
    int envlight_sampled;       /* the integrator samples the envmap as a light */
    int envlight_mode;          /* envsampling_mode used (cdf: uniform on a black map) */
    double envlight_seconds;    /* time to build them */
    long envlight_bad_texels;   /* NaN / Inf / negative texel channels, treated as 0 */
    int envlight_fell_back;     /* the map was black: sampling fell back to uniform */
    int envlight_points;        /* median cut: point lights made */
    int envlight_w, envlight_h; /* the lat-long map sampled (resampled for other kinds) */
    double envlight_kappa;      /* E[L^2] / E[L]^2 of the map (envlight.h) */
    double env_fraction;        /* the envmap's sampling fraction under MIS (lights.h), else 1 */
    nee_mode nee;               /* the path tracer's next-event estimation as run (integrator.h) */
    int lights;                 /* lights the sampling integrators choose among */
    long displaced_spheres, displaced_triangles; /* objects tessellated for displacement maps */
    long displaced_result; /* triangles they became (with the untouched ones) */
    int displace_sphere_rate, displace_triangle_rate;
} render_stats;

render_opts render_defaults(void);

/* Render sc into *out (allocated, width x height; image_free).  opts NULL: render_defaults();
 * stats not NULL.  0, or -1 with *err naming the scene: spp out of [1, SCENE_MAX_SPP] or over
 * SCENE_MAX_CAMERA_SAMPLES, a variance at spp 1, displaced geometry, BVH or tables that cannot
 * be built or exceed the budget, out of memory; then *out and opts->variance hold nothing and
 * opts->start was not called. */
int render_scene(const scene *sc, const render_opts *opts, image *out, render_stats *stats,
                 error *err);

/* Radiance along a camera ray by the scene's integrator, in the context it (integrator.h). */
rgb render_radiance(integrator *it, ray r, rng *g);

/* The same with the camera ray's differentials (NULL: none), for texture filtering. */
rgb render_radiance_diff(integrator *it, ray r, const ray_diff *rd, rng *g);

/* The same from the camera ray's closest hit, found already: got and *h as bvh_intersect (or
 * bvh_intersect_packet) returns and fills them. */
rgb render_radiance_hit(integrator *it, ray r, const ray_diff *rd, int got, const hit *h, rng *g);

#endif
