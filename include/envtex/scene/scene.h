/* scene.h - a scene as a CSE 167/168 `.test` file and envtex's commands describe it
 * (docs/scene-format.md: every command, its defaults and limits); scene_load.h reads one.
 *
 *     if (scene_load(path, NULL, &sc, &err)) ...   ... render ...   scene_free(&sc);
 *
 * The scene holds what the file said, in world space (triangles transformed when read, spheres
 * with their object-to-world matrix, lights at world positions); no BVH or sampling table.
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

/* Limits a scene may not exceed (checked when read, before allocating). */
#define SCENE_MAX_SIZE            16384      /* image width or height */
#define SCENE_MAX_PIXELS          (1L << 26) /* width * height */
#define SCENE_MAX_SPP             1048576
#define SCENE_MAX_CAMERA_SAMPLES  (1LL << 34) /* width * height * spp (docs/robustness.md) */
#define SCENE_MAX_DEPTH           1000        /* maxdepth; -1 (unlimited) is allowed */
#define SCENE_MAX_LIGHTSAMPLES    65536
#define SCENE_MAX_PRIMS           50000000L /* vertices, triangles or spheres */
#define SCENE_MAX_TRANSFORM_STACK 1024
#define SCENE_MAX_LINE            65536 /* bytes in one line, without its '\n' */
#define SCENE_MAX_TEXTURE_NAME    64    /* bytes in a texture's name, with its NUL */

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
    /* texture maps (docs/scene-format.md "Textures"): 0 none, else 1 + an index into
     * scene.textures (scene_map) */
    int diffusemap, specularmap, roughnessmap, emissionmap, bumpmap, displacementmap;
    double bump_strength;       /* `bumpmap NAME STRENGTH`: height units -> world units */
    double displacement_scale;  /* `displacementmap NAME SCALE` (displacemap.h) */
    texmapping_kind texmapping; /* `texmapping`, used when texmapping_given */
    int texmapping_given;       /* 0: the default (scene_material_texmapping) */
    texture_filter texfilter;   /* `texfilter`, default TEXFILTER_TRILINEAR */
} material;

typedef enum light_kind { LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_QUAD } light_kind;

typedef struct scene_light {
    light_kind kind;
    rgb color;       /* intensity (point, directional) or radiance L (quad) */
    vec3 dir;        /* directional: unit, world, pointing TOWARDS the light */
    vec3 pos;        /* point: world position; quad: corner a */
    vec3 ab, ac;     /* quad: world edges; emits on the side of ac x ab */
    double atten[3]; /* point: constant, linear, quadratic */
} scene_light;

typedef enum integrator_kind {
    INTEGRATOR_RAYTRACER,
    INTEGRATOR_ANALYTICDIRECT,
    INTEGRATOR_DIRECT,
    INTEGRATOR_PATHTRACER,
    INTEGRATOR_PREFILTERED /* illumination maps instead of integrals (prefiltered.h) */
} integrator_kind;

typedef enum nee_mode { NEE_OFF, NEE_ON, NEE_MIS } nee_mode;
/* `lightselection`: which lights direct lighting and NEE sample (lights.h) */
typedef enum light_selection {
    LIGHTSELECTION_ALL,  /* every light, `lightsamples` samples of each: the course's; default */
    LIGHTSELECTION_POWER /* each sample one light, picked by power */
} light_selection;
typedef enum sampling_kind { SAMPLING_HEMISPHERE, SAMPLING_COSINE, SAMPLING_BRDF } sampling_kind;
typedef enum envmiss_mode { ENVMISS_ENVMAP, ENVMISS_BLACK } envmiss_mode;
#define SCENE_MAX_MEDIANCUT 65536

/* `envmap FILE [SCALE] [REPRESENTATION]` or `envmap cube PX NX PY NY PZ NZ [SCALE]` (no keyword:
 * by shape, convert_kind_detect). */
typedef struct scene_envmap {
    int present;       /* 0: no envmap (rays that leave see black) */
    char path[1024];   /* resolved (against the scene's folder); six files: the +X face */
    double scale;      /* radiance multiplier, default 1 */
    mat4 xf, inv;      /* envmap frame -> world (transform current at `envmap`) and inverse */
    convert_kind kind; /* the representation: CONVERT_LATLONG (0) unless named or detected */
    int kind_given;    /* 1: the line named it; 0: detected */
    int six_files;     /* 1: `envmap cube PX NX ...` */
    char face_path[CUBEMAP_FACES][1024]; /* six_files: resolved paths, +X -X +Y -Y +Z -Z */
    image img;                           /* the map (every kind but cube); owned */
    cubemap cube;      /* CONVERT_CUBE: the faces (six files, or a cross split); owned */
    double max_height; /* CONVERT_CYLINDRICAL: convert_cylindrical_height */
    int line;          /* the `envmap` line */
} scene_envmap;

