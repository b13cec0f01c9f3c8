/* test_triangle.c - the watertight test: barycentrics, an edge or vertex shared by neighbours
 * taken by exactly one of them, parallel and degenerate cases, two-sided hits, the (tmin, tmax)
 * interval, agreement with an independent long double test. */
#include "envtex/scene/scene.h"
#include "envtex/geometry/triangle.h"

#include "envtex/core/rng.h"
#include "unit.h"

/* Checks for long loops: every passing ck_assert costs a system call (Check records the last
 * passing line), which would dominate the run time; these report failures only. */
#define EXPECT(c)                                                                                  \
    do {                                                                                           \
        if (!(c)) ck_abort_msg("failed: %s", #c);                                                  \
    } while (0)
#define EXPECT_MSG(c, ...)                                                                         \
    do {                                                                                           \
        if (!(c)) ck_abort_msg(__VA_ARGS__);                                                       \
    } while (0)
#define EXPECT_INT_EQ(a, b)                                                                        \
    do {                                                                                           \
        long long a_ = (a), b_ = (b);                                                              \
        if (a_ != b_) ck_abort_msg("%s == %lld, %s == %lld", #a, a_, #b, b_);                      \
    } while (0)
#define EXPECT_NEAR(a, b, tol) unit_near(__FILE__, __LINE__, #a, (a), (b), (tol))

static ray make_ray(vec3 o, vec3 d) { return (ray){o, d, 0.0, INFINITY}; }

static const vec3 P0 = {0, 0, 0}, P1 = {1, 0, 0}, P2 = {0, 1, 0};

/* A ray straight down onto the z = 0 plane at (x, y). */
static ray down_at(double x, double y) { return make_ray(vec3_make(x, y, 2), vec3_make(0, 0, -1)); }

START_TEST(test_triangle_hit_at_the_centroid_has_barycentrics_one_third)
{
    double t, b1, b2;
    ray r = down_at(1.0 / 3, 1.0 / 3);
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 1);
    EXPECT_NEAR(t, 2, 1e-15);
    EXPECT_NEAR(b1, 1.0 / 3, 1e-15);
    EXPECT_NEAR(b2, 1.0 / 3, 1e-15);
    /* b1 weights p1, b2 weights p2: p = b0 p0 + b1 p1 + b2 p2 at an off-centre point */
    vec3 q0 = {1, 2, 3}, q1 = {4, 0, 3}, q2 = {2, 5, 3};
    vec3 p = vec3_add(vec3_add(vec3_scale(q0, 0.2), vec3_scale(q1, 0.5)), vec3_scale(q2, 0.3));
    r = make_ray(vec3_add(p, vec3_make(0.3, -0.2, 4)), vec3_make(-0.3, 0.2, -4));
    EXPECT_INT_EQ(triangle_intersect(q0, q1, q2, &r, &t, &b1, &b2), 1);
    EXPECT_NEAR(t, 1, 1e-14);
    EXPECT_NEAR(b1, 0.5, 1e-14);
    EXPECT_NEAR(b2, 0.3, 1e-14);
}
END_TEST

/* How many of the triangles (c, q[i], q[i + 1]) of a fan, each with the winding flip[i] picks,
 * ray r hits. */
static int fan_hits(vec3 c, const vec3 *q, int n, int closed, const ray *r, unsigned flip)
{
    int hits = 0;
    for (int i = 0; i + 1 < n + closed; i++) {
        double t, b1, b2;
        vec3 u = q[i], v = q[(i + 1) % n];
        hits += flip >> i & 1 ? triangle_intersect(c, v, u, r, &t, &b1, &b2)
                              : triangle_intersect(c, u, v, r, &t, &b1, &b2);
    }
    return hits;
}

/* A point of an edge shared by two triangles, or a vertex inside a fan, belongs to exactly one
 * of them, with either winding and from either side: here the unit triangle's vertices, edge
 * midpoints and other edge points, each seen down, up and slanted, inside four triangles around
 * it.  Catches an inside test with a tolerance (two hits: light counted twice along an edge) or
 * a strict one (no hit: a crack), and a tie rule that depends on the winding. */
START_TEST(test_triangle_an_edge_or_vertex_belongs_to_exactly_one_neighbour)
{
    const double pts[][2] = {{0, 0},    {1, 0},    {0, 1},     /* vertices */
                             {0.5, 0},  {0, 0.5},  {0.5, 0.5}, /* edge midpoints */
                             {0.25, 0}, {0, 0.75}, {0.75, 0.25}};
    const vec3 dirs[] = {{0, 0, -1}, {0, 0, 1}, {0.3, -0.2, -1}, {-1, 0.4, 0.5}};
    for (unsigned i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        vec3 c = vec3_make(pts[i][0], pts[i][1], 0);
        /* four triangles around the point, with corners at the unit triangle's where it has
         * one there: the point lies on their shared edges (and at their shared vertex) */
        vec3 q[4] = {vec3_make(c.x + 1, c.y, 0), vec3_make(c.x, c.y + 1, 0),
                     vec3_make(c.x - 1, c.y, 0), vec3_make(c.x, c.y - 1, 0)};
        for (unsigned k = 0; k < sizeof dirs / sizeof dirs[0]; k++) {
            ray r = make_ray(vec3_madd(c, dirs[k], -2), dirs[k]);
            for (unsigned flip = 0; flip < 16; flip++) {
                int n = fan_hits(c, q, 4, 1, &r, flip);
                EXPECT_MSG(n == 1, "(%g, %g) direction %u windings %u: %d hits", pts[i][0],
                           pts[i][1], k, flip, n);
            }
        }
    }
    /* and on the unit triangle itself, its edge points belong to it or to its mirror image
     * across that edge, never both, never neither */
    const vec3 mirror[3] = {{0.5, -1, 0}, {-1, 0.5, 0}, {1, 1, 0}}; /* across y=0, x=0, x+y=1 */
    for (unsigned i = 3; i < sizeof pts / sizeof pts[0]; i++) {
        int e = pts[i][1] == 0 ? 0 : pts[i][0] == 0 ? 1 : 2;
        vec3 u = e == 1 ? P0 : e == 0 ? P0 : P1, v = e == 0 ? P1 : P2;
        for (unsigned k = 0; k < sizeof dirs / sizeof dirs[0]; k++) {
            vec3 c = vec3_make(pts[i][0], pts[i][1], 0);
            ray r = make_ray(vec3_madd(c, dirs[k], -2), dirs[k]);
            double t, b1, b2;
            int n = triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2) +
                    triangle_intersect(v, u, mirror[e], &r, &t, &b1, &b2);
            EXPECT_MSG(n == 1, "(%g, %g) direction %u: %d hits", pts[i][0], pts[i][1], k, n);
        }
    }
    /* just outside each edge misses */
    const double out[][2] = {
        {0.5, -1e-15}, {-1e-15, 0.5}, {0.5 + 1e-15, 0.5 + 1e-15}, {1 + 1e-15, 0}, {-1e-15, -1e-15}};
    for (unsigned i = 0; i < sizeof out / sizeof out[0]; i++) {
        ray r = down_at(out[i][0], out[i][1]);
        double t, b1, b2;
        EXPECT_MSG(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2) == 0, "hit (%g, %g)", out[i][0],
                   out[i][1]);
    }
}
END_TEST


