/* lights.c - the scene's lights for next-event estimation (see
 * include/envtex/integrators/lights.h). */
#include "envtex/integrators/lights.h"

#include <stdlib.h>
#include <string.h>

#include "envtex/envlight/sis.h"

/* log2 of light k's power (-inf for none), from factors that each fit a double: the power
 * itself may not (4 pi I with I = 1e308, or pi R^2 E for a huge scene), and only the ratios of
 * the powers matter for the choice */
static double light_log2_power(const lights *ls, int k)
{
    double r2 = 2 * log2(ls->radius); /* log2 R^2 */
    if (k == lights_env_index(ls)) {
        const envlight *el = ls->env;
        if (el->fell_back) return -INFINITY;
        return log2(M_PI) + r2 + log2(el->power); /* pi R^2 |L| */
    }
    const scene_light *l = &ls->sc->lights[k];
    double c = log2(l->color.r / 3 + l->color.g / 3 + l->color.b / 3); /* the mean, which rgb_avg
                                                                            overflows past 6e307 */
    switch (l->kind) {
    case LIGHT_QUAD: { /* pi A L, with |ab x ac| = |ab| |ac| sin(angle) computed without overflow */
        double la = vec3_length(l->ab), lc = vec3_length(l->ac);
        if (!(la > 0 && lc > 0)) return -INFINITY;
        double sin_a =
            vec3_length(vec3_cross(vec3_scale(l->ab, 1 / la), vec3_scale(l->ac, 1 / lc)));
        return log2(M_PI) + log2(la) + log2(lc) + log2(sin_a) + c;
    }
    case LIGHT_POINT: return log2(4 * M_PI) + c; /* 4 pi I */
    default: return log2(M_PI) + r2 + c;         /* pi R^2 E */
    }
}

/* The quads of sc's quad lights, in the order of sc->lights (malloc'd, *n of them; NULL when
 * there are none), each the parallelogram a, a+ab, a+ab+ac, a+ac.  -1 when memory runs out. */
static int scene_quads(const scene *sc, bvh_quad **out, long *n)
{
    *out = NULL;
    *n = 0;
    for (int i = 0; i < sc->n_lights; i++) *n += sc->lights[i].kind == LIGHT_QUAD;
    if (*n == 0) return 0;
    bvh_quad *q = *out = malloc((size_t)*n * sizeof *q);
    if (!q) return -1;
    for (int i = 0; i < sc->n_lights; i++)
        if (sc->lights[i].kind == LIGHT_QUAD)
            *q++ = (bvh_quad){sc->lights[i].pos, sc->lights[i].ab, sc->lights[i].ac};
    return 0;
}

/* The quad lights' BVH (lights.h).  Testing every light for every ray cost a path tracer ~90%
 * of its time with 100 quad lights, and 66% with 1000 point lights and no quad at all. */
static int build_quads(lights *ls, const scene *sc, budget *mem, error *err)
{
    bvh_quad *quads;
    long nq;
    if (scene_quads(sc, &quads, &nq))
        return error_set(err, sc->path, 0, "out of memory for the quad lights");
    if (nq == 0) return 0;
    double bytes = (double)nq * sizeof *ls->quad_light;
    int st = budget_charge(mem, bytes, sc->path, 0, err, "%ld quad lights x %zu bytes", nq,
                           sizeof *ls->quad_light);
    if (st == 0 && !(ls->quad_light = malloc((size_t)nq * sizeof *ls->quad_light))) {
        budget_release(mem, bytes);
        st = error_set(err, sc->path, 0, "out of memory for %ld quad lights", nq);
    }
    for (int i = 0; st == 0 && i < sc->n_lights; i++)
        if (sc->lights[i].kind == LIGHT_QUAD) ls->quad_light[ls->n_quads++] = i;
    bvh_prims p = {.name = sc->path, .quads = quads, .n_quads = nq};
    if (st == 0) st = bvh_build(&ls->quad_bvh, p, mem, err);
    free(quads); /* (the bvh keeps a copy) */
    return st;
}

