/* triangle.c - Moller-Trumbore ray-triangle intersection (see
 * include/envtex/geometry/triangle.h). */
#include "envtex/geometry/triangle.h"

int triangle_intersect(vec3 p0, vec3 p1, vec3 p2, const ray *r, double *t_out, double *b1_out,
                       double *b2_out)
{
    vec3 e1 = vec3_sub(p1, p0), e2 = vec3_sub(p2, p0);
    vec3 pv = vec3_cross(r->d, e2);
    double det = vec3_dot(e1, pv); /* = -d . (e1 x e2): zero when parallel or degenerate */
    if (det == 0 || !isfinite(det)) return 0;
    double inv = 1.0 / det;
    vec3 s = vec3_sub(r->o, p0);
    double b1 = vec3_dot(s, pv) * inv; /* Cramer's rule for o + t d = p0 + b1 e1 + b2 e2 */
    if (b1 < -TRIANGLE_EDGE_EPS || b1 > 1 + TRIANGLE_EDGE_EPS) return 0;
    vec3 qv = vec3_cross(s, e1);
    double b2 = vec3_dot(r->d, qv) * inv;
    if (b2 < -TRIANGLE_EDGE_EPS || b1 + b2 > 1 + TRIANGLE_EDGE_EPS) return 0;
    double t = vec3_dot(e2, qv) * inv;
    if (!(t > r->tmin && t < r->tmax)) return 0;
    /* |det| <= eps |d| |e1| |e2|: a sliver of rounding (or an edge-on ray): no hit.  Lengths,
     * not their squares, and eps first: the product of three squared lengths overflows (or
     * underflows) for edges beyond ~1e51 (or below ~1e-54), which rejected every such
     * triangle; this bound stays finite wherever det is.  Tested last, only for a ray that
     * passed every other test: the tests above only reject (a NaN from a tiny det fails the t
     * test), so the order changes no answer, and most rays a BVH leaf offers miss an edge
     * first. */
    double bound = TRIANGLE_DEGENERATE_EPS * vec3_length(r->d) * vec3_length(e1) * vec3_length(e2);
    if (fabs(det) <= bound) return 0;
    *t_out = t;
    *b1_out = b1;
    *b2_out = b2;
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
