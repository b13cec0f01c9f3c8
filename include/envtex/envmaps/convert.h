/* convert.h - one environment held in any of the six representations (latlong.h, cubemap.h,
 * mirrorball.h, angular.h, cylindrical.h, equalarea.h), looked up, measured, and resampled into
 * any other.  Lecture "Environment, Texture Maps", slides 13-14: "cubemap coord to vec:
 * normalize ... easy convert between cube, latlong"; slide 22: d(omega) = d(cos theta) d(phi).
 *
 *     convert_map ll = {0}, cube = {0};
 *     if (convert_read("sky.exr", NULL, &ll, NULL, &err)) ...        // 2:1: lat-long
 *     convert_env in = convert_view(&ll);
 *     if (convert_resample(&in, CONVERT_CUBE, 256, 0, &cube, &err)) ... // 256 x 256 faces
 *     rgb L = convert_lookup(&in, d);                                 // d in the envmap frame
 *     rgb P = convert_power(&in);                                     // integral of L d(omega)
 *     convert_write("sky.exr", &cube, &err);     // sky_px.exr sky_nx.exr ... sky_nz.exr
 *     convert_map_free(&ll); convert_map_free(&cube);
 *
 * Resampling (convert_resample).  An output texel is the AVERAGE OF THE INPUT OVER THE TEXEL'S
 * OWN SOLID ANGLE, not a point sample at its centre: K x K stratified points (the centres of a
 * K x K grid inside the texel's (u, v) square) are mapped through the output representation's
 * uv -> direction, the input is looked up there (bilinear, convert_lookup), and the values are
 * weighted by the Jacobian J = d(omega) / (du dv) at each point:
 *
 *     L_out(texel) = sum_k J_k L_in(d_k) / sum_k J_k          (~ integral L d(omega) / Omega)
 *
 * so the power  P = sum over texels of L(texel) Omega(texel)  (convert_power, with the exact
 * solid angle of each texel) is kept: within 0.5% for a lat-long -> cube -> lat-long or
 * lat-long -> mirror ball -> lat-long round trip of a map with a sun 10^5 times brighter than
 * its sky, away from the poles and from straight behind the ball (tests/unit/envmaps/test_convert.c;
 * docs/envmap-representations.md and README.md give measured figures: a sun at a pole is off
 * by about 6.5% in any output, as the lat-long input's bilinear lookup over-weights its pole
 * row; a sun straight behind a mirror ball or an angular map, on their rim, by up to ~20%).
 * A round trip blurs by about one texel and never turns the map.  Points outside the output's
 * valid region (the corners of a mirror-ball or angular image) are left out; a rim texel that
 * meets the disc but none of whose points falls inside it takes the value at its point nearest
 * the centre (DISC_PULL in convert.c), and a texel wholly outside is 0 with no solid angle.  Directions the input does not hold (a cylinder's
 * caps) look up as 0, so power there is lost, as it must be.
 *
 * With the default samples a stratum is also halved along its longer side while its centre
 * lines span more than half an input texel (pi / E_in radians, E_in as for
 * convert_default_samples), so that texels far larger than 2 pi / E_out along one axis -- the
 * pole rows of an equal-area map, the rim ring of a mirror ball -- still see every input texel
 * twice; the halves are weighted by their share of the stratum.  (Without it a 0.5-degree sun
 * at the zenith lost 67% of its power to a default equal-area map.)
 *
 * The Jacobians (dA = du dv, (a, b) = (2u - 1, 1 - 2v) the disc coordinates, rho = |(a, b)|):
 *     latlong      d(omega) = sin(theta) d(theta) d(phi)       J = 2 pi^2 sin(pi v)
 *     equalarea    d(omega) = d(cos theta) d(phi)              J = 4 pi
 *     cylindrical  d(omega) = d(phi) dz / (1 + z^2)^(3/2)      J = 4 pi h / (1 + z^2)^(3/2)
 *     cube face    d(omega) = dsc dtc / (1 + sc^2 + tc^2)^(3/2)  J = 4 / (1 + sc^2 + tc^2)^(3/2)
 *     mirrorball   omega(rho) = 4 pi rho^2: d(omega) = 4 da db J = 16 inside the disc
 *     angular      theta = pi rho: d(omega) = pi sin(pi rho) / rho da db
 *                                                              J = 4 pi sin(pi rho) / rho
 *
 * Lookups in the disc representations (mirror ball, angular) use only the texels whose square
 * meets the disc, with the bilinear weights renormalized over them: the texels outside hold no
 * environment (black after a conversion, the photographer's background in a probe), and
 * blending them in would darken the whole rim, i.e. the direction straight behind the ball.
 */