/* A ray 2^-60 on one side of an edge through it is decided by the exact sign, where the two
 * products of the edge function round to the same double: here the ray is the z axis and the
 * edge runs from a ~ (1, 1) to b ~ (-1, -1), nudged so that the origin lies 2^-60 left or right
 * of it.  The triangle on the ray's side is hit and its neighbour across the edge is not, in
 * both cases.  Catches an edge function without its exact fallback, which calls both 0 and
 * leaves them to the tie rule, right for one side and wrong for the other. */
START_TEST(test_triangle_a_ray_a_hair_inside_an_edge_hits_the_side_it_is_on)
{
    const double h = 0x1p-30, z = -1;
    for (int side = 0; side < 2; side++) {
        /* side 0: a x b = 2^-60 (the origin left of a -> b); side 1: -2^-60 (right of it) */
        vec3 a = side ? vec3_make(1 + h, 1 + 2 * h, z) : vec3_make(1 + 2 * h, 1 + h, z);
        vec3 b = side ? vec3_make(-1, -1 - h, z) : vec3_make(-1 - h, -1, z);
        vec3 left = vec3_make(1, -1, z), right = vec3_make(-1, 1, z); /* of a -> b */
        ray r = make_ray(vec3_make(0, 0, 5), vec3_make(0, 0, -1));
        double t, b1, b2;
        int hit_left = triangle_intersect(a, b, left, &r, &t, &b1, &b2);
        int hit_right = triangle_intersect(a, right, b, &r, &t, &b1, &b2);
        EXPECT_MSG(hit_left == !side && hit_right == side,
                   "origin %s of the edge: left triangle %d, right triangle %d",
                   side ? "right" : "left", hit_left, hit_right);
    }
}
END_TEST

