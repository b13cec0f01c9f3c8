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
