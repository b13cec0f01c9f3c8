/* main.c - the envtex command line.  Parses arguments, calls the library, prints results.
 * Every failure prints one line `envtex: FILE:LINE: what is wrong` and exits with status 1; a
 * comparison that runs and finds the images differ (`compare` with thresholds, `compare --test`)
 * prints FAIL and exits with status 2.
 *
 *   envtex SCENE                    same as `envtex render SCENE`
 *   envtex render SCENE [-o OUT] [--spp N] [--seed N] [--ref REF] [--variance VAR] [--quiet] [--verbose] [--strict]
 *   envtex compare A B [--diff D.png] [--fail-percent P] [--fail T] [--hard H]
 *   envtex compare --test IMG REF VAR [--img-spp N --ref-spp M] [--alpha A] [--max-fail F]
 *                                     [--diff MAP.png]
 *   envtex tonemap IN OUT.png [--exposure EV] [--op clamp|reinhard|aces] [--gamma G]
 *   envtex convert IN OUT --to KIND [--from KIND] [--width W] [--samples K]
 *   envtex gen-env KIND OUT [--width W] [--value V] [--sun-ratio R] [--sun-radius DEG]
 *                           [--sun-elevation DEG] [--sun-azimuth DEG]
 *   envtex prefilter IN --sh9 | IN OUT --irradiance [--method sh9|exact] | IN OUT --phong S
 *                           [--width W] [--from KIND]      (src/cmd_prefilter.c)
 *   envtex noise X Y Z              Perlin's improved noise at (X, Y, Z), 9 significant digits
 */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envtex/bvh.h"
#include "envtex/compare.h"
#include "envtex/convert.h"
#include "envtex/genenv.h"
#include "envtex/gradetest.h"
#include "envtex/imageio.h"
#include "envtex/perlin.h"
#include "envtex/render.h"
#include "envtex/scene.h"
#include "envtex/tonemap.h"

static const char *usage_text =
    "usage: envtex SCENE                         (same as: envtex render SCENE)\n"
    "       envtex render SCENE [-o OUT.exr|.png|.pfm|.hdr] [--spp N] [--seed N] [--ref REF] [--variance VAR.exr]\n"
    "                           [--quiet] [--verbose] [--strict]\n"
    "       envtex compare A B [--diff DIFF.png] [--fail-percent P] [--fail T] [--hard H]\n"
    "       envtex compare --test IMG REF VAR [--img-spp N --ref-spp M] [--alpha A] [--max-fail F] [--diff MAP.png]\n"
    "       envtex tonemap IN OUT.png [--exposure EV] [--op clamp|reinhard|aces] [--gamma G]\n"
    "       envtex convert IN OUT --to latlong|cube|cross|mirrorball|angular|cylindrical|equalarea\n"
    "                      [--from KIND] [--width W] [--samples K]   (cube: OUT_px.exr ... OUT_nz.exr)\n"
    "       envtex gen-env constant|sky|sun|axes OUT [--width W] [--value V] [--sun-ratio R]\n"
    "                      [--sun-radius DEG] [--sun-elevation DEG] [--sun-azimuth DEG]\n"
    "       envtex prefilter IN --sh9 [--from KIND]       (9 lines: l m R G B)\n"
    "       envtex prefilter IN OUT --irradiance [--method sh9|exact] [--width W] [--from KIND]\n"
    "       envtex prefilter IN OUT --phong S [--width W] [--from KIND]\n"
    "       envtex noise X Y Z                   (Perlin's improved noise, 9 significant digits)\n";

int cmd_prefilter(int argc, char **argv); /* src/cmd_prefilter.c */

static int fail(const error *err)
{
    error_print(err, stderr);
    return 1;
}

/* One line `envtex: WHAT (envtex --help for usage)`, WHAT formatted as printf does; returns 1. */
static int usage_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static int usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "envtex: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, " (envtex --help for usage)\n");
    va_end(ap);
    return 1;
}

/* Parse a whole-token number; 0 on success. */
static int parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || errno == ERANGE || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

static int parse_long(const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno == ERANGE || v < lo || v > hi) return -1;
    *out = v;
    return 0;
}

/* Fetch the value after option argv[*i]; NULL (and a message) if missing. */
static const char *opt_value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc) {
        usage_error("option '%s' needs a value", argv[*i]);
        return NULL;
    }
    return argv[++*i];
}

/* ---- render ------------------------------------------------------------------------------ */

/* Scene warnings are kept until the scene has loaded: a scene that fails prints only its error
 * (one line), a scene that loads prints its warnings before rendering. */
#define MAX_WARNINGS_SHOWN 20
typedef struct warnings {
    error first[MAX_WARNINGS_SHOWN];
    int n;
} warnings;