START_TEST(test_triangle_rays_across_a_shared_edge_hit_exactly_one_side)
{
    /* Two triangles sharing the diagonal edge a-c of a quad, with awkward coordinates. */
    rng g;
    rng_seed(&g, 31, 0);
    for (int quad = 0; quad < 20; quad++) {
        vec3 a = vec3_make(rng_uniform(&g) * 10 - 5, rng_uniform(&g) * 10 - 5, rng_uniform(&g)),
             b = vec3_add(a, vec3_make(3.1 + rng_uniform(&g), 0.3, 0.7)),
             c = vec3_add(a, vec3_make(2.9, 3.7 + rng_uniform(&g), -0.4)),
             d = vec3_add(a, vec3_make(-0.2, 3.3, 0.5 * rng_uniform(&g)));
        vec3 eye = vec3_make(1.3, -0.7, 20);
        for (int i = 1; i < 2000; i++) {
            /* points on the shared edge (as exactly as doubles allow), not at its ends */
            double s = i / 2000.0;
            vec3 on = vec3_add(vec3_scale(a, 1 - s), vec3_scale(c, s));
            ray r = make_ray(eye, vec3_sub(on, eye));
            double t, b1, b2;
            int h1 = triangle_intersect(a, b, c, &r, &t, &b1, &b2);
            int h2 = triangle_intersect(a, c, d, &r, &t, &b1, &b2);
            EXPECT_MSG(h1 + h2 == 1, "quad %d: %d hits at s = %.17g", quad, h1 + h2, s);
        }
        /* and a sweep across the edge, ray by ray, in steps of ~1e-15 of the quad size */
        vec3 mid = vec3_scale(vec3_add(a, c), 0.5), across = vec3_sub(b, d);
        for (int i = -500; i <= 500; i++) {
            vec3 p = vec3_madd(mid, across, i * 1e-15);
            ray r = make_ray(eye, vec3_sub(p, eye));
            double t, b1, b2;
            int h1 = triangle_intersect(a, b, c, &r, &t, &b1, &b2);
            int h2 = triangle_intersect(a, c, d, &r, &t, &b1, &b2);
            EXPECT_MSG(h1 + h2 == 1, "quad %d: %d hits %d steps across the edge", quad, h1 + h2,
                       i);
        }
    }
}
END_TEST

START_TEST(test_triangle_parallel_ray_misses)
{
    double t, b1, b2;
    /* in the plane of the triangle, through its interior */
    ray r = make_ray(vec3_make(-1, 0.25, 0), vec3_make(1, 0, 0));
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 0);
    /* parallel above it */
    r.o.z = 1;
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 0);
}
END_TEST

