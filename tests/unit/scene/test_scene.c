/* test_scene.c - the scene-file parser: every command's effect and default, the transform
 * order, material deduplication, and every error path at its FILE:LINE naming its token. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "envtex/io/imageio.h"
#include "envtex/scene/scene.h"
#include "envtex/scene/scene_load.h"
#include "unit.h"

/* Two lines every valid scene needs; a bad command placed after them is on line 3. */
#define HEAD "size 10 10\ncamera 0 0 5 0 0 0 0 1 0 45\n"

typedef struct warnings {
    int n;
    error last;
} warnings;

static void count_warning(void *ctx, const error *w)
{
    warnings *ws = ctx;
    ws->n++;
    ws->last = *w;
}

static scene_load_opts opts_counting(warnings *ws)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    o.warn = count_warning;
    o.warn_ctx = ws;
    memset(ws, 0, sizeof *ws);
    return o;
}

/* Parse `text` (named "t.test"), which must succeed. */
static void load_ok(const char *text, scene *sc)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    error err = {0};
    int rc = scene_load_string(text, "t.test", &o, sc, &err);
    ck_assert_msg(rc == 0, "unexpected error: %s:%d: %s", err.file, err.line, err.msg);
}

/* Parse `text`, which must fail at `line` with a message containing `what`; *out owns nothing. */
static void load_fails(const char *text, int line, const char *what)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    scene sc;
    error err = {0};
    int rc = scene_load_string(text, "t.test", &o, &sc, &err);
    ck_assert_msg(rc == -1, "no error for:\n%s", text);
    ck_assert_str_eq(err.file, "t.test");
    ck_assert_msg(err.line == line, "error at line %d, expected %d: %s", err.line, line, err.msg);
    ck_assert_msg(strstr(err.msg, what) != NULL, "message '%s' does not contain \"%s\"", err.msg,
                  what);
    ck_assert_ptr_null(sc.materials);
    ck_assert_ptr_null(sc.spheres);
    ck_assert_ptr_null(sc.triangles);
    ck_assert_ptr_null(sc.lights);
    ck_assert_ptr_null(sc.envmap.img.px);
}

/* Load the file `path` (default options), which must fail at `line` of that file with a message
 * containing `what`. */
static void load_file_fails(const char *path, int line, const char *what)
{
    scene sc;
    error err = {0};
    ck_assert_int_eq(scene_load(path, NULL, &sc, &err), -1);
    ck_assert_str_eq(err.file, path);
    ck_assert_msg(err.line == line, "error at line %d, expected %d: %s", err.line, line, err.msg);
    ck_assert_msg(strstr(err.msg, what) != NULL, "message '%s' does not contain \"%s\"", err.msg,
                  what);
}

#define assert_vec_near(a, x, y, z) ck_vec_near(a, vec3_make(x, y, z), 1e-12)

/* ---- every error path ------------------------------------------------------------------- */

typedef struct bad_case {
    const char *text; /* appended to HEAD */
    int line;
    const char *what; /* the offending token (quoted) or the words that name the problem */
} bad_case;

static const bad_case bad_cases[] = {
    /* numbers */
    {"sphere 0 0 0 abc\n", 3, "expected a number for 'sphere' argument 4, got 'abc'"},
    {"sphere 0 0 0 1x\n", 3, "'1x'"},
    {"sphere 0 0 0 nan\n", 3, "got 'nan'"},
    {"sphere 0 0 inf 1\n", 3, "argument 3, got 'inf'"},
    {"sphere 0 0 0 1e999\n", 3, "'1e999'"},
    {"gamma -inf\n", 3, "'-inf'"},
    /* argument counts */
    {"sphere 0 0 0\n", 3, "'sphere' takes 4 arguments, got 3"},
    {"sphere 0 0 0 1 7\n", 3, "from '7'"},
    {"size 10 10 10\n", 3, "'size' takes 2 arguments, got 3"},
    {"pushTransform x\n", 3, "'x'"},
    {"output\n", 3, "'output' takes 1 argument, got 0"},
    {"envmap\n", 3, "'envmap' takes FILE [SCALE] [REPRESENTATION] or cube PX NX PY NY PZ NZ"},
    /* more than the 14 arguments run_line lets through: the forms, not "takes 0 or 14" */
    {"envmap cube a b c d e f 1 x x x x x x x\n", 3,
     "'envmap' takes FILE [SCALE] [REPRESENTATION] or cube PX NX PY NY PZ NZ [SCALE], got 15 "
     "arguments"},
    {"envmap a.exr 1 c\n", 3,
     "'envmap' representation must be 'latlong', 'cube', 'cross', "
     "'mirrorball', 'angular', 'cylindrical' or 'equalarea', got 'c'"},
    {"quadLight 0 0 0 1 0 0 0 1 0 1 1\n", 3, "'quadLight' takes 12 arguments, got 11"},
    /* image size */
    {"size 0 10\n", 3, "'0'"},
    {"size 10 -5\n", 3, "'size' argument 2 must be in [1, 16384], got '-5'"},
    {"size 16385 10\n", 3, "'16385'"},
    {"size 16384 16384\n", 3, "pixels"},
    {"size 10.5 10\n", 3, "expected an integer for 'size' argument 1, got '10.5'"},
    /* renderer settings */
    {"spp 0\n", 3, "'spp' argument 1 must be in [1, 1048576], got '0'"},
    {"spp 1048577\n", 3, "'1048577'"},
    {"spp 2.5\n", 3, "'2.5'"},
    {"maxdepth -2\n", 3, "'-2'"},
    {"maxdepth 1001\n", 3, "'1001'"},
    {"lightsamples 0\n", 3, "'lightsamples' argument 1 must be in [1, 65536], got '0'"},
    {"lightsamples 65537\n", 3, "'65537'"},
    {"integrator foo\n", 3,
     "'integrator' must be 'raytracer', 'analyticdirect', 'direct', "
     "'pathtracer' or 'prefiltered', got 'foo'"},
    {"prefilter sh8\n", 3, "'prefilter' must be 'exact' or 'sh9', got 'sh8'"},
    {"nexteventestimation maybe\n", 3, "'maybe'"},
    {"lightstratify yes\n", 3, "'lightstratify' must be 'off' or 'on', got 'yes'"},
    {"lightselection one\n", 3, "'lightselection' must be 'all' or 'power', got 'one'"},
    {"russianroulette 1\n", 3, "got '1'"},
    {"importancesampling uniform\n", 3, "'uniform'"},
    {"envmiss foo\n", 3, "'envmiss' must be 'envmap' or 'black', got 'foo'"},
    {"gamma 0\n", 3, "'gamma' argument 1 must be > 0, got '0'"},
    {"gamma 1e-5\n", 3, "'gamma' must be from 0.01 to 100, got '1e-5'"},
    {"gamma 101\n", 3, "'gamma' must be from 0.01 to 100, got '101'"},
    /* material state */
    {"brdf foo\n", 3, "'brdf' must be 'phong', 'ggx', 'mirror' or 'glass', got 'foo'"},
    {"roughness -0.1\n", 3, "'roughness' argument 1 must be >= 0, got '-0.1'"},
    {"ior 0\n", 3, "'ior' argument 1 must be > 0, got '0'"},
    {"ior -1.5\n", 3, "'-1.5'"},
    {"ior 1e-200\n", 3, "'ior' must be from 0.01 to 100, got '1e-200'"},
    {"ior 0.0099\n", 3, "'ior' must be from 0.01 to 100, got '0.0099'"},
    {"ior 100.01\n", 3, "'ior' must be from 0.01 to 100, got '100.01'"},
    {"shininess -1\n", 3, "'shininess' argument 1 must be >= 0, got '-1'"},
    {"diffuse 1 -1 0\n", 3, "'diffuse' argument 2 must be >= 0, got '-1'"},
    {"emission 1 1 x\n", 3, "'x'"},
    /* geometry */
    {"sphere 0 0 0 0\n", 3, "'sphere' argument 4 must be > 0, got '0'"},
    {"sphere 0 0 0 -1\n", 3, "'-1'"},
    {"maxverts -1\n", 3, "'-1'"},
    {"maxvertnorms 2.5\n", 3, "'2.5'"},
    {"tri 0 1 2\n", 3, "'tri' vertex index '0' is out of range: 0 vertices"},
    {"vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 3\n", 6,
     "'tri' vertex index '3' is out of range: 3 vertices"},
    {"vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 -1 2\n", 6, "'-1'"},
    {"vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 1.5\n", 6,
     "expected an integer for 'tri' argument 3, got '1.5'"},
    {"vertex 0 0 0\ntrinormal 0 0 0\n", 4, "'trinormal' vertex index '0' is out of range"},
    {"vertexnormal 0 0 0 0 0 1\ntrinormal 0 0 1\n", 4, "'1'"},
    /* transforms */
    {"popTransform\n", 3, "'popTransform' without a matching 'pushTransform'"},
    {"pushTransform\npopTransform\npopTransform\n", 5, "popTransform"},
    {"rotate 0 0 0 45\n", 3, "'rotate' axis is zero"},
    {"scale 1e300 1 1\nscale 1e300 1 1\n", 4, "'scale' makes the current transform overflow"},
    {"scale 1 0 1\nsphere 0 0 0 1\n", 4, "'sphere' needs the inverse of the current transform"},
    {"vertexnormal 0 0 0 0 0 1\nvertexnormal 1 0 0 0 0 1\nvertexnormal 0 1 0 0 0 1\n"
     "scale 1 1 0\ntrinormal 0 1 2\n",
     7, "'trinormal' needs the inverse"},
    {"scale 0 0 0\nenvmap sky.exr\n", 4, "'envmap' needs the inverse"},
    /* lights */
    {"directional 0 0 0 1 1 1\n", 3, "'directional' direction is zero"},
    {"directional 0 1 0 -1 1 1\n", 3, "'directional' argument 4 must be >= 0, got '-1'"},
    {"point 0 0 0 1 x 1\n", 3, "expected a number for 'point' argument 5, got 'x'"},
    {"attenuation 0 0 0\n", 3, "'attenuation' is all zero"},
    {"attenuation 1 -1 0\n", 3, "'-1'"},
    {"quadLight 0 0 0 1 0 0 2 0 0 1 1 1\n", 3, "'quadLight' has zero area"},
    {"quadLight 0 0 0 0 0 0 0 1 0 1 1 1\n", 3, "'quadLight' has zero area"},
    /* parallel to within 1e-14 relative: the area test is relative to |ab| |ac| */
    {"quadLight 0 0 0 1 0 0 1 1e-14 0 1 1 1\n", 3, "'quadLight' has zero area"},
    {"quadLight 0 0 0 1 0 0 0 1 0 1 -1 1\n", 3, "'-1'"},
    /* camera */
    {"camera 0 0 5 0 0 0 0 1 0 0\n", 3, "'camera' fovy must be in (0, 180) degrees, got '0'"},
    {"camera 0 0 5 0 0 0 0 1 0 180\n", 3, "'180'"},
    {"camera 1 2 3 1 2 3 0 1 0 45\n", 3, "'camera' look-from equals look-at"},
    {"camera 0 0 5 0 0 0 0 0 2 45\n", 3, "'camera' up vector (0 0 2) is parallel"},
    {"camera 0 0 5 0 0 0 0 0 0 45\n", 3, "'camera' up vector is zero"},
    /* overflowing eye - center: not "parallel" (its length was Inf, the old test's message) */
    {"camera 0 0 1e308 0 0 -1e308 0 1 0 45\n", 3,
     "'camera' look-from and look-at are too far apart"},
    /* envmap */
    {"envmap a.exr\nenvmap b.exr\n", 4, "envmap given twice (first at line 3)"},
    {"envmap sky.exr 0\n", 3, "'envmap' argument 2 must be > 0, got '0'"},
    {"envmap sky.exr nan\n", 3, "'nan'"},
    {"envmap sky.exr fisheye\n", 3, "got 'fisheye'"},
    {"envmap sky.exr mirrorball 2\n", 3, "got '2' after them"},
    {"envmap sky.exr 2 angular extra\n", 3, "got 'extra' after them"},
    {"envmap cube px.exr nx.exr py.exr\n", 3,
     "'envmap cube' takes six face files PX NX PY NY PZ NZ "
     "and an optional scale, got 3 arguments"},
    {"envmap cube a b c d e f 0\n", 3, "'envmap' argument 8 must be > 0, got '0'"},
    {"envmap cube a b c d e f 1 2\n", 3, "got 8 arguments"},
    {"scale 1 0 1\nenvmap cube a b c d e f\n", 4, "'envmap' needs the inverse"},
    {"envsampling cdf 4\n", 3,
     "'envsampling cdf' takes no count (only 'mediancut N' and 'sis N' do)"},
    /* a corner that overflows where the transform itself does not */
    {"scale 1e300 1 1\nvertex 0 0 0\nvertex 1e10 0 0\nvertex 0 1 0\ntri 0 1 2\n", 7,
     "'tri' corner 1 overflows under the current transform"},
};

/* a loop test: Check passes the case index as _i */
START_TEST(test_each_bad_line_is_an_error_at_its_line_naming_the_token)
{
    char text[1024];
    snprintf(text, sizeof text, "%s%s", HEAD, bad_cases[_i].text);
    load_fails(text, bad_cases[_i].line, bad_cases[_i].what);
}
END_TEST

START_TEST(test_a_scene_without_size_is_an_error_at_the_end)
{
    load_fails("camera 0 0 5 0 0 0 0 1 0 45\n", 0, "no 'size' command");
    load_fails("", 0, "no 'size' command");
}
END_TEST

START_TEST(test_a_scene_without_camera_is_an_error_at_the_end)
{
    load_fails("size 10 10\nsphere 0 0 0 1\n", 0, "no 'camera' command");
}
END_TEST

