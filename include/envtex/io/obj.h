/* obj.h - a Wavefront OBJ reader: positions, normals and texture coordinates (slides 36-37
 * (Interpolating Texture Coordinates): given at the vertices, interpolated across each triangle),
 * faces fan-triangulated.
 *
 *     if (obj_load("bunny.obj", 0, &m, &mem, &err)) ...  // err: "bunny.obj:12: ..."
 *
 * Reads v, vt u [v] (v = 0 by default), vn (as given), f with corners v, v/vt, v//vn, v/vt/vn.
 * Indices are 1-based, negative from the latest record; 0 or beyond is an error.  Other
 * statements are skipped and counted.  Numbers must be finite.
 */
#ifndef ENVTEX_OBJ_H
#define ENVTEX_OBJ_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/vec.h"

/* Default limit on each of v, vt, vn and triangles. */
#define OBJ_MAX_ELEMS 50000000L

/* Longest line accepted, in bytes. */
#define OBJ_MAX_LINE 65536

typedef struct obj_triangle {
    long v[3];  /* 0-based indices into obj_mesh.v */
    long vt[3]; /* into obj_mesh.vt, or -1 where the corner has none */
    long vn[3]; /* into obj_mesh.vn, or -1 */
} obj_triangle;

typedef struct obj_mesh {
    vec3 *v;
    long n_v;
    uv2 *vt;
    long n_vt;
    vec3 *vn;
    long n_vn;
    obj_triangle *tris;
    long n_tris;
    double bytes;           /* the arrays' capacity, charged */
    long n_ignored;         /* statements skipped */
    char first_ignored[32]; /* the first skipped keyword, "" if none */
    int first_ignored_line;
} obj_mesh;

/* Read the regular file `path` into *out (owning the arrays: obj_free); max_elems 0 is
 * OBJ_MAX_ELEMS.  `mem` (NULL: none): the file while read, out->bytes, which stay.  0, or -1
 * with *err (file, line), *out owning nothing and nothing charged. */
int obj_load(const char *path, long max_elems, obj_mesh *out, budget *mem, error *err);

/* The same from NUL-terminated text; `name` in messages. */
int obj_load_string(const char *text, const char *name, long max_elems, obj_mesh *out, budget *mem,
                    error *err);

/* Free and zero *m; safe on a zeroed or freed mesh. */
void obj_free(obj_mesh *m);

#endif
