/* cylindrical.c - cylindrical environment maps (see include/envtex/cylindrical.h). */
#include "envtex/cylindrical.h"

#include <assert.h>

/* d / |d| for a finite non-zero d, else -1.  Divides by the largest |component| first, so the
 * length of a huge or subnormal vector neither overflows nor underflows. */
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
    uv->v = 0.5 - zc / (2.0 * max_height);    /* v = 1/2 - z_cyl / (2 h), in [0, 1] */
    return 0;
}

int cylindrical_uv_to_dir(uv2 uv, double max_height, vec3 *d)
{
    if (!valid_height(max_height) || !isfinite(uv.u) || !(uv.v >= 0 && uv.v <= 1)) return -1;
    double phi = 2.0 * M_PI * uv.u;                  /* phi = 2 pi u */
    double zc = (0.5 - uv.v) * 2.0 * max_height;     /* z_cyl = (1/2 - v) 2 h */
    *d = vec3_normalize(vec3_make(cos(phi), sin(phi), zc)); /* length >= 1: no zero division */
    return 0;
}

rgb cylindrical_lookup_bilinear(const image *map, double max_height, vec3 d)
{
    assert(map->w > 0 && map->h > 0);
    uv2 uv;
    if (cylindrical_dir_to_uv(d, max_height, &uv)) return rgb_gray(0.0);
    int w = map->w, h = map->h;
    /* texel centres at integers: x in [-0.5, W - 0.5), y in [-0.5, H - 0.5] */
    double x = uv.u * w - 0.5, y = uv.v * h - 0.5;
    double x0 = floor(x), y0 = floor(y);
    double ax = x - x0, ay = y - y0;
    int i0 = (int)x0, j0 = (int)y0;
    int i1 = i0 + 1, j1 = j0 + 1;
    if (i0 < 0) i0 += w;   /* wrap in phi */
    if (i1 >= w) i1 -= w;
    if (j0 < 0) j0 = 0;    /* clamp at the cuts */
    if (j1 > h - 1) j1 = h - 1;
    rgb c00 = image_get(map, i0, j0), c10 = image_get(map, i1, j0);
    rgb c01 = image_get(map, i0, j1), c11 = image_get(map, i1, j1);
    /* L = (1-ax)(1-ay) c00 + ax (1-ay) c10 + (1-ax) ay c01 + ax ay c11 */
    rgb top = rgb_add(rgb_scale(c00, 1.0 - ax), rgb_scale(c10, ax));
    rgb bottom = rgb_add(rgb_scale(c01, 1.0 - ax), rgb_scale(c11, ax));
    return rgb_add(rgb_scale(top, 1.0 - ay), rgb_scale(bottom, ay));
}
