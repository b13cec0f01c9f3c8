/* pathtracer.c - `integrator pathtracer` with next-event estimation and MIS
 * (see include/envtex/integrators/pathtracer.h). */
#include "envtex/integrators/pathtracer.h"

#include "envtex/integrators/direct.h"
#include "envtex/integrators/texshade.h"

rgb pathtracer_radiance(integrator *it, ray r, rng *g) { return pathtracer_radiance_diff(it, r, NULL, g); }

/* Ray differentials follow the path while it is a chain of perfect mirror / glass bounces from
 * the camera; the first diffuse or glossy bounce drops them (raydiff.h: no differential of a
 * random direction), and textures further on use their no-footprint fallback. */
rgb pathtracer_radiance_diff(integrator *it, ray r, const ray_diff *rd0, rng *g)
{
    ray_diff rd = {0};
    if (rd0) rd = *rd0;
    const scene *sc = it->sc;
    nee_mode nee = it->has_lights ? it->nee : NEE_OFF;
    int n_light = sc->lightsamples;
    rgb L = rgb_gray(0), beta = rgb_gray(1);
    int specular_chain = 1;  /* only camera and perfect-specular bounces so far */
    int last_delta = 1;      /* the ray came from the camera or a perfect-specular bounce */
    double brdf_pdf_prev = 0; /* pdf of the last BRDF sample (non-delta), for MIS */
    for (int bounce = 0;; bounce++) {
        scene_hit sh;
        integrator_intersect_diff(it, &r, &rd, &sh);
        /* light found by following the path: counted unless next-event estimation has
         * already counted it (nee on), or weighted against it (mis) */
        int counts = last_delta || nee == NEE_OFF; /* NEE never samples from a delta bounce */
        if (sh.kind == SCENE_HIT_NOTHING) {
            rgb Le;
            if (specular_chain) {
                Le = bounce > 0 && sc->envmiss == ENVMISS_BLACK ? rgb_gray(0) : envmap_radiance(&it->env, r.d);
            } else if (!it->has_envlight) {
                Le = rgb_gray(0);
            } else {
                int ke = lights_env_index(&it->ls);
                double pdf_env = 0;
                int mis_env = !counts && nee == NEE_MIS && ke >= 0 && it->el.mode != ENVSAMPLING_MEDIANCUT;
                Le = mis_env ? envlight_radiance_pdf(&it->el, r.d, &pdf_env) : envlight_radiance(&it->el, r.d);
                if (!counts) {
                    if (mis_env) {
                        double pl = lights_selection_prob(&it->ls, ke) * pdf_env; /* lights.h */
                        Le = rgb_scale(Le, integrator_power_heuristic(1, brdf_pdf_prev, n_light, pl));
                    } else if (ke >= 0) {
                        Le = rgb_gray(0); /* sampled by NEE (median cut: only by NEE) */
                    }
                }
            }
            return rgb_fma(L, beta, Le);
        }
        if (sh.kind == SCENE_HIT_LIGHT) {
            rgb Le = lights_quad_radiance(&it->ls, sh.light, r.d);
            if (!counts) {
                if (nee == NEE_MIS) {
                    vec3 d = vec3_normalize(r.d);
                    double t = sh.t * vec3_length(r.d);
                    /* lightsamples x P(light k's sample) x pdf_k: NEE's density of this point */
                    double pl = lights_selection_prob(&it->ls, sh.light) *
                                lights_quad_pdf(&it->ls, sh.light, d, t);
                    Le = rgb_scale(Le, integrator_power_heuristic(1, brdf_pdf_prev, n_light, pl));
                } else {
                    Le = rgb_gray(0);
                }
            }
            return rgb_fma(L, beta, Le);
        }
        const surface *s = &sh.s;
        vec3 wo = vec3_neg(vec3_normalize(r.d));
        L = rgb_fma(L, beta, s->emission); /* emissive geometry is not a sampled light */
        if (bounce >= it->maxdepth) break; /* a path may have at most maxdepth bounces */
        int delta = brdf_is_delta(s);
        if (!delta && nee != NEE_OFF) { /* next-event estimation: the direct light at this vertex */
            rgb Ld = nee == NEE_MIS ? direct_lighting_mis(it, s, wo, g)
                                    : direct_lighting(it, s, wo, g);
            L = rgb_fma(L, beta, Ld);
        }
        brdf_sample_result bs;
        double xi1 = rng_uniform(g), xi2 = rng_uniform(g), xi3 = rng_uniform(g);
        if (!brdf_sample(s, wo, sc->importancesampling, xi1, xi2, xi3, &bs)) break;
        /* An interpolated normal n can send a reflected wi below the geometric surface (ng . wi
         * <= 0): through the object, to light that NEE never sees (its shadow rays leave along
         * ng only, integrator_light_sample).  Such a wi carries nothing, for both strategies. */
        if (!bs.is_delta && vec3_dot(s->ng, bs.wi) <= 0) break;
        beta = rgb_mul(beta, bs.weight);
        specular_chain = specular_chain && bs.is_delta;
        last_delta = bs.is_delta;
        brdf_pdf_prev = bs.pdf;
        if (sc->russianroulette) {
            /* survive with q = min(1, largest throughput component); divide by q if it does */
            double q = fmin(1.0, rgb_max(beta));
            if (!(rng_uniform(g) < q)) break;
            beta = rgb_scale(beta, 1 / q);
        } else if (beta.r == 0 && beta.g == 0 && beta.b == 0) {
            break; /* nothing further along can add to L (a black surface): stop rather than
                    * bounce up to maxdepth (1000 with -1) for nothing.  With roulette, q = 0
                    * already stops it. */
        }
        if (bs.is_delta) {
            ray_diff next;
            texshade_delta_diff(s, &rd, wo, bs.wi, &next);
            rd = next;
        } else {
            rd.has = 0;
        }
        r = ray_spawn(s->p, s->ng, bs.wi);
    }
    return L;
}
