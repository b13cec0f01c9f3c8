/* displace.h - displacement mapping (slide 43 (Displacement Mapping)): tessellate, move each vertex
 * along its normal by a height, recompute the normals; silhouettes and shadows change.
 *
 *     if (displace_sphere(32, height, tex, 0.05, 0, &m, &err)) return -1;
 *     ... m.p[], m.n[] (object space), m.tris[i].v[3], .st[3] ...;  displace_mesh_free(&m);
 *
 * Vertex p moves to p + scale height(ctx, p, n, st) n.  Rate N: a triangle becomes N^2, the
 * unit sphere a UV sphere of 4N(N-1) (N bands, 2N segments, s = phi / 2 pi, t = 1 - theta / pi,
 * no crack or seam).  Normals after: area-weighted.  Counter-clockwise.  docs/texture-mapping.md.
 */
#ifndef ENVTEX_DISPLACE_H
#define ENVTEX_DISPLACE_H

#include "envtex/core/error.h"
#include "envtex/core/vec.h"

#define DISPLACE_MAX_RATE 4096
#define DISPLACE_MAX_TRIS 50000000L /* the scene's SCENE_MAX_PRIMS */

/* Height at an object-space vertex p with unit normal n and texture coordinates st. */
typedef double (*displace_height_fn)(void *ctx, vec3 p, vec3 n, uv2 st);

typedef struct displace_tri {
    long v[3]; /* indices into displace_mesh.p / .n, counter-clockwise */
    uv2 st[3]; /* texture coordinates of the corners */
} displace_tri;

typedef struct displace_mesh {
    vec3 *p; /* displaced vertices (object space) */
    vec3 *n; /* unit area-weighted vertex normals after displacement */
    long n_verts;
    displace_tri *tris;
    long n_tris;
} displace_mesh;

/* Triangle p (normals n, NULL: geometric) at rate 1..DISPLACE_MAX_RATE; the callback sees q
 * (NULL: p) interpolated as p, bit-equal on shared edges.  0, or -1 with *err (rate, over
 * max_tris (0: DISPLACE_MAX_TRIS), zero area without normals, memory), *out owning nothing. */
int displace_triangle(const vec3 p[3], const vec3 q[3], const vec3 n[3], const uv2 st[3], int rate,
                      displace_height_fn height, void *ctx, double scale, long max_tris,
                      displace_mesh *out, error *err);

/* The unit sphere at rate 2..DISPLACE_MAX_RATE, displaced (the caller places it); as above. */
int displace_sphere(int rate, displace_height_fn height, void *ctx, double scale, long max_tris,
                    displace_mesh *out, error *err);

/* Free the arrays, zero *m (safe on a zeroed or freed mesh). */
void displace_mesh_free(displace_mesh *m);

#endif
