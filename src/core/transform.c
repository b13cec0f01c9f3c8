/* transform.c - 4x4 affine transforms (see include/envtex/core/transform.h). */
#include "envtex/core/transform.h"

#include <assert.h>
#include <string.h>

mat4 mat4_identity(void)
{
    mat4 r;
    memset(&r, 0, sizeof r);
    for (int i = 0; i < 4; i++) r.m[i][i] = 1.0;
    return r;
}

mat4 mat4_mul(mat4 a, mat4 b)
{
    mat4 r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a.m[i][k] * b.m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

mat4 mat4_translate(vec3 t)
{
    mat4 r = mat4_identity();
    r.m[0][3] = t.x;
    r.m[1][3] = t.y;
    r.m[2][3] = t.z;
    return r;
}

mat4 mat4_scale(vec3 s)
{
    mat4 r = mat4_identity();
    r.m[0][0] = s.x;
    r.m[1][1] = s.y;
    r.m[2][2] = s.z;
    return r;
}

mat4 mat4_rotate(vec3 axis, double degrees)
{
    /* Rodrigues: R = cos(t) I + (1 - cos(t)) a a^T + sin(t) [a]x, a = axis / |axis| taken
     * with vec3_unit_direction: |axis| from sqrt(x^2 + y^2 + z^2) overflows for 1e200 (a = 0:
     * R = cos(t) I, a scaling) and loses bits for 1e-160 (its squares are subnormal) */
    vec3 a;
    int st = vec3_unit_direction(axis, &a);
    assert(st == 0); /* a zero or non-finite axis is the caller's error */
    (void)st;
    double t = degrees * M_PI / 180.0, c = cos(t), s = sin(t), k = 1.0 - c;
    mat4 r = mat4_identity();
    r.m[0][0] = c + k * a.x * a.x;
    r.m[0][1] = k * a.x * a.y - s * a.z;
    r.m[0][2] = k * a.x * a.z + s * a.y;
    r.m[1][0] = k * a.y * a.x + s * a.z;
    r.m[1][1] = c + k * a.y * a.y;
    r.m[1][2] = k * a.y * a.z - s * a.x;
    r.m[2][0] = k * a.z * a.x - s * a.y;
    r.m[2][1] = k * a.z * a.y + s * a.x;
    r.m[2][2] = c + k * a.z * a.z;
    return r;
}

mat4 mat4_transpose(mat4 a)
{
    mat4 r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) r.m[i][j] = a.m[j][i];
    return r;
}

double mat4_det3(const mat4 *m)
{
    /* det A = a00 (a11 a22 - a12 a21) - a01 (a10 a22 - a12 a20) + a02 (a10 a21 - a11 a20) */
    const double(*a)[4] = m->m;
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

int mat4_inverse(mat4 a, mat4 *out)
{
    /* Gauss-Jordan elimination with partial pivoting on [A | I]. */
    double w[4][8];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            w[i][j] = a.m[i][j];
            w[i][j + 4] = (i == j);
        }
    for (int c = 0; c < 4; c++) {
        int p = c;
        for (int r = c + 1; r < 4; r++)
            if (fabs(w[r][c]) > fabs(w[p][c])) p = r;
        /* An exact zero pivot (or NaN) means singular; scale 0 is the usual cause. */
        if (!(fabs(w[p][c]) > 0.0) || !isfinite(w[p][c])) return -1;
        if (p != c)
            for (int j = 0; j < 8; j++) {
                double t = w[c][j];
                w[c][j] = w[p][j];
                w[p][j] = t;
            }
        double inv = 1.0 / w[c][c];
        for (int j = 0; j < 8; j++) w[c][j] *= inv;
        for (int r = 0; r < 4; r++) {
            if (r == c) continue;
            double f = w[r][c];
            if (f != 0.0)
                for (int j = 0; j < 8; j++) w[r][j] -= f * w[c][j];
        }
    }
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) out->m[i][j] = w[i][j + 4];
    return 0;
}

vec3 mat4_point(const mat4 *m, vec3 p)
{
    const double(*a)[4] = m->m;
    return (vec3){a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3],
                  a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3],
                  a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3]};
}

vec3 mat4_normal(const mat4 *inverse, vec3 n)
{
    /* n' = (M^-1)^T n */
    const double(*a)[4] = inverse->m;
    return (vec3){a[0][0] * n.x + a[1][0] * n.y + a[2][0] * n.z,
                  a[0][1] * n.x + a[1][1] * n.y + a[2][1] * n.z,
                  a[0][2] * n.x + a[1][2] * n.y + a[2][2] * n.z};
}
