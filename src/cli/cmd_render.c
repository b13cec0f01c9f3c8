/* cmd_render.c - `envtex render SCENE [-o OUT] [--spp N] [--seed N] [--ref REF]
 * [--variance VAR] [--quiet] [--verbose] [--strict] [--memory-budget SIZE]` (and `envtex SCENE`):
 * load, check everything that can refuse the run, render (render.h), write, print one summary
 * line. */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "envtex/cli/cli.h"
#include "envtex/geometry/bvh.h"
#include "envtex/io/imageio.h"
#include "envtex/io/infile.h"
#include "envtex/io/tonemap.h"
#include "envtex/render/compare.h"
#include "envtex/render/render.h"
#include "envtex/scene/scene.h"
#include "envtex/scene/scene_load.h"

/* the options, for "did you mean" (cli_unknown) */
static const char *const options[] = {
    "-o", "--memory-budget", "--spp", "--seed", "--ref", "--variance", "--quiet", "--verbose",
    "--strict", NULL};

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

/* The command line of `render`. */
typedef struct render_args {
    const char *scene_path, *out_path, *ref_path, *var_path;
    int quiet, verbose, strict;
    int out_from_scene;        /* no -o: the scene's `output` (or its default) */
    imageio_format out_format; /* IMAGEIO_UNKNOWN: by the extension */
    double mem_limit;
    render_opts ro;
} render_args;

