/* bvh.h - bounding volume hierarchy over a scene's spheres, triangles and quad lights, built
 * with the binned surface area heuristic (Wald 2007), nodes and triangles stored in float.
 *
 *     bvh b;
 *     if (bvh_build(&b, scene_prims(sc), &mem, &err)) ...   // scene.h (lights.h adds quads)
 *     hit h; if (bvh_intersect(&b, &r, &h) == BVH_SURFACE) shade(&h);
 *     bvh_free(&b);
 *
 * Float finds, double decides: conservative float box and triangle tests filter, triangle.h's
 * double test on the scene's corners decides, so every hit is the double test's, bit for bit
 * (docs/design-notes.md, "The float BVH").  At most
 * BVH_MIN_PRIMS primitives: one leaf, tested linearly.  The bvh reads the scene's spheres and
 * triangles on every query: pass the same scene, unchanged.  Queries allocate nothing.
 */
#ifndef ENVTEX_BVH_H
#define ENVTEX_BVH_H

#include <stdint.h>

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/geometry/ray.h"
#include "envtex/geometry/sphere.h"
#include "envtex/geometry/triangle.h"

#define BVH_MIN_PRIMS 8  /* this many primitives or fewer: one leaf, no tree */
#define BVH_LEAF_MAX  8  /* a leaf holds at most this many; the SAH decides below it */
#define BVH_BINS      16 /* SAH bins per axis */
#define BVH_MAX_DEPTH 64 /* traversal stack size; the build stops splitting at depth 62 */
/* SAH: a node visit's cost, in primitive float tests */
#define BVH_TRAVERSAL_COST 2.0
/* Each primitive's box grows by this times (its extent + its largest coordinate) before it is
 * rounded outwards to float: room for the double test's rounding. */
#define BVH_BOX_PAD_REL 0x1p-18
/* The far end of each float slab is widened by 2 gamma(3) = 6 u / (1 - 3 u), u = 2^-24. */
#define BVH_SLAB_SLACK (6 * 0x1p-24f / (1 - 3 * 0x1p-24f))
/* The float triangle test accepts barycentrics this far outside [0, 1] and t this fraction
 * beyond tmax: enough where the three guards below let it decide. */
#define BVH_FILTER_EPS 0x1p-7f
/* A triangle (or quad) whose p0 lies farther from the world's origin than this times its
 * smallest altitude gets no float filter (the double test decides): p0 rounded to float moves
 * by up to |p0| 2^-24, a barycentric error of that over the altitude, which BVH_FILTER_EPS
 * covers only this far (docs/robustness.md, "Numerical hard cases"). */
#define BVH_FILTER_REACH 0x1p10
/* A ray whose origin is farther from a triangle than this in |s| |pv| / |det| (s = o - p0,
 * pv = d x e2, L1 norms: about its distance over the triangle's size and the ray's cosine)
 * gets no float filter: rounding s and pv moves the float barycentrics by about 4 2^-24
 * times that ratio, which must stay under half of BVH_FILTER_EPS. */
#define BVH_FILTER_REACH_RAY 0x1p14f
/* Below this |det| / (|e1| |pv|) (L1 norms; ~ the ray's cosine) the double test decides alone */
#define BVH_GRAZING 0x1p-5f

enum { BVH_MISS = 0, BVH_SURFACE = 1, BVH_QUAD = 2 }; /* what bvh_intersect found */

/* A node (32 bytes), depth-first: the first child is the next node. */
typedef struct bvh_node {
    float box[2][3]; /* lower corner, upper corner */
    int32_t offset;  /* leaf: first index into prims and tris; inner: index of the second child */
    uint16_t count;  /* leaf: number of primitives (> 0); inner: 0 */
    uint8_t axis;    /* inner: the split axis (the first child on the smaller side) */
    uint8_t pad;
} bvh_node;

/* A triangle (or quad: a, ab, ac) for the float test: p0, e1 = p1 - p0, e2 = p2 - p0; e1[0] is
 * NaN for one beyond BVH_FILTER_REACH, which the filter then passes to the double test. */
typedef struct bvh_tri {
    float p0[3], e1[3], e2[3];
} bvh_tri;

/* A quad light: the parallelogram a, a+ab, a+ab+ac, a+ac, opaque from both sides. */
typedef struct bvh_quad {
    vec3 a, ab, ac;
} bvh_quad;

/* What a BVH is built over: spheres and triangles borrowed (unchanged while it lives), quads
 * copied.  Ids: sphere i, then triangle n_spheres + j, then quad n_spheres + n_triangles + k. */
typedef struct bvh_prims {
    const sphere *spheres;
    long n_spheres;
    const triangle *triangles;
    long n_triangles;
    const char *name; /* whose primitives, for messages (a scene file; may be NULL) */
    const bvh_quad *quads;
    long n_quads;
} bvh_prims;

typedef struct bvh {
    bvh_prims prims_of; /* what it was built over (quads: b->quads) */
    bvh_node *nodes;
    long n_nodes;
    uint32_t *prims; /* primitive ids in leaf order */
    bvh_tri *tris;   /* parallel to prims */
    bvh_quad *quads; /* the copied quads (owned) */
    long n_prims;
    long n_spheres, n_surfaces; /* id < n_spheres: a sphere; < n_surfaces: a triangle; a quad */
    int is_tree;                /* 0: a single leaf */
    int depth;                  /* deepest leaf */
    double bytes;               /* what the bvh keeps */
    double build_seconds;
} bvh;

/* Build b over `prims`, charged to `mem` first (NULL: none; the scratch is released after).
 * 0, or -1 with *err (over 2^31 - 1 primitives, the budget, memory) and b holding nothing.
 * bvh_free is safe on a zeroed or failed bvh. */
int bvh_build(bvh *b, bvh_prims prims, budget *mem, error *err);

/* At most the bytes a BVH of n primitives keeps, and in *scratch (may be NULL) what its build
 * holds only while it runs. */
double bvh_bytes(long n, double *scratch);
/* What one more primitive costs a BVH at most, its build's scratch included. */
double bvh_bytes_per_prim(void);
void bvh_free(bvh *b);

/* The closest hit with t in (r->tmin, r->tmax): BVH_SURFACE (*h filled), BVH_QUAD (only h->t
 * and h->prim, the quad's index, set) or BVH_MISS. */
int bvh_intersect(const bvh *b, const ray *r, hit *h);

/* 1 if anything (quads included) lies on the ray with t in (r->tmin, r->tmax). */
int bvh_occluded(const bvh *b, const ray *r);

#endif
