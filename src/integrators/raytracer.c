/* raytracer.c - the Whitted integrator with reflection maps (raytracer.h). */
#include "envtex/integrators/raytracer.h"

#include "envtex/reflection/fresnel.h"
#include "envtex/integrators/texshade.h"

void raytracer_init(raytracer *rt, const scene *sc, const bvh *accel)
{
    rt->sc = sc;
    rt->accel = accel;
    scene_environment(sc, &rt->env);
    rt->maxdepth = sc->maxdepth < 0 ? RAYTRACER_UNLIMITED_DEPTH : sc->maxdepth;
    rt->rays = 0;
    rt->shade = NULL;
    rt->shade_ctx = NULL;
}

static rgb trace(raytracer *rt, ray r, const ray_diff *rd, int depth, double weight);

/* Blinn-Phong direct lighting from point and directional lights, with shadow rays.  kd and ks
 * come from the (textured) surface s, the exponent from the material. */
static rgb direct_lights(raytracer *rt, const hit *h, const surface *s, vec3 view, int highlight)
{
    rgb sum = rgb_gray(0);
    vec3 n = s->n;
    int has_kd = !rgb_is_black(s->kd), has_ks = highlight && !rgb_is_black(s->ks);
    if (!has_kd && !has_ks) return sum;
    for (int i = 0; i < rt->sc->n_lights; i++) {
        const scene_light *l = &rt->sc->lights[i];
        vec3 ldir;
        double atten = 1.0;
        ray shadow;
        if (l->kind == LIGHT_DIRECTIONAL) {
            ldir = l->dir;
            shadow = ray_spawn(h->p, h->ng, ldir);
        } else if (l->kind == LIGHT_POINT) {
            vec3 to = vec3_sub(l->pos, h->p);
            double d = vec3_length(to);
            if (!(d > 0)) continue;
            ldir = vec3_scale(to, 1 / d);
            atten = l->atten[0] + l->atten[1] * d + l->atten[2] * d * d; /* c + l d + q d^2 */
            if (!(atten > 0)) continue;
            shadow = ray_spawn_to(h->p, h->ng, l->pos);
        } else {
            continue; /* quad lights belong to the sampling integrators */
        }
        /* The course's terms, each clamped on its own (FORMAT.md, and the CSE 167 shader it
         * comes from): a light below the horizon (N.L < 0) still gives a highlight where
         * N.H > 0.  On a closed object its shadow ray enters the object and V = 0; on an open
         * surface (a floor lit from just below its plane) the course shows that highlight, so
         * skipping the light at N.L <= 0 rendered such course scenes darker than the course. */
        rgb c = rgb_scale(s->kd, fmax(vec3_dot(n, ldir), 0.0)); /* kd max(N.L, 0) */
        if (has_ks) {
            vec3 half = vec3_normalize(vec3_add(ldir, view)); /* H = (L + V) / |L + V| */
            /* N.H in [0, 1]: two unit vectors' dot product rounds up to 1 + 2^-52, and
             * (1 + 2^-52)^s is Inf for a huge s (1e18): clamp to the highlight's centre */
            double ndoth = fmin(fmax(vec3_dot(n, half), 0.0), 1.0);
            c = rgb_madd(c, s->ks, pow(ndoth, s->shininess)); /* ks max(N.H, 0)^s; 0^0 = 1 */
        }
        if (rgb_is_black(c)) continue; /* nothing to shadow: no shadow ray */
        rt->rays++;
        if (bvh_occluded(rt->accel, &shadow)) continue; /* V = 0 */
        sum = rgb_fma(sum, l->color, rgb_scale(c, 1 / atten));
    }
    return sum;
}

static rgb miss(raytracer *rt, vec3 d, int depth)
{
    /* camera rays see the environment as the background; reflected rays see it unless the
     * scene asks for the lecture's contrast, `envmiss black` */
    if (depth > 0 && rt->sc->envmiss == ENVMISS_BLACK) return rgb_gray(0);
    /* STEP(reflection): a ray that misses the scene, slide 5 (Using Environment for Reflection
     * Map): "directly use envmap if miss geometry" (reflection/envmap.h) */
    /* STUB: (void)rt; (void)d;
     * return rgb_gray(0); */
    return envmap_radiance(&rt->env, d);
    /* END STEP(reflection) */
}

