/* bvh_leaf.h - what the BVH's two traversals share (private to src/geometry/): bvh.c's, one ray
 * at a time, and bvh_packet.c's, a tile's camera rays at a time.  A ray in float for the
 * conservative filters, the double test that decides a primitive, and the hit it leaves. */
#ifndef ENVTEX_BVH_LEAF_H
#define ENVTEX_BVH_LEAF_H

#include <stdint.h>
#include <string.h>

#include "envtex/geometry/ray.h"

struct bvh; /* bvh.h (which bvh.c includes with this header: no include cycle) */

/* The closest hit so far: primitive id (bvh.h's numbering), t and a triangle's barycentrics. */
typedef struct best_hit {
    long id;
    double t, b1, b2;
} best_hit;

/* The float after f (f finite or -Inf): nextafterf(f, INFINITY) without libm's call. */
static inline float bvh_float_next(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    if (f == 0)
        u = 1; /* +0 or -0: the smallest subnormal */
    else
        u += f > 0 ? 1 : -1; /* one unit in the last place away from or towards zero */
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The smallest float >= x, and the largest <= x (x not NaN). */
static inline float bvh_float_up(double x)
{
    float f = (float)x;
    return f < x ? bvh_float_next(f) : f;
}
static inline float bvh_float_down(double x)
{
    float f = (float)x;
    return f > x ? -bvh_float_next(-f) : f;
}

/* One coordinate o of a ray's origin in float, for a direction of sign neg: *of = (float)o and
 * *o_lo = o - *of (to ~2^-48 of o, for the triangle filter's s = o - p0), and the origins the
 * slabs are measured from: the near ends from the float at or beyond o along the ray, the far
 * ends from the one at or before it, so that rounding o to float never narrows a slab. */
static inline void bvh_float_origin(double o, int neg, float *of, float *o_lo, float *o_near,
                                    float *o_far)
{
    float up = bvh_float_up(o), down = bvh_float_down(o);
    *of = (float)o;
    *o_lo = (float)(o - *of);
    *o_near = neg ? down : up;
    *o_far = neg ? up : down;
}

/* 1 if primitive id (a sphere, triangle or quad) meets r with t in (r->tmin, r->tmax): the
 * double test that decides, giving *t and, for a triangle, the barycentrics *b1, *b2. */
int bvh_prim_hit(const struct bvh *b, uint32_t id, const ray *r, double *t, double *b1, double *b2);

/* What ray r found at its closest hit bh, as bvh_intersect returns it: BVH_SURFACE (*h
 * filled) or BVH_QUAD (h->t and h->prim). */
int bvh_hit_of(const struct bvh *b, const ray *r, const best_hit *bh, hit *h);

#endif
