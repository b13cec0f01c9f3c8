/* vec.h - the vector maths of every lecture step: points and directions (vec3), colours (rgb),
 * 2D coordinates (uv2), in double; static inline, allocation free, no NaN checks.
 *
 *     vec3 r = vec3_reflect(d, n);            // r = d - 2 (d.n) n, the mirror direction
 */
#ifndef ENVTEX_VEC_H
#define ENVTEX_VEC_H

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct vec3 {
    double x, y, z;
} vec3; /* a point or a direction */
typedef struct rgb {
    double r, g, b;
} rgb; /* linear radiance or reflectance */
typedef struct uv2 {
    double u, v;
} uv2; /* 2D coordinates, meaning given by the user */

static inline vec3 vec3_make(double x, double y, double z) { return (vec3){x, y, z}; }
static inline vec3 vec3_add(vec3 a, vec3 b) { return (vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline vec3 vec3_sub(vec3 a, vec3 b) { return (vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline vec3 vec3_scale(vec3 a, double s) { return (vec3){a.x * s, a.y * s, a.z * s}; }
static inline vec3 vec3_neg(vec3 a) { return (vec3){-a.x, -a.y, -a.z}; }
static inline vec3 vec3_mul(vec3 a, vec3 b) { return (vec3){a.x * b.x, a.y * b.y, a.z * b.z}; }
/* a + s b */
static inline vec3 vec3_madd(vec3 a, vec3 b, double s)
{
    return (vec3){a.x + s * b.x, a.y + s * b.y, a.z + s * b.z};
}
static inline double vec3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline vec3 vec3_cross(vec3 a, vec3 b)
{
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static inline double vec3_length2(vec3 a) { return vec3_dot(a, a); }
static inline double vec3_length(vec3 a) { return sqrt(vec3_dot(a, a)); }
/* a / |a|; the zero vector stays zero. */
static inline vec3 vec3_normalize(vec3 a)
{
    double l = vec3_length(a);
    return l > 0 ? vec3_scale(a, 1.0 / l) : a;
}
static inline double vec3_max_abs(vec3 a)
{
    double x = fabs(a.x), y = fabs(a.y), z = fabs(a.z);
    return x > y ? (x > z ? x : z) : (y > z ? y : z);
}
/* Unit vector along ANY finite non-zero d (scaled by the largest |component| first: neither
 * 1e200 nor 1e-200 breaks it).  0, or -1 (out untouched) for a zero, infinite or NaN d. */
static inline int vec3_unit_direction(vec3 d, vec3 *out)
{
    if (!(isfinite(d.x) && isfinite(d.y) && isfinite(d.z))) return -1;
    double x = fabs(d.x), y = fabs(d.y), z = fabs(d.z);
    double m = x > y ? (x > z ? x : z) : (y > z ? y : z);
    if (m == 0) return -1;
    d = (vec3){d.x / m, d.y / m, d.z / m};
    double l = sqrt(d.x * d.x + d.y * d.y + d.z * d.z); /* in [1, sqrt 3]: no zero division */
    *out = (vec3){d.x / l, d.y / l, d.z / l};
    return 0;
}
static inline double vec3_get(vec3 a, int axis) { return axis == 0 ? a.x : axis == 1 ? a.y : a.z; }
/* Component-wise min / max (ternaries: no NaN rules). */
static inline vec3 vec3_min(vec3 a, vec3 b)
{
    return (vec3){a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
static inline vec3 vec3_max(vec3 a, vec3 b)
{
    return (vec3){a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}
/* Mirror direction of d about unit n (slide 5 (Using Environment for Reflection Map)). */
static inline vec3 vec3_reflect(vec3 d, vec3 n) { return vec3_madd(d, n, -2.0 * vec3_dot(d, n)); }
/* Angle in radians between two non-zero directions, atan2(|a x b|, a.b): accurate for tiny
 * angles, where acos(a.b) is not. */
static inline double vec3_angle(vec3 a, vec3 b)
{
    a = vec3_normalize(a);
    b = vec3_normalize(b);
    return atan2(vec3_length(vec3_cross(a, b)), vec3_dot(a, b));
}
static inline int vec3_is_finite(vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

/* Orthonormal basis (t, b) completing unit n (Duff et al. 2017). */
static inline void vec3_basis(vec3 n, vec3 *t, vec3 *b)
{
    double sign = copysign(1.0, n.z);
    double a = -1.0 / (sign + n.z);
    double c = n.x * n.y * a;
    *t = (vec3){1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    *b = (vec3){c, sign + n.y * n.y * a, -n.y};
}

static inline rgb rgb_make(double r, double g, double b) { return (rgb){r, g, b}; }
static inline rgb rgb_gray(double v) { return (rgb){v, v, v}; }
static inline rgb rgb_add(rgb a, rgb b) { return (rgb){a.r + b.r, a.g + b.g, a.b + b.b}; }
static inline rgb rgb_mul(rgb a, rgb b) { return (rgb){a.r * b.r, a.g * b.g, a.b * b.b}; }
static inline rgb rgb_scale(rgb a, double s) { return (rgb){a.r * s, a.g * s, a.b * s}; }
/* a + s * b */
static inline rgb rgb_madd(rgb a, rgb b, double s)
{
    return (rgb){a.r + s * b.r, a.g + s * b.g, a.b + s * b.b};
}
/* a + k * b, channel by channel */
static inline rgb rgb_fma(rgb a, rgb k, rgb b)
{
    return (rgb){a.r + k.r * b.r, a.g + k.g * b.g, a.b + k.b * b.b};
}
static inline double rgb_avg(rgb a) { return (a.r + a.g + a.b) / 3.0; }
static inline double rgb_max(rgb a) { return fmax(a.r, fmax(a.g, a.b)); }
static inline int rgb_is_black(rgb a) { return a.r == 0 && a.g == 0 && a.b == 0; }
static inline int rgb_is_finite(rgb a) { return isfinite(a.r) && isfinite(a.g) && isfinite(a.b); }
/* Rec. 709 luminance */
static inline double rgb_luminance(rgb a) { return 0.2126 * a.r + 0.7152 * a.g + 0.0722 * a.b; }

#endif
