/* displace.h - displacement mapping: tessellate a surface finely enough, then move every vertex
 * along its normal by a height, and recompute the normals.  Lecture "Environment, Texture Maps",
 * the displacement-mapping slide of 25-46: unlike a bump map it changes the geometry, so
 * silhouettes and shadows change too.
 *
 *     static double height(void *ctx, vec3 p, vec3 n, uv2 st) { return texture value at st; }
 *     displace_mesh m;
 *     if (displace_sphere(32, height, tex, 0.05, 0, &m, &err)) return -1;
 *     ... m.p[], m.n[] (object space), m.tris[i].v[3] and .st[3] ...
 *     displace_mesh_free(&m);
 *
 * Rates (documented so a scene's cost is predictable):
 *   triangle, rate N: the barycentric grid b1 = i/N, b2 = j/N (i + j <= N): (N+1)(N+2)/2
 *     vertices and N^2 triangles, each winding like the original (p0, p1, p2).
 *   sphere, rate N >= 2: a UV sphere of the unit sphere at the origin with N bands in theta and
 *     2N segments in phi (+z up, the spherical mapping of texmapping.h): 2 + (N-1) 2N vertices,
 *     shared across the phi seam and at the poles (so the displaced mesh has no cracks), and
 *     4N (N-1) triangles, counter-clockwise seen from outside.
 * Heights: vertex k moves to p + scale * height(ctx, p, n, st) * n (a triangle's callback may
 * see its own interpolated point instead of p: displace_triangle's q), with n the normal before
 * displacement (the interpolated vertex normals - corner 0's where they cancel - or the
 * geometric normal; the sphere's p).  The callback sees object space and the vertex's (s, t);
 * for the sphere s = phi / 2 pi (0 on the seam, 0 at the poles), t = 1 - theta / pi.
 * Corner texture coordinates: each triangle keeps its own st[3] (tris[i].st), so triangles
 * across the sphere's seam read s up to 1 (not back to 0) and pole corners take the middle s of
 * their segment: texturing the displaced mesh shows no seam.
 * Normals afterwards: area-weighted vertex normals, n_v = normalize(sum over the triangles at v
 * of (b - a) x (c - a)) (the cross product's length is twice the area); a vertex whose sum is
 * zero keeps its normal from before.
 * Limits: the triangle count is checked against max_tris (0, or a value above
 * DISPLACE_MAX_TRIS: DISPLACE_MAX_TRIS) before anything is allocated.  Errors are values; the
 * height callback must not fail (return 0 for "no displacement").
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
    long v[3];  /* indices into displace_mesh.p / .n, counter-clockwise */
    uv2 st[3];  /* texture coordinates of the corners */
} displace_tri;

typedef struct displace_mesh {
    vec3 *p;    /* displaced vertices (object space) */
    vec3 *n;    /* unit area-weighted vertex normals after displacement */
    long n_verts;
    displace_tri *tris;
    long n_tris;
} displace_mesh;

/* Tessellate triangle (p[3], normals n[3] or NULL for the geometric normal, st[3]) at `rate`
 * (1 .. DISPLACE_MAX_RATE) and displace it.  The height callback's point is q0, q1, q2 (say the
 * object-space corners) interpolated with the weights of p and in the same arithmetic, so two
 * triangles with the same corners along an edge see bit-equal points there, hence equal
 * heights; q NULL: the callback sees p.  Returns 0, or -1 with *err set (rate out of range,
 * more than max_tris triangles, a zero-area triangle with no normals, out of memory); on
 * failure *out owns nothing. */
int displace_triangle(const vec3 p[3], const vec3 q[3], const vec3 n[3], const uv2 st[3], int rate,
                      displace_height_fn height, void *ctx, double scale, long max_tris,
                      displace_mesh *out, error *err);

/* The unit sphere at the origin as a UV sphere at `rate` (2 .. DISPLACE_MAX_RATE), displaced.
 * The caller maps it to the sphere's centre, radius and transform. */
int displace_sphere(int rate, displace_height_fn height, void *ctx, double scale, long max_tris,
                    displace_mesh *out, error *err);

/* Free the arrays and zero *m (safe on a zeroed or freed mesh). */
void displace_mesh_free(displace_mesh *m);

#endif
