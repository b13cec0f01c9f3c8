/* camera.h - the pinhole camera of the CSE 167/168 format:
 * `camera fromx fromy fromz atx aty atz upx upy upz fovy`.
 *
 *     camera cam;
 *     camera_init(&cam, eye, center, up, fovy_degrees, width, height);
 *     ray r = camera_ray(&cam, x + 0.5, y + 0.5);   // through the centre of pixel (x, y)
 *
 * Frame: w = normalize(eye - center) (the camera looks along -w), u = normalize(up x w),
 * v = w x u; equivalently right = normalize(look x up), up' = right x look, so `up` need not be
 * perpendicular to the view.  Pixel coordinates are continuous: x in [0, width) to the right,
 * y in [0, height) DOWN (row 0 at the top).  fovy is the full vertical field of view; the
 * horizontal one follows from the aspect ratio width / height.
 */
#ifndef ENVTEX_CAMERA_H
#define ENVTEX_CAMERA_H

#include "envtex/geometry/ray.h"

typedef struct camera {
    vec3 eye, u, v, w;
    double tan_half_y, tan_half_x;
    int width, height;
} camera;

/* The sine of the angle between `up` and the view below which camera_frame calls them parallel:
 * right = up x w has no reliable direction there (doubles carry ~1e-16 relative error, so 1e-9
 * leaves a wide margin while rejecting only truly parallel vectors). */
#define CAMERA_PARALLEL_EPS 1e-9

/* What camera_frame can refuse (0 = a frame). */
typedef enum camera_frame_status {
    CAMERA_FRAME_OK = 0,
    CAMERA_FRAME_TOO_FAR,       /* eye - center overflows (or a coordinate is not finite) */
    CAMERA_FRAME_SAME_POINT,    /* eye == center: no view direction */
    CAMERA_FRAME_UP_ZERO,       /* up is zero or not finite */
    CAMERA_FRAME_UP_PARALLEL    /* sin(angle(up, view)) <= CAMERA_PARALLEL_EPS */
} camera_frame_status;

/* The camera's orthonormal frame: w = unit(eye - center), u = unit(up x w), v = w x u.  Every
 * length is taken with vec3_unit_direction, so any finite eye, center and up work, however
 * large or small (a cross product of 1e-160 vectors would underflow to 0 otherwise).  Returns
 * CAMERA_FRAME_OK and sets *u, *v, *w, or a status and leaves them untouched.  The scene
 * parser calls it to check a `camera` line, so that camera_init never meets a frame it cannot
 * build. */
camera_frame_status camera_frame(vec3 eye, vec3 center, vec3 up, vec3 *u, vec3 *v, vec3 *w);

/* Caller guarantees camera_frame(eye, center, up) == CAMERA_FRAME_OK and 0 < fovy < 180 (the
 * scene parser checks these); asserts otherwise. */
void camera_init(camera *c, vec3 eye, vec3 center, vec3 up, double fovy_degrees, int width, int height);

/* Ray through continuous pixel position (x, y); unit direction, tmin 0, tmax infinity. */
ray camera_ray(const camera *c, double x, double y);

/* camera_ray(c, x, y) and its differentials into *rd (has = 1): the pinhole's origin does not
 * move (dox = doy = 0), and the unit direction d = v / |v|, v = alpha u + beta v - w, changes by
 *     dd = (dv - (d . dv) d) / |v|        (the derivative of v / |v| along dv)
 * with dv/dx = u tan(fovx/2) / (width/2) and dv/dy = -v tan(fovy/2) / (height/2): one pixel
 * step, scaled by `scale` (> 0; a renderer taking spp samples per pixel passes about
 * 1 / sqrt(spp), since each sample then stands for a smaller part of the pixel). */
ray camera_ray_differential(const camera *c, double x, double y, double scale, ray_diff *rd);

#endif
