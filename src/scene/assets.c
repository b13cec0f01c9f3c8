/* assets.c - the files a scene names, read once the last line is parsed: the envmap (one
 * image or six faces, a cross split into faces), the textures' images and their mip pyramids,
 * and OBJ meshes (parse.h). */
#include "parse.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envtex/io/imageio.h"

int assets_obj_mesh(parser *p, const char *path, const obj_mesh **out)
{
    infile_id id;
    int known = infile_identify(path, &id) == 0;
    for (int i = 0; known && i < p->n_objs; i++)
        if (infile_same(p->objs[i].id, id)) {
            *out = &p->objs[i].mesh;
            return 0;
        }
    obj_mesh m;
    error oe;
    memset(&oe, 0, sizeof oe);
    if (obj_load(path, p->max_prims, &m, p->mem, &oe)) {
        if (oe.line > 0)
            return parse_fail(p, "obj '%s': %s:%d: %s", p->tok[1], oe.file, oe.line, oe.msg);
        return parse_fail(p, "obj '%s': %s: %s", p->tok[1], oe.file, oe.msg);
    }
    if (!known || infile_list_add_id(&p->sc->inputs, path, id, p->err)) { /* (the file went away) */
        budget_release(p->mem, m.bytes);
        obj_free(&m);
        return known ? -1
                     : parse_fail(p, "obj '%s': the file changed while it was read", p->tok[1]);
    }
    if (p->n_objs == p->cap_objs) {
        int cap = p->cap_objs > 0 ? 2 * p->cap_objs : 4;
        parsed_obj *objs = realloc(p->objs, (size_t)cap * sizeof *objs);
        if (!objs) {
            budget_release(p->mem, m.bytes);
            obj_free(&m);
            return parse_fail(p, "out of memory for 'obj'");
        }
        p->objs = objs;
        p->cap_objs = cap;
    }
    p->objs[p->n_objs] = (parsed_obj){id, m};
    *out = &p->objs[p->n_objs++].mesh;
    return 0;
}

/* An envmap image problem, reported at the `envmap` line: "envmap 'TOKEN' (PATH): why" (the
 * resolved path only when it differs from the token). */
static int envmap_error(parser *p, int face, const char *why)
{
    scene_envmap *e = &p->sc->envmap;
    const char *token = p->envmap_token[face];
    const char *path = e->six_files ? e->face_path[face] : e->path;
    if (strcmp(token, path) == 0)
        return error_set(p->err, p->name, e->line, "envmap '%s': %s", token, why);
    return error_set(p->err, p->name, e->line, "envmap '%s' (%s): %s", token, path, why);
}

/* Bad texels (NaN, Inf; for radiance also negative) become 0 once, at load, with one warning
 * at the line that named the image. */
static void clean_texels(parser *p, image *im, int line, int radiance, const char *what,
                         const char *token)
{
    long n = radiance ? image_zero_nonfinite_or_negative(im) : image_zero_nonfinite(im);
    if (n == 0) return;
    int saved = p->line;
    p->line = line;
    parse_warn(p, "%s '%s': %ld %s texel value%s (used as 0)", what, token, n,
               radiance ? "NaN, infinite or negative" : "NaN or infinite", n == 1 ? "" : "s");
    p->line = saved;
}

/* The brightest channel value of an image (after clean_texels: finite, >= 0). */
static double brightest(const image *im)
{
    float m = 0;
    for (size_t i = 0; i < 3 * (size_t)im->w * (size_t)im->h; i++)
        m = im->px[i] > m ? im->px[i] : m;
    return m;
}

/* The scaled envmap must stay a float radiance: scale x the brightest texel <= FLT_MAX.  Past
 * it (`envmap big.pfm 1e300`) the map's radiance is Inf, and Inf x 0 makes NaN pixels.  The n
 * images are cleaned (finite texels), so a scale <= 1 needs no scan. */
