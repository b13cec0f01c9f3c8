/* test_texshade.c - texture maps at a ray hit (include/envtex/integrators/texshade.h), checked
 * against finite differences: a camera ray with differentials scaled to 1e-3 of a pixel and its
 * neighbour ray (o + do/dx, d + dd/dx) hit the surface a first-order step apart, so every
 * derivative texshade computes (dp, dn, dst, dq, and the tangents dp/ds, dp/dt) must match the
 * difference of what the two hits give, to about that step's square.  Each scene has a transform,
 * so the object space that mappings and solid textures see differs from the world. */
#include "envtex/integrators/texshade.h"

#include <string.h>

#include "envtex/geometry/camera.h"
#include "envtex/reflection/fresnel.h"
#include "envtex/integrators/integrator.h"
#include "envtex/geometry/raydiff.h"
#include "envtex/scene/scene_load.h"
#include "unit.h"

#define STEP   1e-3 /* the differential's scale: a thousandth of a pixel */
#define FD_REL 2e-3 /* first-order agreement, relative to the derivative's length */

typedef struct rig {
    scene sc;
    bvh b;
    integrator it;
    camera cam;
} rig;

static void rig_load(rig *r, const char *text)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    error err = {0};
    if (scene_load_string(text, "texshade.test", &o, &r->sc, &err))
        ck_abort_msg("scene: line %d: %s", err.line, err.msg);
    if (bvh_build(&r->b, scene_prims(&r->sc), NULL, &err)) ck_abort_msg("bvh: %s", err.msg);
    if (integrator_init(&r->it, &r->sc, &r->b, NULL, &err)) ck_abort_msg("integrator: %s", err.msg);
    camera_init(&r->cam, r->sc.eye, r->sc.center, r->sc.up, r->sc.fovy, r->sc.width, r->sc.height);
}

static void rig_free(rig *r)
{
    integrator_free(&r->it);
    bvh_free(&r->b);
    scene_free(&r->sc);
}

/* The hit of pixel (x, y)'s ray with differentials (*h0), and of its x and y neighbours. */
typedef struct hits {
    scene_hit h0, hx, hy;
    ray r;
    ray_diff rd;
} hits;

static void trace3(rig *r, double x, double y, hits *out)
{
    out->r = camera_ray_differential(&r->cam, x, y, STEP, &out->rd);
    integrator_intersect_diff(&r->it, &out->r, &out->rd, &out->h0);
    ray rx = {vec3_add(out->r.o, out->rd.dox), vec3_add(out->r.d, out->rd.ddx), 0, INFINITY};
    ray ry = {vec3_add(out->r.o, out->rd.doy), vec3_add(out->r.d, out->rd.ddy), 0, INFINITY};
    integrator_intersect_diff(&r->it, &rx, NULL, &out->hx);
    integrator_intersect_diff(&r->it, &ry, NULL, &out->hy);
    ck_assert_int_eq(out->h0.kind, SCENE_HIT_GEOMETRY);
    ck_assert_int_eq(out->hx.kind, SCENE_HIT_GEOMETRY);
    ck_assert_int_eq(out->hy.kind, SCENE_HIT_GEOMETRY);
    ck_assert(out->h0.s.has_diff);
}

/* got within FD_REL times `scale` of the finite difference `want`, at the caller's line */
static void vec_near_at(const char *file, int line, vec3 got, vec3 want, double scale,
                        const char *what)
{
    double e = vec3_length(vec3_sub(got, want));
    if (!(e <= FD_REL * scale))
        unit_fail_at(file, line,
                     "%s: got (%.9g, %.9g, %.9g), want the finite difference (%.9g, %.9g, %.9g), "
                     "tolerance %.3g (off by %.3g)",
                     what, got.x, got.y, got.z, want.x, want.y, want.z, FD_REL * scale, e);
}

static void uv_near_at(const char *file, int line, uv2 got, uv2 want, double scale,
                       const char *what)
{
    double e = hypot(got.u - want.u, got.v - want.v);
    if (!(e <= FD_REL * scale))
        unit_fail_at(file, line,
                     "%s: got (%.9g, %.9g), want the finite difference (%.9g, %.9g), tolerance "
                     "%.3g (off by %.3g)",
                     what, got.u, got.v, want.u, want.v, FD_REL * scale, e);
}

