/* scene_load.h - the scene parser: a CSE 167/168 `.test` file and envtex's commands
 * (docs/scene-format.md) into a scene (scene.h); for the render and cli layers only.
 *
 *     scene sc;
 *     scene_load_opts o = scene_load_defaults();
 *     if (scene_load("data/scenes/mirror_sphere.test", &o, &sc, &err)) error_print(&err, stderr);
 *     ... render ...
 *     scene_free(&sc);
 */
#ifndef ENVTEX_SCENE_LOAD_H
#define ENVTEX_SCENE_LOAD_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/scene/scene.h"

typedef struct scene_load_opts {
    int strict;         /* unknown commands are errors instead of warnings */
    scene_warn_fn warn; /* each warning; NULL: dropped */
    void *warn_ctx;
    int load_images; /* 1 (default): read the images, build the pyramids; 0: leave them */
    long max_prims;  /* 0 (default): SCENE_MAX_PRIMS; a smaller limit lets tests reach it */
    budget *mem;     /* charged before each allocation the file asks for; NULL: none */
} scene_load_opts;

/* load_images 1, every other field 0 or NULL. */
scene_load_opts scene_load_defaults(void);

/* Read and check a scene file: 0, *out to free with scene_free; or -1, *out owning nothing and
 * err naming FILE:LINE and the token (line 0 for what only the end shows, an image's reason at
 * its `envmap` or `texture` line).  opts NULL: the defaults.  path may be a pipe; the files it
 * names must be regular files, each read once (docs/robustness.md).  What the scene holds
 * stays charged to opts->mem (scene_free does not release it). */
int scene_load(const char *path, const scene_load_opts *opts, scene *out, error *err);

/* The same from a string; `name` names it in messages and its folder resolves relative names
 * ("-" or NULL: the working folder; NULL shows as "<string>", sc->path ""). */
int scene_load_string(const char *text, const char *name, const scene_load_opts *opts, scene *out,
                      error *err);

#endif