START_TEST(test_triangle_degenerate_triangles_are_never_hit)
{
    rng g;
    rng_seed(&g, 32, 0);
    /* two equal corners, all three equal, and three collinear points (exactly representable) */
    vec3 tris[][3] = {{{0, 0, 0}, {0, 0, 0}, {1, 1, 0}},
                      {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}},
                      {{0, 0, 0}, {1, 1, 0}, {2, 2, 0}},
                      {{-1, 0.5, 2}, {0, 0.5, 2}, {4, 0.5, 2}}};
    for (unsigned k = 0; k < sizeof tris / sizeof tris[0]; k++)
        for (int i = 0; i < 20000; i++) {
            vec3 o = vec3_make(rng_uniform(&g) * 6 - 3, rng_uniform(&g) * 6 - 3,
                               rng_uniform(&g) * 6 - 3);
            vec3 target =
                vec3_add(tris[k][i % 3], vec3_scale(vec3_sub(tris[k][(i + 1) % 3], tris[k][i % 3]),
                                                    rng_uniform(&g)));
            ray r = make_ray(o, vec3_sub(target, o)); /* aimed exactly at the segment */
            double t, b1, b2;
            EXPECT_MSG(triangle_intersect(tris[k][0], tris[k][1], tris[k][2], &r, &t, &b1, &b2) ==
                           0,
                       "degenerate triangle %u hit", k);
        }
}
END_TEST

START_TEST(test_triangle_slivers_left_by_rounding_collinear_corners_are_never_hit)
{
    /* a, a + 0.3 v, a + 0.7 v: collinear as typed, a sliver of ~1e-17 area once rounded, whose
     * "normal" is noise; a ray aimed at the segment must not hit it */
    rng g;
    rng_seed(&g, 34, 0);
    for (int k = 0; k < 500; k++) {
        vec3 a = vec3_make(rng_uniform(&g), rng_uniform(&g), rng_uniform(&g));
        vec3 v = vec3_make(rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5);
        vec3 b = vec3_madd(a, v, 0.3), c = vec3_madd(a, v, 0.7);
        for (int i = 0; i < 100; i++) {
            vec3 o = vec3_make(rng_uniform(&g) * 4 - 2, rng_uniform(&g) * 4 - 2,
                               rng_uniform(&g) * 4 - 2);
            ray r = make_ray(o, vec3_sub(vec3_madd(a, v, 0.1 + 0.5 * rng_uniform(&g)), o));
            double t, b1, b2;
            EXPECT_MSG(!triangle_intersect(a, b, c, &r, &t, &b1, &b2), "sliver %d hit by ray %d", k,
                       i);
        }
    }
}
END_TEST

/* An independent reference: Moller-Trumbore (Cramer's rule) in long double, with the
 * barycentrics it finds (inside or not) and the degenerate test on the corners. */
typedef long double ld;
static int reference_long_double(vec3 p0, vec3 p1, vec3 p2, const ray *r, ld *t, ld *b1, ld *b2)
{
    ld e1[3] = {(ld)p1.x - p0.x, (ld)p1.y - p0.y, (ld)p1.z - p0.z};
    ld e2[3] = {(ld)p2.x - p0.x, (ld)p2.y - p0.y, (ld)p2.z - p0.z};
    ld s[3] = {(ld)r->o.x - p0.x, (ld)r->o.y - p0.y, (ld)r->o.z - p0.z};
    ld d[3] = {r->d.x, r->d.y, r->d.z};
    ld pv[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                d[0] * e2[1] - d[1] * e2[0]};
    ld qv[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
                s[0] * e1[1] - s[1] * e1[0]};
    ld det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    *b1 = (s[0] * pv[0] + s[1] * pv[1] + s[2] * pv[2]) / det;
    *b2 = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
    *t = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
    return *b1 >= 0 && *b2 >= 0 && *b1 + *b2 <= 1 && *t > r->tmin && *t < r->tmax;
}

