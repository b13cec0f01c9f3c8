/* equalarea.c - equal-area environment maps (see include/envtex/envmaps/equalarea.h). */
#include "envtex/envmaps/equalarea.h"

#include <assert.h>

int equalarea_dir_to_uv(vec3 d, uv2 *uv)
{
    vec3 n;
    if (vec3_unit_direction(d, &n)) return -1;
    double s2 = n.x * n.x + n.y * n.y;                           /* sin^2 theta */
    double one_minus_z = n.z > 0 ? s2 / (1.0 + n.z) : 1.0 - n.z; /* 1 - z = (1 - z^2)/(1 + z) */
    double phi = s2 > 0 ? atan2(n.y, n.x) : 0.0; /* phi = atan2(y, x); 0 at the poles */
    if (phi < 0) phi += 2.0 * M_PI;              /* wrap to [0, 2 pi) */
    double u = phi / (2.0 * M_PI) + 0.0;         /* + 0.0 turns -0 into +0 */
    if (u >= 1.0) u = 0.0;                       /* -tiny + 2 pi rounds to 2 pi */
    uv->u = u;
    uv->v = 0.5 * one_minus_z; /* v = (1 - cos theta) / 2 */
    return 0;
}

vec3 equalarea_uv_to_dir(uv2 uv)
{
    double v = fmin(fmax(uv.v, 0.0), 1.0);
    double phi = 2.0 * M_PI * uv.u;       /* phi = 2 pi u */
    double z = 1.0 - 2.0 * v;             /* cos theta = 1 - 2 v */
    double s = 2.0 * sqrt(v * (1.0 - v)); /* sin theta = sqrt((1-z)(1+z)) */
    return vec3_make(s * cos(phi), s * sin(phi), z);
}

rgb equalarea_lookup_bilinear(const image *map, vec3 d)
{
    assert(map->w > 0 && map->h > 0);
    uv2 uv;
    if (equalarea_dir_to_uv(d, &uv)) return rgb_gray(0.0);
    return image_bilinear_wrap_u(map, uv);
}

double equalarea_texel_solid_angle(int w, int h)
{
    if (w < 1 || h < 1) return 0.0;
    /* d(omega) = d(cos theta) d(phi) = (2 / h) (2 pi / w) */
    return 4.0 * M_PI / ((double)w * (double)h);
}
