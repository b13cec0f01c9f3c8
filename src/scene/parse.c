/* parse.c - the scene parser's helpers: messages, arguments, the transform stack, the
 * material and the arrays every command adds to; the command tables' dispatch, line by line, and
 * the checks at the end (parse.h). */
#include "parse.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/core/nearmiss.h"

/* ---- messages ---------------------------------------------------------------------------- */

int parse_fail(parser *p, const char *fmt, ...)
{
    char msg[ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return error_set(p->err, p->name, p->line, "%s", msg);
}

void parse_warn(parser *p, const char *fmt, ...)
{
    if (!p->warn) return;
    error w;
    char msg[ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    error_set(&w, p->name, p->line, "%s", msg);
    p->warn(p->warn_ctx, &w);
}

/* ---- growing arrays ---------------------------------------------------------------------- */

int parse_grow(parser *p, void **arr, long *cap, long need, size_t size, const char *what)
{
    if (need <= *cap) return 0;
    long n = *cap > 0 ? *cap : 16;
    while (n < need) n *= 2; /* need <= SCENE_MAX_PRIMS, so n stays far below LONG_MAX */
    double more = (double)(n - *cap) * (double)size;
    if (budget_charge(p->mem, more, p->name, p->line, p->err, "room for %ld more %s x %zu bytes",
                      n - *cap, what, size))
        return -1;
    void *q = realloc(*arr, (size_t)n * size);
    if (!q) {
        budget_release(p->mem, more);
        return parse_fail(p, "out of memory for '%s' (%ld entries)", p->tok[0], need);
    }
    *arr = q;
    *cap = n;
    return 0;
}

/* ---- arguments --------------------------------------------------------------------------- */

int parse_arg_num(parser *p, int i, double *out)
{
    const char *s = p->tok[i];
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0')
        return parse_fail(p, "expected a number for '%s' argument %d, got '%s'", p->tok[0], i, s);
    /* NaN, Inf and overflow ("1e999" gives HUGE_VAL); underflow to a tiny value is harmless */
    if (!isfinite(v))
        return parse_fail(p, "expected a finite number for '%s' argument %d, got '%s'", p->tok[0],
                          i, s);
    *out = v;
    return 0;
}

int parse_arg_nums(parser *p, int first, int n, double *v)
{
    for (int k = 0; k < n; k++)
        if (parse_arg_num(p, first + k, &v[k])) return -1;
    return 0;
}

int parse_arg_int(parser *p, int i, double lo, double hi, long *out)
{
    double v = 0;
    if (parse_arg_num(p, i, &v)) return -1;
    if (v != floor(v))
        return parse_fail(p, "expected an integer for '%s' argument %d, got '%s'", p->tok[0], i,
                          p->tok[i]);
    if (v < lo || v > hi)
        return parse_fail(p, "'%s' argument %d must be in [%.0f, %.0f], got '%s'", p->tok[0], i, lo,
                          hi, p->tok[i]);
    *out = (long)v;
    return 0;
}

int parse_arg_nonneg(parser *p, int i, int strict, double *out)
{
    if (parse_arg_num(p, i, out)) return -1;
    if (strict ? !(*out > 0) : !(*out >= 0))
        return parse_fail(p, "'%s' argument %d must be %s 0, got '%s'", p->tok[0], i,
                          strict ? ">" : ">=", p->tok[i]);
    return 0;
}

int parse_arg_rgb(parser *p, int first, rgb *out)
{
    double v[3];
    for (int k = 0; k < 3; k++)
        if (parse_arg_nonneg(p, first + k, 0, &v[k])) return -1;
    *out = rgb_make(v[0], v[1], v[2]);
    return 0;
}

int parse_arg_word(parser *p, const char *const *words, int n, int *out)
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
    return parse_fail(p, "'%s' must be %s, got '%s'", p->tok[0], list, p->tok[1]);
}

int parse_arg_onoff(parser *p, int *out)
{
    static const char *const w[] = {"off", "on"};
    return parse_arg_word(p, w, 2, out);
}

/* ---- transforms -------------------------------------------------------------------------- */

int parse_xf_apply(parser *p, mat4 m)
{
    mat4 r = mat4_mul(p->xf, m);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(r.m[i][j]))
                return parse_fail(p, "'%s' makes the current transform overflow", p->tok[0]);
    p->xf = r;
    p->inv_state = 0;
    return 0;
}

int parse_xf_inverse(parser *p, const mat4 **inv)
{
    if (p->inv_state == 0) p->inv_state = mat4_inverse(p->xf, &p->inv) == 0 ? 1 : -1;
    if (p->inv_state < 0)
        return parse_fail(p,
                          "'%s' needs the inverse of the current transform, which is singular "
                          "(a 'scale' by 0?)",
                          p->tok[0]);
    *inv = &p->inv;
    return 0;
}

