/* test_raydiff.c - ray differentials (raydiff.h, camera_ray_differential) against finite
 * differences of the rays themselves, and the footprint they give a texture (texshade.h). */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envtex/geometry/camera.h"
#include "envtex/reflection/fresnel.h"
#include "envtex/io/pfm.h"
#include "envtex/geometry/raydiff.h"
#include "envtex/integrators/texshade.h"
#include "envtex/scene/scene_load.h"
#include "unit.h"

/* Central-difference step in pixels: the truncation error is ~h^2 times the third derivative,
 * the rounding error ~1e-16 / h; 1e-3 keeps both near 1e-9. */
/* Differentials carried through a surface are finite steps (the offset ray meets the tangent
 * plane a whole pixel away), exact only to first order: the reflection and refraction tests
 * take them for a step of DIFF_SCALE pixels and divide, which gives the derivative. */
#define DIFF_SCALE 1e-5
#define FD_STEP    1e-3
#define FD_TOL     1e-7

static camera test_camera(void)
{
    camera c;
    camera_init(&c, vec3_make(0.3, 0.2, 5), vec3_make(0, 0, 0), vec3_make(0, 1, 0), 50, 80, 60);
    return c;
}

/* |a - b| <= tol max(1, |b|), reported at the caller's line */
#define assert_vec_near(a, b, tol, what) vec_near_at(__FILE__, __LINE__, a, b, tol, what)
static void vec_near_at(const char *file, int line, vec3 a, vec3 b, double tol, const char *what)
{
    double e = vec3_length(vec3_sub(a, b));
    if (!(e <= tol * fmax(1.0, vec3_length(b))))
        unit_fail_at(file, line,
                     "%s: got (%.17g, %.17g, %.17g), want (%.17g, %.17g, %.17g), tolerance %.3g "
                     "times max(1, |want|) (off by %.3g)",
                     what, a.x, a.y, a.z, b.x, b.y, b.z, tol, e);
}

/* The frame texshade needs at hit h, seen from its front: n = ng, entering, all else 0. */
static surface front_frame(const hit *h)
{
    surface s;
    memset(&s, 0, sizeof s);
    s.entering = 1;
    s.n = s.ng = h->ng;
    return s;
}

START_TEST(test_camera_differentials_are_the_derivatives_of_camera_ray)
{
    camera c = test_camera();
    const double px[4][2] = {{0.5, 0.5}, {40, 30}, {79.5, 12.25}, {3, 59}};
    for (int i = 0; i < 4; i++) {
        double x = px[i][0], y = px[i][1];
        ray_diff rd;
        ray r = camera_ray_differential(&c, x, y, 1.0, &rd);
        ray r0 = camera_ray(&c, x, y);
        ck_assert(rd.has);
        ck_assert(vec3_length(vec3_sub(r.d, r0.d)) == 0); /* the same ray as camera_ray */
        vec3 fx =
            vec3_scale(vec3_sub(camera_ray(&c, x + FD_STEP, y).d, camera_ray(&c, x - FD_STEP, y).d),
                       0.5 / FD_STEP);
        vec3 fy =
            vec3_scale(vec3_sub(camera_ray(&c, x, y + FD_STEP).d, camera_ray(&c, x, y - FD_STEP).d),
                       0.5 / FD_STEP);
        assert_vec_near(rd.ddx, fx, FD_TOL, "ddx");
        assert_vec_near(rd.ddy, fy, FD_TOL, "ddy");
        ck_assert(vec3_length(rd.dox) == 0 && vec3_length(rd.doy) == 0); /* a pinhole */
    }
}
END_TEST

START_TEST(test_camera_differentials_shrink_with_the_scale)
{
    camera c = test_camera();
    ray_diff a, b;
    camera_ray_differential(&c, 10, 20, 1.0, &a);
    camera_ray_differential(&c, 10, 20, 0.25, &b);
    assert_vec_near(b.ddx, vec3_scale(a.ddx, 0.25), 1e-15, "ddx scaled");
    assert_vec_near(b.ddy, vec3_scale(a.ddy, 0.25), 1e-15, "ddy scaled");
}
END_TEST

START_TEST(test_hit_differential_on_a_plane_at_known_distance)
{
    /* looking straight down -z at the plane z = -D: at the image centre one pixel step moves
     * the hit by D tan(fovx / 2) / (W / 2) along u */
    const double D = 7.0;
    camera c;
    camera_init(&c, vec3_make(0, 0, 0), vec3_make(0, 0, -1), vec3_make(0, 1, 0), 60, 64, 64);
    ray_diff rd;
    ray r = camera_ray_differential(&c, 32, 32, 1.0, &rd);
    vec3 p = vec3_scale(r.d, D);
    vec3 dpdx, dpdy;
    ck_assert(raydiff_at_hit(&r, &rd, p, vec3_make(0, 0, 1), &dpdx, &dpdy));
    double k = tan(30 * M_PI / 180) / 32;
    assert_vec_near(dpdx, vec3_make(D * k, 0, 0), 1e-12, "dp/dx");
    assert_vec_near(dpdy, vec3_make(0, -D * k, 0), 1e-12, "dp/dy (rows go down)");
}
END_TEST

