/* cubemap.h - the cube map: an environment stored as six square images on the faces of a cube
 * around the viewer.  Lecture "Environment, Texture Maps", slides 6-9 and 13-14: "take biggest
 * abs of (x,y,z), divide/renorm by it ... cubemap coord to vec: normalize".
 *
 *     cubemap cm = {0};
 *     if (cubemap_from_cross(&cross, &cm, &err)) return -1;  // 4:3 or 3:4 cross image
 *     rgb c = cubemap_lookup_bilinear(&cm, dir);             // dir in the envmap frame
 *     cubemap_free(&cm);
 *
 * Frame.  Directions are in the envmap frame (+z up).  OpenGL's cube-map face table (OpenGL 4.6
 * core spec, table 8.19 "Selection of cube map images"; table 3.21 in older specs) is applied to
 * the envmap-frame direction (x, y, z) AS IT IS, with no axis swap:
 *
 *     face  major axis   sc    tc    ma        s = (sc / |ma| + 1) / 2
 *     0 +X     +x        -z    -y    x         t = (tc / |ma| + 1) / 2
 *     1 -X     -x        +z    -y    x
 *     2 +Y     +y        +x    +z    y         st.u = s grows to the right (column 0 at s = 0)
 *     3 -Y     -y        +x    -z    y         st.v = t grows DOWN (row 0 at t = 0, the top
 *     4 +Z     +z        +x    -y    z                of the face image as stored in a file)
 *     5 -Z     -z        -x    -y    z
 *
 * So the +Z face is the zenith and -Z the nadir.  An OpenGL (y-up) cube map keeps its sky on the
 * +Y face, that is towards envmap +y: in a y-up scene it needs no rotation at all; in a z-up
 * scene put `rotate 1 0 0 90` before `envmap` (maps envmap +y to world +z).
 * Like every OpenGL cube map, a face image is the view of the cube from OUTSIDE (mirrored with
 * respect to what a viewer at the centre sees): on +X the right edge (s = 1) is towards -z.
 * A face of N x N texels: texel (c, r) covers s in [c/N, (c+1)/N), t in [r/N, (r+1)/N); its
 * centre is st = ((c + 0.5) / N, (r + 0.5) / N).
 *
 * Ties (edges and corners, where two or three |components| are equal): the major axis is x if
 * |x| >= |y| and |x| >= |z|, else y if |y| >= |z|, else z ("x before y before z").  The same
 * rule is the only one used, so a direction on an edge always goes to the same face; a point on
 * an edge of the face that loses the tie maps to the same direction, which comes back on the
 * winning face (at the matching edge coordinates).
 *
 * Cross layouts (N = face size; every face unrotated except -Z in the vertical cross):
 *
 *     horizontal cross, 4N x 3N            vertical cross, 3N x 4N
 *           +----+                                +----+
 *           | +Y |                                | +Y |
 *      +----+----+----+----+                 +----+----+----+
 *      | -X | +Z | +X | -Z |                 | -X | +Z | +X |
 *      +----+----+----+----+                 +----+----+----+
 *           | -Y |                                | -Y |
 *           +----+                                +----+
 *                                                 | -Z |  rotated 180 degrees
 *                                                 +----+
 *
 * With the table above the unfolded cube is continuous across every internal edge of both
 * crosses (this is the usual "OpenGL horizontal cross"; its centre cell is the zenith here).
 * Cells outside the cross are black.
 */
#ifndef ENVTEX_CUBEMAP_H
#define ENVTEX_CUBEMAP_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/core/vec.h"

enum cubemap_face {
    CUBEMAP_POS_X, /* 0 */
    CUBEMAP_NEG_X, /* 1 */
    CUBEMAP_POS_Y, /* 2 */
    CUBEMAP_NEG_Y, /* 3 */
    CUBEMAP_POS_Z, /* 4: the zenith */
    CUBEMAP_NEG_Z, /* 5: the nadir */
    CUBEMAP_FACES  /* 6 */
};

typedef struct cubemap {
    int size;                    /* N: every face is N x N texels; 0 when empty */
    image face[CUBEMAP_FACES];   /* indexed by enum cubemap_face; owned, free with cubemap_free */
} cubemap;

/* Which face a direction d (envmap frame, any non-zero finite length: only its direction
 * matters) hits, and where: *face in 0..5, *st in [0,1]^2 (closed: an edge gives 0 or 1).
 * Returns 0, or -1 (outputs untouched) for a zero, infinite or NaN direction. */
int cubemap_dir_to_face(vec3 d, int *face, uv2 *st);

/* The unit direction through point st of face `face` (0..5, asserted):
 * d = normalize(ma axis + sc, tc placed by the table), sc = 2 s - 1, tc = 2 t - 1.
 * st outside [0,1]^2 gives the direction through the face's plane extended beyond its edges
 * (the seamless lookup uses that).  NaN in st gives NaN. */
vec3 cubemap_face_to_dir(int face, uv2 st);

/* Allocate six zero-filled size x size faces into *cm (its old contents are not freed). */
int cubemap_alloc(cubemap *cm, int size, error *err);

/* Free the faces and reset *cm to empty.  Safe on a zeroed or already freed cubemap. */
void cubemap_free(cubemap *cm);

/* Bilinear radiance in direction d (envmap frame, any non-zero finite length), with no seam:
 * a texel needed beyond a face edge is taken from the neighbouring face, found by projecting
 * that texel's centre (on the face's plane extended) through the cube's centre; that lands in
 * exactly the neighbour texel that shares the edge.  The one texel beyond a cube corner (where
 * three faces meet and no fourth texel exists) is the average of the three corner texels, as
 * ARB_seamless_cube_map does, so the lookup is continuous at corners too.
 * A zero, infinite or NaN direction returns black (as latlong_lookup_bilinear does).
 * cm must hold faces (size >= 1, asserted).  Allocates nothing. */
rgb cubemap_lookup_bilinear(const cubemap *cm, vec3 d);

/* Split a horizontal cross (4N x 3N) into six new faces in *cm (layout above).  *cm is
 * overwritten (not freed first); on failure it is left empty. */
int cubemap_from_horizontal_cross(const image *cross, cubemap *cm, error *err);

/* Split a vertical cross (3N x 4N; -Z rotated 180 degrees) into six new faces in *cm. */
int cubemap_from_vertical_cross(const image *cross, cubemap *cm, error *err);

/* Either cross, chosen by the image's shape (4:3 horizontal, 3:4 vertical); any other shape
 * fails with a message giving the size. */
int cubemap_from_cross(const image *cross, cubemap *cm, error *err);

/* Assemble the six faces into a new horizontal (4N x 3N) or vertical (3N x 4N) cross in *out
 * (overwritten, not freed first; the caller frees it with image_free).  Empty cells are black. */
int cubemap_to_horizontal_cross(const cubemap *cm, image *out, error *err);
int cubemap_to_vertical_cross(const cubemap *cm, image *out, error *err);

#endif
