/* analyticdirect.c - exact unshadowed quad-light irradiance (see include/envtex/analyticdirect.h). */
#include "envtex/analyticdirect.h"

vec3 analyticdirect_irradiance_vector(const scene_light *l, vec3 p)
{
    vec3 v[4] = {l->pos, vec3_add(l->pos, l->ab), vec3_add(vec3_add(l->pos, l->ab), l->ac),
                 vec3_add(l->pos, l->ac)};
    vec3 phi = vec3_make(0, 0, 0);
    for (int i = 0; i < 4; i++) {
        vec3 a = vec3_normalize(vec3_sub(v[i], p)), b = vec3_normalize(vec3_sub(v[(i + 1) % 4], p));
        double theta = acos(fmax(-1.0, fmin(1.0, vec3_dot(a, b)))); /* theta_i */
        vec3 gamma = vec3_cross(a, b);                             /* Gamma_i, normalized below */
        double gl = vec3_length(gamma);
        if (gl > 0) phi = vec3_madd(phi, gamma, 0.5 * theta / gl); /* Phi = 1/2 sum theta_i Gamma_i */
    }
    return phi;
}

rgb analyticdirect_radiance(integrator *it, ray r, rng *g)
{
    (void)g;
    scene_hit sh;
    integrator_intersect(it, &r, &sh);
    if (sh.kind == 0) return envmap_radiance(&it->env, r.d);
    if (sh.kind == 2) return lights_quad_radiance(&it->ls, sh.light, r.d);
    const surface *s = &sh.s;
    rgb L = s->emission;
    for (int i = 0; i < it->sc->n_lights; i++) {
        const scene_light *l = &it->sc->lights[i];
        if (l->kind != LIGHT_QUAD) continue;
        /* The corners a, a+ab, a+ab+ac, a+ac turn clockwise seen from the emitting side
         * (ac x ab), so Phi points from p towards the light when p is on that side, and
         * Phi . n < 0 (clamped to 0) when p is behind the light or faces away from it. */
        double irr = vec3_dot(analyticdirect_irradiance_vector(l, s->p), s->n);
        if (irr > 0) L = rgb_fma(L, rgb_scale(s->kd, irr / M_PI), l->color); /* kd/pi L Phi.n */
    }
    return L;
}