static void warn_keep(void *ctx, const error *w)
{
    warnings *ws = ctx;
    if (ws->n < MAX_WARNINGS_SHOWN) ws->first[ws->n] = *w;
    ws->n++;
}

static void warnings_print(const warnings *ws)
{
    for (int i = 0; i < ws->n && i < MAX_WARNINGS_SHOWN; i++) {
        const error *w = &ws->first[i];
        fputs("envtex: warning: ", stderr);
        if (w->file[0]) fprintf(stderr, w->line > 0 ? "%s:%d: " : "%s: ", w->file, w->line);
        fprintf(stderr, "%s\n", w->msg);
    }
    if (ws->n > MAX_WARNINGS_SHOWN)
        fprintf(stderr, "envtex: warning: ... and %d more warnings\n", ws->n - MAX_WARNINGS_SHOWN);
}

/* render_opts.start: the render has passed every check, so its warnings can be shown */
static void warnings_print_at_start(void *ctx) { warnings_print(ctx); }

static void progress_bar(void *ctx, int done, int rows)
{
    (void)ctx;
    int width = 40, filled = (int)((long)done * width / rows);
    fprintf(stderr, "\r[%.*s%*s] %3d%%", filled, "########################################",
            width - filled, "", (int)((long)done * 100 / rows));
    if (done == rows) fputs("\r\033[K", stderr);
    fflush(stderr);
}

/* 1 if a and b name the same existing file (device and inode) */
static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return a && b && a[0] && b[0] && stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

/* An output must not replace a file the scene reads (its own file, the envmap, a texture):
 * the render would succeed and the input be gone. */
static int check_not_an_input(const char *out, const scene *sc, error *err)
{
    const char *what = NULL;
    if (same_file(out, sc->path)) what = sc->path;
    if (sc->envmap.present && same_file(out, sc->envmap.path)) what = sc->envmap.path;
    for (int f = 0; sc->envmap.present && sc->envmap.six_files && f < CUBEMAP_FACES; f++)
        if (same_file(out, sc->envmap.face_path[f])) what = sc->envmap.face_path[f];
    for (int i = 0; i < sc->n_textures; i++)
        if (same_file(out, sc->textures[i].path)) what = sc->textures[i].path;
    if (what) return error_set(err, out, 0, "the output would replace an input of the scene (%s)", what);
    return 0;
}

/* An output must not replace one of the command's input images (`compare --diff REF.exr`,
 * `tonemap a.png a.png`, `convert sky.exr sky.exr`): the command would succeed and the input,
 * often an instructor's reference, be gone.  `inputs` has n paths (NULL entries are skipped). */
static int check_not_replacing(const char *out, const char *const *inputs, int n, error *err)
{
    for (int k = 0; k < n; k++)
        if (inputs[k] && (!strcmp(out, inputs[k]) || same_file(out, inputs[k])))
            return error_set(err, out, 0, "the output would replace the input image %s", inputs[k]);
    return 0;
}

/* Output path must be writable before the render starts: try the temporary file now.  any_name:
 * the format is decided elsewhere (a scene's `output` without a known extension is a PNG). */
static int check_output_as(const char *path, int any_name, error *err)
{
    if (!path[0]) return error_set(err, NULL, 0, "the output file name is empty");
    if (!any_name && !imageio_can_write(path))
        return error_set(err, path, 0, "cannot write this format: use .exr, .png, .pfm or .hdr");
    char tmp[ERROR_FILE_MAX];
    int fd = imageio_tmp_open(path, tmp, err);
    if (fd < 0) return -1;
    close(fd);
    imageio_tmp_abandon(tmp);
    return 0;
}

static int check_output(const char *path, error *err) { return check_output_as(path, 0, err); }