/* 0, or 1 with the usage line printed */
static int parse_args(int argc, char **argv, render_args *a)
{
    memset(a, 0, sizeof *a);
    a->mem_limit = BUDGET_DEFAULT;
    a->ro = render_defaults();
    for (int i = 0; i < argc; i++) {
        const char *o = argv[i], *v;
        long n;
        if (!strcmp(o, "-o")) {
            if (!(a->out_path = cli_opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(o, "--memory-budget")) {
            if (cli_memory_budget_option(argc, argv, &i, &a->mem_limit)) return 1;
        } else if (!strcmp(o, "--spp")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_long(v, 1, SCENE_MAX_SPP, &n))
                return cli_usage_error("--spp needs a whole number from 1 to 1048576, got '%s'", v);
            a->ro.spp = (int)n;
        } else if (!strcmp(o, "--seed")) {
            if (!(v = cli_opt_value(argc, argv, &i))) return 1;
            if (cli_parse_long(v, 0, 0x7fffffffffffffffL, &n))
                return cli_usage_error("--seed needs a whole number >= 0, got '%s'", v);
            a->ro.seed = (uint64_t)n;
        } else if (!strcmp(o, "--ref")) {
            if (!(a->ref_path = cli_opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(o, "--variance")) {
            if (!(a->var_path = cli_opt_value(argc, argv, &i))) return 1;
        } else if (!strcmp(o, "--quiet"))
            a->quiet = 1;
        else if (!strcmp(o, "--verbose"))
            a->verbose = 1;
        else if (!strcmp(o, "--strict"))
            a->strict = 1;
        else if (o[0] == '-' && o[1])
            return cli_unknown("option", o, options);
        else if (!a->scene_path)
            a->scene_path = o;
        else
            return cli_usage_error("unexpected argument '%s'", o);
    }
    if (!a->scene_path) return cli_usage_error("%s", "render needs a scene file");
    return 0;
}

/* An output must not replace a file the render reads: the render would succeed and the input be
 * gone.  The inputs are the scene's (sc->inputs, listed by the loader as it read them: the
 * scene file, its envmap or faces, textures, OBJ meshes) and the --ref image, which cmd_render
 * adds; each is compared by identity, so ./a.obj and a hard link to a.obj are a.obj. */
static int check_not_an_input(const char *out, const scene *sc, const char *ref_path, error *err)
{
    const char *in = infile_list_clash(&sc->inputs, out);
    if (!in) return 0;
    if (ref_path && !strcmp(in, ref_path))
        return error_set(err, out, 0, "the output would replace the --ref image");
    return error_set(err, out, 0, "the output would replace an input of the scene (%s)", in);
}

/* Everything about the outputs that can refuse the run, checked before it renders: the output
 * (and the variance) can be written and replace no input.  The course skeleton writes a PNG
 * under whatever name `output` gives (`output scene2`): a warning, not an error. */
static int check_outputs(render_args *a, scene *sc, warnings *ws, error *err)
{
    if (a->out_from_scene && a->out_path[0] && !imageio_can_write(a->out_path)) {
        a->out_format = IMAGEIO_PNG;
        error w;
        error_set(&w, a->scene_path, sc->output_line,
                  "'output' %s has no .exr, .png, .pfm or "
                  ".hdr extension: written as a PNG under this exact name, as the course "
                  "skeleton does",
                  a->out_path);
        warn_keep(ws, &w);
    }
    if (a->ref_path && infile_list_add(&sc->inputs, a->ref_path, err)) return -1;
    int any_name = a->out_format != IMAGEIO_UNKNOWN;
    if ((any_name ? cli_check_output_any_name(a->out_path, err)
                  : cli_check_output(a->out_path, err)) ||
        check_not_an_input(a->out_path, sc, a->ref_path, err)) {
        if (a->out_from_scene && sc->output_line > 0) { /* the name came from this scene line */
            char msg[ERROR_MSG_MAX]; /* err->msg cannot be an argument of error_set on err */
            snprintf(msg, sizeof msg, "%s", err->msg);
            error_set(err, a->scene_path, sc->output_line, "'output' %s: %s", a->out_path, msg);
        }
        return -1;
    }
    if (!a->var_path) return 0;
    if (cli_check_output(a->var_path, err) || check_not_an_input(a->var_path, sc, a->ref_path, err))
        return -1;
    if (!strcmp(a->var_path, a->out_path) || cli_same_file(a->var_path, a->out_path))
        return error_set(err, a->var_path, 0, "--variance names the output file itself");
    return 0;
}

/* --ref: the reference image, of the render's size */
static int read_ref(const render_args *a, const scene *sc, budget *mem, image *ref, error *err)
{
    if (imageio_read(a->ref_path, ref, mem, err)) return -1;
    if (ref->w != sc->width || ref->h != sc->height)
        return error_set(err, NULL, 0,
                         "--ref %s: image sizes differ: %d x %d against a %d x %d "
                         "reference",
                         a->ref_path, sc->width, sc->height, ref->w, ref->h);
    return 0;
}

/* --verbose: what the envmap cost and how it is sampled */
static void verbose_envmap(const scene *sc, const render_stats *st)
{
    const scene_envmap *e = &sc->envmap;
    int is_cube = e->kind == CONVERT_CUBE;
    int ew = is_cube ? e->cube.size : e->img.w, eh = is_cube ? ew : e->img.h;
    fprintf(stderr, "envtex: envmap %s: %s, %dx%d%s, scale %g, %.1f MB\n", e->path,
            convert_kind_name(e->kind), ew, eh, is_cube ? " per face" : "", e->scale,
            ew * (double)eh * 12 * (is_cube ? 6 : 1) / 1e6);
    if (st->envlight_built && e->kind != CONVERT_LATLONG)
        fprintf(stderr, "envtex: envmap resampled to a %dx%d lat-long map for lighting\n",
                st->envlight_w, st->envlight_h);
    if (sc->envmiss != ENVMISS_ENVMAP)
        fprintf(stderr, "envtex: envmap sampling: none ('envmiss black': the envmap is a "
                        "background only)\n");
    else if (!st->envlight_sampled)
        fprintf(stderr,
                "envtex: envmap sampling: none (the '%s' integrator%s does not sample "
                "the envmap)\n",
                scene_integrator_name(sc->integrator),
                sc->integrator == INTEGRATOR_PATHTRACER ? " without next-event estimation" : "");
    else if (st->envlight_mode != ENVSAMPLING_UNIFORM)
        fprintf(stderr, "envtex: envmap sampling: '%s' tables (%s) built in %.3f s%s\n",
                scene_envsampling_name(st->envlight_mode),
                sc->envsampler == ENVSAMPLER_ALIAS ? "alias" : "binary search",
                st->envlight_seconds, st->envlight_fell_back ? " (black map: equal strata)" : "");
    else
        fprintf(stderr, "envtex: envmap sampling: uniform directions, no tables%s\n",
                st->envlight_fell_back && sc->envsampling != ENVSAMPLING_UNIFORM
                    ? " (black map: uniform fallback)"
                    : "");
    if (st->envlight_points)
        fprintf(stderr, "envtex: %s: %d point lights\n",
                st->envlight_mode == ENVSAMPLING_SIS ? "structured importance sampling"
                                                     : "median cut",
                st->envlight_points);
    if (st->envlight_built && sc->integrator == INTEGRATOR_PATHTRACER && sc->nee == NEE_MIS)
        fprintf(stderr,
                "envtex: MIS: the envmap is sampled at a fraction %.3g of its light "
                "samples (%s; kappa = E[L^2]/E[L]^2 = %.4g)%s\n",
                st->env_fraction,
                sc->envsamplefraction < 0 ? "auto: least variance x time, misfraction.h"
                                          : "envsamplefraction",
                st->envlight_kappa,
                st->nee == NEE_OFF ? "; no other light, so paths run as BRDF sampling alone" : "");
    if (st->envlight_bad_texels)
        fprintf(stderr,
                "envtex: warning: envmap %s: %ld NaN, Inf or negative texel values "
                "(used as 0)\n",
                e->path, st->envlight_bad_texels);
}

/* --verbose: what the render built and what it cost (a scene pays only for what it uses) */
static void verbose_report(const render_args *a, const scene *sc, const render_stats *st,
                           const budget *mem)
{
    fprintf(stderr,
            "envtex: scene %s: %dx%d, %ld spheres and %ld triangles as read (%ld "
            "primitives rendered), %d lights, %d materials\n",
            a->scene_path, sc->width, sc->height, sc->n_spheres, sc->n_triangles, st->prims,
            sc->n_lights, sc->n_materials);
    char peak[32], limit[32];
    budget_format(mem ? mem->peak : 0, peak, sizeof peak);
    budget_format(mem ? mem->limit : 0, limit, sizeof limit);
    fprintf(stderr,
            "envtex: %d input files, each read once (the scene, its envmap, textures, "
            "meshes%s); memory charged: %s at most, %s%s\n",
            sc->inputs.n, a->ref_path ? ", --ref" : "", peak, mem ? "of a budget of " : "no budget",
            mem ? limit : "");
    if (st->bvh_is_tree)
        fprintf(stderr, "envtex: built BVH: %ld nodes, depth %d, %.3f s\n", st->bvh_nodes,
                st->bvh_depth, st->build_seconds);
    else
        fprintf(stderr, "envtex: no BVH (%ld primitives <= %d: tested linearly)\n", st->prims,
                BVH_MIN_PRIMS);
    if (sc->envmap.present)
        verbose_envmap(sc, st);
    else
        fprintf(stderr, "envtex: no envmap\n");
    if (st->lights) {
        const char *how = sc->lightselection == LIGHTSELECTION_POWER
                              ? " (lightselection power: one a light sample, chosen by power)"
                              : " (lightselection all: lightsamples samples of each)";
        const char *plural = st->lights == 1 ? "" : "s";
        fprintf(stderr, "envtex: %d light%s to sample%s\n", st->lights, plural, *plural ? how : "");
    }
    if (sc->n_textures) {
        int mips = 0;
        for (int i = 0; i < sc->n_textures; i++) mips += sc->textures[i].tex.has_mip;
        fprintf(stderr,
                "envtex: %d textures (%d image files), %d mip pyramids (built only for "
                "trilinear/EWA)\n",
                sc->n_textures, sc->n_texture_images, mips);
    }
    if (st->ray_differentials)
        fprintf(stderr, "envtex: ray differentials traced (a trilinear, EWA or bump map needs "
                        "the footprint)\n");
    else
        fprintf(stderr, "envtex: no ray differentials traced (%s)\n",
                sc->n_textures ? "no trilinear, EWA or bump map: nearest and bilinear read one "
                                 "point"
                               : "no textures");
    if (st->displaced_spheres + st->displaced_triangles)
        fprintf(stderr,
                "envtex: displacement: %ld spheres (rate %d) and %ld triangles (rate %d) "
                "tessellated; the BVH holds %ld triangles\n",
                st->displaced_spheres, st->displace_sphere_rate, st->displaced_triangles,
                st->displace_triangle_rate, st->displaced_result);
}

/* The image and its variance, one output: a failure writing either leaves both targets
 * untouched (the image was once committed before a full disk refused the variance).  An
 * OpenEXR output records how it was made (exrfile.h): compare --test reads the sample counts. */
static int write_outputs(const render_args *a, const scene *sc, const render_stats *st,
                         const image *img, const image *var, error *err)
{
    exrfile_attrs at = {.spp = st->spp, .has_seed = 1, .seed = a->ro.seed};
    snprintf(at.integrator, sizeof at.integrator, "%s", scene_integrator_name(sc->integrator));
    snprintf(at.scene, sizeof at.scene, "%s", a->scene_path);
    tonemap_params tm = tonemap_defaults();
    tm.gamma = sc->gamma;
    const char *paths[2] = {a->out_path, a->var_path};
    const image *images[2] = {img, var};
    const tonemap_params *tms[2] = {&tm, NULL};
    const imageio_format formats[2] = {a->out_format, IMAGEIO_UNKNOWN};
    return imageio_write_set_attrs(a->var_path ? 2 : 1, paths, images, tms, formats, &at, err);
}

int cmd_render(int argc, char **argv)
{
    render_args a;
    if (parse_args(argc, argv, &a)) return 1;
    error err = {0};
    scene sc;
    budget mb;
    budget *mem = cli_run_budget(&mb, a.mem_limit);
    scene_load_opts lo = scene_load_defaults();
    lo.strict = a.strict;
    lo.mem = a.ro.mem = mem;
    static warnings ws; /* static: about 40 KB */
    lo.warn = warn_keep;
    lo.warn_ctx = &ws;
    if (scene_load(a.scene_path, &lo, &sc, &err)) return cli_fail(&err);
    a.out_from_scene = !a.out_path;
    if (!a.out_path) a.out_path = sc.output;

    /* Everything that can refuse the run is checked before the render and before the scene's
     * warnings are printed (render_scene's own checks too: it prints them through ro.start once
     * they have passed): a refused run prints one line and writes nothing. */
    int status = 1;
    image img = {0}, ref = {0}, var = {0};
    if (check_outputs(&a, &sc, &ws, &err)) goto done;
    if (a.var_path) a.ro.variance = &var;
    if (a.ref_path && read_ref(&a, &sc, mem, &ref, &err)) goto done;
    a.ro.warn = warn_keep; /* render_scene's own warnings join the scene's */
    a.ro.warn_ctx = &ws;
    if (!a.quiet) {
        a.ro.start = warnings_print_at_start;
        a.ro.start_ctx = &ws;
        if (isatty(STDERR_FILENO)) a.ro.progress = progress_bar;
    }
    render_stats st;
    if (render_scene(&sc, &a.ro, &img, &st, &err)) goto done;
    if (a.verbose) verbose_report(&a, &sc, &st, mem);
    compare_result cr; /* before any file is written: a failure here writes nothing */
    if (a.ref_path && compare_metrics(&img, &ref, &cr, &err)) {
        error_prefix(&err, "--ref %s", a.ref_path);
        goto done;
    }
    if (st.nonfinite_pixels)
        fprintf(stderr, "envtex: warning: %s: %ld pixels are NaN or Inf\n", a.scene_path,
                st.nonfinite_pixels);
    if (st.nonfinite_variance)
        fprintf(stderr, "envtex: warning: %s: %ld pixels of the variance image are NaN or Inf\n",
                a.var_path, st.nonfinite_variance);
    if (write_outputs(&a, &sc, &st, &img, &var, &err)) goto done;
    printf("time_s=%.3f spp=%d rays=%lld mrays_per_s=%.3f nonfinite=%ld build_s=%.3f", st.seconds,
           st.spp, st.rays, st.seconds > 0 ? st.rays / st.seconds / 1e6 : 0.0, st.nonfinite_pixels,
           st.build_seconds);
    if (a.ref_path)
        printf(" relmse=%.6g rmse=%.6g relmse_trim=%.6g", cr.relmse, cr.rmse, cr.relmse_trim);
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
