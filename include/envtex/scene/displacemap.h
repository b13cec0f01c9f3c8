/* displacemap.h - `displacementmap NAME SCALE` (slide 43 (Displacement Mapping)): each sphere and
 * triangle whose material has a displacement map becomes triangles moved along the normal by SCALE
 * times the texture (displace.h), traced instead of it.
 *
 *     if (displacemap_needed(sc) && displacemap_apply(sc, 0, &mem, &work, &st, &err)) ...
 *     ... render `work` ...    displacemap_free(&work);
 *
 * The result owns only its sphere and triangle arrays; the rest is the caller's scene, which
 * must outlive it unchanged.
 */
#ifndef ENVTEX_DISPLACEMAP_H
#define ENVTEX_DISPLACEMAP_H

#include "envtex/core/error.h"
#include "envtex/scene/scene.h"

#define DISPLACEMAP_SPHERE_RATE   96       /* 36480 triangles per sphere */
#define DISPLACEMAP_TRIANGLE_RATE 32       /* 1024 triangles per triangle */
#define DISPLACEMAP_MAX_TRIS      8000000L /* default limit for the displaced scene */

typedef struct displacemap_stats {
    long spheres, triangles;        /* primitives that were displaced */
    long new_triangles;             /* triangles of the result, untouched ones included */
    int sphere_rate, triangle_rate; /* the rates used */
} displacemap_stats;

/* 1 if some sphere's or triangle's material has a displacement map. */
int displacemap_needed(const scene *sc);

/* The displaced scene into *out.  A sphere: 4 N (N - 1) triangles (N: the sphere rate), SCALE
 * object units; a triangle: N^2 (the triangle rate), SCALE world units, along its vertex
 * normals or the angle-weighted normal at the corner (docs/texture-mapping.md).  Output
 * triangles keep the material (its displacement map ignored), have st (a sphere's:
 * st_mapped = 1), q and area-weighted normals, counter-clockwise from outside.  The rates halve
 * (to 2 and 1) until the result fits max_tris (0: DISPLACEMAP_MAX_TRIS) and mem (NULL: none)
 * with its BVH, else an error; mem stays charged.  st may be NULL.  0, or -1 with *err set and
 * *out owning nothing. */
int displacemap_apply(const scene *in, long max_tris, budget *mem, scene *out,
                      displacemap_stats *st, error *err);

/* Free what displacemap_apply allocated (the geometry arrays) and zero *out; never scene_free. */
void displacemap_free(scene *out);

#endif