static int cmd_render(int argc, char **argv)
{
    const char *scene_path = NULL, *out_path = NULL, *ref_path = NULL, *var_path = NULL;
    int quiet = 0, verbose = 0, strict = 0;
    render_opts ro = render_defaults();
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        long n;
        if (!strcmp(a, "-o")) {
            if (!(out_path = opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(a, "--spp")) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_long(v, 1, SCENE_MAX_SPP, &n)) return usage_error("--spp needs a whole number from 1 to 1048576, got '%s'", v);
            ro.spp = (int)n;
        } else if (!strcmp(a, "--seed")) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_long(v, 0, 0x7fffffffffffffffL, &n)) return usage_error("--seed needs a whole number >= 0, got '%s'", v);
            ro.seed = (uint64_t)n;
        } else if (!strcmp(a, "--ref")) {
            if (!(ref_path = opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(a, "--variance")) {
            if (!(var_path = opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(a, "--quiet")) quiet = 1;
        else if (!strcmp(a, "--verbose")) verbose = 1;
        else if (!strcmp(a, "--strict")) strict = 1;
        else if (a[0] == '-' && a[1]) return usage_error("unknown option '%s'", a);
        else if (!scene_path) scene_path = a;
        else return usage_error("unexpected argument '%s'", a);
    }
    if (!scene_path) return usage_error("%s", "render needs a scene file");

    error err = {0};
    scene sc;
    scene_load_opts lo = scene_load_defaults();
    lo.strict = strict;
    static warnings ws; /* static: about 40 KB */
    lo.warn = warn_keep;
    lo.warn_ctx = &ws;
    if (scene_load(scene_path, &lo, &sc, &err)) return fail(&err);
    int out_from_scene = !out_path; /* the scene's `output` (or its default) */
    if (!out_path) out_path = sc.output;

    /* Everything that can refuse the run is checked before the render and before the scene's
     * warnings are printed (render_scene's own checks too: it prints them through ro.start once
     * they have passed): a refused run prints one line and writes nothing. */
    int status = 1;
    image img = {0}, ref = {0}, var = {0};
    /* The course skeleton writes a PNG under whatever name `output` gives (`output scene2`,
     * `output scene6.bmp`); -o names a format by its extension, as every other command does. */
    imageio_format out_format = IMAGEIO_UNKNOWN;
    if (out_from_scene && out_path[0] && !imageio_can_write(out_path)) {
        out_format = IMAGEIO_PNG;
        error w;
        error_set(&w, scene_path, sc.output_line, "'output' %s has no .exr, .png, .pfm or .hdr extension: written "
                  "as a PNG under this exact name, as the course skeleton does", out_path);
        warn_keep(&ws, &w);
    }
    if (check_output_as(out_path, out_format != IMAGEIO_UNKNOWN, &err) || check_not_an_input(out_path, &sc, &err)) {
        if (out_from_scene && sc.output_line > 0) { /* the name came from this line of the scene */
            char msg[ERROR_MSG_MAX]; /* err.msg cannot be an argument of error_set on err: they overlap */
            snprintf(msg, sizeof msg, "%s", err.msg);
            error_set(&err, scene_path, sc.output_line, "'output' %s: %s", out_path, msg);
        }
        goto done;
    }
    if (var_path && (check_output(var_path, &err) || check_not_an_input(var_path, &sc, &err))) goto done;
    if (var_path && (!strcmp(var_path, out_path) || same_file(var_path, out_path))) {
        error_set(&err, var_path, 0, "--variance names the output file itself");
        goto done;
    }
    if (ref_path && (same_file(ref_path, out_path) || (var_path && same_file(ref_path, var_path)))) {
        error_set(&err, ref_path, 0, "the output would replace the --ref image");
        goto done;
    }
    if (var_path) ro.variance = &var;
    if (ref_path) {
        if (imageio_read(ref_path, &ref, &err)) goto done;
        if (ref.w != sc.width || ref.h != sc.height) {
            error_set(&err, NULL, 0, "--ref %s: image sizes differ: %d x %d against a %d x %d reference", ref_path,
                      sc.width, sc.height, ref.w, ref.h);
            goto done;
        }
    }
    ro.warn = warn_keep; /* render_scene's own warnings join the scene's */
    ro.warn_ctx = &ws;
    if (!quiet) { /* printed once render_scene has passed its own checks (spp, the envmap's transform...) */
        ro.start = warnings_print_at_start;
        ro.start_ctx = &ws;
    }
    if (!quiet && isatty(STDERR_FILENO)) {
        ro.progress = progress_bar;
    }
    render_stats st;
    if (render_scene(&sc, &ro, &img, &st, &err)) goto done;
    if (verbose) {
        fprintf(stderr, "envtex: scene %s: %dx%d, %ld spheres and %ld triangles as read (%ld primitives rendered), %d lights, %d materials\n",
                scene_path, sc.width, sc.height, sc.n_spheres, sc.n_triangles, st.prims, sc.n_lights, sc.n_materials);
        if (st.bvh_is_tree)
            fprintf(stderr, "envtex: built BVH: %ld nodes, depth %d, %.3f s\n", st.bvh_nodes, st.bvh_depth, st.build_seconds);
        else
            fprintf(stderr, "envtex: no BVH (%ld primitives <= %d: tested linearly)\n", st.prims, BVH_MIN_PRIMS);
        if (sc.envmap.present) {
            int is_cube = sc.envmap.kind == CONVERT_CUBE;
            int ew = is_cube ? sc.envmap.cube.size : sc.envmap.img.w, eh = is_cube ? ew : sc.envmap.img.h;
            fprintf(stderr, "envtex: envmap %s: %s, %dx%d%s, scale %g, %.1f MB\n", sc.envmap.path,
                    convert_kind_name(sc.envmap.kind), ew, eh, is_cube ? " per face" : "", sc.envmap.scale,
                    ew * (double)eh * 12 * (is_cube ? 6 : 1) / 1e6);
            if (st.envlight_built && sc.envmap.kind != CONVERT_LATLONG)
                fprintf(stderr, "envtex: envmap resampled to a %dx%d lat-long map for lighting\n", st.envlight_w,
                        st.envlight_h);
            if (sc.envmiss != ENVMISS_ENVMAP)
                fprintf(stderr, "envtex: envmap sampling: none ('envmiss black': the envmap is a background only)\n");
            else if (!st.envlight_sampled)
                fprintf(stderr, "envtex: envmap sampling: none (the '%s' integrator%s does not sample the envmap)\n",
                        scene_integrator_name(sc.integrator),
                        sc.integrator == INTEGRATOR_PATHTRACER ? " without next-event estimation" : "");
            else if (st.envlight_mode != ENVSAMPLING_UNIFORM)
                fprintf(stderr, "envtex: envmap sampling: '%s' tables (%s) built in %.3f s%s\n",
                        scene_envsampling_name(st.envlight_mode), sc.envsampler == ENVSAMPLER_ALIAS ? "alias" : "binary search",
                        st.envlight_seconds, st.envlight_fell_back ? " (black map: equal strata)" : "");
            else
                fprintf(stderr, "envtex: envmap sampling: uniform directions, no tables%s\n",
                        st.envlight_fell_back && sc.envsampling != ENVSAMPLING_UNIFORM ? " (black map: uniform fallback)" : "");
            if (st.envlight_points) fprintf(stderr, "envtex: median cut: %d point lights\n", st.envlight_points);
            if (st.envlight_built && sc.integrator == INTEGRATOR_PATHTRACER && sc.nee == NEE_MIS)
                fprintf(stderr, "envtex: MIS: the envmap is sampled at a fraction %.3g of its picks (%s; kappa = E[L^2]/E[L]^2 = %.4g)%s\n",
                        st.env_fraction, sc.envsamplefraction < 0 ? "auto: least variance x time, envlight.h" : "envsamplefraction",
                        st.envlight_kappa, st.nee == NEE_OFF ? "; no other light, so paths run as BRDF sampling alone" : "");
            if (st.envlight_bad_texels)
                fprintf(stderr, "envtex: warning: envmap %s: %ld NaN, Inf or negative texel values (used as 0)\n",
                        sc.envmap.path, st.envlight_bad_texels);
        } else {
            fprintf(stderr, "envtex: no envmap\n");
        }
        if (st.lights) fprintf(stderr, "envtex: %d light%s to sample%s\n", st.lights, st.lights == 1 ? "" : "s", st.lights == 1 ? "" : " (chosen by power)");
        if (sc.n_textures) {
            int mips = 0, packed = 0;
            for (int i = 0; i < sc.n_textures; i++) {
                mips += sc.textures[i].tex.has_mip;
                packed += sc.textures[i].tex.mip.packed != NULL;
            }
            fprintf(stderr, "envtex: %d textures (%d image files), %d mip pyramids (built only for trilinear/EWA), "
                    "%d packed for trilinear\n", sc.n_textures, sc.n_texture_images, mips, packed);
        }
        if (st.ray_differentials)
            fprintf(stderr, "envtex: ray differentials traced (a trilinear, EWA or bump map needs the footprint)\n");
        else
            fprintf(stderr, "envtex: no ray differentials traced (%s)\n",
                    sc.n_textures ? "no trilinear, EWA or bump map: nearest and bilinear read one point"
                                  : "no textures");
        if (st.displaced_spheres + st.displaced_triangles)
            fprintf(stderr, "envtex: displacement: %ld spheres (rate %d) and %ld triangles (rate %d) tessellated; "
                    "the BVH holds %ld triangles\n", st.displaced_spheres, st.displace_sphere_rate,
                    st.displaced_triangles, st.displace_triangle_rate, st.displaced_result);
    }
    compare_result cr; /* before any file is written: a failure here writes nothing */
    if (ref_path && compare_metrics(&img, &ref, &cr, &err)) {
        error_prefix(&err, "--ref %s", ref_path);
        goto done;
    }
    if (st.nonfinite_pixels)
        fprintf(stderr, "envtex: warning: %s: %ld pixels are NaN or Inf\n", scene_path, st.nonfinite_pixels);
    if (st.nonfinite_variance)
        fprintf(stderr, "envtex: warning: %s: %ld pixels of the variance image are NaN or Inf\n", var_path,
                st.nonfinite_variance);
    tonemap_params tm = tonemap_defaults();
    tm.gamma = sc.gamma;
    /* the image and its variance are one output: a failure writing either leaves both targets
     * untouched (the image was once committed before a full disk refused the variance) */
    const char *paths[2] = {out_path, var_path};
    const image *images[2] = {&img, &var};
    const tonemap_params *tms[2] = {&tm, NULL};
    const imageio_format formats[2] = {out_format, IMAGEIO_UNKNOWN};
    if (imageio_write_set(var_path ? 2 : 1, paths, images, tms, formats, &err)) goto done;

    printf("time_s=%.3f spp=%d rays=%lld mrays_per_s=%.3f nonfinite=%ld build_s=%.3f", st.seconds, st.spp,
           st.rays, st.seconds > 0 ? st.rays / st.seconds / 1e6 : 0.0, st.nonfinite_pixels, st.build_seconds);
    if (ref_path) printf(" relmse=%.6g rmse=%.6g relmse_trim=%.6g", cr.relmse, cr.rmse, cr.relmse_trim);
    printf("\n");
    status = 0;
done:
    if (status) error_print(&err, stderr);
    image_free(&img);
    image_free(&ref);
    image_free(&var);
    scene_free(&sc);
    return status;
}

/* ---- compare ----------------------------------------------------------------------------- */

/* envtex compare --test IMG REF VAR: the noise-aware test (gradetest.h) */
static int cmd_compare_test(int argc, char **argv)
{
    const char *paths[3] = {NULL, NULL, NULL}, *map_path = NULL;
    int np = 0;
    gradetest_params p = gradetest_defaults();
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        double *target = NULL;
        if (!strcmp(a, "--diff")) {
            if (!(map_path = opt_value(argc, argv, &i))) return 1;
            continue;
        }
        if (!strcmp(a, "--img-spp")) target = &p.img_spp;
        else if (!strcmp(a, "--ref-spp")) target = &p.ref_spp;
        else if (!strcmp(a, "--alpha")) target = &p.alpha;
        else if (!strcmp(a, "--max-fail")) target = &p.max_fail_fraction;
        if (target) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_double(v, target) || !(*target > 0)) return usage_error("option needs a number > 0, got '%s'", v);
            /* significance and share of pixels are fractions: --max-fail 0.5 means half the pixels
             * (not 0.5%), and 5 would let every pixel fail */
            if (target == &p.alpha && !(*target < 1))
                return usage_error("--alpha is a significance level in (0, 1), got '%s'", v);
            if (target == &p.max_fail_fraction && !(*target <= 1))
                return usage_error("--max-fail is a fraction of the pixels in (0, 1] (0.005 is 0.5%%), got '%s'", v);
        } else if (a[0] == '-' && a[1]) return usage_error("unknown option '%s'", a);
        else if (np < 3) paths[np++] = a;
        else return usage_error("unexpected argument '%s'", a);
    }
    if (np < 3) return usage_error("%s", "compare --test needs IMG REF VAR (VAR from 'envtex render --variance')");
    error err = {0};
    image im[3] = {{0}}, map = {0};
    int status = 1;
    if (map_path && (check_output(map_path, &err) || check_not_replacing(map_path, paths, 3, &err))) goto done;
    for (int k = 0; k < 3; k++)
        if (imageio_read(paths[k], &im[k], &err)) goto done;
    /* A PNG (the course skeleton's raytrace.png) is clamped to [0, 1] and rounded to 8 bits: every
     * pixel brighter than 1 would fail as a bias and the verdict say nothing about the code */
    static const char *const roles[3] = {"image", "reference", "variance"};
    for (int k = 0; k < 3; k++)
        if (imageio_detect(paths[k]) == IMAGEIO_PNG) {
            error_set(&err, paths[k], 0, "the %s is a PNG (8 bits clamped to [0, 1]): the noise-aware test needs "
                      "the linear render (.exr, .pfm or .hdr)", roles[k]);
            goto done;
        }
    gradetest_result r;
    if (gradetest_run(&im[0], &im[1], &im[2], &p, &r, map_path ? &map : NULL, &err)) {
        char msg[ERROR_MSG_MAX]; /* err.msg cannot be an argument of error_set on err: they overlap */
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, paths[0], 0, "%s", msg);
        goto done;
    }
    if (map_path && imageio_write(map_path, &map, NULL, &err)) goto done;
    printf("%s: %ld of %ld pixels (%.4f%%, allowed %.4f%%) fail |z| > %.2f; image total Z = %.2f "
           "(allowed |Z| <= %.2f); %ld NaN/Inf: %s\n",
           r.pass ? "PASS" : "FAIL", r.failed, r.pixels, 100 * r.failed_fraction, 100 * p.max_fail_fraction,
           r.z_threshold, r.mean_z, p.global_z, r.nonfinite, r.why);
    status = r.pass ? 0 : 2;
