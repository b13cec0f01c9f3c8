/* commands_texture.c - envtex's texture commands (docs/scene-format.md "Textures"): textured
 * vertices and triangles, `texture` (an image file or a procedural kind), the material's maps,
 * mapping and filter, in the table commands_texture (parse.h). */
#include "parse.h"

#include <stdlib.h>
#include <string.h>

#include "envtex/textures/perlin.h"

static int cmd_vertextex(parser *p)
{
    double v[5];
    if (parse_arg_nums(p, 1, 5, v)) return -1;
    if (p->n_vtex >= p->max_prims)
        return parse_fail(p, "more than %ld textured vertices", p->max_prims);
    if (parse_grow(p, (void **)&p->vtex, &p->cap_vtex, p->n_vtex + 1, sizeof *p->vtex,
                   "textured vertices"))
        return -1;
    p->vtex[p->n_vtex++] = (vertex_tex){vec3_make(v[0], v[1], v[2]), {v[3], v[4]}};
    return 0;
}

static int cmd_tritex(parser *p)
{
    long idx[3];
    if (parse_tri_indices(p, p->n_vtex, "textured vertices", idx)) return -1;
    triangle t;
    memset(&t, 0, sizeof t);
    t.has_st = 1;
    for (int k = 0; k < 3; k++) {
        const vertex_tex *v = &p->vtex[idx[k]];
        t.q[k] = v->p;
        t.p[k] = mat4_point(&p->xf, v->p);
        t.st[k] = v->st;
    }
    return parse_add_triangle(p, &t);
}

static int cmd_texmapping(parser *p)
{
    static const char *const w[] = {"uv", "planar", "cylindrical", "spherical", "cube"};
    int k = 0;
    if (parse_arg_word(p, w, 5, &k)) return -1; /* texmapping_kind order */
    p->mat.texmapping = (texmapping_kind)k;
    p->mat.texmapping_given = 1;
    return 0;
}

static int cmd_texfilter(parser *p)
{
    static const char *const w[] = {"nearest", "bilinear", "trilinear", "ewa"};
    int k = 0;
    if (parse_arg_word(p, w, 4, &k)) return -1; /* texture_filter order */
    p->mat.texfilter = (texture_filter)k;
    return 0;
}

/* Texture names are found through a hash index (open addressing, at most half full), so a scene
 * of many `texture` lines reads in linear time (docs/design-notes.md, "The scene parser"). */
static size_t name_slot(const parser *p, const char *name)
{
    unsigned long h = 2166136261u; /* FNV-1a */
    for (const unsigned char *c = (const unsigned char *)name; *c; c++) h = (h ^ *c) * 16777619u;
    return (size_t)h & (p->tex_slots - 1);
}

/* Index of the texture called `name`, or -1. */
static int find_texture(const parser *p, const char *name)
{
    if (!p->tex_index) return -1;
    for (size_t k = name_slot(p, name);; k = (k + 1) & (p->tex_slots - 1)) {
        int i = p->tex_index[k];
        if (i < 0 || strcmp(p->sc->textures[i].name, name) == 0) return i;
    }
}

/* Put texture i (stored, named, not yet indexed) in the index, which doubles at half full. */
static int index_texture(parser *p, int i)
{
    if (2 * ((size_t)i + 1) > p->tex_slots) {
        size_t slots = p->tex_slots ? 2 * p->tex_slots : 64;
        int *slot = malloc(slots * sizeof *slot);
        if (!slot) return parse_fail(p, "out of memory for 'texture'");
        for (size_t k = 0; k < slots; k++) slot[k] = -1;
        free(p->tex_index);
        p->tex_index = slot;
        p->tex_slots = slots;
        for (int j = 0; j < i; j++) index_texture(p, j); /* fits: no growth */
    }
    size_t k = name_slot(p, p->sc->textures[i].name);
    while (p->tex_index[k] >= 0) k = (k + 1) & (p->tex_slots - 1);
    p->tex_index[k] = i;
    return 0;
}

