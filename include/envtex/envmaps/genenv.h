/* genenv.h - procedural HDR environments for the repository's own test data, 2:1 lat-long
 * maps: constant (furnace tests), sky, sun (the sky and a bright disc), axes (L(d) =
 * (d + 1) / 2: red +x, green +y, blue +z).
 *
 *     genenv_params p = genenv_defaults();
 *     image env; if (genenv_make(GENENV_SUN, &p, &env, &err)) ...
 */
#ifndef ENVTEX_GENENV_H
#define ENVTEX_GENENV_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"

typedef enum genenv_kind { GENENV_CONSTANT, GENENV_SKY, GENENV_SUN, GENENV_AXES } genenv_kind;

typedef struct genenv_params {
    int width;                /* map width; height = width / 2 (at least 1) */
    double value;             /* constant: the radiance */
    double sun_ratio;         /* sun: disc radiance / mean sky radiance, default 1e5 */
    double sun_radius_deg;    /* sun: angular radius in degrees, default 0.5 */
    double sun_elevation_deg; /* sun: height above the horizon in [-90, 90], default 35 */
    double sun_azimuth_deg;   /* sun: phi of the sun (any finite angle), default 60 */
} genenv_params;

genenv_params genenv_defaults(void);

/* "constant", "sky", "sun", "axes" -> *kind; -1 if unknown. */
int genenv_kind_parse(const char *name, genenv_kind *kind);

/* The map into *out (image_free).  -1 with *err for a bad size, or a parameter not finite or
 * outside its range (value >= 0, sun_ratio > 0, sun_radius_deg in (0, 90)). */
int genenv_make(genenv_kind kind, const genenv_params *p, image *out, error *err);

#endif