START_TEST(test_hit_differential_is_none_for_a_grazing_offset_ray_and_without_differentials)
{
    ray r = {vec3_make(0, 0, 1), vec3_make(1, 0, 0), 0, INFINITY};
    ray_diff rd = {1, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    vec3 dx, dy;
    /* the ray and its offsets run inside the plane's direction: n . d = 0 */
    ck_assert(!raydiff_at_hit(&r, &rd, vec3_make(1, 0, 0), vec3_make(0, 0, 1), &dx, &dy));
    ck_assert(vec3_length(dx) == 0 && vec3_length(dy) == 0);
    rd.has = 0;
    ck_assert(!raydiff_at_hit(&r, &rd, vec3_make(1, 0, 0), vec3_make(0, 0, 1), &dx, &dy));
    ck_assert(!raydiff_at_hit(&r, NULL, vec3_make(1, 0, 0), vec3_make(0, 0, 1), &dx, &dy));
}
END_TEST

/* The unit sphere at the origin seen by test_camera: hit point of the ray through (x, y). */
static int sphere_hit_at(const camera *c, double x, double y, vec3 *p, vec3 *d)
{
    ray r = camera_ray(c, x, y);
    double b = vec3_dot(r.o, r.d), cc = vec3_dot(r.o, r.o) - 1, disc = b * b - cc;
    if (disc < 0) return 0;
    *p = vec3_madd(r.o, r.d, -b - sqrt(disc));
    *d = r.d;
    return 1;
}

START_TEST(test_reflection_differentials_match_finite_differences_on_a_mirror_sphere)
{
    camera c = test_camera();
    const double px[3][2] = {{40, 30}, {44, 26}, {35.5, 33}};
    for (int i = 0; i < 3; i++) {
        double x = px[i][0], y = px[i][1];
        ray_diff rd;
        ray r = camera_ray_differential(&c, x, y, DIFF_SCALE, &rd);
        vec3 p, d;
        ck_assert(sphere_hit_at(&c, x, y, &p, &d));
        vec3 dpdx, dpdy;
        ck_assert(raydiff_at_hit(&r, &rd, p, p, &dpdx, &dpdy));
        /* n = p on the unit sphere, so dn = dp exactly */
        ray_diff out;
        raydiff_reflect(&rd, dpdx, dpdy, vec3_neg(d), p, dpdx, dpdy, &out);
        ck_assert(out.has);
        out.ddx = vec3_scale(out.ddx, 1 / DIFF_SCALE);
        out.ddy = vec3_scale(out.ddy, 1 / DIFF_SCALE);
        out.dox = vec3_scale(out.dox, 1 / DIFF_SCALE);
        /* finite differences of the reflected direction and of the hit point */
        vec3 pa, pb, da, db;
        ck_assert(sphere_hit_at(&c, x + FD_STEP, y, &pa, &da) &&
                  sphere_hit_at(&c, x - FD_STEP, y, &pb, &db));
        vec3 fd = vec3_scale(vec3_sub(vec3_reflect(da, pa), vec3_reflect(db, pb)), 0.5 / FD_STEP);
        vec3 fp = vec3_scale(vec3_sub(pa, pb), 0.5 / FD_STEP);
        assert_vec_near(out.ddx, fd, 1e-6, "reflected ddx");
        assert_vec_near(out.dox, fp, 1e-6, "reflected dox");
        ck_assert(sphere_hit_at(&c, x, y + FD_STEP, &pa, &da) &&
                  sphere_hit_at(&c, x, y - FD_STEP, &pb, &db));
        fd = vec3_scale(vec3_sub(vec3_reflect(da, pa), vec3_reflect(db, pb)), 0.5 / FD_STEP);
        assert_vec_near(out.ddy, fd, 1e-6, "reflected ddy");
    }
}
END_TEST

START_TEST(test_refraction_differentials_match_finite_differences_at_a_curved_surface)
{
    /* into the unit sphere (glass, n_t / n_i = 1.5), and - pretending the camera's ray were
     * inside the ball, normal turned inward - out of it (1 / 1.5): both branches of eta */
    camera c = test_camera();
    const double etas[2] = {1.5, 1 / 1.5};
    for (int e = 0; e < 2; e++) {
        double x = 41, y = 28, eta_ti = etas[e];
        ray_diff rd;
        ray r = camera_ray_differential(&c, x, y, DIFF_SCALE, &rd);
        vec3 p, d;
        ck_assert(sphere_hit_at(&c, x, y, &p, &d));
        vec3 dpdx, dpdy, wi;
        ck_assert(raydiff_at_hit(&r, &rd, p, p, &dpdx, &dpdy));
        ray_diff out;
        /* the normal on wo's side: outward entering, inward leaving (a ray inside the ball) */
        vec3 n = eta_ti > 1 ? p : vec3_neg(p);
        ck_assert(fresnel_refract(d, n, eta_ti, &wi));
        ck_assert(raydiff_refract(&rd, dpdx, dpdy, vec3_neg(d), n,
                                  vec3_scale(dpdx, eta_ti > 1 ? 1 : -1),
                                  vec3_scale(dpdy, eta_ti > 1 ? 1 : -1), 1 / eta_ti, wi, &out));
        out.ddx = vec3_scale(out.ddx, 1 / DIFF_SCALE);
        out.ddy = vec3_scale(out.ddy, 1 / DIFF_SCALE);
        vec3 pa, pb, da, db, ta, tb;
        ck_assert(sphere_hit_at(&c, x + FD_STEP, y, &pa, &da) &&
                  sphere_hit_at(&c, x - FD_STEP, y, &pb, &db));
        ck_assert(fresnel_refract(da, eta_ti > 1 ? pa : vec3_neg(pa), eta_ti, &ta) &&
                  fresnel_refract(db, eta_ti > 1 ? pb : vec3_neg(pb), eta_ti, &tb));
        assert_vec_near(out.ddx, vec3_scale(vec3_sub(ta, tb), 0.5 / FD_STEP), 1e-6,
                        "refracted ddx");
        ck_assert(sphere_hit_at(&c, x, y + FD_STEP, &pa, &da) &&
                  sphere_hit_at(&c, x, y - FD_STEP, &pb, &db));
        ck_assert(fresnel_refract(da, eta_ti > 1 ? pa : vec3_neg(pa), eta_ti, &ta) &&
                  fresnel_refract(db, eta_ti > 1 ? pb : vec3_neg(pb), eta_ti, &tb));
        assert_vec_near(out.ddy, vec3_scale(vec3_sub(ta, tb), 0.5 / FD_STEP), 1e-6,
                        "refracted ddy");
    }
}
END_TEST

START_TEST(test_no_differentials_in_means_none_out)
{
    ray_diff none = {0}, out;
    vec3 z = vec3_make(0, 0, 0), n = vec3_make(0, 0, 1);
    raydiff_reflect(&none, z, z, n, n, z, z, &out);
    ck_assert(!out.has);
    ck_assert(!raydiff_refract(&none, z, z, n, n, z, z, 1 / 1.5, vec3_neg(n), &out));
    ck_assert(!out.has);
    /* grazing transmission: cos_t = 0 would divide by zero in dmu */
    ray_diff some = {1, z, vec3_make(1e-3, 0, 0), z, z};
    ck_assert(!raydiff_refract(&some, z, z, n, n, z, z, 1.5, vec3_make(1, 0, 0), &out));
    ck_assert(!out.has);
}
END_TEST

/* Offset rays are (o + do, unit(d) + dd) (ray.h: the differentials are of the UNIT direction,
 * and a ray's d need not be unit), and the tangent plane's normal may have any length
 * (raydiff.h): the footprint must not change when either is scaled.  The plane z = -7 seen at
 * an angle, with offset origins too (as after a mirror), so that every term of
 * t_x = n . (p - (o + dox)) / n . (d + ddx) counts.  Catches d taken as given (a ray of length
 * 3 moved by a third of a pixel's step) and the grazing test made absolute in |ng|. */
START_TEST(test_hit_differential_ignores_the_lengths_of_d_and_ng)
{
    vec3 d = vec3_normalize(vec3_make(0.3, -0.2, -1));
    ray r = {vec3_make(0.5, 1, 0), d, 0, INFINITY};
    ray_diff rd = {1, vec3_make(0.01, 0.002, 0), vec3_make(0.004, 0.001, 0.0005),
                   vec3_make(-0.001, 0.02, 0.003), vec3_make(0.0005, -0.006, 0.001)};
    vec3 p = vec3_madd(r.o, d, 7 / -d.z), ng = vec3_make(0, 0, 1);
    vec3 dx, dy;
    ck_assert(raydiff_at_hit(&r, &rd, p, ng, &dx, &dy));
    /* the offset ray's own hit on z = -7, minus p */
    vec3 ox = vec3_add(r.o, rd.dox), wx = vec3_add(d, rd.ddx);
    vec3 oy = vec3_add(r.o, rd.doy), wy = vec3_add(d, rd.ddy);
    assert_vec_near(dx, vec3_sub(vec3_madd(ox, wx, (-7 - ox.z) / wx.z), p), 1e-12, "dp/dx");
    assert_vec_near(dy, vec3_sub(vec3_madd(oy, wy, (-7 - oy.z) / wy.z), p), 1e-12, "dp/dy");
    const double scales[4] = {3, 0.01, 1e-20, 1e20};
    for (int i = 0; i < 4; i++) {
        ray rs = r;
        rs.d = vec3_scale(d, scales[i]);
        vec3 ex, ey;
        ck_assert(raydiff_at_hit(&rs, &rd, p, ng, &ex, &ey));
        assert_vec_near(ex, dx, 1e-12, "dp/dx with a scaled d");
        assert_vec_near(ey, dy, 1e-12, "dp/dy with a scaled d");
        ck_assert(raydiff_at_hit(&r, &rd, p, vec3_scale(ng, scales[i]), &ex, &ey));
        assert_vec_near(ex, dx, 1e-12, "dp/dx with a scaled ng");
        assert_vec_near(ey, dy, 1e-12, "dp/dy with a scaled ng");
    }
}
END_TEST

/* The grazing limit is relative, |n . (d + dd)| <= RAYDIFF_MIN_COS |n| |d + dd| (raydiff.h):
 * an offset ray at a cosine of 1e-14 gives no differential though 1e-14 is no zero division;
 * and when one axis grazes and the other does not, BOTH outputs are zero.  rd.has = 0 gives
 * none even for a ray that would hit the plane squarely.  Catches the test written as
 * n . d' != 0, the x result left behind when y fails, and has ignored. */
START_TEST(test_hit_differential_is_none_when_either_offset_ray_nearly_grazes_or_has_is_zero)
{
    ray r = {vec3_make(0, 0, 1), vec3_make(0, 0, -1), 0, INFINITY};
    vec3 p = vec3_make(0, 0, 0), ng = vec3_make(0, 0, 1), dx, dy;
    /* d + ddy = (1, 0, -1e-14): nearly in the plane */
    ray_diff rd = {1, vec3_make(0, 0, 0), vec3_make(0.01, 0, 0), vec3_make(0, 0, 0),
                   vec3_make(1, 0, 1 - 1e-14)};
    ck_assert(!raydiff_at_hit(&r, &rd, p, ng, &dx, &dy));
    ck_assert(vec3_length(dx) == 0 && vec3_length(dy) == 0);
    rd.ddy = vec3_make(0, 0.01, 0); /* both fine: a differential */
    ck_assert(raydiff_at_hit(&r, &rd, p, ng, &dx, &dy));
    ck_assert(vec3_length(dx) > 0 && vec3_length(dy) > 0);
    rd.has = 0;
    ck_assert(!raydiff_at_hit(&r, &rd, p, ng, &dx, &dy));
    ck_assert(vec3_length(dx) == 0 && vec3_length(dy) == 0);
}
END_TEST

/* Grazing transmission is cos_t <= RAYDIFF_MIN_COS (raydiff.h), not only cos_t = 0: at
 * cos_t = 1e-13 dmu's eta^2 cos_i / cos_t is 1e13 times too big to be a footprint.  Catches the
 * guard written as cos_t > 0. */
START_TEST(test_refraction_differentials_stop_just_above_grazing_too)
{
    vec3 z = vec3_make(0, 0, 0), n = vec3_make(0, 0, 1);
    ray_diff some = {1, z, vec3_make(1e-3, 0, 0), z, vec3_make(0, 1e-3, 0)}, out;
    vec3 wi = vec3_normalize(vec3_make(1, 0, -1e-13));
    ck_assert(fabs(vec3_dot(wi, n)) < RAYDIFF_MIN_COS);
    ck_assert(!raydiff_refract(&some, z, z, n, n, z, z, 1.5, wi, &out));
    ck_assert(!out.has);
    wi = vec3_normalize(vec3_make(1, 0, -1e-6)); /* still shallow, but a differential */
    ck_assert(raydiff_refract(&some, z, z, n, n, z, z, 1.5, wi, &out));
    ck_assert(out.has);
}
END_TEST

/* A reflected or refracted ray starts at the hit, so its origin moves with the hit point:
 * do = dp (raydiff.h), each axis its own.  Catches dox and doy swapped in either function. */
START_TEST(test_reflected_and_refracted_origins_move_with_the_hit_point)
{
    vec3 n = vec3_make(0, 0, 1), wo = vec3_normalize(vec3_make(0.3, 0.1, 1));
    vec3 dpdx = vec3_make(0.01, 0.002, 0), dpdy = vec3_make(-0.003, 0.02, 0);
    vec3 dn = vec3_make(0.001, 0, 0), wi;
    ray_diff in = {1, vec3_make(0, 0, 0), vec3_make(0.002, 0, 0.001), vec3_make(0, 0, 0),
                   vec3_make(0, 0.002, 0.0005)},
             out;
    raydiff_reflect(&in, dpdx, dpdy, wo, n, dn, dn, &out);
    ck_assert(out.has);
    ck_assert(vec3_length(vec3_sub(out.dox, dpdx)) == 0 &&
              vec3_length(vec3_sub(out.doy, dpdy)) == 0);
    ck_assert(fresnel_refract(vec3_neg(wo), n, 1.5, &wi));
    ck_assert(raydiff_refract(&in, dpdx, dpdy, wo, n, dn, dn, 1 / 1.5, wi, &out));
    ck_assert(vec3_length(vec3_sub(out.dox, dpdx)) == 0 &&
              vec3_length(vec3_sub(out.doy, dpdy)) == 0);
}
END_TEST

/* ---- footprints at scene hits (texshade.h) ---------------------------------------------- */

/* A 1 x 1 quad facing the camera at distance D, (s, t) = (x, y) + 0.5: one world unit is one
 * texture unit.  A 64-texel texture, trilinear. */
static const char *plane_scene = "size 64 64\n"
                                 "camera 0 0 0  0 0 -1  0 1 0  60\n"
                                 "texture chk checker 8  0 0 0  1 1 1\n"
                                 "diffusemap chk\n"
                                 "vertextex -0.5 -0.5 -7  0 0\n"
                                 "vertextex 0.5 -0.5 -7  1 0\n"
                                 "vertextex 0.5 0.5 -7  1 1\n"
                                 "vertextex -0.5 0.5 -7  0 1\n"
                                 "tritex 0 1 2\n"
                                 "tritex 0 2 3\n";

/* hit of the ray (r, rd) on triangle `prim` of sc (brute force: the scenes here are tiny) */
static int find_hit(const scene *sc, const ray *r, hit *h)
{
    for (long i = 0; i < sc->n_triangles; i++) {
        const triangle *tr = &sc->triangles[i];
        vec3 e1 = vec3_sub(tr->p[1], tr->p[0]), e2 = vec3_sub(tr->p[2], tr->p[0]);
        vec3 pv = vec3_cross(r->d, e2);
        double det = vec3_dot(e1, pv);
        if (fabs(det) < 1e-12) continue;
        vec3 tv = vec3_sub(r->o, tr->p[0]);
        double b1 = vec3_dot(tv, pv) / det;
        vec3 qv = vec3_cross(tv, e1);
        double b2 = vec3_dot(r->d, qv) / det, t = vec3_dot(e2, qv) / det;
        if (b1 < 0 || b2 < 0 || b1 + b2 > 1 || t <= 0) continue;
        memset(h, 0, sizeof *h);
        h->t = t;
        h->p = vec3_madd(r->o, r->d, t);
        h->ng = h->ns = vec3_normalize(vec3_cross(e1, e2));
        h->bary = (uv2){b1, b2};
        h->prim = i;
        h->material = tr->material;
        return 1;
    }
    return 0;
}

START_TEST(test_footprint_of_a_plane_at_known_distance_picks_the_mip_level)
{
    scene sc;
    error err = {0};
    ck_assert_msg(scene_load_string(plane_scene, NULL, NULL, &sc, &err) == 0, "%s", err.msg);
    camera c;
    camera_init(&c, sc.eye, sc.center, sc.up, sc.fovy, sc.width, sc.height);
    ray_diff rd;
    ray r = camera_ray_differential(&c, 32, 32, 1.0, &rd);
    hit h;
    ck_assert(find_hit(&sc, &r, &h));
    surface s = front_frame(&h);
    texshade_differentials(&sc, &h, &r, &rd, &s);
    ck_assert(s.has_diff);
    texshade_point tp;
    texshade_point_at(&sc, &h, &s, &tp);
    double w = 7 * tan(30 * M_PI / 180) / 32; /* texture units per pixel */
    ck_assert(fabs(tp.st.u - 0.5) < 1e-12 && fabs(tp.st.v - 0.5) < 1e-12);
    ck_assert_msg(fabs(tp.dst_dx.u - w) < 1e-12 && fabs(tp.dst_dx.v) < 1e-12, "ds/dx %g, want %g",
                  tp.dst_dx.u, w);
    ck_assert(fabs(tp.dst_dy.v + w) < 1e-12 && fabs(tp.dst_dy.u) < 1e-12);
    /* a 64 x 64 pyramid: level log2(64 w) */
    image img;
    ck_assert(image_alloc(&img, 64, 64, &err) == 0);
    for (int i = 0; i < 64 * 64 * 3; i++) img.px[i] = 0.5f;
    mipmap m;
    ck_assert(mipmap_build(&m, &img, WRAP_REPEAT, &err) == 0);
    double level = mipmap_level_for_footprint(&m, fmax(fabs(tp.dst_dx.u), fabs(tp.dst_dy.v)) * 64);
    ck_assert_msg(fabs(level - log2(64 * w)) < 1e-9, "level %g, want %g", level, log2(64 * w));
    mipmap_free(&m);
    image_free(&img);
    scene_free(&sc);
}
END_TEST

/* A mirror direction about a bumped shading normal can dip below the geometric surface (near
 * grazing); it is still a reflection, and carries raydiff_reflect's differentials, not a
 * refraction's (texshade_delta_diff once told them apart by the side of ng).  A refraction
 * crosses the shading normal and carries raydiff_refract's. */
START_TEST(test_delta_diff_tells_reflection_from_refraction_by_the_shading_normal)
{
    surface s;
    memset(&s, 0, sizeof s);
    s.has_diff = 1;
    s.entering = 1;
    s.ior = 1.5;
    s.ng = vec3_make(0, 0, 1);
    s.n = vec3_normalize(vec3_make(0.6, 0, 0.8)); /* bumped, on ng's side */
    s.dpdx = vec3_make(0.01, 0, 0);
    s.dpdy = vec3_make(0, 0.01, 0);
    s.dndx = vec3_make(0, 0.002, 0);
    s.dndy = vec3_make(0.001, 0, -0.00075);
    ray_diff rd = {1, vec3_make(0.01, 0, 0), vec3_make(0, 0.003, 0.001), vec3_make(0, 0.01, 0),
                   vec3_make(0.002, 0, 0)};
    vec3 wo = vec3_normalize(vec3_make(-0.5, 0, 1));                /* above ng, and above n */
    vec3 wi = vec3_sub(vec3_scale(s.n, 2 * vec3_dot(wo, s.n)), wo); /* mirror about n */
    ck_assert(vec3_dot(wo, s.n) > 0 && wi.z < 0);                   /* below the surface */
    ray_diff got, want;
    texshade_delta_diff(&s, &rd, wo, wi, &got);
    raydiff_reflect(&rd, s.dpdx, s.dpdy, wo, s.n, s.dndx, s.dndy, &want);
    ck_assert(got.has && want.has);
    ck_assert_msg(vec3_length(vec3_sub(got.ddx, want.ddx)) < 1e-15 &&
                      vec3_length(vec3_sub(got.ddy, want.ddy)) < 1e-15,
                  "a mirror direction below ng got other differentials than raydiff_reflect's");
    /* a refraction through the same bumped normal */
    vec3 wt;
    ck_assert(fresnel_refract(vec3_scale(wo, -1), s.n, 1.5, &wt));
    texshade_delta_diff(&s, &rd, wo, wt, &got);
    ck_assert(raydiff_refract(&rd, s.dpdx, s.dpdy, wo, s.n, s.dndx, s.dndy, 1 / 1.5, wt, &want));
    ck_assert(got.has);
    ck_assert(vec3_length(vec3_sub(got.ddx, want.ddx)) < 1e-15 &&
              vec3_length(vec3_sub(got.ddy, want.ddy)) < 1e-15);
}
END_TEST

/* Where an interpolated normal faces away from the viewer the integrators shade with s->n =
 * s->ng: a flat mirror, whose reflected differentials are the incoming ones mirrored,
 * dwi = dd - 2 (dd . ng) ng.  The vertex normals' change (dn) once went into them anyway and
 * bent the reflected footprint by a curvature the facet does not have (ds/dx several times
 * the neighbouring pixel's). */
START_TEST(test_a_mirror_falling_back_to_the_geometric_normal_reflects_the_footprint_flat)
{
    const char *text = "size 64 64\ncamera -4 0 5  0 0 0  0 1 0  45\n"
                       "texture chk checker 8  0 0 0  1 1 1\ndiffusemap chk\nbrdf mirror\n"
                       "vertexnormal -2 -2 0  1 0.3 0.3\nvertexnormal 2 -2 0  1 -0.3 0.25\n"
                       "vertexnormal 0 2 0  1 0.1 0.35\ntrinormal 0 1 2\n";
    scene sc;
    error err = {0};
    ck_assert_msg(scene_load_string(text, NULL, NULL, &sc, &err) == 0, "%s", err.msg);
    const triangle *tr = &sc.triangles[0];
    ck_assert(tr->has_normals);
    camera c;
    camera_init(&c, sc.eye, sc.center, sc.up, sc.fovy, sc.width, sc.height);
    ray_diff rd;
    ray r = camera_ray_differential(&c, 36, 36, 1.0, &rd);
    hit h;
    ck_assert(find_hit(&sc, &r, &h));
    double b1 = h.bary.u, b2 = h.bary.v; /* the interpolated normal, as the triangle's hit has */
    h.ns = vec3_normalize(
        vec3_add(vec3_add(vec3_scale(tr->n[0], 1 - b1 - b2), vec3_scale(tr->n[1], b1)),
                 vec3_scale(tr->n[2], b2)));
    vec3 view = vec3_neg(r.d);
    /* the integrators' frame: ns faces away from the viewer here, so n = ng */
    ck_assert(vec3_dot(view, h.ng) > 0 && vec3_dot(view, h.ns) < 0);
    surface s;
    memset(&s, 0, sizeof s);
    s.entering = 1;
    s.ng = s.n = h.ng;
    texshade_differentials(&sc, &h, &r, &rd, &s);
    ck_assert(s.has_diff);
    ray_diff out;
    texshade_delta_diff(&s, &rd, view, vec3_reflect(r.d, s.n), &out);
    ck_assert(out.has);
    vec3 n = s.ng; /* dwi = dd - 2 (dd . n) n */
    assert_vec_near(out.ddx, vec3_madd(rd.ddx, n, -2 * vec3_dot(rd.ddx, n)), 1e-12,
                    "ddx of a flat mirror");
    assert_vec_near(out.ddy, vec3_madd(rd.ddy, n, -2 * vec3_dot(rd.ddy, n)), 1e-12,
                    "ddy of a flat mirror");
    /* seen with its own interpolated normal the same hit does curve: dn is not zero */
    s.n = h.ns;
    texshade_differentials(&sc, &h, &r, &rd, &s);
    ck_assert(vec3_length(s.dndx) > 1e-4 && vec3_length(s.dndy) > 1e-4);
    scene_free(&sc);
}
END_TEST

START_TEST(test_barycentric_st_at_a_hit_interpolates_the_corners)
{
    scene sc;
    error err = {0};
    ck_assert(scene_load_string(plane_scene, NULL, NULL, &sc, &err) == 0);
    camera c;
    camera_init(&c, sc.eye, sc.center, sc.up, sc.fovy, sc.width, sc.height);
    for (int k = 0; k < 5; k++) {
        double x = 30 + 1.1 * k, y = 33.5 - 0.9 * k; /* the quad covers pixels 28 .. 36 */
        ray r = camera_ray(&c, x, y);
        hit h;
        ck_assert(find_hit(&sc, &r, &h));
        surface s;
        memset(&s, 0, sizeof s);
        texshade_point tp;
        texshade_point_at(&sc, &h, &s, &tp);
        /* (s, t) = (x, y) + 0.5 of the hit point on this quad */
        ck_assert(fabs(tp.st.u - (h.p.x + 0.5)) < 1e-12 && fabs(tp.st.v - (h.p.y + 0.5)) < 1e-12);
        ck_assert(tp.dst_dx.u == 0 && tp.dst_dy.v == 0); /* no differentials: no footprint */
    }
    scene_free(&sc);
}
END_TEST

START_TEST(test_diffusemap_replaces_kd_and_untextured_materials_are_untouched)
{
    const char *text = "size 8 8\ncamera 0 0 0  0 0 -1  0 1 0  60\n"
                       "texture c checker 4  0.2 0.4 0.6  0.2 0.4 0.6\n"
                       "diffuse 0.9 0.9 0.9\n"
                       "vertex -1 -1 -3\nvertex 1 -1 -3\nvertex 0 1 -3\ntri 0 1 2\n"
                       "diffusemap c\nspecularmap c\nemissionmap c\n"
                       "vertex -1 -1 -2\nvertex 1 -1 -2\nvertex 0 1 -2\ntri 3 4 5\n";
    scene sc;
    error err = {0};
    ck_assert_msg(scene_load_string(text, NULL, NULL, &sc, &err) == 0, "%s", err.msg);
    ck_assert(!texshade_material_has_maps(&sc.materials[sc.triangles[0].material]));
    ck_assert(texshade_material_has_maps(&sc.materials[sc.triangles[1].material]));
    ck_assert(texshade_scene_needs_differentials(&sc)); /* checker, trilinear by default */
    ray r = {vec3_make(0, 0, 0), vec3_make(0, 0, -1), 0, INFINITY};
    hit h;
    ck_assert(find_hit(&sc, &r, &h) && h.prim == 0); /* brute force returns the first: tri 0 */
    surface s = front_frame(&h);
    brdf_surface_from_material(&s, &sc.materials[h.material]);
    texshade_surface(&sc, &h, &r, NULL, &s);
    ck_assert(s.kd.r == 0.9 && rgb_is_black(s.emission));
    h.prim = 1;
    h.material = sc.triangles[1].material;
    brdf_surface_from_material(&s, &sc.materials[h.material]);
    texshade_surface(&sc, &h, &r, NULL, &s);
    ck_assert(fabs(s.kd.r - 0.2) < 1e-12 && fabs(s.kd.g - 0.4) < 1e-12 &&
              fabs(s.kd.b - 0.6) < 1e-12);
    ck_assert(fabs(s.ks.b - 0.6) < 1e-12 && fabs(s.emission.g - 0.4) < 1e-12);
    scene_free(&sc);
}
END_TEST

/* Camera rays carry differentials only when a map uses a footprint: trilinear or EWA filtering,
 * or a bump map (its step); nearest and bilinear maps read one point, so a scene of those alone
 * traces none, and its maps read the same with or without them (the image bit for bit). */
START_TEST(test_differentials_only_for_maps_that_use_a_footprint)
{
    const char *head =
        "size 8 8\ncamera 0 0 0  0 0 -1  0 1 0  60\n"
        "texture c checker 4  0.1 0.2 0.3  0.7 0.8 0.9\ntexture n fbm 3 4  0 0 0  1 1 1\n";
    const char *mats[] = {
        "texfilter nearest\ndiffusemap c\nroughnessmap n\nspecularmap n\nemissionmap c\n",
        "texfilter bilinear\ndiffusemap n\nspecularmap c\n",
        "texfilter nearest\nbumpmap c 1\n",
        "texfilter ewa\ndiffusemap c\n",
        "texfilter trilinear\nemissionmap n\n",
        "texfilter ewa\n"};
    const int needs[] = {0, 0, 1, 1, 1, 0};
    for (int k = 0; k < 6; k++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "%s%svertex -4 -4 -3\nvertex 4 -4 -3\nvertex 0 4 -3\ntri 0 1 2\n", head, mats[k]);
        scene sc;
        error err = {0};
        ck_assert_msg(scene_load_string(text, NULL, NULL, &sc, &err) == 0, "%s", err.msg);
        const material *m = &sc.materials[sc.triangles[0].material];
        ck_assert_msg(texshade_material_needs_footprint(m) == needs[k], "material %d", k);
        ck_assert_msg(texshade_scene_needs_differentials(&sc) == needs[k], "scene %d", k);
        if (!needs[k] && texshade_material_has_maps(m)) {
            /* the footprint is not read: the same colours with differentials and without */
            camera c;
            camera_init(&c, sc.eye, sc.center, sc.up, sc.fovy, 8, 8);
            for (int y = 0; y < 8; y++)
                for (int x = 0; x < 8; x++) {
                    ray_diff rd;
                    ray r = camera_ray_differential(&c, x + 0.3, y + 0.6, 1.0, &rd);
                    hit h;
                    if (!find_hit(&sc, &r, &h)) continue;
                    surface a = front_frame(&h), b = front_frame(&h);
                    brdf_surface_from_material(&a, m);
                    brdf_surface_from_material(&b, m);
                    texshade_surface(&sc, &h, &r, &rd, &a);
                    texshade_surface(&sc, &h, &r, NULL, &b);
                    ck_assert(a.has_diff && !b.has_diff);
                    ck_assert(a.kd.r == b.kd.r && a.kd.g == b.kd.g && a.kd.b == b.kd.b);
                    ck_assert(a.ks.r == b.ks.r && a.emission.g == b.emission.g &&
                              a.roughness == b.roughness);
                }
        }
        scene_free(&sc);
    }
}
END_TEST

