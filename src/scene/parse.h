/* parse.h - the scene parser's inside, private to src/scene/ (the public entry: scene_load.h):
 * its state, the helpers every command uses (parse_*), the command tables, the asset loaders.
 *
 * One pass, line by line: each line is split into tokens and handed to its command's handler
 * (parse_run_line), which sees p->tok[1..] with the argument count checked and checks its
 * arguments completely before it changes the scene.  The helpers that return int return 0,
 * or -1 with *p->err set at the current line.
 */
#ifndef ENVTEX_SCENE_PARSE_H
#define ENVTEX_SCENE_PARSE_H

#include <stddef.h>

#include "envtex/io/obj.h"
#include "envtex/scene/scene.h"

/* At most 12 arguments (quadLight), plus room to name the first extra token in messages. */
#define MAX_TOKENS 16

typedef struct vertex_normal {
    vec3 p, n;
} vertex_normal;
typedef struct vertex_tex {
    vec3 p;
    uv2 st;
} vertex_tex;
/* An OBJ file read once (by identity) and its mesh. */
typedef struct parsed_obj {
    infile_id id;
    obj_mesh mesh;
} parsed_obj;

typedef struct parser {
    scene *sc;
    /* the load options (scene_load.h), copied */
    int strict;
    scene_warn_fn warn;
    void *warn_ctx;
    int load_images;
    budget *mem;
    const char *name; /* scene name for messages (err->file) */
    char base[1024];  /* the scene file's folder with a trailing '/', or "" */
    error *err;
    int line;              /* 1-based line being read */
    char *tok[MAX_TOKENS]; /* the current line's tokens: tok[0] is the command */
    int ntok;              /* may exceed MAX_TOKENS: only counted */
    mat4 xf;               /* object -> world, current */
    mat4 inv;              /* its inverse when inv_state == 1 */
    int inv_state;         /* 0 not computed, 1 valid, -1 singular */
    mat4 *stack;           /* pushTransform's */
    int depth, stack_cap;
    int first_quad_line; /* for parse_finish's warnings */
    int first_delta_line;
    material mat;
    double atten[3];
    /* vertex lists */
    vec3 *verts;
    long n_verts, cap_verts;
    vertex_normal *vnorms;
    long n_vnorms, cap_vnorms;
    vertex_tex *vtex; /* `vertextex`, for `tritex` */
    long n_vtex, cap_vtex;
    /* the scene's arrays' capacities */
    long cap_spheres, cap_tris;
    long cap_lights, cap_materials;
    long cap_textures;
    /* bookkeeping */
    long max_prims;
    parsed_obj *objs; /* each OBJ file read so far (assets_obj_mesh) */
    int n_objs, cap_objs;
    int *tex_index;   /* texture names' hash: indices into sc->textures, -1 empty */
    size_t tex_slots; /* a power of two, or 0 */
    int seen_size, warned_order;
    char envmap_token[CUBEMAP_FACES][1024]; /* the envmap file name(s) as written */
} parser;

/* ---- parse.c: messages, arguments, the current state ------------------------------------- */

/* Set *p->err to "NAME:LINE: message" at the current line; returns -1. */
int parse_fail(parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* A warning at the current line through p->warn (NULL: dropped). */
void parse_warn(parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Room for `need` elements of `size` bytes in *arr (capacity *cap), doubling, charged first. */
int parse_grow(parser *p, void **arr, long *cap, long need, size_t size, const char *what);

/* Argument i (1-based) as a finite double (the whole token). */
int parse_arg_num(parser *p, int i, double *out);

/* Arguments first..first+n-1 into v[0..n-1]. */
int parse_arg_nums(parser *p, int first, int n, double *v);

/* Argument i as an integer in [lo, hi] ("1e1" is 10; "10.5" an error). */
int parse_arg_int(parser *p, int i, double lo, double hi, long *out);

/* Argument i as a number >= 0 (strict = 0) or > 0 (strict = 1). */
int parse_arg_nonneg(parser *p, int i, int strict, double *out);

/* Arguments first..first+2 as a colour, each >= 0. */
int parse_arg_rgb(parser *p, int first, rgb *out);

/* Argument 1 as one of `n` keywords (exact); *out its index. */
int parse_arg_word(parser *p, const char *const *words, int n, int *out);

/* Argument 1 as `off` (0) or `on` (1). */
int parse_arg_onoff(parser *p, int *out);

/* Right-multiply the current transform: the command written last applies first. */
int parse_xf_apply(parser *p, mat4 m);

/* The inverse of the current transform (once per change); singular: an error naming the command. */
int parse_xf_inverse(parser *p, const mat4 **inv);

/* `pushTransform` (at most SCENE_MAX_TRANSFORM_STACK deep). */
int parse_xf_push(parser *p);

/* `popTransform`; an error when none is saved. */
int parse_xf_pop(parser *p);

/* Index of the current material state: the last stored one if nothing changed, else a new one. */
int parse_material_index(parser *p, int *out);

/* The three indices of a tri / trinormal, each in [0, count). */
int parse_tri_indices(parser *p, long count, const char *list, long idx[3]);

/* Store triangle t (world corners p[]: the current transform of q[]). */
int parse_add_triangle(parser *p, const triangle *t);

/* Store light l (world space; the current transform does not apply). */
int parse_add_light(parser *p, const scene_light *l);

/* A file name resolved against the scene file's folder (absolute names kept). */
int parse_relative_path(parser *p, const char *file, char *dst, size_t size);

/* Free what only the parser holds and give its memory back to the budget. */
void parse_free(parser *p);

/* ---- parse.c: the commands, line by line ------------------------------------------------- */

/* A command: keyword, handler (0, or -1 with *p->err set), the argument counts parse_run_line
 * checks, and `forms` for "'%s' takes FORMS, got N arguments" (NULL: from the counts). */
typedef struct parse_command {
    const char *name;
    int (*run)(parser *p);
    int min_args, max_args;
    const char *forms;
} parse_command;

/* The command tables (ended by name NULL), looked up in this order: the course's, the texture
 * commands, envtex's own. */
extern const parse_command commands_course[];
extern const parse_command commands_texture[];
extern const parse_command commands_envtex[];

/* Split `line` (modified in place; '#' starts a comment) into p->tok and run its command;
 * unknown commands are warnings (errors when strict). */
int parse_run_line(parser *p, char *line);

/* After the last line: the whole-file checks and warnings, then the images (unless
 * load_images is 0). */
int parse_finish(parser *p);

/* ---- assets.c: the files a scene names --------------------------------------------------- */

/* The mesh of the OBJ file `path`, parsed once however often (and however spelled) it is named,
 * and added to the scene's inputs.  *out is owned by the parser (parse_free). */
int assets_obj_mesh(parser *p, const char *path, const obj_mesh **out);

/* Read each image texture's file once, then build the pyramids the filters need (one per file
 * and wrap mode).  Errors at the `texture` line with the reader's reason. */
int assets_load_textures(parser *p);

/* Read the envmap image(s), zero bad texels, settle the representation (a cross split into
 * faces); errors at the `envmap` line. */
int assets_load_envmap(parser *p);

#endif