done:
    if (status == 1) error_print(&err, stderr);
    for (int k = 0; k < 3; k++) image_free(&im[k]);
    image_free(&map);
    return status;
}

static int cmd_compare(int argc, char **argv)
{
    if (argc > 0 && !strcmp(argv[0], "--test")) return cmd_compare_test(argc - 1, argv + 1);
    const char *a_path = NULL, *b_path = NULL, *diff_path = NULL;
    compare_thresholds_params th = compare_thresholds_defaults();
    int use_thresholds = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        double *target = NULL;
        if (!strcmp(a, "--diff")) {
            if (!(diff_path = opt_value(argc, argv, &i))) return 1;
            continue;
        }
        if (!strcmp(a, "--fail-percent")) target = &th.fail_percent;
        else if (!strcmp(a, "--fail")) target = &th.fail_thresh;
        else if (!strcmp(a, "--hard")) target = &th.hard_thresh;
        if (target) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_double(v, target) || *target < 0) return usage_error("a threshold must be a number >= 0, got '%s'", v);
            use_thresholds = 1;
        } else if (a[0] == '-' && a[1]) return usage_error("unknown option '%s'", a);
        else if (!a_path) a_path = a;
        else if (!b_path) b_path = a;
        else return usage_error("unexpected argument '%s'", a);
    }
    if (!b_path) return usage_error("%s", "compare needs two images: A (tested) and B (reference)");
    error err = {0};
    image a = {0}, b = {0}, d = {0};
    int status = 1;
    const char *inputs[2] = {a_path, b_path};
    if (diff_path && (check_output(diff_path, &err) || check_not_replacing(diff_path, inputs, 2, &err))) goto done;
    if (imageio_read(a_path, &a, &err) || imageio_read(b_path, &b, &err)) goto done;
    compare_result cr;
    if (compare_metrics(&a, &b, &cr, &err)) {
        char msg[ERROR_MSG_MAX]; /* err.msg cannot be an argument of error_set on err: they overlap */
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, a_path, 0, "%s (against %s)", msg, b_path);
        goto done;
    }
    /* nan: A's NaN/Inf pixels; ref_nan: B's.  Either pixel non-finite leaves it out of the sums */
    printf("rmse=%.6g relmse=%.6g psnr=%.3f max_abs=%.6g nan=%ld relmse_trim=%.6g ref_nan=%ld\n", cr.rmse, cr.relmse,
           cr.psnr, cr.max_abs, cr.nonfinite, cr.relmse_trim, cr.ref_nonfinite);
    if (diff_path) {
        if (compare_diff_image(&a, &b, &d, &err) || imageio_write(diff_path, &d, NULL, &err)) goto done;
    }
    status = 0;
    if (use_thresholds) {
        compare_verdict v;
        compare_thresholds(&a, &b, &th, &v);
        char where[64] = ""; /* where the largest difference is; none when every pixel agrees */
        if (v.max_x >= 0) snprintf(where, sizeof where, " at (%d, %d)", v.max_x, v.max_y);
        printf("%s: %ld of %ld pixels (%.3f%%) differ by more than %g (allowed %g%%), max %.6g%s (hard limit %g), %ld NaN/Inf: %s\n",
               v.pass ? "PASS" : "FAIL", v.failed, v.pixels, v.failed_percent, th.fail_thresh,
               th.fail_percent, v.max_diff, where, th.hard_thresh, v.nonfinite, v.why);
        if (!v.pass) status = 2; /* a failed comparison is not an error: status 2 */
    }
