/* envmap.h - the environment seen by rays that leave the scene (lecture slides 3-5: "directly
 * use envmap if miss geometry").  Wraps the map, in whichever representation the scene gave it
 * (lat-long, cube map, mirror ball, angular map, cylindrical panorama, equal-area map: see
 * convert.h and docs/envmap-representations.md), with the scene's `envmap` settings: the
 * radiance scale and the transform current at the command, which maps the envmap frame (+z up)
 * to the world.  Renders look the same whichever representation holds the environment.
 *
 *     envmap env;
 *     scene_environment(sc, &env);                 // scene.h; no envmap: black everywhere
 *     rgb L = envmap_radiance(&env, world_dir);    // radiance arriving from direction world_dir
 *                                                  // (travelling along -world_dir), i.e. seen
 *                                                  // looking along world_dir
 *     image ll = {0};                              // any representation as a lat-long map:
 *     if (envmap_to_latlong(&env, 0, 0, &ll, &err)) ...  // (envlight samples lat-long maps)
 */
#ifndef ENVTEX_ENVMAP_H
#define ENVTEX_ENVMAP_H

#include "envtex/envmaps/convert.h"
#include "envtex/core/transform.h"

typedef struct envmap {
    int present;          /* 0: black */
    convert_kind kind;    /* the representation (CONVERT_LATLONG unless the scene said otherwise) */
    const image *img;     /* kind CONVERT_LATLONG: the lat-long map (owned by the scene), which
                             envlight.h samples directly; NULL for every other kind, whose map
                             envmap_to_latlong converts first */
    const image *map;     /* the image of every kind but CONVERT_CUBE (== img for lat-long) */
    const cubemap *cube;  /* kind CONVERT_CUBE: the six faces (owned by the scene); else NULL */
    double max_height;    /* kind CONVERT_CYLINDRICAL: the cylinder's half height h (> 0) */
    double scale;
    mat4 to_env;          /* world direction -> envmap-frame direction (inverse of scene xf) */
} envmap;

/* The environment `map` seen through `scale` and to_env (world direction -> envmap frame, the
 * inverse of the transform at `envmap`); the map is borrowed and must outlive *env.  NULL or a
 * map without pixels gives present = 0 (black).  A cylindrical map without a height gets
 * convert_cylindrical_height.  scene_environment (scene.h) calls it with the scene's envmap. */
void envmap_init(envmap *env, const convert_env *map, double scale, const mat4 *to_env);

/* The representation as convert.h sees it (a view; no scale, no transform). */
convert_env envmap_view(const envmap *env);

/* Radiance seen looking along world direction d (any non-zero length): scale * L(to_env d),
 * the representation's bilinear lookup (convert_lookup; for a lat-long map exactly
 * latlong_lookup_bilinear).  Black if there is no envmap or d is zero / NaN. */
rgb envmap_radiance(const envmap *env, vec3 d);

/* World direction -> envmap-frame direction (not normalized). */
static inline vec3 envmap_to_frame(const envmap *env, vec3 d) { return mat4_dir(&env->to_env, d); }

/* The environment as a new lat-long map in *out (width x width/2; free with image_free), in the
 * envmap frame and WITHOUT the scale, i.e. what env->img would hold for a lat-long envmap: each
 * texel the solid-angle average of the map over the texel (convert_resample: power kept within
 * 0.5% for real maps, the exceptions - a sun at a pole, on a disc map's rim - in convert.h).  width <= 0 and samples <= 0 pick convert_default_width / convert_default_samples.
 * A lat-long envmap of the requested width is copied exactly.  Fails (out left empty) on an
 * envmap that is not present, or a size image_check_size refuses. */
int envmap_to_latlong(const envmap *env, int width, int samples, image *out, error *err);

#endif
