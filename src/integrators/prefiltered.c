/* prefiltered.c - the integrator that shades from illumination maps (see
 * include/envtex/integrators/prefiltered.h). */
#include "envtex/integrators/prefiltered.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "envtex/envlight/envlight.h"
#include "envtex/envmaps/latlong.h"

/* Does material m show a diffuse part, a Phong lobe (its maps count: texshade.h sets kd, ks)? */
static int has_diffuse(const material *m)
{
    return m->brdf == BRDF_PHONG && (!rgb_is_black(m->diffuse) || m->diffusemap);
}
static int has_lobe(const material *m)
{
    return m->brdf == BRDF_PHONG && (!rgb_is_black(m->specular) || m->specularmap);
}

/* Refuse what the maps cannot shade, before any is built. */
static int check_scene(const scene *sc, const envmap *env, error *err)
{
    for (int i = 0; i < sc->n_materials; i++) {
        const material *m = &sc->materials[i];
        if (m->brdf == BRDF_GGX)
            return error_set(err, sc->path, 0,
                             "the 'prefiltered' integrator has maps for "
                             "diffuse and Phong lobes only: a 'brdf ggx' material has neither (use "
                             "'brdf phong', or another integrator)");
        if (has_lobe(m) && m->shininess > PREFILTER_MAX_SHININESS)
            return error_set(err, sc->path, 0,
                             "the 'prefiltered' integrator makes Phong maps of "
                             "shininess up to %g, not %g (use 'brdf mirror' for a perfect mirror)",
                             PREFILTER_MAX_SHININESS, m->shininess);
    }
    if (env->present && !envlight_transform_is_conformal(&env->to_env))
        return error_set(err, sc->path, sc->envmap.line,
                         "envmap %s: its transform is not a "
                         "rotation (nor a rotation times a uniform scale), so the 'prefiltered' "
                         "integrator's maps, made in the envmap's frame, cannot follow it (put "
                         "only 'rotate' before 'envmap')",
                         sc->envmap.path);
    return 0;
}

/* Charge a w x w/2 map of RGB floats to the run's budget before making it. */
static int charge_map(prefiltered *pf, const scene *sc, int w, const char *what, error *err)
{
    double bytes = (double)w * (w / 2) * 3 * sizeof(float);
    if (budget_charge(pf->mem, bytes, sc->path, 0, err, "%s map of %d x %d texels", what, w, w / 2))
        return -1;
    pf->charged += bytes;
    return 0;
}

/* The distinct shininesses of the materials with a lobe, counted up to `most` + 1. */
static int count_exponents(const scene *sc, int most)
{
    int n = 0;
    for (int i = 0; i < sc->n_materials && n <= most; i++) {
        const material *m = &sc->materials[i];
        int seen = !has_lobe(m);
        for (int j = 0; j < i && !seen; j++)
            seen = has_lobe(&sc->materials[j]) && sc->materials[j].shininess == m->shininess;
        n += !seen;
    }
    return n;
}

/* One Phong map per distinct shininess; phong_of[i] names material i's. */
static int build_phong(prefiltered *pf, const scene *sc, const convert_env *view, error *err)
{
    int n = sc->n_materials;
    if (pf->lit && count_exponents(sc, PREFILTERED_MAX_PHONG_MAPS) > PREFILTERED_MAX_PHONG_MAPS)
        return error_set(err, sc->path, 0,
                         "the 'prefiltered' integrator makes one Phong map per "
                         "distinct shininess, at most %d: this scene has more (round the "
                         "exponents to fewer values)",
                         PREFILTERED_MAX_PHONG_MAPS);
    pf->phong_of = malloc((size_t)(n > 0 ? n : 1) * sizeof *pf->phong_of);
    pf->phong_s = malloc((size_t)(n > 0 ? n : 1) * sizeof *pf->phong_s);
    pf->phong = calloc((size_t)(n > 0 ? n : 1), sizeof *pf->phong);
    if (!pf->phong_of || !pf->phong_s || !pf->phong)
        return error_set(err, sc->path, 0, "out of memory");
    for (int i = 0; i < n; i++) {
        const material *m = &sc->materials[i];
        pf->phong_of[i] = -1;
        if (!has_lobe(m) || !pf->lit) continue;
        int k = 0;
        while (k < pf->n_phong && pf->phong_s[k] != m->shininess) k++;
        if (k == pf->n_phong) { /* a new exponent: its map */
            double s = m->shininess;
            if (charge_map(pf, sc, prefilter_phong_width(s), "a Phong", err)) return -1;
            if (prefilter_phong(view, s, prefilter_phong_width(s), &pf->phong[k], err))
                return error_prefix(err, "%s: the Phong map of shininess %g", sc->path, s);
            pf->phong_s[k] = s;
            pf->n_phong++;
        }
        pf->phong_of[i] = k;
    }
    return 0;
}