done:
    if (status == 1) error_print(&err, stderr);
    image_free(&a);
    image_free(&b);
    image_free(&d);
    return status;
}

/* ---- tonemap ----------------------------------------------------------------------------- */

static int cmd_tonemap(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    tonemap_params tm = tonemap_defaults();
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        if (!strcmp(a, "--exposure")) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_double(v, &tm.exposure)) return usage_error("--exposure needs a number, got '%s'", v);
        } else if (!strcmp(a, "--op")) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (tonemap_op_parse(v, &tm.op)) return usage_error("--op must be clamp, reinhard or aces, got '%s'", v);
        } else if (!strcmp(a, "--gamma")) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_double(v, &tm.gamma) || !(tm.gamma > 0)) return usage_error("--gamma needs a number > 0, got '%s'", v);
        } else if (a[0] == '-' && a[1]) return usage_error("unknown option '%s'", a);
        else if (!in) in = a;
        else if (!out) out = a;
        else return usage_error("unexpected argument '%s'", a);
    }
    if (!out) return usage_error("%s", "tonemap needs IN and OUT.png");
    error err = {0};
    image img = {0};
    int status = 1;
    /* exposure, operator and gamma act only on the 8-bit PNG: an .exr, .hdr or .pfm OUT was
     * written as an unchanged copy of IN, the options silently ignored */
    const char *dot = strrchr(out, '.');
    if (!dot || strchr(dot, '/') || strcasecmp(dot, ".png")) {
        error_set(&err, out, 0, "tonemap writes an 8-bit PNG: name the output .png (an HDR "
                                "output would be IN unchanged, without the tone mapping)");
        goto done;
    }
    if (check_output(out, &err) || check_not_replacing(out, &in, 1, &err)) goto done;
    if (imageio_read(in, &img, &err)) goto done;
    if (imageio_write(out, &img, &tm, &err)) goto done;
    status = 0;
