/* integrator.c - the shared context of the integrators (integrator.h). */
#include "envtex/integrators/integrator.h"

#include <string.h>
#include <time.h>

#include "envtex/envlight/misfraction.h"
#include "envtex/envlight/sis.h"
#include "envtex/geometry/sphere.h"
#include "envtex/integrators/prefiltered.h"
#include "envtex/integrators/texshade.h"

/* Radius of a sphere around the scene's geometry and lights: the "R" that converts a distant
 * light's radiance or irradiance into the power it delivers to the scene. */
static double scene_radius(const scene *sc)
{
    vec3 lo = vec3_make(INFINITY, INFINITY, INFINITY), hi = vec3_neg(lo);
    for (long i = 0; i < sc->n_spheres; i++) {
        vec3 a, b;
        sphere_bounds(&sc->spheres[i], &a, &b);
        lo = vec3_min(lo, a);
        hi = vec3_max(hi, b);
    }
    for (long i = 0; i < sc->n_triangles; i++)
        for (int k = 0; k < 3; k++) {
            lo = vec3_min(lo, sc->triangles[i].p[k]);
            hi = vec3_max(hi, sc->triangles[i].p[k]);
        }
    for (int i = 0; i < sc->n_lights; i++)
        if (sc->lights[i].kind == LIGHT_QUAD) {
            const scene_light *l = &sc->lights[i];
            vec3 c[4] = {l->pos, vec3_add(l->pos, l->ab), vec3_add(l->pos, l->ac),
                         vec3_add(vec3_add(l->pos, l->ab), l->ac)};
            for (int k = 0; k < 4; k++) {
                lo = vec3_min(lo, c[k]);
                hi = vec3_max(hi, c[k]);
            }
        }
    if (!(hi.x >= lo.x)) return 1.0; /* nothing in the scene */
    double r = 0.5 * vec3_length(vec3_sub(hi, lo));
    return r > 0 ? r : 1.0;
}

/* The envmap as a light that is sampled: `envsampling sis N` adds its point lights (sis.h) */
static int build_sampled_envlight(envlight *el, const envmap *env, const scene *sc, budget *mem,
                                  error *err)
{
    if (sc->envsampling == ENVSAMPLING_SIS)
        return sis_envlight_build(el, env, sc->envsampler, sc->mediancut_lights, mem, err);
    return envlight_build(el, env, sc->envsampling, sc->envsampler, sc->mediancut_lights, mem, err);
}

int integrator_init(integrator *it, const scene *sc, const bvh *accel, budget *mem, error *err)
{
    memset(it, 0, sizeof *it);
    it->env_fraction = 1; /* MIS sets its own below */
    it->sc = sc;
    it->accel = accel;
    scene_environment(sc, &it->env);
    it->maxdepth = sc->maxdepth < 0 ? INTEGRATOR_UNLIMITED_DEPTH : sc->maxdepth;
    if (sc->integrator == INTEGRATOR_RAYTRACER) {
        raytracer_init(&it->rt, sc, accel);
        return 0;
    }
    if (sc->integrator == INTEGRATOR_PREFILTERED) { /* the ray tracer, shading from the maps */
        raytracer_init(&it->rt, sc, accel);
        return prefiltered_init(&it->pf, &it->rt, mem, err);
    }
    clock_t t0 = clock();
    int samples_lights = sc->integrator == INTEGRATOR_DIRECT ||
                         (sc->integrator == INTEGRATOR_PATHTRACER && sc->nee != NEE_OFF);
    /* The envmap lights the scene unless `envmiss black` makes it a background only. */
    int env_lights = it->env.present && sc->envmiss == ENVMISS_ENVMAP &&
                     sc->integrator != INTEGRATOR_ANALYTICDIRECT;
    if (env_lights) {
        /* tables only for an integrator that samples the envmap; otherwise just the
         * piecewise-constant lookup, without a pass over the texels */
        if (samples_lights ? build_sampled_envlight(&it->el, &it->env, sc, mem, err)
                           : envlight_build_lookup(&it->el, &it->env, mem, err)) {
            /* about the scene's `envmap` (its transform, most often): reported at its line */
            char why[ERROR_MSG_MAX];
            /* err->msg cannot be an argument of error_set on err */
            snprintf(why, sizeof why, "%s", err->msg);
            return error_set(err, sc->path, sc->envmap.line, "envmap %s: %s", sc->envmap.path, why);
        }
        it->has_envlight = 1;
        it->samples_env = samples_lights;
    }
    const envlight *lit = it->has_envlight && samples_lights ? &it->el : NULL;
    if (lights_build(&it->ls, sc, lit, scene_radius(sc), mem, err)) {
        integrator_free(it);
        return -1;
    }
    it->has_lights = 1;
    if (sc->integrator == INTEGRATOR_PATHTRACER && sc->nee == NEE_MIS &&
        lights_env_index(&it->ls) >= 0 && it->el.mode != ENVSAMPLING_MEDIANCUT &&
        it->el.mode != ENVSAMPLING_SIS) {
        /* MIS: sample the envmap at a fraction of its picks (lights.h); auto: the fraction that
         * minimizes variance x time for diffuse surfaces under this map (misfraction.h) */
        double c = sc->envsamplefraction >= 0
                       ? sc->envsamplefraction
                       : misfraction_choose(&it->el, INTEGRATOR_MIS_LIGHT_COST, NULL);
        lights_set_env_fraction(&it->ls, c);
        it->env_fraction = it->ls.env_fraction;
    }
    /* nothing to sample: no light, or the envmap alone (index 0) at c = 0 */
    int nothing = it->ls.n == 0 || (lights_env_index(&it->ls) == 0 && it->env_fraction == 0);
    it->nee = nothing ? NEE_OFF : sc->nee;
    it->build_seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    return 0;
}

