/* commands_envtex.c - envtex's own commands (docs/scene-format.md): the environment map and
 * how it is sampled, OBJ meshes, glass's index of refraction, light selection and the
 * prefiltered integrator's map, in the table commands_envtex (parse.h). */
#include "parse.h"

#include <stdlib.h>
#include <string.h>

#include "envtex/envlight/sis.h"

static int cmd_lightselection(parser *p)
{
    static const char *const w[] = {"all", "power"}; /* light_selection order */
    int k = 0;
    if (parse_arg_word(p, w, 2, &k)) return -1;
    p->sc->lightselection = (light_selection)k;
    return 0;
}

/* `prefilter exact|sh9`: the irradiance map of `integrator prefiltered` */
static int cmd_prefilter(parser *p)
{
    static const char *const w[] = {"exact", "sh9"}; /* irradiance_method order */
    int k = 0;
    if (parse_arg_word(p, w, 2, &k)) return -1;
    p->sc->prefilter = (irradiance_method)k;
    return 0;
}

static int cmd_envmiss(parser *p)
{
    static const char *const w[] = {"envmap", "black"}; /* envmiss_mode order */
    int k = 0;
    if (parse_arg_word(p, w, 2, &k)) return -1;
    p->sc->envmiss = (envmiss_mode)k;
    return 0;
}

/* Indices of refraction outside [SCENE_IOR_MIN, SCENE_IOR_MAX] are typing mistakes (water 1.33,
 * glass 1.5, diamond 2.42; an air bubble in water 0.75); far enough out, eta^2 under- or
 * overflows in Fresnel's equations and refraction returns NaN directions */
#define SCENE_IOR_MIN 0.01
#define SCENE_IOR_MAX 100.0
static int cmd_ior(parser *p)
{
    if (parse_arg_nonneg(p, 1, 1, &p->mat.ior)) return -1;
    if (!(p->mat.ior >= SCENE_IOR_MIN && p->mat.ior <= SCENE_IOR_MAX))
        return parse_fail(p, "'ior' must be from %g to %g, got '%s'", SCENE_IOR_MIN, SCENE_IOR_MAX,
                          p->tok[1]);
    return 0;
}

static int cmd_envsampling(parser *p)
{
    /* the words in envsampling_mode order, from their one home (scene.c), up to "unknown" */
    const char *words[16];
    int n_words = 0;
    while (n_words < 16) {
        words[n_words] = scene_envsampling_name((envsampling_mode)n_words);
        if (strcmp(words[n_words], "unknown") == 0) break;
        n_words++;
    }
    int k = 0;
    if (parse_arg_word(p, words, n_words, &k)) return -1;
    if (k != ENVSAMPLING_MEDIANCUT && k != ENVSAMPLING_SIS && p->ntok > 2)
        return parse_fail(p, "'envsampling %s' takes no count (only 'mediancut N' and 'sis N' do)",
                          words[k]);
    if (p->ntok > 2) { /* the count of mediancut's or sis's point lights */
        long n;
        if (parse_arg_int(p, 2, 1, k == ENVSAMPLING_SIS ? SIS_MAX_LIGHTS : SCENE_MAX_MEDIANCUT, &n))
            return -1;
        p->sc->mediancut_lights = (int)n;
    }
    p->sc->envsampling = (envsampling_mode)k;
    return 0;
}

static int cmd_envsampler(parser *p)
{
    static const char *const w[] = {"binary", "alias"}; /* envsampler_kind order */
    int k = 0;
    if (parse_arg_word(p, w, 2, &k)) return -1;
    p->sc->envsampler = (envsampler_kind)k;
    return 0;
}

/* `envsamplefraction auto|F`: under MIS, the probability that an envmap pick is sampled */
static int cmd_envsamplefraction(parser *p)
{
    if (strcmp(p->tok[1], "auto") == 0) {
        p->sc->envsamplefraction = -1;
        return 0;
    }
    double f = 0;
    if (parse_arg_num(p, 1, &f)) return -1;
    if (!(f >= 0 && f <= 1))
        return parse_fail(p, "'envsamplefraction' must be 'auto' or a number in [0, 1], got '%s'",
                          p->tok[1]);
    p->sc->envsamplefraction = f;
    return 0;
}

/* Token i of an `envmap` line as a file name into dst (relative names are relative to the scene
 * file's folder; absolute ones are kept), remembering the token as written for messages. */
static int envmap_file(parser *p, int i, char *dst, size_t size, char *token, size_t token_size)
{
    const char *file = p->tok[i];
    size_t n = strlen(file);
    if (n >= token_size)
        return parse_fail(p, "'envmap' file name is longer than %zu bytes", token_size - 1);
    const char *base = file[0] == '/' ? "" : p->base;
    int w = snprintf(dst, size, "%s%s", base, file);
    if (w < 0 || (size_t)w >= size)
        return parse_fail(p, "'envmap' path '%s%s' is longer than %zu bytes", base, file, size - 1);
    memcpy(token, file, n + 1);
    return 0;
}

/* 1 if token i reads as a number (finite or not: parse_arg_nonneg then names what is wrong). */
static int token_is_number(const parser *p, int i)
{
    char *end;
    (void)strtod(p->tok[i], &end);
    return end != p->tok[i] && *end == '\0';
}

/* `envmap FILE [SCALE] [latlong|cube|cross|mirrorball|angular|cylindrical|equalarea]` or
 * `envmap cube PX NX PY NY PZ NZ [SCALE]`.  The images are read by parse_finish(). */
