/* direct.c - `integrator direct`: direct lighting by light sampling (see include/envtex/direct.h). */
#include "envtex/direct.h"

#include "envtex/texshade.h"

rgb direct_lighting(integrator *it, const surface *s, vec3 wo, rng *g)
{
    rgb sum = rgb_gray(0);
    if (brdf_is_delta(s) || !it->has_lights) return sum;
    const lights *ls = &it->ls;
    int n = it->sc->lightsamples;
    int m = integrator_strata(n, it->sc->lightstratify);
    for (int k = 0; k < ls->n; k++) {
        int is_delta_light = k != lights_env_index(ls) && ls->sc->lights[k].kind != LIGHT_QUAD;
        int nk = is_delta_light ? 1 : n; /* a point or directional light needs one sample */
        rgb lk = rgb_gray(0);
        for (int j = 0; j < nk; j++) {
            double xi1 = rng_uniform(g), xi2 = rng_uniform(g), xi3 = rng_uniform(g);
            int strat = !is_delta_light && integrator_stratum(j, m, &xi1, &xi2);
            light_sample l;
            rgb c;
            if (!integrator_light_sample(it, s, wo, k, xi1, xi2, xi3, strat, &l, &c)) continue;
            lk = rgb_madd(lk, c, l.is_delta ? 1 : 1 / l.pdf); /* f Li cos / pdf (delta: f E cos) */
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