START_TEST(test_a_line_longer_than_the_limit_is_an_error_not_an_overflow)
{
    size_t n = SCENE_MAX_LINE + 1; /* one byte too long */
    char *text = malloc(strlen(HEAD) + n + 2);
    ck_assert_ptr_nonnull(text);
    strcpy(text, HEAD);
    memset(text + strlen(HEAD), '1', n);
    text[strlen(HEAD) + n] = '\0';
    load_fails(text, 3, "line is longer than 65536 bytes");
    /* exactly at the limit (a comment) is fine */
    char *ok = malloc(strlen(HEAD) + SCENE_MAX_LINE + 2);
    ck_assert_ptr_nonnull(ok);
    strcpy(ok, HEAD);
    memset(ok + strlen(HEAD), ' ', SCENE_MAX_LINE);
    ok[strlen(HEAD)] = '#';
    strcpy(ok + strlen(HEAD) + SCENE_MAX_LINE, "\n");
    scene sc;
    load_ok(ok, &sc);
    scene_free(&sc);
    free(text);
    free(ok);
}
END_TEST

START_TEST(test_push_deeper_than_the_stack_limit_is_an_error)
{
    size_t each = strlen("pushTransform\n");
    char *text = malloc(strlen(HEAD) + each * (SCENE_MAX_TRANSFORM_STACK + 1) + 1);
    ck_assert_ptr_nonnull(text);
    char *w = text + sprintf(text, "%s", HEAD);
    for (int i = 0; i < SCENE_MAX_TRANSFORM_STACK; i++) w += sprintf(w, "pushTransform\n");
    /* the limit itself is fine (a warning for the unbalanced pushes at the end) */
    warnings ws;
    scene_load_opts o = opts_counting(&ws);
    scene sc;
    error err = {0};
    ck_assert_int_eq(scene_load_string(text, "t.test", &o, &sc, &err), 0);
    ck_assert_int_eq(ws.n, 1);
    ck_assert_ptr_nonnull(strstr(ws.last.msg, "1024 'pushTransform' without 'popTransform'"));
    scene_free(&sc);
    /* one more is not */
    sprintf(w, "pushTransform\n");
    load_fails(text, 2 + SCENE_MAX_TRANSFORM_STACK + 1, "nested deeper than 1024");
    free(text);
}
END_TEST

START_TEST(test_more_primitives_than_the_limit_is_an_error)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    o.max_prims = 3;
    scene sc;
    error err = {0};
    const char *three = HEAD "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                             "tri 0 1 2\ntri 0 1 2\ntri 0 1 2\n"
                             "sphere 0 0 0 1\nsphere 0 0 0 1\nsphere 0 0 0 1\n";
    ck_assert_int_eq(scene_load_string(three, "t.test", &o, &sc, &err), 0);
    scene_free(&sc);

    ck_assert_int_eq(scene_load_string(HEAD "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                            "vertex 0 0 1\n",
                                       "t.test", &o, &sc, &err),
                     -1);
    ck_assert_int_eq(err.line, 6);
    ck_assert_str_eq(err.msg, "more than 3 vertices");

    char text[1024];
    snprintf(text, sizeof text, "%s%s", three, "tri 0 1 2\n");
    ck_assert_int_eq(scene_load_string(text, "t.test", &o, &sc, &err), -1);
    ck_assert_int_eq(err.line, 12);
    ck_assert_str_eq(err.msg, "more than 3 triangles");

    snprintf(text, sizeof text, "%s%s", three, "sphere 0 0 0 1\n");
    ck_assert_int_eq(scene_load_string(text, "t.test", &o, &sc, &err), -1);
    ck_assert_int_eq(err.line, 12);
    ck_assert_str_eq(err.msg, "more than 3 spheres");
    ck_assert_ptr_null(sc.spheres);
}
END_TEST

/* Each limit at its exact bound: the largest value is taken, one more is refused (an off-by-one
 * in the name lengths would write the terminating NUL past the array). */
START_TEST(test_limits_hold_at_their_exact_bounds)
{
    scene sc;
    char text[2600], name[1100];
    /* output: 1023 bytes fit sc.output[1024], 1024 do not */
    memset(name, 'o', 1024);
    name[1023] = '\0';
    snprintf(text, sizeof text, HEAD "output %s\n", name);
    load_ok(text, &sc);
    ck_assert_uint_eq(strlen(sc.output), 1023);
    scene_free(&sc);
    name[1023] = 'o';
    name[1024] = '\0';
    snprintf(text, sizeof text, HEAD "output %s\n", name);
    load_fails(text, 3, "'output' file name is longer than 1023 bytes");
    /* texture names: 63 bytes fit SCENE_MAX_TEXTURE_NAME (64), 64 do not */
    memset(name, 't', SCENE_MAX_TEXTURE_NAME);
    name[SCENE_MAX_TEXTURE_NAME - 1] = '\0';
    snprintf(text, sizeof text, HEAD "texture %s checker 8 0 0 0 1 1 1\ndiffusemap %s\n", name,
             name);
    load_ok(text, &sc);
    ck_assert_str_eq(sc.textures[0].name, name);
    scene_free(&sc);
    name[SCENE_MAX_TEXTURE_NAME - 1] = 't';
    name[SCENE_MAX_TEXTURE_NAME] = '\0';
    snprintf(text, sizeof text, HEAD "texture %s checker 8 0 0 0 1 1 1\n", name);
    load_fails(text, 3, "is longer than 63 bytes");
    /* gamma: both ends of [0.01, 100] are taken */
    load_ok(HEAD "gamma 100\n", &sc);
    ck_assert_double_eq(sc.gamma, 100);
    scene_free(&sc);
    load_ok(HEAD "gamma 0.01\n", &sc);
    ck_assert_double_eq(sc.gamma, 0.01);
    scene_free(&sc);
    /* ior: both ends of [0.01, 100] are taken */
    load_ok(HEAD "ior 100\nsphere 0 0 0 1\nior 0.01\nsphere 0 0 0 1\n", &sc);
    ck_assert_double_eq(sc.materials[sc.spheres[0].material].ior, 100);
    ck_assert_double_eq(sc.materials[sc.spheres[1].material].ior, 0.01);
    scene_free(&sc);
    /* camera samples: 8192 x 8192 x 256 is exactly 2^34, one more spp is over */
    load_ok("size 8192 8192\nspp 256\ncamera 0 0 5 0 0 0 0 1 0 45\n", &sc);
    scene_free(&sc);
    load_fails(
        "size 8192 8192\nspp 257\ncamera 0 0 5 0 0 0 0 1 0 45\n", 0,
        "size 8192 x 8192 at spp 257 asks for 17246978048 camera samples, over the limit of 2^34");
    /* the primitive limit counts textured vertices too */
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    o.max_prims = 3;
    error err = {0};
    const char *three = HEAD "vertextex 0 0 0 0 0\nvertextex 1 0 0 1 0\nvertextex 0 1 0 0 1\n";
    ck_assert_msg(scene_load_string(three, "t.test", &o, &sc, &err) == 0, "%s", err.msg);
    scene_free(&sc);
    snprintf(text, sizeof text, "%svertextex 0 0 1 1 1\n", three);
    ck_assert_int_eq(scene_load_string(text, "t.test", &o, &sc, &err), -1);
    ck_assert_int_eq(err.line, 6);
    ck_assert_str_eq(err.msg, "more than 3 textured vertices");
}
END_TEST

START_TEST(test_a_huge_maxverts_hint_allocates_nothing_huge)
{
    /* uncapped, this asks for 24 TB: realloc fails (or ASan aborts) and the test fails */
    scene sc;
    load_ok(HEAD "maxverts 999999999999\nmaxvertnorms 999999999999\n"
                 "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 2\n",
            &sc);
    ck_assert_int_eq(sc.n_triangles, 1);
    scene_free(&sc);
}
END_TEST

START_TEST(test_a_nul_byte_makes_the_file_an_error)
{
    char dir[] = "/tmp/test_scene_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[256];
    snprintf(path, sizeof path, "%s/bin.test", dir);
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    static const char bytes[] = "size 10 10\n# comment\ncam\0era\n";
    fwrite(bytes, 1, sizeof bytes - 1, f);
    fclose(f);
    load_file_fails(path, 3, "binary file?");
    unlink(path);
    rmdir(dir);
}
END_TEST

START_TEST(test_a_missing_file_is_an_error_naming_it)
{
    load_file_fails("/nonexistent/dir/x.test", 0, "cannot open");
}
END_TEST

/* ---- warnings and --strict -------------------------------------------------------------- */

START_TEST(test_unknown_commands_are_warnings_with_file_and_line)
{
    warnings ws;
    scene_load_opts o = opts_counting(&ws);
    scene sc;
    error err = {0};
    ck_assert_int_eq(
        scene_load_string(HEAD "foo 1 2\nsphere 0 0 0 1\nbar\n", "t.test", &o, &sc, &err), 0);
    ck_assert_int_eq(ws.n, 2);
    ck_assert_str_eq(ws.last.file, "t.test");
    ck_assert_int_eq(ws.last.line, 5);
    ck_assert_str_eq(ws.last.msg, "unknown command 'bar' (ignored)");
    ck_assert_int_eq(sc.n_spheres, 1);
    scene_free(&sc);
    /* without a callback the warnings are dropped */
    o.warn = NULL;
    ck_assert_int_eq(scene_load_string(HEAD "foo\n", "t.test", &o, &sc, &err), 0);
    scene_free(&sc);
}
END_TEST

START_TEST(test_strict_makes_unknown_commands_errors)
{
    warnings ws;
    scene_load_opts o = opts_counting(&ws);
    o.strict = 1;
    scene sc;
    error err = {0};
    ck_assert_int_eq(scene_load_string(HEAD "sphere 0 0 0 1\nfoo 1 2\n", "t.test", &o, &sc, &err),
                     -1);
    ck_assert_int_eq(err.line, 4);
    ck_assert_str_eq(err.msg, "unknown command 'foo'");
    ck_assert_int_eq(ws.n, 0);
    ck_assert_ptr_null(sc.spheres);
}
END_TEST

START_TEST(test_commands_before_size_warn_once_even_when_strict)
{
    warnings ws;
    scene_load_opts o = opts_counting(&ws);
    o.strict = 1;
    scene sc;
    error err = {0};
    ck_assert_int_eq(scene_load_string("# first\ncamera 0 0 5 0 0 0 0 1 0 45\nsphere 0 0 0 1\n"
                                       "size 10 10\n",
                                       "t.test", &o, &sc, &err),
                     0);
    ck_assert_int_eq(ws.n, 1);
    ck_assert_int_eq(ws.last.line, 2);
    ck_assert_ptr_nonnull(strstr(ws.last.msg, "'camera' comes before 'size'"));
    ck_assert_int_eq(sc.width, 10);
    scene_free(&sc);
    /* size first: no warning */
    ck_assert_int_eq(scene_load_string(HEAD, "t.test", &o, &sc, &err), 0);
    ck_assert_int_eq(ws.n, 1);
    scene_free(&sc);
}
END_TEST

/* Load `text` (which must load) and check its warnings: exactly `n` of them, the last at `line`
 * and containing `what` (n = 0: none, line and what unused). */
#define expect_warnings(text, n, line, what) warnings_at(__FILE__, __LINE__, text, n, line, what)
static void warnings_at(const char *file, int at, const char *text, int n, int line,
                        const char *what)
{
    warnings ws;
    scene_load_opts o = opts_counting(&ws);
    scene sc;
    error err = {0};
    if (scene_load_string(text, "t.test", &o, &sc, &err) != 0)
        unit_fail_at(file, at, "the scene does not load: %s", err.msg);
    if (ws.n != n)
        unit_fail_at(file, at, "got %d warnings, want %d (the last: %s) for:\n%s", ws.n, n,
                     ws.last.msg, text);
    if (n > 0 && ws.last.line != line)
        unit_fail_at(file, at, "the last warning: got line %d, want %d", ws.last.line, line);
    if (n > 0 && !strstr(ws.last.msg, what))
        unit_fail_at(file, at, "the last warning: got '%s', want it to hold '%s'", ws.last.msg,
                     what);
    scene_free(&sc);
}

/* A quad light in a scene rendered by the Whitted raytracer (hw1's renderer, hw2's light): one
 * warning at the first quadLight's line, since the raytracer ignores quad lights; none when an
 * integrator that uses them is chosen, before or after the light */
START_TEST(test_quad_lights_under_the_raytracer_warn_at_the_first_one)
{
    const char *quads =
        "quadLight -1 -1 2  2 0 0  0 2 0  3 3 3\nquadLight 1 1 2  2 0 0  0 2 0  3 3 3\n";
    char text[512];
    snprintf(text, sizeof text, HEAD "sphere 0 0 0 1\n%s", quads);
    expect_warnings(text, 1, 4, "ignores quad lights");
    static const char *const others[] = {"integrator analyticdirect\n", "integrator direct\n",
                                         "integrator pathtracer\n"};
    for (int i = 0; i < 3; i++) {
        snprintf(text, sizeof text, HEAD "%s%sintegrator raytracer\n%s", quads, others[i],
                 others[i]);
        expect_warnings(text, 0, 0, NULL);
    }
}
END_TEST

/* Point and directional lights under analyticdirect (hw2's renderer, hw1's lights): one warning
 * at the first of them, since analyticdirect integrates quad lights only; none under the
 * integrators that sample them, or when the scene has only quad lights.  Catches a scene that
 * renders black with no word of why (an audit found it silent). */
START_TEST(test_point_lights_under_analyticdirect_warn_at_the_first_one)
{
    const char *lights =
        "quadLight -1 -1 2  2 0 0  0 2 0  3 3 3\ndirectional 0 0 1 1 1 1\npoint 0 0 2 1 1 1\n";
    char text[512];
    snprintf(text, sizeof text, HEAD "integrator analyticdirect\nsphere 0 0 0 1\n%s", lights);
    expect_warnings(text, 1, 6, "point and directional lights are ignored");
    static const char *const others[] = {"integrator direct\n",
                                         "integrator pathtracer\nnexteventestimation on\n",
                                         "integrator raytracer\n"};
    for (int i = 0; i < 3; i++) {
        snprintf(text, sizeof text, HEAD "integrator analyticdirect\npoint 0 0 2 1 1 1\n%s",
                 others[i]);
        expect_warnings(text, 0, 0, NULL);
    }
    expect_warnings(HEAD "integrator analyticdirect\nquadLight -1 -1 2  2 0 0  0 2 0  3 3 3\n", 0,
                    0, NULL);
}
END_TEST

/* Point and directional lights in the path tracer with NEE off (its default): no path can hit
 * one, so they light nothing; one warning at the first of them, none with NEE on or mis or with
 * quad lights only.  Catches a scene that renders black with no word of why (an audit of the
 * integrators noted it). */