/* Away from the edges (1e-9 in barycentrics) and from the degenerate threshold, the watertight
 * test agrees with the long double reference on every hit and miss, t and barycentrics to
 * 1e-12, for ordinary, thin and sliver triangles, rays from any side, finite and infinite tmax.
 * Catches a wrong axis turn or shear (rays along x or y), edge functions assigned to the wrong
 * corners, or t measured along the turned axis with the wrong sign. */
START_TEST(test_triangle_agrees_with_a_long_double_reference_away_from_edges)
{
    rng g;
    rng_seed(&g, 77, 0);
    int compared = 0, hits = 0;
    for (int k = 0; k < 3000; k++) {
        vec3 a = vec3_make(rng_uniform(&g), rng_uniform(&g), rng_uniform(&g));
        vec3 v = vec3_make(rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5);
        vec3 w = vec3_make(rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5);
        double off = pow(10, -6 * rng_uniform(&g)); /* ordinary to thin (1e-6) */
        vec3 b = vec3_madd(a, v, 0.3), c = vec3_madd(vec3_madd(a, v, 0.7), w, off);
        for (int i = 0; i < 20; i++) {
            vec3 o = vec3_make(rng_uniform(&g) * 4 - 2, rng_uniform(&g) * 4 - 2,
                               rng_uniform(&g) * 4 - 2);
            vec3 aim = vec3_madd(vec3_madd(a, vec3_sub(b, a), 1.4 * rng_uniform(&g) - 0.2),
                                 vec3_sub(c, a), 1.4 * rng_uniform(&g) - 0.2);
            ray r = make_ray(o, vec3_sub(aim, o));
            r.tmax = i % 4 ? INFINITY : 0.5 + rng_uniform(&g);
            ld t0, u0, v0;
            int h0 = reference_long_double(a, b, c, &r, &t0, &u0, &v0);
            ld margin = fminl(fminl(fabsl(u0), fabsl(v0)), fabsl(1 - u0 - v0));
            vec3 n = vec3_cross(vec3_sub(b, a), vec3_sub(c, a));
            double sine = fabs(vec3_dot(n, r.d)) / (vec3_length(n) * vec3_length(r.d));
            /* the condition: the corner angle's and the ray's incidence sines (1 / kappa) */
            double kappa = vec3_length(vec3_sub(b, a)) * vec3_length(vec3_sub(c, a)) /
                           vec3_length(n) / sine, tol = 1e-14 * kappa;
            if (margin < tol || fabsl(t0 - r.tmax) < tol || sine < 1e-8) continue;
            double t1 = 0, u1 = 0, v1 = 0;
            int h1 = triangle_intersect(a, b, c, &r, &t1, &u1, &v1);
            EXPECT_MSG(h1 == h0, "triangle %d ray %d: hit %d, reference %d", k, i, h1, h0);
            EXPECT_MSG(!h0 || (fabsl(t1 - t0) <= tol * fabsl(t0) && fabsl(u1 - u0) <= tol &&
                               fabsl(v1 - v0) <= tol),
                       "triangle %d ray %d: t %.17g (%.17Lg), b %.17g %.17g (%.17Lg %.17Lg)", k,
                       i, t1, t0, u1, v1, u0, v0);
            compared++;
            hits += h0;
        }
    }
    /* rays along each axis, where the turn to z differs */
    for (int axis = 0; axis < 3; axis++)
        for (int sign = -1; sign <= 1; sign += 2) {
            vec3 q[3] = {{0.1, 0.2, 0.3}, {0.1, 0.2, 0.3}, {0.1, 0.2, 0.3}};
            double *c1 = axis == 0 ? &q[1].y : axis == 1 ? &q[1].z : &q[1].x;
            double *c2 = axis == 0 ? &q[2].z : axis == 1 ? &q[2].x : &q[2].y;
            *c1 += 1, *c2 += 1;
            vec3 d = vec3_make(axis == 0 ? sign : 0, axis == 1 ? sign : 0, axis == 2 ? sign : 0);
            vec3 aim = vec3_add(vec3_scale(q[0], 0.5), vec3_add(vec3_scale(q[1], 0.2),
                                                                vec3_scale(q[2], 0.3)));
            ray r = make_ray(vec3_madd(aim, d, -3), d);
            double t, b1, b2;
            EXPECT_MSG(triangle_intersect(q[0], q[1], q[2], &r, &t, &b1, &b2), "axis %d missed",
                       axis);
            EXPECT_NEAR(t, 3, 1e-15);
            EXPECT_NEAR(b1, 0.2, 1e-15);
            EXPECT_NEAR(b2, 0.3, 1e-15);
        }
    EXPECT_MSG(compared > 40000 && hits > 10000, "compared %d, hits %d", compared, hits);
}
END_TEST

