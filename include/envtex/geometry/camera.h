/* camera.h - the pinhole camera of the CSE 167/168 `camera` command (from, at, up, fovy).
 *
 *     camera_init(&cam, eye, center, up, fovy_degrees, width, height);
 *     ray r = camera_ray(&cam, x + 0.5, y + 0.5);   // through the centre of pixel (x, y)
 *
 * w = unit(eye - center) (looking along -w), u = unit(up x w), v = w x u: up need not be
 * perpendicular to the view.  Pixels: x in [0, width) right, y in [0, height) DOWN.  fovy is
 * the full vertical field of view in degrees.
 */
#ifndef ENVTEX_CAMERA_H
#define ENVTEX_CAMERA_H

#include "envtex/geometry/ray.h"

typedef struct camera {
    vec3 eye, u, v, w;
    double tan_half_y, tan_half_x;
    int width, height;
} camera;

/* sin(angle(up, view)) at or below which they are parallel (far above rounding, ~1e-16). */
#define CAMERA_PARALLEL_EPS 1e-9

/* What camera_frame refuses. */
typedef enum camera_frame_status {
    CAMERA_FRAME_OK = 0,
    CAMERA_FRAME_TOO_FAR,    /* eye - center overflows, or not finite */
    CAMERA_FRAME_SAME_POINT, /* eye == center: no view direction */
    CAMERA_FRAME_UP_ZERO,    /* up is zero or not finite */
    CAMERA_FRAME_UP_PARALLEL /* sin(angle(up, view)) <= CAMERA_PARALLEL_EPS */
} camera_frame_status;

/* The frame above for any finite inputs: CAMERA_FRAME_OK and *u, *v, *w, or a status (them
 * untouched).  The parser checks `camera` with it. */
camera_frame_status camera_frame(vec3 eye, vec3 center, vec3 up, vec3 *u, vec3 *v, vec3 *w);

/* Needs camera_frame(eye, center, up) == CAMERA_FRAME_OK and 0 < fovy < 180 (asserted). */
void camera_init(camera *c, vec3 eye, vec3 center, vec3 up, double fovy_degrees, int width,
                 int height);

/* The ray through pixel position (x, y): unit d, t in (0, infinity). */
ray camera_ray(const camera *c, double x, double y);

/* camera_ray and, per pixel step times `scale` (> 0, ~1 / sqrt(spp)), *rd (has = 1,
 * dox = doy = 0, dd = (dq - (d . dq) d) / |q| for d = q / |q|, dq/dx = u tan(fovx/2) /
 * (width/2), dq/dy = -v tan(fovy/2) / (height/2)). */
ray camera_ray_differential(const camera *c, double x, double y, double scale, ray_diff *rd);

#endif
