/* test_sphere.c - ray-sphere intersection under affine transforms: inside / outside / tangent
 * rays, rays leaving the surface, ellipsoid normals (inverse transpose), the (tmin, tmax)
 * interval, precision far from the origin, and NaN rays. */
#include "envtex/scene/scene.h"
#include "envtex/geometry/sphere.h"

#include <string.h>

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

static sphere make_sphere(vec3 c, double r, mat4 xf)
{
    sphere s;
    memset(&s, 0, sizeof s);
    s.center = c;
    s.radius = r;
    s.xf = xf;
    EXPECT_INT_EQ(mat4_inverse(xf, &s.inv), 0);
    return s;
}

static sphere unit_sphere(void) { return make_sphere(vec3_make(0, 0, 0), 1, mat4_identity()); }

static ray make_ray(vec3 o, vec3 d) { return (ray){o, d, 0.0, INFINITY}; }

static vec3 random_unit(rng *r)
{
    double z = 2 * rng_uniform(r) - 1, phi = 2 * M_PI * rng_uniform(r);
    double s = sqrt(fmax(0.0, 1 - z * z));
    return vec3_make(s * cos(phi), s * sin(phi), z);
}

/* |a - b| <= tol per component (tol 0: equal) */
START_TEST(test_sphere_ray_from_outside_hits_the_near_side)
{
    sphere s = unit_sphere();
    ray r = make_ray(vec3_make(0, 0, 5), vec3_make(0, 0, -1));
    double t;
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
    EXPECT_NEAR(t, 4, 1e-15);
    hit h;
    sphere_hit(&s, &r, t, &h);
    EXPECT_NEAR(h.t, 4, 1e-15);
    ck_vec_near(h.p, vec3_make(0, 0, 1), 1e-15);
    ck_vec_near(h.ng, vec3_make(0, 0, 1), 1e-15);
    ck_vec_near(h.ns, h.ng, 0);
    /* t is in units of |d|: a direction of length 2 halves it */
    r.d = vec3_make(0, 0, -2);
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
    EXPECT_NEAR(t, 2, 1e-15);
    /* a ray pointing away misses */
    r.d = vec3_make(0, 0, 1);
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
}
END_TEST

START_TEST(test_sphere_ray_from_inside_hits_the_far_root)
{
    sphere s = make_sphere(vec3_make(1, 2, 3), 2, mat4_identity());
    double t;
    ray r = make_ray(vec3_make(1, 2, 3), vec3_make(0, 1, 0)); /* from the centre: b = 0 */
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
    EXPECT_NEAR(t, 2, 1e-15);
    r = make_ray(vec3_make(1, 2, 4), vec3_make(0, 0, 1));
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
    EXPECT_NEAR(t, 1, 1e-15);
    r.d = vec3_make(0, 0, -1);
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
    EXPECT_NEAR(t, 3, 1e-15);
    hit h;
    sphere_hit(&s, &r, t, &h);
    ck_vec_near(h.ng, vec3_make(0, 0, -1), 1e-15); /* outward, not flipped to the ray */
}
END_TEST

START_TEST(test_sphere_tangent_and_grazing_rays)
{
    sphere s = unit_sphere();
    double t = -1;
    /* exactly tangent: a double root; a hit at t = 5 or a miss are both acceptable */
    ray r = make_ray(vec3_make(-5, 1, 0), vec3_make(1, 0, 0));
    if (sphere_intersect(&s, &r, &t)) EXPECT_NEAR(t, 5, 1e-7);
    /* just outside misses */
    r.o.y = 1 + 1e-9;
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    /* just inside hits at 5 - sqrt(1 - y^2) */
    double y = 1 - 1e-6;
    r.o.y = y;
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
    EXPECT_NEAR(t, 5 - sqrt(1 - y * y), 1e-9);
}
END_TEST

