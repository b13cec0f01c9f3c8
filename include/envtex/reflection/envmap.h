/* envmap.h - the environment seen by rays that miss the scene (slide 5 (Using Environment for
 * Reflection Map): "directly use envmap if miss geometry"): a map in any representation
 * (convert.h), the `envmap` scale, and its transform (envmap frame -> world).
 *
 *     scene_environment(sc, &env);                 // scene.h; no envmap: black everywhere
 *     rgb L = envmap_radiance(&env, world_dir);    // seen looking along world_dir
 */
#ifndef ENVTEX_ENVMAP_H
#define ENVTEX_ENVMAP_H

#include "envtex/envmaps/convert.h"
#include "envtex/core/transform.h"

typedef struct envmap {
    int present; /* 0: black */
    convert_kind kind;
    const image *img;    /* lat-long only (else NULL): the map envlight.h samples */
    const image *map;    /* every kind but CONVERT_CUBE (borrowed) */
    const cubemap *cube; /* CONVERT_CUBE only (borrowed), else NULL */
    double max_height;   /* CONVERT_CYLINDRICAL: h > 0 */
    double scale;
    mat4 to_env; /* world direction -> envmap frame */
} envmap;

/* `map` (borrowed: it must outlive *env) with `scale` and to_env; NULL or no pixels: present
 * = 0.  A cylinder without a height gets convert_cylindrical_height. */
void envmap_init(envmap *env, const convert_env *map, double scale, const mat4 *to_env);

/* The map as a view, without scale or transform. */
convert_env envmap_view(const envmap *env);

/* scale * convert_lookup(to_env d) for world d; black if not present or d is zero or NaN. */
rgb envmap_radiance(const envmap *env, vec3 d);

/* World direction -> envmap frame (not normalized). */
static inline vec3 envmap_to_frame(const envmap *env, vec3 d) { return mat4_dir(&env->to_env, d); }

/* The map as a new width x width/2 lat-long image (image_free), unscaled, by convert_resample
 * (<= 0: its defaults).  Fails (out empty) if not present or on a bad size. */
int envmap_to_latlong(const envmap *env, int width, int samples, image *out, error *err);

#endif