#ifndef ENVTEX_CONVERT_H
#define ENVTEX_CONVERT_H

#include <stddef.h>

#include "envtex/core/budget.h"
#include "envtex/envmaps/cubemap.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/core/vec.h"

/* The representations.  The order is fixed: CONVERT_LATLONG is 0, so a zeroed struct holds a
 * lat-long map. */
typedef enum convert_kind {
    CONVERT_LATLONG,     /* latlong.h */
    CONVERT_CUBE,        /* cubemap.h: six faces (from six files or a cross) */
    CONVERT_MIRRORBALL,  /* mirrorball.h */
    CONVERT_ANGULAR,     /* angular.h */
    CONVERT_CYLINDRICAL, /* cylindrical.h, with its half height h (max_height) */
    CONVERT_EQUALAREA,   /* equalarea.h */
    CONVERT_KINDS
} convert_kind;

/* An environment in one representation, as a view: owns nothing. */
typedef struct convert_env {
    convert_kind kind;
    const image *img;     /* every kind but CONVERT_CUBE; non-empty */
    const cubemap *cube;  /* CONVERT_CUBE; size >= 1 */
    double max_height;    /* CONVERT_CYLINDRICAL: the cylinder is cut at z_cyl = +-h, h > 0 */
} convert_env;

/* An environment in one representation, owning its pixels (free with convert_map_free). */
typedef struct convert_map {
    convert_kind kind;
    image img;            /* every kind but CONVERT_CUBE */
    cubemap cube;         /* CONVERT_CUBE */
    double max_height;    /* CONVERT_CYLINDRICAL */
    long bad_texels;      /* convert_read: NaN, infinite or negative channel values it read as 0 */
} convert_map;

/* "latlong", "cube", "cross" (also CONVERT_CUBE: one image holding the faces), "mirrorball",
 * "angular", "cylindrical", "equalarea" -> *kind.  0, or -1 (kind untouched) if unknown. */
int convert_kind_parse(const char *word, convert_kind *kind);

/* The keyword of `kind` (a static string): "latlong", "cube", ... */
const char *convert_kind_name(convert_kind kind);

/* The representation of a w x h image from its shape alone: 2:1 is lat-long, 4:3 or 3:4 a
 * cube cross (CONVERT_CUBE).  Anything else (square: mirror ball or angular map; other shapes)
 * cannot be told and fails with a message (no file name: the caller adds it) naming the size
 * and the keywords to choose from. */
int convert_kind_detect(int w, int h, convert_kind *kind, error *err);

/* The default half height of a w x h cylindrical panorama: h = pi H / W, which makes the
 * texels on the horizon square (the image's height 2h in the units of its width 2 pi);
 * a 2:1 panorama reaches atan(pi/2) = 57.5 degrees above and below the horizon.  0 if w < 1. */
double convert_cylindrical_height(int w, int h);

/* A view of *m (which must outlive it). */
convert_env convert_view(const convert_map *m);

/* Free the pixels; *m becomes an empty lat-long map.  Safe on a zeroed or freed map. */
void convert_map_free(convert_map *m);

/* Radiance in direction d (envmap frame, any non-zero finite length): the representation's
 * bilinear lookup (seamless across cube edges, wrapping at the phi seam; disc kinds over the
 * texels that meet the disc, see above).  Black for a zero or non-finite d, and where the
 * representation holds nothing (beyond a cylinder's extent).  Allocates nothing. */
rgb convert_lookup(const convert_env *env, vec3 d);

/* Number of faces (6 for a cube, else 1) and the size of each face image. */
int convert_faces(const convert_env *env);
const image *convert_face_image(const convert_env *env, int face);

/* Exact solid angle (steradians) of the valid part of texel (c, r) of face `face` (0 unless
 * kind is CONVERT_CUBE); indices in range (asserted).  Closed forms: lat-long and equal-area
 * (their headers), cylindrical (phi width times [z / sqrt(1 + z^2)] between the row's edges),
 * cube (the solid angle of a rectangle on the plane at distance 1, by inclusion-exclusion of
 * F(x, y) = atan2(x y, sqrt(1 + x^2 + y^2))), mirror ball (4 x the area of the texel's square
 * inside the unit disc, computed exactly).  Angular: no closed form; a midpoint rule of 4 x 4
 * to 16 x 16 sub-cells over the square (J vanishes at the rim, so the clipped texels are
 * accurate too; measured, the whole disc sums to 4 pi within 6e-6, relative, from 7 x 7 up and
 * within 1.5e-7 from 128 x 128 up).  Each representation's texels sum to its whole extent: 4 pi,
 * or 4 pi sin(atan h) for a cylinder. */
