/* scene_load.c - the CSE 167/168 `.test` scene parser plus envtex's commands (see
 * include/envtex/scene/scene.h and docs/scene-format.md).
 *
 * One pass, line by line.  Each line is copied into a fixed buffer, split into white-space
 * separated tokens, and handed to the command's handler through a table.  Handlers check their
 * arguments completely before they change the scene, so every error names the line and the
 * token that is wrong.  Arrays grow by doubling, so a 100k-triangle mesh costs O(n).
 */
#include "envtex/scene/scene.h"
#include <assert.h>
#include <errno.h>
#include <float.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envtex/geometry/camera.h"
#include "envtex/io/obj.h"
#include "envtex/textures/perlin.h"
#include "parse.h"

/* maxverts / maxvertnorms are only capacity hints: a hostile "maxverts 999999999999" must not
 * reserve gigabytes, so a hint reserves at most this many entries (arrays still grow past it). */
#define HINT_CAP (1L << 20)

/* sin of the angle between a quad light's edges below which it is a sliver of no area: rounding
 * of exactly parallel edges leaves |ab x ac| ~ 1e-16 |ab| |ac|. */
#define QUAD_PARALLEL_EPS 1e-12

/* ---- commands --------------------------------------------------------------------------- */
/* Each handler sees p->tok[1..] with the argument count already checked. */

static int cmd_size(parser *p)
{
    long w = 0, h = 0;
    if (parse_arg_int(p, 1, 1, SCENE_MAX_SIZE, &w) || parse_arg_int(p, 2, 1, SCENE_MAX_SIZE, &h)) return -1;
    if (w * h > SCENE_MAX_PIXELS)
        return parse_fail(p, "'size' %ld x %ld is %ld pixels, more than the limit %ld", w, h, w * h,
                    (long)SCENE_MAX_PIXELS);
    p->sc->width = (int)w;
    p->sc->height = (int)h;
    return 0;
}

static int cmd_maxdepth(parser *p)
{
    long d = 0;
    if (parse_arg_int(p, 1, -1, SCENE_MAX_DEPTH, &d)) return -1;
    p->sc->maxdepth = (int)d;
    return 0;
}

static int cmd_output(parser *p)
{
    /* kept as written: relative to the working folder, as the course skeleton does */
    size_t n = strlen(p->tok[1]);
    if (n >= sizeof p->sc->output)
        return parse_fail(p, "'output' file name is longer than %zu bytes", sizeof p->sc->output - 1);
    memcpy(p->sc->output, p->tok[1], n + 1);
    p->sc->output_line = p->line; /* so a refused name points at its line (main.c) */
    return 0;
}

static int cmd_camera(parser *p)
{
    double v[10];
    if (parse_arg_nums(p, 1, 10, v)) return -1;
    vec3 from = vec3_make(v[0], v[1], v[2]), at = vec3_make(v[3], v[4], v[5]);
    vec3 up = vec3_make(v[6], v[7], v[8]);
    if (!(v[9] > 0 && v[9] < 180))
        return parse_fail(p, "'camera' fovy must be in (0, 180) degrees, got '%s'", p->tok[10]);
    vec3 u, v_, w; /* the frame camera_init will build: checked here, with its own arithmetic */
    switch (camera_frame(from, at, up, &u, &v_, &w)) {
    case CAMERA_FRAME_OK: break;
    case CAMERA_FRAME_TOO_FAR:
        return parse_fail(p, "'camera' look-from and look-at are too far apart (their difference overflows)");
    case CAMERA_FRAME_SAME_POINT: return parse_fail(p, "'camera' look-from equals look-at");
    case CAMERA_FRAME_UP_ZERO: return parse_fail(p, "'camera' up vector is zero");
    case CAMERA_FRAME_UP_PARALLEL:
        return parse_fail(p, "'camera' up vector (%s %s %s) is parallel to the view direction",
                    p->tok[7], p->tok[8], p->tok[9]);
    }
    scene *sc = p->sc;
    sc->has_camera = 1;
    sc->eye = from;
    sc->center = at;
    sc->up = up;
    sc->fovy = v[9];
    return 0;
}

/* 1 if m is exactly the identity (a sphere without a transform: sphere.c skips the products) */
static int is_identity(const mat4 *m)
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (m->m[i][j] != (i == j)) return 0;
    return 1;
}

static int cmd_sphere(parser *p)
{
    double v[4];
    if (parse_arg_nums(p, 1, 3, v) || parse_arg_nonneg(p, 4, 1, &v[3])) return -1;
    const mat4 *inv = NULL;
    if (parse_xf_inverse(p, &inv)) return -1;
    scene *sc = p->sc;
    if (sc->n_spheres >= p->max_prims)
        return parse_fail(p, "more than %ld spheres", p->max_prims);
    int m;
    if (parse_material_index(p, &m)) return -1;
    if (parse_grow(p, (void **)&sc->spheres, &p->cap_spheres, sc->n_spheres + 1, sizeof *sc->spheres,
             "spheres"))
        return -1;
    sphere *s = &sc->spheres[sc->n_spheres++];
    s->center = vec3_make(v[0], v[1], v[2]);
    s->radius = v[3];
    s->xf = p->xf;
    s->inv = *inv;
    s->untransformed = is_identity(&s->xf) && is_identity(&s->inv);
    s->material = m;
    return 0;
}

/* maxverts / maxvertnorms: capacity hints, capped at HINT_CAP. */
static int cmd_maxverts(parser *p)
{
    long n = 0;
    if (parse_arg_int(p, 1, 0, 1e18, &n)) return -1;
    if (n > HINT_CAP) n = HINT_CAP;
    if (strcmp(p->tok[0], "maxverts") == 0)
        return parse_grow(p, (void **)&p->verts, &p->cap_verts, n, sizeof *p->verts, "vertices");
    return parse_grow(p, (void **)&p->vnorms, &p->cap_vnorms, n, sizeof *p->vnorms, "vertex normals");
}