START_TEST(test_sphere_ray_leaving_the_surface_outward_does_not_hit_it_again)
{
    rng g;
    rng_seed(&g, 21, 0);
    /* a unit sphere, an ellipsoid, and a sphere far from the origin */
    mat4 ell =
        mat4_mul(mat4_translate(vec3_make(3, -1, 2)),
                 mat4_mul(mat4_rotate(vec3_make(1, 1, 0), 30), mat4_scale(vec3_make(2, 1, 0.5))));
    sphere ss[3] = {unit_sphere(), make_sphere(vec3_make(0, 0, 0), 1, ell),
                    make_sphere(vec3_make(1e4, 0, 0), 10, mat4_identity())};
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 20000; i++) {
            /* hit the sphere from a random outside point */
            vec3 target =
                mat4_point(&ss[k].xf, vec3_add(ss[k].center,
                                               vec3_scale(random_unit(&g), 0.999 * ss[k].radius)));
            vec3 from = vec3_add(target, vec3_scale(random_unit(&g), 30 * ss[k].radius + 10));
            ray r = make_ray(from, vec3_normalize(vec3_sub(target, from)));
            double t;
            if (!sphere_intersect(&ss[k], &r, &t)) continue; /* origin inside: skip */
            hit h;
            sphere_hit(&ss[k], &r, t, &h);
            /* leave outward (any direction in the outer hemisphere) */
            vec3 d = random_unit(&g);
            if (vec3_dot(d, h.ng) < 0) d = vec3_neg(d);
            ray out = ray_spawn(h.p, h.ng, d);
            double t2;
            EXPECT_MSG(!sphere_intersect(&ss[k], &out, &t2), "sphere %d: self hit at t = %g", k,
                       t2);
            /* leave inward (well away from tangent): hit the far side, at a positive distance */
            if (vec3_dot(d, h.ng) > 0.05) {
                ray in = ray_spawn(h.p, h.ng, vec3_neg(d));
                EXPECT_INT_EQ(sphere_intersect(&ss[k], &in, &t2), 1);
                hit h2;
                sphere_hit(&ss[k], &in, t2, &h2);
                EXPECT(vec3_length(vec3_sub(h2.p, h.p)) > 1e-6 * ss[k].radius);
            }
        }
}
END_TEST

START_TEST(test_sphere_ray_leaving_the_unit_sphere_inward_crosses_the_chord)
{
    rng g;
    rng_seed(&g, 22, 0);
    sphere s = unit_sphere();
    for (int i = 0; i < 20000; i++) {
        vec3 p = random_unit(&g), d = random_unit(&g);
        if (vec3_dot(d, p) > -0.01) continue;
        ray r = ray_spawn(p, p, d);
        double t;
        EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
        EXPECT_NEAR(t, -2 * vec3_dot(p, d), 1e-6); /* chord length from p along d */
    }
}
END_TEST

START_TEST(test_sphere_ellipsoid_normal_is_the_analytic_one)
{
    /* x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 has normal (x/a^2, y/b^2, z/c^2) */
    const double a = 2, b = 0.5, c = 3;
    vec3 off = vec3_make(1, -2, 0.5);
    mat4 xf = mat4_mul(mat4_translate(off), mat4_scale(vec3_make(a, b, c)));
    sphere s = make_sphere(vec3_make(0, 0, 0), 1, xf);
    rng g;
    rng_seed(&g, 23, 0);
    int hits = 0;
    for (int i = 0; i < 20000; i++) {
        ray r = make_ray(vec3_add(off, vec3_scale(random_unit(&g), 10)), vec3_make(0, 0, 0));
        r.d = vec3_normalize(
            vec3_sub(vec3_add(off, vec3_mul(random_unit(&g), vec3_make(a, b, c))), r.o));
        double t;
        if (!sphere_intersect(&s, &r, &t)) continue;
        hits++;
        hit h;
        sphere_hit(&s, &r, t, &h);
        vec3 q = vec3_sub(h.p, off);
        EXPECT_NEAR(q.x * q.x / (a * a) + q.y * q.y / (b * b) + q.z * q.z / (c * c), 1, 1e-12);
        vec3 n = vec3_normalize(vec3_make(q.x / (a * a), q.y / (b * b), q.z / (c * c)));
        ck_vec_near(h.ng, n, 1e-12);
        EXPECT_NEAR(vec3_length(h.ng), 1, 1e-15);
        EXPECT(vec3_dot(h.ng, r.d) < 0); /* from outside: the outward normal faces the ray */
        ck_vec_near(h.p, vec3_madd(r.o, r.d, t), 1e-12); /* the world point is o + t d */
    }
    ck_assert_int_gt(hits, 10000);
}
END_TEST

