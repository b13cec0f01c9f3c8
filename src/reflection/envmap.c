/* envmap.c - the environment seen by rays that leave the scene (see
 * include/envtex/reflection/envmap.h). */
#include "envtex/reflection/envmap.h"

#include <string.h>

#include "envtex/envmaps/latlong.h"

void envmap_init(envmap *env, const convert_env *map, double scale, const mat4 *to_env)
{
    memset(env, 0, sizeof *env);
    if (!map || (map->kind == CONVERT_CUBE ? !map->cube || map->cube->size == 0
                                           : !map->img || map->img->w == 0))
        return;
    env->present = 1;
    env->kind = map->kind;
    if (map->kind == CONVERT_CUBE)
        env->cube = map->cube;
    else
        env->map = map->img;
    if (map->kind == CONVERT_LATLONG) env->img = map->img;
    if (map->kind == CONVERT_CYLINDRICAL)
        env->max_height = map->max_height > 0
                              ? map->max_height
                              : convert_cylindrical_height(map->img->w, map->img->h);
    env->scale = scale;
    env->to_env = *to_env;
}

convert_env envmap_view(const envmap *env)
{
    convert_env v;
    v.kind = env->kind;
    v.img = env->map;
    v.cube = env->cube;
    v.max_height = env->max_height;
    return v;
}

rgb envmap_radiance(const envmap *env, vec3 d)
{
    if (!env->present) return rgb_gray(0);
    vec3 f = envmap_to_frame(env, d);
    /* the common case without the dispatch */
    if (env->kind == CONVERT_LATLONG)
        return rgb_scale(latlong_lookup_bilinear(env->img, f), env->scale);
    convert_env v = envmap_view(env);
    return rgb_scale(convert_lookup(&v, f), env->scale);
}

int envmap_to_latlong(const envmap *env, int width, int samples, image *out, error *err)
{
    memset(out, 0, sizeof *out);
    if (!env->present) return error_set(err, NULL, 0, "no environment map to convert");
    convert_env v = envmap_view(env);
    convert_map m;
    if (convert_resample(&v, CONVERT_LATLONG, width, samples, &m, err)) return -1;
    *out = m.img; /* the map's only allocation moves to the caller */
    return 0;
}