static int cmd_vertex(parser *p)
{
    double v[3];
    if (parse_arg_nums(p, 1, 3, v)) return -1;
    if (p->n_verts >= p->max_prims)
        return parse_fail(p, "more than %ld vertices", p->max_prims);
    if (parse_grow(p, (void **)&p->verts, &p->cap_verts, p->n_verts + 1, sizeof *p->verts, "vertices"))
        return -1;
    p->verts[p->n_verts++] = vec3_make(v[0], v[1], v[2]);
    return 0;
}

static int cmd_vertexnormal(parser *p)
{
    double v[6];
    if (parse_arg_nums(p, 1, 6, v)) return -1;
    /* a direction: only its direction is kept (so 1e300 or 1e-300 components work).  A zero
     * normal is kept as zero, not refused: OBJ converters write `vertexnormal 0 0 0 0 0 0` as a
     * placeholder for OBJ's unused index 0; a `trinormal` that uses it is flat shaded. */
    vec3 n;
    if (vec3_unit_direction(vec3_make(v[3], v[4], v[5]), &n)) n = vec3_make(0, 0, 0);
    if (p->n_vnorms >= p->max_prims)
        return parse_fail(p, "more than %ld vertex normals", p->max_prims);
    if (parse_grow(p, (void **)&p->vnorms, &p->cap_vnorms, p->n_vnorms + 1, sizeof *p->vnorms,
             "vertex normals"))
        return -1;
    p->vnorms[p->n_vnorms++] = (vertex_normal){vec3_make(v[0], v[1], v[2]), n};
    return 0;
}

static int cmd_tri(parser *p)
{
    long idx[3];
    if (parse_tri_indices(p, p->n_verts, "vertices", idx)) return -1;
    triangle t;
    memset(&t, 0, sizeof t);
    for (int k = 0; k < 3; k++) {
        t.q[k] = p->verts[idx[k]];
        t.p[k] = mat4_point(&p->xf, t.q[k]);
    }
    return parse_add_triangle(p, &t);
}

/* 1 for the zero normal cmd_vertexnormal keeps for a `vertexnormal` written with normal 0 0 0 */
static int is_zero_normal(vec3 n) { return n.x == 0 && n.y == 0 && n.z == 0; }

static int cmd_trinormal(parser *p)
{
    long idx[3];
    if (parse_tri_indices(p, p->n_vnorms, "vertexnormals", idx)) return -1;
    const mat4 *inv = NULL;
    if (parse_xf_inverse(p, &inv)) return -1;
    triangle t;
    memset(&t, 0, sizeof t);
    /* a corner with a zero normal (cmd_vertexnormal) has no normal to interpolate: the triangle
     * is flat shaded, as an OBJ face with a degenerate normal (cmd_obj) */
    t.has_normals = 1;
    for (int k = 0; k < 3; k++) t.has_normals &= !is_zero_normal(p->vnorms[idx[k]].n);
    for (int k = 0; k < 3; k++) {
        const vertex_normal *v = &p->vnorms[idx[k]];
        t.q[k] = v->p;
        t.p[k] = mat4_point(&p->xf, v->p);
        if (!t.has_normals) continue;
        /* n' = (M^-1)^T n, normalized */
        if (vec3_unit_direction(mat4_normal(inv, v->n), &t.n[k]))
            return parse_fail(p, "'trinormal' normal of vertex '%s' degenerates under the current "
                           "transform", p->tok[k + 1]);
    }
    return parse_add_triangle(p, &t);
}

static int cmd_translate(parser *p)
{
    double v[3];
    if (parse_arg_nums(p, 1, 3, v)) return -1;
    return parse_xf_apply(p, mat4_translate(vec3_make(v[0], v[1], v[2])));
}

static int cmd_rotate(parser *p)
{
    double v[4];
    if (parse_arg_nums(p, 1, 4, v)) return -1;
    vec3 axis = vec3_make(v[0], v[1], v[2]), unit;
    /* only the direction counts: 1e-300 and 1e300 are axes too (vec3_length underflows or
     * overflows there) */
    if (vec3_unit_direction(axis, &unit)) return parse_fail(p, "'rotate' axis is zero");
    return parse_xf_apply(p, mat4_rotate(axis, v[3]));
}

static int cmd_scale(parser *p)
{
    double v[3];
    if (parse_arg_nums(p, 1, 3, v)) return -1;
    /* a zero factor is allowed here; it is an error only where an inverse is needed */
    return parse_xf_apply(p, mat4_scale(vec3_make(v[0], v[1], v[2])));
}

/* Lights are in world space: the current transform does not apply (docs/scene-format.md). */
static int cmd_directional(parser *p)
{
    double v[3];
    scene_light l;
    memset(&l, 0, sizeof l);
    if (parse_arg_nums(p, 1, 3, v) || parse_arg_rgb(p, 4, &l.color)) return -1;
    /* only the direction counts, at any length: vec3_length overflows for 1e200 (normalized
     * to 0: a light that lit nothing) and underflows for 1e-170 (refused as zero) */
    if (vec3_unit_direction(vec3_make(v[0], v[1], v[2]), &l.dir)) return parse_fail(p, "'directional' direction is zero");
    l.kind = LIGHT_DIRECTIONAL;
    return parse_add_light(p, &l);
}

static int cmd_point(parser *p)
{
    double v[3];
    scene_light l;
    memset(&l, 0, sizeof l);
    if (parse_arg_nums(p, 1, 3, v) || parse_arg_rgb(p, 4, &l.color)) return -1;
    l.kind = LIGHT_POINT;
    l.pos = vec3_make(v[0], v[1], v[2]);
    memcpy(l.atten, p->atten, sizeof l.atten); /* the attenuation current when read */
    return parse_add_light(p, &l);
}

static int cmd_attenuation(parser *p)
{
    double v[3];
    for (int k = 0; k < 3; k++)
        if (parse_arg_nonneg(p, k + 1, 0, &v[k])) return -1;
    /* point lights are divided by c + l d + q d^2: all zero would divide by zero */
    if (v[0] == 0 && v[1] == 0 && v[2] == 0) return parse_fail(p, "'attenuation' is all zero");
    memcpy(p->atten, v, sizeof v);
    return 0;
}