START_TEST(test_sphere_hit_respects_tmin_and_tmax)
{
    sphere s = unit_sphere();
    ray r = make_ray(vec3_make(0, 0, 5), vec3_make(0, 0, -1));
    double t = 0;
    r.tmax = 3.9;
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    r.tmax = 4.0; /* open interval: t = tmax is not a hit */
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    r.tmax = 4.1;
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
    EXPECT_NEAR(t, 4, 1e-15);
    r.tmax = INFINITY;
    r.tmin = 4.5; /* past the near side: the far side */
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
    EXPECT_NEAR(t, 6, 1e-15);
    r.tmin = 6.5;
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    /* open at both ends for both roots: t = tmin is not a hit either (a ray starting exactly on
     * the sphere, tmin 0, must not hit it at t = 0), nor is the far root at t = tmax */
    r.tmin = 4.0;
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 1);
    EXPECT_NEAR(t, 6, 1e-15);
    r.tmin = 4.5;
    r.tmax = 6.0;
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    ray on = make_ray(vec3_make(0, 0, 1), vec3_make(0, 0, -1)); /* on the sphere, inwards */
    EXPECT_INT_EQ(sphere_intersect(&s, &on, &t), 1);
    EXPECT_NEAR(t, 2, 1e-15);
}
END_TEST

/* t of the first hit in long double (64-bit mantissa on x86; at worst double elsewhere): from
 * the perpendicular foot, t = (C - o).d - sqrt(R^2 - |perp|^2), no cancellation of big squares */
static double exact_t(vec3 o, vec3 d, vec3 c, double radius)
{
    long double dx = d.x, dy = d.y, dz = d.z, l = sqrtl(dx * dx + dy * dy + dz * dz);
    dx /= l, dy /= l, dz /= l;
    long double cx = (long double)c.x - o.x, cy = (long double)c.y - o.y,
                cz = (long double)c.z - o.z;
    long double along = cx * dx + cy * dy + cz * dz;
    long double px = cx - along * dx, py = cy - along * dy, pz = cz - along * dz;
    long double h2 = (long double)radius * radius - (px * px + py * py + pz * pz);
    return (double)((along - sqrtl(h2)) / l);
}

START_TEST(test_sphere_far_from_the_origin_keeps_precision)
{
    rng g;
    rng_seed(&g, 24, 0);
    vec3 c = vec3_make(1e6, 3e5, -2e5);
    /* centre in the object coordinates, and centre by a translation: both must be precise */
    sphere ss[2] = {make_sphere(c, 1, mat4_identity()),
                    make_sphere(vec3_make(0, 0, 0), 1, mat4_translate(c))};
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 5000; i++) {
            vec3 o = vec3_scale(random_unit(&g), 3);
            /* aim at a random point of the disc facing the ray, up to 0.99 R off centre */
            vec3 aim = vec3_add(c, vec3_scale(random_unit(&g), 0.99));
            ray r = make_ray(o, vec3_normalize(vec3_sub(aim, o)));
            double t;
            EXPECT_INT_EQ(sphere_intersect(&ss[k], &r, &t), 1);
            /* 1e-6 absolute at t ~ 1.1e6: relative 1e-12.  The textbook b^2 - ac loses all of
             * the discriminant here (b^2 ~ 1e12 with rounding ~1e-4 against R^2 = 1). */
            EXPECT_NEAR(t, exact_t(o, r.d, c, 1), 1e-6);
        }
}
END_TEST

START_TEST(test_sphere_nan_or_zero_ray_misses_without_crashing)
{
    sphere s = unit_sphere();
    double t = 123;
    ray r = make_ray(vec3_make(0, 0, 5), vec3_make(NAN, 0, -1));
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    r.d = vec3_make(NAN, NAN, NAN);
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    r.d = vec3_make(0, 0, 0);
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    r = make_ray(vec3_make(NAN, 0, 5), vec3_make(0, 0, -1));
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    r = make_ray(vec3_make(0, 0, 5), vec3_make(0, 0, -1));
    r.tmax = NAN;
    EXPECT_INT_EQ(sphere_intersect(&s, &r, &t), 0);
    EXPECT(t == 123); /* untouched on a miss */
}
END_TEST