int parse_xf_push(parser *p)
{
    if (p->depth >= SCENE_MAX_TRANSFORM_STACK)
        return parse_fail(p, "'pushTransform' nested deeper than %d", SCENE_MAX_TRANSFORM_STACK);
    if (p->depth >= p->stack_cap) {
        long cap = p->stack_cap;
        if (parse_grow(p, (void **)&p->stack, &cap, p->depth + 1, sizeof *p->stack, "transforms"))
            return -1;
        p->stack_cap = (int)cap;
    }
    p->stack[p->depth++] = p->xf;
    return 0;
}

int parse_xf_pop(parser *p)
{
    if (p->depth == 0) return parse_fail(p, "'popTransform' without a matching 'pushTransform'");
    p->xf = p->stack[--p->depth];
    p->inv_state = 0;
    return 0;
}

/* ---- materials, triangles, lights, files ------------------------------------------------- */

static int rgb_equal(rgb a, rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

static int material_equal(const material *a, const material *b)
{
    return rgb_equal(a->ambient, b->ambient) && rgb_equal(a->diffuse, b->diffuse) &&
           rgb_equal(a->specular, b->specular) && rgb_equal(a->emission, b->emission) &&
           a->shininess == b->shininess && a->brdf == b->brdf && a->roughness == b->roughness &&
           a->ior == b->ior && a->diffusemap == b->diffusemap && a->specularmap == b->specularmap &&
           a->roughnessmap == b->roughnessmap && a->emissionmap == b->emissionmap &&
           a->bumpmap == b->bumpmap && a->displacementmap == b->displacementmap &&
           a->bump_strength == b->bump_strength && a->displacement_scale == b->displacement_scale &&
           a->texmapping == b->texmapping && a->texmapping_given == b->texmapping_given &&
           a->texfilter == b->texfilter;
}

int parse_material_index(parser *p, int *out)
{
    scene *sc = p->sc;
    if (sc->n_materials > 0 && material_equal(&sc->materials[sc->n_materials - 1], &p->mat)) {
        *out = sc->n_materials - 1;
        return 0;
    }
    if (parse_grow(p, (void **)&sc->materials, &p->cap_materials, (long)sc->n_materials + 1,
                   sizeof *sc->materials, "materials"))
        return -1;
    sc->materials[sc->n_materials] = p->mat;
    *out = sc->n_materials++;
    return 0;
}

int parse_tri_indices(parser *p, long count, const char *list, long idx[3])
{
    for (int k = 0; k < 3; k++) {
        double v = 0;
        if (parse_arg_num(p, k + 1, &v)) return -1;
        if (v != floor(v))
            return parse_fail(p, "expected an integer for '%s' argument %d, got '%s'", p->tok[0],
                              k + 1, p->tok[k + 1]);
        if (v < 0 || v >= (double)count)
            return parse_fail(p, "'%s' vertex index '%s' is out of range: %ld %s defined so far",
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

int parse_add_triangle(parser *p, const triangle *t)
{
    scene *sc = p->sc;
    for (int k = 0; k < 3; k++)
        if (!vec3_is_finite(t->p[k]))
            return parse_fail(p, "'%s' corner %d overflows under the current transform", p->tok[0],
                              k);
    if (sc->n_triangles >= p->max_prims)
        return parse_fail(p, "more than %ld triangles", p->max_prims);
    int m;
    if (parse_material_index(p, &m)) return -1;
    if (parse_grow(p, (void **)&sc->triangles, &p->cap_tris, sc->n_triangles + 1,
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

int parse_add_light(parser *p, const scene_light *l)
{
    scene *sc = p->sc;
    if (sc->n_lights >= p->max_prims) return parse_fail(p, "more than %ld lights", p->max_prims);
    if (parse_grow(p, (void **)&sc->lights, &p->cap_lights, (long)sc->n_lights + 1,
                   sizeof *sc->lights, "lights"))
        return -1;
    sc->lights[sc->n_lights++] = *l;
    if (l->kind != LIGHT_QUAD && !p->first_delta_line) p->first_delta_line = p->line;
    return 0;
}

int parse_relative_path(parser *p, const char *file, char *dst, size_t size)
{
    const char *base = file[0] == '/' ? "" : p->base;
    int w = snprintf(dst, size, "%s%s", base, file);
    if (w < 0 || (size_t)w >= size)
        return parse_fail(p, "'%s' path '%s%s' is longer than %zu bytes", p->tok[0], base, file,
                          size - 1);
    return 0;
}

/* ---- lines ------------------------------------------------------------------------------- */

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

static const parse_command *const command_tables[] = {commands_course, commands_texture,
                                                      commands_envtex};
#define N_TABLES (sizeof command_tables / sizeof command_tables[0])

/* The command called `name` in the tables, or NULL. */
static const parse_command *find_command(const char *name)
{
    for (size_t t = 0; t < N_TABLES; t++)
        for (const parse_command *c = command_tables[t]; c->name; c++)
            if (strcmp(name, c->name) == 0) return c;
    return NULL;
}

/* " (did you mean 'NAME'?)" for the command closest to `name` (nearmiss.h), or "" */
static void did_you_mean(const char *name, char *out, size_t n)
{
    nearmiss m;
    nearmiss_start(&m, name);
    for (size_t t = 0; t < N_TABLES; t++)
        for (const parse_command *c = command_tables[t]; c->name; c++) nearmiss_offer(&m, c->name);
    const char *best = nearmiss_best(&m);
    if (best) snprintf(out, n, " (did you mean '%s'?)", best);
    else out[0] = '\0';
}

int parse_run_line(parser *p, char *line)
{
    tokenize(p, line);
    if (p->ntok == 0) return 0;
    const char *name = p->tok[0];
    const parse_command *c = find_command(name);
    if (!c) {
        char hint[96];
        did_you_mean(name, hint, sizeof hint);
        if (p->strict) return parse_fail(p, "unknown command '%s'%s", name, hint);
        parse_warn(p, "unknown command '%s'%s (ignored)", name, hint);
        return 0;
    }
    if (strcmp(c->name, "size") == 0) {
        p->seen_size = 1;
    } else if (!p->seen_size && !p->warned_order) {
        p->warned_order = 1;
        parse_warn(p, "'%s' comes before 'size' (the course puts 'size' first)", name);
    }
    int nargs = p->ntok - 1;
    if (nargs < c->min_args || nargs > c->max_args) {
        if (c->forms)
            return parse_fail(p, "'%s' takes %s, got %d argument%s", name, c->forms, nargs,
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

int parse_finish(parser *p)
{
    scene *sc = p->sc;
    p->line = 0;
    if (!p->seen_size) return error_set(p->err, p->name, 0, "no 'size' command");
    if (!sc->has_camera) return error_set(p->err, p->name, 0, "no 'camera' command");
    long long samples = (long long)sc->width * sc->height * sc->spp;
    if (samples > SCENE_MAX_CAMERA_SAMPLES)
        return error_set(
            p->err, p->name, 0,
            "size %d x %d at spp %d asks for %lld camera samples, over the limit of 2^34",
            sc->width, sc->height, sc->spp, samples);
    if (p->depth > 0)
        parse_warn(p, "%d 'pushTransform' without 'popTransform' at the end of the file", p->depth);
    if (p->first_quad_line &&
        sc->integrator == INTEGRATOR_RAYTRACER) { /* hw1's renderer with hw2's light */
        p->line = p->first_quad_line;
        parse_warn(
            p,
            "the 'raytracer' integrator ignores quad lights (they neither light, show nor block): "
            "use 'integrator analyticdirect', 'direct' or 'pathtracer'");
        p->line = 0;
    }
    if (p->first_delta_line &&
        sc->integrator == INTEGRATOR_ANALYTICDIRECT) { /* hw2's renderer with hw1's lights */
        p->line = p->first_delta_line;
        parse_warn(
            p,
            "the 'analyticdirect' integrator lights with quad lights only: point and directional "
            "lights are ignored (use 'integrator direct' or 'pathtracer', which sample them)");
        p->line = 0;
    }
    if (p->first_delta_line && sc->integrator == INTEGRATOR_PATHTRACER && sc->nee == NEE_OFF) {
        p->line = p->first_delta_line; /* a path never hits a point: only NEE reaches one */
        parse_warn(
            p, "with 'nexteventestimation off' the path tracer never reaches point or directional "
               "lights (no path can hit one): they light nothing; use 'nexteventestimation on' or "
               "'mis'");
        p->line = 0;
    }
    if ((p->first_quad_line || p->first_delta_line) && sc->integrator == INTEGRATOR_PREFILTERED) {
        int a = p->first_quad_line, b = p->first_delta_line; /* the first light of either kind */
        p->line = a && (!b || a < b) ? a : b;
        parse_warn(p,
                   "the 'prefiltered' integrator lights with the envmap's prefiltered maps only: "
                   "point, directional and quad lights are ignored (use 'integrator direct' or "
                   "'pathtracer')");
        p->line = 0;
    }
    if (p->load_images && assets_load_textures(p)) return -1;
    if (sc->envmap.present && p->load_images && assets_load_envmap(p)) return -1;
    return 0;
}

void parse_free(parser *p)
{
    budget *mem = p->mem;
    budget_release(
        mem, (double)p->cap_verts * sizeof *p->verts + (double)p->cap_vnorms * sizeof *p->vnorms +
                 (double)p->cap_vtex * sizeof *p->vtex + (double)p->stack_cap * sizeof *p->stack);
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