/* The numbers after `texture NAME KIND` for each procedural kind, then two colours. */
static int texture_params(parser *p, texture_kind kind, scene_texture *st)
{
    /* arguments after NAME KIND: checker FREQ, perlin SCALE, fbm / turbulence SCALE OCTAVES,
     * marble SCALE FREQUENCY AMPLITUDE OCTAVES, wood SCALE RINGS AMPLITUDE; then c0, c1 */
    static const int nparams[] = {0, 1, 1, 2, 2, 4, 3}; /* texture_kind order */
    static const char *const usage[] = {"",
                                        "FREQUENCY",
                                        "SCALE",
                                        "SCALE OCTAVES",
                                        "SCALE OCTAVES",
                                        "SCALE FREQUENCY AMPLITUDE OCTAVES",
                                        "SCALE RINGS AMPLITUDE"};
    int np = nparams[kind], nargs = p->ntok - 1;
    if (nargs != 2 + np + 6)
        return parse_fail(p,
                          "'texture NAME %s' takes %s R0 G0 B0 R1 G1 B1 (%d arguments after the "
                          "kind), got %d",
                          texture_kind_name(kind), usage[kind], np + 6, nargs - 2);
    rgb c0, c1;
    if (parse_arg_rgb(p, 3 + np, &c0) || parse_arg_rgb(p, 6 + np, &c1)) return -1;
    error te;
    memset(&te, 0, sizeof te);
    if (kind == TEXTURE_CHECKER) {
        double f;
        if (parse_arg_nonneg(p, 3, 1, &f)) return -1;
        if (texture_init_checker(&st->tex, c0, c1, f, &te)) return parse_fail(p, "%s", te.msg);
        return 0;
    }
    texture_solid_params sp;
    memset(&sp, 0, sizeof sp);
    sp.c0 = c0;
    sp.c1 = c1;
    if (parse_arg_nonneg(p, 3, 1, &sp.scale)) return -1;
    long oct = 0;
    switch (kind) {
    case TEXTURE_FBM:
    case TEXTURE_TURBULENCE:
        if (parse_arg_int(p, 4, 1, PERLIN_MAX_OCTAVES, &oct)) return -1;
        break;
    case TEXTURE_MARBLE:
        if (parse_arg_nonneg(p, 4, 0, &sp.frequency) || parse_arg_num(p, 5, &sp.amplitude) ||
            parse_arg_int(p, 6, 1, PERLIN_MAX_OCTAVES, &oct))
            return -1;
        break;
    case TEXTURE_WOOD:
        if (parse_arg_nonneg(p, 4, 0, &sp.rings) || parse_arg_num(p, 5, &sp.amplitude)) return -1;
        break;
    default: break;
    }
    sp.octaves = (int)oct;
    if (texture_init_solid(&st->tex, kind, &sp, &te)) return parse_fail(p, "%s", te.msg);
    return 0;
}

/* `texture NAME FILE [repeat|clamp|mirror]` or `texture NAME KIND PARAMS... R0 G0 B0 R1 G1 B1`.
 * A kind keyword wins over a file of that name (write ./checker for the file). */
