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
