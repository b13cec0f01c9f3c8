/* lights.c - the scene's lights for next-event estimation (see include/envtex/lights.h). */
#include "envtex/lights.h"

#include <stdlib.h>
#include <string.h>

#include "envtex/triangle.h"

static double light_power(const lights *ls, int k)
{
    if (k == lights_env_index(ls)) {
        const envlight *el = ls->env;
        double p = el->power;
        if (el->fell_back) p = 0;
        return M_PI * ls->radius * ls->radius * p; /* pi R^2 |L| */
    }
    const scene_light *l = &ls->sc->lights[k];
    double c = rgb_avg(l->color);
    switch (l->kind) {
    case LIGHT_QUAD: return M_PI * vec3_length(vec3_cross(l->ab, l->ac)) * c; /* pi A L */
    case LIGHT_POINT: return 4 * M_PI * c;                                     /* 4 pi I */
    default: return M_PI * ls->radius * ls->radius * c;                        /* pi R^2 E */
    }
}

int lights_build(lights *ls, const scene *sc, const envlight *env, double scene_radius, error *err)
{
    memset(ls, 0, sizeof *ls);
    ls->sc = sc;
    ls->env = env;
    ls->radius = scene_radius > 0 ? scene_radius : 1;
    ls->env_fraction = 1;
    ls->n = sc->n_lights + (env ? 1 : 0);
    if (ls->n == 0) return 0;
    double *w = malloc((size_t)ls->n * sizeof *w);
    if (!w) return error_set(err, sc->path, 0, "out of memory for %d lights", ls->n);
    for (int k = 0; k < ls->n; k++) w[k] = light_power(ls, k);
    /* all zero (e.g. black lights): distrib1d falls back to uniform, which is still correct */
    int st = distrib1d_init(&ls->choose, w, ls->n, err);
    free(w);
    return st;
}

void lights_free(lights *ls) { distrib1d_free(&ls->choose); }

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

void lights_set_env_fraction(lights *ls, double c) { ls->env_fraction = c >= 0 && c <= 1 ? c : 1; }

/* the emitting normal of a quad: along ac x ab */
static vec3 quad_normal(const scene_light *l) { return vec3_normalize(vec3_cross(l->ac, l->ab)); }

int lights_sample(const lights *ls, int k, vec3 p, vec3 ng, double xi1, double xi2, double xi3,
                  int stratified, light_sample *out)
{
    out->is_delta = 0;
    if (k == lights_env_index(ls)) {
        const envlight *el = ls->env;
        if (el->mode == ENVSAMPLING_MEDIANCUT) {
            /* a stratum as a point light: shade with its centroid, jitter only the shadow ray.
             * The caller already picked the envmap; pick the stratum inside it. */
            int j;
            double prob;
            vec3 sd;
            if (!envlight_mediancut_pick(el, xi1, xi2, xi3, &j, &sd, &prob)) return 0;
            out->wi = el->points[j].dir;
            out->Li = rgb_scale(el->points[j].power, 1 / prob);
            out->pdf = 0;
            out->is_delta = 1;
            out->shadow = ray_spawn(p, ng, sd);
            return 1;
        }
        envlight_sample_result s;
        if (!envlight_sample(el, xi1, xi2, stratified, &s)) return 0;
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
    int found = 0;
    ray rr = *r;
    for (int i = 0; i < ls->sc->n_lights; i++) {
        const scene_light *l = &ls->sc->lights[i];
        if (l->kind != LIGHT_QUAD) continue;
        vec3 a = l->pos, b = vec3_add(l->pos, l->ab), c = vec3_add(b, l->ac), d = vec3_add(l->pos, l->ac);
        double t, b1, b2;
        /* the parallelogram a, a+ab, a+ab+ac, a+ac as two triangles */
        if (triangle_intersect(a, b, c, &rr, &t, &b1, &b2) || triangle_intersect(a, c, d, &rr, &t, &b1, &b2)) {
            found = 1;
            *k = i;
            *t_out = t;
            rr.tmax = t;
        }
    }
    return found;
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
