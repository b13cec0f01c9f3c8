/* texmapping.c - the lecture's (s, t) parameterizations (texmapping.h). */
#include "envtex/textures/texmapping.h"

#include <assert.h>
#include <string.h>

static const char *const names[] = {"uv", "planar", "cylindrical", "spherical", "cube"};

int texmapping_parse(const char *name, texmapping_kind *out)
{
    for (int k = 0; k < 5; k++)
        if (strcmp(name, names[k]) == 0) {
            *out = (texmapping_kind)k;
            return 0;
        }
    return -1;
}

const char *texmapping_name(texmapping_kind k)
{
    assert(k >= TEXMAPPING_UV && k <= TEXMAPPING_CUBE);
    return names[k];
}

/* phi = atan2(y, x) wrapped to [0, 2 pi); s = phi / 2 pi, kept below 1 (atan2 of a tiny negative
 * y gives -tiny, and -tiny + 2 pi rounds to 2 pi). */
static double phi_s(vec3 q)
{
    double phi = atan2(q.y, q.x);
    if (phi < 0) phi += 2 * M_PI;
    double s = phi / (2 * M_PI);
    return s < 1.0 ? s : 0.0;
}

uv2 texmapping_planar(vec3 q)
{
    /* STEP(parameterization): planar mapping, slide 31 (Planar mapping): "like projections, drop z
     * coord" (texmapping.h) */
    /* STUB: (void)q;
     * return (uv2){0, 0}; */
    return (uv2){q.x, q.y};
    /* END STEP(parameterization) */
}

uv2 texmapping_cylindrical(vec3 q)
{
    /* STEP(parameterization): cylindrical mapping about z, slide 32 (Cylindrical Mapping), with its
     * seam at phi = 0 (phi_s; texmapping.h) */
    /* STUB: (void)q; (void)phi_s;
     * return (uv2){0, 0}; */
    return (uv2){phi_s(q), q.z};
    /* END STEP(parameterization) */
}

uv2 texmapping_spherical(vec3 q)
{
    /* STEP(parameterization): spherical mapping, slide 33 (Spherical Mapping): "use
     * latitude/long.", t = 1 at the pole +z; q = 0 maps to the equator (phi_s; texmapping.h) */
    /* STUB: (void)q; (void)phi_s;
     * return (uv2){0, 0}; */
    /* theta = atan2(sqrt(x^2 + y^2), z): the angle from +z, exact near the poles (acos is not),
     * and atan2(0, 0) = 0 for q = 0 */
    double theta = atan2(hypot(q.x, q.y), q.z); /* hypot: no overflow, no underflow */
    if (q.x == 0 && q.y == 0 && q.z == 0) theta = 0.5 * M_PI;
    return (uv2){phi_s(q), 1.0 - theta / M_PI}; /* t = 1 - theta / pi */
    /* END STEP(parameterization) */
}

/* Face axis (0 x, 1 y, 2 z), its sign, right and up axes: the table of the header. */
typedef struct face_frame {
    int axis;
    double sign;
    vec3 right, up;
} face_frame;
static const face_frame faces[6] = {
    {0, +1, {0, 1, 0}, {0, 0, 1}}, {0, -1, {0, -1, 0}, {0, 0, 1}}, {1, +1, {-1, 0, 0}, {0, 0, 1}},
    {1, -1, {1, 0, 0}, {0, 0, 1}}, {2, +1, {1, 0, 0}, {0, 1, 0}},  {2, -1, {1, 0, 0}, {0, -1, 0}},
};

static int cube_face_of(vec3 q)
{
    double x = fabs(q.x), y = fabs(q.y), z = fabs(q.z);
    if (x >= y && x >= z) return q.x >= 0 ? 0 : 1; /* ties: x before y before z */
    if (y >= z) return q.y >= 0 ? 2 : 3;
    return q.z >= 0 ? 4 : 5;
}

uv2 texmapping_cube_face(vec3 q, int face)
{
    assert(face >= 0 && face < 6);
    /* STEP(parameterization): cube mapping, slides 34-35 (Cube Mapping): q projected from the
     * centre onto the plane of the given face, in that face's right and up axes, mapped to [0, 1];
     * (0.5, 0.5) when q has no component along the face's axis (texmapping.h) */
    /* STUB: (void)q; (void)face;
     * return (uv2){0.5, 0.5}; */
    const face_frame *f = &faces[face];
    double a = fabs(vec3_get(q, f->axis));
    if (!(a > 0)) return (uv2){0.5, 0.5};
    /* s = (1 + r / |a|) / 2, t = (1 + u / |a|) / 2 : central projection onto the face */
    return (uv2){0.5 * (1.0 + vec3_dot(q, f->right) / a), 0.5 * (1.0 + vec3_dot(q, f->up) / a)};
    /* END STEP(parameterization) */
}

