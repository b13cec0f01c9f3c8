/* angular.c - Debevec's angular map (see include/envtex/envmaps/angular.h). */
#include "envtex/envmaps/angular.h"

#include <assert.h>

/* How far rho may exceed 1 and still count as the rim: a few ulps of 1, the rounding of
 * sqrt(a^2 + b^2) for a rim point computed with cos / sin or by angular_dir_to_uv. */
#define ANGULAR_RIM_SLACK 1e-15

int angular_dir_to_uv(vec3 d, uv2 *uv)
{
    vec3 r;
    if (vec3_unit_direction(d, &r)) return -1;
    double s = sqrt(r.y * r.y + r.z * r.z); /* sin theta */
    if (s == 0) {                           /* on the axis: the centre, or the rim's top */
        *uv = r.x > 0 ? (uv2){0.5, 0.5} : (uv2){0.5, 0.0};
        return 0;
    }
    double theta = atan2(s, r.x);                  /* angle from +x, exact near 0 and pi */
    double k = theta / M_PI / s;                   /* rho / sin theta, rho = theta / pi */
    double a = r.y * k, b = r.z * k;               /* (a, b) = (y, z) / |(y, z)| * rho */
    uv->u = fmin(fmax(0.5 * (a + 1.0), 0.0), 1.0); /* a = 2u - 1, clamped against rounding */
    uv->v = fmin(fmax(0.5 * (1.0 - b), 0.0), 1.0); /* b = 1 - 2v */
    return 0;
}

int angular_uv_to_dir(uv2 uv, vec3 *d)
{
    double a = 2.0 * uv.u - 1.0, b = 1.0 - 2.0 * uv.v;
    double rho = sqrt(a * a + b * b);
    if (!(rho <= 1.0 + ANGULAR_RIM_SLACK)) return -1; /* outside the disc (or NaN) */
    if (rho == 0) {                                   /* the centre: no azimuth needed */
        *d = vec3_make(1.0, 0.0, 0.0);
        return 0;
    }
    double theta = M_PI * fmin(rho, 1.0); /* theta = pi rho */
    double k = sin(theta) / rho;
    *d = vec3_make(cos(theta), a * k, b * k); /* (cos theta, sin theta a/rho, sin theta b/rho) */
    return 0;
}

rgb angular_lookup_bilinear(const image *probe, vec3 d)
{
    assert(probe->w > 0 && probe->h > 0);
    uv2 uv;
    if (angular_dir_to_uv(d, &uv)) return rgb_gray(0.0);
    return image_bilinear_clamp(probe, uv);
}
