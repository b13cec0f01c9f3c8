/* render.c - the pixel loop (see include/envtex/render/render.h). */
#include "envtex/render/render.h"

#include <string.h>
#include <time.h>

#include "envtex/integrators/analyticdirect.h"
#include "envtex/geometry/bvh.h"
#include "envtex/geometry/camera.h"
#include "envtex/integrators/direct.h"
#include "envtex/scene/displacemap.h"
#include "envtex/integrators/integrator.h"
#include "envtex/integrators/pathtracer.h"
#include "envtex/core/rng.h"
#include "envtex/integrators/texshade.h"

rgb render_radiance(integrator *it, ray r, rng *g) { return render_radiance_diff(it, r, NULL, g); }

rgb render_radiance_diff(integrator *it, ray r, const ray_diff *rd, rng *g)
{
    switch (it->sc->integrator) {
    case INTEGRATOR_RAYTRACER:
    case INTEGRATOR_PREFILTERED: return raytracer_trace_diff(&it->rt, r, rd); /* its own shade */
    case INTEGRATOR_ANALYTICDIRECT: return analyticdirect_radiance_diff(it, r, rd, g);
    case INTEGRATOR_DIRECT: return direct_radiance_diff(it, r, rd, g);
    default: return pathtracer_radiance_diff(it, r, rd, g);
    }
}

/* Camera rays' differentials are scaled by max(1 / sqrt(spp), RENDER_MIN_DIFF_SCALE): with spp
 * samples in a pixel each stands for a 1 / sqrt(spp) wide part of it (pbrt does the same and
 * stops at 1/8, so a very high spp still filters over an eighth of a pixel). */
#define RENDER_MIN_DIFF_SCALE 0.125

render_opts render_defaults(void)
{
    render_opts o;
    memset(&o, 0, sizeof o);
    return o;
}

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