/* point and normals equal bit for bit (memcmp: -0 and +0 differ) */
static int same_hit_bits(const hit *a, const hit *b)
{
    return memcmp(&a->p, &b->p, sizeof a->p) == 0 && memcmp(&a->ng, &b->ng, sizeof a->ng) == 0 &&
           memcmp(&a->ns, &b->ns, sizeof a->ns) == 0;
}

/* a sphere marked untransformed (no matrix products) finds exactly the t, point and normal of
 * the general path through the identity matrices, for rays from outside, from inside and
 * missing */
START_TEST(test_sphere_untransformed_fast_path_gives_the_general_paths_t)
{
    rng g;
    rng_seed(&g, 5, 0);
    sphere general = make_sphere(vec3_make(0.5, -2, 3), 1.5, mat4_identity());
    sphere fast = general;
    fast.untransformed = 1;
    int hits = 0;
    for (int i = 0; i < 20000; i++) {
        double s = i % 2 ? 1 : 6;
        vec3 o = vec3_add(general.center, vec3_scale(random_unit(&g), s * rng_uniform(&g)));
        ray r = make_ray(o, vec3_scale(random_unit(&g), 0.5 + rng_uniform(&g)));
        double t0 = -1, t1 = -1;
        int h0 = sphere_intersect(&general, &r, &t0), h1 = sphere_intersect(&fast, &r, &t1);
        EXPECT_INT_EQ(h1, h0);
        if (h0) {
            if (t1 != t0) ck_abort_msg("ray %d: t %.17g untransformed, %.17g general", i, t1, t0);
            /* and sphere_hit's point and normal, bit for bit (the identity's products are exact) */
            hit a, b;
            sphere_hit(&general, &r, t0, &a);
            sphere_hit(&fast, &r, t1, &b);
            if (!same_hit_bits(&a, &b) || b.t != t1 || b.bary.u != 0 || b.bary.v != 0)
                ck_abort_msg("ray %d: sphere_hit differs untransformed", i);
            hits++;
        }
    }
    ck_assert_int_gt(hits, 12000); /* every inside ray and a share of the outside ones */
    /* rays along the axes with -0 and +0 coordinates, from a sphere at the origin: the general
     * path's products turn -0 into +0, and the fast path must too (a -0 in a normal flips an
     * atan2 further on); both given the general path's t (sphere.h: t itself may differ there) */
    const double v[] = {-0.0, 0.0, 0.5, -0.5, 1, -1, 5, -5, 0.3};
    general = make_sphere(vec3_make(0, 0, 0), 1, mat4_identity());
    fast = general;
    fast.untransformed = 1;
    int n = 0;
    for (int k = 0; k < 9 * 9 * 9 * 27; k++) {
        int q = k / 27, m = k % 27;
        vec3 o = vec3_make(v[q % 9], v[q / 9 % 9], v[q / 81]);
        vec3 d = vec3_make(v[m % 3], v[m / 3 % 3], v[m / 9 + 3 * (m % 2)]); /* +-0 and 0.5 mixed */
        ray r = make_ray(o, d);
        double t0;
        if (!sphere_intersect(&general, &r, &t0)) continue;
        hit a, b;
        sphere_hit(&general, &r, t0, &a);
        sphere_hit(&fast, &r, t0, &b);
        if (!same_hit_bits(&a, &b))
            ck_abort_msg("o (%g %g %g) d (%g %g %g): sphere_hit's bits differ untransformed", o.x,
                         o.y, o.z, d.x, d.y, d.z);
        n++;
    }
    ck_assert_int_gt(n, 1000);
}
END_TEST

