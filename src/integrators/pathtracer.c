/* pathtracer.c - `integrator pathtracer` with next-event estimation and MIS
 * (see include/envtex/integrators/pathtracer.h). */
#include "envtex/integrators/pathtracer.h"

#include "envtex/integrators/direct.h"
#include "envtex/integrators/texshade.h"

/* What the path remembers of its last bounce, to weigh the light it finds. */
typedef struct path_state {
    nee_mode nee;       /* as run: off without lights */
    int n_light;        /* lightsamples */
    int specular_chain; /* only camera and perfect-specular bounces so far */
    int last_delta;     /* the ray came from the camera or a perfect-specular bounce */
    double brdf_pdf;    /* pdf of the last BRDF sample (non-delta), for MIS */
} path_state;

/* Light found by following the path is counted unless next-event estimation has already
 * counted it (nee on) or weighs against it (mis).  NEE never samples from a delta bounce. */
static int path_counts_light(const path_state *ps) { return ps->last_delta || ps->nee == NEE_OFF; }

/* The environment along direction d, which left the scene after `bounce` bounces: the
 * bilinear reflection map down a specular chain, else the piecewise-constant light, weighted
 * by the power heuristic against NEE's density of d (mis) or dropped when NEE sampled it. */
static rgb escaped_radiance(integrator *it, const path_state *ps, vec3 d, int bounce)
{
    const scene *sc = it->sc;
    if (ps->specular_chain)
        return bounce > 0 && sc->envmiss == ENVMISS_BLACK ? rgb_gray(0)
                                                          : envmap_radiance(&it->env, d);
    if (!it->has_envlight) return rgb_gray(0);
    int counts = path_counts_light(ps);
    int ke = lights_env_index(&it->ls);
    double pdf_env = 0;
    /* point lights (median cut, sis) have no density: only NEE finds them */
    int points = it->el.mode == ENVSAMPLING_MEDIANCUT || it->el.mode == ENVSAMPLING_SIS;
    int mis_env = !counts && ps->nee == NEE_MIS && ke >= 0 && !points;
    rgb Le = mis_env ? envlight_radiance_pdf(&it->el, d, &pdf_env) : envlight_radiance(&it->el, d);
    if (counts) return Le;
    if (mis_env) {
        double pl = lights_selection_prob(&it->ls, ke) * pdf_env; /* lights.h */
        return rgb_scale(Le, integrator_power_heuristic(1, ps->brdf_pdf, ps->n_light, pl));
    }
    return ke >= 0 ? rgb_gray(0) : Le; /* sampled by NEE (point lights: only by NEE) */
}

/* Quad light sh->light hit by ray r: its radiance, weighted as escaped_radiance's. */
static rgb quad_light_radiance(integrator *it, const path_state *ps, const scene_hit *sh, ray r)
{
    rgb Le = lights_quad_radiance(&it->ls, sh->light, r.d);
    if (path_counts_light(ps)) return Le;
    if (ps->nee != NEE_MIS) return rgb_gray(0);
    vec3 d = vec3_normalize(r.d);
    double t = sh->t * vec3_length(r.d);
    /* lightsamples x P(light k's sample) x pdf_k: NEE's density of this point */
    double pl =
        lights_selection_prob(&it->ls, sh->light) * lights_quad_pdf(&it->ls, sh->light, d, t);
    return rgb_scale(Le, integrator_power_heuristic(1, ps->brdf_pdf, ps->n_light, pl));
}

/* Russian roulette: survive with q = min(1, largest throughput component), then divide by q.
 * Without it a zero throughput (a black surface) ends the path: nothing further along can add
 * to L.  Returns 0 to end the path. */
static int path_survives(const scene *sc, rgb *beta, rng *g)
{
    if (sc->russianroulette) {
        double q = fmin(1.0, rgb_max(*beta));
        if (!(rng_uniform(g) < q)) return 0;
        *beta = rgb_scale(*beta, 1 / q);
        return 1;
    }
    return !(beta->r == 0 && beta->g == 0 && beta->b == 0);
}

/* Ray differentials follow the path while it is a chain of perfect mirror / glass bounces from
 * the camera; the first diffuse or glossy bounce drops them (raydiff.h: no differential of a
 * random direction), and textures further on use their no-footprint fallback. */
rgb pathtracer_radiance_hit(integrator *it, ray r, const ray_diff *rd0, const scene_hit *first,
                            rng *g)
{
    ray_diff rd = {0};
    if (rd0) rd = *rd0;
    const scene *sc = it->sc;
    path_state ps = {it->has_lights ? it->nee : NEE_OFF, sc->lightsamples, 1, 1, 0};
    rgb L = rgb_gray(0), beta = rgb_gray(1);
    scene_hit sh = *first;
    for (int bounce = 0;; bounce++) {
        if (bounce > 0) integrator_intersect_diff(it, &r, &rd, &sh); /* the next vertex */
        if (sh.kind == SCENE_HIT_NOTHING)
            return rgb_fma(L, beta, escaped_radiance(it, &ps, r.d, bounce));
        if (sh.kind == SCENE_HIT_LIGHT)
            return rgb_fma(L, beta, quad_light_radiance(it, &ps, &sh, r));
        const surface *s = &sh.s;
        vec3 wo = vec3_neg(vec3_normalize(r.d));
        L = rgb_fma(L, beta, s->emission);            /* emissive geometry is not a sampled light */
        if (bounce >= it->maxdepth) break;            /* a path may have at most maxdepth bounces */
        if (!brdf_is_delta(s) && ps.nee != NEE_OFF) { /* next-event estimation: direct light */
            rgb Ld = ps.nee == NEE_MIS ? direct_lighting_mis(it, s, wo, g)
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
        beta = rgb_mul(beta, bs.weight); /* beta *= f cos / pdf */
        ps.specular_chain = ps.specular_chain && bs.is_delta;
        ps.last_delta = bs.is_delta;
        ps.brdf_pdf = bs.pdf;
        if (!path_survives(sc, &beta, g)) break;
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