int render_scene(const scene *sc, const render_opts *opts, image *out, render_stats *stats, error *err)
{
    render_opts def = render_defaults();
    if (!opts) opts = &def;
    memset(stats, 0, sizeof *stats);
    out->w = out->h = 0;
    out->px = NULL;
    int spp = opts->spp > 0 ? opts->spp : sc->spp;
    if (spp < 1 || spp > SCENE_MAX_SPP)
        return error_set(err, sc->path, 0, "spp %d is out of range [1, %d]", spp, SCENE_MAX_SPP);
    if ((long long)sc->width * sc->height * spp > SCENE_MAX_CAMERA_SAMPLES)
        return error_set(err, sc->path, 0, "size %d x %d at spp %d asks for %lld camera samples, over the limit of 2^34",
                         sc->width, sc->height, spp, (long long)sc->width * sc->height * spp);
    if (opts->variance && spp < 2)
        return error_set(err, sc->path, 0, "a per-pixel variance needs at least 2 samples per pixel (spp is 1)");

    double t0 = now_seconds();
    /* Displacement maps move geometry: render a displaced copy (the caller's scene is not
     * touched; displacemap.h) */
    scene displaced;
    int has_displaced = 0;
    if (displacemap_needed(sc)) {
        displacemap_stats ds;
        if (displacemap_apply(sc, 0, opts->mem, &displaced, &ds, err)) return -1;
        has_displaced = 1;
        stats->displaced_spheres = ds.spheres;
        stats->displaced_triangles = ds.triangles;
        stats->displaced_result = ds.new_triangles;
        stats->displace_sphere_rate = ds.sphere_rate;
        stats->displace_triangle_rate = ds.triangle_rate;
        sc = &displaced;
    }
    bvh accel;
    if (lights_scene_bvh(&accel, sc, opts->mem, err)) { /* its quad lights too (lights.h) */
        if (has_displaced) displacemap_free(&displaced);
        return -1;
    }
    integrator it;
    if (integrator_init(&it, sc, &accel, opts->mem, err)) {
        bvh_free(&accel);
        if (has_displaced) displacemap_free(&displaced);
        return -1;
    }
    stats->build_seconds = now_seconds() - t0;
    if (image_alloc(out, sc->width, sc->height, err) ||
        (opts->variance && image_alloc(opts->variance, sc->width, sc->height, err))) {
        image_free(out);
        integrator_free(&it);
        bvh_free(&accel);
        if (has_displaced) displacemap_free(&displaced);
        return error_prefix(err, "%s: output image", sc->path);
    }

    if (opts->warn && it.el.fell_back && sc->envsampling != ENVSAMPLING_UNIFORM) {
        /* the "an all-zero map falls back to uniform with a warning": nothing to
         * importance sample (a scene that asked for uniform directions loses nothing).  Only a
         * light built for sampling measures the map, so only one can have fallen back (a
         * lookup-only light, envlight_build_lookup, never sets fell_back). */
        error w;
        error_set(&w, sc->path, sc->envmap.line,
                  "envmap %s is black (no texel above 0): 'envsampling %s' %s", sc->envmap.path,
                  scene_envsampling_name(sc->envsampling),
                  sc->envsampling == ENVSAMPLING_MEDIANCUT
                      ? "has no energy to divide and cuts the map into strata of equal texel counts instead"
                      : "has nothing to importance sample and samples uniform directions instead");
        opts->warn(opts->warn_ctx, &w);
    }
    if (opts->start) opts->start(opts->start_ctx); /* nothing below refuses the render */

    camera cam;
    camera_init(&cam, sc->eye, sc->center, sc->up, sc->fovy, sc->width, sc->height);
    /* ray differentials only where a texture map uses a footprint: other scenes pay nothing */
    int with_diff = texshade_scene_needs_differentials(sc);
    double diff_scale = fmax(1.0 / sqrt((double)spp), RENDER_MIN_DIFF_SCALE);

    double t1 = now_seconds();
    for (int y = 0; y < sc->height; y++) {
        for (int x = 0; x < sc->width; x++) {
            rng r;
            rng_seed(&r, opts->seed, (uint64_t)y * (uint64_t)sc->width + (uint64_t)x);
            /* Welford's running mean and sum of squared deviations, in double */
            rgb mean = rgb_gray(0), m2 = rgb_gray(0);
            for (int s = 0; s < spp; s++) {
                double jx = 0.5, jy = 0.5;
                if (spp > 1) {
                    jx = rng_uniform(&r);
                    jy = rng_uniform(&r);
                }
                rgb v;
                if (with_diff) {
                    ray_diff rd;
                    ray cr = camera_ray_differential(&cam, x + jx, y + jy, diff_scale, &rd);
                    v = render_radiance_diff(&it, cr, &rd, &r);
                } else {
                    v = render_radiance(&it, camera_ray(&cam, x + jx, y + jy), &r);
                }
                rgb d = rgb_make(v.r - mean.r, v.g - mean.g, v.b - mean.b);
                mean = rgb_madd(mean, d, 1.0 / (s + 1));         /* mean += (v - mean) / n */
                m2 = rgb_add(m2, rgb_make(d.r * (v.r - mean.r), d.g * (v.g - mean.g), d.b * (v.b - mean.b)));
            }
            rgb c = mean;
            if (opts->variance) { /* variance of the mean: M2 / (n - 1) / n */
                image_set(opts->variance, x, y, rgb_scale(m2, 1.0 / ((double)(spp - 1) * spp)));
                stats->nonfinite_variance += !image_px_is_finite(image_px(opts->variance, x, y));
            }
            image_set(out, x, y, c);
            /* counted as stored: a finite double above FLT_MAX becomes Inf in the float image */
            stats->nonfinite_pixels += !image_px_is_finite(image_px(out, x, y));
        }
        if (opts->progress) opts->progress(opts->progress_ctx, y + 1, sc->height);
    }
    stats->seconds = now_seconds() - t1;
    stats->rays = it.rays + it.rt.rays;
    stats->envlight_built = it.has_envlight;
    stats->envlight_sampled = it.samples_env;
    if (it.has_envlight) {
        stats->envlight_mode = it.el.mode;
        stats->envlight_seconds = it.el.build_seconds;
        stats->envlight_bad_texels = it.el.n_bad;
        stats->envlight_fell_back = it.el.fell_back;
        stats->envlight_points = it.el.n_points;
        stats->envlight_w = it.el.w;
        stats->envlight_h = it.el.h;
        stats->envlight_kappa = it.el.kappa;
    }
    stats->lights = it.has_lights ? it.ls.n : 0;
    stats->env_fraction = it.env_fraction;
    stats->nee = it.nee;
    stats->spp = spp;
    stats->prims = accel.n_prims;
    stats->bvh_is_tree = accel.is_tree;
    stats->ray_differentials = with_diff;
    stats->bvh_nodes = accel.n_nodes;
    stats->bvh_depth = accel.depth;
    integrator_free(&it);
    bvh_free(&accel);
    if (has_displaced) displacemap_free(&displaced);
    return 0;
}