int lights_scene_bvh(bvh *b, const scene *sc, budget *mem, error *err)
{
    bvh_prims p = scene_prims(sc);
    bvh_quad *quads = NULL;
    int sees_quads =
        sc->integrator != INTEGRATOR_RAYTRACER && sc->integrator != INTEGRATOR_PREFILTERED;
    if (sees_quads && scene_quads(sc, &quads, &p.n_quads)) {
        memset(b, 0, sizeof *b);
        return error_set(err, sc->path, 0, "out of memory for the quad lights");
    }
    p.quads = quads;
    int st = bvh_build(b, p, mem, err);
    free(quads); /* (the bvh keeps a copy) */
    return st;
}

int lights_build(lights *ls, const scene *sc, const envlight *env, double scene_radius, budget *mem,
                 error *err)
{
    memset(ls, 0, sizeof *ls);
    ls->sc = sc;
    ls->env = env;
    ls->radius = scene_radius > 0 ? scene_radius : 1;
    ls->env_fraction = 1;
    ls->selection = sc->lightselection;
    ls->n = sc->n_lights + (env ? 1 : 0);
    if (ls->n == 0) return 0;
    double *w = malloc((size_t)ls->n * sizeof *w);
    if (!w) return error_set(err, sc->path, 0, "out of memory for %d lights", ls->n);
    /* w_k = P_k / max P = 2^(log2 P_k - max log2 P): at most 1, so their sum cannot overflow
     * (two point lights of intensity 1e307 did) */
    double top = -INFINITY;
    for (int k = 0; k < ls->n; k++) {
        w[k] = light_log2_power(ls, k);
        if (w[k] > top) top = w[k];
    }
    for (int k = 0; k < ls->n; k++) w[k] = top > -INFINITY ? exp2(w[k] - top) : 0.0;
    /* all zero (e.g. black lights): distrib1d falls back to uniform, which is still correct */
    int st = distrib1d_init(&ls->choose, w, ls->n, err); /* fails only when memory runs out */
    free(w);
    if (st) error_set(err, sc->path, 0, "out of memory for the choice among %d lights", ls->n);
    if (st == 0 && (st = build_quads(ls, sc, mem, err)) != 0) lights_free(ls);
    return st;
}

void lights_free(lights *ls)
{
    distrib1d_free(&ls->choose);
    bvh_free(&ls->quad_bvh); /* safe on a zeroed or failed build */
    free(ls->quad_light);
    ls->quad_light = NULL;
    ls->n_quads = 0;
}

int lights_pick(const lights *ls, double xi, int *k, double *prob)
{
    if (ls->n == 0) return 0;
    double rem = xi;
    if (ls->n == 1) { /* one light (the envmap alone, say): no table to search */
        *k = 0;
        *prob = 1;
    } else {
        *k = distrib1d_sample(&ls->choose, xi, prob, &rem);
    }
    if (*k == lights_env_index(ls) && ls->env_fraction < 1) {
        /* keep the envmap pick with probability c: rem is uniform in [0,1) given the pick */
        if (!(rem < ls->env_fraction)) return 0;
        *prob *= ls->env_fraction;
    }
    return *prob > 0;
}

double lights_pick_prob(const lights *ls, int k)
{
    if (!ls->n) return 0;
    double p = distrib1d_pmf(&ls->choose, k);
    return k == lights_env_index(ls) ? p * ls->env_fraction : p;
}

double lights_selection_prob(const lights *ls, int k)
{
    if (ls->selection == LIGHTSELECTION_POWER) return lights_pick_prob(ls, k);
    return k == lights_env_index(ls) ? ls->env_fraction : 1.0; /* every light: its own samples */
}

void lights_set_env_fraction(lights *ls, double c) { ls->env_fraction = c >= 0 && c <= 1 ? c : 1; }

/* the emitting normal of a quad: along ac x ab */
static vec3 quad_normal(const scene_light *l) { return vec3_normalize(vec3_cross(l->ac, l->ab)); }

