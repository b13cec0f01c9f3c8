/* transform.h - 4x4 affine transforms as the CSE 167 format builds them: `translate`,
 * `rotate`, `scale` right-multiply the current matrix, so the last command applies first.
 *
 *     m = mat4_mul(m, mat4_rotate(vec3_make(0, 0, 1), 90));   // degrees
 *     vec3 p = mat4_point(&m, q);
 *
 * Points take the translation, directions do not, normals use the inverse transpose.
 */
#ifndef ENVTEX_TRANSFORM_H
#define ENVTEX_TRANSFORM_H

#include "envtex/core/vec.h"

typedef struct mat4 {
    double m[4][4];
} mat4; /* m[row][col], column vectors: p' = M p */

mat4 mat4_identity(void);
mat4 mat4_mul(mat4 a, mat4 b); /* a b: b applies first */
mat4 mat4_translate(vec3 t);
mat4 mat4_scale(vec3 s);
/* Rotation by `degrees` about `axis` (any finite non-zero length; asserted; Rodrigues). */
mat4 mat4_rotate(vec3 axis, double degrees);
mat4 mat4_transpose(mat4 a);
/* Determinant of the upper-left 3x3: negative if M mirrors (turns corners clockwise). */
double mat4_det3(const mat4 *m);
/* Inverse of an affine matrix: 0, or -1 (*out untouched) if singular. */
int mat4_inverse(mat4 a, mat4 *out);

vec3 mat4_point(const mat4 *m, vec3 p); /* M (p, 1) */
/* M (d, 0) */
static inline vec3 mat4_dir(const mat4 *m, vec3 d)
{
    const double(*a)[4] = m->m;
    return (vec3){a[0][0] * d.x + a[0][1] * d.y + a[0][2] * d.z,
                  a[1][0] * d.x + a[1][1] * d.y + a[1][2] * d.z,
                  a[2][0] * d.x + a[2][1] * d.y + a[2][2] * d.z};
}
/* A normal by the inverse transpose: pass the INVERSE of the object's matrix. */
vec3 mat4_normal(const mat4 *inverse, vec3 n);

#endif