done:
    if (status) error_print(&err, stderr);
    image_free(&img);
    return status;
}

/* ---- convert ----------------------------------------------------------------------------- */

/* envtex convert IN OUT --to KIND [--from KIND] [--width W] [--samples K]: resample an
 * environment into another representation (convert.h).  `cube` reads or writes six files
 * IN_px.EXT ... IN_nz.EXT; `cross` one horizontal cross image.  Prints one summary line. */
static int cmd_convert(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *to = NULL, *from = NULL;
    long width = 0, samples = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        if (!strcmp(a, "--to")) {
            if (!(to = opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(a, "--from")) {
            if (!(from = opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(a, "--width")) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_long(v, 1, IMAGE_MAX_SIDE, &width)) return usage_error("--width needs a whole number from 1 to 32768, got '%s'", v);
        } else if (!strcmp(a, "--samples")) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_long(v, 1, CONVERT_MAX_SAMPLES, &samples)) return usage_error("--samples needs a whole number from 1 to 64, got '%s'", v);
        } else if (a[0] == '-' && a[1]) return usage_error("unknown option '%s'", a);
        else if (!in) in = a;
        else if (!out) out = a;
        else return usage_error("unexpected argument '%s'", a);
    }
    if (!out) return usage_error("%s", "convert needs IN and OUT");
    convert_kind kind, from_kind;
    if (!to) return usage_error("%s", "convert needs --to latlong|cube|cross|mirrorball|angular|cylindrical|equalarea");
    if (convert_kind_parse(to, &kind)) return usage_error("--to must be latlong, cube, cross, mirrorball, angular, cylindrical or equalarea, got '%s'", to);
    if (from && convert_kind_parse(from, &from_kind)) return usage_error("--from must be latlong, cube, cross, mirrorball, angular, cylindrical or equalarea, got '%s'", from);
    int six = !strcmp(to, "cube");
    error err = {0};
    convert_map src = {0}, dst = {0};
    int status = 1;
    /* every output file must be writable, and none an input, before the work starts: the
     * input is IN, or IN's six faces when it is read as a cube */
    char in_faces[CUBEMAP_FACES][ERROR_FILE_MAX];
    const char *inputs[CUBEMAP_FACES] = {in};
    int n_inputs = 1;
    if (from && !strcmp(from, "cube")) {
        for (int f = 0; f < CUBEMAP_FACES; f++) {
            if (convert_face_path(in, f, in_faces[f], sizeof in_faces[f], &err)) goto done;
            inputs[f] = in_faces[f];
        }
        n_inputs = CUBEMAP_FACES;
    }
    for (int f = 0; f < (six ? CUBEMAP_FACES : 1); f++) {
        char name[ERROR_FILE_MAX];
        if (six && convert_face_path(out, f, name, sizeof name, &err)) goto done;
        if (check_output(six ? name : out, &err) || check_not_replacing(six ? name : out, inputs, n_inputs, &err))
            goto done;
    }
    if (convert_read(in, from, &src, &err)) goto done;
    if (src.bad_texels)
        fprintf(stderr, "envtex: warning: %s: %ld NaN, infinite or negative texel value%s (used as 0)\n",
                in, src.bad_texels, src.bad_texels == 1 ? "" : "s");
    convert_env sv = convert_view(&src);
    if (convert_resample(&sv, kind, (int)width, (int)samples, &dst, &err)) {
        char msg[ERROR_MSG_MAX];
        memcpy(msg, err.msg, sizeof msg);
        error_set(&err, out, 0, "%s", msg);
        goto done;
    }
    if (kind == CONVERT_CUBE && !six ? convert_write_cross(out, &dst, &err) : convert_write(out, &dst, &err)) goto done;
    convert_env dv = convert_view(&dst);
    double p0 = rgb_luminance(convert_power(&sv)), p1 = rgb_luminance(convert_power(&dv));
    const image *si = convert_face_image(&sv, 0), *di = convert_face_image(&dv, 0);
    printf("from=%s %dx%d%s to=%s %dx%d%s samples=%d power_in=%.6g power_out=%.6g power_change=%+.4f%%\n",
           convert_kind_name(src.kind), si->w, si->h, src.kind == CONVERT_CUBE ? "x6" : "",
           six ? "cube" : to, di->w, di->h, kind == CONVERT_CUBE ? "x6" : "",
           samples > 0 ? (int)samples : convert_default_samples(&sv, kind, di->w), p0, p1,
           p0 > 0 ? 100.0 * (p1 / p0 - 1.0) : 0.0);
    status = 0;