/* An HDR image map may hold negative texels (a height map may mean them); as a diffuse,
 * specular or emission colour they read as 0, like the parser's colours, which must be >= 0
 * (a negative kd once shaded a negative radiance) */
START_TEST(test_colour_maps_from_negative_texels_read_as_zero)
{
    char dir[] = "/tmp/test_raydiff_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[256], text[1024];
    snprintf(path, sizeof path, "%s/neg.pfm", dir);
    image img;
    error err = {0};
    ck_assert_int_eq(image_alloc(&img, 2, 2, &err), 0);
    for (int i = 0; i < 2 * 2 * 3; i++) img.px[i] = i % 3 == 1 ? 0.5f : -2.0f; /* (-2, 0.5, -2) */
    ck_assert_int_eq(pfm_write(path, &img, &err), 0);
    image_free(&img);
    snprintf(text, sizeof text,
             "size 8 8\ncamera 0 0 0  0 0 -1  0 1 0  60\ntexture c %s\ntexfilter nearest\n"
             "diffusemap c\nspecularmap c\nemissionmap c\n"
             "vertex -1 -1 -3\nvertex 1 -1 -3\nvertex 0 1 -3\ntri 0 1 2\n",
             path);
    scene sc;
    ck_assert_msg(scene_load_string(text, NULL, NULL, &sc, &err) == 0, "%s", err.msg);
    ray r = {vec3_make(0, 0, 0), vec3_make(0, 0, -1), 0, INFINITY};
    hit h;
    ck_assert(find_hit(&sc, &r, &h));
    surface s = front_frame(&h);
    brdf_surface_from_material(&s, &sc.materials[h.material]);
    texshade_surface(&sc, &h, &r, NULL, &s);
    ck_assert_msg(s.kd.r == 0 && s.kd.b == 0 && fabs(s.kd.g - 0.5) < 1e-6, "kd (%g %g %g)", s.kd.r,
                  s.kd.g, s.kd.b);
    ck_assert(s.ks.r == 0 && s.ks.b == 0 && s.emission.r == 0 && s.emission.b == 0);
    ck_assert(fabs(s.emission.g - 0.5) < 1e-6);
    scene_free(&sc);
    remove(path);
    rmdir(dir);
}
END_TEST