START_TEST(test_point_lights_in_the_path_tracer_without_nee_warn)
{
    expect_warnings(HEAD "integrator pathtracer\nquadLight -1 -1 2  2 0 0  0 2 0  3 3 3\n"
                         "point 0 0 2 1 1 1\ndirectional 0 0 1 1 1 1\n",
                    1, 5, "never reaches point or directional lights");
    expect_warnings(HEAD "integrator pathtracer\nnexteventestimation on\npoint 0 0 2 1 1 1\n", 0, 0,
                    NULL);
    expect_warnings(HEAD
                    "integrator pathtracer\nnexteventestimation mis\ndirectional 0 0 1 1 1 1\n",
                    0, 0, NULL);
    expect_warnings(HEAD "integrator pathtracer\nquadLight -1 -1 2  2 0 0  0 2 0  3 3 3\n", 0, 0,
                    NULL);
    expect_warnings(HEAD "integrator direct\npoint 0 0 2 1 1 1\n", 0, 0, NULL);
}
END_TEST

/* ---- lexical rules ---------------------------------------------------------------------- */

START_TEST(test_comments_blank_lines_crlf_and_tabs_are_tolerated)
{
    scene sc;
    load_ok("\xEF\xBB\xBFsize\t64 32\r\n" /* a BOM kept would make "\xEF\xBB\xBFsize" unknown */
            "# a comment\r\n"
            "\r\n"
            "   \t# an indented comment\r\n"
            "  \t \r\n"
            "camera 0 0 5  0 0 0\t0 1 0 45   # trailing comment\r\n"
            "sphere 1 2 3 0.5\r\n"
            "output out.png",
            &sc);
    ck_assert_int_eq(sc.width, 64);
    ck_assert_int_eq(sc.height, 32);
    ck_assert_int_eq(sc.n_spheres, 1);
    ck_assert_double_eq(sc.spheres[0].radius, 0.5);
    ck_assert_str_eq(sc.output, "out.png");
    scene_free(&sc);
    /* line numbers count comments and blank lines, and CRLF is one line end */
    load_ok("\xEF\xBB\xBF# a comment after a BOM\nsize 8 8\ncamera 0 0 5 0 0 0 0 1 0 45\n", &sc);
    ck_assert_int_eq(sc.width, 8);
    scene_free(&sc);
    load_fails("# c\r\n\r\nsize 10 10\r\ncamera 0 0 5 0 0 0 0 1 0 45\r\n\r\nsphere 0 0 0 q\r\n", 6,
               "'q'");
}
END_TEST

/* ---- each command's effect -------------------------------------------------------------- */

START_TEST(test_defaults_are_the_courses)
{
    scene sc;
    load_ok(HEAD, &sc);
    ck_assert_str_eq(sc.path, "t.test");
    ck_assert_str_eq(sc.output, "raytrace.png");
    ck_assert_int_eq(sc.maxdepth, 5);
    ck_assert_int_eq(sc.integrator, INTEGRATOR_RAYTRACER);
    ck_assert_int_eq(sc.spp, 1);
    ck_assert_int_eq(sc.lightsamples, 1);
    ck_assert_int_eq(sc.lightstratify, 0);
    ck_assert_int_eq(sc.lightselection, LIGHTSELECTION_ALL); /* the course's: every light */
    ck_assert_int_eq(sc.nee, NEE_OFF);
    ck_assert_int_eq(sc.russianroulette, 0);
    ck_assert_int_eq(sc.importancesampling, SAMPLING_HEMISPHERE);
    ck_assert_double_eq(sc.gamma, 0);
    ck_assert_int_eq(sc.envmiss, ENVMISS_ENVMAP);
    ck_assert_int_eq(sc.envmap.present, 0);
    ck_assert_double_eq(sc.envmap.scale, 1);
    ck_assert_int_eq(sc.n_materials, 0);
    ck_assert_int_eq(sc.n_spheres, 0);
    ck_assert_int_eq(sc.n_triangles, 0);
    ck_assert_int_eq(sc.n_lights, 0);
    scene_free(&sc);

    material m = scene_default_material();
    ck_assert_double_eq(m.ambient.r, 0.2);
    ck_assert_double_eq(m.ambient.g, 0.2);
    ck_assert_double_eq(m.ambient.b, 0.2);
    ck_assert(rgb_is_black(m.diffuse) && rgb_is_black(m.specular) && rgb_is_black(m.emission));
    ck_assert_double_eq(m.shininess, 0);
    ck_assert_int_eq(m.brdf, BRDF_PHONG);
    ck_assert_double_eq(m.roughness, 0);
    ck_assert_double_eq(m.ior, 1.5);

    scene_load_opts o = scene_load_defaults();
    ck_assert_int_eq(o.strict, 0);
    ck_assert_int_eq(o.load_images, 1);
    ck_assert_ptr_null(o.warn);
}
END_TEST

START_TEST(test_image_and_camera_commands_are_stored)
{
    scene sc;
    load_ok("size 640 480\ncamera 1 2 3 4 5 6 0 1 1 30\noutput sub/x.png\nmaxdepth -1\n", &sc);
    ck_assert_int_eq(sc.width, 640);
    ck_assert_int_eq(sc.height, 480);
    ck_assert_int_eq(sc.has_camera, 1);
    assert_vec_near(sc.eye, 1, 2, 3);
    assert_vec_near(sc.center, 4, 5, 6);
    assert_vec_near(sc.up, 0, 1, 1); /* as written: the camera orthogonalises it */
    ck_assert_double_eq(sc.fovy, 30);
    ck_assert_str_eq(sc.output, "sub/x.png");
    ck_assert_int_eq(sc.maxdepth, -1);
    scene_free(&sc);
    /* "10.0" and "1e1" are integers */
    load_ok("size 10.0 1e1\ncamera 0 0 5 0 0 0 0 1 0 45\nmaxdepth 1000\n", &sc);
    ck_assert_int_eq(sc.width, 10);
    ck_assert_int_eq(sc.height, 10);
    ck_assert_int_eq(sc.maxdepth, 1000);
    scene_free(&sc);
}
END_TEST

/* Cameras whose vectors are tiny or whose points are far from the origin are valid: each has a
 * view direction and an up that is not along it.  Catches lengths taken as sqrt(x^2 + ...):
 * the first cross product underflows to 0 (camera_init then asserted: a crash), the second's
 * 1e155^2 overflows (reported as "parallel"), the third's 1e-300^2 underflows ("equals"). */
START_TEST(test_cameras_with_tiny_or_huge_but_valid_vectors_are_accepted)
{
    static const char *const cameras[] = {
        "camera 0 0 1e10 0 0 0 0 1e-163 1e-160 45\n",
        "camera 1e155 0 0 0 0 0 0 1 0 45\n",
        "camera 0 0 1e-300 0 0 0 0 1 0 45\n",
        "camera 0 0 4 0 0 0 0 1e-300 0 45\n",
    };
    for (size_t i = 0; i < sizeof cameras / sizeof cameras[0]; i++) {
        char text[256];
        snprintf(text, sizeof text, "size 8 8\n%s", cameras[i]);
        scene sc;
        load_ok(text, &sc);
        ck_assert_int_eq(sc.has_camera, 1);
        scene_free(&sc);
    }
}
END_TEST

START_TEST(test_renderer_settings_are_stored)
{
    scene sc;
    load_ok(HEAD "spp 1048576\nlightsamples 65536\nlightstratify on\nnexteventestimation mis\n"
                 "russianroulette on\nimportancesampling brdf\ngamma 2.2\nenvmiss black\n"
                 "lightselection power\n",
            &sc);
    ck_assert_int_eq(sc.lightselection, LIGHTSELECTION_POWER);
    ck_assert_int_eq(sc.spp, SCENE_MAX_SPP);
    ck_assert_int_eq(sc.lightsamples, SCENE_MAX_LIGHTSAMPLES);
    ck_assert_int_eq(sc.lightstratify, 1);
    ck_assert_int_eq(sc.nee, NEE_MIS);
    ck_assert_int_eq(sc.russianroulette, 1);
    ck_assert_int_eq(sc.importancesampling, SAMPLING_BRDF);
    ck_assert_double_eq(sc.gamma, 2.2);
    ck_assert_int_eq(sc.envmiss, ENVMISS_BLACK);
    scene_free(&sc);
    load_ok(HEAD "lightstratify on\nlightstratify off\nnexteventestimation on\n"
                 "russianroulette off\nimportancesampling cosine\nenvmiss envmap\n"
                 "lightselection power\nlightselection all\n",
            &sc);
    ck_assert_int_eq(sc.lightselection, LIGHTSELECTION_ALL);
    ck_assert_int_eq(sc.lightstratify, 0);
    ck_assert_int_eq(sc.nee, NEE_ON);
    ck_assert_int_eq(sc.russianroulette, 0);
    ck_assert_int_eq(sc.importancesampling, SAMPLING_COSINE);
    ck_assert_int_eq(sc.envmiss, ENVMISS_ENVMAP);
    scene_free(&sc);
    load_ok(HEAD "nexteventestimation on\nnexteventestimation off\nimportancesampling cosine\n"
                 "importancesampling hemisphere\n",
            &sc);
    ck_assert_int_eq(sc.nee, NEE_OFF);
    ck_assert_int_eq(sc.importancesampling, SAMPLING_HEMISPHERE);
    scene_free(&sc);
}
END_TEST

START_TEST(test_every_integrator_name_round_trips)
{
    static const integrator_kind kinds[] = {INTEGRATOR_RAYTRACER, INTEGRATOR_ANALYTICDIRECT,
                                            INTEGRATOR_DIRECT, INTEGRATOR_PATHTRACER,
                                            INTEGRATOR_PREFILTERED};
    for (int i = 0; i < 5; i++) {
        char text[256];
        snprintf(text, sizeof text, HEAD "integrator %s\n", scene_integrator_name(kinds[i]));
        scene sc;
        load_ok(text, &sc);
        ck_assert_int_eq(sc.integrator, kinds[i]);
        scene_free(&sc);
    }
    ck_assert_str_eq(scene_integrator_name(INTEGRATOR_ANALYTICDIRECT), "analyticdirect");
    ck_assert_str_eq(scene_integrator_name(INTEGRATOR_PATHTRACER), "pathtracer");
}
END_TEST

START_TEST(test_each_object_takes_the_material_current_when_read)
{
    scene sc;
    load_ok(HEAD "sphere 0 0 0 1\n"
                 "ambient 0.1 0.2 0.3\ndiffuse 0.4 0.5 0.6\nspecular 0.7 0.8 0.9\n"
                 "emission 1 2 3\nshininess 50\nbrdf ggx\nroughness 0.25\nior 1.33\n"
                 "sphere 0 0 0 1\n"
                 "brdf mirror\nsphere 0 0 0 1\nbrdf glass\nsphere 0 0 0 1\n"
                 "brdf phong\nsphere 0 0 0 1\n",
            &sc);
    ck_assert_int_eq(sc.n_spheres, 5);
    ck_assert_int_eq(sc.n_materials, 5);
    const material *d = &sc.materials[sc.spheres[0].material];
    material def = scene_default_material();
    ck_assert_double_eq(d->ambient.g, def.ambient.g);
    ck_assert(rgb_is_black(d->diffuse));
    const material *m = &sc.materials[sc.spheres[1].material];
    ck_assert_double_eq(m->ambient.r, 0.1);
    ck_assert_double_eq(m->ambient.b, 0.3);
    ck_assert_double_eq(m->diffuse.g, 0.5);
    ck_assert_double_eq(m->specular.b, 0.9);
    ck_assert_double_eq(m->emission.r, 1);
    ck_assert_double_eq(m->emission.b, 3);
    ck_assert_double_eq(m->shininess, 50);
    ck_assert_int_eq(m->brdf, BRDF_GGX);
    ck_assert_double_eq(m->roughness, 0.25);
    ck_assert_double_eq(m->ior, 1.33);
    ck_assert_int_eq(sc.materials[sc.spheres[2].material].brdf, BRDF_MIRROR);
    ck_assert_int_eq(sc.materials[sc.spheres[3].material].brdf, BRDF_GLASS);
    ck_assert_int_eq(sc.materials[sc.spheres[4].material].brdf, BRDF_PHONG);
    /* the state carries over: the later spheres keep the earlier diffuse */
    ck_assert_double_eq(sc.materials[sc.spheres[4].material].diffuse.r, 0.4);
    scene_free(&sc);
}
END_TEST

START_TEST(test_materials_are_stored_once_until_the_state_changes)
{
    scene sc;
    load_ok(HEAD "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                 "diffuse 1 0 0\ntri 0 1 2\ntri 0 1 2\nsphere 0 0 0 1\n"
                 "diffuse 1 0 0\ntri 0 1 2\n"                /* same value: no new material */
                 "diffuse 0 1 0\ndiffuse 1 0 0\ntri 0 1 2\n" /* changed and back: none either */
                 "diffuse 0 0 1\ntri 0 1 2\n"                /* a real change */
                 "diffuse 1 0 0\nsphere 0 0 0 1\n",          /* back to the first: a third */
            &sc);
    ck_assert_int_eq(sc.n_triangles, 5);
    ck_assert_int_eq(sc.n_materials, 3);
    ck_assert_int_eq(sc.triangles[0].material, 0);
    ck_assert_int_eq(sc.triangles[1].material, 0);
    ck_assert_int_eq(sc.spheres[0].material, 0);
    ck_assert_int_eq(sc.triangles[2].material, 0);
    ck_assert_int_eq(sc.triangles[3].material, 0);
    ck_assert_int_eq(sc.triangles[4].material, 1);
    ck_assert_double_eq(sc.materials[1].diffuse.b, 1);
    ck_assert_int_eq(sc.spheres[1].material, 2);
    scene_free(&sc);
}
END_TEST

