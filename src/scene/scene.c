/* scene.c - the CSE 167/168 `.test` scene parser plus envtex's commands (see
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

#include "envtex/envlight/sis.h"
#include "envtex/geometry/camera.h"
#include "envtex/io/imageio.h"
#include "envtex/io/obj.h"
#include "envtex/textures/perlin.h"

/* A command has at most 12 arguments (quadLight); a few more slots let us name the first extra
 * token in "takes N arguments, got M" messages. */
#define MAX_TOKENS 16

/* maxverts / maxvertnorms are only capacity hints: a hostile "maxverts 999999999999" must not
 * reserve gigabytes, so a hint reserves at most this many entries (arrays still grow past it). */
#define HINT_CAP (1L << 20)

/* sin of the angle between a quad light's edges below which it is a sliver of no area: rounding
 * of exactly parallel edges leaves |ab x ac| ~ 1e-16 |ab| |ac|. */
#define QUAD_PARALLEL_EPS 1e-12

typedef struct vertex_normal { vec3 p, n; } vertex_normal;
typedef struct vertex_tex { vec3 p; uv2 st; } vertex_tex;

typedef struct parser {
    scene *sc;
    const scene_load_opts *opts;
    const char *name;          /* scene name for messages (err->file) */
    char base[1024];           /* the scene file's folder with its trailing '/', or "" */
    error *err;
    int line;                  /* 1-based line being read */
    /* the current line's tokens: tok[0] is the command */
    char *tok[MAX_TOKENS];
    int ntok;                  /* number of tokens (may exceed MAX_TOKENS: only counted) */
    /* transform state */
    mat4 xf;                   /* object -> world, current */
    mat4 inv;                  /* its inverse when inv_state == 1 */
    int inv_state;             /* 0 not computed, 1 valid, -1 singular */
    mat4 *stack;               /* saved transforms (pushTransform) */
    int depth, stack_cap;
    int first_quad_line;       /* the first `quadLight`, for the raytracer's warning (finish) */
    int first_delta_line;      /* the first `point` or `directional`, for analyticdirect's */
    /* material and light state */
    material mat;
    double atten[3];
    /* vertex lists (the scene keeps only world-space triangles) */
    vec3 *verts;
    long n_verts, cap_verts;
    vertex_normal *vnorms;
    long n_vnorms, cap_vnorms;
    vertex_tex *vtex;          /* `vertextex`: a third list, for `tritex` */
    long n_vtex, cap_vtex;
    /* capacities of the scene's arrays */
    long cap_spheres, cap_tris;
    long cap_lights, cap_materials;
    long cap_textures;
    /* bookkeeping */
    long max_prims;            /* SCENE_MAX_PRIMS unless the options lower it */
    struct parsed_obj {        /* each OBJ file read so far, parsed once (cmd_obj) */
        infile_id id;
        obj_mesh mesh;
    } *objs;
    int n_objs, cap_objs;
    int *tex_index;            /* texture names: slots of indices into sc->textures, -1 empty */
    size_t tex_slots;          /* a power of two, or 0 */
    int seen_size, warned_order;
    char envmap_token[CUBEMAP_FACES][1024]; /* the envmap file name(s) as written, for messages */
} parser;

/* ---- messages --------------------------------------------------------------------------- */