static int cmd_envmap(parser *p)
{
    scene_envmap *e = &p->sc->envmap;
    int nargs = p->ntok - 1;
    if (e->present) return parse_fail(p, "envmap given twice (first at line %d)", e->line);
    if (nargs == 0)
        return parse_fail(p,
                          "'envmap' takes FILE [SCALE] [REPRESENTATION] or cube PX NX PY NY PZ NZ "
                          "[SCALE], got no arguments");
    double scale = 1.0;
    int six = strcmp(p->tok[1], "cube") == 0 && nargs > 1;
    if (six) {
        if (nargs != 7 && nargs != 8)
            return parse_fail(
                p,
                "'envmap cube' takes six face files PX NX PY NY PZ NZ and an optional "
                "scale, got %d argument%s",
                nargs - 1, nargs == 2 ? "" : "s");
        if (nargs == 8 && parse_arg_nonneg(p, 8, 1, &scale)) return -1;
    } else {
        int i = 2;
        if (i <= nargs && token_is_number(p, i)) {
            if (parse_arg_nonneg(p, i, 1, &scale)) return -1;
            i++;
        }
        if (i <= nargs) {
            convert_kind kind;
            if (convert_kind_parse(p->tok[i], &kind))
                return parse_fail(p,
                                  "'envmap' representation must be 'latlong', 'cube', 'cross', "
                                  "'mirrorball', 'angular', 'cylindrical' or 'equalarea', got '%s'",
                                  p->tok[i]);
            e->kind = kind;
            e->kind_given = 1;
            i++;
        }
        if (i <= nargs)
            return parse_fail(p,
                              "'envmap FILE' takes a scale and a representation at most, got '%s' "
                              "after them",
                              p->tok[i]);
    }
    const mat4 *inv = NULL;
    if (parse_xf_inverse(p, &inv)) return -1;
    if (six) {
        for (int f = 0; f < CUBEMAP_FACES; f++)
            if (envmap_file(p, 2 + f, e->face_path[f], sizeof e->face_path[f], p->envmap_token[f],
                            sizeof p->envmap_token[f]))
                return -1;
        memcpy(e->path, e->face_path[0], sizeof e->path);
        e->kind = CONVERT_CUBE;
        e->kind_given = 1;
        e->six_files = 1;
    } else if (envmap_file(p, 1, e->path, sizeof e->path, p->envmap_token[0],
                           sizeof p->envmap_token[0])) {
        return -1;
    }
    e->present = 1;
    e->scale = scale;
    e->xf = p->xf;
    e->inv = *inv;
    e->line = p->line;
    return 0;
}

/* `obj FILE`: every triangle of the mesh, under the current transform and material.  Corners
 * with vt give st (all three needed), with vn give normals (all three, each non-degenerate under
 * the transform, else the triangle is flat shaded). */
static int cmd_obj(parser *p)
{
    char path[1024];
    if (parse_relative_path(p, p->tok[1], path, sizeof path)) return -1;
    const obj_mesh *mp = NULL;
    if (assets_obj_mesh(p, path, &mp)) return -1;
    const obj_mesh m = *mp;
    if (m.n_tris > p->max_prims - p->sc->n_triangles)
        return parse_fail(p, "obj '%s' has %ld triangles: more than %ld triangles in the scene",
                          p->tok[1], m.n_tris, p->max_prims);
    if (m.n_ignored > 0)
        parse_warn(p, "obj '%s': %ld statement%s ignored (the first, '%s', at %s:%d)", p->tok[1],
                   m.n_ignored, m.n_ignored == 1 ? "" : "s", m.first_ignored, path,
                   m.first_ignored_line);
    const mat4 *inv = NULL;
    if (m.n_vn > 0 && parse_xf_inverse(p, &inv)) return -1;
    if (m.n_tris > 0 &&
        parse_grow(p, (void **)&p->sc->triangles, &p->cap_tris, p->sc->n_triangles + m.n_tris,
                   sizeof *p->sc->triangles, "triangles"))
        return error_prefix(p->err, "obj '%s'", p->tok[1]);
    for (long i = 0; i < m.n_tris; i++) {
        const obj_triangle *o = &m.tris[i];
        triangle t;
        memset(&t, 0, sizeof t);
        t.has_st = o->vt[0] >= 0 && o->vt[1] >= 0 && o->vt[2] >= 0;
        t.has_normals = o->vn[0] >= 0 && o->vn[1] >= 0 && o->vn[2] >= 0;
        for (int k = 0; k < 3; k++) {
            t.q[k] = m.v[o->v[k]];
            t.p[k] = mat4_point(&p->xf, t.q[k]);
            if (t.has_st) t.st[k] = m.vt[o->vt[k]];
            if (t.has_normals) {
                vec3 n = mat4_normal(inv, m.vn[o->vn[k]]); /* n' = (M^-1)^T n */
                if (vec3_unit_direction(n, &t.n[k])) t.has_normals = 0;
            }
        }
        if (parse_add_triangle(p, &t)) return -1;
    }
    return 0;
}

const parse_command commands_envtex[] = {
    {"obj", cmd_obj, 1, 1, NULL},
    {"lightselection", cmd_lightselection, 1, 1, NULL},
    {"envmap", cmd_envmap, 0, MAX_TOKENS - 2,
     "FILE [SCALE] [REPRESENTATION] or cube PX NX PY NY PZ NZ [SCALE]"},
    {"envmiss", cmd_envmiss, 1, 1, NULL},
    {"ior", cmd_ior, 1, 1, NULL},
    {"envsampling", cmd_envsampling, 1, 2, NULL},
    {"envsampler", cmd_envsampler, 1, 1, NULL},
    {"envsamplefraction", cmd_envsamplefraction, 1, 1, NULL},
    {"prefilter", cmd_prefilter, 1, 1, NULL},
    {NULL, NULL, 0, 0, NULL},
};
