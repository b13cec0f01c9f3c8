/* scene.h - a scene as the CSE 167/168 `.test` file describes it, plus envtex's commands
 * (docs/scene-format.md lists every command, its arguments, defaults and limits).
 *
 *     scene sc;
 *     scene_load_opts o = scene_load_defaults();
 *     if (scene_load("data/scenes/mirror_sphere.test", &o, &sc, &err))
 *         error_print(&err, stderr);
 *     ... render ...
 *     scene_free(&sc);
 *
 * Data flows one way: scene file -> scene -> integrator -> image.  The scene holds only what
 * the file said, already in world space: triangles are transformed when read; spheres keep
 * their object-to-world matrix (a scaled sphere is an ellipsoid); lights keep world positions.
 * It builds no acceleration structure or sampling table: the integrator builds what it needs.
 */
#ifndef ENVTEX_SCENE_H
#define ENVTEX_SCENE_H

#include <stdint.h>

#include "envtex/core/budget.h"
#include "envtex/geometry/bvh.h"
#include "envtex/envmaps/convert.h"
#include "envtex/envlight/envlight.h"
#include "envtex/envlight/prefilter.h"
#include "envtex/reflection/envmap.h"
#include "envtex/core/error.h"
#include "envtex/core/image.h"
#include "envtex/io/infile.h"
#include "envtex/textures/texmapping.h"
#include "envtex/textures/texture.h"
#include "envtex/geometry/sphere.h"
#include "envtex/core/transform.h"
#include "envtex/geometry/triangle.h"
#include "envtex/core/vec.h"

/* Limits a scene may not exceed (checked when read, before anything is allocated). */
#define SCENE_MAX_SIZE 16384         /* image width or height */
#define SCENE_MAX_PIXELS (1L << 26)  /* width * height */
#define SCENE_MAX_SPP 1048576
/* width * height * spp: about 17 billion camera samples, an hour or more of rendering even for
 * the simplest scene; each limit alone would allow 2^46 (docs/robustness.md) */
#define SCENE_MAX_CAMERA_SAMPLES (1LL << 34)
#define SCENE_MAX_DEPTH 1000         /* maxdepth; -1 (unlimited, with Russian roulette) is allowed */
#define SCENE_MAX_LIGHTSAMPLES 65536
#define SCENE_MAX_PRIMS 50000000L    /* vertices, triangles or spheres */
#define SCENE_MAX_TRANSFORM_STACK 1024
#define SCENE_MAX_LINE 65536         /* bytes in one line, without its '\n' */
#define SCENE_MAX_TEXTURE_NAME 64    /* bytes in a texture's name, with its NUL */

typedef enum brdf_kind {
    BRDF_PHONG, /* course default: Blinn-Phong for `raytracer`, modified Phong for path tracers */
    BRDF_GGX,
    BRDF_MIRROR, /* perfect mirror weighted by `specular` */
    BRDF_GLASS   /* smooth dielectric, index `ior`, exact Fresnel */
} brdf_kind;

typedef struct material {
    rgb ambient, diffuse, specular, emission;
    double shininess;
    brdf_kind brdf;
    double roughness; /* GGX alpha */
    double ior;       /* index of refraction for BRDF_GLASS */
    /* texture maps (envtex; docs/scene-format.md "Textures").  Each map is 0 for none, else 1 +
     * an index into scene.textures (so a zeroed material has no maps): see scene_map(). */
    int diffusemap, specularmap, roughnessmap, emissionmap, bumpmap, displacementmap;
    double bump_strength;      /* `bumpmap NAME STRENGTH`: height units -> world units */
    double displacement_scale; /* `displacementmap NAME SCALE`: units per unit of value (world for triangles, object for spheres: displacemap.h) */
    texmapping_kind texmapping; /* `texmapping`, used when texmapping_given */
    int texmapping_given;      /* 0: the object's default (scene_material_texmapping) */
    texture_filter texfilter;  /* `texfilter`, default TEXFILTER_TRILINEAR */
} material;



typedef enum light_kind { LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_QUAD } light_kind;

typedef struct scene_light {
    light_kind kind;
    rgb color;          /* intensity (point, directional) or radiance L (quad) */
    vec3 dir;           /* directional: unit, world, pointing TOWARDS the light */
    vec3 pos;           /* point: world position; quad: corner a */
    vec3 ab, ac;        /* quad: world edges; emits on the side of ac x ab (FORMAT.md) */
    double atten[3];    /* point: constant, linear, quadratic */
} scene_light;

typedef enum integrator_kind {
    INTEGRATOR_RAYTRACER,
    INTEGRATOR_ANALYTICDIRECT,
    INTEGRATOR_DIRECT,
    INTEGRATOR_PATHTRACER,
    INTEGRATOR_PREFILTERED /* prefiltered.h: illumination maps instead of integrals */
} integrator_kind;

