/* obj.h - a Wavefront OBJ mesh reader: positions, texture coordinates and normals, with faces
 * fan-triangulated.  Lecture "Environment, Texture Maps", slides 25-27: texture coordinates are
 * given at the vertices (the `vt` records) and interpolated across each triangle.
 *
 *     obj_mesh m;
 *     if (obj_load("scenes/bunny.obj", 0, &m, &mem, &err)) ...  // err: "scenes/bunny.obj:12: ..."
 *     for (long i = 0; i < m.n_tris; i++) { const obj_triangle *t = &m.tris[i]; ... }
 *     obj_free(&m);
 *
 * What is read:
 *   v x y z [w] | v x y z r g b   position (extra numbers ignored)
 *   vt u [v [w]]                  texture coordinate (s, t) = (u, v); v defaults to 0
 *   vn x y z                      normal (not normalized here; zero is allowed)
 *   f c1 c2 c3 [c4 ...]           a face; each corner is  v | v/vt | v//vn | v/vt/vn
 *                                 polygons are fanned: (c1, c2, c3), (c1, c3, c4), ...
 * Indices are 1-based; a negative index counts back from the last record read so far (-1 is
 * the latest), as the format says.  Index 0, or one beyond the records read so far, is an error.
 * Every other statement (o, g, s, usemtl, mtllib, l, p, ...) is skipped and counted in
 * n_ignored (the first one's keyword and line are kept, so a caller can warn once).  Blank lines
 * and `#` comments (also after a statement) are skipped; a trailing `\r` is white space.  A
 * UTF-8 byte-order mark (EF BB BF) at the start of the text is skipped, as in scene files.
 *
 * Errors are values: err->file is the OBJ's name, err->line the line, err->msg what is wrong
 * ("expected a number for 'v', got 'abc'", "index 9 of 'f' is out of range: 8 vertices so far",
 * "more than 1000 vertices").  Numbers must be finite (nan, inf, 1e999 are errors).  The count
 * of each record is checked against `max_elems`, and what an array grows by (its capacity
 * doubles: 24 bytes a vertex or normal, 16 a texture coordinate, 72 a triangle) is charged to
 * the memory budget `mem` (budget.h; NULL: none), BEFORE the array grows.
 */
#ifndef ENVTEX_OBJ_H
#define ENVTEX_OBJ_H

#include "envtex/core/budget.h"
#include "envtex/core/error.h"
#include "envtex/core/vec.h"

/* Default limit on each of v, vt, vn and triangles (the scene's SCENE_MAX_PRIMS). */
#define OBJ_MAX_ELEMS 50000000L

/* Longest line accepted, in bytes (a face with thousands of corners still fits). */
#define OBJ_MAX_LINE 65536

typedef struct obj_triangle {
    long v[3];  /* 0-based indices into obj_mesh.v */
    long vt[3]; /* into obj_mesh.vt, or -1 where the corner has none */
    long vn[3]; /* into obj_mesh.vn, or -1 */
} obj_triangle;

typedef struct obj_mesh {
    vec3 *v; long n_v;
    uv2 *vt; long n_vt;
    vec3 *vn; long n_vn;
    obj_triangle *tris; long n_tris;
    double bytes;              /* what the arrays hold (their capacity), charged to the budget */
    long n_ignored;            /* statements skipped */
    char first_ignored[32];    /* the first skipped keyword (truncated), "" if none */
    int first_ignored_line;
} obj_mesh;

/* Read the regular file `path` (an OBJ) into *out (arrays owned by *out; free with obj_free).
 * max_elems: limit on each record count; 0 means OBJ_MAX_ELEMS.  `mem`: the run's memory budget
 * (may be NULL), charged the file's bytes while it is read and out->bytes, which stay charged
 * (obj_free does not release them).  Returns 0, or -1 with *err set (file and line) and *out
 * owning nothing (and nothing left charged). */
int obj_load(const char *path, long max_elems, obj_mesh *out, budget *mem, error *err);

/* The same from text in memory (NUL-terminated); `name` is used in messages. */
int obj_load_string(const char *text, const char *name, long max_elems, obj_mesh *out, budget *mem,
                    error *err);

/* Free the arrays and zero *m.  Safe on a zeroed or freed mesh. */
void obj_free(obj_mesh *m);

#endif
