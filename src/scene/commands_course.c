/* commands_course.c - the commands of the CSE 167/168 scene format (hw1-hw4: image, camera,
 * geometry, transforms, lights, materials, renderer settings; docs/scene-format.md), in the
 * table commands_course (parse.h). */
#include "parse.h"

#include <math.h>
#include <string.h>

#include "envtex/geometry/camera.h"

/* maxverts / maxvertnorms are only capacity hints: a hostile "maxverts 999999999999" must not
 * reserve gigabytes, so a hint reserves at most this many entries (arrays still grow past it). */
#define HINT_CAP (1L << 20)

/* sin of the angle between a quad light's edges below which it is a sliver of no area: rounding
 * of exactly parallel edges leaves |ab x ac| ~ 1e-16 |ab| |ac|. */
#define QUAD_PARALLEL_EPS 1e-12

static int cmd_size(parser *p)
{
    long w = 0, h = 0;
    if (parse_arg_int(p, 1, 1, SCENE_MAX_SIZE, &w) || parse_arg_int(p, 2, 1, SCENE_MAX_SIZE, &h))
        return -1;
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
        return parse_fail(p, "'output' file name is longer than %zu bytes",
                          sizeof p->sc->output - 1);
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
        return parse_fail(
            p, "'camera' look-from and look-at are too far apart (their difference overflows)");
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
    if (sc->n_spheres >= p->max_prims) return parse_fail(p, "more than %ld spheres", p->max_prims);
    int m;
    if (parse_material_index(p, &m)) return -1;
    if (parse_grow(p, (void **)&sc->spheres, &p->cap_spheres, sc->n_spheres + 1,
                   sizeof *sc->spheres, "spheres"))
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
    return parse_grow(p, (void **)&p->vnorms, &p->cap_vnorms, n, sizeof *p->vnorms,
                      "vertex normals");
}

static int cmd_vertex(parser *p)
{
    double v[3];
    if (parse_arg_nums(p, 1, 3, v)) return -1;
    if (p->n_verts >= p->max_prims) return parse_fail(p, "more than %ld vertices", p->max_prims);
    if (parse_grow(p, (void **)&p->verts, &p->cap_verts, p->n_verts + 1, sizeof *p->verts,
                   "vertices"))
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
            return parse_fail(p,
                              "'trinormal' normal of vertex '%s' degenerates under the current "
                              "transform",
                              p->tok[k + 1]);
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
    if (vec3_unit_direction(vec3_make(v[0], v[1], v[2]), &l.dir))
        return parse_fail(p, "'directional' direction is zero");
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
    if (strcmp(k, "ambient") == 0)
        p->mat.ambient = c;
    else if (strcmp(k, "diffuse") == 0)
        p->mat.diffuse = c;
    else if (strcmp(k, "specular") == 0)
        p->mat.specular = c;
    else
        p->mat.emission = c;
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

/* output encoding c^(1/g): gammas outside [SCENE_GAMMA_MIN, SCENE_GAMMA_MAX] are typing
 * mistakes (the course uses 2.2), refused here rather than after the render by the PNG writer */
#define SCENE_GAMMA_MIN 0.01
#define SCENE_GAMMA_MAX 100.0
static int cmd_gamma(parser *p)
{
    if (parse_arg_nonneg(p, 1, 1, &p->sc->gamma)) return -1;
    if (!(p->sc->gamma >= SCENE_GAMMA_MIN && p->sc->gamma <= SCENE_GAMMA_MAX))
        return parse_fail(p, "'gamma' must be from %g to %g, got '%s'", SCENE_GAMMA_MIN,
                          SCENE_GAMMA_MAX, p->tok[1]);
    return 0;
}

/* Geometry first: it is most of the lines of a big scene. */
const parse_command commands_course[] = {
    {"vertex", cmd_vertex, 3, 3, NULL},
    {"tri", cmd_tri, 3, 3, NULL},
    {"vertexnormal", cmd_vertexnormal, 6, 6, NULL},
    {"trinormal", cmd_trinormal, 3, 3, NULL},
    {"sphere", cmd_sphere, 4, 4, NULL},
    {"size", cmd_size, 2, 2, NULL},
    {"maxdepth", cmd_maxdepth, 1, 1, NULL},
    {"output", cmd_output, 1, 1, NULL},
    {"camera", cmd_camera, 10, 10, NULL},
    {"maxverts", cmd_maxverts, 1, 1, NULL},
    {"maxvertnorms", cmd_maxverts, 1, 1, NULL},
    {"translate", cmd_translate, 3, 3, NULL},
    {"rotate", cmd_rotate, 4, 4, NULL},
    {"scale", cmd_scale, 3, 3, NULL},
    {"pushTransform", parse_xf_push, 0, 0, NULL},
    {"popTransform", parse_xf_pop, 0, 0, NULL},
    {"directional", cmd_directional, 6, 6, NULL},
    {"point", cmd_point, 6, 6, NULL},
    {"attenuation", cmd_attenuation, 3, 3, NULL},
    {"ambient", cmd_colour, 3, 3, NULL},
    {"diffuse", cmd_colour, 3, 3, NULL},
    {"specular", cmd_colour, 3, 3, NULL},
    {"emission", cmd_colour, 3, 3, NULL},
    {"shininess", cmd_shininess, 1, 1, NULL},
    {"integrator", cmd_integrator, 1, 1, NULL},
    {"quadLight", cmd_quadlight, 12, 12, NULL},
    {"lightsamples", cmd_lightsamples, 1, 1, NULL},
    {"lightstratify", cmd_lightstratify, 1, 1, NULL},
    {"spp", cmd_spp, 1, 1, NULL},
    {"nexteventestimation", cmd_nee, 1, 1, NULL},
    {"russianroulette", cmd_russianroulette, 1, 1, NULL},
    {"importancesampling", cmd_importancesampling, 1, 1, NULL},
    {"brdf", cmd_brdf, 1, 1, NULL},
    {"roughness", cmd_roughness, 1, 1, NULL},
    {"gamma", cmd_gamma, 1, 1, NULL},
    {NULL, NULL, 0, 0, NULL},
};
