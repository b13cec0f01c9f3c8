/* test_camera.c - the pinhole camera of the scene format: the centre pixel looks at `center`,
 * the field of view is the full vertical angle, row 0 is at the top, x grows to the right
 * (right = look x up), and an `up` that is not perpendicular still gives an orthonormal frame. */
#include "envtex/geometry/camera.h"

#include <signal.h>

#include "unit.h"

START_TEST(test_camera_centre_pixel_looks_at_the_centre)
{
    camera c;
    vec3 eye = vec3_make(1, 2, 3), at = vec3_make(-2, 0.5, 7);
    camera_init(&c, eye, at, vec3_make(0, 1, 0), 45, 64, 48);
    ray r = camera_ray(&c, 32, 24); /* the image centre (a pixel corner with even sizes) */
    ck_vec_near(r.o, eye, 0);
    ck_vec_near(r.d, vec3_normalize(vec3_sub(at, eye)), 1e-15);
    ck_assert_near(vec3_length(r.d), 1, 1e-15);
    ck_assert(r.tmin == 0 && isinf(r.tmax));
    /* odd sizes: the centre of pixel (w/2, h/2) is the image centre */
    camera_init(&c, eye, at, vec3_make(0, 1, 0), 45, 65, 49);
    r = camera_ray(&c, 32 + 0.5, 24 + 0.5);
    ck_vec_near(r.d, vec3_normalize(vec3_sub(at, eye)), 1e-15);
}
END_TEST

START_TEST(test_camera_top_and_bottom_edge_rays_span_fovy)
{
    const double fovs[] = {1, 30, 45, 90, 120, 179};
    for (unsigned i = 0; i < sizeof fovs / sizeof fovs[0]; i++) {
        camera c;
        camera_init(&c, vec3_make(0, 0, 5), vec3_make(0, 0, 0), vec3_make(0, 1, 0), fovs[i], 200,
                    100);
        ray top = camera_ray(&c, 100, 0), bottom = camera_ray(&c, 100, 100);
        ck_assert_near(vec3_angle(top.d, bottom.d), fovs[i] * M_PI / 180, 1e-12);
        /* the horizontal field follows from the aspect: tan(fovx/2) = 2 tan(fovy/2) */
        ray left = camera_ray(&c, 0, 50), right = camera_ray(&c, 200, 50);
        ck_assert_near(vec3_angle(left.d, right.d), 2 * atan(2 * tan(fovs[i] * M_PI / 360)), 1e-12);
    }
}
END_TEST

START_TEST(test_camera_row_0_is_at_the_top_and_x_grows_to_the_right)
{
    /* looking down -z with up +y: right is +x (look x up = (0,0,-1) x (0,1,0) = (1,0,0)) */
    camera c;
    camera_init(&c, vec3_make(0, 0, 5), vec3_make(0, 0, 0), vec3_make(0, 1, 0), 60, 40, 30);
    ray top = camera_ray(&c, 20, 0.5), bottom = camera_ray(&c, 20, 29.5);
    ck_assert(top.d.y > 0.3 && bottom.d.y < -0.3);
    ray left = camera_ray(&c, 0.5, 15), right = camera_ray(&c, 39.5, 15);
    ck_assert(left.d.x < -0.3 && right.d.x > 0.3);
    /* the orientation test's camera: at (0,-5,0) looking at the origin, z up: right is +x */
    camera_init(&c, vec3_make(0, -5, 0), vec3_make(0, 0, 0), vec3_make(0, 0, 1), 60, 40, 30);
    ray r = camera_ray(&c, 39.5, 15), u = camera_ray(&c, 20, 0.5);
    ck_assert(r.d.x > 0.3 && fabs(r.d.z) < 1e-15);
    ck_assert(u.d.z > 0.3 && fabs(u.d.x) < 1e-15);
    ck_vec_near(c.u, vec3_make(1, 0, 0), 1e-15);
    ck_vec_near(c.v, vec3_make(0, 0, 1), 1e-15);
    ck_vec_near(c.w, vec3_make(0, -1, 0), 1e-15);
}
END_TEST

START_TEST(test_camera_frame_is_orthonormal_for_a_slanted_up)
{
    /* the course scenes use up = (0 1 1), not perpendicular to the view */
    camera c;
    camera_init(&c, vec3_make(0, -4, 4), vec3_make(0, 0, 0), vec3_make(0, 1, 1), 30, 64, 64);
    ck_assert_near(vec3_length(c.u), 1, 1e-15);
    ck_assert_near(vec3_length(c.v), 1, 1e-15);
    ck_assert_near(vec3_length(c.w), 1, 1e-15);
    ck_assert_near(vec3_dot(c.u, c.v), 0, 1e-15);
    ck_assert_near(vec3_dot(c.v, c.w), 0, 1e-15);
    ck_assert_near(vec3_dot(c.w, c.u), 0, 1e-15);
    vec3 x = vec3_cross(c.u, c.v); /* right-handed: u x v = w */
    ck_vec_near(x, c.w, 1e-15);
    /* v leans towards the given up, and u is perpendicular to it */
    ck_assert(vec3_dot(c.v, vec3_make(0, 1, 1)) > 0);
    ck_assert_near(vec3_dot(c.u, vec3_make(0, 1, 1)), 0, 1e-15);
    /* a generic slanted up, from a generic position */
    camera_init(&c, vec3_make(3, -1, 2), vec3_make(-1, 4, 0.5), vec3_make(0.2, 0.3, 1), 50, 10, 20);
    ck_assert_near(vec3_dot(c.u, c.v), 0, 1e-15);
    ck_assert_near(vec3_dot(c.u, c.w), 0, 1e-15);
    ck_assert_near(vec3_dot(c.v, c.w), 0, 1e-15);
    ck_assert_near(vec3_length(c.u), 1, 1e-15);
    ck_assert_near(vec3_length(c.v), 1, 1e-15);
}
END_TEST

