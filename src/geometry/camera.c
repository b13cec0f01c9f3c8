/* camera.c - the pinhole camera (see include/envtex/geometry/camera.h). */
#include "envtex/geometry/camera.h"

#include <assert.h>

camera_frame_status camera_frame(vec3 eye, vec3 center, vec3 up, vec3 *u, vec3 *v, vec3 *w)
{
    vec3 d = vec3_sub(eye, center), wn, upn, right;
    if (!(isfinite(d.x) && isfinite(d.y) && isfinite(d.z))) return CAMERA_FRAME_TOO_FAR;
    if (vec3_unit_direction(d, &wn))
        return CAMERA_FRAME_SAME_POINT; /* w = (eye - center) / |...| */
    if (vec3_unit_direction(up, &upn)) return CAMERA_FRAME_UP_ZERO;
    vec3 r = vec3_cross(upn, wn); /* |up x w| = sin(angle) for unit vectors */
    if (!(vec3_length(r) > CAMERA_PARALLEL_EPS) || vec3_unit_direction(r, &right))
        return CAMERA_FRAME_UP_PARALLEL;
    *w = wn;
    *u = right;                 /* u = up x w / |...| */
    *v = vec3_cross(wn, right); /* v = w x u */
    return CAMERA_FRAME_OK;
}

void camera_init(camera *c, vec3 eye, vec3 center, vec3 up, double fovy_degrees, int width,
                 int height)
{
    assert(width > 0 && height > 0 && fovy_degrees > 0 && fovy_degrees < 180);
    c->eye = eye;
    camera_frame_status st = camera_frame(eye, center, up, &c->u, &c->v, &c->w);
    assert(st == CAMERA_FRAME_OK); /* eye != center and up not parallel to the view */
    (void)st;
    c->tan_half_y = tan(fovy_degrees * M_PI / 360.0); /* tan(fovy / 2)             */
    c->tan_half_x = c->tan_half_y * (double)width / (double)height;
    c->width = width;
    c->height = height;
}

ray camera_ray(const camera *c, double x, double y)
{
    /* alpha = tan(fovx/2) (x - w/2) / (w/2),  beta = tan(fovy/2) (h/2 - y) / (h/2) */
    double alpha = c->tan_half_x * (x - c->width * 0.5) / (c->width * 0.5);
    double beta = c->tan_half_y * (c->height * 0.5 - y) / (c->height * 0.5);
    vec3 d = vec3_sub(vec3_add(vec3_scale(c->u, alpha), vec3_scale(c->v, beta)), c->w);
    return (ray){c->eye, vec3_normalize(d), 0.0, INFINITY};
}

ray camera_ray_differential(const camera *c, double x, double y, double scale, ray_diff *rd)
{
    double alpha = c->tan_half_x * (x - c->width * 0.5) / (c->width * 0.5);
    double beta = c->tan_half_y * (c->height * 0.5 - y) / (c->height * 0.5);
    vec3 v = vec3_sub(vec3_add(vec3_scale(c->u, alpha), vec3_scale(c->v, beta)), c->w);
    double len = vec3_length(v); /* >= 1: the w component alone has length 1 */
    vec3 d = vec3_normalize(v);  /* exactly camera_ray's direction */
    vec3 dvx = vec3_scale(c->u, scale * c->tan_half_x / (c->width * 0.5));   /* dv/dx */
    vec3 dvy = vec3_scale(c->v, -scale * c->tan_half_y / (c->height * 0.5)); /* dv/dy */
    rd->has = 1;
    rd->dox = rd->doy = vec3_make(0, 0, 0);
    /* d(v / |v|) = (dv - (d . dv) d) / |v| */
    rd->ddx = vec3_scale(vec3_madd(dvx, d, -vec3_dot(d, dvx)), 1 / len);
    rd->ddy = vec3_scale(vec3_madd(dvy, d, -vec3_dot(d, dvy)), 1 / len);
    return (ray){c->eye, d, 0.0, INFINITY};
}