START_TEST(test_triangle_is_hit_from_the_back_too)
{
    double t, b1, b2;
    ray r = make_ray(vec3_make(0.25, 0.25, -3), vec3_make(0, 0, 1)); /* below, against the normal */
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 1);
    EXPECT_NEAR(t, 3, 1e-15);
    EXPECT_NEAR(b1, 0.25, 1e-15);
    EXPECT_NEAR(b2, 0.25, 1e-15);
}
END_TEST

START_TEST(test_triangle_hit_respects_tmin_and_tmax_and_misses_behind)
{
    double t = 7, b1, b2;
    ray r = down_at(0.2, 0.2);
    r.tmax = 2; /* open interval: t = 2 is not a hit */
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 0);
    r.tmax = 2.5;
    r.tmin = 2;
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 0);
    r.tmin = 1.5;
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 1);
    EXPECT_NEAR(t, 2, 1e-15);
    ray behind = make_ray(vec3_make(0.2, 0.2, -1), vec3_make(0, 0, -1));
    t = 7;
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &behind, &t, &b1, &b2), 0);
    EXPECT(t == 7); /* outputs untouched on a miss */
}
END_TEST

START_TEST(test_triangle_nan_ray_misses)
{
    double t, b1, b2;
    ray r = make_ray(vec3_make(0.2, 0.2, 1), vec3_make(NAN, 0, -1));
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 0);
    r = make_ray(vec3_make(NAN, 0.2, 1), vec3_make(0, 0, -1));
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 0);
    r = make_ray(vec3_make(0.2, 0.2, 1), vec3_make(0, 0, 0));
    EXPECT_INT_EQ(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2), 0);
}
END_TEST

START_TEST(test_triangle_random_hits_reproduce_the_aimed_point)
{
    rng g;
    rng_seed(&g, 33, 0);
    for (int i = 0; i < 20000; i++) {
        vec3 q[3];
        for (int k = 0; k < 3; k++)
            q[k] = vec3_make(rng_uniform(&g) * 4 - 2, rng_uniform(&g) * 4 - 2,
                             rng_uniform(&g) * 4 - 2);
        double w1 = rng_uniform(&g), w2 = rng_uniform(&g);
        if (w1 + w2 > 1) w1 = 1 - w1, w2 = 1 - w2;
        vec3 p = vec3_add(q[0], vec3_add(vec3_scale(vec3_sub(q[1], q[0]), w1),
                                         vec3_scale(vec3_sub(q[2], q[0]), w2)));
        vec3 o = vec3_make(rng_uniform(&g) * 10 - 5, rng_uniform(&g) * 10 - 5, 6);
        ray r = make_ray(o, vec3_sub(p, o)); /* t = 1 at p */
        vec3 n = vec3_cross(vec3_sub(q[1], q[0]), vec3_sub(q[2], q[0]));
        double cosang = fabs(vec3_dot(vec3_normalize(n), vec3_normalize(r.d)));
        if (cosang < 0.05 || vec3_length(n) < 0.05) continue; /* ill-conditioned: skip */
        double t, b1, b2;
        EXPECT_INT_EQ(triangle_intersect(q[0], q[1], q[2], &r, &t, &b1, &b2), 1);
        EXPECT_NEAR(t, 1, 1e-11);
        EXPECT_NEAR(b1, w1, 1e-10);
        EXPECT_NEAR(b2, w2, 1e-10);
    }
}
END_TEST

