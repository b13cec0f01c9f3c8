/* cylindrical.c - cylindrical environment maps (see include/envtex/envmaps/cylindrical.h). */
#include "envtex/envmaps/cylindrical.h"

#include <assert.h>

static int valid_height(double h) { return isfinite(h) && h > 0; }

int cylindrical_dir_to_uv(vec3 d, double max_height, uv2 *uv)
{
    vec3 n;
    if (!valid_height(max_height) || vec3_unit_direction(d, &n)) return -1;
    double s = sqrt(n.x * n.x + n.y * n.y);   /* sin theta: distance from the axis */
    if (s == 0) return -1;                    /* a pole: infinitely high on the cylinder */
    double zc = n.z / s;                      /* z_cyl = z / sqrt(x^2 + y^2) = cot theta */
    if (!(fabs(zc) <= max_height)) return -1; /* beyond the cut (also zc = inf for tiny s) */
    double phi = atan2(n.y, n.x);             /* phi = atan2(y, x) */
    if (phi < 0) phi += 2.0 * M_PI;           /* wrap to [0, 2 pi) */
    double u = phi / (2.0 * M_PI) + 0.0;      /* + 0.0 turns -0 into +0 */
    if (u >= 1.0) u = 0.0;                    /* -tiny + 2 pi rounds to 2 pi */
    uv->u = u;
    uv->v = 0.5 - zc / (2.0 * max_height); /* v = 1/2 - z_cyl / (2 h), in [0, 1] */
    return 0;
}

int cylindrical_uv_to_dir(uv2 uv, double max_height, vec3 *d)
{
    if (!valid_height(max_height) || !isfinite(uv.u) || !(uv.v >= 0 && uv.v <= 1)) return -1;
    double phi = 2.0 * M_PI * uv.u;                         /* phi = 2 pi u */
    double zc = (0.5 - uv.v) * 2.0 * max_height;            /* z_cyl = (1/2 - v) 2 h */
    *d = vec3_normalize(vec3_make(cos(phi), sin(phi), zc)); /* length >= 1: no zero division */
    return 0;
}

rgb cylindrical_lookup_bilinear(const image *map, double max_height, vec3 d)
{
    assert(map->w > 0 && map->h > 0);
    uv2 uv;
    if (cylindrical_dir_to_uv(d, max_height, &uv)) return rgb_gray(0.0);
    return image_bilinear_wrap_u(map, uv);
}
