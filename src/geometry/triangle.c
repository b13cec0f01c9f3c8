/* triangle.c - the watertight ray-triangle test of Woop, Benthin and Wald (JCGT 2013), in
 * double precision (see include/envtex/geometry/triangle.h). */
#include "envtex/geometry/triangle.h"

/* Corner p in the ray's frame: translated to the ray's origin, its axes taken in the order k
 * (the ray's largest axis last) and sheared by (sx, sy), so that the ray runs along +z from
 * (0, 0, 0).  A corner two triangles share lands on the same doubles in both. */
static vec3 ray_frame(vec3 p, const ray *r, const int k[3], double sx, double sy)
{
    double v[3] = {p.x - r->o.x, p.y - r->o.y, p.z - r->o.z};
    return vec3_make(v[k[0]] + sx * v[k[2]], v[k[1]] + sy * v[k[2]], v[k[2]]);
}

/* The edge function a.x b.y - a.y b.x: twice the signed area of the 2D triangle (0, a, b),
 * positive when the origin is left of a -> b.  Its sign is exact: rounding keeps the order
 * of the two products, and where they round to the same double their exact rounding errors
 * (fma) decide.  Two triangles that share the edge compute the same value, negated. */
static double edge_function(vec3 a, vec3 b)
{
    double p = a.x * b.y, q = a.y * b.x;
    if (p != q) return p - q;
    return fma(a.x, b.y, -p) - fma(a.y, b.x, -q);
}

/* Does a triangle turned by s (+1: inside is left of its edges) take the origin, which lies
 * exactly on the line of its edge a -> b?  The tie goes to the side of the origin nudged by
 * (-1, tiny): of two triangles sharing the edge exactly one takes it, and of the triangles
 * around a vertex exactly one takes the vertex. */
static int takes_tie(vec3 a, vec3 b, double s)
{
    double dx = s * (b.x - a.x), dy = s * (b.y - a.y); /* the edge with inside on its left */
    return dy > 0 || (dy == 0 && dx > 0);
}

int triangle_intersect(vec3 p0, vec3 p1, vec3 p2, const ray *r, double *t_out, double *b1_out,
                       double *b2_out)
{
    /* The ray's frame: its largest axis becomes z, and x, y are sheared by z so that the ray
     * is the z axis; the test is then 2D, at the origin. */
    double d[3] = {r->d.x, r->d.y, r->d.z}, ax = fabs(d[0]), ay = fabs(d[1]), az = fabs(d[2]);
    int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    int k[3] = {kz == 2 ? 0 : kz + 1, kz == 0 ? 2 : kz - 1, kz};
    double inv_dz = 1 / d[kz], sx = -d[k[0]] * inv_dz, sy = -d[k[1]] * inv_dz;
    vec3 a = ray_frame(p0, r, k, sx, sy), b = ray_frame(p1, r, k, sx, sy),
         c = ray_frame(p2, r, k, sx, sy);
    /* The edge functions: the barycentrics times det, twice the projected area. */
    double e0 = edge_function(b, c), e1 = edge_function(c, a), e2 = edge_function(a, b);
    int neg = (e0 < 0) | (e1 < 0) | (e2 < 0), pos = (e0 > 0) | (e1 > 0) | (e2 > 0);
    if (neg & pos) return 0; /* on both sides of its edges: outside */
    double det = e0 + e1 + e2, s = det > 0 ? 1 : -1;
    if (det == 0 || !isfinite(det)) return 0;
    if ((e0 == 0 && !takes_tie(b, c, s)) || (e1 == 0 && !takes_tie(c, a, s)) ||
        (e2 == 0 && !takes_tie(a, b, s)))
        return 0;
    double inv_det = 1 / det, t = (e0 * a.z + e1 * b.z + e2 * c.z) * inv_det * inv_dz;
    if (!(t > r->tmin && t < r->tmax)) return 0;
    /* |d . (e1 x e2)| <= eps |d| |e1| |e2|: a degenerate triangle, or a ray within 1e-10 rad of
     * its plane: no hit.  From the corners alone, so a collinear triangle stays degenerate
     * wherever the ray starts; lengths, not their squares, so no overflow before det's. */
    vec3 u = vec3_sub(p1, p0), v = vec3_sub(p2, p0);
    double det3 = vec3_dot(u, vec3_cross(r->d, v));
    if (fabs(det3) <= TRIANGLE_DEGENERATE_EPS * vec3_length(r->d) * vec3_length(u) * vec3_length(v))
        return 0;
    *t_out = t;
    *b1_out = e1 * inv_det;
    *b2_out = e2 * inv_det;
    return 1;
}

int triangle_intersect_parallelogram(vec3 a, vec3 ab, vec3 ac, const ray *r, double *t)
{
    vec3 b = vec3_add(a, ab), c = vec3_add(b, ac), d = vec3_add(a, ac);
    double b1, b2;
    ray rr = *r;
    int h = triangle_intersect(a, b, c, &rr, t, &b1, &b2); /* (a, a+ab, a+ab+ac) */
    if (h) rr.tmax = *t;
    return triangle_intersect(a, c, d, &rr, t, &b1, &b2) || h; /* (a, a+ab+ac, a+ac) */
}

void triangle_hit(const triangle *tr, double b1, double b2, hit *h)
{
    double b0 = 1 - b1 - b2;
    /* p = b0 p0 + b1 p1 + b2 p2 : the barycentric interpolation of the lecture */
    h->p = vec3_add(vec3_add(vec3_scale(tr->p[0], b0), vec3_scale(tr->p[1], b1)),
                    vec3_scale(tr->p[2], b2));
    h->ng = vec3_normalize(vec3_cross(vec3_sub(tr->p[1], tr->p[0]), vec3_sub(tr->p[2], tr->p[0])));
    if (tr->has_normals) {
        vec3 n = vec3_add(vec3_add(vec3_scale(tr->n[0], b0), vec3_scale(tr->n[1], b1)),
                          vec3_scale(tr->n[2], b2));
        h->ns = vec3_normalize(n);
        /* the given normals define the outside: turn the winding's normal to agree with them */
        if (vec3_dot(h->ns, h->ng) < 0) h->ng = vec3_neg(h->ng);
    } else {
        h->ns = h->ng;
    }
    h->bary = (uv2){b1, b2};
}
