/* test_triangle.c - Moller-Trumbore: barycentrics, inclusive edges and vertices, no cracks
 * along a shared edge, parallel and degenerate cases, two-sided hits, the (tmin, tmax) interval. */
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

START_TEST(test_triangle_edges_and_vertices_are_inside)
{
    double t, b1, b2;
    const double pts[][2] = {{0, 0},    {1, 0},    {0, 1},     /* vertices */
                             {0.5, 0},  {0, 0.5},  {0.5, 0.5}, /* edge midpoints */
                             {0.25, 0}, {0, 0.75}, {0.75, 0.25}};
    for (unsigned i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        ray r = down_at(pts[i][0], pts[i][1]);
        EXPECT_MSG(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2) == 1, "missed (%g, %g)",
                   pts[i][0], pts[i][1]);
    }
    /* just outside each edge misses (1e-9 is far beyond the 1e-12 tolerance) */
    const double out[][2] = {
        {0.5, -1e-9}, {-1e-9, 0.5}, {0.5 + 1e-9, 0.5 + 1e-9}, {1 + 1e-9, 0}, {-1e-9, -1e-9}};
    for (unsigned i = 0; i < sizeof out / sizeof out[0]; i++) {
        ray r = down_at(out[i][0], out[i][1]);
        EXPECT_MSG(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2) == 0, "hit (%g, %g)", out[i][0],
                   out[i][1]);
    }
}
END_TEST

/* The tolerance is TRIANGLE_EDGE_EPS in barycentric units at every edge and every vertex alike
 * (triangle.h): points half of it outside each edge, and half of it beyond each vertex along
 * its edges, still hit.  On this triangle a ray straight down at (x, y) has b1 = x and b2 = y
 * exactly.  Catches one barycentric's bound losing its tolerance (b1 > 1 instead of
 * b1 > 1 + eps rejected a point just beyond p1 but not the same point beyond p2). */
START_TEST(test_triangle_edge_tolerance_is_the_same_at_every_edge_and_vertex)
{
    double t, b1, b2;
    const double e = 0.5 * TRIANGLE_EDGE_EPS;
    const double pts[][2] = {{0.5, -e},
                             {-e, 0.5},
                             {0.5 + e / 2, 0.5 + e / 2}, /* edges */
                             {-e, -e},
                             {-e, 0},
                             {0, -e}, /* beyond p0 */
                             {1 + e, 0},
                             {1 + e / 2, -e / 2},
                             {1, -e}, /* beyond p1 */
                             {0, 1 + e},
                             {-e / 2, 1 + e / 2},
                             {-e, 1}}; /* beyond p2 */
    for (unsigned i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        ray r = down_at(pts[i][0], pts[i][1]);
        EXPECT_MSG(triangle_intersect(P0, P1, P2, &r, &t, &b1, &b2) == 1, "missed (%.17g, %.17g)",
                   pts[i][0], pts[i][1]);
    }
}
END_TEST