static int fail(parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(parser *p, const char *fmt, ...)
{
    char msg[ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return error_set(p->err, p->name, p->line, "%s", msg);
}

static void warn(parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void warn(parser *p, const char *fmt, ...)
{
    if (!p->opts->warn) return;
    error w;
    char msg[ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    error_set(&w, p->name, p->line, "%s", msg);
    p->opts->warn(p->opts->warn_ctx, &w);
}

/* ---- growing arrays --------------------------------------------------------------------- */

/* Make room for `need` elements (`what`) of `size` bytes in *arr (capacity *cap), doubling; what
 * the array grows by is charged to the budget first. */
static int grow(parser *p, void **arr, long *cap, long need, size_t size, const char *what)
{
    if (need <= *cap) return 0;
    long n = *cap > 0 ? *cap : 16;
    while (n < need) n *= 2; /* need <= SCENE_MAX_PRIMS, so n stays far below LONG_MAX */
    double more = (double)(n - *cap) * (double)size;
    if (budget_charge(p->opts->mem, more, p->name, p->line, p->err,
                      "room for %ld more %s x %zu bytes", n - *cap, what, size))
        return -1;
    void *q = realloc(*arr, (size_t)n * size);
    if (!q) {
        budget_release(p->opts->mem, more);
        return fail(p, "out of memory for '%s' (%ld entries)", p->tok[0], need);
    }
    *arr = q;
    *cap = n;
    return 0;
}

/* ---- arguments -------------------------------------------------------------------------- */

/* Argument i (1-based) as a finite double: strtod must consume the whole token. */
static int arg_num(parser *p, int i, double *out)
{
    const char *s = p->tok[i];
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0')
        return fail(p, "expected a number for '%s' argument %d, got '%s'", p->tok[0], i, s);
    /* NaN, Inf and overflow ("1e999" gives HUGE_VAL); underflow to a tiny value is harmless */
    if (!isfinite(v))
        return fail(p, "expected a finite number for '%s' argument %d, got '%s'", p->tok[0], i, s);
    *out = v;
    return 0;
}

/* Arguments first..first+n-1 into v[0..n-1]. */
static int arg_nums(parser *p, int first, int n, double *v)
{
    for (int k = 0; k < n; k++)
        if (arg_num(p, first + k, &v[k])) return -1;
    return 0;
}

/* Argument i as an integer in [lo, hi] ("10", "10.0" and "1e1" are 10; "10.5" is an error). */
static int arg_int(parser *p, int i, double lo, double hi, long *out)
{
    double v = 0;
    if (arg_num(p, i, &v)) return -1;
    if (v != floor(v))
        return fail(p, "expected an integer for '%s' argument %d, got '%s'", p->tok[0], i,
                    p->tok[i]);
    if (v < lo || v > hi)
        return fail(p, "'%s' argument %d must be in [%.0f, %.0f], got '%s'", p->tok[0], i, lo, hi,
                    p->tok[i]);
    *out = (long)v;
    return 0;
}

/* Argument i as a number >= 0 (strict = 0) or > 0 (strict = 1). */
static int arg_nonneg(parser *p, int i, int strict, double *out)
{
    if (arg_num(p, i, out)) return -1;
    if (strict ? !(*out > 0) : !(*out >= 0))
        return fail(p, "'%s' argument %d must be %s 0, got '%s'", p->tok[0], i,
                    strict ? ">" : ">=", p->tok[i]);
    return 0;
}

/* Arguments first..first+2 as a colour with every channel >= 0. */
static int arg_rgb(parser *p, int first, rgb *out)
{
    double v[3];
    for (int k = 0; k < 3; k++)
        if (arg_nonneg(p, first + k, 0, &v[k])) return -1;
    *out = rgb_make(v[0], v[1], v[2]);
    return 0;
}

/* Argument 1 as one of `n` keywords (exact, lower case); *out = its index. */
static int arg_word(parser *p, const char *const *words, int n, int *out)
{
    for (int k = 0; k < n; k++)
        if (strcmp(p->tok[1], words[k]) == 0) {
            *out = k;
            return 0;
        }
    char list[256] = "";
    size_t len = 0;
    for (int k = 0; k < n; k++) {
        const char *sep = k == 0 ? "" : k == n - 1 ? " or " : ", ";
        int w = snprintf(list + len, sizeof list - len, "%s'%s'", sep, words[k]);
        if (w < 0 || (size_t)w >= sizeof list - len) break;
        len += (size_t)w;
    }
    return fail(p, "'%s' must be %s, got '%s'", p->tok[0], list, p->tok[1]);
}

static int arg_onoff(parser *p, int *out)
{
    static const char *const w[] = {"off", "on"};
    return arg_word(p, w, 2, out);
}

/* ---- transforms ------------------------------------------------------------------------- */

/* Right-multiply the current transform (OpenGL): the command written last applies first. */
static int xf_apply(parser *p, mat4 m)
{
    mat4 r = mat4_mul(p->xf, m);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(r.m[i][j]))
                return fail(p, "'%s' makes the current transform overflow", p->tok[0]);
    p->xf = r;
    p->inv_state = 0;
    return 0;
}

/* The inverse of the current transform, computed once per change; an error names the command
 * that needs it (a sphere, a trinormal, an envmap) when the transform is singular. */
static int xf_inverse(parser *p, const mat4 **inv)
{
    if (p->inv_state == 0) p->inv_state = mat4_inverse(p->xf, &p->inv) == 0 ? 1 : -1;
    if (p->inv_state < 0)
        return fail(p, "'%s' needs the inverse of the current transform, which is singular "
                       "(a 'scale' by 0?)", p->tok[0]);
    *inv = &p->inv;
    return 0;
}

/* ---- materials -------------------------------------------------------------------------- */

static int rgb_equal(rgb a, rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

static int material_equal(const material *a, const material *b)
{
    return rgb_equal(a->ambient, b->ambient) && rgb_equal(a->diffuse, b->diffuse) &&
           rgb_equal(a->specular, b->specular) && rgb_equal(a->emission, b->emission) &&
           a->shininess == b->shininess && a->brdf == b->brdf && a->roughness == b->roughness &&
           a->ior == b->ior && a->diffusemap == b->diffusemap &&
           a->specularmap == b->specularmap && a->roughnessmap == b->roughnessmap &&
           a->emissionmap == b->emissionmap && a->bumpmap == b->bumpmap &&
           a->displacementmap == b->displacementmap && a->bump_strength == b->bump_strength &&
           a->displacement_scale == b->displacement_scale && a->texmapping == b->texmapping &&
           a->texmapping_given == b->texmapping_given && a->texfilter == b->texfilter;
}

/* Index of the current material state: the last stored one if nothing changed since, else a
 * new entry (so a mesh of 100k triangles with one material stores one material). */
static int material_index(parser *p, int *out)
{
    scene *sc = p->sc;
    if (sc->n_materials > 0 && material_equal(&sc->materials[sc->n_materials - 1], &p->mat)) {
        *out = sc->n_materials - 1;
        return 0;
    }
    if (grow(p, (void **)&sc->materials, &p->cap_materials, (long)sc->n_materials + 1,
             sizeof *sc->materials, "materials"))
        return -1;
    sc->materials[sc->n_materials] = p->mat;
    *out = sc->n_materials++;
    return 0;
}

/* ---- commands --------------------------------------------------------------------------- */
/* Each handler sees p->tok[1..] with the argument count already checked. */

static int cmd_size(parser *p)
{
    long w = 0, h = 0;
    if (arg_int(p, 1, 1, SCENE_MAX_SIZE, &w) || arg_int(p, 2, 1, SCENE_MAX_SIZE, &h)) return -1;
    if (w * h > SCENE_MAX_PIXELS)
        return fail(p, "'size' %ld x %ld is %ld pixels, more than the limit %ld", w, h, w * h,
                    (long)SCENE_MAX_PIXELS);
    p->sc->width = (int)w;
    p->sc->height = (int)h;
    return 0;
}

static int cmd_maxdepth(parser *p)
{
    long d = 0;
    if (arg_int(p, 1, -1, SCENE_MAX_DEPTH, &d)) return -1;
    p->sc->maxdepth = (int)d;
    return 0;
}

static int cmd_output(parser *p)
{
    /* kept as written: relative to the working folder, as the course skeleton does */
    size_t n = strlen(p->tok[1]);
    if (n >= sizeof p->sc->output)
        return fail(p, "'output' file name is longer than %zu bytes", sizeof p->sc->output - 1);
    memcpy(p->sc->output, p->tok[1], n + 1);
    p->sc->output_line = p->line; /* so a refused name points at its line (main.c) */
    return 0;
}

static int cmd_camera(parser *p)
{
    double v[10];
    if (arg_nums(p, 1, 10, v)) return -1;
    vec3 from = vec3_make(v[0], v[1], v[2]), at = vec3_make(v[3], v[4], v[5]);
    vec3 up = vec3_make(v[6], v[7], v[8]);
    if (!(v[9] > 0 && v[9] < 180))
        return fail(p, "'camera' fovy must be in (0, 180) degrees, got '%s'", p->tok[10]);
    vec3 u, v_, w; /* the frame camera_init will build: checked here, with its own arithmetic */
    switch (camera_frame(from, at, up, &u, &v_, &w)) {
    case CAMERA_FRAME_OK: break;
    case CAMERA_FRAME_TOO_FAR:
        return fail(p, "'camera' look-from and look-at are too far apart (their difference overflows)");
    case CAMERA_FRAME_SAME_POINT: return fail(p, "'camera' look-from equals look-at");
    case CAMERA_FRAME_UP_ZERO: return fail(p, "'camera' up vector is zero");
    case CAMERA_FRAME_UP_PARALLEL:
        return fail(p, "'camera' up vector (%s %s %s) is parallel to the view direction",
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
    if (arg_nums(p, 1, 3, v) || arg_nonneg(p, 4, 1, &v[3])) return -1;
    const mat4 *inv = NULL;
    if (xf_inverse(p, &inv)) return -1;
    scene *sc = p->sc;
    if (sc->n_spheres >= p->max_prims)
        return fail(p, "more than %ld spheres", p->max_prims);
    int m;
    if (material_index(p, &m)) return -1;
    if (grow(p, (void **)&sc->spheres, &p->cap_spheres, sc->n_spheres + 1, sizeof *sc->spheres,
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
    if (arg_int(p, 1, 0, 1e18, &n)) return -1;
    if (n > HINT_CAP) n = HINT_CAP;
    if (strcmp(p->tok[0], "maxverts") == 0)
        return grow(p, (void **)&p->verts, &p->cap_verts, n, sizeof *p->verts, "vertices");
    return grow(p, (void **)&p->vnorms, &p->cap_vnorms, n, sizeof *p->vnorms, "vertex normals");
}

static int cmd_vertex(parser *p)
{
    double v[3];
    if (arg_nums(p, 1, 3, v)) return -1;
    if (p->n_verts >= p->max_prims)
        return fail(p, "more than %ld vertices", p->max_prims);
    if (grow(p, (void **)&p->verts, &p->cap_verts, p->n_verts + 1, sizeof *p->verts, "vertices"))
        return -1;
    p->verts[p->n_verts++] = vec3_make(v[0], v[1], v[2]);
    return 0;
}

static int cmd_vertexnormal(parser *p)
{
    double v[6];
    if (arg_nums(p, 1, 6, v)) return -1;
    /* a direction: only its direction is kept (so 1e300 or 1e-300 components work).  A zero
     * normal is kept as zero, not refused: OBJ converters write `vertexnormal 0 0 0 0 0 0` as a
     * placeholder for OBJ's unused index 0; a `trinormal` that uses it is flat shaded. */
    vec3 n;
    if (vec3_unit_direction(vec3_make(v[3], v[4], v[5]), &n)) n = vec3_make(0, 0, 0);
    if (p->n_vnorms >= p->max_prims)
        return fail(p, "more than %ld vertex normals", p->max_prims);
    if (grow(p, (void **)&p->vnorms, &p->cap_vnorms, p->n_vnorms + 1, sizeof *p->vnorms,
             "vertex normals"))
        return -1;
    p->vnorms[p->n_vnorms++] = (vertex_normal){vec3_make(v[0], v[1], v[2]), n};
    return 0;
}

/* The three indices of a tri / trinormal, each in [0, count). */
static int tri_indices(parser *p, long count, const char *list, long idx[3])
{
    for (int k = 0; k < 3; k++) {
        double v = 0;
        if (arg_num(p, k + 1, &v)) return -1;
        if (v != floor(v))
            return fail(p, "expected an integer for '%s' argument %d, got '%s'", p->tok[0], k + 1,
                        p->tok[k + 1]);
        if (v < 0 || v >= (double)count)
            return fail(p, "'%s' vertex index '%s' is out of range: %ld %s defined so far",
                        p->tok[0], p->tok[k + 1], count, list);
        idx[k] = (long)v;
    }
    return 0;
}

/* Swap a triangle's corners 1 and 2 with everything attached to them. */
static void swap_corners_1_2(triangle *t)
{
    triangle c = *t;
    t->p[1] = c.p[2];
    t->p[2] = c.p[1];
    t->n[1] = c.n[2];
    t->n[2] = c.n[1];
    t->st[1] = c.st[2];
    t->st[2] = c.st[1];
    t->q[1] = c.q[2];
    t->q[2] = c.q[1];
}

/* Store triangle t, whose world corners p[] are the current transform of its object corners. */
static int add_triangle(parser *p, const triangle *t)
{
    scene *sc = p->sc;
    for (int k = 0; k < 3; k++)
        if (!vec3_is_finite(t->p[k]))
            return fail(p, "'%s' corner %d overflows under the current transform", p->tok[0], k);
    if (sc->n_triangles >= p->max_prims)
        return fail(p, "more than %ld triangles", p->max_prims);
    int m;
    if (material_index(p, &m)) return -1;
    if (grow(p, (void **)&sc->triangles, &p->cap_tris, sc->n_triangles + 1,
             sizeof *sc->triangles, "triangles"))
        return -1;
    triangle *d = &sc->triangles[sc->n_triangles++];
    *d = *t;
    d->material = m;
    if (!d->has_st) { /* st = (b1, b2): the barycentric coordinates of the corners as written */
        d->st[0] = (uv2){0, 0};
        d->st[1] = (uv2){1, 0};
        d->st[2] = (uv2){0, 1};
    }
    /* A mirroring transform (det < 0) turns the corners clockwise: M e1 x M e2 =
     * det(M) (M^-1)^T (e1 x e2) would point inward, and glass would refract the wrong way.
     * Swapping corners 1 and 2 (with their normals, st and object corners, so every point keeps
     * its attributes) makes e1 x e2 the outward normal again. */
    if (mat4_det3(&p->xf) < 0) swap_corners_1_2(d);
    return 0;
}

static int cmd_tri(parser *p)
{
    long idx[3];
    if (tri_indices(p, p->n_verts, "vertices", idx)) return -1;
    triangle t;
    memset(&t, 0, sizeof t);
    for (int k = 0; k < 3; k++) {
        t.q[k] = p->verts[idx[k]];
        t.p[k] = mat4_point(&p->xf, t.q[k]);
    }
    return add_triangle(p, &t);
}

/* 1 for the zero normal cmd_vertexnormal keeps for a `vertexnormal` written with normal 0 0 0 */
static int is_zero_normal(vec3 n) { return n.x == 0 && n.y == 0 && n.z == 0; }

static int cmd_trinormal(parser *p)
{
    long idx[3];
    if (tri_indices(p, p->n_vnorms, "vertexnormals", idx)) return -1;
    const mat4 *inv = NULL;
    if (xf_inverse(p, &inv)) return -1;
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
            return fail(p, "'trinormal' normal of vertex '%s' degenerates under the current "
                           "transform", p->tok[k + 1]);
    }
    return add_triangle(p, &t);
}

static int cmd_translate(parser *p)
{
    double v[3];
    if (arg_nums(p, 1, 3, v)) return -1;
    return xf_apply(p, mat4_translate(vec3_make(v[0], v[1], v[2])));
}

static int cmd_rotate(parser *p)
{
    double v[4];
    if (arg_nums(p, 1, 4, v)) return -1;
    vec3 axis = vec3_make(v[0], v[1], v[2]), unit;
    /* only the direction counts: 1e-300 and 1e300 are axes too (vec3_length underflows or
     * overflows there) */
    if (vec3_unit_direction(axis, &unit)) return fail(p, "'rotate' axis is zero");
    return xf_apply(p, mat4_rotate(axis, v[3]));
}

static int cmd_scale(parser *p)
{
    double v[3];
    if (arg_nums(p, 1, 3, v)) return -1;
    /* a zero factor is allowed here; it is an error only where an inverse is needed */
    return xf_apply(p, mat4_scale(vec3_make(v[0], v[1], v[2])));
}

static int cmd_push(parser *p)
{
    if (p->depth >= SCENE_MAX_TRANSFORM_STACK)
        return fail(p, "'pushTransform' nested deeper than %d", SCENE_MAX_TRANSFORM_STACK);
    if (p->depth >= p->stack_cap) {
        long cap = p->stack_cap;
        if (grow(p, (void **)&p->stack, &cap, p->depth + 1, sizeof *p->stack, "transforms"))
            return -1;
        p->stack_cap = (int)cap;
    }
    p->stack[p->depth++] = p->xf;
    return 0;
}

static int cmd_pop(parser *p)
{
    if (p->depth == 0) return fail(p, "'popTransform' without a matching 'pushTransform'");
    p->xf = p->stack[--p->depth];
    p->inv_state = 0;
    return 0;
}

static int add_light(parser *p, const scene_light *l)
{
    scene *sc = p->sc;
    if (sc->n_lights >= p->max_prims)
        return fail(p, "more than %ld lights", p->max_prims);
    if (grow(p, (void **)&sc->lights, &p->cap_lights, (long)sc->n_lights + 1, sizeof *sc->lights,
             "lights"))
        return -1;
    sc->lights[sc->n_lights++] = *l;
    if (l->kind != LIGHT_QUAD && !p->first_delta_line) p->first_delta_line = p->line;
    return 0;
}

/* Lights are in world space: the current transform does not apply (docs/scene-format.md). */
static int cmd_directional(parser *p)
{
    double v[3];
    scene_light l;
    memset(&l, 0, sizeof l);
    if (arg_nums(p, 1, 3, v) || arg_rgb(p, 4, &l.color)) return -1;
    /* only the direction counts, at any length: vec3_length overflows for 1e200 (normalized
     * to 0: a light that lit nothing) and underflows for 1e-170 (refused as zero) */
    if (vec3_unit_direction(vec3_make(v[0], v[1], v[2]), &l.dir)) return fail(p, "'directional' direction is zero");
    l.kind = LIGHT_DIRECTIONAL;
    return add_light(p, &l);
}

static int cmd_point(parser *p)
{
    double v[3];
    scene_light l;
    memset(&l, 0, sizeof l);
    if (arg_nums(p, 1, 3, v) || arg_rgb(p, 4, &l.color)) return -1;
    l.kind = LIGHT_POINT;
    l.pos = vec3_make(v[0], v[1], v[2]);
    memcpy(l.atten, p->atten, sizeof l.atten); /* the attenuation current when read */
    return add_light(p, &l);
}

static int cmd_attenuation(parser *p)
{
    double v[3];
    for (int k = 0; k < 3; k++)
        if (arg_nonneg(p, k + 1, 0, &v[k])) return -1;
    /* point lights are divided by c + l d + q d^2: all zero would divide by zero */
    if (v[0] == 0 && v[1] == 0 && v[2] == 0) return fail(p, "'attenuation' is all zero");
    memcpy(p->atten, v, sizeof v);
    return 0;
}

static int cmd_colour(parser *p)
{
    rgb c;
    if (arg_rgb(p, 1, &c)) return -1;
    const char *k = p->tok[0];
    if (strcmp(k, "ambient") == 0) p->mat.ambient = c;
    else if (strcmp(k, "diffuse") == 0) p->mat.diffuse = c;
    else if (strcmp(k, "specular") == 0) p->mat.specular = c;
    else p->mat.emission = c;
    return 0;
}

static int cmd_shininess(parser *p) { return arg_nonneg(p, 1, 0, &p->mat.shininess); }

static int cmd_integrator(parser *p)
{
    /* in the order of integrator_kind */
    static const char *const w[] = {"raytracer", "analyticdirect", "direct", "pathtracer",
                                    "prefiltered"};
    int k = 0;
    if (arg_word(p, w, 5, &k)) return -1;
    p->sc->integrator = (integrator_kind)k;
    return 0;
}

/* `prefilter exact|sh9`: the irradiance map of `integrator prefiltered` */
static int cmd_prefilter(parser *p)
{
    static const char *const w[] = {"exact", "sh9"}; /* irradiance_method order */
    int k = 0;
    if (arg_word(p, w, 2, &k)) return -1;
    p->sc->prefilter = (irradiance_method)k;
    return 0;
}

static int cmd_quadlight(parser *p)
{
    double v[9];
    scene_light l;
    memset(&l, 0, sizeof l);
    if (arg_nums(p, 1, 9, v) || arg_rgb(p, 10, &l.color)) return -1;
    l.kind = LIGHT_QUAD;
    l.pos = vec3_make(v[0], v[1], v[2]);
    l.ab = vec3_make(v[3], v[4], v[5]);
    l.ac = vec3_make(v[6], v[7], v[8]);
    /* area = |ab x ac| = |ab| |ac| sin(angle) */
    double area = vec3_length(vec3_cross(l.ab, l.ac));
    if (!(area > QUAD_PARALLEL_EPS * vec3_length(l.ab) * vec3_length(l.ac)))
        return fail(p, "'quadLight' has zero area (edges ab and ac are zero or parallel)");
    if (!p->first_quad_line) p->first_quad_line = p->line;
    return add_light(p, &l);
}

static int cmd_lightsamples(parser *p)
{
    long n = 0;
    if (arg_int(p, 1, 1, SCENE_MAX_LIGHTSAMPLES, &n)) return -1;
    p->sc->lightsamples = (int)n;
    return 0;
}

static int cmd_lightstratify(parser *p) { return arg_onoff(p, &p->sc->lightstratify); }

static int cmd_lightselection(parser *p)
{
    static const char *const w[] = {"all", "power"}; /* light_selection order */
    int k = 0;
    if (arg_word(p, w, 2, &k)) return -1;
    p->sc->lightselection = (light_selection)k;
    return 0;
}

static int cmd_spp(parser *p)
{
    long n = 0;
    if (arg_int(p, 1, 1, SCENE_MAX_SPP, &n)) return -1;
    p->sc->spp = (int)n;
    return 0;
}

static int cmd_nee(parser *p)
{
    static const char *const w[] = {"off", "on", "mis"}; /* nee_mode order */
    int k = 0;
    if (arg_word(p, w, 3, &k)) return -1;
    p->sc->nee = (nee_mode)k;
    return 0;
}

static int cmd_russianroulette(parser *p) { return arg_onoff(p, &p->sc->russianroulette); }

static int cmd_importancesampling(parser *p)
{
    static const char *const w[] = {"hemisphere", "cosine", "brdf"}; /* sampling_kind order */
    int k = 0;
    if (arg_word(p, w, 3, &k)) return -1;
    p->sc->importancesampling = (sampling_kind)k;
    return 0;
}

static int cmd_brdf(parser *p)
{
    static const char *const w[] = {"phong", "ggx", "mirror", "glass"}; /* brdf_kind order */
    int k = 0;
    if (arg_word(p, w, 4, &k)) return -1;
    p->mat.brdf = (brdf_kind)k;
    return 0;
}

static int cmd_roughness(parser *p) { return arg_nonneg(p, 1, 0, &p->mat.roughness); }
/* Indices of refraction outside [SCENE_IOR_MIN, SCENE_IOR_MAX] are typing mistakes (water 1.33,
 * glass 1.5, diamond 2.42; an air bubble in water 0.75); far enough out, eta^2 under- or
 * overflows in Fresnel's equations and refraction returns NaN directions */
#define SCENE_IOR_MIN 0.01
#define SCENE_IOR_MAX 100.0
static int cmd_ior(parser *p)
{
    if (arg_nonneg(p, 1, 1, &p->mat.ior)) return -1;
    if (!(p->mat.ior >= SCENE_IOR_MIN && p->mat.ior <= SCENE_IOR_MAX))
        return fail(p, "'ior' must be from %g to %g, got '%s'", SCENE_IOR_MIN, SCENE_IOR_MAX, p->tok[1]);
    return 0;
}
/* output encoding c^(1/g): gammas outside [SCENE_GAMMA_MIN, SCENE_GAMMA_MAX] are typing
 * mistakes (the course uses 2.2), refused here rather than after the render by the PNG writer */
#define SCENE_GAMMA_MIN 0.01
#define SCENE_GAMMA_MAX 100.0
static int cmd_gamma(parser *p)
{
    if (arg_nonneg(p, 1, 1, &p->sc->gamma)) return -1;
    if (!(p->sc->gamma >= SCENE_GAMMA_MIN && p->sc->gamma <= SCENE_GAMMA_MAX))
        return fail(p, "'gamma' must be from %g to %g, got '%s'", SCENE_GAMMA_MIN, SCENE_GAMMA_MAX, p->tok[1]);
    return 0;
}

static int cmd_envmiss(parser *p)
{
    static const char *const w[] = {"envmap", "black"}; /* envmiss_mode order */
    int k = 0;
    if (arg_word(p, w, 2, &k)) return -1;
    p->sc->envmiss = (envmiss_mode)k;
    return 0;
}

/* the words of `envsampling`, in envsampling_mode order (scene_envsampling_name too) */
static const char *const envsampling_words[] = {"uniform", "cdf", "cdf-sintheta", "mediancut",
                                                "sis"};
#define N_ENVSAMPLING_WORDS ((int)(sizeof envsampling_words / sizeof envsampling_words[0]))

static int cmd_envsampling(parser *p)
{
    int k = 0;
    if (arg_word(p, envsampling_words, N_ENVSAMPLING_WORDS, &k)) return -1;
    if (k != ENVSAMPLING_MEDIANCUT && k != ENVSAMPLING_SIS && p->ntok > 2)
        return fail(p, "'envsampling %s' takes no count (only 'mediancut N' and 'sis N' do)",
                    envsampling_words[k]);
    if (p->ntok > 2) { /* the count of mediancut's or sis's point lights */
        long n;
        if (arg_int(p, 2, 1, k == ENVSAMPLING_SIS ? SIS_MAX_LIGHTS : SCENE_MAX_MEDIANCUT, &n))
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
    if (arg_word(p, w, 2, &k)) return -1;
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
    if (arg_num(p, 1, &f)) return -1;
    if (!(f >= 0 && f <= 1))
        return fail(p, "'envsamplefraction' must be 'auto' or a number in [0, 1], got '%s'", p->tok[1]);
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
        return fail(p, "'envmap' file name is longer than %zu bytes", token_size - 1);
    const char *base = file[0] == '/' ? "" : p->base;
    int w = snprintf(dst, size, "%s%s", base, file);
    if (w < 0 || (size_t)w >= size)
        return fail(p, "'envmap' path '%s%s' is longer than %zu bytes", base, file, size - 1);
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
    if (e->present) return fail(p, "envmap given twice (first at line %d)", e->line);
    if (nargs == 0)
        return fail(p, "'envmap' takes FILE [SCALE] [REPRESENTATION] or cube PX NX PY NY PZ NZ "
                       "[SCALE], got no arguments");
    double scale = 1.0;
    int six = strcmp(p->tok[1], "cube") == 0 && nargs > 1;
    if (six) {
        if (nargs != 7 && nargs != 8)
            return fail(p, "'envmap cube' takes six face files PX NX PY NY PZ NZ and an optional "
                           "scale, got %d argument%s", nargs - 1, nargs == 2 ? "" : "s");
        if (nargs == 8 && arg_nonneg(p, 8, 1, &scale)) return -1;
    } else {
        int i = 2;
        if (i <= nargs && token_is_number(p, i)) {
            if (arg_nonneg(p, i, 1, &scale)) return -1;
            i++;
        }
        if (i <= nargs) {
            convert_kind kind;
            if (convert_kind_parse(p->tok[i], &kind))
                return fail(p, "'envmap' representation must be 'latlong', 'cube', 'cross', "
                               "'mirrorball', 'angular', 'cylindrical' or 'equalarea', got '%s'",
                            p->tok[i]);
            e->kind = kind;
            e->kind_given = 1;
            i++;
        }
        if (i <= nargs)
            return fail(p, "'envmap FILE' takes a scale and a representation at most, got '%s' "
                           "after them", p->tok[i]);
    }
    const mat4 *inv = NULL;
    if (xf_inverse(p, &inv)) return -1;
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

/* A file name token resolved against the scene file's folder (absolute names are kept). */
static int scene_relative_path(parser *p, const char *file, char *dst, size_t size)
{
    const char *base = file[0] == '/' ? "" : p->base;
    int w = snprintf(dst, size, "%s%s", base, file);
    if (w < 0 || (size_t)w >= size)
        return fail(p, "'%s' path '%s%s' is longer than %zu bytes", p->tok[0], base, file,
                    size - 1);
    return 0;
}

static int cmd_vertextex(parser *p)
{
    double v[5];
    if (arg_nums(p, 1, 5, v)) return -1;
    if (p->n_vtex >= p->max_prims)
        return fail(p, "more than %ld textured vertices", p->max_prims);
    if (grow(p, (void **)&p->vtex, &p->cap_vtex, p->n_vtex + 1, sizeof *p->vtex,
             "textured vertices"))
        return -1;
    p->vtex[p->n_vtex++] = (vertex_tex){vec3_make(v[0], v[1], v[2]), {v[3], v[4]}};
    return 0;
}

static int cmd_tritex(parser *p)
{
    long idx[3];
    if (tri_indices(p, p->n_vtex, "textured vertices", idx)) return -1;
    triangle t;
    memset(&t, 0, sizeof t);
    t.has_st = 1;
    for (int k = 0; k < 3; k++) {
        const vertex_tex *v = &p->vtex[idx[k]];
        t.q[k] = v->p;
        t.p[k] = mat4_point(&p->xf, v->p);
        t.st[k] = v->st;
    }
    return add_triangle(p, &t);
}

/* The mesh of the OBJ file `path` (token: as the line wrote it), parsed on its first `obj` line
 * and kept for the next ones that name the same file, however spelled. */
static int parsed_obj(parser *p, const char *path, const obj_mesh **out)
{
    infile_id id;
    int known = infile_identify(path, &id) == 0;
    for (int i = 0; known && i < p->n_objs; i++)
        if (infile_same(p->objs[i].id, id)) {
            *out = &p->objs[i].mesh;
            return 0;
        }
    obj_mesh m;
    error oe;
    memset(&oe, 0, sizeof oe);
    if (obj_load(path, p->max_prims, &m, p->opts->mem, &oe)) {
        if (oe.line > 0) return fail(p, "obj '%s': %s:%d: %s", p->tok[1], oe.file, oe.line, oe.msg);
        return fail(p, "obj '%s': %s: %s", p->tok[1], oe.file, oe.msg);
    }
    if (!known || infile_list_add_id(&p->sc->inputs, path, id, p->err)) { /* (the file went away) */
        budget_release(p->opts->mem, m.bytes);
        obj_free(&m);
        return known ? -1 : fail(p, "obj '%s': the file changed while it was read", p->tok[1]);
    }
    if (p->n_objs == p->cap_objs) {
        int cap = p->cap_objs > 0 ? 2 * p->cap_objs : 4;
        struct parsed_obj *objs = realloc(p->objs, (size_t)cap * sizeof *objs);
        if (!objs) {
            budget_release(p->opts->mem, m.bytes);
            obj_free(&m);
            return fail(p, "out of memory for 'obj'");
        }
        p->objs = objs;
        p->cap_objs = cap;
    }
    p->objs[p->n_objs] = (struct parsed_obj){id, m};
    *out = &p->objs[p->n_objs++].mesh;
    return 0;
}

/* `obj FILE`: every triangle of the mesh, under the current transform and material.  Corners
 * with vt give st (all three needed), with vn give normals (all three, each non-degenerate under
 * the transform, else the triangle is flat shaded). */
static int cmd_obj(parser *p)
{
    char path[1024];
    if (scene_relative_path(p, p->tok[1], path, sizeof path)) return -1;
    const obj_mesh *mp = NULL;
    if (parsed_obj(p, path, &mp)) return -1;
    const obj_mesh m = *mp;
    if (m.n_tris > p->max_prims - p->sc->n_triangles)
        return fail(p, "obj '%s' has %ld triangles: more than %ld triangles in the scene",
                    p->tok[1], m.n_tris, p->max_prims);
    if (m.n_ignored > 0)
        warn(p, "obj '%s': %ld statement%s ignored (the first, '%s', at %s:%d)", p->tok[1],
             m.n_ignored, m.n_ignored == 1 ? "" : "s", m.first_ignored, path,
             m.first_ignored_line);
    const mat4 *inv = NULL;
    if (m.n_vn > 0 && xf_inverse(p, &inv)) return -1;
    if (m.n_tris > 0 && grow(p, (void **)&p->sc->triangles, &p->cap_tris,
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
        if (add_triangle(p, &t)) return -1;
    }
    return 0;
}

static int cmd_texmapping(parser *p)
{
    static const char *const w[] = {"uv", "planar", "cylindrical", "spherical", "cube"};
    int k = 0;
    if (arg_word(p, w, 5, &k)) return -1; /* texmapping_kind order */
    p->mat.texmapping = (texmapping_kind)k;
    p->mat.texmapping_given = 1;
    return 0;
}

static int cmd_texfilter(parser *p)
{
    static const char *const w[] = {"nearest", "bilinear", "trilinear", "ewa"};
    int k = 0;
    if (arg_word(p, w, 4, &k)) return -1; /* texture_filter order */
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
        if (!slot) return fail(p, "out of memory for 'texture'");
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
        return fail(p, "'texture NAME %s' takes %s R0 G0 B0 R1 G1 B1 (%d arguments after the "
                       "kind), got %d", texture_kind_name(kind), usage[kind], np + 6, nargs - 2);
    rgb c0, c1;
    if (arg_rgb(p, 3 + np, &c0) || arg_rgb(p, 6 + np, &c1)) return -1;
    error te;
    memset(&te, 0, sizeof te);
    if (kind == TEXTURE_CHECKER) {
        double f;
        if (arg_nonneg(p, 3, 1, &f)) return -1;
        if (texture_init_checker(&st->tex, c0, c1, f, &te)) return fail(p, "%s", te.msg);
        return 0;
    }
    texture_solid_params sp;
    memset(&sp, 0, sizeof sp);
    sp.c0 = c0;
    sp.c1 = c1;
    if (arg_nonneg(p, 3, 1, &sp.scale)) return -1;
    long oct = 0;
    switch (kind) {
    case TEXTURE_FBM:
    case TEXTURE_TURBULENCE:
        if (arg_int(p, 4, 1, PERLIN_MAX_OCTAVES, &oct)) return -1;
        break;
    case TEXTURE_MARBLE:
        if (arg_nonneg(p, 4, 0, &sp.frequency) || arg_num(p, 5, &sp.amplitude) ||
            arg_int(p, 6, 1, PERLIN_MAX_OCTAVES, &oct))
            return -1;
        break;
    case TEXTURE_WOOD:
        if (arg_nonneg(p, 4, 0, &sp.rings) || arg_num(p, 5, &sp.amplitude)) return -1;
        break;
    default: break;
    }
    sp.octaves = (int)oct;
    if (texture_init_solid(&st->tex, kind, &sp, &te)) return fail(p, "%s", te.msg);
    return 0;
}

/* `texture NAME FILE [repeat|clamp|mirror]` or `texture NAME KIND PARAMS... R0 G0 B0 R1 G1 B1`.
 * A kind keyword wins over a file of that name (write ./checker for the file). */
static int cmd_texture(parser *p)
{
    const char *name = p->tok[1];
    if (strlen(name) >= SCENE_MAX_TEXTURE_NAME)
        return fail(p, "'texture' name '%s' is longer than %d bytes", name,
                    SCENE_MAX_TEXTURE_NAME - 1);
    int prev = find_texture(p, name);
    if (prev >= 0)
        return fail(p, "texture '%s' defined twice (first at line %d)", name,
                    p->sc->textures[prev].line);
    if (p->sc->n_textures >= p->max_prims)
        return fail(p, "more than %ld textures", p->max_prims);
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
            return fail(p, "'texture NAME FILE' takes a wrap mode at most, got '%s' after it",
                        p->tok[4]);
        st.wrap = WRAP_REPEAT;
        if (p->ntok - 1 == 3 && texlookup_wrap_parse(p->tok[3], &st.wrap))
            return fail(p, "'texture' wrap mode must be 'repeat', 'clamp' or 'mirror', got '%s'",
                        p->tok[3]);
        const char *file = p->tok[2];
        if (strlen(file) >= sizeof st.token)
            return fail(p, "'texture' file name is longer than %zu bytes", sizeof st.token - 1);
        if (scene_relative_path(p, file, st.path, sizeof st.path)) return -1;
        memcpy(st.token, file, strlen(file) + 1);
        st.tex.kind = TEXTURE_IMAGE; /* the image is read by load_textures */
        st.tex.wrap = st.wrap;
    }
    scene *sc = p->sc;
    long cap = p->cap_textures;
    if (grow(p, (void **)&sc->textures, &cap, (long)sc->n_textures + 1, sizeof *sc->textures,
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
        return fail(p, "'%s': unknown texture '%s' (define it with 'texture' first)", p->tok[0],
                    p->tok[1]);
    double amount = 0;
    if (p->ntok - 1 == 2 && arg_num(p, 2, &amount)) return -1;
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
    {"pushTransform", cmd_push, 0, 0},
    {"popTransform", cmd_pop, 0, 0},
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
        if (p->opts->strict) return fail(p, "unknown command '%s'", name);
        warn(p, "unknown command '%s' (ignored)", name);
        return 0;
    }
    if (c->run == cmd_size) {
        p->seen_size = 1;
    } else if (!p->seen_size && !p->warned_order) {
        p->warned_order = 1;
        warn(p, "'%s' comes before 'size' (the course puts 'size' first)", name);
    }
    int nargs = p->ntok - 1;
    if (nargs < c->min_args || nargs > c->max_args) {
        if (command_forms(c))
            return fail(p, "'%s' takes %s, got %d argument%s", name, command_forms(c), nargs,
                        nargs == 1 ? "" : "s");
        char takes[64];
        if (c->min_args == c->max_args)
            snprintf(takes, sizeof takes, "%d argument%s", c->min_args,
                     c->min_args == 1 ? "" : "s");
        else
            snprintf(takes, sizeof takes, "%d or %d arguments", c->min_args, c->max_args);
        if (nargs > c->max_args)
            return fail(p, "'%s' takes %s, got %d (from '%s' on)", name, takes, nargs,
                        p->tok[c->max_args + 1]);
        return fail(p, "'%s' takes %s, got %d", name, takes, nargs);
    }
    return c->run(p);
}

/* An envmap image problem, reported at the `envmap` line: "envmap 'TOKEN' (PATH): why" (the
 * resolved path only when it differs from the token). */
static int envmap_error(parser *p, int face, const char *why)
{
    scene_envmap *e = &p->sc->envmap;
    const char *token = p->envmap_token[face];
    const char *path = e->six_files ? e->face_path[face] : e->path;
    if (strcmp(token, path) == 0)
        return error_set(p->err, p->name, e->line, "envmap '%s': %s", token, why);
    return error_set(p->err, p->name, e->line, "envmap '%s' (%s): %s", token, path, why);
}

/* Read the envmap image(s) and settle the representation: six faces, or one image whose kind
 * was named or is detected from its shape (convert_kind_detect); a cross is split into faces. */
/* Bad texels (NaN, Inf; for radiance also negative) become 0 once, at load, with one warning
 * at the line that named the image. */
static void clean_texels(parser *p, image *im, int line, int radiance, const char *what, const char *token)
{
    long n = radiance ? image_zero_nonfinite_or_negative(im) : image_zero_nonfinite(im);
    if (n == 0) return;
    int saved = p->line;
    p->line = line;
    warn(p, "%s '%s': %ld %s texel value%s (used as 0)", what, token, n,
         radiance ? "NaN, infinite or negative" : "NaN or infinite", n == 1 ? "" : "s");
    p->line = saved;
}

/* The brightest channel value of an image (after clean_texels: finite, >= 0). */
static double brightest(const image *im)
{
    float m = 0;
    for (size_t i = 0; i < 3 * (size_t)im->w * (size_t)im->h; i++) m = im->px[i] > m ? im->px[i] : m;
    return m;
}

/* The scaled envmap must stay a float radiance: scale x the brightest texel <= FLT_MAX.  Past
 * it (`envmap big.pfm 1e300`) the map's radiance is Inf, and Inf x 0 makes NaN pixels.  The n
 * images are cleaned (finite texels), so a scale <= 1 needs no scan. */
static int check_envmap_scale(parser *p, const image *im, int n)
{
    scene_envmap *e = &p->sc->envmap;
    if (e->scale <= 1) return 0;
    double bright = 0;
    for (int f = 0; f < n; f++) bright = fmax(bright, brightest(&im[f]));
    if (!(e->scale * bright <= FLT_MAX)) {
        char why[160];
        snprintf(why, sizeof why, "scale %g times its brightest texel %g is %g, above the largest float "
                 "radiance (%g)", e->scale, bright, e->scale * bright, (double)FLT_MAX);
        return envmap_error(p, 0, why);
    }
    return 0;
}

/* Read envmap image `face` (0 for a one-file map) from `path` into *im, recording the file as an
 * input; a cube face that names the same file as an earlier face copies it (read once). */
static int read_envmap_image(parser *p, int face, const char *path, image *im)
{
    scene_envmap *e = &p->sc->envmap;
    error ie;
    memset(&ie, 0, sizeof ie);
    infile_id id, earlier;
    int known = infile_identify(path, &id) == 0;
    for (int f = 0; known && f < face; f++)
        if (infile_identify(e->face_path[f], &earlier) == 0 && infile_same(id, earlier)) {
            const image *src = &e->cube.face[f];
            double bytes = (double)src->w * src->h * IMAGE_TEXEL_BYTES;
            if (budget_charge(p->opts->mem, bytes, path, 0, &ie, "%d x %d texels x %d bytes",
                              src->w, src->h, IMAGE_TEXEL_BYTES) ||
                image_alloc(im, src->w, src->h, &ie))
                return envmap_error(p, face, ie.msg);
            memcpy(im->px, src->px, (size_t)src->w * (size_t)src->h * IMAGE_TEXEL_BYTES);
            return 0;
        }
    if (imageio_read(path, im, p->opts->mem, &ie)) return envmap_error(p, face, ie.msg);
    if (!known) return envmap_error(p, face, "the file changed while it was read");
    if (infile_list_add_id(&p->sc->inputs, path, id, &ie)) return envmap_error(p, face, ie.msg);
    clean_texels(p, im, e->line, 1, "envmap", p->envmap_token[face]);
    return 0;
}

/* A cross split into its six faces (half its texels), the cross then freed. */
static int split_cross(parser *p)
{
    scene_envmap *e = &p->sc->envmap;
    error ie;
    memset(&ie, 0, sizeof ie);
    double cross = (double)e->img.w * e->img.h * IMAGE_TEXEL_BYTES;
    if (budget_charge(p->opts->mem, cross / 2, e->path, 0, &ie,
                      "six %d x %d cube faces of %d bytes a texel", e->img.w / 4, e->img.w / 4,
                      IMAGE_TEXEL_BYTES) ||
        cubemap_from_cross(&e->img, &e->cube, &ie))
        return envmap_error(p, 0, ie.msg);
    image_free(&e->img);
    budget_release(p->opts->mem, cross);
    return 0;
}

static int load_envmap(parser *p)
{
    scene_envmap *e = &p->sc->envmap;
    error ie;
    memset(&ie, 0, sizeof ie);
    if (e->six_files) {
        for (int f = 0; f < CUBEMAP_FACES; f++) {
            image *im = &e->cube.face[f];
            if (read_envmap_image(p, f, e->face_path[f], im)) return -1;
            char why[128];
            if (im->w != im->h) {
                snprintf(why, sizeof why, "a cube face must be square, not %d x %d", im->w, im->h);
                return envmap_error(p, f, why);
            }
            if (im->w != e->cube.face[0].w) {
                snprintf(why, sizeof why, "cube faces differ in size: %d x %d here, %d x %d for +X",
                         im->w, im->h, e->cube.face[0].w, e->cube.face[0].h);
                return envmap_error(p, f, why);
            }
        }
        e->cube.size = e->cube.face[0].w;
        return check_envmap_scale(p, e->cube.face, CUBEMAP_FACES);
    }
    if (read_envmap_image(p, 0, e->path, &e->img)) return -1;
    if (check_envmap_scale(p, &e->img, 1)) return -1;
    if (!e->kind_given && convert_kind_detect(e->img.w, e->img.h, &e->kind, &ie))
        return envmap_error(p, 0, ie.msg);
    if (e->kind == CONVERT_CUBE && split_cross(p)) return -1;
    if (e->kind == CONVERT_CYLINDRICAL) e->max_height = convert_cylindrical_height(e->img.w, e->img.h);
    return 0;
}

/* "texture 'NAME' file 'TOKEN' (PATH): why" at the `texture` line, the resolved path only when
 * it differs from the token. */
static int texture_file_error(parser *p, const scene_texture *t, const char *why)
{
    if (strcmp(t->token, t->path) == 0)
        return error_set(p->err, p->name, t->line, "texture '%s' file '%s': %s", t->name,
                         t->token, why);
    return error_set(p->err, p->name, t->line, "texture '%s' file '%s' (%s): %s", t->name, t->token,
                     t->path, why);
}

/* Read the image of texture t, or share that of an earlier texture naming the same file (by
 * identity: a.png, ./a.png and a hard link are one file, read once). */
static int load_texture_image(parser *p, scene_texture *t)
{
    scene *sc = p->sc;
    int known = infile_identify(t->path, &t->file) == 0;
    for (int j = 0; known && j < sc->n_textures && &sc->textures[j] != t; j++)
        if (sc->textures[j].image >= 0 && infile_same(sc->textures[j].file, t->file)) {
            t->image = sc->textures[j].image;
            return 0;
        }
    error ie;
    memset(&ie, 0, sizeof ie);
    image *im = &sc->texture_images[sc->n_texture_images];
    if (imageio_read(t->path, im, p->opts->mem, &ie)) return texture_file_error(p, t, ie.msg);
    t->image = sc->n_texture_images++; /* scene_free frees it from here on */
    if (!known) return texture_file_error(p, t, "the file changed while it was read");
    if (infile_list_add_id(&sc->inputs, t->path, t->file, &ie))
        return texture_file_error(p, t, ie.msg);
    clean_texels(p, im, t->line, 0, "texture file", t->token);
    return 0;
}

/* The texture whose pyramid texture i can use: the first with i's image and wrap mode (a mip
 * pyramid depends on nothing else), possibly i itself. */
static int pyramid_owner(const scene *sc, int i)
{
    const scene_texture *t = &sc->textures[i];
    for (int j = 0; j < i; j++)
        if (sc->textures[j].image == t->image && sc->textures[j].wrap == t->wrap) return j;
    return i;
}

/* Read each image texture's file (once per distinct file, however many textures name it),
 * then build the mip pyramids the materials' filters need, one per file and wrap mode (the
 * materials' maps are pointed at the texture that owns it).  Errors are reported at the
 * `texture` line with the reader's reason. */
static int load_textures(parser *p)
{
    scene *sc = p->sc;
    int n_images = 0;
    for (int i = 0; i < sc->n_textures; i++) n_images += sc->textures[i].tex.kind == TEXTURE_IMAGE;
    if (n_images > 0) {
        sc->texture_images = calloc((size_t)n_images, sizeof *sc->texture_images);
        if (!sc->texture_images) return error_set(p->err, p->name, 0, "out of memory for textures");
    }
    for (int i = 0; i < sc->n_textures; i++) {
        scene_texture *t = &sc->textures[i];
        if (t->tex.kind != TEXTURE_IMAGE) continue;
        if (load_texture_image(p, t)) return -1;
        texture_init_image(&t->tex, &sc->texture_images[t->image], t->wrap);
    }
    for (int m = 0; m < sc->n_materials; m++) {
        material *mt = &sc->materials[m];
        int *refs[6] = {&mt->diffusemap, &mt->specularmap, &mt->roughnessmap,
                        &mt->emissionmap, &mt->bumpmap, &mt->displacementmap};
        for (int k = 0; k < 6; k++) {
            if (*refs[k] <= 0) continue;
            if (sc->textures[*refs[k] - 1].image >= 0)
                *refs[k] = pyramid_owner(sc, *refs[k] - 1) + 1;
            scene_texture *t = &sc->textures[*refs[k] - 1];
            error ie;
            memset(&ie, 0, sizeof ie);
            if (texture_prepare(&t->tex, mt->texfilter, p->opts->mem, &ie))
                return error_set(p->err, p->name, t->line, "texture '%s': %s", t->name, ie.msg);
        }
    }
    return 0;
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
        warn(p, "%d 'pushTransform' without 'popTransform' at the end of the file", p->depth);
    if (p->first_quad_line && sc->integrator == INTEGRATOR_RAYTRACER) { /* hw1's renderer with hw2's light */
        p->line = p->first_quad_line;
        warn(p, "the 'raytracer' integrator ignores quad lights (they neither light, show nor block): "
                "use 'integrator analyticdirect', 'direct' or 'pathtracer'");
        p->line = 0;
    }
    if (p->first_delta_line && sc->integrator == INTEGRATOR_ANALYTICDIRECT) { /* hw2's renderer with hw1's lights */
        p->line = p->first_delta_line;
        warn(p, "the 'analyticdirect' integrator lights with quad lights only: point and directional "
                "lights are ignored (use 'integrator direct' or 'pathtracer', which sample them)");
        p->line = 0;
    }
    if (p->first_delta_line && sc->integrator == INTEGRATOR_PATHTRACER && sc->nee == NEE_OFF) {
        p->line = p->first_delta_line; /* a path never hits a point: only NEE reaches one */
        warn(p, "with 'nexteventestimation off' the path tracer never reaches point or directional "
                "lights (no path can hit one): they light nothing; use 'nexteventestimation on' or 'mis'");
        p->line = 0;
    }
    if ((p->first_quad_line || p->first_delta_line) && sc->integrator == INTEGRATOR_PREFILTERED) {
        int a = p->first_quad_line, b = p->first_delta_line; /* the first light of either kind */
        p->line = a && (!b || a < b) ? a : b;
        warn(p, "the 'prefiltered' integrator lights with the envmap's prefiltered maps only: "
                "point, directional and quad lights are ignored (use 'integrator direct' or "
                "'pathtracer')");
        p->line = 0;
    }
    if (p->opts->load_images && load_textures(p)) return -1;
    if (sc->envmap.present && p->opts->load_images && load_envmap(p)) return -1;
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
        if (take > limit - n) return fail(p, "line is longer than %d bytes", SCENE_MAX_LINE);
        if (memchr(start, '\0', take)) return fail(p, "NUL byte in the file (binary file?)");
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
    if (n > SCENE_MAX_LINE) return fail(p, "line is longer than %d bytes", SCENE_MAX_LINE);
    *n_out = n;
    return 1;
}

/* Free what only the parser holds (the vertex lists, the transform stack, the parsed OBJ
 * meshes) and give its memory back to the budget. */
static void parser_free(parser *p)
{
    budget *mem = p->opts->mem;
    budget_release(mem, (double)p->cap_verts * sizeof *p->verts +
                            (double)p->cap_vnorms * sizeof *p->vnorms +
                            (double)p->cap_vtex * sizeof *p->vtex +
                            (double)p->stack_cap * sizeof *p->stack);
    free(p->stack);
    free(p->verts);
    free(p->vnorms);
    free(p->vtex);
    for (int i = 0; i < p->n_objs; i++) {
        budget_release(mem, p->objs[i].mesh.bytes);
        obj_free(&p->objs[i].mesh);
    }
    free(p->objs);
    free(p->tex_index);
}

/* Parse the lines of `src` into *out. */
static int parse(line_source *src, const char *name, const scene_load_opts *opts, scene *out,
                 error *err)
{
    scene_load_opts defaults = scene_load_defaults();
    parser p;
    memset(&p, 0, sizeof p);
    p.sc = out;
    p.opts = opts ? opts : &defaults;
    p.name = name ? name : "<string>";
    p.err = err;
    p.xf = mat4_identity();
    p.mat = scene_default_material();
    p.atten[0] = 1.0; /* attenuation 1 0 0: no fall-off */
    p.max_prims = p.opts->max_prims > 0 && p.opts->max_prims < SCENE_MAX_PRIMS
                      ? p.opts->max_prims : SCENE_MAX_PRIMS;

    scene_init(out);
    int rc = -1;
    char *buf = NULL;
    if (name && strcmp(name, "-") != 0) {
        size_t n = strlen(name);
        if (n >= sizeof out->path) {
            error_set(err, name, 0, "scene path is longer than %zu bytes", sizeof out->path - 1);
            goto done;
        }
        memcpy(out->path, name, n + 1);
        const char *slash = strrchr(name, '/');
        if (slash) {
            size_t b = (size_t)(slash - name) + 1;
            if (b >= sizeof p.base) {
                error_set(err, name, 0, "scene folder is longer than %zu bytes",
                          sizeof p.base - 1);
                goto done;
            }
            memcpy(p.base, name, b);
            p.base[b] = '\0';
        }
    } else if (name) {
        memcpy(out->path, "-", 2);
    }

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
    parser_free(&p);
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
    return parse(&src, name, opts, out, err);
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
        rc = parse(&src, path, opts, out, err);
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
