/* analyticdirect.c - exact unshadowed quad-light irradiance (analyticdirect.h). */
#include "envtex/integrators/analyticdirect.h"

/* Clipping keeps a corner of height >= 0 and adds a crossing on an edge whose ends differ in
 * sign: at most 2 corners an edge, 8 for the quad.  Exactly, a convex quad cut by a plane has at
 * most 5; but where p lies in (or very near) the light's plane every height rounds to about 0,
 * the signs can alternate +, -, +, - round the quad, and the clipped polygon has 6 corners. */
#define CLIPPED_MAX 8

/* Phi = 1/2 sum_i theta_i Gamma_i over the n-gon v, seen from p */
static vec3 polygon_irradiance_vector(const vec3 *v, int n, vec3 p)
{
    vec3 phi = vec3_make(0, 0, 0);
    for (int i = 0; i < n; i++) {
        vec3 a = vec3_sub(v[i], p), b = vec3_sub(v[(i + 1) % n], p);
        double la = vec3_length(a), lb = vec3_length(b);
        if (!(la > 0) || !(lb > 0)) continue; /* p on a corner: that edge subtends nothing */
        a = vec3_scale(a, 1 / la);
        b = vec3_scale(b, 1 / lb);
        double theta = acos(fmax(-1.0, fmin(1.0, vec3_dot(a, b)))); /* theta_i */
        vec3 gamma = vec3_cross(a, b);                              /* Gamma_i, normalized below */
        double gl = vec3_length(gamma);
        /* Phi = 1/2 sum theta_i Gamma_i */
        if (gl > 0) phi = vec3_madd(phi, gamma, 0.5 * theta / gl);
    }
    return phi;
}

/* the corners a, a+ab, a+ab+ac, a+ac */
static void quad_corners(const scene_light *l, vec3 v[4])
{
    v[0] = l->pos;
    v[1] = vec3_add(l->pos, l->ab);
    v[2] = vec3_add(vec3_add(l->pos, l->ab), l->ac);
    v[3] = vec3_add(l->pos, l->ac);
}

vec3 analyticdirect_irradiance_vector(const scene_light *l, vec3 p)
{
    vec3 v[4];
    quad_corners(l, v);
    return polygon_irradiance_vector(v, 4, p);
}

double analyticdirect_irradiance(const scene_light *l, vec3 p, vec3 n)
{
    vec3 v[4];
    quad_corners(l, v);
    /* the back of the light does not emit: p must lie on the side of ac x ab */
    if (!(vec3_dot(vec3_sub(p, l->pos), vec3_cross(l->ac, l->ab)) > 0)) return 0;
    /* clip to the upper half-space of p (Sutherland-Hodgman against one plane): height
     * h = (v - p) . n, and an edge crossing h = 0 is cut at v_i + (v_j - v_i) h_i / (h_i - h_j) */
    double h[4];
    for (int i = 0; i < 4; i++) h[i] = vec3_dot(vec3_sub(v[i], p), n);
    vec3 c[CLIPPED_MAX];
    int m = 0;
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) % 4;
        if (h[i] >= 0) c[m++] = v[i];
        if ((h[i] >= 0) != (h[j] >= 0)) /* v_i + (v_j - v_i) h_i / (h_i - h_j) */
            c[m++] = vec3_add(v[i], vec3_scale(vec3_sub(v[j], v[i]), h[i] / (h[i] - h[j])));
    }
    if (m < 3) return 0; /* the whole light is below the horizon */
    /* The corners turn clockwise seen from the emitting side (ac x ab), so Phi points from p
     * towards the light; the clipped polygon lies above the horizon, so Phi . n >= 0 up to
     * rounding */
    return fmax(0.0, vec3_dot(polygon_irradiance_vector(c, m, p), n));
}

rgb analyticdirect_radiance_hit(integrator *it, ray r, const ray_diff *rd, const scene_hit *sh,
                                rng *g)
{
    (void)rd, (void)g;
    if (sh->kind == SCENE_HIT_NOTHING) return envmap_radiance(&it->env, r.d);
    if (sh->kind == SCENE_HIT_LIGHT) return lights_quad_radiance(&it->ls, sh->light, r.d);
    const surface *s = &sh->s;
    rgb L = s->emission;
    for (int i = 0; i < it->sc->n_lights; i++) {
        const scene_light *l = &it->sc->lights[i];
        if (l->kind != LIGHT_QUAD) continue;
        double irr = analyticdirect_irradiance(l, s->p, s->n); /* Phi . n of the visible part */
        if (irr > 0) L = rgb_fma(L, rgb_scale(s->kd, irr / M_PI), l->color); /* kd/pi L Phi.n */
    }
    return L;
}
