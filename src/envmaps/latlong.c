/* latlong.c - latitude-longitude environment maps (see include/envtex/envmaps/latlong.h). */
#include "envtex/envmaps/latlong.h"

#include "envtex/core/stepcheck.h"

int latlong_dir_to_uv(vec3 d, uv2 *uv)
{
    if (vec3_unit_direction(d, &d)) return -1; /* any finite non-zero length */
    /* STEP(latlong): the lat-long lookup of a direction: its spherical coordinates (theta from +z,
     * phi about z) as the map's (u, v) (latlong.h), slide 9 (Environment Map Representations):
     * "convert direction to spherical coords, direct lookup" */
    /* STUB: uv->u = 0; uv->v = 0; return -1; */
    double rxy = sqrt(d.x * d.x + d.y * d.y);
    double theta = atan2(rxy, d.z);               /* theta = acos(z / |d|), stable form */
    double phi = rxy > 0 ? atan2(d.y, d.x) : 0.0; /* phi = atan2(y, x), 0 at the poles */
    if (phi < 0) phi += 2 * M_PI;                 /* wrap to [0, 2 pi) */
    double u = phi / (2 * M_PI);
    if (u >= 1.0) u = 0.0; /* -tiny + 2 pi rounds to 2 pi */
    uv->u = u;
    uv->v = theta / M_PI;
    return 0;
    /* END STEP(latlong) */
}

vec3 latlong_uv_to_dir(uv2 uv)
{
    /* STEP(latlong): the way back: the unit direction whose spherical coordinates the map's (u, v)
     * stand for (slide 9 (Environment Map Representations)) */
    /* STUB: (void)uv; return vec3_make(0, 0, 1); */
    double theta = M_PI * uv.v, phi = 2 * M_PI * uv.u;
    double s = sin(theta);
    return vec3_make(s * cos(phi), s * sin(phi), cos(theta));
    /* END STEP(latlong) */
}

rgb latlong_lookup_bilinear(const image *map, vec3 d)
{
    uv2 uv;
    if (latlong_dir_to_uv(d, &uv)) return rgb_gray(0);
    STEPCHECK_COORD(uv.u, 0.0, 1.0, "latlong", "u");
    STEPCHECK_COORD(uv.v, 0.0, 1.0, "latlong", "v");
    return image_bilinear_wrap_u(map, uv);
}

rgb latlong_lookup_nearest(const image *map, vec3 d)
{
    uv2 uv;
    if (latlong_dir_to_uv(d, &uv)) return rgb_gray(0);
    STEPCHECK_COORD(uv.u, 0.0, 1.0, "latlong", "u");
    STEPCHECK_COORD(uv.v, 0.0, 1.0, "latlong", "v");
    int x = (int)(uv.u * map->w), y = (int)(uv.v * map->h);
    if (x >= map->w) x = map->w - 1;
    if (y >= map->h) y = map->h - 1;
    return image_get(map, x, y);
}

double latlong_texel_solid_angle(int r, int w, int h)
{
    /* d(omega) = d(cos theta) d(phi): no sin theta in the lecture's (u = cos theta, phi) form */
    double ct0 = cos(M_PI * r / h), ct1 = cos(M_PI * (r + 1) / h);
    return (ct0 - ct1) * 2 * M_PI / w;
}
