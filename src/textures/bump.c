/* bump.c - Blinn's bump mapping (see include/envtex/textures/bump.h). */
#include "envtex/textures/bump.h"

int bump_normal(vec3 n, vec3 ng, vec3 dp_ds, vec3 dp_dt, double dh_ds, double dh_dt,
                double strength, vec3 *out)
{
    *out = n;
    /* the tangents projected onto n's plane, T - (T.n) n, so that with no slope the result is
     * n itself (an interpolated shading normal is not dP/ds x dP/dt) */
    dp_ds = vec3_madd(dp_ds, n, -vec3_dot(dp_ds, n));
    dp_dt = vec3_madd(dp_dt, n, -vec3_dot(dp_dt, n));
    vec3 base = vec3_cross(dp_ds, dp_dt); /* dP/ds x dP/dt, now along n */
    double side = vec3_dot(base, n);
    if (!(side != 0) || !isfinite(side)) return -1; /* no plane, or NaN */
    double ks = strength * dh_ds, kt = strength * dh_dt;
    if (!isfinite(ks) || !isfinite(kt)) return -1;
    /* STEP(bump): Blinn's bump mapping (Blinn 1978), slide 42 (Bump Mapping): "texture = change in
     * surface normal": the normal perturbed by the height's derivatives dh/ds and dh/dt (bump.h) */
    /* STUB: vec3 np = base; */
    /* N' = dP/ds x dP/dt + k dh/ds (n x dP/dt) + k dh/dt (dP/ds x n) */
    vec3 np = vec3_add(
        base, vec3_add(vec3_scale(vec3_cross(n, dp_dt), ks), vec3_scale(vec3_cross(dp_ds, n), kt)));
    /* END STEP(bump) */
    if (side < 0) np = vec3_neg(np); /* left-handed (s, t): turn to n's side */
    vec3 u;
    if (vec3_unit_direction(np, &u)) return -1;
    double c = vec3_dot(u, ng);
    if (c < BUMP_MIN_COS) {
        /* tilt back along ng: the tangential part t = u - c ng keeps its direction and
         * n' = normalize(t + a ng) with a / |t| chosen so n'.ng = BUMP_MIN_COS */
        vec3 t = vec3_madd(u, ng, -c);
        double tl = vec3_length(t);
        if (!(tl > 0)) {
            *out = ng;
            return 0;
        }
        double a = BUMP_MIN_COS / sqrt(1.0 - BUMP_MIN_COS * BUMP_MIN_COS) * tl;
        if (vec3_unit_direction(vec3_madd(t, ng, a), &u)) return -1;
    }
    *out = u;
    return 0;
}