/* Hits do not depend on the scene's unit: the same triangle and ray scaled by 10^-100 .. 10^100
 * (corners, origin and direction alike) give the same hit, t and barycentrics.  Catches a
 * sliver bound built from squared lengths, whose product overflowed to inf (or underflowed to
 * 0) for edges beyond ~1e51 (below ~1e-54) and rejected every such triangle. */
START_TEST(test_triangle_hits_do_not_depend_on_the_scene_scale)
{
    const vec3 a = {-1, -1, 0.5}, b = {2, -1, 0}, c = {0, 1.5, 0.25};
    const vec3 o = {0.1, 0.2, 3}, d = {0.05, -0.1, -1};
    for (int e = -100; e <= 100; e += 5) {
        double s = pow(10, e);
        ray r = make_ray(vec3_scale(o, s), vec3_scale(d, s));
        double t, b1, b2;
        EXPECT_MSG(triangle_intersect(vec3_scale(a, s), vec3_scale(b, s), vec3_scale(c, s), &r, &t,
                                      &b1, &b2),
                   "scale 1e%d: no hit", e);
        /* o + t d = b0 a + b1 b + b2 c at scale 1: t = 2.7 / 1.005 ... check against scale 1 */
        ray r1 = make_ray(o, d);
        double t1, c1, c2;
        EXPECT(triangle_intersect(a, b, c, &r1, &t1, &c1, &c2));
        EXPECT_NEAR(t, t1, 1e-13);
        EXPECT_NEAR(b1, c1, 1e-13);
        EXPECT_NEAR(b2, c2, 1e-13);
        /* a unit direction at that scale: t scales instead */
        r = make_ray(vec3_scale(o, s), vec3_normalize(d));
        EXPECT_MSG(triangle_intersect(vec3_scale(a, s), vec3_scale(b, s), vec3_scale(c, s), &r, &t,
                                      &b1, &b2),
                   "scale 1e%d, unit direction: no hit", e);
        EXPECT_NEAR(t / (s * vec3_length(d)), t1, 1e-13);
    }
}
END_TEST

Suite *triangle_suite(void)
{
    Suite *s = suite_create("triangle");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_triangle_hit_at_the_centroid_has_barycentrics_one_third);
    tcase_add_test(tc, test_triangle_an_edge_or_vertex_belongs_to_exactly_one_neighbour);
    tcase_add_test(tc, test_triangle_a_ray_a_hair_inside_an_edge_hits_the_side_it_is_on);
    tcase_add_test(tc, test_triangle_rays_across_a_shared_edge_hit_exactly_one_side);
    tcase_add_test(tc, test_triangle_parallel_ray_misses);
    tcase_add_test(tc, test_triangle_degenerate_triangles_are_never_hit);
    tcase_add_test(tc, test_triangle_slivers_left_by_rounding_collinear_corners_are_never_hit);
    tcase_add_test(tc, test_triangle_is_hit_from_the_back_too);
    tcase_add_test(tc, test_triangle_hit_respects_tmin_and_tmax_and_misses_behind);
    tcase_add_test(tc, test_triangle_nan_ray_misses);
    tcase_add_test(tc, test_triangle_random_hits_reproduce_the_aimed_point);
    tcase_add_test(tc, test_triangle_agrees_with_a_long_double_reference_away_from_edges);
    tcase_add_test(tc, test_triangle_hits_do_not_depend_on_the_scene_scale);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(triangle_suite)