static uv2 uv_sub(uv2 a, uv2 b) { return (uv2){a.u - b.u, a.v - b.v}; }

/* texshade_point_at's st, q and footprints, and texshade_differentials' dp and dn, against the
 * neighbours' hits; then the tangents invert the footprint: dp/dx = dp/ds ds/dx + dp/dt dt/dx. */
#define check_point(r, x, y, what) check_point_at(__FILE__, __LINE__, r, x, y, what)
static void check_point_at(const char *file, int line, rig *r, double x, double y,
                           const char *what)
{
    hits H;
    trace3(r, x, y, &H);
    const surface *s0 = &H.h0.s, *sx = &H.hx.s, *sy = &H.hy.s;
    char msg[160];
    /* dp and dn (texshade_differentials) */
    double plen = vec3_length(s0->dpdx);
    snprintf(msg, sizeof msg, "%s: dp/dx", what);
    vec_near_at(file, line, s0->dpdx, vec3_sub(sx->p, s0->p), plen, msg);
    snprintf(msg, sizeof msg, "%s: dn/dx", what);
    vec3 fdn = vec3_sub(sx->n, s0->n);
    vec_near_at(file, line, s0->dndx, fdn, fmax(vec3_length(fdn), 1e-3 * plen), msg);
    snprintf(msg, sizeof msg, "%s: dn/dy", what);
    fdn = vec3_sub(sy->n, s0->n);
    vec_near_at(file, line, s0->dndy, fdn, fmax(vec3_length(fdn), 1e-3 * plen), msg);
    /* st, q and their footprints (texshade_point_at) */
    texshade_point t0, tx, ty;
    texshade_point_at(&r->sc, &H.h0.h, s0, &t0);
    texshade_point_at(&r->sc, &H.hx.h, sx, &tx);
    texshade_point_at(&r->sc, &H.hy.h, sy, &ty);
    uv2 fst = uv_sub(tx.st, t0.st);
    if (!(fabs(fst.u) < 0.25 && fabs(fst.v) < 0.25))
        unit_fail_at(file, line, "%s: a seam between the neighbours", what);
    snprintf(msg, sizeof msg, "%s: dst/dx", what);
    uv_near_at(file, line, t0.dst_dx, fst, hypot(fst.u, fst.v), msg);
    snprintf(msg, sizeof msg, "%s: dst/dy", what);
    fst = uv_sub(ty.st, t0.st);
    uv_near_at(file, line, t0.dst_dy, fst, hypot(fst.u, fst.v), msg);
    snprintf(msg, sizeof msg, "%s: dq/dx", what);
    vec3 fq = vec3_sub(tx.q, t0.q);
    vec_near_at(file, line, t0.dq_dx, fq, vec3_length(fq), msg);
    /* the tangents: a step (ds, dt) in texture space is dp_ds ds + dp_dt dt in the world */
    texshade_tangents(&r->sc, &H.h0.h, &t0);
    vec3 back = vec3_add(vec3_scale(t0.dp_ds, t0.dst_dx.u), vec3_scale(t0.dp_dt, t0.dst_dx.v));
    snprintf(msg, sizeof msg, "%s: dp/ds ds/dx + dp/dt dt/dx", what);
    vec_near_at(file, line, back, s0->dpdx, plen, msg);
    vec3 backq = vec3_add(vec3_scale(t0.dq_ds, t0.dst_dx.u), vec3_scale(t0.dq_dt, t0.dst_dx.v));
    snprintf(msg, sizeof msg, "%s: dq/ds ds/dx + dq/dt dt/dx", what);
    vec_near_at(file, line, backq, t0.dq_dx, vec3_length(t0.dq_dx), msg);
}

#define CAMERA "size 64 64\ncamera 0.2 0.4 6  0 0 0  0 1 0  40\n"

/* A sphere moved and scaled (radius 0.5 x 2 = 1): spherical mapping by default (uv means
 * spherical on a sphere), on the unit direction from the centre in object space. */
