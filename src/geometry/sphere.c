/* sphere.c - ray-sphere intersection under an affine transform (see
 * include/envtex/geometry/sphere.h). */
#include "envtex/geometry/sphere.h"

int sphere_intersect(const sphere *s, const ray *r, double *t_out)
{
    /* Object-space ray: o' = M^-1 o - c, d' = M^-1 d (not renormalized: t stays the world t);
     * without a transform M^-1 = I: o' = o - c, d' = d, and the matrix products are skipped. */
    vec3 o, d;
    if (s->untransformed) {
        o = vec3_sub(r->o, s->center);
        d = r->d;
    } else {
        o = vec3_sub(mat4_point(&s->inv, r->o), s->center);
        d = mat4_dir(&s->inv, r->d);
    }
    /* |o + t d|^2 = R^2  ->  a t^2 + 2 b t + c = 0 with a = d.d, b = o.d, c = o.o - R^2 */
    double a = vec3_dot(d, d), b = vec3_dot(o, d);
    if (!(a > 0)) return 0;
    /* the discriminant b^2 - a c cancels badly for a far origin; the same quantity over a,
     * (b^2 - a c) / a = R^2 - |o - (b/a) d|^2, loses far less  (Hearn & Baker; Ray Tracing Gems
     * ch. 7) */
    vec3 perp = vec3_madd(o, d, -b / a);
    double R2 = s->radius * s->radius;
    double disc = R2 - vec3_dot(perp, perp); /* = (b^2 - a c) / a */
    if (disc < 0) return 0;
    double c = vec3_dot(o, o) - R2;
    /* stable roots: q = -(b + sign(b) sqrt(a disc)); t0 = q / a, t1 = c / q */
    double q = -(b + copysign(sqrt(a * disc), b));
    double t0 = q / a, t1 = q != 0 ? c / q : t0;
    if (t0 > t1) {
        double tmp = t0;
        t0 = t1;
        t1 = tmp;
    }
    if (t0 > r->tmin && t0 < r->tmax) {
        *t_out = t0;
        return 1;
    }
    if (t1 > r->tmin && t1 < r->tmax) {
        *t_out = t1;
        return 1;
    }
    return 0;
}

/* An object-space point po near the sphere moved onto it along its radius: o + t d is off the
 * surface by t's error, which grows with the ray's length (a camera 1e8 away: 1e-8); the
 * projected point is off by a few ulps of |center| + radius, what ray.h's offset covers. */
static vec3 onto_sphere(const sphere *s, vec3 po, vec3 *local)
{
    vec3 l = vec3_sub(po, s->center);
    double len = vec3_length(l);
    *local = len > 0 ? vec3_scale(l, s->radius / len) : l; /* (a radius 0 sphere's centre) */
    return vec3_add(s->center, *local);
}

void sphere_hit(const sphere *s, const ray *r, double t, hit *h)
{
    h->t = t;
    h->bary = (uv2){0, 0}; /* a sphere's (s, t) comes from its texture mapping (texshade.h) */
    vec3 local;
    if (s->untransformed) {
        /* M = I: the general path's bits: its products are exact, and its translation's + 0
         * turns a -0 into +0, so p gets the same + 0 */
        h->p = vec3_add(onto_sphere(s, vec3_add(r->o, vec3_scale(r->d, t)), &local),
                        vec3_make(0, 0, 0));
        h->ng = h->ns = vec3_normalize(vec3_add(local, vec3_make(0, 0, 0)));
        return;
    }
    vec3 po = vec3_add(mat4_point(&s->inv, r->o), vec3_scale(mat4_dir(&s->inv, r->d), t));
    h->p = mat4_point(&s->xf, onto_sphere(s, po, &local));
    /* normal: object normal (p - c) through the inverse transpose */
    h->ng = h->ns = vec3_normalize(mat4_normal(&s->inv, local));
}

void sphere_bounds(const sphere *s, vec3 *lo, vec3 *hi)
{
    *lo = vec3_make(INFINITY, INFINITY, INFINITY);
    *hi = vec3_neg(*lo);
    for (int i = 0; i < 8; i++) {
        vec3 c = vec3_make(s->center.x + (i & 1 ? s->radius : -s->radius),
                           s->center.y + (i & 2 ? s->radius : -s->radius),
                           s->center.z + (i & 4 ? s->radius : -s->radius));
        vec3 w = mat4_point(&s->xf, c);
        *lo = vec3_min(*lo, w);
        *hi = vec3_max(*hi, w);
    }
}
