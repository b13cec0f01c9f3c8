/* envmap.c - the environment seen by rays that leave the scene (see include/envtex/envmap.h). */
#include "envtex/envmap.h"

#include <string.h>

#include "envtex/latlong.h"

void envmap_init(envmap *env, const scene *sc)
{
    memset(env, 0, sizeof *env);
    if (!sc->envmap.present || sc->envmap.img.w == 0) return;
    env->present = 1;
    env->img = &sc->envmap.img;
    env->scale = sc->envmap.scale;
    env->to_env = sc->envmap.inv;
}

rgb envmap_radiance(const envmap *env, vec3 d)
{
    if (!env->present) return rgb_gray(0);
    return rgb_scale(latlong_lookup_bilinear(env->img, envmap_to_frame(env, d)), env->scale);
}