void integrator_free(integrator *it)
{
    if (it->has_envlight) envlight_free(&it->el);
    if (it->has_lights) lights_free(&it->ls);
    it->has_envlight = it->has_lights = 0;
    prefiltered_free(it->pf);
    it->pf = NULL;
}

void integrator_intersect(integrator *it, const ray *r, scene_hit *out)
{
    integrator_intersect_diff(it, r, NULL, out);
}

void integrator_intersect_diff(integrator *it, const ray *r, const ray_diff *rd, scene_hit *out)
{
    int got = bvh_intersect(it->accel, r, &out->h);
    integrator_scene_hit(it, r, rd, got, out);
}

void integrator_scene_hit(integrator *it, const ray *r, const ray_diff *rd, int got, scene_hit *out)
{
    it->rays++;
    ray rr = *r;
    out->kind = SCENE_HIT_NOTHING;
    if (got == BVH_QUAD) { /* the quads are in the scene's BVH (lights_scene_bvh) */
        out->kind = SCENE_HIT_LIGHT;
        out->light = it->ls.quad_light[out->h.prim];
        out->t = out->h.t;
        return;
    }
    if (got) {
        out->kind = SCENE_HIT_GEOMETRY;
        rr.tmax = out->h.t;
    }
    int k;
    double t;
    /* quads outside the scene's BVH (bvh_build's): their own; a scene without pays no call */
    if (it->accel->prims_of.n_quads == 0 && it->has_lights && it->ls.n_quads > 0 &&
        lights_intersect_quad(&it->ls, &rr, &k, &t)) {
        out->kind = SCENE_HIT_LIGHT;
        out->light = k;
        out->t = t;
        return;
    }
    if (out->kind != SCENE_HIT_GEOMETRY) return;
    /* the shading frame, turned towards the ray's origin (two-sided surfaces) */
    const hit *h = &out->h;
    surface *s = &out->s;
    int outside = vec3_dot(r->d, h->ng) < 0;
    s->p = h->p;
    s->ng = outside ? h->ng : vec3_neg(h->ng);
    s->n = outside ? h->ns : vec3_neg(h->ns);
    if (vec3_dot(s->n, r->d) > 0) s->n = s->ng; /* interpolated normal facing away: use ng */
    s->entering = outside;
    brdf_surface_from_material(s, &it->sc->materials[h->material]);
    texshade_surface(it->sc, h, r, rd, s); /* footprint, then the texture maps */
}

int integrator_occluded(integrator *it, const ray *shadow)
{
    it->rays++;
    if (bvh_occluded(it->accel, shadow)) return 1;
    /* a quad light is opaque to shadow rays as it is to camera and BRDF rays, which stop at it
     * (either side): otherwise NEE would light what BRDF sampling finds in its shadow.  The
     * shadow ray to a point of light k stops short of k's plane, so k never blocks itself. */
    int k;
    double t;
    return it->accel->prims_of.n_quads == 0 && it->has_lights && it->ls.n_quads > 0 &&
           lights_intersect_quad(&it->ls, shadow, &k, &t);
}

int integrator_strata(int n, int stratify)
{
    if (!stratify) return 0;
    int m = (int)sqrt((double)n);
    while ((m + 1) * (m + 1) <= n) m++; /* sqrt can round down past a perfect square */
    return m;
}

int integrator_stratum(int j, int m, double *xi1, double *xi2)
{
    if (m <= 0 || j >= m * m) return 0;
    /* STEP(stratified): stratified light samples, slide 23 (How to Sample 2D Distribution): "works
     * with any sampling scheme (stratified etc.)": sample j of m x m moved into a cell of its own
     * of the unit square's m x m grid; return 1 (integrator.h) */
    /* STUB: (void)xi1; (void)xi2;
     * return 0; */
    *xi1 = ((j % m) + *xi1) / m; /* stratum (j mod m, j / m) of the grid */
    *xi2 = ((j / m) + *xi2) / m;
    return 1;
    /* END STEP(stratified) */
}

int integrator_light_sample(integrator *it, const surface *s, vec3 wo, int k, double xi1,
                            double xi2, double xi3, int stratified, light_sample *l, rgb *f_li_cos)
{
    if (!lights_sample(&it->ls, k, s->p, s->ng, xi1, xi2, xi3, stratified, l)) return 0;
    double cos_i = vec3_dot(s->n, l->wi);
    if (cos_i <= 0 || vec3_dot(s->ng, l->shadow.d) <= 0) return 0;
    rgb f = brdf_eval(s, wo, l->wi);
    if (rgb_is_black(f)) return 0;
    if (integrator_occluded(it, &l->shadow)) return 0; /* V = 0 */
    *f_li_cos = rgb_scale(rgb_mul(f, l->Li), cos_i);   /* f Li cos(theta) */
    return 1;
}