Suite *raydiff_suite(void)
{
    Suite *s = suite_create("raydiff");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_camera_differentials_are_the_derivatives_of_camera_ray);
    tcase_add_test(tc, test_camera_differentials_shrink_with_the_scale);
    tcase_add_test(tc, test_hit_differential_on_a_plane_at_known_distance);
    tcase_add_test(
        tc, test_hit_differential_is_none_for_a_grazing_offset_ray_and_without_differentials);
    tcase_add_test(tc, test_reflection_differentials_match_finite_differences_on_a_mirror_sphere);
    tcase_add_test(tc, test_refraction_differentials_match_finite_differences_at_a_curved_surface);
    tcase_add_test(tc, test_no_differentials_in_means_none_out);
    tcase_add_test(tc, test_hit_differential_ignores_the_lengths_of_d_and_ng);
    tcase_add_test(
        tc, test_hit_differential_is_none_when_either_offset_ray_nearly_grazes_or_has_is_zero);
    tcase_add_test(tc, test_refraction_differentials_stop_just_above_grazing_too);
    tcase_add_test(tc, test_reflected_and_refracted_origins_move_with_the_hit_point);
    tcase_add_test(tc, test_footprint_of_a_plane_at_known_distance_picks_the_mip_level);
    tcase_add_test(tc, test_barycentric_st_at_a_hit_interpolates_the_corners);
    tcase_add_test(tc, test_delta_diff_tells_reflection_from_refraction_by_the_shading_normal);
    tcase_add_test(tc,
                   test_a_mirror_falling_back_to_the_geometric_normal_reflects_the_footprint_flat);
    tcase_add_test(tc, test_diffusemap_replaces_kd_and_untextured_materials_are_untouched);
    tcase_add_test(tc, test_differentials_only_for_maps_that_use_a_footprint);
    tcase_add_test(tc, test_colour_maps_from_negative_texels_read_as_zero);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(raydiff_suite)