uv2 texmapping_cube(vec3 q, int *face)
{
    int f = cube_face_of(q);
    if (face) *face = f;
    return texmapping_cube_face(q, f);
}

uv2 texmapping_point(texmapping_kind k, vec3 q)
{
    switch (k) {
    case TEXMAPPING_PLANAR: return texmapping_planar(q);
    case TEXMAPPING_CYLINDRICAL: return texmapping_cylindrical(q);
    case TEXMAPPING_SPHERICAL: return texmapping_spherical(q);
    case TEXMAPPING_CUBE: return texmapping_cube(q, NULL);
    case TEXMAPPING_UV: break;
    }
    assert(!"texmapping_point: uv needs the vertices");
    return (uv2){0, 0};
}

uv2 texmapping_uv_interpolate(const uv2 st[3], double b1, double b2)
{
    /* STEP(barycentric): interpolate the texture coordinates, slide 36 (Interpolating Texture
     * Coordinates): "same weights to combine texture coordinates"; b1 and b2 are the weights of
     * vertices 1 and 2 (texmapping.h) */
    /* STUB: (void)b1; (void)b2;
     * return st[0]; */
    double b0 = 1.0 - b1 - b2;
    /* st = b0 st0 + b1 st1 + b2 st2 */
    return (uv2){b0 * st[0].u + b1 * st[1].u + b2 * st[2].u,
                 b0 * st[0].v + b1 * st[1].v + b2 * st[2].v};
    /* END STEP(barycentric) */
}

double texmapping_wrap_delta(double d)
{
    if (!isfinite(d)) return 0.0;
    /* from 2^52 on every double is an integer, a whole number of turns; and there d - 0.5
     * would round (to even), leaving 1 */
    if (fabs(d) >= 0x1p52) return 0.0;
    d -= ceil(d - 0.5); /* d - round-half-down: lands in (-0.5, 0.5] */
    return d;
}

/* Exact differential of the cube mapping on face f: with a = sign q_axis (> 0 on its face),
 * d(r / a) = dr / a - r da / a^2. */
static uv2 cube_delta(vec3 q, int face, vec3 dq)
{
    const face_frame *f = &faces[face];
    double a = f->sign * vec3_get(q, f->axis);
    if (!(a > 0)) return (uv2){0, 0};
    double da = f->sign * vec3_get(dq, f->axis);
    double r = vec3_dot(q, f->right), u = vec3_dot(q, f->up);
    double dr = vec3_dot(dq, f->right), du = vec3_dot(dq, f->up);
    return (uv2){0.5 * (dr / a - r * da / (a * a)), 0.5 * (du / a - u * da / (a * a))};
}

/* st(q + dq) - st(q) for mapping k, seam-aware (the s difference wrapped where s is periodic). */
static uv2 delta(texmapping_kind k, vec3 q, uv2 st, vec3 dq)
{
    if (k == TEXMAPPING_CUBE) return cube_delta(q, cube_face_of(q), dq);
    if (k == TEXMAPPING_PLANAR) return (uv2){dq.x, dq.y}; /* linear: exact */
    uv2 b = texmapping_point(k, vec3_add(q, dq));
    return (uv2){texmapping_wrap_delta(b.u - st.u), b.v - st.v};
}

void texmapping_differentials(texmapping_kind k, vec3 q, vec3 dq_dx, vec3 dq_dy, uv2 *dst_dx,
                              uv2 *dst_dy)
{
    assert(k != TEXMAPPING_UV);
    uv2 st = texmapping_point(k, q);
    *dst_dx = delta(k, q, st, dq_dx);
    *dst_dy = delta(k, q, st, dq_dy);
}

