/* render.c - the pixel loop (see include/envtex/render/render.h). */
#include "envtex/render/render.h"

#include <string.h>
#include <time.h>

#include "envtex/integrators/analyticdirect.h"
#include "envtex/geometry/bvh.h"
#include "envtex/geometry/bvh_packet.h"
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
    hit h;
    int got = bvh_intersect(it->accel, &r, &h); /* the first hit, then what follows from it */
    return render_radiance_hit(it, r, rd, got, &h, g);
}

rgb render_radiance_hit(integrator *it, ray r, const ray_diff *rd, int got, const hit *h, rng *g)
{
    integrator_kind kind = it->sc->integrator;
    if (kind == INTEGRATOR_RAYTRACER || kind == INTEGRATOR_PREFILTERED) /* its own shade */
        return raytracer_trace_hit(&it->rt, r, rd, got, h);
    scene_hit sh;
    if (got) sh.h = *h;
    integrator_scene_hit(it, &r, rd, got, &sh);
    switch (kind) {
    case INTEGRATOR_ANALYTICDIRECT: return analyticdirect_radiance_hit(it, r, rd, &sh, g);
    case INTEGRATOR_DIRECT: return direct_radiance_hit(it, r, rd, &sh, g);
    default: return pathtracer_radiance_hit(it, r, rd, &sh, g);
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

/* The samples per pixel: the caller's, else the scene's, within the limits. */
static int samples_per_pixel(const scene *sc, const render_opts *opts, int *out, error *err)
{
    int spp = opts->spp > 0 ? opts->spp : sc->spp;
    if (spp < 1 || spp > SCENE_MAX_SPP)
        return error_set(err, sc->path, 0, "spp %d is out of range [1, %d]", spp, SCENE_MAX_SPP);
    long long samples = (long long)sc->width * sc->height * spp;
    if (samples > SCENE_MAX_CAMERA_SAMPLES)
        return error_set(err, sc->path, 0,
                         "size %d x %d at spp %d asks for %lld camera samples, over the limit of "
                         "2^34",
                         sc->width, sc->height, spp, samples);
    if (opts->variance && spp < 2)
        return error_set(err, sc->path, 0,
                         "a per-pixel variance needs at least 2 samples per pixel (spp is 1)");
    *out = spp;
    return 0;
}

/* What a render builds before its first pixel: the displaced copy of the scene (if a map moves
 * geometry), the BVH and the integrator's context.  Freed by release. */
typedef struct built {
    const scene *sc; /* the caller's scene, or &displaced */
    scene displaced;
    int has_displaced;
    bvh accel;
    integrator it;
} built;

static void release_displaced(built *b)
{
    if (b->has_displaced) displacemap_free(&b->displaced);
}

/* Build what sc needs, charged to mem.  0, or -1 with *err and nothing left to free. */
static int build(const scene *sc, budget *mem, built *b, render_stats *stats, error *err)
{
    b->sc = sc;
    b->has_displaced = 0;
    /* displacement maps move geometry: render a displaced copy (the caller's scene is not
     * touched; displacemap.h) */
    if (displacemap_needed(sc)) {
        displacemap_stats ds;
        if (displacemap_apply(sc, 0, mem, &b->displaced, &ds, err)) return -1;
        b->has_displaced = 1;
        stats->displaced_spheres = ds.spheres;
        stats->displaced_triangles = ds.triangles;
        stats->displaced_result = ds.new_triangles;
        stats->displace_sphere_rate = ds.sphere_rate;
        stats->displace_triangle_rate = ds.triangle_rate;
        b->sc = &b->displaced;
    }
    if (lights_scene_bvh(&b->accel, b->sc, mem, err)) { /* its quad lights too (lights.h) */
        release_displaced(b);
        return -1;
    }
    if (integrator_init(&b->it, b->sc, &b->accel, mem, err)) {
        bvh_free(&b->accel);
        release_displaced(b);
        return -1;
    }
    return 0;
}

static void release(built *b)
{
    integrator_free(&b->it);
    bvh_free(&b->accel);
    release_displaced(b);
}

/* An all-zero map that the scene importance samples falls back to uniform, with a warning (a
 * scene that asked for uniform directions loses nothing).  Only a light built for sampling
 * measures the map, so only one can have fallen back. */
static void warn_if_black_envmap(const scene *sc, const integrator *it, const render_opts *opts)
{
    if (!opts->warn || !it->el.fell_back || sc->envsampling == ENVSAMPLING_UNIFORM) return;
    int cut = sc->envsampling == ENVSAMPLING_MEDIANCUT;
    error w;
    error_set(&w, sc->path, sc->envmap.line,
              "envmap %s is black (no texel above 0): 'envsampling %s' %s", sc->envmap.path,
              scene_envsampling_name(sc->envsampling),
              cut ? "has no energy to divide and cuts the map into strata of equal texel counts "
                    "instead"
                  : "has nothing to importance sample and samples uniform directions instead");
    opts->warn(opts->warn_ctx, &w);
}

/* How camera rays are made: with differentials only where a texture map uses a footprint. */
typedef struct pixel_sampler {
    camera cam;
    int spp;
    int with_diff;
    double diff_scale;
} pixel_sampler;

_Static_assert(RENDER_TILE *RENDER_TILE <= BVH_PACKET, "a tile's camera rays are one packet");

/* A tile of pixels: RENDER_TILE x RENDER_TILE at most, cut by the image's edge. */

typedef struct tile {
    int x0, y0, w, h;
    rng r[BVH_PACKET];                    /* pixel i's random stream */
    rgb mean[BVH_PACKET], m2[BVH_PACKET]; /* its samples' mean and sum of squared deviations */
} tile;

/* Sample v, the n-th, into the running mean and M2 (the sum of squared deviations). */
static void welford_add(rgb *mean, rgb *m2, rgb v, int n)
{
    rgb d = rgb_make(v.r - mean->r, v.g - mean->g, v.b - mean->b);
    rgb m = rgb_madd(*mean, d, 1.0 / n); /* mean += (v - mean) / n */
    *m2 = rgb_add(*m2, rgb_make(d.r * (v.r - m.r), d.g * (v.g - m.g),
                                d.b * (v.b - m.b))); /* M2 += (v - mean_old)(v - mean) */
    *mean = m;
}

/* Sample s of every pixel of t: the camera rays through (x + jx, y + jy), traced together
 * (bvh_packet.h: the hits bvh_intersect would find), then each pixel's sample goes on through
 * the integrator from its own hit, drawing from its own stream: the same numbers as pixel by
 * pixel.  Welford's running update in double keeps each pixel's mean and M2. */
static void tile_sample(integrator *it, const pixel_sampler *ps, tile *t, int s)
{
    int n = t->w * t->h, got[BVH_PACKET];
    ray cr[BVH_PACKET];
    ray_diff rd[BVH_PACKET];
    hit hits[BVH_PACKET];
    for (int y = 0, i = 0; y < t->h; y++)
        for (int x = 0; x < t->w; x++, i++) {
            double jx = 0.5, jy = 0.5; /* one sample: the pixel's centre */
            if (ps->spp > 1) {
                jx = rng_uniform(&t->r[i]);
                jy = rng_uniform(&t->r[i]);
            }
            double px = t->x0 + x + jx, py = t->y0 + y + jy;
            cr[i] = ps->with_diff
                        ? camera_ray_differential(&ps->cam, px, py, ps->diff_scale, &rd[i])
                        : camera_ray(&ps->cam, px, py);
        }
    bvh_intersect_packet(it->accel, cr, n, got, hits);
    for (int i = 0; i < n; i++) {
        const ray_diff *rdi = ps->with_diff ? &rd[i] : NULL;
        rgb v = render_radiance_hit(it, cr[i], rdi, got[i], &hits[i], &t->r[i]);
        welford_add(&t->mean[i], &t->m2[i], v, s + 1);
    }
}

/* The tile's pixels: the mean of each one's spp samples (the box filter) into out, and the
 * variance of that mean, M2 / (n - 1) / n, into opts->variance.  Pixel (x, y) draws from
 * stream y * width + x of the seed. */
static void render_tile(integrator *it, const pixel_sampler *ps, const render_opts *opts, tile *t,
                        image *out, render_stats *stats)
{
    int n = t->w * t->h, spp = ps->spp;
    for (int i = 0; i < n; i++) {
        uint64_t x = (uint64_t)(t->x0 + i % t->w), y = (uint64_t)(t->y0 + i / t->w);
        rng_seed(&t->r[i], opts->seed, y * (uint64_t)it->sc->width + x);
        t->mean[i] = t->m2[i] = rgb_gray(0);
    }
    for (int s = 0; s < spp; s++) tile_sample(it, ps, t, s);
    for (int i = 0; i < n; i++) {
        int x = t->x0 + i % t->w, y = t->y0 + i / t->w;
        if (opts->variance) {
            image_set(opts->variance, x, y, rgb_scale(t->m2[i], 1.0 / ((double)(spp - 1) * spp)));
            stats->nonfinite_variance += !image_px_is_finite(image_px(opts->variance, x, y));
        }
        image_set(out, x, y, t->mean[i]);
        /* counted as stored: a finite double above FLT_MAX becomes Inf in the float image */
        stats->nonfinite_pixels += !image_px_is_finite(image_px(out, x, y));
    }
}

/* Every pixel into out (and the variance of its mean into opts->variance), a row of tiles at
 * a time. */
static void render_pixels(integrator *it, const pixel_sampler *ps, const render_opts *opts,
                          image *out, render_stats *stats)
{
    int w = it->sc->width, h = it->sc->height;
    tile t;
    for (int y = 0; y < h; y += RENDER_TILE) {
        int th = h - y < RENDER_TILE ? h - y : RENDER_TILE;
        for (int x = 0; x < w; x += RENDER_TILE) {
            t.x0 = x;
            t.y0 = y;
            t.w = w - x < RENDER_TILE ? w - x : RENDER_TILE;
            t.h = th;
            render_tile(it, ps, opts, &t, out, stats);
        }
        for (int row = y; row < y + th; row++)
            if (opts->progress) opts->progress(opts->progress_ctx, row + 1, h);
    }
}

/* What was built, for the summary line and --verbose. */
static void record_built(const built *b, render_stats *stats)
{
    const integrator *it = &b->it;
    stats->rays = it->rays + it->rt.rays;
    stats->envlight_built = it->has_envlight;
    stats->envlight_sampled = it->samples_env;
    if (it->has_envlight) {
        stats->envlight_mode = it->el.mode;
        stats->envlight_seconds = it->el.build_seconds;
        stats->envlight_bad_texels = it->el.n_bad;
        stats->envlight_fell_back = it->el.fell_back;
        stats->envlight_points = it->el.n_points;
        stats->envlight_w = it->el.w;
        stats->envlight_h = it->el.h;
        stats->envlight_kappa = it->el.kappa;
    }
    stats->lights = it->has_lights ? it->ls.n : 0;
    stats->env_fraction = it->env_fraction;
    stats->nee = it->nee;
    stats->prims = b->accel.n_prims;
    stats->bvh_is_tree = b->accel.is_tree;
    stats->bvh_nodes = b->accel.n_nodes;
    stats->bvh_depth = b->accel.depth;
}

int render_scene(const scene *sc, const render_opts *opts, image *out, render_stats *stats,
                 error *err)
{
    render_opts def = render_defaults();
    if (!opts) opts = &def;
    memset(stats, 0, sizeof *stats);
    out->w = out->h = 0;
    out->px = NULL;
    pixel_sampler ps;
    if (samples_per_pixel(sc, opts, &ps.spp, err)) return -1;

    double t0 = now_seconds();
    built b;
    if (build(sc, opts->mem, &b, stats, err)) return -1;
    sc = b.sc;
    stats->build_seconds = now_seconds() - t0;
    if (image_alloc(out, sc->width, sc->height, err) ||
        (opts->variance && image_alloc(opts->variance, sc->width, sc->height, err))) {
        image_free(out);
        release(&b);
        return error_prefix(err, "%s: output image", sc->path);
    }
    warn_if_black_envmap(sc, &b.it, opts);
    if (opts->start) opts->start(opts->start_ctx); /* nothing below refuses the render */

    camera_init(&ps.cam, sc->eye, sc->center, sc->up, sc->fovy, sc->width, sc->height);
    ps.with_diff = texshade_scene_needs_differentials(sc); /* other scenes pay nothing */
    ps.diff_scale = fmax(1.0 / sqrt((double)ps.spp), RENDER_MIN_DIFF_SCALE);
    double t1 = now_seconds();
    render_pixels(&b.it, &ps, opts, out, stats);
    stats->seconds = now_seconds() - t1;
    record_built(&b, stats);
    stats->spp = ps.spp;
    stats->ray_differentials = ps.with_diff;
    release(&b);
    return 0;
}