START_TEST(test_translate_then_rotate_rotates_the_object_first)
{
    /* right-multiplied: M = T R, so (1,0,0) -> R -> (0,1,0) -> T -> (1,1,0) */
    scene sc;
    load_ok(HEAD "translate 1 0 0\nrotate 0 0 1 90\nsphere 0 0 0 1\n"
                 "vertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\ntri 0 1 2\n",
            &sc);
    const sphere *s = &sc.spheres[0];
    assert_vec_near(s->center, 0, 0, 0);
    ck_assert_double_eq(s->radius, 1);
    assert_vec_near(mat4_point(&s->xf, vec3_make(1, 0, 0)), 1, 1, 0);
    assert_vec_near(mat4_point(&s->inv, vec3_make(1, 1, 0)), 1, 0, 0);
    const triangle *t = &sc.triangles[0];
    ck_assert_int_eq(t->has_normals, 0);
    assert_vec_near(t->p[0], 1, 1, 0);
    assert_vec_near(t->p[1], 0, 0, 0);
    assert_vec_near(t->p[2], 1, 0, 1);
    scene_free(&sc);
    /* the other order translates first: (1,0,0) -> (2,0,0) -> (0,2,0) */
    load_ok(HEAD "rotate 0 0 1 90\ntranslate 1 0 0\nsphere 0 0 0 1\n", &sc);
    assert_vec_near(mat4_point(&sc.spheres[0].xf, vec3_make(1, 0, 0)), 0, 2, 0);
    scene_free(&sc);
}
END_TEST

/* only a sphere read under the identity is marked untransformed (sphere.c then skips M^-1): one
 * under any transform, even one that a later pop undoes, is not, and one after the pop is */
START_TEST(test_sphere_is_marked_untransformed_only_under_the_identity)
{
    scene sc;
    load_ok(HEAD "sphere 1 2 3 1\npushTransform\ntranslate 1 0 0\nsphere 0 0 0 1\npopTransform\n"
                 "sphere 0 0 0 1\nscale 1 1 2\nsphere 0 0 0 1\nscale 1 1 0.5\nsphere 0 0 0 1\n"
                 "rotate 0 0 1 90\nsphere 0 0 0 1\n",
            &sc);
    ck_assert_int_eq(sc.n_spheres, 6);
    ck_assert_int_eq(sc.spheres[0].untransformed, 1);
    ck_assert_int_eq(sc.spheres[1].untransformed, 0); /* translate */
    ck_assert_int_eq(sc.spheres[2].untransformed, 1); /* popped back to the identity */
    ck_assert_int_eq(sc.spheres[3].untransformed, 0); /* scale */
    ck_assert_int_eq(sc.spheres[4].untransformed, 1); /* scale 2 then 0.5: exactly I again */
    ck_assert_int_eq(sc.spheres[5].untransformed, 0); /* rotate */
    scene_free(&sc);
}
END_TEST

START_TEST(test_tri_uses_the_transform_current_at_tri_not_at_vertex)
{
    scene sc;
    load_ok(HEAD "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntranslate 0 0 5\ntri 0 1 2\n", &sc);
    assert_vec_near(sc.triangles[0].p[1], 1, 0, 5);
    scene_free(&sc);
}
END_TEST

/* `rotate` accepts any finite non-zero axis, however long or short (as `vertexnormal` and
 * `camera` do): 1e-300 was refused as "zero" and 1e200 collapsed the object to a point. */
START_TEST(test_rotate_takes_tiny_and_huge_axes_by_their_direction)
{
    static const char *const axes[] = {"1e-300 2e-300 3e-300", "1e-170 2e-170 3e-170",
                                       "1e200 2e200 3e200"};
    scene ref;
    load_ok(HEAD "rotate 1 2 3 90\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\ntri 0 1 2\n", &ref);
    for (int a = 0; a < 3; a++) {
        char text[512];
        snprintf(text, sizeof text,
                 HEAD "rotate %s 90\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\ntri 0 1 2\n",
                 axes[a]);
        scene sc;
        load_ok(text, &sc);
        for (int k = 0; k < 3; k++) {
            vec3 w = ref.triangles[0].p[k];
            assert_vec_near(sc.triangles[0].p[k], w.x, w.y, w.z);
        }
        scene_free(&sc);
    }
    scene_free(&ref);
    load_fails(HEAD "rotate 0 0 0 90\n", 3, "'rotate' axis is zero");
}
END_TEST

/* `directional` likewise: the direction of 1e200 or 1e-170 times (1, 2, 3) is that of (1, 2, 3)
 * (it was normalized to 0, a light that lit nothing, or refused as zero) */
START_TEST(test_directional_takes_tiny_and_huge_directions_by_their_direction)
{
    static const char *const dirs[] = {"1e-300 2e-300 3e-300", "1e-170 2e-170 3e-170",
                                       "1e200 2e200 3e200"};
    vec3 want = vec3_normalize(vec3_make(1, 2, 3));
    for (int a = 0; a < 3; a++) {
        char text[512];
        snprintf(text, sizeof text, HEAD "directional %s 1 1 1\n", dirs[a]);
        scene sc;
        load_ok(text, &sc);
        ck_assert_int_eq(sc.n_lights, 1);
        assert_vec_near(sc.lights[0].dir, want.x, want.y, want.z);
        scene_free(&sc);
    }
    load_fails(HEAD "directional 0 0 0 1 1 1\n", 3, "'directional' direction is zero");
}
END_TEST

START_TEST(test_pop_restores_the_transform_saved_by_push)
{
    scene sc;
    load_ok(HEAD "scale 2 2 2\npushTransform\ntranslate 5 0 0\npushTransform\nscale 3 1 1\n"
                 "popTransform\nsphere 0 0 0 1\npopTransform\nsphere 0 0 0 1\n",
            &sc);
    /* first: S(2) T(5,0,0): (1,0,0) -> (6,0,0) -> (12,0,0) */
    assert_vec_near(mat4_point(&sc.spheres[0].xf, vec3_make(1, 0, 0)), 12, 0, 0);
    /* second: S(2) only */
    assert_vec_near(mat4_point(&sc.spheres[1].xf, vec3_make(1, 0, 0)), 2, 0, 0);
    assert_vec_near(mat4_point(&sc.spheres[1].inv, vec3_make(2, 0, 0)), 1, 0, 0);
    scene_free(&sc);
}
END_TEST

START_TEST(test_a_scaled_sphere_keeps_an_ellipsoid_matrix_and_its_inverse)
{
    scene sc;
    load_ok(HEAD "scale 2 1 0.5\nsphere 1 0 0 3\n", &sc);
    const sphere *s = &sc.spheres[0];
    assert_vec_near(s->center, 1, 0, 0); /* object space, as written */
    ck_assert_double_eq(s->radius, 3);
    mat4 id = mat4_mul(s->xf, s->inv);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) ck_assert_near(id.m[i][j], i == j, 1e-12);
    assert_vec_near(mat4_point(&s->xf, vec3_make(0, 0, 3)), 0, 0, 1.5);
    scene_free(&sc);
}
END_TEST

START_TEST(test_trinormal_transforms_normals_by_the_inverse_transpose)
{
    scene sc;
    load_ok(HEAD "vertexnormal 0 0 0 1 1 0\nvertexnormal 1 0 0 0 0 3\nvertexnormal 0 1 0 0 0 1\n"
                 "scale 2 1 1\ntrinormal 0 1 2\n",
            &sc);
    const triangle *t = &sc.triangles[0];
    ck_assert_int_eq(t->has_normals, 1);
    assert_vec_near(t->p[1], 2, 0, 0);
    /* (M^-1)^T (1,1,0) = (0.5, 1, 0), normalised; a plain M would give (2, 1, 0) */
    double l = sqrt(0.25 + 1);
    assert_vec_near(t->n[0], 0.5 / l, 1 / l, 0);
    assert_vec_near(t->n[1], 0, 0, 1); /* unit even when written with length 3 */
    scene_free(&sc);
    /* normals of any finite length: 1e300 (its square overflows) and 1e-300 (underflows).
     * Catches a length from sqrt of squares ("degenerates under the current transform") */
    load_ok(HEAD "vertexnormal 0 0 0 1e300 1e300 0\nvertexnormal 1 0 0 0 0 1e-300\nvertexnormal 0 "
                 "1 0 0 0 1\n"
                 "trinormal 0 1 2\n",
            &sc);
    assert_vec_near(sc.triangles[0].n[0], sqrt(0.5), sqrt(0.5), 0);
    assert_vec_near(sc.triangles[0].n[1], 0, 0, 1);
    scene_free(&sc);
    /* a transform whose inverse transpose makes a unit normal ~1e300 long */
    load_ok(HEAD "vertexnormal 0 0 0 1 1 0\nvertexnormal 1 0 0 0 0 1\nvertexnormal 0 1 0 0 0 1\n"
                 "scale 1e-300 1 1\ntrinormal 0 1 2\n",
            &sc);
    assert_vec_near(sc.triangles[0].n[0], 1, 0, 0); /* (1e300, 1, 0) normalised */
    scene_free(&sc);
}
END_TEST

/* OBJ-to-scene converters write `vertexnormal 0 0 0 0 0 0` as a placeholder for OBJ's index 0,
 * which no trinormal uses: the scene loads (it was refused at that line).  A trinormal that does
 * use a zero normal is flat shaded, as an OBJ face with a degenerate normal. */
START_TEST(test_a_zero_vertexnormal_loads_and_a_trinormal_using_it_is_flat)
{
    scene sc;
    load_ok(HEAD "maxvertnorms 4\nvertexnormal 0 0 0 0 0 0\n"
                 "vertexnormal 0 0 0 0 0 1\nvertexnormal 1 0 0 0 0 1\nvertexnormal 0 1 0 1 0 0\n"
                 "trinormal 1 2 3\ntrinormal 0 2 3\n",
            &sc);
    ck_assert_int_eq(sc.n_triangles, 2);
    ck_assert_int_eq(sc.triangles[0].has_normals, 1);
    assert_vec_near(sc.triangles[0].n[2], 1, 0, 0);
    ck_assert_int_eq(sc.triangles[1].has_normals, 0); /* corner 0 has no normal */
    assert_vec_near(sc.triangles[1].p[1], 1, 0, 0);
    scene_free(&sc);
}
END_TEST

START_TEST(test_lights_are_in_world_space_and_point_takes_the_current_attenuation)
{
    scene sc;
    load_ok(HEAD "translate 5 0 0\nscale 2 2 2\n"
                 "directional 0 3 0 0.1 0.2 0.3\npoint 1 2 3 4 5 6\n"
                 "attenuation 0 1 0.5\npoint 0 0 0 1 1 1\n"
                 "quadLight 1 2 3 1 0 0 0 0 2 7 8 9\n",
            &sc);
    ck_assert_int_eq(sc.n_lights, 4);
    const scene_light *l = sc.lights;
    ck_assert_int_eq(l[0].kind, LIGHT_DIRECTIONAL);
    assert_vec_near(l[0].dir, 0, 1, 0); /* unit, towards the light, not transformed */
    ck_assert_double_eq(l[0].color.b, 0.3);
    ck_assert_int_eq(l[1].kind, LIGHT_POINT);
    assert_vec_near(l[1].pos, 1, 2, 3);
    ck_assert_double_eq(l[1].color.g, 5);
    ck_assert_double_eq(l[1].atten[0], 1);
    ck_assert_double_eq(l[1].atten[1], 0);
    ck_assert_double_eq(l[1].atten[2], 0);
    ck_assert_double_eq(l[2].atten[0], 0);
    ck_assert_double_eq(l[2].atten[1], 1);
    ck_assert_double_eq(l[2].atten[2], 0.5);
    ck_assert_int_eq(l[3].kind, LIGHT_QUAD);
    assert_vec_near(l[3].pos, 1, 2, 3);
    assert_vec_near(l[3].ab, 1, 0, 0);
    assert_vec_near(l[3].ac, 0, 0, 2);
    ck_assert_double_eq(l[3].color.r, 7);
    scene_free(&sc);
}
END_TEST

START_TEST(test_envmap_takes_file_scale_and_the_current_transform)
{
    scene sc;
    load_ok(HEAD "envmap sky.exr\n", &sc);
    ck_assert_int_eq(sc.envmap.present, 1);
    ck_assert_str_eq(sc.envmap.path, "sky.exr");
    ck_assert_double_eq(sc.envmap.scale, 1);
    ck_assert_int_eq(sc.envmap.line, 3);
    ck_assert_ptr_null(sc.envmap.img.px); /* load_images = 0 */
    assert_vec_near(mat4_dir(&sc.envmap.xf, vec3_make(0, 0, 1)), 0, 0, 1);
    scene_free(&sc);
    /* rotate 1 0 0 -90 gives a y-up world its sky overhead: envmap +z -> world +y */
    load_ok(HEAD "rotate 1 0 0 -90\nenvmap sky.exr 2.5\n", &sc);
    ck_assert_double_eq(sc.envmap.scale, 2.5);
    ck_assert_int_eq(sc.envmap.line, 4);
    assert_vec_near(mat4_dir(&sc.envmap.xf, vec3_make(0, 0, 1)), 0, 1, 0);
    assert_vec_near(mat4_dir(&sc.envmap.inv, vec3_make(0, 1, 0)), 0, 0, 1);
    scene_free(&sc);
}
END_TEST

START_TEST(test_envmap_paths_are_relative_to_the_scene_folder)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    scene sc;
    error err = {0};
    ck_assert_int_eq(
        scene_load_string(HEAD "envmap sky.exr\noutput out/a.png\n", "dir/x.test", &o, &sc, &err),
        0);
    ck_assert_str_eq(sc.envmap.path, "dir/sky.exr");
    ck_assert_str_eq(sc.output, "out/a.png"); /* output stays relative to the working folder */
    ck_assert_str_eq(sc.path, "dir/x.test");
    scene_free(&sc);
    ck_assert_int_eq(scene_load_string(HEAD "envmap /abs/sky.exr\n", "dir/x.test", &o, &sc, &err),
                     0);
    ck_assert_str_eq(sc.envmap.path, "/abs/sky.exr");
    scene_free(&sc);
    ck_assert_int_eq(
        scene_load_string(HEAD "envmap ../hdri/sky.exr\n", "a/b/x.test", &o, &sc, &err), 0);
    ck_assert_str_eq(sc.envmap.path, "a/b/../hdri/sky.exr");
    scene_free(&sc);
    /* no folder, "-" and NULL: the working folder */
    ck_assert_int_eq(scene_load_string(HEAD "envmap sky.exr\n", "x.test", &o, &sc, &err), 0);
    ck_assert_str_eq(sc.envmap.path, "sky.exr");
    scene_free(&sc);
    ck_assert_int_eq(scene_load_string(HEAD "envmap sky.exr\n", "-", &o, &sc, &err), 0);
    ck_assert_str_eq(sc.envmap.path, "sky.exr");
    scene_free(&sc);
    ck_assert_int_eq(scene_load_string(HEAD "envmap sky.exr\n", NULL, &o, &sc, &err), 0);
    ck_assert_str_eq(sc.envmap.path, "sky.exr");
    ck_assert_str_eq(sc.path, "");
    scene_free(&sc);
    ck_assert_int_eq(scene_load_string(HEAD "envmap sky.exr 0\n", NULL, &o, &sc, &err), -1);
    ck_assert_str_eq(err.file, "<string>");
}
END_TEST

