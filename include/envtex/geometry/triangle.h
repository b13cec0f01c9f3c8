/* triangle.h - ray-triangle intersection with barycentric coordinates, which interpolate
 * (s,t) and normals: p = b0 p0 + b1 p1 + b2 p2, b0 = 1 - b1 - b2.
 *
 *     double t, b1, b2;
 *     if (triangle_intersect(p0, p1, p2, &r, &t, &b1, &b2)) ...
 *
 * Watertight (Woop, Benthin and Wald, JCGT 2013; pbrt-v4's IntersectTriangle), in double
 * precision: the corners are moved into the ray's frame (translated to its origin, sheared so
 * that it runs along z) and the ray's point is tested against the three 2D edge functions,
 * whose signs are exact.  Two triangles sharing an edge compute the same edge function, so a
 * ray through the edge hits exactly one of them (no crack, no double hit); a ray exactly on an
 * edge line goes to the side a fixed rule picks, so a vertex inside a fan belongs to exactly
 * one of its triangles.  Degenerate (zero-area) triangles are never hit.
 */
#ifndef ENVTEX_TRIANGLE_H
#define ENVTEX_TRIANGLE_H

#include "envtex/geometry/ray.h"

/* A scene triangle (`tri`, `trinormal`, `tritex`, an OBJ face). */
typedef struct triangle {
    vec3 p[3]; /* world corners: (p1 - p0) x (p2 - p0) is the outward normal (corners 1
                       and 2 swapped, with n, st, q, under a mirroring transform) */
    vec3 n[3]; /* world-space unit vertex normals (trinormal); unused if !has_normals */
    int has_normals;
    int material;
    uv2 st[3]; /* `tritex` or an OBJ's vt (has_st = 1), else (0,0), (1,0), (0,1) as written */
    int has_st;
    int st_mapped; /* 1: st already holds the material's point mapping (a displaced sphere's
                       tessellation, displacemap.h), interpolated as for `uv`; 0 from a file */
    vec3 q[3];     /* OBJECT-space corners (as written, before the transform), for the point
                       mappings and solid textures: P_object = sum b_i q_i */
} triangle;

/* Degenerate (never hit) when |d . (e1 x e2)| is below this fraction of |d| |e1| |e2|: a corner
 * or grazing angle under 1e-10 rad. */
#define TRIANGLE_DEGENERATE_EPS 1e-10

/* 1 if the ray meets the triangle at t in (r->tmin, r->tmax); b1, b2: the weights of p1, p2. */
int triangle_intersect(vec3 p0, vec3 p1, vec3 p2, const ray *r, double *t, double *b1, double *b2);

/* The same for the parallelogram a, a+ab, a+ab+ac, a+ac, as its two triangles: 1 and *t. */
int triangle_intersect_parallelogram(vec3 a, vec3 ab, vec3 ac, const ray *r, double *t);

/* h->p, h->ng (unit, from the winding, turned to agree with given normals), h->ns (the unit
 * interpolated normal, or ng) and h->bary of the hit at barycentrics (b1, b2). */
void triangle_hit(const triangle *tr, double b1, double b2, hit *h);

#endif