static int check_envmap_scale(parser *p, const image *im, int n)
{
    scene_envmap *e = &p->sc->envmap;
    if (e->scale <= 1) return 0;
    double bright = 0;
    for (int f = 0; f < n; f++) bright = fmax(bright, brightest(&im[f]));
    if (!(e->scale * bright <= FLT_MAX)) {
        char why[160];
        snprintf(why, sizeof why,
                 "scale %g times its brightest texel %g is %g, above the largest float "
                 "radiance (%g)",
                 e->scale, bright, e->scale * bright, (double)FLT_MAX);
        return envmap_error(p, 0, why);
    }
    return 0;
}

/* Read envmap image `face` (0 for a one-file map) from `path` into *im, recording the file as an
 * input; a cube face that names the same file as an earlier face copies it (read once). */
static int read_envmap_image(parser *p, int face, const char *path, image *im)
{
    scene_envmap *e = &p->sc->envmap;
    error ie;
    memset(&ie, 0, sizeof ie);
    infile_id id, earlier;
    int known = infile_identify(path, &id) == 0;
    for (int f = 0; known && f < face; f++)
        if (infile_identify(e->face_path[f], &earlier) == 0 && infile_same(id, earlier)) {
            const image *src = &e->cube.face[f];
            double bytes = (double)src->w * src->h * IMAGE_TEXEL_BYTES;
            if (budget_charge(p->mem, bytes, path, 0, &ie, "%d x %d texels x %d bytes", src->w,
                              src->h, IMAGE_TEXEL_BYTES) ||
                image_alloc(im, src->w, src->h, &ie))
                return envmap_error(p, face, ie.msg);
            memcpy(im->px, src->px, (size_t)src->w * (size_t)src->h * IMAGE_TEXEL_BYTES);
            return 0;
        }
    if (imageio_read(path, im, p->mem, &ie)) return envmap_error(p, face, ie.msg);
    if (!known) return envmap_error(p, face, "the file changed while it was read");
    if (infile_list_add_id(&p->sc->inputs, path, id, &ie)) return envmap_error(p, face, ie.msg);
    clean_texels(p, im, e->line, 1, "envmap", p->envmap_token[face]);
    return 0;
}

/* A cross split into its six faces (half its texels), the cross then freed. */
static int split_cross(parser *p)
{
    scene_envmap *e = &p->sc->envmap;
    error ie;
    memset(&ie, 0, sizeof ie);
    double cross = (double)e->img.w * e->img.h * IMAGE_TEXEL_BYTES;
    if (budget_charge(p->mem, cross / 2, e->path, 0, &ie,
                      "six %d x %d cube faces of %d bytes a texel", e->img.w / 4, e->img.w / 4,
                      IMAGE_TEXEL_BYTES) ||
        cubemap_from_cross(&e->img, &e->cube, &ie))
        return envmap_error(p, 0, ie.msg);
    image_free(&e->img);
    budget_release(p->mem, cross);
    return 0;
}

int assets_load_envmap(parser *p)
{
    scene_envmap *e = &p->sc->envmap;
    error ie;
    memset(&ie, 0, sizeof ie);
    if (e->six_files) {
        for (int f = 0; f < CUBEMAP_FACES; f++) {
            image *im = &e->cube.face[f];
            if (read_envmap_image(p, f, e->face_path[f], im)) return -1;
            char why[128];
            if (im->w != im->h) {
                snprintf(why, sizeof why, "a cube face must be square, not %d x %d", im->w, im->h);
                return envmap_error(p, f, why);
            }
            if (im->w != e->cube.face[0].w) {
                snprintf(why, sizeof why, "cube faces differ in size: %d x %d here, %d x %d for +X",
                         im->w, im->h, e->cube.face[0].w, e->cube.face[0].h);
                return envmap_error(p, f, why);
            }
        }
        e->cube.size = e->cube.face[0].w;
        return check_envmap_scale(p, e->cube.face, CUBEMAP_FACES);
    }
    if (read_envmap_image(p, 0, e->path, &e->img)) return -1;
    if (check_envmap_scale(p, &e->img, 1)) return -1;
    if (!e->kind_given && convert_kind_detect(e->img.w, e->img.h, &e->kind, &ie))
        return envmap_error(p, 0, ie.msg);
    if (e->kind == CONVERT_CUBE && split_cross(p)) return -1;
    if (e->kind == CONVERT_CYLINDRICAL)
        e->max_height = convert_cylindrical_height(e->img.w, e->img.h);
    return 0;
}