START_TEST(test_texshade_sphere_under_a_transform_matches_finite_differences)
{
    rig r;
    rig_load(&r, CAMERA "pushTransform\ntranslate 0.3 0.2 0\nrotate 1 0 0 30\nscale 2 2 2\nsphere "
                        "0 0 0 0.5\npopTransform\n");
    const double px[][2] = {{40, 25}, {28, 38}, {35, 30}};
    for (int i = 0; i < 3; i++) {
        check_point(&r, px[i][0], px[i][1], "sphere");
        hits H;
        trace3(&r, px[i][0], px[i][1], &H);
        texshade_point tp;
        texshade_point_at(&r.sc, &H.h0.h, &H.h0.s, &tp);
        ck_assert_int_eq(tp.mapping, TEXMAPPING_SPHERICAL);
        /* q = M^-1 p: the object-space point, at distance 0.5 from the object's centre */
        ck_assert_near(vec3_length(tp.q), 0.5, 1e-9);
        ck_assert_msg(fabs(vec3_length(H.h0.s.p) - 1) > 1e-3,
                      "the world point should not be the object point");
    }
    rig_free(&r);
}
END_TEST

/* An ellipsoid (scale 2 1 1): its normal field is the inverse transpose's, (x/4, y, z) up to
 * length, and dn/dx follows it; seen from inside (the camera in the ellipsoid) s->n is -ns and
 * dn/dx is turned with it. */
START_TEST(test_texshade_normal_derivatives_of_an_ellipsoid_outside_and_inside)
{
    rig r;
    rig_load(&r, CAMERA "pushTransform\nscale 2 1 1\nsphere 0 0 0 1\npopTransform\n");
    check_point(&r, 38, 27, "ellipsoid");
    rig_free(&r);
    rig_load(&r, "size 64 64\ncamera 0.1 0.1 0.2  0.6 0.3 1  0 1 0  60\npushTransform\nscale 2 1 "
                 "1\nsphere 0 0 0 1\npopTransform\n");
    hits H;
    trace3(&r, 36, 29, &H);
    ck_assert_int_eq(H.h0.s.entering, 0);
    check_point(&r, 36, 29, "inside the ellipsoid");
    rig_free(&r);
}
END_TEST

/* A triangle with vertex normals under a transform, with the planar mapping of its object-space
 * point: q = b0 q0 + b1 q1 + b2 q2 = M^-1 p, and dn, dst, dq follow the neighbours. */
START_TEST(test_texshade_mapped_triangle_with_vertex_normals_matches_finite_differences)
{
    rig r;
    rig_load(
        &r, CAMERA
        "texmapping planar\npushTransform\ntranslate 0.2 -0.1 0\nrotate 0 1 0 20\nscale 1.5 1 1\n"
        "vertexnormal -1 -1 0  -0.3 -0.2 1\nvertexnormal 1 -1 0  0.4 -0.1 1\nvertexnormal 0 1 0  0 "
        "0.5 1\n"
        "trinormal 0 1 2\npopTransform\n");
    check_point(&r, 33, 35, "planar triangle");
    hits H;
    trace3(&r, 33, 35, &H);
    texshade_point tp;
    texshade_point_at(&r.sc, &H.h0.h, &H.h0.s, &tp);
    /* p = T R S q: undo each */
    vec3 p = vec3_sub(H.h0.s.p, vec3_make(0.2, -0.1, 0));
    double a = -20 * M_PI / 180;
    vec3 q = vec3_make(cos(a) * p.x + sin(a) * p.z, p.y, -sin(a) * p.x + cos(a) * p.z);
    q.x /= 1.5;
    ck_assert_msg(vec3_length(vec3_sub(tp.q, q)) < 1e-9, "q = (%g, %g, %g), want (%g, %g, %g)",
                  tp.q.x, tp.q.y, tp.q.z, q.x, q.y, q.z);
    ck_assert_near(tp.st.u, q.x, 1e-9); /* planar: (s, t) = (x, y) */
    ck_assert_near(tp.st.v, q.y, 1e-9);
    rig_free(&r);
}
END_TEST

/* The same with per-vertex (s, t) (`tritex`): st = sum b_i st_i, and its footprint. */
START_TEST(test_texshade_uv_triangle_matches_finite_differences)
{
    rig r;
    rig_load(
        &r, CAMERA
        "pushTransform\nrotate 1 0 0 -25\nvertextex -1 -1 0  0.1 0.2\nvertextex 1 -1 0  0.9 0.1\n"
        "vertextex 0 1 0  0.4 0.95\ntritex 0 1 2\npopTransform\n");
    check_point(&r, 30, 36, "uv triangle");
    rig_free(&r);
}
END_TEST