done:
    if (status) error_print(&err, stderr);
    convert_map_free(&src);
    convert_map_free(&dst);
    return status;
}

/* ---- gen-env ----------------------------------------------------------------------------- */

static int cmd_gen_env(int argc, char **argv)
{
    const char *kind_name = NULL, *out = NULL;
    genenv_params p = genenv_defaults();
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v;
        double *target = NULL;
        if (!strcmp(a, "--width")) {
            long n;
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_long(v, 2, IMAGE_MAX_SIDE, &n)) return usage_error("--width needs a whole number from 2 to 32768, got '%s'", v);
            p.width = (int)n;
            continue;
        }
        if (!strcmp(a, "--value")) target = &p.value;
        else if (!strcmp(a, "--sun-ratio")) target = &p.sun_ratio;
        else if (!strcmp(a, "--sun-radius")) target = &p.sun_radius_deg;
        else if (!strcmp(a, "--sun-elevation")) target = &p.sun_elevation_deg;
        else if (!strcmp(a, "--sun-azimuth")) target = &p.sun_azimuth_deg;
        if (target) {
            if (!(v = opt_value(argc, argv, &i))) return 1;
            if (parse_double(v, target)) return usage_error("%s needs a finite number, got '%s'", a, v);
        } else if (a[0] == '-' && a[1]) return usage_error("unknown option '%s'", a);
        else if (!kind_name) kind_name = a;
        else if (!out) out = a;
        else return usage_error("unexpected argument '%s'", a);
    }
    if (!out) return usage_error("%s", "gen-env needs KIND and OUT");
    genenv_kind kind;
    if (genenv_kind_parse(kind_name, &kind)) return usage_error("unknown environment kind '%s' (constant, sky, sun, axes)", kind_name);
    error err = {0};
    image img = {0};
    int status = 1;
    if (check_output(out, &err)) goto done;
    if (genenv_make(kind, &p, &img, &err)) {
        error_prefix(&err, "gen-env %s", kind_name);
        goto done;
    }
    if (imageio_write(out, &img, NULL, &err)) goto done;
    status = 0;
