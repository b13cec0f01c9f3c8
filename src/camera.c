/* camera.c - the pinhole camera (see include/envtex/camera.h). */
#include "envtex/camera.h"

#include <assert.h>

void camera_init(camera *c, vec3 eye, vec3 center, vec3 up, double fovy_degrees, int width, int height)
{
    assert(width > 0 && height > 0 && fovy_degrees > 0 && fovy_degrees < 180);
    c->eye = eye;
    c->w = vec3_normalize(vec3_sub(eye, center));        /* w = (eye - center) / |...| */
    c->u = vec3_normalize(vec3_cross(up, c->w));         /* u = up x w / |...|        */
    assert(vec3_length2(c->u) > 0); /* eye != center and up not parallel to the view */
    c->v = vec3_cross(c->w, c->u);                       /* v = w x u                 */
    c->tan_half_y = tan(fovy_degrees * M_PI / 360.0);    /* tan(fovy / 2)             */
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
    vec3 d = vec3_normalize(v); /* exactly camera_ray's direction */
    vec3 dvx = vec3_scale(c->u, scale * c->tan_half_x / (c->width * 0.5));   /* dv/dx */
    vec3 dvy = vec3_scale(c->v, -scale * c->tan_half_y / (c->height * 0.5)); /* dv/dy */
    rd->has = 1;
    rd->dox = rd->doy = vec3_make(0, 0, 0);
    /* d(v / |v|) = (dv - (d . dv) d) / |v| */
    rd->ddx = vec3_scale(vec3_madd(dvx, d, -vec3_dot(d, dvx)), 1 / len);
    rd->ddy = vec3_scale(vec3_madd(dvy, d, -vec3_dot(d, dvy)), 1 / len);
    return (ray){c->eye, d, 0.0, INFINITY};
}