double convert_texel_solid_angle(const convert_env *env, int face, int c, int r);

/* Total power: sum over texels of L(texel) Omega(texel), per channel, summed in double (the
 * integral of L over the sphere for a piecewise-constant map).  NaN texels make it NaN. */
rgb convert_power(const convert_env *env);

/* The output width that holds about the input's detail, and the default samples per side.
 * Widths: lat-long, equal-area and cylindrical maps are W x W/2; mirror-ball and angular maps
 * W x W; a cube map has W x W faces.  The default keeps the texels per radian: an input of
 * "equivalent lat-long width" E (lat-long, equal-area, cylindrical: their width; cube: 4 N;
 * mirror ball: 2 W; angular: 3 W / 2, from the length of the circle that holds the 90-degree
 * directions) gives E for the 2:1 kinds, E/4 for cube faces, E/2 for a mirror ball, 2E/3 for
 * an angular map (at least 1).
 * Default samples: K = ceil(2 E_in / E_out) clamped to [4, CONVERT_MAX_SAMPLES], so a texel
 * that shrinks the input still sees every input texel about twice per side (and strata wider
 * than that are split further: convert_resample). */
int convert_default_width(const convert_env *in, convert_kind to);
int convert_default_samples(const convert_env *in, convert_kind to, int width);

#define CONVERT_MAX_SAMPLES 64

/* Resample *in into representation `to` (see above) into *out (overwritten, not freed first;
 * on failure it is empty).  width <= 0: convert_default_width; samples <= 0:
 * convert_default_samples with wide strata split (see above), else exactly K x K points, K in
 * [1, CONVERT_MAX_SAMPLES].  A cylindrical output gets
 * h = convert_cylindrical_height.  When `to` is the input's own kind at the same size (and
 * cylinder height) the texels are copied exactly.  Fails on a size image_check_size refuses or
 * a bad sample count. */
int convert_resample(const convert_env *in, convert_kind to, int width, int samples,
                     convert_map *out, error *err);

/* ---- files -------------------------------------------------------------------------------- */

/* The file name of cube face `face` written as PATH: a suffix before the extension,
 * "sky.exr" -> "sky_px.exr", "sky_nx.exr", "sky_py.exr", "sky_ny.exr", "sky_pz.exr",
 * "sky_nz.exr" (faces in the order +X -X +Y -Y +Z -Z); a name without extension gets the
 * suffix at its end.  -1 if it does not fit in `size` bytes. */
int convert_face_path(const char *path, int face, char *out, size_t size, error *err);

/* Read an environment: `from` is a keyword of convert_kind_parse or NULL to detect the kind
 * from the image's shape (convert_kind_detect).  "cube" reads the six files
 * convert_face_path(path, 0..5) (same size, square); "cross" (or a detected 4:3 / 3:4 image)
 * splits one cross image.  A cylindrical map gets convert_cylindrical_height.  Radiance is
 * never NaN, infinite or negative: such channel values become 0 (image_zero_nonfinite_or_negative,
 * as the scene's envmap does), counted in out->bad_texels for the caller to report; left in, one
 * NaN texel would spread through the bilinear lookups into its neighbours and make the power
 * NaN.  The images, and a cross's faces, are charged to `mem` (budget.h; NULL: none) before
 * they are allocated, and stay charged.  *out is overwritten; on failure it is empty and err
 * names the file. */
int convert_read(const char *path, const char *from, convert_map *out, budget *mem, error *err);

/* Write *m to `path` (format by extension, imageio.h).  A cube map becomes six files named by
 * convert_face_path, written as one set by imageio_write_set: each face first goes to a
 * temporary file beside its target, and only when all six are complete are they renamed over
 * the targets; a failure before that removes the temporaries and leaves every target untouched.
 * (Should a rename itself fail half way, the message says how many were already replaced.) */
int convert_write(const char *path, const convert_map *m, error *err);

/* Write a cube map as one horizontal cross image (4N x 3N, cubemap.h), atomically. */
int convert_write_cross(const char *path, const convert_map *m, error *err);

#endif