static int cmd_colour(parser *p)
{
    rgb c;
    if (parse_arg_rgb(p, 1, &c)) return -1;
    const char *k = p->tok[0];
    if (strcmp(k, "ambient") == 0) p->mat.ambient = c;
    else if (strcmp(k, "diffuse") == 0) p->mat.diffuse = c;
    else if (strcmp(k, "specular") == 0) p->mat.specular = c;
    else p->mat.emission = c;
    return 0;
}

static int cmd_shininess(parser *p) { return parse_arg_nonneg(p, 1, 0, &p->mat.shininess); }

static int cmd_integrator(parser *p)
{
    /* in the order of integrator_kind */
    static const char *const w[] = {"raytracer", "analyticdirect", "direct", "pathtracer",
                                    "prefiltered"};
    int k = 0;
    if (parse_arg_word(p, w, 5, &k)) return -1;
    p->sc->integrator = (integrator_kind)k;
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

static int cmd_quadlight(parser *p)
{
    double v[9];
    scene_light l;
    memset(&l, 0, sizeof l);
    if (parse_arg_nums(p, 1, 9, v) || parse_arg_rgb(p, 10, &l.color)) return -1;
    l.kind = LIGHT_QUAD;
    l.pos = vec3_make(v[0], v[1], v[2]);
    l.ab = vec3_make(v[3], v[4], v[5]);
    l.ac = vec3_make(v[6], v[7], v[8]);
    /* area = |ab x ac| = |ab| |ac| sin(angle) */
    double area = vec3_length(vec3_cross(l.ab, l.ac));
    if (!(area > QUAD_PARALLEL_EPS * vec3_length(l.ab) * vec3_length(l.ac)))
        return parse_fail(p, "'quadLight' has zero area (edges ab and ac are zero or parallel)");
    if (!p->first_quad_line) p->first_quad_line = p->line;
    return parse_add_light(p, &l);
}

static int cmd_lightsamples(parser *p)
{
    long n = 0;
    if (parse_arg_int(p, 1, 1, SCENE_MAX_LIGHTSAMPLES, &n)) return -1;
    p->sc->lightsamples = (int)n;
    return 0;
}

static int cmd_lightstratify(parser *p) { return parse_arg_onoff(p, &p->sc->lightstratify); }

static int cmd_lightselection(parser *p)
{
    static const char *const w[] = {"all", "power"}; /* light_selection order */
    int k = 0;
    if (parse_arg_word(p, w, 2, &k)) return -1;
    p->sc->lightselection = (light_selection)k;
    return 0;
}

static int cmd_spp(parser *p)
{
    long n = 0;
    if (parse_arg_int(p, 1, 1, SCENE_MAX_SPP, &n)) return -1;
    p->sc->spp = (int)n;
    return 0;
}

static int cmd_nee(parser *p)
{
    static const char *const w[] = {"off", "on", "mis"}; /* nee_mode order */
    int k = 0;
    if (parse_arg_word(p, w, 3, &k)) return -1;
    p->sc->nee = (nee_mode)k;
    return 0;
}

static int cmd_russianroulette(parser *p) { return parse_arg_onoff(p, &p->sc->russianroulette); }

static int cmd_importancesampling(parser *p)
{
    static const char *const w[] = {"hemisphere", "cosine", "brdf"}; /* sampling_kind order */
    int k = 0;
    if (parse_arg_word(p, w, 3, &k)) return -1;
    p->sc->importancesampling = (sampling_kind)k;
    return 0;
}

static int cmd_brdf(parser *p)
{
    static const char *const w[] = {"phong", "ggx", "mirror", "glass"}; /* brdf_kind order */
    int k = 0;
    if (parse_arg_word(p, w, 4, &k)) return -1;
    p->mat.brdf = (brdf_kind)k;
    return 0;
}

static int cmd_roughness(parser *p) { return parse_arg_nonneg(p, 1, 0, &p->mat.roughness); }
/* Indices of refraction outside [SCENE_IOR_MIN, SCENE_IOR_MAX] are typing mistakes (water 1.33,
 * glass 1.5, diamond 2.42; an air bubble in water 0.75); far enough out, eta^2 under- or
 * overflows in Fresnel's equations and refraction returns NaN directions */
#define SCENE_IOR_MIN 0.01
#define SCENE_IOR_MAX 100.0
static int cmd_ior(parser *p)
{
    if (parse_arg_nonneg(p, 1, 1, &p->mat.ior)) return -1;
    if (!(p->mat.ior >= SCENE_IOR_MIN && p->mat.ior <= SCENE_IOR_MAX))
        return parse_fail(p, "'ior' must be from %g to %g, got '%s'", SCENE_IOR_MIN, SCENE_IOR_MAX, p->tok[1]);
    return 0;
}
/* output encoding c^(1/g): gammas outside [SCENE_GAMMA_MIN, SCENE_GAMMA_MAX] are typing
 * mistakes (the course uses 2.2), refused here rather than after the render by the PNG writer */
#define SCENE_GAMMA_MIN 0.01
#define SCENE_GAMMA_MAX 100.0
static int cmd_gamma(parser *p)
{
    if (parse_arg_nonneg(p, 1, 1, &p->sc->gamma)) return -1;
    if (!(p->sc->gamma >= SCENE_GAMMA_MIN && p->sc->gamma <= SCENE_GAMMA_MAX))
        return parse_fail(p, "'gamma' must be from %g to %g, got '%s'", SCENE_GAMMA_MIN, SCENE_GAMMA_MAX, p->tok[1]);
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

/* the words of `envsampling`, in envsampling_mode order (scene_envsampling_name too) */
static const char *const envsampling_words[] = {"uniform", "cdf", "cdf-sintheta", "mediancut"};
#define N_ENVSAMPLING_WORDS ((int)(sizeof envsampling_words / sizeof envsampling_words[0]))

static int cmd_envsampling(parser *p)
{
    int k = 0;
    if (parse_arg_word(p, envsampling_words, N_ENVSAMPLING_WORDS, &k)) return -1;
    if (k != ENVSAMPLING_MEDIANCUT && p->ntok > 2)
        return parse_fail(p, "'envsampling %s' takes no count (only 'mediancut N' does)", envsampling_words[k]);
    if (p->ntok > 2) {
        long n;
        if (parse_arg_int(p, 2, 1, SCENE_MAX_MEDIANCUT, &n)) return -1;
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
        return parse_fail(p, "'envsamplefraction' must be 'auto' or a number in [0, 1], got '%s'", p->tok[1]);
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

/* 1 if token i reads as a number (finite or not: arg_nonneg then names what is wrong). */
static int token_is_number(const parser *p, int i)
{
    char *end;
    (void)strtod(p->tok[i], &end);
    return end != p->tok[i] && *end == '\0';
}

/* `envmap FILE [SCALE] [latlong|cube|cross|mirrorball|angular|cylindrical|equalarea]` or
 * `envmap cube PX NX PY NY PZ NZ [SCALE]`.  The images are read by finish(). */
static int cmd_envmap(parser *p)
{
    scene_envmap *e = &p->sc->envmap;
    int nargs = p->ntok - 1;
    if (e->present) return parse_fail(p, "envmap given twice (first at line %d)", e->line);
    if (nargs == 0)
        return parse_fail(p, "'envmap' takes FILE [SCALE] [REPRESENTATION] or cube PX NX PY NY PZ NZ "
                       "[SCALE], got no arguments");
    double scale = 1.0;
    int six = strcmp(p->tok[1], "cube") == 0 && nargs > 1;
    if (six) {
        if (nargs != 7 && nargs != 8)
            return parse_fail(p, "'envmap cube' takes six face files PX NX PY NY PZ NZ and an optional "
                           "scale, got %d argument%s", nargs - 1, nargs == 2 ? "" : "s");
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
                return parse_fail(p, "'envmap' representation must be 'latlong', 'cube', 'cross', "
                               "'mirrorball', 'angular', 'cylindrical' or 'equalarea', got '%s'",
                            p->tok[i]);
            e->kind = kind;
            e->kind_given = 1;
            i++;
        }
        if (i <= nargs)
            return parse_fail(p, "'envmap FILE' takes a scale and a representation at most, got '%s' "
                           "after them", p->tok[i]);
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

/* ---- texture mapping (envtex) ----------------------------------------------------------- */

static int cmd_vertextex(parser *p)
{
    double v[5];
    if (parse_arg_nums(p, 1, 5, v)) return -1;
    if (p->n_vtex >= p->max_prims)
        return parse_fail(p, "more than %ld textured vertices", p->max_prims);
    if (parse_grow(p, (void **)&p->vtex, &p->cap_vtex, p->n_vtex + 1, sizeof *p->vtex,
             "textured vertices"))
        return -1;
    p->vtex[p->n_vtex++] = (vertex_tex){vec3_make(v[0], v[1], v[2]), {v[3], v[4]}};
    return 0;
}

static int cmd_tritex(parser *p)
{
    long idx[3];
    if (parse_tri_indices(p, p->n_vtex, "textured vertices", idx)) return -1;
    triangle t;
    memset(&t, 0, sizeof t);
    t.has_st = 1;
    for (int k = 0; k < 3; k++) {
        const vertex_tex *v = &p->vtex[idx[k]];
        t.q[k] = v->p;
        t.p[k] = mat4_point(&p->xf, v->p);
        t.st[k] = v->st;
    }
    return parse_add_triangle(p, &t);
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
    if (m.n_tris > 0 && parse_grow(p, (void **)&p->sc->triangles, &p->cap_tris,
                             p->sc->n_triangles + m.n_tris, sizeof *p->sc->triangles, "triangles"))
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

static int cmd_texmapping(parser *p)
{
    static const char *const w[] = {"uv", "planar", "cylindrical", "spherical", "cube"};
    int k = 0;
    if (parse_arg_word(p, w, 5, &k)) return -1; /* texmapping_kind order */
    p->mat.texmapping = (texmapping_kind)k;
    p->mat.texmapping_given = 1;
    return 0;
}

static int cmd_texfilter(parser *p)
{
    static const char *const w[] = {"nearest", "bilinear", "trilinear", "ewa"};
    int k = 0;
    if (parse_arg_word(p, w, 4, &k)) return -1; /* texture_filter order */
    p->mat.texfilter = (texture_filter)k;
    return 0;
}

/* Texture names are found through a hash index (open addressing, at most half full), so a scene
 * of many `texture` lines reads in linear time: a linear search took 6 s for 20000 textures. */
static size_t name_slot(const parser *p, const char *name)
{
    unsigned long h = 2166136261u; /* FNV-1a */
    for (const unsigned char *c = (const unsigned char *)name; *c; c++) h = (h ^ *c) * 16777619u;
    return (size_t)h & (p->tex_slots - 1);
}

/* Index of the texture called `name`, or -1. */
static int find_texture(const parser *p, const char *name)
{
    if (!p->tex_index) return -1;
    for (size_t k = name_slot(p, name);; k = (k + 1) & (p->tex_slots - 1)) {
        int i = p->tex_index[k];
        if (i < 0 || strcmp(p->sc->textures[i].name, name) == 0) return i;
    }
}

/* Put texture i (stored, named, not yet indexed) in the index, which doubles at half full. */
static int index_texture(parser *p, int i)
{
    if (2 * ((size_t)i + 1) > p->tex_slots) {
        size_t slots = p->tex_slots ? 2 * p->tex_slots : 64;
        int *slot = malloc(slots * sizeof *slot);
        if (!slot) return parse_fail(p, "out of memory for 'texture'");
        for (size_t k = 0; k < slots; k++) slot[k] = -1;
        free(p->tex_index);
        p->tex_index = slot;
        p->tex_slots = slots;
        for (int j = 0; j < i; j++) index_texture(p, j); /* fits: no growth */
    }
    size_t k = name_slot(p, p->sc->textures[i].name);
    while (p->tex_index[k] >= 0) k = (k + 1) & (p->tex_slots - 1);
    p->tex_index[k] = i;
    return 0;
}

/* The numbers after `texture NAME KIND` for each procedural kind, then two colours. */
static int texture_params(parser *p, texture_kind kind, scene_texture *st)
{
    /* arguments after NAME KIND: checker FREQ, perlin SCALE, fbm / turbulence SCALE OCTAVES,
     * marble SCALE FREQUENCY AMPLITUDE OCTAVES, wood SCALE RINGS AMPLITUDE; then c0, c1 */
    static const int nparams[] = {0, 1, 1, 2, 2, 4, 3}; /* texture_kind order */
    static const char *const usage[] = {
        "", "FREQUENCY", "SCALE", "SCALE OCTAVES", "SCALE OCTAVES",
        "SCALE FREQUENCY AMPLITUDE OCTAVES", "SCALE RINGS AMPLITUDE"};
    int np = nparams[kind], nargs = p->ntok - 1;
    if (nargs != 2 + np + 6)
        return parse_fail(p, "'texture NAME %s' takes %s R0 G0 B0 R1 G1 B1 (%d arguments after the "
                       "kind), got %d", texture_kind_name(kind), usage[kind], np + 6, nargs - 2);
    rgb c0, c1;
    if (parse_arg_rgb(p, 3 + np, &c0) || parse_arg_rgb(p, 6 + np, &c1)) return -1;
    error te;
    memset(&te, 0, sizeof te);
    if (kind == TEXTURE_CHECKER) {
        double f;
        if (parse_arg_nonneg(p, 3, 1, &f)) return -1;
        if (texture_init_checker(&st->tex, c0, c1, f, &te)) return parse_fail(p, "%s", te.msg);
        return 0;
    }
    texture_solid_params sp;
    memset(&sp, 0, sizeof sp);
    sp.c0 = c0;
    sp.c1 = c1;
    if (parse_arg_nonneg(p, 3, 1, &sp.scale)) return -1;
    long oct = 0;
    switch (kind) {
    case TEXTURE_FBM:
    case TEXTURE_TURBULENCE:
        if (parse_arg_int(p, 4, 1, PERLIN_MAX_OCTAVES, &oct)) return -1;
        break;
    case TEXTURE_MARBLE:
        if (parse_arg_nonneg(p, 4, 0, &sp.frequency) || parse_arg_num(p, 5, &sp.amplitude) ||
            parse_arg_int(p, 6, 1, PERLIN_MAX_OCTAVES, &oct))
            return -1;
        break;
    case TEXTURE_WOOD:
        if (parse_arg_nonneg(p, 4, 0, &sp.rings) || parse_arg_num(p, 5, &sp.amplitude)) return -1;
        break;
    default: break;
    }
    sp.octaves = (int)oct;
    if (texture_init_solid(&st->tex, kind, &sp, &te)) return parse_fail(p, "%s", te.msg);
    return 0;
}

/* `texture NAME FILE [repeat|clamp|mirror]` or `texture NAME KIND PARAMS... R0 G0 B0 R1 G1 B1`.
 * A kind keyword wins over a file of that name (write ./checker for the file). */
static int cmd_texture(parser *p)
{
    const char *name = p->tok[1];
    if (strlen(name) >= SCENE_MAX_TEXTURE_NAME)
        return parse_fail(p, "'texture' name '%s' is longer than %d bytes", name,
                    SCENE_MAX_TEXTURE_NAME - 1);
    int prev = find_texture(p, name);
    if (prev >= 0)
        return parse_fail(p, "texture '%s' defined twice (first at line %d)", name,
                    p->sc->textures[prev].line);
    if (p->sc->n_textures >= p->max_prims)
        return parse_fail(p, "more than %ld textures", p->max_prims);
    scene_texture st;
    memset(&st, 0, sizeof st);
    memcpy(st.name, name, strlen(name) + 1);
    st.line = p->line;
    st.image = -1;
    texture_kind kind;
    if (texture_kind_parse(p->tok[2], &kind) == 0) {
        if (texture_params(p, kind, &st)) return -1;
    } else {
        if (p->ntok - 1 > 3)
            return parse_fail(p, "'texture NAME FILE' takes a wrap mode at most, got '%s' after it",
                        p->tok[4]);
        st.wrap = WRAP_REPEAT;
        if (p->ntok - 1 == 3 && texlookup_wrap_parse(p->tok[3], &st.wrap))
            return parse_fail(p, "'texture' wrap mode must be 'repeat', 'clamp' or 'mirror', got '%s'",
                        p->tok[3]);
        const char *file = p->tok[2];
        if (strlen(file) >= sizeof st.token)
            return parse_fail(p, "'texture' file name is longer than %zu bytes", sizeof st.token - 1);
        if (parse_relative_path(p, file, st.path, sizeof st.path)) return -1;
        memcpy(st.token, file, strlen(file) + 1);
        st.tex.kind = TEXTURE_IMAGE; /* the image is read by assets_load_textures */
        st.tex.wrap = st.wrap;
    }
    scene *sc = p->sc;
    long cap = p->cap_textures;
    if (parse_grow(p, (void **)&sc->textures, &cap, (long)sc->n_textures + 1, sizeof *sc->textures,
             "textures"))
        return -1;
    p->cap_textures = cap;
    sc->textures[sc->n_textures++] = st;
    return index_texture(p, sc->n_textures - 1);
}

/* diffusemap, specularmap, roughnessmap, emissionmap NAME; bumpmap NAME STRENGTH;
 * displacementmap NAME SCALE: material state naming a texture defined before. */
static int cmd_map(parser *p)
{
    int i = find_texture(p, p->tok[1]);
    if (i < 0)
        return parse_fail(p, "'%s': unknown texture '%s' (define it with 'texture' first)", p->tok[0],
                    p->tok[1]);
    double amount = 0;
    if (p->ntok - 1 == 2 && parse_arg_num(p, 2, &amount)) return -1;
    const char *k = p->tok[0];
    int ref = i + 1; /* 0 means none */
    if (strcmp(k, "diffusemap") == 0) p->mat.diffusemap = ref;
    else if (strcmp(k, "specularmap") == 0) p->mat.specularmap = ref;
    else if (strcmp(k, "roughnessmap") == 0) p->mat.roughnessmap = ref;
    else if (strcmp(k, "emissionmap") == 0) p->mat.emissionmap = ref;
    else if (strcmp(k, "bumpmap") == 0) {
        p->mat.bumpmap = ref;
        p->mat.bump_strength = amount;
    } else {
        p->mat.displacementmap = ref;
        p->mat.displacement_scale = amount;
    }
    return 0;
}

static int cmd_nomaps(parser *p)
{
    p->mat.diffusemap = p->mat.specularmap = p->mat.roughnessmap = 0;
    p->mat.emissionmap = p->mat.bumpmap = p->mat.displacementmap = 0;
    p->mat.bump_strength = p->mat.displacement_scale = 0;
    return 0;
}

typedef struct command {
    const char *name;
    int (*run)(parser *p);
    int min_args, max_args;
} command;

/* Geometry first: it is most of the lines of a big scene. */
static const command commands[] = {
    {"vertex", cmd_vertex, 3, 3},
    {"tri", cmd_tri, 3, 3},
    {"vertexnormal", cmd_vertexnormal, 6, 6},
    {"trinormal", cmd_trinormal, 3, 3},
    {"sphere", cmd_sphere, 4, 4},
    {"vertextex", cmd_vertextex, 5, 5},
    {"tritex", cmd_tritex, 3, 3},
    {"obj", cmd_obj, 1, 1},
    {"texmapping", cmd_texmapping, 1, 1},
    {"texture", cmd_texture, 2, 12}, /* cmd_texture checks each kind's count */
    {"texfilter", cmd_texfilter, 1, 1},
    {"diffusemap", cmd_map, 1, 1},
    {"specularmap", cmd_map, 1, 1},
    {"roughnessmap", cmd_map, 1, 1},
    {"emissionmap", cmd_map, 1, 1},
    {"bumpmap", cmd_map, 2, 2},
    {"displacementmap", cmd_map, 2, 2},
    {"nomaps", cmd_nomaps, 0, 0},
    {"size", cmd_size, 2, 2},
    {"maxdepth", cmd_maxdepth, 1, 1},
    {"output", cmd_output, 1, 1},
    {"camera", cmd_camera, 10, 10},
    {"maxverts", cmd_maxverts, 1, 1},
    {"maxvertnorms", cmd_maxverts, 1, 1},
    {"translate", cmd_translate, 3, 3},
    {"rotate", cmd_rotate, 4, 4},
    {"scale", cmd_scale, 3, 3},
    {"pushTransform", parse_xf_push, 0, 0},
    {"popTransform", parse_xf_pop, 0, 0},
    {"directional", cmd_directional, 6, 6},
    {"point", cmd_point, 6, 6},
    {"attenuation", cmd_attenuation, 3, 3},
    {"ambient", cmd_colour, 3, 3},
    {"diffuse", cmd_colour, 3, 3},
    {"specular", cmd_colour, 3, 3},
    {"emission", cmd_colour, 3, 3},
    {"shininess", cmd_shininess, 1, 1},
    {"integrator", cmd_integrator, 1, 1},
    {"quadLight", cmd_quadlight, 12, 12},
    {"lightsamples", cmd_lightsamples, 1, 1},
    {"lightstratify", cmd_lightstratify, 1, 1},
    {"lightselection", cmd_lightselection, 1, 1},
    {"spp", cmd_spp, 1, 1},
    {"nexteventestimation", cmd_nee, 1, 1},
    {"russianroulette", cmd_russianroulette, 1, 1},
    {"importancesampling", cmd_importancesampling, 1, 1},
    {"brdf", cmd_brdf, 1, 1},
    {"roughness", cmd_roughness, 1, 1},
    {"gamma", cmd_gamma, 1, 1},
    {"envmap", cmd_envmap, 0, MAX_TOKENS - 2}, /* cmd_envmap checks the two forms itself */
    {"envmiss", cmd_envmiss, 1, 1},
    {"ior", cmd_ior, 1, 1},
    {"envsampling", cmd_envsampling, 1, 2},
    {"envsampler", cmd_envsampler, 1, 1},
    {"envsamplefraction", cmd_envsamplefraction, 1, 1},
    {"prefilter", cmd_prefilter, 1, 1},
};

/* The forms of a command whose handler checks its own argument counts, for a count outside
 * [min_args, max_args]: "'texture' takes 2 or 12 arguments" would misstate what it takes.
 * NULL for the others ("N arguments", "N or M arguments" say it). */
static const char *command_forms(const command *c)
{
    if (c->run == cmd_texture) return "NAME FILE [WRAP] or NAME KIND PARAMS... R0 G0 B0 R1 G1 B1";
    if (c->run == cmd_envmap)
        return "FILE [SCALE] [REPRESENTATION] or cube PX NX PY NY PZ NZ [SCALE]";
    return NULL;
}

/* ---- lines ------------------------------------------------------------------------------ */

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/* Split the NUL-terminated line in place; a token starting with '#' ends the line. */
static void tokenize(parser *p, char *s)
{
    p->ntok = 0;
    for (;;) {
        while (is_space(*s)) s++;
        if (*s == '\0' || *s == '#') return;
        if (p->ntok < MAX_TOKENS) p->tok[p->ntok] = s;
        p->ntok++;
        while (*s && !is_space(*s)) s++;
        if (*s == '\0') return;
        *s++ = '\0';
    }
}

static int run_line(parser *p)
{
    if (p->ntok == 0) return 0;
    const char *name = p->tok[0];
    const command *c = NULL;
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(name, commands[i].name) == 0) {
            c = &commands[i];
            break;
        }
    if (!c) {
        if (p->strict) return parse_fail(p, "unknown command '%s'", name);
        parse_warn(p, "unknown command '%s' (ignored)", name);
        return 0;
    }
    if (c->run == cmd_size) {
        p->seen_size = 1;
    } else if (!p->seen_size && !p->warned_order) {
        p->warned_order = 1;
        parse_warn(p, "'%s' comes before 'size' (the course puts 'size' first)", name);
    }
    int nargs = p->ntok - 1;
    if (nargs < c->min_args || nargs > c->max_args) {
        if (command_forms(c))
            return parse_fail(p, "'%s' takes %s, got %d argument%s", name, command_forms(c), nargs,
                        nargs == 1 ? "" : "s");
        char takes[64];
        if (c->min_args == c->max_args)
            snprintf(takes, sizeof takes, "%d argument%s", c->min_args,
                     c->min_args == 1 ? "" : "s");
        else
            snprintf(takes, sizeof takes, "%d or %d arguments", c->min_args, c->max_args);
        if (nargs > c->max_args)
            return parse_fail(p, "'%s' takes %s, got %d (from '%s' on)", name, takes, nargs,
                        p->tok[c->max_args + 1]);
        return parse_fail(p, "'%s' takes %s, got %d", name, takes, nargs);
    }
    return c->run(p);
}

/* After the last line: what a renderer needs, then the envmap image. */
static int finish(parser *p)
{
    scene *sc = p->sc;
    p->line = 0;
    if (!p->seen_size) return error_set(p->err, p->name, 0, "no 'size' command");
    if (!sc->has_camera) return error_set(p->err, p->name, 0, "no 'camera' command");
    long long samples = (long long)sc->width * sc->height * sc->spp;
    if (samples > SCENE_MAX_CAMERA_SAMPLES)
        return error_set(p->err, p->name, 0,
                         "size %d x %d at spp %d asks for %lld camera samples, over the limit of 2^34",
                         sc->width, sc->height, sc->spp, samples);
    if (p->depth > 0)
        parse_warn(p, "%d 'pushTransform' without 'popTransform' at the end of the file", p->depth);
    if (p->first_quad_line && sc->integrator == INTEGRATOR_RAYTRACER) { /* hw1's renderer with hw2's light */
        p->line = p->first_quad_line;
        parse_warn(p, "the 'raytracer' integrator ignores quad lights (they neither light, show nor block): "
                "use 'integrator analyticdirect', 'direct' or 'pathtracer'");
        p->line = 0;
    }
    if (p->first_delta_line && sc->integrator == INTEGRATOR_ANALYTICDIRECT) { /* hw2's renderer with hw1's lights */
        p->line = p->first_delta_line;
        parse_warn(p, "the 'analyticdirect' integrator lights with quad lights only: point and directional "
                "lights are ignored (use 'integrator direct' or 'pathtracer', which sample them)");
        p->line = 0;
    }
    if (p->first_delta_line && sc->integrator == INTEGRATOR_PATHTRACER && sc->nee == NEE_OFF) {
        p->line = p->first_delta_line; /* a path never hits a point: only NEE reaches one */
        parse_warn(p, "with 'nexteventestimation off' the path tracer never reaches point or directional "
                "lights (no path can hit one): they light nothing; use 'nexteventestimation on' or 'mis'");
        p->line = 0;
    }
    if ((p->first_quad_line || p->first_delta_line) && sc->integrator == INTEGRATOR_PREFILTERED) {
        int a = p->first_quad_line, b = p->first_delta_line; /* the first light of either kind */
        p->line = a && (!b || a < b) ? a : b;
        parse_warn(p, "the 'prefiltered' integrator lights with the envmap's prefiltered maps only: "
                "point, directional and quad lights are ignored (use 'integrator direct' or "
                "'pathtracer')");
        p->line = 0;
    }
    if (p->load_images && assets_load_textures(p)) return -1;
    if (sc->envmap.present && p->load_images && assets_load_envmap(p)) return -1;
    return 0;
}

static void scene_init(scene *sc)
{
    memset(sc, 0, sizeof *sc);
    snprintf(sc->output, sizeof sc->output, "raytrace.png");
    sc->maxdepth = 5;
    sc->integrator = INTEGRATOR_RAYTRACER;
    sc->spp = 1;
    sc->lightsamples = 1;
    sc->lightselection = LIGHTSELECTION_ALL;
    sc->nee = NEE_OFF;
    sc->importancesampling = SAMPLING_HEMISPHERE;
    sc->envmiss = ENVMISS_ENVMAP;
    sc->envsampling = ENVSAMPLING_CDF;
    sc->mediancut_lights = 64;
    sc->envsampler = ENVSAMPLER_BINARY;
    sc->envsamplefraction = -1; /* auto */
    sc->envmap.scale = 1.0;
    sc->envmap.xf = mat4_identity();
    sc->envmap.inv = mat4_identity();
    sc->fovy = 0;
}

/* Where the lines come from: a string (text, len), or a file read a chunk at a time, so that a
 * scene is checked as it arrives: /dev/zero or a binary file fails at its first NUL byte or
 * over-long line, not when memory runs out. */
#define SCENE_READ_CHUNK (1 << 16)
typedef struct line_source {
    FILE *f;           /* NULL for a string */
    const char *chunk; /* the string, or `buf` below for a file */
    size_t len, pos;   /* bytes in chunk, and the next one to read */
    int eof;           /* nothing more to come after chunk */
    char *buf;         /* a file's chunk buffer (SCENE_READ_CHUNK bytes) */
} line_source;

/* The next line (without its '\n') into line[0..n-1], NUL-terminated; line has room for
 * SCENE_MAX_LINE + 4 bytes (a first line may carry a 3-byte byte-order mark).  Returns 1 for a
 * line, 0 at the end, -1 on error: a NUL byte or a line over SCENE_MAX_LINE bytes (reported at
 * the parser's current line), or a read error (reported for the file, line 0). */
static int next_line(parser *p, line_source *src, char *line, size_t *n_out)
{
    size_t n = 0, limit = SCENE_MAX_LINE + (p->line == 1 ? 3 : 0);
    int any = 0; /* a byte of this line (or its '\n') was read */
    for (;;) {
        if (src->pos == src->len) {
            if (src->eof || !src->f) break;
            src->len = fread(src->buf, 1, SCENE_READ_CHUNK, src->f);
            src->pos = 0;
            if (src->len == 0) {
                if (ferror(src->f)) /* the file's fault, not a line's: no line number */
                    return error_set(p->err, p->name, 0, "cannot read: %s", strerror(errno));
                src->eof = 1;
            }
            continue;
        }
        const char *start = src->chunk + src->pos;
        size_t avail = src->len - src->pos;
        const char *nl = memchr(start, '\n', avail);
        size_t take = nl ? (size_t)(nl - start) : avail;
        any = 1;
        if (take > limit - n) return parse_fail(p, "line is longer than %d bytes", SCENE_MAX_LINE);
        if (memchr(start, '\0', take)) return parse_fail(p, "NUL byte in the file (binary file?)");
        memcpy(line + n, start, take);
        n += take;
        src->pos += take + (nl != NULL);
        if (nl) break;
    }
    if (!any) return 0;
    line[n] = '\0';
    /* a UTF-8 byte-order mark some editors write is not part of the first keyword */
    if (p->line == 1 && n >= 3 && memcmp(line, "\xEF\xBB\xBF", 3) == 0) {
        memmove(line, line + 3, n - 2);
        n -= 3;
    }
    if (n > SCENE_MAX_LINE) return parse_fail(p, "line is longer than %d bytes", SCENE_MAX_LINE);
    *n_out = n;
    return 1;
}

/* A parser for scene *sc (not touched here) at the file's start: identity transform, the
 * default material, attenuation 1 0 0, the options copied. */
static void parser_init(parser *p, scene *sc, const scene_load_opts *opts, const char *name,
                        error *err)
{
    memset(p, 0, sizeof *p);
    p->sc = sc;
    p->strict = opts->strict;
    p->warn = opts->warn;
    p->warn_ctx = opts->warn_ctx;
    p->load_images = opts->load_images;
    p->mem = opts->mem;
    p->name = name ? name : "<string>";
    p->err = err;
    p->xf = mat4_identity();
    p->mat = scene_default_material();
    p->atten[0] = 1.0; /* attenuation 1 0 0: no fall-off */
    p->max_prims = opts->max_prims > 0 && opts->max_prims < SCENE_MAX_PRIMS ? opts->max_prims
                                                                           : SCENE_MAX_PRIMS;
}

/* The scene's path (sc->path) and the folder its relative file names are read from (p->base),
 * from `name` ("-" or NULL: the working folder). */
static int scene_paths(parser *p, const char *name)
{
    scene *out = p->sc;
    if (!name) return 0;
    if (strcmp(name, "-") == 0) {
        memcpy(out->path, "-", 2);
        return 0;
    }
    size_t n = strlen(name);
    if (n >= sizeof out->path)
        return error_set(p->err, name, 0, "scene path is longer than %zu bytes",
                         sizeof out->path - 1);
    memcpy(out->path, name, n + 1);
    const char *slash = strrchr(name, '/');
    if (!slash) return 0;
    size_t b = (size_t)(slash - name) + 1;
    if (b >= sizeof p->base)
        return error_set(p->err, name, 0, "scene folder is longer than %zu bytes",
                         sizeof p->base - 1);
    memcpy(p->base, name, b);
    p->base[b] = '\0';
    return 0;
}

/* Parse the lines of `src` into *out. */
static int load_lines(line_source *src, const char *name, const scene_load_opts *opts, scene *out,
                      error *err)
{
    scene_load_opts defaults = scene_load_defaults();
    parser p;
    parser_init(&p, out, opts ? opts : &defaults, name, err);
    scene_init(out);
    int rc = -1;
    char *buf = NULL;
    if (scene_paths(&p, name)) goto done;
    buf = malloc(SCENE_MAX_LINE + 4);
    if (!buf) {
        error_set(err, p.name, 0, "out of memory");
        goto done;
    }
    for (;;) {
        p.line++;
        size_t n;
        int got = next_line(&p, src, buf, &n);
        if (got < 0) goto done;
        if (got == 0) break; /* the end (finish() sets the line to 0) */
        tokenize(&p, buf);
        if (run_line(&p)) goto done;
    }
    if (finish(&p)) goto done;
    rc = 0;
done:
    free(buf);
    parse_free(&p);
    if (rc) scene_free(out);
    return rc;
}

/* ---- public ----------------------------------------------------------------------------- */

scene_load_opts scene_load_defaults(void)
{
    scene_load_opts o;
    memset(&o, 0, sizeof o);
    o.load_images = 1;
    return o;
}

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

int scene_load_string(const char *text, const char *name, const scene_load_opts *opts, scene *out,
                      error *err)
{
    assert(text && out);
    line_source src = {NULL, text, strlen(text), 0, 1, NULL};
    return load_lines(&src, name, opts, out, err);
}

int scene_load(const char *path, const scene_load_opts *opts, scene *out, error *err)
{
    assert(path && out);
    memset(out, 0, sizeof *out);
    infile_id id;
    int fd = infile_open_stream(path, &id, err); /* a regular file or a pipe, never blocking */
    if (fd < 0) return -1;
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        int e = errno;
        close(fd);
        return error_set(err, path, 0, "cannot open: %s", strerror(e));
    }
    int rc = -1;
    char *chunk = malloc(SCENE_READ_CHUNK);
    if (!chunk) {
        error_set(err, path, 0, "out of memory");
    } else {
        line_source src = {f, chunk, 0, 0, 0, chunk};
        rc = load_lines(&src, path, opts, out, err);
    }
    if (rc == 0 && infile_list_add_id(&out->inputs, path, id, err)) { /* the scene's own file */
        scene_free(out);
        rc = -1;
    }
    free(chunk);
    fclose(f);
    return rc;
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
