/* scene.c - the scene's own functions (scene.h): freeing it, the default material, its
 * envmap as rays see it, the names of its modes.  The parser is scene_load.c. */
#include "envtex/scene/scene.h"

#include <stdlib.h>
#include <string.h>

material scene_default_material(void)
{
    material m;
    memset(&m, 0, sizeof m);
    m.ambient = rgb_gray(0.2);
    m.brdf = BRDF_PHONG;
    m.ior = 1.5;
    m.texfilter = TEXFILTER_TRILINEAR; /* no maps (0), default mapping */
    return m;
}

void scene_free(scene *sc)
{
    if (!sc) return;
    free(sc->materials);
    free(sc->spheres);
    free(sc->triangles);
    free(sc->lights);
    for (int i = 0; i < sc->n_textures; i++) texture_free(&sc->textures[i].tex);
    free(sc->textures);
    for (int i = 0; i < sc->n_texture_images; i++) image_free(&sc->texture_images[i]);
    free(sc->texture_images);
    image_free(&sc->envmap.img);
    cubemap_free(&sc->envmap.cube);
    infile_list_free(&sc->inputs);
    memset(sc, 0, sizeof *sc);
}

void scene_environment(const scene *sc, envmap *env)
{
    const scene_envmap *e = &sc->envmap;
    convert_env map = {e->kind, &e->img, &e->cube, e->max_height};
    envmap_init(env, e->present ? &map : NULL, e->scale, &e->inv);
}

texmapping_kind scene_material_texmapping(const material *m, int is_sphere)
{
    if (!m->texmapping_given) return is_sphere ? TEXMAPPING_SPHERICAL : TEXMAPPING_UV;
    if (is_sphere && m->texmapping == TEXMAPPING_UV) return TEXMAPPING_SPHERICAL;
    return m->texmapping;
}

/* the words of `envsampling`, in envsampling_mode order (their one home: cmd_envsampling
 * reads them through scene_envsampling_name) */
static const char *const envsampling_words[] = {"uniform", "cdf", "cdf-sintheta", "mediancut",
                                                "sis"};
#define N_ENVSAMPLING_WORDS ((int)(sizeof envsampling_words / sizeof envsampling_words[0]))

const char *scene_envsampling_name(envsampling_mode m)
{
    return (int)m >= 0 && (int)m < N_ENVSAMPLING_WORDS ? envsampling_words[m] : "unknown";
}

const char *scene_integrator_name(integrator_kind k)
{
    switch (k) {
    case INTEGRATOR_RAYTRACER: return "raytracer";
    case INTEGRATOR_ANALYTICDIRECT: return "analyticdirect";
    case INTEGRATOR_DIRECT: return "direct";
    case INTEGRATOR_PATHTRACER: return "pathtracer";
    case INTEGRATOR_PREFILTERED: return "prefiltered";
    }
    return "unknown";
}