typedef enum nee_mode { NEE_OFF, NEE_ON, NEE_MIS } nee_mode;
/* `lightselection all|power` (envtex's): which lights direct lighting and NEE sample (lights.h) */
typedef enum light_selection {
    LIGHTSELECTION_ALL,  /* every light, `lightsamples` samples of each: the course's; default */
    LIGHTSELECTION_POWER /* each sample of one light picked by power: for scenes of many lights */
} light_selection;
typedef enum sampling_kind { SAMPLING_HEMISPHERE, SAMPLING_COSINE, SAMPLING_BRDF } sampling_kind;
typedef enum envmiss_mode { ENVMISS_ENVMAP, ENVMISS_BLACK } envmiss_mode;
#define SCENE_MAX_MEDIANCUT 65536

/* `envmap FILE [SCALE] [latlong|cube|cross|mirrorball|angular|cylindrical|equalarea]` or
 * `envmap cube PX NX PY NY PZ NZ [SCALE]` (docs/scene-format.md).  Without a keyword the
 * representation is detected from the image's shape when scene_load reads it (2:1 lat-long,
 * 4:3 or 3:4 a cube cross; a square image needs the keyword). */
typedef struct scene_envmap {
    int present;        /* 0: no envmap (rays that leave see black) */
    char path[1024];    /* resolved path (relative to the scene file's folder); the +X face
                           of the six-file form */
    double scale;       /* radiance multiplier, default 1 */
    mat4 xf, inv;       /* envmap frame -> world (transform current at `envmap`) and inverse */
    convert_kind kind;  /* the representation: CONVERT_LATLONG (0) unless named or detected */
    int kind_given;     /* 1: the line named it (keyword or six-file form); 0: detect */
    int six_files;      /* 1: `envmap cube PX NX PY NY PZ NZ` */
    char face_path[CUBEMAP_FACES][1024]; /* six_files: resolved paths, +X -X +Y -Y +Z -Z */
    image img;          /* the map for every kind but cube (lat-long, mirror ball, ...), loaded
                           by scene_load; owned */
    cubemap cube;       /* kind CONVERT_CUBE: the faces (six files, or a cross split); owned */
    double max_height;  /* kind CONVERT_CYLINDRICAL: half height h of the cylinder, set when
                           loaded to convert_cylindrical_height (pi H / W: square texels) */
    int line;           /* line of the `envmap` command, for messages */
} scene_envmap;

/* `texture NAME FILE [repeat|clamp|mirror]` or `texture NAME KIND PARAMS...` */
typedef struct scene_texture {
    char name[SCENE_MAX_TEXTURE_NAME];
    texture tex;        /* image textures: initialised by scene_load once the image is read
                           (load_images = 0 leaves tex.img NULL: not for rendering) */
    int image;          /* index into scene.texture_images, or -1 (procedural, or not loaded) */
    infile_id file;     /* image textures, once loaded: the file's identity (infile.h) */
    wrap_mode wrap;     /* image textures */
    char path[1024];    /* image textures: resolved path (relative to the scene's folder) */
    char token[1024];   /* the file name as written, for messages */
    int line;           /* line of the `texture` command */
} scene_texture;

typedef struct scene {
    /* image and camera */
    int width, height;         /* `size`; required */
    char output[1024];         /* `output`, default "raytrace.png", relative to the working folder */
    int output_line;           /* the line of `output` in the scene file; 0 for the default */
    int has_camera;
    vec3 eye, center, up;      /* `camera` */
    double fovy;               /* degrees */
    /* renderer settings */
    int maxdepth;              /* default 5; -1 unlimited */
    integrator_kind integrator;
    int spp;                   /* default 1 */
    int lightsamples;          /* default 1 */
    int lightstratify;         /* 0/1 */
    light_selection lightselection; /* default LIGHTSELECTION_ALL */
    nee_mode nee;
    int russianroulette;       /* 0/1 */
    sampling_kind importancesampling;
    double gamma;              /* 0: not given (PNG gets the sRGB curve) */
    envmiss_mode envmiss;
    envsampling_mode envsampling; /* default ENVSAMPLING_CDF */
    int mediancut_lights;      /* N of `envsampling mediancut N` or `sis N`, default 64 */
    envsampler_kind envsampler; /* default ENVSAMPLER_BINARY */
    double envsamplefraction;  /* `envsamplefraction F` in [0, 1]; -1 = auto (lights.h) */
    irradiance_method prefilter; /* `prefilter exact|sh9`, default exact */
    scene_envmap envmap;
    /* geometry, materials, lights: arrays owned by the scene */
    material *materials; int n_materials;
    sphere *spheres; long n_spheres;
    triangle *triangles; long n_triangles;
    scene_light *lights; int n_lights;
    /* textures (envtex): owned, freed by scene_free */
    scene_texture *textures; int n_textures;    /* in file order; material maps point here */
    image *texture_images; int n_texture_images; /* one per distinct file: read once */
    /* where it came from */
    char path[1024];
    infile_list inputs;        /* every file read: the scene itself, the envmap (or its faces),
                                  the textures and OBJ meshes, each once by identity (infile.h),
                                  so no output replaces one (main.c); owned */
} scene;

