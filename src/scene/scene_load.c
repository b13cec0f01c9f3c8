/* scene_load.c - scene_load and scene_load_string (scene_load.h): the lines of a file or a
 * string, one at a time, through the parser (parse.h). */
#include "envtex/scene/scene_load.h"

#include <assert.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "parse.h"

/* The scene before its first line: the course's defaults (docs/scene-format.md). */
static void scene_init(scene *sc)
{
    memset(sc, 0, sizeof *sc);
    snprintf(sc->output, sizeof sc->output, "raytrace.png");
    sc->maxdepth = 5;
    sc->integrator = INTEGRATOR_RAYTRACER;
    sc->spp = 1;
    sc->lightsamples = 1;
    sc->lightselection = LIGHTSELECTION_ALL;
    sc->nee = NEE_OFF;
    sc->importancesampling = SAMPLING_HEMISPHERE;
    sc->envmiss = ENVMISS_ENVMAP;
    sc->envsampling = ENVSAMPLING_CDF;
    sc->mediancut_lights = 64;
    sc->envsampler = ENVSAMPLER_BINARY;
    sc->envsamplefraction = -1; /* auto */
    sc->envmap.scale = 1.0;
    sc->envmap.xf = mat4_identity();
    sc->envmap.inv = mat4_identity();
    sc->fovy = 0;
}

/* Where the lines come from: a string (text, len), or a file read a chunk at a time, so that a
 * scene is checked as it arrives: /dev/zero or a binary file fails at its first NUL byte or
 * over-long line, not when memory runs out. */
#define SCENE_READ_CHUNK (1 << 16)
typedef struct line_source {
    FILE *f;           /* NULL for a string */
    const char *chunk; /* the string, or `buf` below for a file */
    size_t len, pos;   /* bytes in chunk, and the next one to read */
    int eof;           /* nothing more to come after chunk */
    char *buf;         /* a file's chunk buffer (SCENE_READ_CHUNK bytes) */
} line_source;

/* The next line (without its '\n') into line[0..n-1], NUL-terminated; line has room for
 * SCENE_MAX_LINE + 4 bytes (a first line may carry a 3-byte byte-order mark).  Returns 1 for a
 * line, 0 at the end, -1 on error: a NUL byte or a line over SCENE_MAX_LINE bytes (reported at
 * the parser's current line), or a read error (reported for the file, line 0). */
static int next_line(parser *p, line_source *src, char *line, size_t *n_out)
{
    size_t n = 0, limit = SCENE_MAX_LINE + (p->line == 1 ? 3 : 0);
    int any = 0; /* a byte of this line (or its '\n') was read */
    for (;;) {
        if (src->pos == src->len) {
            if (src->eof || !src->f) break;
            src->len = fread(src->buf, 1, SCENE_READ_CHUNK, src->f);
            src->pos = 0;
            if (src->len == 0) {
                if (ferror(src->f)) /* the file's fault, not a line's: no line number */
                    return error_set(p->err, p->name, 0, "cannot read: %s", strerror(errno));
                src->eof = 1;
            }
            continue;
        }
        const char *start = src->chunk + src->pos;
        size_t avail = src->len - src->pos;
        const char *nl = memchr(start, '\n', avail);
        size_t take = nl ? (size_t)(nl - start) : avail;
        any = 1;
        if (take > limit - n) return parse_fail(p, "line is longer than %d bytes", SCENE_MAX_LINE);
        if (memchr(start, '\0', take)) return parse_fail(p, "NUL byte in the file (binary file?)");
        memcpy(line + n, start, take);
        n += take;
        src->pos += take + (nl != NULL);
        if (nl) break;
    }
    if (!any) return 0;
    line[n] = '\0';
    /* a UTF-8 byte-order mark some editors write is not part of the first keyword */
    if (p->line == 1 && n >= 3 && memcmp(line, "\xEF\xBB\xBF", 3) == 0) {
        memmove(line, line + 3, n - 2);
        n -= 3;
    }
    if (n > SCENE_MAX_LINE) return parse_fail(p, "line is longer than %d bytes", SCENE_MAX_LINE);
    *n_out = n;
    return 1;
}

/* A parser for scene *sc (not touched here) at the file's start: identity transform, the
 * default material, attenuation 1 0 0, the options copied. */
