/* cubemap.h - six square images on the faces of a cube around the viewer (slides 6-9 (Environment
 * Maps): "take biggest abs of (x,y,z), divide by it ... to vec: normalize").
 *
 *     if (cubemap_from_cross(&cross, &cm, &err)) return -1;  // 4:3 or 3:4 cross image
 *     rgb c = cubemap_lookup_bilinear(&cm, dir);             // any non-zero finite dir
 *
 * OpenGL's face table (4.6 core, table 8.19) on the envmap-frame (x, y, z), no axis swap:
 *     face  0 +X  1 -X  2 +Y  3 -Y  4 +Z  5 -Z      s = (sc / |ma| + 1) / 2, right
 *     sc    -z    +z    +x    +x    +x    -x        t = (tc / |ma| + 1) / 2, DOWN
 *     tc    -y    -y    +z    -z    -y    -y        ma = the major component
 * +Z is the zenith.  Faces are seen from outside, as OpenGL's.  Ties: x before y before z.
 * Crosses: horizontal 4N x 3N, +Y above -X +Z +X -Z, -Y below; vertical 3N x 4N, -Z under -Y
 * turned 180 degrees (docs/envmap-representations.md).
 */
#ifndef ENVTEX_CUBEMAP_H
#define ENVTEX_CUBEMAP_H

#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/core/vec.h"

enum cubemap_face {
    CUBEMAP_POS_X,
    CUBEMAP_NEG_X,
    CUBEMAP_POS_Y,
    CUBEMAP_NEG_Y,
    CUBEMAP_POS_Z, /* the zenith */
    CUBEMAP_NEG_Z,
    CUBEMAP_FACES
};

typedef struct cubemap {
    int size;                  /* faces are N x N; 0 when empty */
    image face[CUBEMAP_FACES]; /* owned: cubemap_free */
} cubemap;

/* d -> *face, *st in [0,1]^2 (closed): 0, or -1 (untouched) for a zero or non-finite d. */
int cubemap_dir_to_face(vec3 d, int *face, uv2 *st);

/* Unit d through st of face 0..5 (asserted); st beyond [0,1]^2 extends the face's plane. */
vec3 cubemap_face_to_dir(int face, uv2 st);

/* Six zero-filled size x size faces into *cm (old contents not freed). */
int cubemap_alloc(cubemap *cm, int size, error *err);

/* Free the faces; *cm becomes empty.  Safe on a zeroed or freed cubemap. */
void cubemap_free(cubemap *cm);

/* Seamless bilinear radiance at d: beyond an edge the neighbour face's texel, beyond a corner
 * the three corner texels' mean (ARB_seamless_cube_map).  Black for a bad d.  cm->size >= 1
 * (asserted); allocates nothing. */
rgb cubemap_lookup_bilinear(const cubemap *cm, vec3 d);

/* A horizontal / vertical / either (by shape) cross into six new faces in *cm (overwritten,
 * not freed first; empty on failure, naming the size). */
int cubemap_from_horizontal_cross(const image *cross, cubemap *cm, error *err);
int cubemap_from_vertical_cross(const image *cross, cubemap *cm, error *err);
int cubemap_from_cross(const image *cross, cubemap *cm, error *err);

/* The faces as a new cross in *out (not freed first; image_free); empty cells black. */
int cubemap_to_horizontal_cross(const cubemap *cm, image *out, error *err);
int cubemap_to_vertical_cross(const cubemap *cm, image *out, error *err);

#endif