START_TEST(test_camera_rays_are_unit_and_linear_in_the_image_plane)
{
    /* every ray meets the plane at distance 1 along the view in a point linear in (x, y) */
    camera c;
    camera_init(&c, vec3_make(0, 0, 0), vec3_make(0, 0, -1), vec3_make(0, 1, 0), 90, 8, 4);
    for (int y = 0; y <= 4; y++)
        for (int x = 0; x <= 8; x++) {
            ray r = camera_ray(&c, x, y);
            ck_assert_near(vec3_length(r.d), 1, 1e-15);
            vec3 p = vec3_scale(r.d, -1 / r.d.z);          /* on the plane z = -1 */
            ck_assert_near(p.x, 2.0 * (x - 4) / 4, 1e-14); /* tan(fovx/2) = 2 */
            ck_assert_near(p.y, (2.0 - y) / 2, 1e-14);     /* tan(fovy/2) = 1 */
        }
}
END_TEST

/* camera_frame works for any finite vectors that have a frame, and says why when there is
 * none.  Catches lengths from sqrt of squares (1e-163 x 1e-160 underflows: the parser once let
 * this camera through and camera_init asserted), an overflowing eye - center reported as
 * anything else, and a parallel test on unnormalised vectors. */
START_TEST(test_camera_frame_handles_tiny_and_huge_vectors_and_names_each_failure)
{
    vec3 u, v, w;
    ck_assert_int_eq(camera_frame(vec3_make(0, 0, 1e10), vec3_make(0, 0, 0),
                                  vec3_make(0, 1e-163, 1e-160), &u, &v, &w),
                     CAMERA_FRAME_OK);
    ck_vec_near(u, vec3_make(1, 0, 0), 1e-15); /* up's part across the view is +y: right = +x */
    ck_assert_near(vec3_length(u), 1, 1e-15);
    ck_assert_near(vec3_length(v), 1, 1e-15);
    ck_assert_near(vec3_dot(u, w), 0, 1e-15);
    ck_assert_int_eq(camera_frame(vec3_make(1e300, 0, 0), vec3_make(0, 0, 0),
                                  vec3_make(0, 1e300, 0), &u, &v, &w),
                     CAMERA_FRAME_OK);
    ck_vec_near(w, vec3_make(1, 0, 0), 1e-15);
    ck_assert_int_eq(camera_frame(vec3_make(0, 0, 1e308), vec3_make(0, 0, -1e308),
                                  vec3_make(0, 1, 0), &u, &v, &w),
                     CAMERA_FRAME_TOO_FAR);
    ck_assert_int_eq(
        camera_frame(vec3_make(1, 2, 3), vec3_make(1, 2, 3), vec3_make(0, 1, 0), &u, &v, &w),
        CAMERA_FRAME_SAME_POINT);
    ck_assert_int_eq(
        camera_frame(vec3_make(0, 0, 1), vec3_make(0, 0, 0), vec3_make(0, 0, 0), &u, &v, &w),
        CAMERA_FRAME_UP_ZERO);
    ck_assert_int_eq(camera_frame(vec3_make(0, 0, 1e-300), vec3_make(0, 0, 0),
                                  vec3_make(0, 1e-300, 1), &u, &v, &w),
                     CAMERA_FRAME_UP_PARALLEL); /* sin(angle) = 1e-300, however small the vectors */
}
END_TEST

/* Programmer errors are asserts (camera.h): the scene parser refuses these cameras. */
START_TEST(test_camera_with_eye_at_the_centre_asserts)
{
    camera c;
    camera_init(&c, vec3_make(1, 2, 3), vec3_make(1, 2, 3), vec3_make(0, 1, 0), 45, 8, 8);
}
END_TEST

START_TEST(test_camera_with_up_along_the_view_asserts)
{
    camera c;
    camera_init(&c, vec3_make(0, 0, 5), vec3_make(0, 0, 0), vec3_make(0, 0, 2), 45, 8, 8);
}
END_TEST

Suite *camera_suite(void)
{
    Suite *s = suite_create("camera");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_camera_centre_pixel_looks_at_the_centre);
    tcase_add_test(tc, test_camera_top_and_bottom_edge_rays_span_fovy);
    tcase_add_test(tc, test_camera_row_0_is_at_the_top_and_x_grows_to_the_right);
    tcase_add_test(tc, test_camera_frame_is_orthonormal_for_a_slanted_up);
    tcase_add_test(tc, test_camera_rays_are_unit_and_linear_in_the_image_plane);
    tcase_add_test(tc, test_camera_frame_handles_tiny_and_huge_vectors_and_names_each_failure);
#ifndef NDEBUG
    tcase_add_test_raise_signal(tc, test_camera_with_eye_at_the_centre_asserts, SIGABRT);
    tcase_add_test_raise_signal(tc, test_camera_with_up_along_the_view_asserts, SIGABRT);
#endif
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(camera_suite)