typedef void (*scene_warn_fn)(void *ctx, const error *warning);

typedef struct scene_load_opts {
    int strict;          /* unknown commands are errors instead of warnings */
    scene_warn_fn warn;  /* called for each warning (may be NULL: warnings are dropped) */
    void *warn_ctx;
    int load_images;     /* 1 (default): read the envmap and texture images (and build the
                          * pyramids their filters need); 0: leave them (parser tests) */
    long max_prims;      /* 0 (default): SCENE_MAX_PRIMS; a smaller limit lets tests reach it */
    budget *mem;         /* the run's memory budget (budget.h), charged before each allocation
                          * from what the file claims: the scene's arrays as they grow, OBJ
                          * meshes, images, mip pyramids; NULL (default): none, only the limits */
} scene_load_opts;

scene_load_opts scene_load_defaults(void);

/* Read and check a scene file.  On failure err names FILE:LINE and the offending token, *out
 * owns nothing, and -1 is returned.  On success free with scene_free.  `opts` may be NULL
 * (scene_load_defaults()).  Messages read like
 *     err->file "dir/x.test", err->line 7, err->msg "expected a number for 'sphere' argument 4,
 *     got 'abc'"
 * Errors found only at the end ("no 'size' command", "no 'camera' command") have line 0; an
 * envmap image that cannot be read is reported at the `envmap` line with the reader's reason.
 * The file is read a chunk at a time and each line is checked as it arrives (a NUL byte or a
 * line over SCENE_MAX_LINE bytes stops the reading there), so `path` may be a pipe (a FIFO
 * nobody writes to reads as empty; a device, socket or folder is refused: infile.h).
 * Every other file (envmap, cube faces, textures, OBJ meshes) must be a regular file, and is
 * read once however many lines name it and however they spell it (by identity: a.png, ./a.png,
 * a hard link): textures of one file share its image (and, with one wrap mode, its mip
 * pyramid), and each `obj` line of one mesh appends its own transformed triangles from one
 * parse.  What the scene holds stays charged to opts->mem (scene_free does not release it). */
int scene_load(const char *path, const scene_load_opts *opts, scene *out, error *err);

/* The same from a string in memory; `name` is used in messages and as the base folder for
 * relative file names ("-" or NULL: the working folder; NULL shows as "<string>" in messages
 * and leaves sc->path empty). */
int scene_load_string(const char *text, const char *name, const scene_load_opts *opts, scene *out,
                      error *err);

/* Free everything the scene owns and zero *sc (safe on a zeroed or already freed scene). */
void scene_free(scene *sc);

/* Default material state (ambient 0.2, all else 0, shininess 0, phong, roughness 0, ior 1.5). */
material scene_default_material(void);

/* "raytracer", "analyticdirect", "direct", "pathtracer" or "prefiltered" (static strings), as
 * in the file. */
const char *scene_integrator_name(integrator_kind k);
/* "uniform", "cdf", "cdf-sintheta", "mediancut" or "sis" (static strings), the words of
 * `envsampling`. */
const char *scene_envsampling_name(envsampling_mode m);

/* The scene's spheres and triangles, as bvh_build takes them (borrowed). */
static inline bvh_prims scene_prims(const scene *sc)
{
    return (bvh_prims){sc->spheres, sc->n_spheres, sc->triangles, sc->n_triangles, sc->path};
}

/* The scene's envmap as rays see it (envmap.h): borrowed, the scene must outlive *env.  A scene
 * without one, or whose envmap holds no pixels (a parser test's scene), gives present = 0. */
void scene_environment(const scene *sc, envmap *env);

/* The texture of a material map reference (0 = none): NULL, or the texture (owned by sc). */
static inline const texture *scene_map(const scene *sc, int ref)
{
    return ref > 0 && ref <= sc->n_textures ? &sc->textures[ref - 1].tex : NULL;
}

/* The (s, t) mapping material m uses on a sphere (is_sphere = 1) or a triangle: the one
 * `texmapping` gave, else spheres spherical and triangles uv.  `texmapping uv` on a sphere is
 * its natural parameterization, the spherical mapping. */
texmapping_kind scene_material_texmapping(const material *m, int is_sphere);

#endif