START_TEST(test_scene_load_resolves_envmap_beside_a_scene_file)
{
    char dir[] = "/tmp/test_scene_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[256], want[256];
    snprintf(path, sizeof path, "%s/x.test", dir);
    snprintf(want, sizeof want, "%s/hdri/sky.exr", dir);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(HEAD "envmap hdri/sky.exr 3\r\n", f);
    fclose(f);
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    scene sc;
    error err = {0};
    ck_assert_int_eq(scene_load(path, &o, &sc, &err), 0);
    ck_assert_str_eq(sc.path, path);
    ck_assert_str_eq(sc.envmap.path, want);
    ck_assert_double_eq(sc.envmap.scale, 3);
    scene_free(&sc);
    unlink(path);
    rmdir(dir);
}
END_TEST

START_TEST(test_an_unreadable_envmap_is_an_error_at_its_line_with_the_reason)
{
    scene sc;
    error err = {0};
    ck_assert_int_eq(
        scene_load_string(HEAD "# sky\nenvmap missing.exr\n", "nowhere/x.test", NULL, &sc, &err),
        -1);
    ck_assert_str_eq(err.file, "nowhere/x.test");
    ck_assert_int_eq(err.line, 4);
    ck_assert_str_eq(err.msg,
                     "envmap 'missing.exr' (nowhere/missing.exr): cannot open: No such file or "
                     "directory");
    ck_assert_ptr_null(sc.envmap.img.px);
}
END_TEST