static int build(prefiltered *pf, const scene *sc, error *err)
{
    convert_env view = envmap_view(pf->env);
    int diffuse = 0;
    for (int i = 0; i < sc->n_materials; i++) diffuse |= has_diffuse(&sc->materials[i]);
    if (pf->lit && diffuse && pf->method == IRRADIANCE_SH9) {
        prefilter_sh9 sh;
        if (prefilter_sh9_project(&view, &sh, err)) return error_prefix(err, "%s", sc->path);
        prefilter_sh9_matrix(&sh, &pf->q);
    } else if (pf->lit && diffuse) {
        if (charge_map(pf, sc, PREFILTERED_IRRADIANCE_WIDTH, "an irradiance", err)) return -1;
        if (prefilter_irradiance_exact(&view, PREFILTERED_IRRADIANCE_WIDTH, &pf->irradiance, err))
            return error_prefix(err, "%s: the irradiance map", sc->path);
    }
    return build_phong(pf, sc, &view, err);
}

int prefiltered_init(prefiltered **out, raytracer *rt, budget *mem, error *err)
{
    const scene *sc = rt->sc;
    *out = NULL;
    if (check_scene(sc, &rt->env, err)) return -1;
    prefiltered *pf = calloc(1, sizeof *pf);
    if (!pf) return error_set(err, sc->path, 0, "out of memory");
    pf->env = &rt->env;
    pf->mem = mem;
    pf->materials = sc->materials;
    pf->lit = rt->env.present && sc->envmiss == ENVMISS_ENVMAP;
    pf->method = sc->prefilter;
    clock_t t0 = clock();
    if (build(pf, sc, err)) {
        prefiltered_free(pf);
        return -1;
    }
    pf->build_seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    rt->shade = prefiltered_shade;
    rt->shade_ctx = pf;
    *out = pf;
    return 0;
}

void prefiltered_free(prefiltered *pf)
{
    if (!pf) return;
    budget_release(pf->mem, pf->charged);
    image_free(&pf->irradiance);
    for (int k = 0; k < pf->n_phong; k++) image_free(&pf->phong[k]);
    free(pf->phong);
    free(pf->phong_s);
    free(pf->phong_of);
    free(pf);
}

rgb prefiltered_irradiance(const prefiltered *pf, vec3 n)
{
    if (!pf->lit) return rgb_gray(0);
    vec3 ne = envmap_to_frame(pf->env, n); /* world -> envmap frame */
    rgb e;
    if (pf->method == IRRADIANCE_SH9) {
        vec3 u;
        if (vec3_unit_direction(ne, &u)) return rgb_gray(0);
        e = rgb_scale(prefilter_sh9_quadratic_eval(&pf->q, u), 1.0 / M_PI); /* E(n) / pi */
        /* nine coefficients ring below 0 behind a bright source: light is never negative */
        e = rgb_make(fmax(e.r, 0.0), fmax(e.g, 0.0), fmax(e.b, 0.0));
    } else {
        if (!pf->irradiance.px) return rgb_gray(0); /* no material asked for it */
        e = latlong_lookup_bilinear(&pf->irradiance, ne);
    }
    return rgb_scale(e, pf->env->scale);
}

rgb prefiltered_shade(void *ctx, const material *m, const surface *s, vec3 view, int *reflect)
{
    const prefiltered *pf = ctx;
    rgb c = s->emission;
    if (s->kind == BRDF_MIRROR || s->kind == BRDF_GLASS) return c; /* the ray tracer bounces */
    *reflect = 0; /* a Phong lobe: its map, not a mirror bounce */
    if (!rgb_is_black(s->kd)) c = rgb_fma(c, s->kd, prefiltered_irradiance(pf, s->n)); /* kd E/pi */
    int k = pf->phong_of[m - pf->materials];
    if (k >= 0 && !rgb_is_black(s->ks)) {
        vec3 r = vec3_reflect(vec3_neg(view), s->n); /* the mirror direction of the view */
        rgb L = latlong_lookup_bilinear(&pf->phong[k], envmap_to_frame(pf->env, r));
        double cos_r = fmax(0.0, vec3_dot(r, s->n)); /* the course lobe's cosine, at its axis */
        c = rgb_fma(c, s->ks, rgb_scale(L, pf->env->scale * cos_r)); /* ks (n.r) phong_S(r) */
    }
    return c;
}