/* "texture 'NAME' file 'TOKEN' (PATH): why" at the `texture` line, the resolved path only when
 * it differs from the token. */
static int texture_file_error(parser *p, const scene_texture *t, const char *why)
{
    if (strcmp(t->token, t->path) == 0)
        return error_set(p->err, p->name, t->line, "texture '%s' file '%s': %s", t->name, t->token,
                         why);
    return error_set(p->err, p->name, t->line, "texture '%s' file '%s' (%s): %s", t->name, t->token,
                     t->path, why);
}

/* Read the image of texture t, or share that of an earlier texture naming the same file (by
 * identity: a.png, ./a.png and a hard link are one file, read once). */
static int load_texture_image(parser *p, scene_texture *t)
{
    scene *sc = p->sc;
    int known = infile_identify(t->path, &t->file) == 0;
    for (int j = 0; known && j < sc->n_textures && &sc->textures[j] != t; j++)
        if (sc->textures[j].image >= 0 && infile_same(sc->textures[j].file, t->file)) {
            t->image = sc->textures[j].image;
            return 0;
        }
    error ie;
    memset(&ie, 0, sizeof ie);
    image *im = &sc->texture_images[sc->n_texture_images];
    if (imageio_read(t->path, im, p->mem, &ie)) return texture_file_error(p, t, ie.msg);
    t->image = sc->n_texture_images++; /* scene_free frees it from here on */
    if (!known) return texture_file_error(p, t, "the file changed while it was read");
    if (infile_list_add_id(&sc->inputs, t->path, t->file, &ie))
        return texture_file_error(p, t, ie.msg);
    clean_texels(p, im, t->line, 0, "texture file", t->token);
    return 0;
}

/* The texture whose pyramid texture i can use: the first with i's image and wrap mode (a mip
 * pyramid depends on nothing else), possibly i itself. */
static int pyramid_owner(const scene *sc, int i)
{
    const scene_texture *t = &sc->textures[i];
    for (int j = 0; j < i; j++)
        if (sc->textures[j].image == t->image && sc->textures[j].wrap == t->wrap) return j;
    return i;
}

int assets_load_textures(parser *p)
{
    scene *sc = p->sc;
    int n_images = 0;
    for (int i = 0; i < sc->n_textures; i++) n_images += sc->textures[i].tex.kind == TEXTURE_IMAGE;
    if (n_images > 0) {
        sc->texture_images = calloc((size_t)n_images, sizeof *sc->texture_images);
        if (!sc->texture_images) return error_set(p->err, p->name, 0, "out of memory for textures");
    }
    for (int i = 0; i < sc->n_textures; i++) {
        scene_texture *t = &sc->textures[i];
        if (t->tex.kind != TEXTURE_IMAGE) continue;
        if (load_texture_image(p, t)) return -1;
        texture_init_image(&t->tex, &sc->texture_images[t->image], t->wrap);
    }
    for (int m = 0; m < sc->n_materials; m++) {
        material *mt = &sc->materials[m];
        int *refs[6] = {&mt->diffusemap,  &mt->specularmap, &mt->roughnessmap,
                        &mt->emissionmap, &mt->bumpmap,     &mt->displacementmap};
        for (int k = 0; k < 6; k++) {
            if (*refs[k] <= 0) continue;
            if (sc->textures[*refs[k] - 1].image >= 0)
                *refs[k] = pyramid_owner(sc, *refs[k] - 1) + 1;
            scene_texture *t = &sc->textures[*refs[k] - 1];
            error ie;
            memset(&ie, 0, sizeof ie);
            if (texture_prepare(&t->tex, mt->texfilter, p->mem, &ie))
                return error_set(p->err, p->name, t->line, "texture '%s': %s", t->name, ie.msg);
        }
    }
    return 0;
}