static void parser_init(parser *p, scene *sc, const scene_load_opts *opts, const char *name,
                        error *err)
{
    memset(p, 0, sizeof *p);
    p->sc = sc;
    p->strict = opts->strict;
    p->warn = opts->warn;
    p->warn_ctx = opts->warn_ctx;
    p->load_images = opts->load_images;
    p->mem = opts->mem;
    p->name = name ? name : "<string>";
    p->err = err;
    p->xf = mat4_identity();
    p->mat = scene_default_material();
    p->atten[0] = 1.0; /* attenuation 1 0 0: no fall-off */
    p->max_prims = opts->max_prims > 0 && opts->max_prims < SCENE_MAX_PRIMS ? opts->max_prims
                                                                            : SCENE_MAX_PRIMS;
}

/* The scene's path (sc->path) and the folder its relative file names are read from (p->base),
 * from `name` ("-" or NULL: the working folder). */
static int scene_paths(parser *p, const char *name)
{
    scene *out = p->sc;
    if (!name) return 0;
    if (strcmp(name, "-") == 0) {
        memcpy(out->path, "-", 2);
        return 0;
    }
    size_t n = strlen(name);
    if (n >= sizeof out->path)
        return error_set(p->err, name, 0, "scene path is longer than %zu bytes",
                         sizeof out->path - 1);
    memcpy(out->path, name, n + 1);
    const char *slash = strrchr(name, '/');
    if (!slash) return 0;
    size_t b = (size_t)(slash - name) + 1;
    if (b >= sizeof p->base)
        return error_set(p->err, name, 0, "scene folder is longer than %zu bytes",
                         sizeof p->base - 1);
    memcpy(p->base, name, b);
    p->base[b] = '\0';
    return 0;
}

/* Parse the lines of `src` into *out. */
static int load_lines(line_source *src, const char *name, const scene_load_opts *opts, scene *out,
                      error *err)
{
    scene_load_opts defaults = scene_load_defaults();
    parser p;
    parser_init(&p, out, opts ? opts : &defaults, name, err);
    scene_init(out);
    int rc = -1;
    char *buf = NULL;
    if (scene_paths(&p, name)) goto done;
    buf = malloc(SCENE_MAX_LINE + 4);
    if (!buf) {
        error_set(err, p.name, 0, "out of memory");
        goto done;
    }
    for (;;) {
        p.line++;
        size_t n;
        int got = next_line(&p, src, buf, &n);
        if (got < 0) goto done;
        if (got == 0) break; /* the end (parse_finish sets the line to 0) */
        if (parse_run_line(&p, buf)) goto done;
    }
    if (parse_finish(&p)) goto done;
    rc = 0;
done:
    free(buf);
    parse_free(&p);
    if (rc) scene_free(out);
    return rc;
}

scene_load_opts scene_load_defaults(void)
{
    scene_load_opts o;
    memset(&o, 0, sizeof o);
    o.load_images = 1;
    return o;
}

int scene_load_string(const char *text, const char *name, const scene_load_opts *opts, scene *out,
                      error *err)
{
    assert(text && out);
    line_source src = {NULL, text, strlen(text), 0, 1, NULL};
    return load_lines(&src, name, opts, out, err);
}

int scene_load(const char *path, const scene_load_opts *opts, scene *out, error *err)
{
    assert(path && out);
    memset(out, 0, sizeof *out);
    infile_id id;
    int fd = infile_open_stream(path, &id, err); /* a regular file or a pipe, never blocking */
    if (fd < 0) return -1;
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        int e = errno;
        close(fd);
        return error_set(err, path, 0, "cannot open: %s", strerror(e));
    }
    int rc = -1;
    char *chunk = malloc(SCENE_READ_CHUNK);
    if (!chunk) {
        error_set(err, path, 0, "out of memory");
    } else {
        line_source src = {f, chunk, 0, 0, 0, chunk};
        rc = load_lines(&src, path, opts, out, err);
    }
    if (rc == 0 && infile_list_add_id(&out->inputs, path, id, err)) { /* the scene's own file */
        scene_free(out);
        rc = -1;
    }
    free(chunk);
    fclose(f);
    return rc;
}