/* A solid texture's bump map (Perlin) has derivatives along both object-space tangents dq/ds and
 * dq/dt: the bumped normal leans along both (east and north on the sphere), not only one. */
START_TEST(test_texshade_procedural_bump_tilts_the_normal_both_ways)
{
    rig r;
    rig_load(&r, CAMERA "texture b perlin 4  0 0 0  1 1 1\nbumpmap b 0.2\nsphere 0 0 0 1\n");
    double east = 0, north = 0;
    for (int y = 26; y < 40; y += 3)
        for (int x = 26; x < 40; x += 3) {
            hits H;
            trace3(&r, x, y, &H);
            texshade_point tp;
            texshade_point_at(&r.sc, &H.h0.h, &H.h0.s, &tp);
            texshade_tangents(&r.sc, &H.h0.h, &tp);
            vec3 dn = vec3_sub(H.h0.s.n, H.h0.h.ns);
            east = fmax(east, fabs(vec3_dot(dn, vec3_normalize(tp.dp_ds))));
            north = fmax(north, fabs(vec3_dot(dn, vec3_normalize(tp.dp_dt))));
        }
    ck_assert_msg(east > 1e-3 && north > 1e-3,
                  "the bumps tilt the normal east by at most %g, north by %g", east, north);
    rig_free(&r);
}
END_TEST

/* `texmapping uv` on a sphere means spherical (a sphere has no vertices to carry (s, t)). */
START_TEST(test_texshade_uv_on_a_sphere_is_spherical)
{
    rig r;
    rig_load(&r, CAMERA "texmapping uv\nsphere 0 0 0 1\n");
    hits H;
    trace3(&r, 35, 30, &H);
    texshade_point tp;
    texshade_point_at(&r.sc, &H.h0.h, &H.h0.s, &tp);
    ck_assert_int_eq(tp.mapping, TEXMAPPING_SPHERICAL);
    uv2 want = texmapping_point(TEXMAPPING_SPHERICAL, tp.q);
    ck_assert(tp.st.u == want.u && tp.st.v == want.v);
    rig_free(&r);
}
END_TEST

/* A ray refracted out of glass carries differentials made with eta = n_i / n_t = ior / 1 (the
 * surface is left: s->entering = 0), as raydiff_refract computes them directly. */
START_TEST(test_texshade_refraction_out_of_glass_uses_the_inverse_index)
{
    rig r;
    rig_load(&r, "size 64 64\ncamera 0.1 0.1 0  0.3 0.2 1  0 1 0  40\nbrdf glass\nior 1.5\nsphere "
                 "0 0 0 1\n");
    hits H;
    trace3(&r, 30, 33, &H);
    const surface *s = &H.h0.s;
    ck_assert_int_eq(s->entering, 0);
    vec3 d = vec3_normalize(H.r.d), wo = vec3_neg(d), wi;
    ck_assert(fresnel_refract(d, s->n, 1 / 1.5, &wi)); /* fresnel.h: eta = n_t / n_i */
    ray_diff got, want;
    texshade_delta_diff(s, &H.rd, wo, wi, &got);
    ck_assert(raydiff_refract(&H.rd, s->dpdx, s->dpdy, wo, s->n, s->dndx, s->dndy, 1.5, wi, &want));
    ck_assert(got.has);
    ck_assert(vec3_length(vec3_sub(got.ddx, want.ddx)) <= 1e-12 * vec3_length(want.ddx));
    ck_assert(vec3_length(vec3_sub(got.ddy, want.ddy)) <= 1e-12 * vec3_length(want.ddy));
    rig_free(&r);
}
END_TEST

static Suite *texshade_suite(void)
{
    Suite *s = suite_create("texshade");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_texshade_sphere_under_a_transform_matches_finite_differences);
    tcase_add_test(tc, test_texshade_normal_derivatives_of_an_ellipsoid_outside_and_inside);
    tcase_add_test(tc,
                   test_texshade_mapped_triangle_with_vertex_normals_matches_finite_differences);
    tcase_add_test(tc, test_texshade_uv_triangle_matches_finite_differences);
    tcase_add_test(tc, test_texshade_procedural_bump_tilts_the_normal_both_ways);
    tcase_add_test(tc, test_texshade_uv_on_a_sphere_is_spherical);
    tcase_add_test(tc, test_texshade_refraction_out_of_glass_uses_the_inverse_index);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(texshade_suite)
