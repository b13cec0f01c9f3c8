/* mirrorball.c - mirror-ball light probes (see include/envtex/envmaps/mirrorball.h). */
#include "envtex/envmaps/mirrorball.h"

#include <assert.h>

int mirrorball_dir_to_uv(vec3 d, uv2 *uv)
{
    vec3 r;
    if (vec3_unit_direction(d, &r)) return -1;
    /* n = (r + V) / |r + V| with V = +x, and |r + V|^2 = 2 (1 + r_x).  Behind the ball 1 + r_x
     * cancels; use 1 + r_x = (1 - r_x^2) / (1 - r_x) = (r_y^2 + r_z^2) / (1 - r_x) there. */
    double s2 = r.y * r.y + r.z * r.z;
    double one_plus_rx = r.x >= 0 ? 1.0 + r.x : s2 / (1.0 - r.x);
    if (one_plus_rx == 0) { /* r = -V: the whole rim; take its top point */
        *uv = (uv2){0.5, 0.0};
        return 0;
    }
    double k = 1.0 / sqrt(2.0 * one_plus_rx);
    double a = r.y * k, b = r.z * k; /* (a, b) = (n_y, n_z) */
    /* a = 2u - 1, b = 1 - 2v; a^2 + b^2 = (1 - r_x)/2 <= 1, clamped against rounding */
    uv->u = fmin(fmax(0.5 * (a + 1.0), 0.0), 1.0);
    uv->v = fmin(fmax(0.5 * (1.0 - b), 0.0), 1.0);
    return 0;
}

/* How far a^2 + b^2 may exceed 1 and still count as the rim: a few ulps of 1, the rounding of
 * a^2 + b^2 for a rim point that mirrorball_dir_to_uv (or a cos/sin) produced. */
#define MIRRORBALL_RIM_SLACK 1e-15

int mirrorball_uv_to_dir(uv2 uv, vec3 *d)
{
    double a = 2.0 * uv.u - 1.0, b = 1.0 - 2.0 * uv.v;
    double rho2 = a * a + b * b;
    if (!(rho2 <= 1.0 + MIRRORBALL_RIM_SLACK)) return -1; /* outside the ball (or NaN) */
    rho2 = fmin(rho2, 1.0);
    double nx = sqrt(1.0 - rho2); /* n = (sqrt(1 - a^2 - b^2), a, b) */
    /* r = 2 (n.V) n - V = 2 n_x n - (1, 0, 0) */
    *d = vec3_make(1.0 - 2.0 * rho2, 2.0 * nx * a, 2.0 * nx * b); /* 2 n_x^2 - 1 = 1 - 2 rho^2 */
    return 0;
}

rgb mirrorball_lookup_bilinear(const image *probe, vec3 d)
{
    assert(probe->w > 0 && probe->h > 0);
    uv2 uv;
    if (mirrorball_dir_to_uv(d, &uv)) return rgb_gray(0.0);
    return image_bilinear_clamp(probe, uv);
}