int lights_sample(const lights *ls, int k, vec3 p, vec3 ng, double xi1, double xi2, double xi3,
                  int stratified, light_sample *out)
{
    out->is_delta = 0;
    if (k == lights_env_index(ls)) {
        const envlight *el = ls->env;
        if (el->mode == ENVSAMPLING_MEDIANCUT || el->mode == ENVSAMPLING_SIS) {
            /* a stratum as a point light: shade with its centroid, jitter only the shadow ray.
             * The caller already picked the envmap; pick the stratum inside it. */
            int j;
            double prob;
            vec3 sd;
            int ok = el->mode == ENVSAMPLING_SIS
                         ? sis_pick(el, xi1, xi2, xi3, &j, &sd, &prob)
                         : envlight_mediancut_pick(el, xi1, xi2, xi3, &j, &sd, &prob);
            if (!ok) return 0;
            out->wi = el->points[j].dir;
            out->Li = rgb_scale(el->points[j].power, 1 / prob);
            out->pdf = 0;
            out->is_delta = 1;
            out->shadow = ray_spawn(p, ng, sd);
            return 1;
        }
        envlight_sample_result s;
        if (!(stratified ? envlight_sample_stratified(el, xi1, xi2, &s)
                         : envlight_sample(el, xi1, xi2, &s)))
            return 0;
        out->wi = s.wi;
        out->Li = s.L;
        out->pdf = s.pdf;
        out->shadow = ray_spawn(p, ng, s.wi);
        return !rgb_is_black(s.L);
    }
    const scene_light *l = &ls->sc->lights[k];
    if (l->kind == LIGHT_DIRECTIONAL) {
        out->wi = l->dir;
        out->Li = l->color;
        out->pdf = 0;
        out->is_delta = 1;
        out->shadow = ray_spawn(p, ng, l->dir);
        return 1;
    }
    if (l->kind == LIGHT_POINT) {
        vec3 to = vec3_sub(l->pos, p);
        double d = vec3_length(to);
        double atten = l->atten[0] + l->atten[1] * d + l->atten[2] * d * d; /* c + l d + q d^2 */
        if (!(d > 0) || !(atten > 0)) return 0;
        out->wi = vec3_scale(to, 1 / d);
        out->Li = rgb_scale(l->color, 1 / atten);
        out->pdf = 0;
        out->is_delta = 1;
        out->shadow = ray_spawn_to(p, ng, l->pos);
        return 1;
    }
    /* quad: a point uniform in area, q = a + xi1 ab + xi2 ac; pdf_omega = d^2 / (A |cos_l|) */
    vec3 q = vec3_add(l->pos, vec3_add(vec3_scale(l->ab, xi1), vec3_scale(l->ac, xi2)));
    vec3 to = vec3_sub(q, p);
    double d2 = vec3_length2(to), d = sqrt(d2);
    if (!(d > 0)) return 0;
    vec3 wi = vec3_scale(to, 1 / d);
    double area = vec3_length(vec3_cross(l->ab, l->ac));
    double cos_l = -vec3_dot(wi, quad_normal(l));
    if (cos_l <= 0) return 0; /* the back of the light, which does not emit */
    (void)stratified;
    out->wi = wi;
    out->Li = l->color;
    out->pdf = d2 / (area * cos_l);
    out->shadow = ray_spawn_to(p, ng, q);
    return 1;
}

int lights_intersect_quad(const lights *ls, const ray *r, int *k, double *t_out)
{
    hit h;
    if (ls->n_quads == 0 || bvh_intersect(&ls->quad_bvh, r, &h) != BVH_QUAD) return 0;
    *k = ls->quad_light[h.prim];
    *t_out = h.t;
    return 1;
}

rgb lights_quad_radiance(const lights *ls, int k, vec3 d)
{
    const scene_light *l = &ls->sc->lights[k];
    return vec3_dot(d, quad_normal(l)) < 0 ? l->color : rgb_gray(0);
}

double lights_quad_pdf(const lights *ls, int k, vec3 wi, double t)
{
    const scene_light *l = &ls->sc->lights[k];
    double area = vec3_length(vec3_cross(l->ab, l->ac));
    double cos_l = -vec3_dot(wi, quad_normal(l));
    if (cos_l <= 0) return 0;
    return t * t / (area * cos_l); /* unit wi: the distance is t */
}
