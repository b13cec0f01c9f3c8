/* scene_load.h - the scene parser: reads a CSE 167/168 `.test` file (plus envtex's commands,
 * docs/scene-format.md) into a scene (scene.h), and reads the files it names.
 *
 *     scene sc;
 *     error err;
 *     scene_load_opts o = scene_load_defaults();
 *     if (scene_load("data/scenes/mirror_sphere.test", &o, &sc, &err))
 *         error_print(&err, stderr);
 *     ... render ...
 *     scene_free(&sc);
 *
 * Only the render and cli layers include this header (tests/layers/run-tests): everything
 * below them takes a scene already read.
 */
#ifndef ENVTEX_SCENE_LOAD_H
#define ENVTEX_SCENE_LOAD_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/scene/scene.h"

typedef struct scene_load_opts {
    int strict;          /* unknown commands are errors instead of warnings */
    scene_warn_fn warn;  /* called for each warning (may be NULL: warnings are dropped) */
    void *warn_ctx;
    int load_images;     /* 1 (default): read the envmap and texture images (and build the
                          * pyramids their filters need); 0: leave them (parser tests) */
    long max_prims;      /* 0 (default): SCENE_MAX_PRIMS; a smaller limit lets tests reach it */
    budget *mem;         /* the run's memory budget (budget.h), charged before each allocation
                          * from what the file claims: the scene's arrays as they grow, OBJ
                          * meshes, images, mip pyramids; NULL (default): none, only the limits */
} scene_load_opts;

/* strict 0, no warning callback, load_images 1, max_prims 0, no budget. */
scene_load_opts scene_load_defaults(void);

/* Read and check a scene file.  On failure err names FILE:LINE and the offending token, *out
 * owns nothing, and -1 is returned.  On success free with scene_free.  `opts` may be NULL
 * (scene_load_defaults()).  Messages read like
 *     err->file "dir/x.test", err->line 7, err->msg "expected a number for 'sphere' argument 4,
 *     got 'abc'"
 * Errors found only at the end ("no 'size' command", "no 'camera' command") have line 0; an
 * envmap image that cannot be read is reported at the `envmap` line with the reader's reason.
 * The file is read a chunk at a time and each line is checked as it arrives (a NUL byte or a
 * line over SCENE_MAX_LINE bytes stops the reading there), so `path` may be a pipe (a FIFO
 * nobody writes to reads as empty; a device, socket or folder is refused: infile.h).
 * Every other file (envmap, cube faces, textures, OBJ meshes) must be a regular file, and is
 * read once however many lines name it and however they spell it (by identity: a.png, ./a.png,
 * a hard link): textures of one file share its image (and, with one wrap mode, its mip
 * pyramid), and each `obj` line of one mesh appends its own transformed triangles from one
 * parse.  What the scene holds stays charged to opts->mem (scene_free does not release it). */
int scene_load(const char *path, const scene_load_opts *opts, scene *out, error *err);

/* The same from a string in memory; `name` is used in messages and as the base folder for
 * relative file names ("-" or NULL: the working folder; NULL shows as "<string>" in messages
 * and leaves sc->path empty). */
int scene_load_string(const char *text, const char *name, const scene_load_opts *opts, scene *out,
                      error *err);

#endif
