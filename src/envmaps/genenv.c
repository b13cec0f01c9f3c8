/* genenv.c - procedural HDR environments (see include/envtex/envmaps/genenv.h). */
#include "envtex/envmaps/genenv.h"

#include <string.h>

#include "envtex/envmaps/latlong.h"

genenv_params genenv_defaults(void)
{
    genenv_params p;
    p.width = 512;
    p.value = 1.0;
    p.sun_ratio = 1e5;
    p.sun_radius_deg = 0.5;
    p.sun_elevation_deg = 35;
    p.sun_azimuth_deg = 60;
    return p;
}

int genenv_kind_parse(const char *name, genenv_kind *kind)
{
    static const char *names[] = {"constant", "sky", "sun", "axes"};
    for (int i = 0; i < 4; i++)
        if (strcmp(name, names[i]) == 0) {
            *kind = (genenv_kind)i;
            return 0;
        }
    return -1;
}

/* The smooth sky: zenith blue, white-ish horizon, dim ground, continuous at the horizon. */
static rgb sky(vec3 d)
{
    double z = d.z;
    if (z >= 0) {
        double t = sqrt(z); /* fast change just above the horizon, as a real sky has */
        rgb horizon = rgb_make(1.0, 0.95, 0.9), zenith = rgb_make(0.25, 0.45, 1.0);
        return rgb_add(rgb_scale(horizon, 1 - t), rgb_scale(zenith, t));
    }
    double t = fmin(1.0, -z * 8); /* blend into the ground within ~7 degrees */
    rgb horizon = rgb_make(1.0, 0.95, 0.9), ground = rgb_make(0.25, 0.2, 0.15);
    return rgb_add(rgb_scale(horizon, 1 - t), rgb_scale(ground, t));
}

int genenv_make(genenv_kind kind, const genenv_params *p, image *out, error *err)
{
    out->w = out->h = 0;
    out->px = NULL;
    if (!(p->value >= 0) || !isfinite(p->value))
        return error_set(err, NULL, 0, "value must be finite and >= 0");
    if (!(p->sun_ratio > 0) || !isfinite(p->sun_ratio))
        return error_set(err, NULL, 0, "sun ratio must be finite and > 0");
    if (!(p->sun_radius_deg > 0 && p->sun_radius_deg < 90))
        return error_set(err, NULL, 0, "sun radius must be in (0, 90) degrees");
    if (!(p->sun_elevation_deg >= -90 && p->sun_elevation_deg <= 90)) /* NaN fails too */
        return error_set(err, NULL, 0, "sun elevation must be in [-90, 90] degrees");
    if (!isfinite(p->sun_azimuth_deg)) return error_set(err, NULL, 0, "sun azimuth must be finite");
    int w = p->width, h = p->width / 2 > 0 ? p->width / 2 : 1;
    if (image_alloc(out, w, h, err)) return -1;

    double mean = 0; /* solid-angle weighted mean of the sky, for the sun's radiance */
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            vec3 d = latlong_uv_to_dir((uv2){(x + 0.5) / w, (y + 0.5) / h});
            rgb c;
            switch (kind) {
            case GENENV_CONSTANT: c = rgb_gray(p->value); break;
            case GENENV_AXES: c = rgb_make((d.x + 1) / 2, (d.y + 1) / 2, (d.z + 1) / 2); break;
            default: c = sky(d); break;
            }
            mean += rgb_avg(c) * latlong_texel_solid_angle(y, w, h);
            image_set(out, x, y, c);
        }
    if (kind != GENENV_SUN) return 0;
    mean /= 4 * M_PI;

    /* the sun disc, antialiased: each texel gets the covered fraction of 8 x 8 sub-samples */
    double el = p->sun_elevation_deg * M_PI / 180, az = p->sun_azimuth_deg * M_PI / 180;
    vec3 sun = vec3_make(cos(el) * cos(az), cos(el) * sin(az), sin(el));
    double cos_r = cos(p->sun_radius_deg * M_PI / 180);
    double L_sun = p->sun_ratio * mean;
    for (int y = 0; y < h; y++) {
        /* skip rows that cannot touch the disc */
        double th0 = M_PI * y / h, th1 = M_PI * (y + 1) / h, th_sun = acos(sun.z), r = acos(cos_r);
        if (th1 < th_sun - r - M_PI / h || th0 > th_sun + r + M_PI / h) continue;
        for (int x = 0; x < w; x++) {
            int inside = 0;
            for (int j = 0; j < 8; j++)
                for (int i = 0; i < 8; i++) {
                    vec3 d =
                        latlong_uv_to_dir((uv2){(x + (i + 0.5) / 8) / w, (y + (j + 0.5) / 8) / h});
                    inside += vec3_dot(d, sun) >= cos_r;
                }
            if (!inside) continue;
            double f = inside / 64.0;
            rgb c = image_get(out, x, y);
            image_set(out, x, y, rgb_add(rgb_scale(c, 1 - f), rgb_gray(L_sun * f)));
        }
    }
    return 0;
}