/* `texture NAME FILE [WRAP]` or `texture NAME KIND PARAMS...` */
typedef struct scene_texture {
    char name[SCENE_MAX_TEXTURE_NAME];
    texture tex;    /* an image texture's tex.img is NULL unless load_images */
    int image;      /* index into scene.texture_images, or -1 (procedural, not loaded) */
    infile_id file; /* once loaded: the file's identity (infile.h) */
    wrap_mode wrap;
    char path[1024];  /* resolved against the scene's folder */
    char token[1024]; /* the file name as written */
    int line;         /* the `texture` line */
} scene_texture;

typedef struct scene {
    /* image and camera */
    int width, height; /* `size`; required */
    char output[1024]; /* `output`, default "raytrace.png" (the working folder's) */
    int output_line;   /* its line; 0 for the default */
    int has_camera;
    vec3 eye, center, up; /* `camera` */
    double fovy;          /* degrees */
    /* renderer settings */
    int maxdepth; /* default 5; -1 unlimited */
    integrator_kind integrator;
    int spp;                        /* default 1 */
    int lightsamples;               /* default 1 */
    int lightstratify;              /* 0/1 */
    light_selection lightselection; /* default LIGHTSELECTION_ALL */
    nee_mode nee;
    int russianroulette; /* 0/1 */
    sampling_kind importancesampling;
    double gamma; /* 0: not given (PNG gets the sRGB curve) */
    envmiss_mode envmiss;
    envsampling_mode envsampling; /* default ENVSAMPLING_CDF */
    int mediancut_lights;         /* N of `envsampling mediancut N` or `sis N`, default 64 */
    envsampler_kind envsampler;   /* default ENVSAMPLER_BINARY */
    double envsamplefraction;     /* in [0, 1]; -1 = auto (lights.h) */
    irradiance_method prefilter;  /* `prefilter exact|sh9`, default exact */
    scene_envmap envmap;
    /* geometry, materials, lights: owned */
    material *materials;
    int n_materials;
    sphere *spheres;
    long n_spheres;
    triangle *triangles;
    long n_triangles;
    scene_light *lights;
    int n_lights;
    /* textures: owned */
    scene_texture *textures;
    int n_textures; /* in file order; the maps' references */
    image *texture_images;
    int n_texture_images; /* one per distinct file */
    /* where it came from */
    char path[1024];
    infile_list inputs; /* every file read, once by identity (infile.h); owned */
} scene;

/* A warning (FILE:LINE: what) for the caller, with its ctx; *warning is valid during the call. */
typedef void (*scene_warn_fn)(void *ctx, const error *warning);

/* Free everything the scene owns and zero *sc (safe on a zeroed or already freed scene). */
void scene_free(scene *sc);

/* Default material state (ambient 0.2, all else 0, shininess 0, phong, roughness 0, ior 1.5). */
material scene_default_material(void);

/* The integrator's word in the file (a static string). */
const char *scene_integrator_name(integrator_kind k);
/* The word of `envsampling` for m (a static string). */
const char *scene_envsampling_name(envsampling_mode m);

/* The scene's spheres and triangles, as bvh_build takes them (borrowed; no quads: lights.h). */
static inline bvh_prims scene_prims(const scene *sc)
{
    return (bvh_prims){
        sc->spheres, sc->n_spheres, sc->triangles, sc->n_triangles, sc->path, NULL, 0};
}

/* The scene's envmap as rays see it (envmap.h), borrowed: the scene must outlive *env.  No
 * envmap, or one without pixels (not loaded), gives present = 0. */
void scene_environment(const scene *sc, envmap *env);

/* The texture of a material's map reference: NULL for 0 (none), else owned by sc. */
static inline const texture *scene_map(const scene *sc, int ref)
{
    return ref > 0 && ref <= sc->n_textures ? &sc->textures[ref - 1].tex : NULL;
}

/* The (s, t) mapping m uses on a sphere (is_sphere = 1) or a triangle: `texmapping`'s, else
 * spherical and uv; uv on a sphere is its own parameterization, spherical. */
texmapping_kind scene_material_texmapping(const material *m, int is_sphere);

#endif