done:
    if (status) error_print(&err, stderr);
    image_free(&img);
    return status;
}

/* ---- noise ------------------------------------------------------------------------------- */

static int cmd_noise(int argc, char **argv)
{
    double v[3];
    if (argc != 3) return usage_error("%s", "noise needs three numbers X Y Z");
    for (int k = 0; k < 3; k++)
        if (parse_double(argv[k], &v[k])) return usage_error("noise needs finite numbers, got '%s'", argv[k]);
    printf("%.9g\n", perlin_noise(v[0], v[1], v[2]));
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fputs(usage_text, stderr);
        return 1;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help")) {
        fputs(usage_text, stdout);
        return 0;
    }
    if (!strcmp(cmd, "render")) return cmd_render(argc - 2, argv + 2);
    if (!strcmp(cmd, "compare")) return cmd_compare(argc - 2, argv + 2);
    if (!strcmp(cmd, "tonemap")) return cmd_tonemap(argc - 2, argv + 2);
    if (!strcmp(cmd, "gen-env")) return cmd_gen_env(argc - 2, argv + 2);
    if (!strcmp(cmd, "convert")) return cmd_convert(argc - 2, argv + 2);
    if (!strcmp(cmd, "noise")) return cmd_noise(argc - 2, argv + 2);
    if (!strcmp(cmd, "prefilter")) return cmd_prefilter(argc - 2, argv + 2);
    return cmd_render(argc - 1, argv + 1); /* envtex SCENE [options] */
}