int texmapping_tangents(texmapping_kind k, vec3 q, vec3 n, vec3 *dq_ds, vec3 *dq_dt)
{
    assert(k != TEXMAPPING_UV);
    vec3 e1, e2;
    vec3_basis(n, &e1, &e2);
    *dq_ds = e1;
    *dq_dt = e2;
    double h = TEXMAPPING_TANGENT_STEP * fmax(vec3_length(q), 1.0);
    /* J = d(s, t) / d(a, b) along e1, e2, by central differences (each half wrapped) */
    vec3 qa = vec3_madd(q, e1, -h), qb = vec3_madd(q, e2, -h);
    uv2 sa = texmapping_point(k, qa), sb = texmapping_point(k, qb);
    uv2 fa = delta(k, qa, sa, vec3_scale(e1, 2 * h)), fb = delta(k, qb, sb, vec3_scale(e2, 2 * h));
    if (k == TEXMAPPING_CUBE) { /* on q's own face, not the neighbours' */
        int f = cube_face_of(q);
        fa = cube_delta(q, f, vec3_scale(e1, 2 * h));
        fb = cube_delta(q, f, vec3_scale(e2, 2 * h));
    }
    double sda = fa.u / (2 * h), tda = fa.v / (2 * h), sdb = fb.u / (2 * h), tdb = fb.v / (2 * h);
    double det = sda * tdb - sdb * tda;
    double scale = fmax(vec3_length2(q), 1.0); /* the Jacobian shrinks like 1 / |q| */
    if (!(fabs(det) * scale > TEXMAPPING_SINGULAR_EPS) || !isfinite(det)) return -1;
    /* [dq/ds dq/dt] = [e1 e2] J^-1,  J^-1 = [tdb -sdb; -tda sda] / det */
    *dq_ds = vec3_scale(vec3_sub(vec3_scale(e1, tdb), vec3_scale(e2, tda)), 1.0 / det);
    *dq_dt = vec3_scale(vec3_sub(vec3_scale(e2, sda), vec3_scale(e1, sdb)), 1.0 / det);
    return 0;
}

int texmapping_triangle_tangents(const vec3 p[3], const uv2 st[3], vec3 *dp_ds, vec3 *dp_dt)
{
    vec3 e1 = vec3_sub(p[1], p[0]), e2 = vec3_sub(p[2], p[0]);
    double s1 = st[1].u - st[0].u, t1 = st[1].v - st[0].v;
    double s2 = st[2].u - st[0].u, t2 = st[2].v - st[0].v;
    double det = s1 * t2 - s2 * t1;
    double ext = fmax(fmax(fabs(s1), fabs(s2)), fmax(fabs(t1), fabs(t2)));
    if (fabs(det) > TEXMAPPING_SINGULAR_EPS * ext * ext && isfinite(det)) {
        /* [e1 e2] = [dp/ds dp/dt] [s1 s2; t1 t2]  =>  multiply by the inverse */
        *dp_ds = vec3_scale(vec3_sub(vec3_scale(e1, t2), vec3_scale(e2, t1)), 1.0 / det);
        *dp_dt = vec3_scale(vec3_sub(vec3_scale(e2, s1), vec3_scale(e1, s2)), 1.0 / det);
        vec3 ng = vec3_cross(e1, e2);
        if (vec3_length2(ng) > 0) return 0;
    }
    vec3 ng = vec3_cross(e1, e2);
    vec3 n;
    if (vec3_unit_direction(ng, &n)) {
        *dp_ds = *dp_dt = vec3_make(0, 0, 0);
    } else {
        vec3_basis(n, dp_ds, dp_dt);
    }
    return -1;
}

int texmapping_triangle_differentials(const vec3 p[3], const uv2 st[3], vec3 dp_dx, vec3 dp_dy,
                                      uv2 *dst_dx, uv2 *dst_dy)
{
    *dst_dx = *dst_dy = (uv2){0, 0};
    vec3 e1 = vec3_sub(p[1], p[0]), e2 = vec3_sub(p[2], p[0]);
    /* normal equations of dp = db1 e1 + db2 e2:
     * [e1.e1 e1.e2; e1.e2 e2.e2] (db1, db2) = (e1.dp, e2.dp) */
    double a = vec3_dot(e1, e1), b = vec3_dot(e1, e2), c = vec3_dot(e2, e2);
    double det = a * c - b * b; /* = |e1 x e2|^2 >= 0 */
    if (!(det > TEXMAPPING_SINGULAR_EPS * a * c) || !isfinite(det)) return -1;
    vec3 d[2] = {dp_dx, dp_dy};
    uv2 *out[2] = {dst_dx, dst_dy};
    for (int k = 0; k < 2; k++) {
        double r1 = vec3_dot(e1, d[k]), r2 = vec3_dot(e2, d[k]);
        double db1 = (c * r1 - b * r2) / det, db2 = (a * r2 - b * r1) / det;
        /* dst = db1 (st1 - st0) + db2 (st2 - st0) */
        out[k]->u = db1 * (st[1].u - st[0].u) + db2 * (st[2].u - st[0].u);
        out[k]->v = db1 * (st[1].v - st[0].v) + db2 * (st[2].v - st[0].v);
    }
    return 0;
}