START_TEST(test_triangle_rays_across_a_shared_edge_find_no_crack)
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
        for (int i = 0; i <= 2000; i++) {
            /* points exactly on the shared edge (as exactly as doubles allow) */
            double s = i / 2000.0;
            vec3 on = vec3_add(vec3_scale(a, 1 - s), vec3_scale(c, s));
            ray r = make_ray(eye, vec3_sub(on, eye));
            double t, b1, b2;
            int h1 = triangle_intersect(a, b, c, &r, &t, &b1, &b2);
            int h2 = triangle_intersect(a, c, d, &r, &t, &b1, &b2);
            EXPECT_MSG(h1 || h2, "quad %d: crack at s = %.17g", quad, s);
        }
        /* and a sweep across the edge, ray by ray, in steps of ~1e-15 of the quad size */
        vec3 mid = vec3_scale(vec3_add(a, c), 0.5), across = vec3_sub(b, d);
        for (int i = -500; i <= 500; i++) {
            vec3 p = vec3_madd(mid, across, i * 1e-15);
            ray r = make_ray(eye, vec3_sub(p, eye));
            double t, b1, b2;
            int h1 = triangle_intersect(a, b, c, &r, &t, &b1, &b2);
            int h2 = triangle_intersect(a, c, d, &r, &t, &b1, &b2);
            EXPECT_MSG(h1 || h2, "quad %d: crack %d steps across the edge", quad, i);
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

/* Moller-Trumbore with the sliver test first, as written before triangle.c moved it last (a
 * cost only for rays that pass every other test): the reference the reordering must match. */
static int reference_sliver_test_first(vec3 p0, vec3 p1, vec3 p2, const ray *r, double *t_out,
                                       double *b1_out, double *b2_out)
{
    vec3 e1 = vec3_sub(p1, p0), e2 = vec3_sub(p2, p0);
    vec3 pv = vec3_cross(r->d, e2);
    double det = vec3_dot(e1, pv);
    if (det == 0 || !isfinite(det)) return 0;
    double bound = TRIANGLE_DEGENERATE_EPS * vec3_length(r->d) * vec3_length(e1) * vec3_length(e2);
    if (fabs(det) <= bound) return 0;
    double inv = 1.0 / det;
    vec3 s = vec3_sub(r->o, p0);
    double b1 = vec3_dot(s, pv) * inv;
    if (b1 < -TRIANGLE_EDGE_EPS || b1 > 1 + TRIANGLE_EDGE_EPS) return 0;
    vec3 qv = vec3_cross(s, e1);
    double b2 = vec3_dot(r->d, qv) * inv;
    if (b2 < -TRIANGLE_EDGE_EPS || b1 + b2 > 1 + TRIANGLE_EDGE_EPS) return 0;
    double t = vec3_dot(e2, qv) * inv;
    if (!(t > r->tmin && t < r->tmax)) return 0;
    *t_out = t;
    *b1_out = b1;
    *b2_out = b2;
    return 1;
}

/* the sliver test's place changes no answer: the same hits, t and barycentrics as testing it
 * first, for ordinary triangles, slivers (collinear corners, rounded) and near-slivers whose det
 * lies around the threshold, hit or missed, with finite tmax */
START_TEST(test_triangle_sliver_test_last_gives_the_same_answers_as_first)
{
    rng g;
    rng_seed(&g, 77, 0);
    int hits = 0, slivers_missed = 0;
    for (int k = 0; k < 3000; k++) {
        vec3 a = vec3_make(rng_uniform(&g), rng_uniform(&g), rng_uniform(&g));
        vec3 v = vec3_make(rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5);
        vec3 w = vec3_make(rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5, rng_uniform(&g) - 0.5);
        /* off the line a + s v by 10^-(0..12): ordinary, thin, and slivers at the threshold */
        double off = pow(10, -12 * rng_uniform(&g)) * (k % 3 != 0);
        vec3 b = vec3_madd(a, v, 0.3), c = vec3_madd(vec3_madd(a, v, 0.7), w, off);
        for (int i = 0; i < 20; i++) {
            vec3 o = vec3_make(rng_uniform(&g) * 4 - 2, rng_uniform(&g) * 4 - 2,
                               rng_uniform(&g) * 4 - 2);
            vec3 aim = vec3_madd(vec3_madd(a, vec3_sub(b, a), 1.4 * rng_uniform(&g) - 0.2),
                                 vec3_sub(c, a), 1.4 * rng_uniform(&g) - 0.2);
            ray r = make_ray(o, vec3_sub(aim, o));
            r.tmax = i % 4 ? INFINITY : 0.5 + rng_uniform(&g);
            double t0 = 0, u0 = 0, v0 = 0, t1 = 0, u1 = 0, v1 = 0;
            int h0 = reference_sliver_test_first(a, b, c, &r, &t0, &u0, &v0);
            int h1 = triangle_intersect(a, b, c, &r, &t1, &u1, &v1);
            EXPECT_MSG(h1 == h0, "triangle %d ray %d: hit %d, reference %d", k, i, h1, h0);
            EXPECT_MSG(!h0 || (t1 == t0 && u1 == u0 && v1 == v0), "triangle %d ray %d: another hit",
                       k, i);
            hits += h0;
            slivers_missed += !h0 && k % 3 == 0;
        }
    }
    EXPECT_MSG(hits > 5000 && slivers_missed == 20000, "hits %d, slivers missed %d", hits,
               slivers_missed);
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
    tcase_add_test(tc, test_triangle_edges_and_vertices_are_inside);
    tcase_add_test(tc, test_triangle_edge_tolerance_is_the_same_at_every_edge_and_vertex);
    tcase_add_test(tc, test_triangle_rays_across_a_shared_edge_find_no_crack);
    tcase_add_test(tc, test_triangle_parallel_ray_misses);
    tcase_add_test(tc, test_triangle_degenerate_triangles_are_never_hit);
    tcase_add_test(tc, test_triangle_slivers_left_by_rounding_collinear_corners_are_never_hit);
    tcase_add_test(tc, test_triangle_is_hit_from_the_back_too);
    tcase_add_test(tc, test_triangle_hit_respects_tmin_and_tmax_and_misses_behind);
    tcase_add_test(tc, test_triangle_nan_ray_misses);
    tcase_add_test(tc, test_triangle_random_hits_reproduce_the_aimed_point);
    tcase_add_test(tc, test_triangle_sliver_test_last_gives_the_same_answers_as_first);
    tcase_add_test(tc, test_triangle_hits_do_not_depend_on_the_scene_scale);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(triangle_suite)
