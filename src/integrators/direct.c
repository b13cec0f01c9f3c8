/* direct.c - direct lighting by light sampling: `integrator direct` and the path tracer's
 * next-event estimation (see include/envtex/integrators/direct.h). */
#include "envtex/integrators/direct.h"

#include "envtex/integrators/texshade.h"

/* The four numbers of a light sample, in this order: the selection's xc, then lights_sample's
 * (xi1, xi2, xi3).  (Statements, not an initializer list, whose order C leaves open.) */
static void draw(rng *g, double *xc, double xi[3])
{
    *xc = rng_uniform(g);
    for (int i = 0; i < 3; i++) xi[i] = rng_uniform(g);
}

/* One light sample of light k at s, of selection probability sel (lights.h): f Li cos / (sel pdf),
 * weighted by the power heuristic against BRDF sampling when mis (lightsamples light samples to
 * one BRDF sample); a point, directional or median-cut light: f E cos / sel. */
static rgb one_sample(integrator *it, const surface *s, vec3 wo, int k, double sel,
                      const double xi[3], int strat, int mis)
{
    light_sample l;
    rgb c;
    if (!integrator_light_sample(it, s, wo, k, xi[0], xi[1], xi[2], strat, &l, &c))
        return rgb_gray(0);
    if (l.is_delta) return rgb_scale(c, 1 / sel);
    double pl = sel * l.pdf; /* the density of this sample among all the light samples */
    double w = 1;
    if (mis) {
        double pb = brdf_pdf(s, wo, l.wi, it->sc->importancesampling);
        w = integrator_power_heuristic(it->sc->lightsamples, pl, 1, pb);
    }
    return rgb_scale(c, w / pl); /* f Li cos / pdf, MIS weighted */
}

/* `lightselection all` (the course's): the sum over every light k of (1/n_k) sum_j f Li cos / pdf
 * with n_k = lightsamples (stratified on a grid of k's own), or 1 for a point or directional
 * light (a delta: more samples would all be the same).  The envmap keeps each of its samples with
 * probability c = lights_selection_prob (xc). */
static rgb every_light(integrator *it, const surface *s, vec3 wo, rng *g, int mis)
{
    const lights *ls = &it->ls;
    rgb sum = rgb_gray(0);
    for (int k = 0; k < ls->n; k++) {
        int delta_light = k != lights_env_index(ls) && ls->sc->lights[k].kind != LIGHT_QUAD;
        int n = delta_light ? 1 : it->sc->lightsamples;
        int m = integrator_strata(n, it->sc->lightstratify);
        double sel = lights_selection_prob(ls, k);
        rgb lk = rgb_gray(0);
        for (int j = 0; j < n; j++) {
            double xc, xi[3];
            draw(g, &xc, xi);
            int strat = integrator_stratum(j, m, &xi[0], &xi[1]);
            if (!(xc < sel)) continue; /* the envmap not sampled this time (fraction c) */
            lk = rgb_add(lk, one_sample(it, s, wo, k, sel, xi, strat, mis));
        }
        sum = rgb_madd(sum, lk, 1.0 / n);
    }
    return sum;
}

/* `lightselection power`: lightsamples samples, each of one light picked by power (lights_pick),
 * averaged; stratified over all of them together. */
static rgb by_power(integrator *it, const surface *s, vec3 wo, rng *g, int mis)
{
    int n = it->sc->lightsamples, m = integrator_strata(n, it->sc->lightstratify);
    rgb sum = rgb_gray(0);
    for (int j = 0; j < n; j++) {
        double xc, xi[3];
        draw(g, &xc, xi);
        int strat = integrator_stratum(j, m, &xi[0], &xi[1]);
        int k;
        double pick;
        if (!lights_pick(&it->ls, xc, &k, &pick)) continue; /* none this time (envmap fraction) */
        sum = rgb_add(sum, one_sample(it, s, wo, k, pick, xi, strat, mis));
    }
    return rgb_scale(sum, 1.0 / n);
}

static rgb light_sampling(integrator *it, const surface *s, vec3 wo, rng *g, int mis)
{
    if (brdf_is_delta(s) || !it->has_lights) return rgb_gray(0);
    if (it->ls.selection == LIGHTSELECTION_POWER) return by_power(it, s, wo, g, mis);
    return every_light(it, s, wo, g, mis);
}

rgb direct_lighting(integrator *it, const surface *s, vec3 wo, rng *g)
{
    return light_sampling(it, s, wo, g, 0);
}

rgb direct_lighting_mis(integrator *it, const surface *s, vec3 wo, rng *g)
{
    return light_sampling(it, s, wo, g, 1);
}

/* What a ray that leaves the scene sees after `depth` perfect-specular bounces. */
static rgb escaped(integrator *it, vec3 d, int depth)
{
    if (depth > 0 && it->sc->envmiss == ENVMISS_BLACK) return rgb_gray(0);
    return envmap_radiance(&it->env, d); /* bilinear: no other strategy competes here */
}

rgb direct_radiance_hit(integrator *it, ray r, const ray_diff *rd0, const scene_hit *first, rng *g)
{
    rgb L = rgb_gray(0), beta = rgb_gray(1);
    ray_diff rd = {0};
    if (rd0) rd = *rd0;
    scene_hit sh = *first;
    for (int depth = 0;; depth++) {
        if (depth > 0) integrator_intersect_diff(it, &r, &rd, &sh);
        if (sh.kind == SCENE_HIT_NOTHING) return rgb_fma(L, beta, escaped(it, r.d, depth));
        if (sh.kind == SCENE_HIT_LIGHT)
            return rgb_fma(L, beta, lights_quad_radiance(&it->ls, sh.light, r.d));
        vec3 wo = vec3_neg(vec3_normalize(r.d));
        L = rgb_fma(L, beta, sh.s.emission);
        if (!brdf_is_delta(&sh.s)) return rgb_fma(L, beta, direct_lighting(it, &sh.s, wo, g));
        /* a mirror or glass: follow it to something that can be lit */
        if (depth >= it->maxdepth) return L;
        brdf_sample_result bs;
        double xi1 = rng_uniform(g), xi2 = rng_uniform(g), xi3 = rng_uniform(g);
        if (!brdf_sample(&sh.s, wo, it->sc->importancesampling, xi1, xi2, xi3, &bs)) return L;
        beta = rgb_mul(beta, bs.weight);
        ray_diff next;
        texshade_delta_diff(&sh.s, &rd, wo, bs.wi, &next); /* the footprint goes on */
        rd = next;
        r = ray_spawn(sh.s.p, sh.s.ng, bs.wi);
    }
}