START_TEST(test_sphere_bounds_contain_the_transformed_surface)
{
    mat4 xf =
        mat4_mul(mat4_translate(vec3_make(5, 0, -3)),
                 mat4_mul(mat4_rotate(vec3_make(1, 2, 3), 40), mat4_scale(vec3_make(3, 1, 0.2))));
    sphere s = make_sphere(vec3_make(0.5, 0, 0), 2, xf);
    vec3 lo, hi;
    sphere_bounds(&s, &lo, &hi);
    rng g;
    rng_seed(&g, 25, 0);
    for (int i = 0; i < 10000; i++) {
        vec3 p = mat4_point(&s.xf, vec3_add(s.center, vec3_scale(random_unit(&g), s.radius)));
        EXPECT(p.x >= lo.x && p.y >= lo.y && p.z >= lo.z);
        EXPECT(p.x <= hi.x && p.y <= hi.y && p.z <= hi.z);
    }
    /* and for an untransformed sphere they are tight */
    sphere u = make_sphere(vec3_make(1, 2, 3), 0.5, mat4_identity());
    sphere_bounds(&u, &lo, &hi);
    ck_vec_near(lo, vec3_make(0.5, 1.5, 2.5), 0);
    ck_vec_near(hi, vec3_make(1.5, 2.5, 3.5), 0);
}
END_TEST

/* A hit from a ray 1e2 .. 1e10 long lies on the sphere to a few ulps of |center| + radius, and
 * so does an ellipsoid's (its object-space point), for rays from every side.  Catches a hit
 * point taken as o + t d alone, off the sphere by t's error (1e-8 for a ray 1e8 long), which
 * the leaving ray's offset (ray.h) does not cover. */
START_TEST(test_sphere_hit_point_lies_on_the_sphere_however_far_the_ray_came)
{
    rng g;
    rng_seed(&g, 9, 0);
    const vec3 c = {0.5, -2, 3};
    const double R = 1.5;
    sphere plain = make_sphere(c, R, mat4_identity());
    sphere oval = make_sphere(c, R, mat4_scale(vec3_make(2, 1, 0.5)));
    double worst = 0;
    for (int i = 0; i < 4000; i++) {
        const sphere *s = i % 2 ? &oval : &plain;
        double dist = pow(10, 2 + 8 * rng_uniform(&g));
        vec3 aim = vec3_madd(c, random_unit(&g), 0.9 * R * rng_uniform(&g)); /* inside */
        vec3 wc = mat4_point(&s->xf, aim), from = vec3_madd(wc, random_unit(&g), dist);
        ray r = make_ray(from, vec3_sub(wc, from));
        double t;
        if (!sphere_intersect(s, &r, &t)) ck_abort_msg("ray %d from %g away missed", i, dist);
        hit h;
        sphere_hit(s, &r, t, &h);
        vec3 po = mat4_point(&s->inv, h.p); /* object space */
        double off = fabs(vec3_length(vec3_sub(po, c)) - R) / (vec3_max_abs(c) + R);
        worst = fmax(worst, off);
    }
    ck_assert_msg(worst < 1e-14, "a hit point is %g (of |center| + radius) off the sphere", worst);
}
END_TEST

Suite *sphere_suite(void)
{
    Suite *s = suite_create("sphere");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_sphere_ray_from_outside_hits_the_near_side);
    tcase_add_test(tc, test_sphere_ray_from_inside_hits_the_far_root);
    tcase_add_test(tc, test_sphere_tangent_and_grazing_rays);
    tcase_add_test(tc, test_sphere_ray_leaving_the_surface_outward_does_not_hit_it_again);
    tcase_add_test(tc, test_sphere_ray_leaving_the_unit_sphere_inward_crosses_the_chord);
    tcase_add_test(tc, test_sphere_ellipsoid_normal_is_the_analytic_one);
    tcase_add_test(tc, test_sphere_hit_respects_tmin_and_tmax);
    tcase_add_test(tc, test_sphere_far_from_the_origin_keeps_precision);
    tcase_add_test(tc, test_sphere_hit_point_lies_on_the_sphere_however_far_the_ray_came);
    tcase_add_test(tc, test_sphere_nan_or_zero_ray_misses_without_crashing);
    tcase_add_test(tc, test_sphere_untransformed_fast_path_gives_the_general_paths_t);
    tcase_add_test(tc, test_sphere_bounds_contain_the_transformed_surface);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(sphere_suite)
