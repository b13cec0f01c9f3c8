/* envmap.h - the environment seen by rays that leave the scene (lecture slides 3-5: "directly
 * use envmap if miss geometry").  Wraps the map's representation (lat-long now) with the scene's
 * `envmap FILE [SCALE]` settings: the radiance scale and the transform current at the command,
 * which maps the envmap frame (+z up) to the world.
 *
 *     envmap env;
 *     envmap_init(&env, sc);                       // no envmap in the scene: black everywhere
 *     rgb L = envmap_radiance(&env, world_dir);    // radiance arriving FROM direction -world_dir
 *                                                  // i.e. seen looking along world_dir
 */
#ifndef ENVTEX_ENVMAP_H
#define ENVTEX_ENVMAP_H

#include "envtex/scene.h"

typedef struct envmap {
    int present;        /* 0: black */
    const image *img;   /* the lat-long map (owned by the scene) */
    double scale;
    mat4 to_env;        /* world direction -> envmap-frame direction (inverse of scene xf) */
} envmap;

void envmap_init(envmap *env, const scene *sc);

/* Radiance seen looking along world direction d (any non-zero length): scale * L(to_env d),
 * bilinear lookup.  Black if there is no envmap or d is zero / NaN. */
rgb envmap_radiance(const envmap *env, vec3 d);

/* World direction -> envmap-frame direction (not normalized). */
static inline vec3 envmap_to_frame(const envmap *env, vec3 d) { return mat4_dir(&env->to_env, d); }

#endif