static int cmd_texture(parser *p)
{
    const char *name = p->tok[1];
    if (strlen(name) >= SCENE_MAX_TEXTURE_NAME)
        return parse_fail(p, "'texture' name '%s' is longer than %d bytes", name,
                          SCENE_MAX_TEXTURE_NAME - 1);
    int prev = find_texture(p, name);
    if (prev >= 0)
        return parse_fail(p, "texture '%s' defined twice (first at line %d)", name,
                          p->sc->textures[prev].line);
    if (p->sc->n_textures >= p->max_prims)
        return parse_fail(p, "more than %ld textures", p->max_prims);
    scene_texture st;
    memset(&st, 0, sizeof st);
    memcpy(st.name, name, strlen(name) + 1);
    st.line = p->line;
    st.image = -1;
    texture_kind kind;
    if (texture_kind_parse(p->tok[2], &kind) == 0) {
        if (texture_params(p, kind, &st)) return -1;
    } else {
        if (p->ntok - 1 > 3)
            return parse_fail(p, "'texture NAME FILE' takes a wrap mode at most, got '%s' after it",
                              p->tok[4]);
        st.wrap = WRAP_REPEAT;
        if (p->ntok - 1 == 3 && texlookup_wrap_parse(p->tok[3], &st.wrap))
            return parse_fail(p,
                              "'texture' wrap mode must be 'repeat', 'clamp' or 'mirror', got '%s'",
                              p->tok[3]);
        const char *file = p->tok[2];
        if (strlen(file) >= sizeof st.token)
            return parse_fail(p, "'texture' file name is longer than %zu bytes",
                              sizeof st.token - 1);
        if (parse_relative_path(p, file, st.path, sizeof st.path)) return -1;
        memcpy(st.token, file, strlen(file) + 1);
        st.tex.kind = TEXTURE_IMAGE; /* the image is read by assets_load_textures */
        st.tex.wrap = st.wrap;
    }
    scene *sc = p->sc;
    long cap = p->cap_textures;
    if (parse_grow(p, (void **)&sc->textures, &cap, (long)sc->n_textures + 1, sizeof *sc->textures,
                   "textures"))
        return -1;
    p->cap_textures = cap;
    sc->textures[sc->n_textures++] = st;
    return index_texture(p, sc->n_textures - 1);
}

/* diffusemap, specularmap, roughnessmap, emissionmap NAME; bumpmap NAME STRENGTH;
 * displacementmap NAME SCALE: material state naming a texture defined before. */
static int cmd_map(parser *p)
{
    int i = find_texture(p, p->tok[1]);
    if (i < 0)
        return parse_fail(p, "'%s': unknown texture '%s' (define it with 'texture' first)",
                          p->tok[0], p->tok[1]);
    double amount = 0;
    if (p->ntok - 1 == 2 && parse_arg_num(p, 2, &amount)) return -1;
    const char *k = p->tok[0];
    int ref = i + 1; /* 0 means none */
    if (strcmp(k, "diffusemap") == 0)
        p->mat.diffusemap = ref;
    else if (strcmp(k, "specularmap") == 0)
        p->mat.specularmap = ref;
    else if (strcmp(k, "roughnessmap") == 0)
        p->mat.roughnessmap = ref;
    else if (strcmp(k, "emissionmap") == 0)
        p->mat.emissionmap = ref;
    else if (strcmp(k, "bumpmap") == 0) {
        p->mat.bumpmap = ref;
        p->mat.bump_strength = amount;
    } else {
        p->mat.displacementmap = ref;
        p->mat.displacement_scale = amount;
    }
    return 0;
}

static int cmd_nomaps(parser *p)
{
    p->mat.diffusemap = p->mat.specularmap = p->mat.roughnessmap = 0;
    p->mat.emissionmap = p->mat.bumpmap = p->mat.displacementmap = 0;
    p->mat.bump_strength = p->mat.displacement_scale = 0;
    return 0;
}

const parse_command commands_texture[] = {
    {"vertextex", cmd_vertextex, 5, 5, NULL},
    {"tritex", cmd_tritex, 3, 3, NULL},
    {"texmapping", cmd_texmapping, 1, 1, NULL},
    {"texture", cmd_texture, 2, 12, "NAME FILE [WRAP] or NAME KIND PARAMS... R0 G0 B0 R1 G1 B1"},
    {"texfilter", cmd_texfilter, 1, 1, NULL},
    {"diffusemap", cmd_map, 1, 1, NULL},
    {"specularmap", cmd_map, 1, 1, NULL},
    {"roughnessmap", cmd_map, 1, 1, NULL},
    {"emissionmap", cmd_map, 1, 1, NULL},
    {"bumpmap", cmd_map, 2, 2, NULL},
    {"displacementmap", cmd_map, 2, 2, NULL},
    {"nomaps", cmd_nomaps, 0, 0, NULL},
    {NULL, NULL, 0, 0, NULL},
};
