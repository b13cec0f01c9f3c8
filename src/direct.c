/* direct.c - `integrator direct`: direct lighting by light sampling (see include/envtex/direct.h). */
#include "envtex/direct.h"

#include "envtex/texshade.h"

rgb direct_lighting(integrator *it, const surface *s, vec3 wo, rng *g)
{
    rgb sum = rgb_gray(0);
    if (brdf_is_delta(s) || !it->has_lights) return sum;
    const lights *ls = &it->ls;
    int n = it->sc->lightsamples;
    int m = it->sc->lightstratify ? (int)sqrt((double)n) : 0; /* an m x m grid of strata */
    while (m > 0 && (m + 1) * (m + 1) <= n) m++;
    for (int k = 0; k < ls->n; k++) {
        int is_delta_light = k != lights_env_index(ls) && ls->sc->lights[k].kind != LIGHT_QUAD;
        int nk = is_delta_light ? 1 : n; /* a point or directional light needs one sample */
        rgb lk = rgb_gray(0);
        for (int j = 0; j < nk; j++) {
            double xi1 = rng_uniform(g), xi2 = rng_uniform(g), xi3 = rng_uniform(g);
            int strat = m > 0 && j < m * m && !is_delta_light;
            if (strat) { /* stratum (j mod m, j / m) of the grid */
                xi1 = ((j % m) + xi1) / m;
                xi2 = ((j / m) + xi2) / m;
            }
            light_sample ls_s;
            if (!lights_sample(ls, k, s->p, s->ng, xi1, xi2, xi3, strat, &ls_s)) continue;
            double cos_i = vec3_dot(s->n, ls_s.wi);
            if (cos_i <= 0 || vec3_dot(s->ng, ls_s.shadow.d) <= 0) continue;
            rgb f = brdf_eval(s, wo, ls_s.wi);
            if (rgb_is_black(f)) continue;
            if (integrator_occluded(it, &ls_s.shadow)) continue;
            /* f cos Li / pdf  (a delta light: f cos E) */
            double w = ls_s.is_delta ? cos_i : cos_i / ls_s.pdf;
            lk = rgb_fma(lk, f, rgb_scale(ls_s.Li, w));
        }
        sum = rgb_madd(sum, lk, 1.0 / nk);
    }
    return sum;
}

/* What a ray that leaves the scene sees after `depth` perfect-specular bounces. */
static rgb escaped(integrator *it, vec3 d, int depth)
{
    if (depth > 0 && it->sc->envmiss == ENVMISS_BLACK) return rgb_gray(0);
    return envmap_radiance(&it->env, d); /* bilinear: no other strategy competes here */
}

rgb direct_radiance(integrator *it, ray r, rng *g) { return direct_radiance_diff(it, r, NULL, g); }

rgb direct_radiance_diff(integrator *it, ray r, const ray_diff *rd0, rng *g)
{
    rgb L = rgb_gray(0), beta = rgb_gray(1);
    ray_diff rd = {0};
    if (rd0) rd = *rd0;
    for (int depth = 0;; depth++) {
        scene_hit sh;
        integrator_intersect_diff(it, &r, &rd, &sh);
        if (sh.kind == 0) return rgb_fma(L, beta, escaped(it, r.d, depth));
        if (sh.kind == 2) return rgb_fma(L, beta, lights_quad_radiance(&it->ls, sh.light, r.d));
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