static rgb shade(raytracer *rt, ray r, const ray_diff *rd, int depth, double weight,
                 const hit *found);

static rgb trace(raytracer *rt, ray r, const ray_diff *rd, int depth, double weight)
{
    hit h;
    int got = bvh_intersect(rt->accel, &r, &h);
    return shade(rt, r, rd, depth, weight, got ? &h : NULL);
}

/* What ray r sees at its closest hit, found (NULL: it missed), at depth `depth`. */
static rgb shade(raytracer *rt, ray r, const ray_diff *rd, int depth, double weight,
                 const hit *found)
{
    rt->rays++;
    if (!found) return miss(rt, r.d, depth);
    const hit h = *found;
    const material *m = &rt->sc->materials[h.material];
    vec3 d = vec3_normalize(r.d), view = vec3_neg(d);
    int outside = vec3_dot(d, h.ng) < 0;
    /* shade with normals facing the viewer (two-sided surfaces) */
    surface s;
    s.p = h.p;
    s.n = outside ? h.ns : vec3_neg(h.ns);
    s.ng = outside ? h.ng : vec3_neg(h.ng);
    if (vec3_dot(s.n, view) < 0) s.n = s.ng; /* interpolated normal facing away: fall back */
    s.entering = outside;
    brdf_surface_from_material(&s, m);
    texshade_surface(rt->sc, &h, &r, rd, &s); /* footprint; kd, ks, emission, n from the maps */
    vec3 n = s.n;

    /* I = A + E + lights (E: `emission` or its light map) */
    int reflect = 1;
    rgb c;
    if (rt->shade) {
        c = rt->shade(rt->shade_ctx, m, &s, view, &reflect); /* prefiltered.h */
    } else {
        c = rgb_add(m->ambient, s.emission);
        int highlight = m->brdf == BRDF_PHONG || m->brdf == BRDF_GGX;
        c = rgb_add(c, direct_lights(rt, &h, &s, view, highlight));
    }
    if (depth >= rt->maxdepth) return c;
    ray_diff next;

    if (m->brdf == BRDF_GLASS) {
        /* entering: eta = ior / 1; leaving: eta = 1 / ior */
        double eta = outside ? m->ior : 1.0 / m->ior;
        double cos_i = vec3_dot(view, n);
        double F = fresnel_dielectric(cos_i, eta);
        vec3 refl = vec3_reflect(d, n);
        if (weight * F > RAYTRACER_MIN_WEIGHT) {
            texshade_delta_diff(&s, rd, view, refl, &next);
            c = rgb_madd(c, trace(rt, ray_spawn(h.p, h.ng, refl), &next, depth + 1, weight * F), F);
        }
        vec3 tdir;
        if (F < 1 && weight * (1 - F) > RAYTRACER_MIN_WEIGHT && fresnel_refract(d, n, eta, &tdir)) {
            texshade_delta_diff(&s, rd, view, tdir, &next);
            rgb Lt = trace(rt, ray_spawn(h.p, h.ng, tdir), &next, depth + 1, weight * (1 - F));
            c = rgb_madd(c, Lt, 1 - F);
        }
        return c;
    }
    /* STEP(reflection): the mirror, slide 5 (Using Environment for Reflection Map): "Color +=
     * reflectivity * Color of reflected ray", the reflected ray traced from the hit, recursively;
     * its weight, the footprint it carries (texshade_delta_diff) and when it stops: raytracer.h */
    /* STUB: (void)reflect; (void)weight; (void)rd; */
    double ks = rgb_max(s.ks);
    if (reflect && ks > 0 && weight * ks > RAYTRACER_MIN_WEIGHT) {
        /* Color += reflectivity * Color of reflected ray (ks: `specular` or its map) */
        vec3 refl = vec3_reflect(d, n);
        texshade_delta_diff(&s, rd, view, refl, &next);
        rgb li = trace(rt, ray_spawn(h.p, h.ng, refl), &next, depth + 1, weight * ks);
        c = rgb_fma(c, s.ks, li);
    }
    /* END STEP(reflection) */
    return c;
}

rgb raytracer_trace(raytracer *rt, ray r) { return trace(rt, r, NULL, 0, 1.0); }

rgb raytracer_trace_hit(raytracer *rt, ray r, const ray_diff *rd, int got, const hit *h)
{
    return shade(rt, r, rd, 0, 1.0, got ? h : NULL);
}