START_TEST(test_a_readable_envmap_is_loaded_when_images_are_on)
{
    char dir[] = "/tmp/test_scene_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char img_path[256], scene_path[256];
    snprintf(img_path, sizeof img_path, "%s/sky.pfm", dir);
    snprintf(scene_path, sizeof scene_path, "%s/x.test", dir);
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 4, 2, &err), 0);
    image_set(&im, 3, 1, rgb_make(0.25, 0.5, 2.0));
    ck_assert_msg(imageio_write(img_path, &im, NULL, &err) == 0, "%s", err.msg);
    image_free(&im);
    FILE *f = fopen(scene_path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(HEAD "envmap sky.pfm\n", f);
    fclose(f);
    scene sc;
    ck_assert_msg(scene_load(scene_path, NULL, &sc, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(sc.envmap.img.w, 4);
    ck_assert_int_eq(sc.envmap.img.h, 2);
    ck_assert_double_eq(image_get(&sc.envmap.img, 3, 1).b, 2.0);
    scene_free(&sc);
    ck_assert_ptr_null(sc.envmap.img.px);
    /* a scale that takes the brightest texel (2) past FLT_MAX is an error at the envmap's line
     * (catches a missing check: the map's radiance was Inf, and pixels NaN); up to it is fine */
    f = fopen(scene_path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(HEAD "envmap sky.pfm 1.8e38\n", f);
    fclose(f);
    ck_assert_int_eq(scene_load(scene_path, NULL, &sc, &err), -1);
    ck_assert_int_eq(err.line, 3);
    ck_assert_msg(strstr(err.msg, "above the largest float radiance"), "%s", err.msg);
    f = fopen(scene_path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(HEAD "envmap sky.pfm 1.6e38\n", f);
    fclose(f);
    ck_assert_msg(scene_load(scene_path, NULL, &sc, &err) == 0, "%s", err.msg);
    scene_free(&sc);
    unlink(scene_path);
    unlink(img_path);
    rmdir(dir);
}
END_TEST

/* A NaN, infinite or negative envmap texel would make every bilinear lookup that touches it NaN
 * (0 x NaN is NaN): the loader zeroes them once and says how many, at the envmap's line; a
 * texture's NaN and infinite values likewise (negative ones may be meant). */
START_TEST(test_bad_texels_are_zeroed_at_load_with_one_warning_each)
{
    char dir[] = "/tmp/test_scene_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char env_path[256], tex_path[256], scene_path[256];
    snprintf(env_path, sizeof env_path, "%s/sky.pfm", dir);
    snprintf(tex_path, sizeof tex_path, "%s/t.pfm", dir);
    snprintf(scene_path, sizeof scene_path, "%s/x.test", dir);
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 4, 2, &err), 0);
    image_set(&im, 0, 0, rgb_make(NAN, 1, 1));
    image_set(&im, 1, 0, rgb_make(1, -2, 1));
    image_set(&im, 2, 1, rgb_make(1, 1, INFINITY));
    ck_assert_msg(imageio_write(env_path, &im, NULL, &err) == 0, "%s", err.msg);
    ck_assert_msg(imageio_write(tex_path, &im, NULL, &err) == 0, "%s", err.msg);
    image_free(&im);
    FILE *f = fopen(scene_path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(HEAD "envmap sky.pfm\ntexture t t.pfm\ndiffusemap t\nsphere 0 0 0 1\n", f);
    fclose(f);
    warnings ws;
    scene_load_opts o = opts_counting(&ws);
    o.load_images = 1;
    scene sc;
    ck_assert_msg(scene_load(scene_path, &o, &sc, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(ws.n, 2);
    ck_assert_int_eq(ws.last.line, 3); /* textures are read first, the envmap last */
    ck_assert_msg(strstr(ws.last.msg, "envmap 'sky.pfm': 3 NaN, infinite or negative texel values"),
                  "%s", ws.last.msg);
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 4; x++) {
            rgb c = image_get(&sc.envmap.img, x, y);
            ck_assert(isfinite(c.r) && isfinite(c.g) && isfinite(c.b) && c.r >= 0 && c.g >= 0 &&
                      c.b >= 0);
        }
    ck_assert_double_eq(image_get(&sc.envmap.img, 0, 0).r, 0.0);
    ck_assert_double_eq(image_get(&sc.envmap.img, 1, 0).g, 0.0);
    ck_assert_double_eq(image_get(&sc.envmap.img, 0, 0).g, 1.0);
    ck_assert_double_eq(image_get(&sc.texture_images[0], 1, 0).g, -2.0); /* kept in a texture */
    ck_assert_double_eq(image_get(&sc.texture_images[0], 2, 1).b, 0.0);
    scene_free(&sc);
    unlink(scene_path);
    unlink(env_path);
    unlink(tex_path);
    rmdir(dir);
}
END_TEST

START_TEST(test_envmap_keyword_names_the_representation_after_an_optional_scale)
{
    static const struct {
        const char *line;
        convert_kind kind;
        double scale;
    } cases[] = {
        {"envmap p.exr mirrorball\n", CONVERT_MIRRORBALL, 1},
        {"envmap p.exr 3 angular\n", CONVERT_ANGULAR, 3},
        {"envmap p.exr 0.5 latlong\n", CONVERT_LATLONG, 0.5},
        {"envmap p.exr cross\n", CONVERT_CUBE, 1}, /* one image: a cross */
        {"envmap p.exr cube\n", CONVERT_CUBE, 1},  /* the same */
        {"envmap p.exr cylindrical\n", CONVERT_CYLINDRICAL, 1},
        {"envmap p.exr 2 equalarea\n", CONVERT_EQUALAREA, 2},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[256];
        snprintf(text, sizeof text, HEAD "%s", cases[i].line);
        scene sc;
        load_ok(text, &sc);
        ck_assert_int_eq(sc.envmap.kind, cases[i].kind);
        ck_assert_int_eq(sc.envmap.kind_given, 1);
        ck_assert_int_eq(sc.envmap.six_files, 0);
        ck_assert_double_eq(sc.envmap.scale, cases[i].scale);
        ck_assert_str_eq(sc.envmap.path, "p.exr");
        scene_free(&sc);
    }
    /* no keyword: detected when the image is read; a file named "cube" alone is a file */
    scene sc;
    load_ok(HEAD "envmap cube\n", &sc);
    ck_assert_int_eq(sc.envmap.kind_given, 0);
    ck_assert_int_eq(sc.envmap.six_files, 0);
    ck_assert_str_eq(sc.envmap.path, "cube");
    scene_free(&sc);
}
END_TEST

START_TEST(test_envmap_cube_takes_six_faces_relative_to_the_scene_folder)
{
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    scene sc;
    error err = {0};
    ck_assert_int_eq(scene_load_string(HEAD "envmap cube px.exr nx.exr py.exr ny.exr pz.exr "
                                            "/abs/nz.exr 2\n",
                                       "dir/x.test", &o, &sc, &err),
                     0);
    ck_assert_int_eq(sc.envmap.kind, CONVERT_CUBE);
    ck_assert_int_eq(sc.envmap.six_files, 1);
    ck_assert_int_eq(sc.envmap.kind_given, 1);
    ck_assert_double_eq(sc.envmap.scale, 2);
    ck_assert_str_eq(sc.envmap.face_path[0], "dir/px.exr");
    ck_assert_str_eq(sc.envmap.face_path[3], "dir/ny.exr");
    ck_assert_str_eq(sc.envmap.face_path[5], "/abs/nz.exr");
    ck_assert_str_eq(sc.envmap.path, "dir/px.exr");
    scene_free(&sc);
    /* without the scale */
    load_ok(HEAD "envmap cube a b c d e f\n", &sc);
    ck_assert_double_eq(sc.envmap.scale, 1);
    ck_assert_str_eq(sc.envmap.face_path[4], "e");
    scene_free(&sc);
}
END_TEST

/* A folder with images for the loading tests below. */
typedef struct img_dir {
    char dir[64];
    char scene[128];
} img_dir;

static void img_dir_make(img_dir *d)
{
    snprintf(d->dir, sizeof d->dir, "/tmp/test_scene_XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(d->dir));
    snprintf(d->scene, sizeof d->scene, "%s/x.test", d->dir);
}

/* Write a w x h PFM named `name` in the folder, every texel `value`. */
static void img_write(const img_dir *d, const char *name, int w, int h, double value)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", d->dir, name);
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, w, h, &err), 0);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) image_set(&im, x, y, rgb_gray(value));
    ck_assert_msg(imageio_write(path, &im, NULL, &err) == 0, "%s", err.msg);
    image_free(&im);
}

/* Load a scene of HEAD + `line` from the folder with images on: 0 or -1 and *err. */
static int img_scene_load(const img_dir *d, const char *line, scene *sc, error *err)
{
    FILE *f = fopen(d->scene, "w");
    ck_assert_ptr_nonnull(f);
    fputs(HEAD, f);
    fputs(line, f);
    fclose(f);
    return scene_load(d->scene, NULL, sc, err);
}

static void img_dir_remove(img_dir *d)
{
    char cmd[160];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", d->dir);
    ck_assert_int_eq(system(cmd), 0);
}

START_TEST(test_envmap_representation_is_detected_from_the_image_shape)
{
    img_dir d;
    img_dir_make(&d);
    img_write(&d, "ll.pfm", 8, 4, 1);
    img_write(&d, "hcross.pfm", 8, 6, 2);
    img_write(&d, "vcross.pfm", 6, 8, 3);
    scene sc;
    error err = {0};
    ck_assert_msg(img_scene_load(&d, "envmap ll.pfm\n", &sc, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(sc.envmap.kind, CONVERT_LATLONG);
    ck_assert_int_eq(sc.envmap.img.w, 8);
    scene_free(&sc);
    /* a 4:3 cross is split into six 2 x 2 faces; the cross itself is not kept */
    ck_assert_msg(img_scene_load(&d, "envmap hcross.pfm\n", &sc, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(sc.envmap.kind, CONVERT_CUBE);
    ck_assert_int_eq(sc.envmap.cube.size, 2);
    ck_assert_ptr_null(sc.envmap.img.px);
    ck_assert_double_eq(image_get(&sc.envmap.cube.face[CUBEMAP_POS_Z], 1, 1).r, 2);
    scene_free(&sc);
    ck_assert_ptr_null(sc.envmap.cube.face[0].px);
    ck_assert_msg(img_scene_load(&d, "envmap vcross.pfm 2\n", &sc, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(sc.envmap.kind, CONVERT_CUBE);
    ck_assert_int_eq(sc.envmap.cube.size, 2);
    ck_assert_double_eq(sc.envmap.scale, 2);
    scene_free(&sc);
    /* a keyword overrides the shape: a 2:1 image read as an equal-area map */
    ck_assert_msg(img_scene_load(&d, "envmap ll.pfm equalarea\n", &sc, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(sc.envmap.kind, CONVERT_EQUALAREA);
    ck_assert_int_eq(sc.envmap.img.w, 8);
    scene_free(&sc);
    img_dir_remove(&d);
}
END_TEST

START_TEST(test_a_square_envmap_without_a_keyword_is_an_error_naming_file_and_line)
{
    img_dir d;
    img_dir_make(&d);
    img_write(&d, "probe.pfm", 8, 8, 1);
    img_write(&d, "wide.pfm", 9, 3, 1);
    scene sc;
    error err = {0};
    ck_assert_int_eq(img_scene_load(&d, "# a probe\nenvmap probe.pfm\n", &sc, &err), -1);
    ck_assert_str_eq(err.file, d.scene);
    ck_assert_int_eq(err.line, 4);
    ck_assert_msg(strstr(err.msg, "envmap 'probe.pfm'") &&
                      strstr(err.msg, "square image (8 x 8)") && strstr(err.msg, "mirrorball") &&
                      strstr(err.msg, "angular"),
                  "%s", err.msg);
    ck_assert_ptr_null(sc.envmap.img.px);
    ck_assert_int_eq(img_scene_load(&d, "envmap wide.pfm\n", &sc, &err), -1);
    ck_assert_int_eq(err.line, 3);
    ck_assert_msg(strstr(err.msg, "cannot tell the representation of a 9 x 3 image"), "%s",
                  err.msg);
    /* named, both load */
    ck_assert_msg(img_scene_load(&d, "envmap probe.pfm mirrorball\n", &sc, &err) == 0, "%s",
                  err.msg);
    ck_assert_int_eq(sc.envmap.kind, CONVERT_MIRRORBALL);
    scene_free(&sc);
    ck_assert_msg(img_scene_load(&d, "envmap wide.pfm cylindrical\n", &sc, &err) == 0, "%s",
                  err.msg);
    ck_assert_int_eq(sc.envmap.kind, CONVERT_CYLINDRICAL);
    ck_assert_double_eq_tol(sc.envmap.max_height, M_PI * 3 / 9, 1e-15); /* square horizon texels */
    scene_free(&sc);
    /* "cross" on an image that is not one: the splitter's reason */
    ck_assert_int_eq(img_scene_load(&d, "envmap probe.pfm cross\n", &sc, &err), -1);
    ck_assert_int_eq(err.line, 3);
    ck_assert_msg(strstr(err.msg, "envmap 'probe.pfm'") && strstr(err.msg, "8 x 8"), "%s", err.msg);
    img_dir_remove(&d);
}
END_TEST

START_TEST(test_six_cube_faces_load_and_a_bad_face_is_named)
{
    img_dir d;
    img_dir_make(&d);
    static const char *const names[6] = {"px.pfm", "nx.pfm", "py.pfm",
                                         "ny.pfm", "pz.pfm", "nz.pfm"};
    for (int f = 0; f < 6; f++) img_write(&d, names[f], 4, 4, f + 1);
    img_write(&d, "small.pfm", 2, 2, 1);
    img_write(&d, "flat.pfm", 4, 2, 1);
    scene sc;
    error err = {0};
    ck_assert_msg(img_scene_load(&d, "envmap cube px.pfm nx.pfm py.pfm ny.pfm pz.pfm nz.pfm 2\n",
                                 &sc, &err) == 0,
                  "%s", err.msg);
    ck_assert_int_eq(sc.envmap.kind, CONVERT_CUBE);
    ck_assert_int_eq(sc.envmap.cube.size, 4);
    for (int f = 0; f < 6; f++)
        ck_assert_double_eq(image_get(&sc.envmap.cube.face[f], 3, 0).g, f + 1);
    scene_free(&sc);
    /* faces of different sizes, a face that is not square, a missing face: each named */
    ck_assert_int_eq(
        img_scene_load(&d, "envmap cube px.pfm nx.pfm py.pfm small.pfm pz.pfm nz.pfm\n", &sc, &err),
        -1);
    ck_assert_int_eq(err.line, 3);
    ck_assert_msg(strstr(err.msg, "'small.pfm'") && strstr(err.msg, "differ in size"), "%s",
                  err.msg);
    ck_assert_ptr_null(sc.envmap.cube.face[0].px);
    ck_assert_int_eq(
        img_scene_load(&d, "envmap cube px.pfm nx.pfm py.pfm ny.pfm flat.pfm nz.pfm\n", &sc, &err),
        -1);
    ck_assert_msg(strstr(err.msg, "'flat.pfm'") && strstr(err.msg, "square, not 4 x 2"), "%s",
                  err.msg);
    ck_assert_int_eq(
        img_scene_load(&d, "envmap cube px.pfm nx.pfm py.pfm ny.pfm pz.pfm gone.pfm\n", &sc, &err),
        -1);
    ck_assert_msg(strstr(err.msg, "'gone.pfm'") && strstr(err.msg, "No such file"), "%s", err.msg);
    /* a scale that takes the brightest face's texel (6) past the largest float */
    ck_assert_int_eq(img_scene_load(&d,
                                    "envmap cube px.pfm nx.pfm py.pfm ny.pfm pz.pfm nz.pfm 1e38\n",
                                    &sc, &err),
                     -1);
    ck_assert_msg(strstr(err.msg, "scale 1e+38 times its brightest texel 6"), "%s", err.msg);
    ck_assert_ptr_null(sc.envmap.cube.face[0].px);
    img_dir_remove(&d);
}
END_TEST

START_TEST(test_a_100k_triangle_mesh_parses_with_one_material)
{
    enum { N = 225 }; /* N x N vertices, 2 (N-1)^2 = 100352 triangles */
    size_t cap = (size_t)N * N * 40 + (size_t)(N - 1) * (N - 1) * 2 * 32 + 256;
    char *text = malloc(cap);
    ck_assert_ptr_nonnull(text);
    char *w = text + sprintf(text, HEAD "diffuse 0.5 0.5 0.5\n");
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) w += sprintf(w, "vertex %d %d 0\n", x, y);
    for (int y = 0; y + 1 < N; y++)
        for (int x = 0; x + 1 < N; x++) {
            int a = y * N + x;
            w += sprintf(w, "tri %d %d %d\ntri %d %d %d\n", a, a + 1, a + N + 1, a, a + N + 1,
                         a + N);
        }
    ck_assert_uint_lt((size_t)(w - text), cap);
    scene sc;
    load_ok(text, &sc);
    ck_assert_int_eq(sc.n_triangles, 2L * (N - 1) * (N - 1));
    ck_assert_int_eq(sc.n_materials, 1);
    const triangle *last = &sc.triangles[sc.n_triangles - 1];
    assert_vec_near(last->p[0], N - 2, N - 2, 0);
    assert_vec_near(last->p[2], N - 2, N - 1, 0);
    scene_free(&sc);
    free(text);
}
END_TEST

START_TEST(test_scene_free_is_safe_twice_and_on_a_zeroed_scene)
{
    scene sc;
    memset(&sc, 0, sizeof sc);
    scene_free(&sc);
    load_ok(HEAD "sphere 0 0 0 1\n", &sc);
    scene_free(&sc);
    scene_free(&sc);
    ck_assert_ptr_null(sc.spheres);
    ck_assert_int_eq(sc.n_spheres, 0);
}
END_TEST

/* ---- texture mapping (envtex) ----------------------------------------------------------- */

START_TEST(test_tritex_keeps_object_corners_world_corners_and_st)
{
    scene sc;
    load_ok(HEAD "vertextex 0 0 0 0 0\nvertextex 1 0 0 2 0\nvertextex 0 1 0 0 0.5\n"
                 "translate 0 0 -3\ntritex 0 1 2\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                 "tri 0 1 2\n",
            &sc);
    ck_assert_int_eq(sc.n_triangles, 2);
    const triangle *t = &sc.triangles[0];
    ck_assert_int_eq(t->has_st, 1);
    ck_assert_double_eq(t->st[1].u, 2);
    ck_assert_double_eq(t->st[2].v, 0.5);
    assert_vec_near(t->q[1], 1, 0, 0);  /* object space: as written */
    assert_vec_near(t->p[1], 1, 0, -3); /* world: transformed */
    /* a plain tri: no st given, defaults make st = (b1, b2); object corners kept */
    t = &sc.triangles[1];
    ck_assert_int_eq(t->has_st, 0);
    ck_assert_double_eq(t->st[1].u, 1);
    ck_assert_double_eq(t->st[2].v, 1);
    assert_vec_near(t->q[2], 0, 1, 0);
    scene_free(&sc);
    load_fails(HEAD "vertextex 0 0 0 0 0\ntritex 0 0 1\n", 4,
               "'tritex' vertex index '1' is out of range: 1 textured vertices");
    load_fails(HEAD "vertextex 0 0 0 0\n", 3, "'vertextex' takes 5 arguments");
    load_fails(HEAD "vertextex 0 0 0 0 nan\n", 3, "'nan'");
}
END_TEST

/* A mirroring transform (odd number of negative scale factors) turns counter-clockwise corners
 * clockwise: the stored triangle must still have (p1 - p0) x (p2 - p0) pointing outward, along
 * (M^-1)^T (e1 x e2) of the corners as written, and each stored corner must keep its own object
 * corner, st and normal.  Catches corners stored as transformed (the mirrored triangle's normal
 * then points inward: glass refracts the wrong way, docs/scene-format.md). */
START_TEST(test_a_mirroring_transform_keeps_triangles_counter_clockwise_from_outside)
{
    static const char *const xfs[] = {"", "scale -1 1 1\n", "scale -1 -1 1\n", "scale 1 1 -2\n",
                                      "rotate 1 2 3 40\nscale -1 -1 -1\n"};
    for (int x = 0; x < 5; x++) {
        char text[1024];
        snprintf(text, sizeof text,
                 HEAD
                 "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                 "vertextex 0 0 0 0.1 0.2\nvertextex 1 0 0 0.3 0.4\nvertextex 0 1 0 0.5 0.6\n"
                 "vertexnormal 0 0 0 1 0 1\nvertexnormal 1 0 0 0 1 1\nvertexnormal 0 1 0 0 0 1\n"
                 "%stri 0 1 2\ntritex 0 1 2\ntrinormal 0 1 2\n",
                 xfs[x]);
        scene sc;
        load_ok(text, &sc);
        ck_assert_int_eq(sc.n_triangles, 3);
        mat4 m = mat4_identity(), inv;
        if (x == 1) m = mat4_scale(vec3_make(-1, 1, 1));
        if (x == 2) m = mat4_scale(vec3_make(-1, -1, 1));
        if (x == 3) m = mat4_scale(vec3_make(1, 1, -2));
        if (x == 4)
            m = mat4_mul(mat4_rotate(vec3_make(1, 2, 3), 40), mat4_scale(vec3_make(-1, -1, -1)));
        ck_assert_int_eq(mat4_inverse(m, &inv), 0);
        /* outward: the object's +z (counter-clockwise corners) through the inverse transpose */
        vec3 out = vec3_normalize(mat4_normal(&inv, vec3_make(0, 0, 1)));
        const double st[3][2] = {{0.1, 0.2}, {0.3, 0.4}, {0.5, 0.6}};
        const vec3 nobj[3] = {{1, 0, 1}, {0, 1, 1}, {0, 0, 1}};
        for (int i = 0; i < 3; i++) {
            const triangle *t = &sc.triangles[i];
            vec3 ng =
                vec3_normalize(vec3_cross(vec3_sub(t->p[1], t->p[0]), vec3_sub(t->p[2], t->p[0])));
            ck_assert_msg(vec3_dot(ng, out) > 1 - 1e-12,
                          "transform %d, triangle %d: normal (%g %g %g), "
                          "outward (%g %g %g)",
                          x, i, ng.x, ng.y, ng.z, out.x, out.y, out.z);
            for (int k = 0; k < 3; k++) {
                vec3 q = t->q[k], pw = mat4_point(&m, q);
                assert_vec_near(t->p[k], pw.x, pw.y, pw.z); /* world corner = M object corner */
                int c = q.x == 1 ? 1 : q.y == 1 ? 2 : 0;    /* which corner as written */
                if (i == 0) { /* tri: st = (b1, b2) of the corners as written */
                    ck_assert_double_eq(t->st[k].u, c == 1);
                    ck_assert_double_eq(t->st[k].v, c == 2);
                }
                if (i == 1) {
                    ck_assert_double_eq(t->st[k].u, st[c][0]);
                    ck_assert_double_eq(t->st[k].v, st[c][1]);
                }
                if (i == 2) {
                    vec3 n = vec3_normalize(mat4_normal(&inv, nobj[c]));
                    assert_vec_near(t->n[k], n.x, n.y, n.z);
                }
            }
        }
        scene_free(&sc);
    }
}
END_TEST

START_TEST(test_map_commands_are_material_state_stored_once)
{
    scene sc;
    load_ok(HEAD "texture c checker 4 0 0 0 1 1 1\ntexture w wood 2 8 0.5 0.4 0.2 0 0.8 0.5 0.2\n"
                 "sphere 0 0 0 1\n"
                 "diffusemap c\nsphere 0 0 0 1\nsphere 1 0 0 1\n"
                 "bumpmap w 0.25\ntexmapping cube\ntexfilter ewa\nsphere 2 0 0 1\n"
                 "nomaps\nsphere 3 0 0 1\n",
            &sc);
    ck_assert_int_eq(sc.n_textures, 2);
    ck_assert_int_eq(sc.n_materials, 4);
    ck_assert_int_eq(sc.spheres[1].material, sc.spheres[2].material); /* dedup still works */
    const material *m0 = &sc.materials[sc.spheres[0].material];
    ck_assert_int_eq(m0->diffusemap, 0);
    ck_assert_ptr_null(scene_map(&sc, m0->diffusemap));
    ck_assert_int_eq(m0->texfilter, TEXFILTER_TRILINEAR); /* the default */
    ck_assert_int_eq(scene_material_texmapping(m0, 1), TEXMAPPING_SPHERICAL);
    ck_assert_int_eq(scene_material_texmapping(m0, 0), TEXMAPPING_UV);
    const material *m1 = &sc.materials[sc.spheres[1].material];
    ck_assert_ptr_eq(scene_map(&sc, m1->diffusemap), &sc.textures[0].tex);
    const material *m2 = &sc.materials[sc.spheres[3].material];
    ck_assert_ptr_eq(scene_map(&sc, m2->bumpmap), &sc.textures[1].tex);
    ck_assert_double_eq(m2->bump_strength, 0.25);
    ck_assert_int_eq(m2->texfilter, TEXFILTER_EWA);
    ck_assert_int_eq(scene_material_texmapping(m2, 0), TEXMAPPING_CUBE);
    const material *m3 = &sc.materials[sc.spheres[4].material];
    ck_assert_int_eq(m3->diffusemap + m3->bumpmap, 0);
    ck_assert_int_eq(m3->texfilter, TEXFILTER_EWA); /* nomaps clears maps only */
    ck_assert_int_ne(sc.spheres[4].material, sc.spheres[0].material);
    scene_free(&sc);
    /* `texmapping uv` on a sphere is its natural, spherical parameterization */
    load_ok(HEAD "texmapping uv\ntexture d displace.png\ndisplacementmap d -0.5\nsphere 0 0 0 1\n",
            &sc);
    const material *m = &sc.materials[sc.spheres[0].material];
    ck_assert_int_eq(scene_material_texmapping(m, 1), TEXMAPPING_SPHERICAL);
    ck_assert_double_eq(m->displacement_scale, -0.5);
    ck_assert_int_eq(sc.textures[0].tex.kind, TEXTURE_IMAGE);
    ck_assert_str_eq(sc.textures[0].path, "displace.png");
    scene_free(&sc);
}
END_TEST

START_TEST(test_procedural_textures_take_their_documented_parameters)
{
    scene sc;
    load_ok(HEAD "texture a checker 8 0 0 0 1 1 1\n"
                 "texture b perlin 3 0 0 0 1 1 1\n"
                 "texture c fbm 2 6 0 0 0 1 1 1\n"
                 "texture d turbulence 2 5 0 0 0 1 1 1\n"
                 "texture e marble 1.5 4 8 6 0.1 0.1 0.1 0.9 0.9 0.9\n"
                 "texture f wood 2 8 0.5 0.4 0.2 0 0.8 0.5 0.2\n"
                 "texture g img.exr clamp\n",
            &sc);
    ck_assert_int_eq(sc.n_textures, 7);
    ck_assert_int_eq(sc.textures[0].tex.kind, TEXTURE_CHECKER);
    ck_assert_double_eq(sc.textures[0].tex.frequency, 8);
    ck_assert_int_eq(sc.textures[2].tex.solid.octaves, 6);
    ck_assert_double_eq(sc.textures[3].tex.solid.scale, 2);
    const texture_solid_params *mb = &sc.textures[4].tex.solid;
    ck_assert_double_eq(mb->frequency, 4);
    ck_assert_double_eq(mb->amplitude, 8);
    ck_assert_int_eq(mb->octaves, 6);
    ck_assert_double_eq(mb->c1.g, 0.9);
    ck_assert_double_eq(sc.textures[5].tex.solid.rings, 8);
    ck_assert_int_eq(sc.textures[6].wrap, WRAP_CLAMP);
    ck_assert_int_eq(sc.textures[6].line, 9);
    scene_free(&sc);
}
END_TEST

START_TEST(test_texture_errors_name_their_line_and_token)
{
    load_fails(HEAD "diffusemap nothing\n", 3, "unknown texture 'nothing'");
    load_fails(HEAD "texture a checker 8 0 0 0 1 1 1\ntexture a perlin 1 0 0 0 1 1 1\n", 4,
               "texture 'a' defined twice (first at line 3)");
    load_fails(HEAD "texture a checker 8 0 0 0 1 1\n", 3, "takes FREQUENCY R0 G0 B0 R1 G1 B1");
    load_fails(HEAD "texture a checker 8 0 0 0 1 1 1 9\n", 3,
               "(7 arguments after the kind), got 8");
    load_fails(HEAD "texture a checker 0 0 0 0 1 1 1\n", 3, "must be > 0, got '0'");
    load_fails(HEAD "texture a fbm 1 0 0 0 0 1 1 1\n", 3, "must be in [1, 30], got '0'");
    load_fails(HEAD "texture a fbm 1 2.5 0 0 0 1 1 1\n", 3, "expected an integer");
    load_fails(HEAD "texture a wood 1 -8 0 0 0 0 1 1 1\n", 3, "got '-8'");
    load_fails(HEAD "texture a perlin 1 0 0 0 1 1 -1\n", 3, "got '-1'");
    load_fails(HEAD "texture a img.png wrap\n", 3,
               "wrap mode must be 'repeat', 'clamp' or "
               "'mirror', got 'wrap'");
    load_fails(HEAD "texture a img.png clamp x\n", 3, "got 'x' after it");
    load_fails(HEAD "texture a\n", 3,
               "'texture' takes NAME FILE [WRAP] or NAME KIND PARAMS... "
               "R0 G0 B0 R1 G1 B1, got 1 argument");
    load_fails(HEAD "texture a marble 1 2 3 4 0 0 0 1 1 1 9\n", 3,
               "'texture' takes NAME FILE "
               "[WRAP] or NAME KIND PARAMS... R0 G0 B0 R1 G1 B1, got 13 arguments");
    load_fails(HEAD "texmapping sphere\n", 3, "got 'sphere'");
    load_fails(HEAD "texfilter linear\n", 3, "got 'linear'");
    load_fails(HEAD "texture t checker 1 0 0 0 1 1 1\nbumpmap t\n", 4, "takes 2 arguments");
    load_fails(HEAD "texture t checker 1 0 0 0 1 1 1\nbumpmap t abc\n", 4, "'abc'");
}
END_TEST

/* A file is read a chunk (64 KB) at a time, and a line may straddle chunks: the byte-order mark
 * and a first line at the limit across the first boundary, a '\n' as the last byte of one chunk,
 * a CRLF split between two, and a last line without '\n'.  The file must give the same scene as
 * the same text parsed from a string.  Catches a chunk-joining error (a line cut in two, a
 * byte dropped or doubled at a boundary) and a first line that may not carry its BOM. */
START_TEST(test_a_scene_file_is_read_across_its_chunks_as_one_text)
{
    const size_t chunk = 65536;
    size_t cap = 4 * chunk + 4096, n = 0;
    char *text = malloc(cap);
    ck_assert_ptr_nonnull(text);
    memcpy(text, "\xEF\xBB\xBF#", 4); /* the first line: BOM + SCENE_MAX_LINE bytes, over 64 KB */
    memset(text + 4, ' ', SCENE_MAX_LINE - 1);
    n = 3 + SCENE_MAX_LINE;
    text[n++] = '\n';
    n += (size_t)sprintf(text + n, HEAD "sphere 1 2 3 0.5\n");
    /* a comment up to a '\n' that is the last byte of the second chunk, then a sphere */
    text[n++] = '#';
    while (n < 2 * chunk - 1) text[n++] = 'x';
    text[n++] = '\n';
    n += (size_t)sprintf(text + n, "sphere 4 5 6 0.25\n");
    /* a comment ending in a CRLF whose '\r' ends the third chunk; a sphere across the fourth */
    text[n++] = '#';
    while (n < 3 * chunk - 1) text[n++] = 'y';
    text[n++] = '\r';
    text[n++] = '\n';
    text[n++] = '#';
    while (n < 4 * chunk - 10) text[n++] = 'z';
    text[n++] = '\n';
    n += (size_t)sprintf(text + n, "sphere 7 8 9 1.75"); /* the last line: no '\n' */
    text[n] = '\0';

    char dir[] = "/tmp/test_scene_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[512];
    snprintf(path, sizeof path, "%s/chunks.test", dir);
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(text, 1, n, f), n);
    fclose(f);
    scene_load_opts o = scene_load_defaults();
    o.load_images = 0;
    scene from_file, from_string;
    error err = {0};
    ck_assert_msg(scene_load(path, &o, &from_file, &err) == 0, "%s:%d: %s", err.file, err.line,
                  err.msg);
    load_ok(text, &from_string);
    ck_assert_int_eq(from_file.n_spheres, 3);
    ck_assert_int_eq(from_string.n_spheres, 3);
    const double want[3][4] = {{1, 2, 3, 0.5}, {4, 5, 6, 0.25}, {7, 8, 9, 1.75}};
    for (int k = 0; k < 3; k++) {
        const sphere *a = &from_file.spheres[k], *b = &from_string.spheres[k];
        assert_vec_near(a->center, want[k][0], want[k][1], want[k][2]);
        ck_assert_double_eq(a->radius, want[k][3]);
        assert_vec_near(b->center, want[k][0], want[k][1], want[k][2]);
        ck_assert_double_eq(b->radius, want[k][3]);
    }
    scene_free(&from_file);
    scene_free(&from_string);
    /* a first line of 65537 bytes is too long, at line 1: without a BOM it may not use the
     * BOM's 3 bytes, and after one (left out) a reader that lets it through writes past its
     * line buffer (make asan sees that) */
    static const char *const bom[] = {"", "\xEF\xBB\xBF"};
    for (int b = 0; b < 2; b++) {
        f = fopen(path, "wb");
        ck_assert_ptr_nonnull(f);
        fputs(bom[b], f);
        fputc('#', f);
        for (int k = 0; k < SCENE_MAX_LINE; k++) fputc(' ', f);
        fputs("\n" HEAD, f);
        fclose(f);
        load_file_fails(path, 1, "line is longer than 65536 bytes");
    }
    unlink(path);
    rmdir(dir);
    free(text);
}
END_TEST

/* A file that never ends (/dev/zero) is refused at its first NUL byte, line 1, instead of read
 * until memory runs out (the whole file used to be read before the NUL check).  Catches a
 * reader that checks only after the end of the file: this test then runs out of memory or time. */
/* A pipe that never ends (a child writes zeros until the pipe is closed): the reader checks each
 * line as it arrives, so it fails at the first byte instead of filling memory. */
START_TEST(test_an_endless_binary_stream_is_refused_at_its_first_nul)
{
    int fds[2];
    ck_assert_int_eq(pipe(fds), 0);
    pid_t child = fork();
    ck_assert_int_ge(child, 0);
    if (child == 0) {
        close(fds[0]);
        static const char zeros[4096];
        while (write(fds[1], zeros, sizeof zeros) > 0) {}
        _exit(0); /* the reader closed its end: EPIPE (or SIGPIPE) */
    }
    close(fds[1]);
    char path[64];
    snprintf(path, sizeof path, "/dev/fd/%d", fds[0]);
    load_file_fails(path, 1, "NUL byte");
    close(fds[0]);
    ck_assert_int_eq(waitpid(child, NULL, 0), child);
}
END_TEST

/* A device, a folder or a FIFO nobody writes to: one line, and no read that could block.  Only
 * regular files and pipes are scenes (infile_open_stream). */
START_TEST(test_a_device_or_folder_is_no_scene_and_a_silent_fifo_reads_as_empty)
{
    if (access("/dev/zero", R_OK) == 0) load_file_fails("/dev/zero", 0, "it is a character device");
    load_file_fails("/", 0, "it is a directory, not a regular file or a pipe");
    char fifo[] = "/tmp/envtex_fifo_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(fifo));
    char path[64];
    snprintf(path, sizeof path, "%s/f", fifo);
    ck_assert_int_eq(mkfifo(path, 0600), 0);
    load_file_fails(path, 0, "no 'size' command"); /* no writer: end of file at once */
    unlink(path);
    rmdir(fifo);
}
END_TEST

/* Write `text` to dir/name. */
static void write_file(const char *dir, const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(text, f);
    fclose(f);
}

static void remove_file(const char *dir, const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    unlink(path);
}

START_TEST(test_obj_meshes_load_under_the_transform_and_material)
{
    char dir[] = "/tmp/test_scene_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    write_file(dir, "quad.obj",
               "o quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
               "vt 1 1\nvt 0 1\nvn 0 0 2\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf 1 2 4\n");
    write_file(dir, "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
    write_file(dir, "x.test", HEAD "diffuse 1 0 0\nscale 2 2 2\nobj quad.obj\nobj bad.obj\n");
    char path[512];
    snprintf(path, sizeof path, "%s/x.test", dir);
    warnings ws;
    scene_load_opts o = opts_counting(&ws);
    scene sc;
    error err = {0};
    ck_assert_int_eq(scene_load(path, &o, &sc, &err), -1);
    /* the scene's FILE:LINE of the obj command, then the obj's own FILE:LINE and reason */
    ck_assert_str_eq(err.file, path);
    ck_assert_int_eq(err.line, 6);
    ck_assert_ptr_nonnull(strstr(err.msg, "obj 'bad.obj': "));
    ck_assert_ptr_nonnull(strstr(err.msg, "bad.obj:3: index 3 of 'f' is out of range"));
    write_file(dir, "x.test", HEAD "diffuse 1 0 0\nscale 2 2 2\nobj quad.obj\n");
    ws.n = 0;
    ck_assert_msg(scene_load(path, &o, &sc, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(sc.n_triangles, 3);
    ck_assert_int_eq(sc.n_materials, 1);
    ck_assert_double_eq(sc.materials[0].diffuse.r, 1);
    const triangle *t = &sc.triangles[1]; /* the fan's second: corners 1, 3, 4 */
    assert_vec_near(t->p[1], 2, 2, 0);
    assert_vec_near(t->q[1], 1, 1, 0);
    ck_assert_int_eq(t->has_st, 1);
    ck_assert_double_eq(t->st[2].v, 1);
    ck_assert_int_eq(t->has_normals, 1);
    assert_vec_near(t->n[0], 0, 0, 1); /* normalized after the inverse transpose */
    ck_assert_int_eq(sc.triangles[2].has_st, 0);
    ck_assert_int_eq(sc.triangles[2].has_normals, 0);
    ck_assert_int_eq(ws.n, 1); /* "o quad" skipped: one warning for the file */
    ck_assert_ptr_nonnull(strstr(ws.last.msg, "ignored"));
    scene_free(&sc);
    /* the scene's primitive limit covers the mesh */
    o.max_prims = 2;
    ck_assert_int_eq(scene_load(path, &o, &sc, &err), -1);
    ck_assert_int_eq(err.line, 5);
    /* counting the triangles already in the scene: 2 + 3 > 4 is refused before any is added */
    write_file(dir, "x.test",
               HEAD "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 2\ntri 0 1 2\n"
                    "obj quad.obj\n");
    o.max_prims = 4;
    ck_assert_int_eq(scene_load(path, &o, &sc, &err), -1);
    ck_assert_int_eq(err.line, 8);
    ck_assert_msg(
        strstr(err.msg, "obj 'quad.obj' has 3 triangles: more than 4 triangles in the scene"), "%s",
        err.msg);
    write_file(dir, "x.test", HEAD "obj missing.obj\n");
    ck_assert_int_eq(scene_load(path, NULL, &sc, &err), -1);
    ck_assert_int_eq(err.line, 3);
    ck_assert_ptr_nonnull(strstr(err.msg, "cannot open"));
    remove_file(dir, "quad.obj");
    remove_file(dir, "bad.obj");
    remove_file(dir, "x.test");
    rmdir(dir);
}
END_TEST

START_TEST(test_texture_images_are_read_once_and_pyramids_built_only_when_needed)
{
    char dir[] = "/tmp/test_scene_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char img_path[512], path[512];
    snprintf(img_path, sizeof img_path, "%s/wood.pfm", dir);
    snprintf(path, sizeof path, "%s/x.test", dir);
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 4, 2, &err), 0);
    image_set(&im, 1, 0, rgb_make(0.5, 0.25, 2));
    ck_assert_msg(imageio_write(img_path, &im, NULL, &err) == 0, "%s", err.msg);
    image_free(&im);
    write_file(dir, "x.test",
               HEAD "texture a wood.pfm\ntexture b wood.pfm mirror\n"
                    "texture c wood.pfm clamp\ntexture d wood.pfm\n"
                    "texfilter nearest\ndiffusemap a\nsphere 0 0 0 1\n"
                    "texfilter trilinear\ndiffusemap b\nsphere 0 0 0 1\n"
                    "texfilter ewa\ndiffusemap c\nsphere 0 0 0 1\n");
    scene sc;
    ck_assert_msg(scene_load(path, NULL, &sc, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(sc.n_texture_images, 1); /* three textures, one file read */
    ck_assert_ptr_eq(sc.textures[0].tex.img, sc.textures[1].tex.img);
    ck_assert_double_eq(image_get(sc.textures[2].tex.img, 1, 0).b, 2);
    ck_assert_int_eq(sc.textures[1].tex.wrap, WRAP_MIRROR);
    ck_assert_int_eq(sc.textures[0].tex.has_mip, 0); /* nearest needs none */
    ck_assert_int_eq(sc.textures[1].tex.has_mip, 1); /* trilinear does, */
    ck_assert_int_eq(sc.textures[2].tex.has_mip, 1); /* and EWA */
    ck_assert_int_eq(sc.textures[3].tex.has_mip, 0); /* unused */
    scene_free(&sc);
    scene_free(&sc);
    write_file(dir, "x.test", HEAD "# maps\ntexture a missing.png\n");
    ck_assert_int_eq(scene_load(path, NULL, &sc, &err), -1);
    ck_assert_int_eq(err.line, 4);
    ck_assert_ptr_nonnull(strstr(err.msg, "texture 'a' file 'missing.png' ("));
    ck_assert_ptr_nonnull(strstr(err.msg, "cannot open"));
    ck_assert_ptr_null(sc.textures);
    ck_assert_ptr_null(sc.texture_images);
    unlink(img_path);
    remove_file(dir, "x.test");
    rmdir(dir);
}
END_TEST

/* A texture file named three ways (a path, ./ and a hard link) is read once and its pyramid
 * built once; an OBJ named three ways is parsed once and each line appends its own triangles;
 * the scene lists every file it read once, by identity, for main.c's output check. */
START_TEST(test_files_named_many_ways_are_read_once_and_listed_as_inputs)
{
    char dir[] = "/tmp/test_scene_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char img_path[512], link_path[512], path[512];
    snprintf(img_path, sizeof img_path, "%s/wood.pfm", dir);
    snprintf(link_path, sizeof link_path, "%s/link.pfm", dir);
    snprintf(path, sizeof path, "%s/x.test", dir);
    image im = {0};
    error err = {0};
    ck_assert_int_eq(image_alloc(&im, 8, 8, &err), 0);
    ck_assert_msg(imageio_write(img_path, &im, NULL, &err) == 0, "%s", err.msg);
    image_free(&im);
    ck_assert_int_eq(link(img_path, link_path), 0);
    write_file(dir, "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    write_file(dir, "x.test",
               HEAD "texture a wood.pfm\ntexture b ./wood.pfm\ntexture c link.pfm\n"
                    "texfilter trilinear\ndiffusemap a\nsphere 0 0 0 1\ndiffusemap b\n"
                    "sphere 0 0 0 1\ndiffusemap c\nsphere 0 0 0 1\n"
                    "obj quad.obj\nobj ./quad.obj\ntranslate 1 0 0\nobj ././quad.obj\n");
    scene sc;
    ck_assert_msg(scene_load(path, NULL, &sc, &err) == 0, "%s", err.msg);
    ck_assert_int_eq(sc.n_texture_images, 1);
    ck_assert_int_eq(sc.textures[0].tex.has_mip, 1); /* one pyramid, used by the three maps */
    ck_assert_int_eq(sc.textures[1].tex.has_mip + sc.textures[2].tex.has_mip, 0);
    for (int m = 0; m < sc.n_materials; m++)
        ck_assert(sc.materials[m].diffusemap == 0 || sc.materials[m].diffusemap == 1);
    ck_assert_int_eq(sc.n_triangles, 6);            /* three lines of two triangles */
    assert_vec_near(sc.triangles[4].p[1], 2, 0, 0); /* the last line's own transform */
    ck_assert_int_eq(sc.inputs.n, 3);               /* wood.pfm, quad.obj, the scene */
    ck_assert_str_eq(sc.inputs.at[2].path, path);
    ck_assert_ptr_nonnull(strstr(sc.inputs.at[0].path, "quad.obj")); /* at its line */
    ck_assert_ptr_nonnull(strstr(sc.inputs.at[1].path, "wood.pfm")); /* at the end */
    ck_assert_ptr_nonnull(infile_list_clash(&sc.inputs, link_path));
    scene_free(&sc);
    unlink(img_path);
    unlink(link_path);
    remove_file(dir, "quad.obj");
    remove_file(dir, "x.test");
    rmdir(dir);
}
END_TEST

/* A mesh named by many `obj` lines is parsed once (its arrays charged once: the peak grows by
 * the triangles alone), and the triangles each line appends are charged, so a budget refuses
 * the line that would exceed it, naming the mesh and the budget. */
START_TEST(test_an_obj_named_often_is_parsed_once_and_its_triangles_are_charged)
{
    char dir[] = "/tmp/test_scene_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[512];
    snprintf(path, sizeof path, "%s/x.test", dir);
    char *mesh = malloc(20000 * 8 + 64); /* 20000 vertices, one triangle */
    ck_assert_ptr_nonnull(mesh);
    mesh[0] = '\0';
    for (int i = 0; i < 20000; i++) strcat(mesh + (i > 0 ? 8 * (i - 1) : 0), "v 0 0 0\n");
    strcat(mesh + 8 * 19999, "f 1 2 3\n");
    write_file(dir, "m.obj", mesh);
    free(mesh);
    double peak[2];
    for (int k = 0; k < 2; k++) {
        write_file(dir, "x.test",
                   k == 0 ? HEAD "obj m.obj\n" : HEAD "obj m.obj\nobj ./m.obj\nobj m.obj\n");
        budget mem;
        budget_init(&mem, 1e9);
        scene_load_opts o = scene_load_defaults();
        o.mem = &mem;
        scene sc;
        error err = {0};
        ck_assert_msg(scene_load(path, &o, &sc, &err) == 0, "%s", err.msg);
        ck_assert_int_eq(sc.n_triangles, k == 0 ? 1 : 3);
        peak[k] = mem.peak;
        scene_free(&sc);
    }
    ck_assert_msg(peak[1] == peak[0], "peak %g for three lines, %g for one", peak[1], peak[0]);
    /* a mesh of 1000 triangles: a budget that holds one line's (1024 scene triangles) refuses the
     * second line, which needs room for 1024 more */
    char *tris = malloc(1000 * 8 + 64);
    ck_assert_ptr_nonnull(tris);
    strcpy(tris, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for (int i = 0; i < 1000; i++) strcat(tris + 24 + 8 * (i > 0 ? i - 1 : 0), "f 1 2 3\n");
    write_file(dir, "t.obj", tris);
    free(tris);
    write_file(dir, "x.test", HEAD "obj t.obj\n");
    budget mem;
    budget_init(&mem, 1e9);
    scene_load_opts o = scene_load_defaults();
    o.mem = &mem;
    scene sc;
    error err = {0};
    ck_assert_msg(scene_load(path, &o, &sc, &err) == 0, "%s", err.msg);
    scene_free(&sc);
    write_file(dir, "x.test", HEAD "obj t.obj\nobj ./t.obj\n");
    budget_init(&mem, mem.peak);
    ck_assert_int_eq(scene_load(path, &o, &sc, &err), -1);
    ck_assert_int_eq(err.line, 4);
    ck_assert_msg(strstr(err.msg, "obj './t.obj': room for 1024 more triangles x "), "%s", err.msg);
    ck_assert_ptr_nonnull(strstr(err.msg, "beyond the memory budget of"));
    remove_file(dir, "t.obj");
    remove_file(dir, "m.obj");
    remove_file(dir, "x.test");
    rmdir(dir);
}
END_TEST

Suite *scene_suite(void)
{
    Suite *s = suite_create("scene");
    TCase *errors = tcase_create("errors");
    tcase_add_loop_test(errors, test_each_bad_line_is_an_error_at_its_line_naming_the_token, 0,
                        (int)(sizeof bad_cases / sizeof bad_cases[0]));
    tcase_add_test(errors, test_a_scene_without_size_is_an_error_at_the_end);
    tcase_add_test(errors, test_a_scene_without_camera_is_an_error_at_the_end);
    tcase_add_test(errors, test_a_line_longer_than_the_limit_is_an_error_not_an_overflow);
    tcase_add_test(errors, test_a_scene_file_is_read_across_its_chunks_as_one_text);
    tcase_add_test(errors, test_an_endless_binary_stream_is_refused_at_its_first_nul);
    tcase_add_test(errors, test_a_device_or_folder_is_no_scene_and_a_silent_fifo_reads_as_empty);
    tcase_add_test(errors, test_push_deeper_than_the_stack_limit_is_an_error);
    tcase_add_test(errors, test_more_primitives_than_the_limit_is_an_error);
    tcase_add_test(errors, test_limits_hold_at_their_exact_bounds);
    tcase_add_test(errors, test_a_huge_maxverts_hint_allocates_nothing_huge);
    tcase_add_test(errors, test_a_nul_byte_makes_the_file_an_error);
    tcase_add_test(errors, test_a_missing_file_is_an_error_naming_it);
    tcase_add_test(errors, test_an_unreadable_envmap_is_an_error_at_its_line_with_the_reason);
    suite_add_tcase(s, errors);

    TCase *lex = tcase_create("lexical");
    tcase_add_test(lex, test_unknown_commands_are_warnings_with_file_and_line);
    tcase_add_test(lex, test_strict_makes_unknown_commands_errors);
    tcase_add_test(lex, test_commands_before_size_warn_once_even_when_strict);
    tcase_add_test(lex, test_comments_blank_lines_crlf_and_tabs_are_tolerated);
    suite_add_tcase(s, lex);

    TCase *cmds = tcase_create("commands");
    tcase_add_test(cmds, test_defaults_are_the_courses);
    tcase_add_test(cmds, test_image_and_camera_commands_are_stored);
    tcase_add_test(cmds, test_cameras_with_tiny_or_huge_but_valid_vectors_are_accepted);
    tcase_add_test(cmds, test_renderer_settings_are_stored);
    tcase_add_test(cmds, test_every_integrator_name_round_trips);
    tcase_add_test(cmds, test_each_object_takes_the_material_current_when_read);
    tcase_add_test(cmds, test_materials_are_stored_once_until_the_state_changes);
    tcase_add_test(cmds, test_translate_then_rotate_rotates_the_object_first);
    tcase_add_test(cmds, test_sphere_is_marked_untransformed_only_under_the_identity);
    tcase_add_test(cmds, test_tri_uses_the_transform_current_at_tri_not_at_vertex);
    tcase_add_test(cmds, test_pop_restores_the_transform_saved_by_push);
    tcase_add_test(cmds, test_a_scaled_sphere_keeps_an_ellipsoid_matrix_and_its_inverse);
    tcase_add_test(cmds, test_trinormal_transforms_normals_by_the_inverse_transpose);
    tcase_add_test(cmds, test_a_zero_vertexnormal_loads_and_a_trinormal_using_it_is_flat);
    tcase_add_test(cmds, test_a_mirroring_transform_keeps_triangles_counter_clockwise_from_outside);
    tcase_add_test(cmds, test_rotate_takes_tiny_and_huge_axes_by_their_direction);
    tcase_add_test(cmds, test_quad_lights_under_the_raytracer_warn_at_the_first_one);
    tcase_add_test(cmds, test_point_lights_under_analyticdirect_warn_at_the_first_one);
    tcase_add_test(cmds, test_point_lights_in_the_path_tracer_without_nee_warn);
    tcase_add_test(cmds, test_directional_takes_tiny_and_huge_directions_by_their_direction);
    tcase_add_test(cmds, test_lights_are_in_world_space_and_point_takes_the_current_attenuation);
    tcase_add_test(cmds, test_envmap_takes_file_scale_and_the_current_transform);
    tcase_add_test(cmds, test_envmap_paths_are_relative_to_the_scene_folder);
    tcase_add_test(cmds, test_scene_load_resolves_envmap_beside_a_scene_file);
    tcase_add_test(cmds, test_a_readable_envmap_is_loaded_when_images_are_on);
    tcase_add_test(cmds, test_bad_texels_are_zeroed_at_load_with_one_warning_each);
    tcase_add_test(cmds, test_envmap_keyword_names_the_representation_after_an_optional_scale);
    tcase_add_test(cmds, test_envmap_cube_takes_six_faces_relative_to_the_scene_folder);
    tcase_add_test(cmds, test_envmap_representation_is_detected_from_the_image_shape);
    tcase_add_test(cmds, test_a_square_envmap_without_a_keyword_is_an_error_naming_file_and_line);
    tcase_add_test(cmds, test_six_cube_faces_load_and_a_bad_face_is_named);
    tcase_add_test(cmds, test_a_100k_triangle_mesh_parses_with_one_material);
    tcase_add_test(cmds, test_scene_free_is_safe_twice_and_on_a_zeroed_scene);
    suite_add_tcase(s, cmds);
    TCase *tex = tcase_create("textures");
    tcase_add_test(tex, test_tritex_keeps_object_corners_world_corners_and_st);
    tcase_add_test(tex, test_map_commands_are_material_state_stored_once);
    tcase_add_test(tex, test_procedural_textures_take_their_documented_parameters);
    tcase_add_test(tex, test_texture_errors_name_their_line_and_token);
    tcase_add_test(tex, test_obj_meshes_load_under_the_transform_and_material);
    tcase_add_test(tex, test_texture_images_are_read_once_and_pyramids_built_only_when_needed);
    tcase_add_test(tex, test_files_named_many_ways_are_read_once_and_listed_as_inputs);
    tcase_add_test(tex, test_an_obj_named_often_is_parsed_once_and_its_triangles_are_charged);
    suite_add_tcase(s, tex);
    return s;
}

UNIT_MAIN(scene_suite)
