/* genenv.h - procedural HDR environments, so the repository makes its own test data.
 * All are lat-long maps (2:1) in the envmap frame (+z up, row 0 at the zenith; latlong.h).
 *
 *   constant  L = value everywhere (furnace tests)
 *   sky       a smooth sky: blue zenith to a bright horizon, a dim brown ground
 *   sun       the sky plus a small disc whose radiance is sun_ratio times the sky's mean
 *   axes      L(d) = (d + 1) / 2 per channel: red towards +x, green towards +y, blue towards +z;
 *             orientation tests read the direction back from the colour
 *
 *     genenv_params p = genenv_defaults();
 *     p.width = 256;
 *     image env; if (genenv_make(GENENV_SUN, &p, &env, &err)) ...
 */
#ifndef ENVTEX_GENENV_H
#define ENVTEX_GENENV_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"

typedef enum genenv_kind { GENENV_CONSTANT, GENENV_SKY, GENENV_SUN, GENENV_AXES } genenv_kind;

typedef struct genenv_params {
    int width;               /* map width; height = width / 2 (at least 1) */
    double value;            /* constant: the radiance */
    double sun_ratio;        /* sun: disc radiance / mean sky radiance, default 1e5 */
    double sun_radius_deg;   /* sun: angular radius in degrees, default 0.5 (the real sun: 0.27) */
    double sun_elevation_deg;/* sun: height above the horizon in [-90, 90], default 35 */
    double sun_azimuth_deg;  /* sun: phi of the sun (any finite angle), default 60 */
} genenv_params;

genenv_params genenv_defaults(void);

/* Parse "constant", "sky", "sun", "axes"; -1 if unknown. */
int genenv_kind_parse(const char *name, genenv_kind *kind);

/* Make the map into *out (allocated; free with image_free).  Returns 0, or -1 with *err set on
 * a size image_check_size refuses or a parameter out of range: value finite and >= 0 (0 is a
 * black map), sun_ratio finite and > 0, sun_radius_deg in (0, 90), the sun's angles finite. */
int genenv_make(genenv_kind kind, const genenv_params *p, image *out, error *err);

#endif
