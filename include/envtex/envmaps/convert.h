/* convert.h - one environment in any of the six representations, looked up, measured and resampled
 * into any other (slide 9 (Environment Map Representations): "easy convert between cube, latlong";
 * slide 22 (Sampling General 2D Distributions)).
 *
 *     convert_env in = convert_view(&ll);                   // ll read by convert_read
 *     if (convert_resample(&in, CONVERT_CUBE, 256, 0, &cube, &err)) ... // 256 x 256 faces
 *     convert_write("sky.exr", &cube, &err);      // sky_px.exr sky_nx.exr ... sky_nz.exr
 *
 * Directions are in the envmap frame.  An output texel is the input's average over the
 * texel's solid angle, sum_k J_k L(d_k) / sum_k J_k over K x K strata, J = d(omega) / (du dv),
 * so the power sum L Omega is kept (docs/envmap-representations.md: the Jacobians, rim rules,
 * measured errors).  Disc lookups blend only the texels that meet the disc.
 */
#ifndef ENVTEX_CONVERT_H
#define ENVTEX_CONVERT_H

#include <stddef.h>

#include "envtex/core/budget.h"
#include "envtex/envmaps/cubemap.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* The representations; CONVERT_LATLONG is 0, so a zeroed struct holds a lat-long map. */
typedef enum convert_kind {
    CONVERT_LATLONG, /* latlong.h, and so on */
    CONVERT_CUBE,
    CONVERT_MIRRORBALL,
    CONVERT_ANGULAR,
    CONVERT_CYLINDRICAL,
    CONVERT_EQUALAREA,
    CONVERT_KINDS
} convert_kind;

/* A view: owns nothing. */
typedef struct convert_env {
    convert_kind kind;
    const image *img;    /* non-empty; all kinds but CONVERT_CUBE */
    const cubemap *cube; /* CONVERT_CUBE: size >= 1 */
    double max_height;   /* CONVERT_CYLINDRICAL: h > 0 */
} convert_env;

/* Owns its pixels: convert_map_free. */
typedef struct convert_map {
    convert_kind kind;
    image img;         /* every kind but CONVERT_CUBE */
    cubemap cube;      /* CONVERT_CUBE */
    double max_height; /* CONVERT_CYLINDRICAL */
    long bad_texels;   /* convert_read: bad channel values it made 0 */
} convert_map;

/* "latlong", "cube", "cross" (a cube), "mirrorball", "angular", "cylindrical", "equalarea":
 * 0, or -1 (kind untouched) if unknown. */
int convert_kind_parse(const char *word, convert_kind *kind);

/* The keyword of `kind` (a static string). */
const char *convert_kind_name(convert_kind kind);

/* The kind by shape: 2:1 lat-long, 4:3 or 3:4 a cube cross; others fail, naming the size and
 * the keywords (not the file). */
int convert_kind_detect(int w, int h, convert_kind *kind, error *err);

/* Default half height of a w x h cylindrical panorama, pi h / w (square texels on the
 * horizon); 0 if w < 1. */
double convert_cylindrical_height(int w, int h);

/* A view of *m (which must outlive it). */
convert_env convert_view(const convert_map *m);

/* Free the pixels; *m becomes an empty lat-long map.  Safe on a zeroed or freed map. */
void convert_map_free(convert_map *m);

/* Bilinear radiance at d as each module's (discs: above); black for a bad d and beyond a
 * cylinder.  Allocates nothing. */
rgb convert_lookup(const convert_env *env, vec3 d);

/* 6 faces for a cube, else 1, and the image of each. */
int convert_faces(const convert_env *env);
const image *convert_face_image(const convert_env *env, int face);

/* Steradians of the part of texel (c, r) of `face` (0 unless a cube) holding directions,
 * indices asserted; exact but for the angular map.  They sum to 4 pi (cylinder:
 * 4 pi sin(atan h)). */
double convert_texel_solid_angle(const convert_env *env, int face, int c, int r);

/* Power per channel: sum of L Omega over texels, in double (NaN if a texel is). */
rgb convert_power(const convert_env *env);

/* Default width W (2:1 kinds W x W/2, discs W x W, cube faces W x W) keeping texels per
 * radian: from E (2:1 width, cube 4 N, ball 2 W, angular 3 W / 2), E, E/4 cube, E/2 ball,
 * 2E/3 angular (>= 1).  Default K = ceil(2 E_in / E_out) in [4, CONVERT_MAX_SAMPLES]. */
int convert_default_width(const convert_env *in, convert_kind to);
int convert_default_samples(const convert_env *in, convert_kind to, int width);

#define CONVERT_MAX_SAMPLES 64

/* *in as kind `to` in *out (not freed first; empty on failure).  <= 0: the default width / K
 * (strata wider than half an input texel halved), else exactly K x K.  A cylinder gets
 * convert_cylindrical_height; the same kind and size is copied.  Fails on a bad size or K. */
int convert_resample(const convert_env *in, convert_kind to, int width, int samples,
                     convert_map *out, error *err);

/* The file of cube face `face` of PATH: "sky.exr" -> "sky_px.exr" ... "sky_nz.exr" (+X -X +Y
 * -Y +Z -Z; no extension: the suffix at the end).  -1 if it does not fit in `size` bytes. */
int convert_face_path(const char *path, int face, char *out, size_t size, error *err);

/* Read a map of kind `from` (NULL: by shape); "cube" reads the six convert_face_path files.
 * A cylinder gets convert_cylindrical_height; bad channel values become 0 (bad_texels).
 * Charged to `mem` (NULL: none) first, and stays.  *out overwritten; empty on failure. */
int convert_read(const char *path, const char *from, convert_map *out, budget *mem, error *err);

/* Write *m to `path` (format by extension, imageio.h); a cube map as its six convert_face_path
 * files, all or none (imageio_write_set). */
int convert_write(const char *path, const convert_map *m, error *err);

/* A cube map as one horizontal cross image, atomically. */
int convert_write_cross(const char *path, const convert_map *m, error *err);

#endif
