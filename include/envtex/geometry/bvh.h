/* bvh.h - bounding volume hierarchy over a scene's spheres and triangles, built with the binned
 * surface area heuristic (Wald 2007).  A scene with at most BVH_MIN_PRIMS primitives gets no
 * tree (one leaf, tested linearly, without a slab test): it pays nothing for a structure it
 * cannot gain from (the slab test of an all-space box was 7-11% of such renders' instructions).
 *
 *     bvh b;
 *     if (bvh_build(&b, scene_prims(sc), &mem, &err)) ...   // scene.h
 *     hit h; if (bvh_intersect(&b, &r, &h)) shade(&h);
 *     bvh_free(&b);
 *
 * The bvh keeps a pointer to nothing in the scene but reads it on every query: pass the same
 * scene, unchanged, to every call.  Queries allocate nothing.
 */
#ifndef ENVTEX_BVH_H
#define ENVTEX_BVH_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/geometry/ray.h"
#include "envtex/geometry/sphere.h"
#include "envtex/geometry/triangle.h"

/* With this many primitives or fewer, a linear loop beats a tree (measured: make bench). */
#define BVH_MIN_PRIMS 8
#define BVH_LEAF_MAX 4   /* a node with this many primitives or fewer becomes a leaf */
#define BVH_BINS 16      /* SAH bins per axis */
#define BVH_MAX_DEPTH 64 /* traversal stack size; the build stops splitting at depth 62
                         * (traversal stacks one child per interior node on its path) */

typedef struct bvh_node {
    vec3 lo, hi;   /* bounds */
    int first;     /* leaf: first index into prims; inner: index of the right child (left = +1) */
    int count;     /* leaf: number of primitives (> 0); inner: 0 */
    int axis;      /* inner: split axis, to visit the nearer child first */
} bvh_node;

typedef struct bvh_tri { vec3 p0, p1, p2; } bvh_tri;

/* The primitives a BVH is built over (borrowed: they must outlive the bvh, unchanged).  Ids:
 * sphere i is id i, triangle j is id n_spheres + j. */
typedef struct bvh_prims {
    const sphere *spheres; long n_spheres;
    const triangle *triangles; long n_triangles;
    const char *name;  /* whose primitives, for messages (a scene file; may be NULL) */
} bvh_prims;

typedef struct bvh {
    bvh_prims prims_of; /* what it was built over */
    bvh_node *nodes; long n_nodes;
    unsigned *prims;  /* primitive ids in leaf order: id < n_spheres is a sphere, else a triangle */
    bvh_tri *tris;    /* triangle corners in leaf order (cache friendly), parallel to prims */
    long n_prims;
    long n_spheres;
    int is_tree;      /* 0: a single leaf (no tree was worth building) */
    int depth;        /* deepest leaf */
    double build_seconds;
} bvh;

/* Build b over the spheres and triangles of `prims` (borrowed), its memory charged to `mem` first (budget.h, bvh_bytes;
 * NULL: no budget): the tree stays charged, the build's scratch is released.  Returns 0, or -1
 * with *err set (more than 2^31 - 1 primitives, the budget, out of memory) and b holding
 * nothing.  Free with bvh_free, which is safe on a zeroed or failed bvh. */
int bvh_build(bvh *b, bvh_prims prims, budget *mem, error *err);

/* The bytes a BVH of n primitives keeps (nodes, the leaf order, the triangles' corners: about
 * 200 a primitive), and in *scratch (may be NULL) what its build holds only while it runs. */
double bvh_bytes(long n, double *scratch);
/* What one more primitive costs a BVH, its build's scratch included (the slope of bvh_bytes). */
double bvh_bytes_per_prim(void);
void bvh_free(bvh *b);

/* Closest hit with t in (r->tmin, r->tmax): fills *h completely and returns 1, else 0. */
int bvh_intersect(const bvh *b, const ray *r, hit *h);

/* 1 if anything lies on the ray with t in (r->tmin, r->tmax) (shadow rays; any hit will do). */
int bvh_occluded(const bvh *b, const ray *r);

#endif
