/* displacemap.c - displacement maps applied to a scene before rendering
 * (see include/envtex/scene/displacemap.h). */
#include "envtex/scene/displacemap.h"

#include <stdlib.h>
#include <string.h>

#include "envtex/geometry/bvh.h"
#include "envtex/textures/displace.h"

static const texture *disp_map(const scene *sc, int material)
{
    return scene_map(sc, sc->materials[material].displacementmap);
}

int displacemap_needed(const scene *sc)
{
    for (long i = 0; i < sc->n_spheres; i++)
        if (disp_map(sc, sc->spheres[i].material)) return 1;
    for (long i = 0; i < sc->n_triangles; i++)
        if (disp_map(sc, sc->triangles[i].material)) return 1;
    return 0;
}

/* What the height callbacks need. */
typedef struct height_ctx {
    const texture *tex;
    const material *m;
    texmapping_kind mapping;
    /* sphere: object space = center + radius p */
    vec3 center;
    double radius;
    /* triangle: q and the normal before displacement of each vertex, in the callback's order */
    vec3 *qv, *nv;
    long n_q, cap_q;
} height_ctx;

static double eval_height(const height_ctx *c, uv2 st, vec3 q)
{
    texture_query tq = {0};
    tq.st = st;
    tq.p = q;
    tq.filter = c->m->texfilter; /* no footprint: the full-resolution texture */
    return texture_eval_scalar(c->tex, &tq);
}

static double sphere_height(void *ctx, vec3 p, vec3 n, uv2 st)
{
    (void)n;
    const height_ctx *c = ctx;
    if (c->mapping != TEXMAPPING_SPHERICAL) st = texmapping_point(c->mapping, p);
    return eval_height(c, st, vec3_madd(c->center, p, c->radius)); /* P_object = c + R p */
}

/* Corner (s, t) of a displaced sphere's triangle under the sphere's mapping (never uv), from
 * the tessellation's spherical corner st (displace.h: s up to 1 across the seam, a pole corner
 * at the middle s of its segment).  The mapping sees what the undisplaced sphere's does, the
 * unit direction u = (sin theta cos phi, sin theta sin phi, cos theta) with phi = 2 pi s,
 * theta = pi (1 - t), and never the displaced object point: texshade would map that point as
 * a triangle's (no centre, no radius) and show the texture elsewhere.
 *   spherical    the tessellation's st itself
 *   cylindrical  its s (seam-aware), t = u.z
 *   planar       (u.x, u.y)
 *   cube         every corner projected on the face of the triangle's centre direction
 *                (texmapping_cube_face), so a triangle across a face edge is not torn apart */
static void sphere_corner_st(texmapping_kind mapping, const uv2 sph[3], uv2 out[3])
{
    vec3 u[3], mid = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        double phi = 2 * M_PI * sph[k].u, theta = M_PI * (1.0 - sph[k].v);
        u[k] = vec3_make(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
        mid = vec3_add(mid, u[k]);
    }
    int face = 0;
    if (mapping == TEXMAPPING_CUBE) texmapping_cube(mid, &face);
    for (int k = 0; k < 3; k++) {
        switch (mapping) {
        case TEXMAPPING_CYLINDRICAL: out[k] = (uv2){sph[k].u, u[k].z}; break; /* (phi / 2 pi, z) */
        case TEXMAPPING_PLANAR: out[k] = (uv2){u[k].x, u[k].y}; break;        /* (x, y) */
        case TEXMAPPING_CUBE: out[k] = texmapping_cube_face(u[k], face); break;
        default: out[k] = sph[k]; break; /* spherical: (phi / 2 pi, 1 - theta / pi) */
        }
    }
}

/* The height at a triangle's grid vertex: q is its object-space point, interpolated from the
 * corners q like the world point (displace_triangle), so neighbours that share an edge see the
 * same q there, read the same height and move their shared vertices alike (the weld below needs
 * bit-equal positions). */
static double triangle_height(void *ctx, vec3 q, vec3 n, uv2 st)
{
    height_ctx *c = ctx;
    if (c->n_q < c->cap_q) {
        c->qv[c->n_q] = q;
        c->nv[c->n_q] = n;
    }
    c->n_q++;
    if (c->mapping != TEXMAPPING_UV) st = texmapping_point(c->mapping, q);
    return eval_height(c, st, q);
}

/* Triangles the displaced scene needs at the given rates. */
static long count_tris(const scene *in, int srate, int trate)
{
    long n = 0;
    for (long i = 0; i < in->n_spheres; i++)
        n += disp_map(in, in->spheres[i].material) ? 4L * srate * (srate - 1) : 0;
    for (long i = 0; i < in->n_triangles; i++)
        n += disp_map(in, in->triangles[i].material) ? (long)trate * trate : 1;
    return n;
}

/* ---- corner normals of triangles without normals ------------------------------------------
 * Each displaced triangle is tessellated on its own, so a shared edge is moved alike on both
 * sides only if both sides move its points along the same normals.  The geometric normals of
 * two triangles that meet at an angle differ, and would open a crack along the edge up to
 * twice as wide as the displacement h (2 h sin(a / 2), a the angle between the normals); so a
 * corner without a normal takes the angle-weighted mean of the unit geometric normals of every
 * displaced triangle without normals at the same position (Thurmer and Wuthrich's weights: a
 * corner's share does not depend on how its face is split into triangles). */

/* One corner: where it is (its position p and a normal n, both compared exactly), and which it
 * is (corner `k` of triangle `tri`). */
typedef struct corner_ref {
    vec3 p, n;
    long tri;
    int k;
} corner_ref;

static int vec3_order(vec3 a, vec3 b)
{
    if (a.x != b.x) return a.x < b.x ? -1 : 1;
    if (a.y != b.y) return a.y < b.y ? -1 : 1;
    if (a.z != b.z) return a.z < b.z ? -1 : 1;
    return 0;
}

/* Order corners by p, then n: corners at the same place end up adjacent. */
static int corner_order(const void *a, const void *b)
{
    const corner_ref *ca = a, *cb = b;
    int o = vec3_order(ca->p, cb->p);
    return o ? o : vec3_order(ca->n, cb->n);
}

/* The unit geometric normal of tr, or -1 for a zero-area triangle. */
static int face_normal(const triangle *tr, vec3 *n)
{
    vec3 e1 = vec3_sub(tr->p[1], tr->p[0]), e2 = vec3_sub(tr->p[2], tr->p[0]);
    return vec3_unit_direction(vec3_cross(e1, e2), n);
}

/* cn[3 i + k] = the welded normal of corner k of triangle i, for every displaced triangle i
 * without normals and with an area (others untouched):
 *     n = normalize(sum over the corners c at that position of angle_c n_face(c))
 * (a sum that cancels keeps the triangle's own geometric normal).  0, or -1 out of memory. */
static int weld_corner_normals(const scene *in, vec3 *cn)
{
    long n = 0;
    size_t n_corners = (size_t)(3 * (in->n_triangles > 0 ? in->n_triangles : 1));
    corner_ref *refs = malloc(n_corners * sizeof *refs);
    if (!refs) return -1;
    for (long i = 0; i < in->n_triangles; i++) {
        const triangle *tr = &in->triangles[i];
        vec3 f;
        if (!disp_map(in, tr->material) || tr->has_normals || face_normal(tr, &f)) continue;
        for (int k = 0; k < 3; k++) refs[n++] = (corner_ref){tr->p[k], {0, 0, 0}, i, k};
    }
    qsort(refs, (size_t)n, sizeof *refs, corner_order);
    for (long a = 0, b; a < n; a = b) {
        vec3 sum = {0, 0, 0};
        for (b = a; b < n && corner_order(&refs[a], &refs[b]) == 0; b++) {
            const triangle *tr = &in->triangles[refs[b].tri];
            int k = refs[b].k;
            vec3 f = {0, 0, 0}; /* face_normal succeeded for every collected corner (above) */
            face_normal(tr, &f);
            /* the corner's angle between its two edges */
            double angle = vec3_angle(vec3_sub(tr->p[(k + 1) % 3], tr->p[k]),
                                      vec3_sub(tr->p[(k + 2) % 3], tr->p[k]));
            sum = vec3_madd(sum, f, angle);
        }
        for (long c = a; c < b; c++) {
            const triangle *tr = &in->triangles[refs[c].tri];
            vec3 u;
            if (vec3_unit_direction(sum, &u)) face_normal(tr, &u); /* cancelled: its own */
            cn[3 * refs[c].tri + refs[c].k] = u;
        }
    }
    free(refs);
    return 0;
}

/* ---- normals along the edges of the tessellated patches -----------------------------------
 * displace_triangle averages the normals of a patch's own triangles only, so a vertex on the
 * edge between two patches gets a one-sided normal from each, and the shading creases along
 * every edge of the original mesh.  The vertices on a patch's border (fewer than the six
 * triangles of an inner vertex of the grid) are collected as corners of the output
 * triangles, keyed by their displaced position and their normal before displacement (equal on
 * both sides of a smooth edge; different across a hard edge of a trinormal mesh, which stays
 * hard), and get the area-weighted normal of all the triangles around them:
 *     n_v = normalize(sum over those triangles of (b - a) x (c - a)). */

typedef struct seam_list {
    corner_ref *at;
    long n, cap;
} seam_list;

static int seam_push(seam_list *sl, corner_ref c)
{
    if (sl->n == sl->cap) {
        long cap = sl->cap ? 2 * sl->cap : 1024;
        corner_ref *at = realloc(sl->at, (size_t)cap * sizeof *at);
        if (!at) return -1;
        sl->at = at;
        sl->cap = cap;
    }
    sl->at[sl->n++] = c;
    return 0;
}

/* The border corners of patch m, whose first output triangle is number `first`; nv: its
 * vertices' normals before displacement; valence: scratch of m.n_verts ints. */
static int seam_collect(const displace_mesh *m, const vec3 *nv, long first, int *valence,
                        seam_list *sl)
{
    memset(valence, 0, (size_t)m->n_verts * sizeof *valence);
    for (long t = 0; t < m->n_tris; t++)
        for (int k = 0; k < 3; k++) valence[m->tris[t].v[k]]++;
    for (long t = 0; t < m->n_tris; t++)
        for (int k = 0; k < 3; k++) {
            long v = m->tris[t].v[k];
            if (valence[v] < 6 && seam_push(sl, (corner_ref){m->p[v], nv[v], first + t, k}))
                return -1;
        }
    return 0;
}

/* Each group of border corners at the same place gets the normal of all its triangles. */
static void seam_weld(seam_list *sl, scene *out)
{
    if (sl->n == 0) return; /* no displaced triangle: sl->at is NULL, which qsort must not get */
    qsort(sl->at, (size_t)sl->n, sizeof *sl->at, corner_order);
    for (long a = 0, b; a < sl->n; a = b) {
        vec3 sum = {0, 0, 0};
        for (b = a; b < sl->n && corner_order(&sl->at[a], &sl->at[b]) == 0; b++) {
            const vec3 *p = out->triangles[sl->at[b].tri].p;
            sum = vec3_add(sum, vec3_cross(vec3_sub(p[1], p[0]), vec3_sub(p[2], p[0])));
        }
        vec3 u;
        if (vec3_unit_direction(sum, &u)) continue; /* cancelled: keep the patch's normals */
        for (long c = a; c < b; c++) out->triangles[sl->at[c].tri].n[sl->at[c].k] = u;
    }
}

void displacemap_free(scene *out)
{
    free(out->spheres);
    free(out->triangles);
    memset(out, 0, sizeof *out);
}

/* The rates for scene `in`: both halved together from the defaults (down to 2 and 1) until the
 * triangles fit *cap, the smallest of max_tris (0: DISPLACEMAP_MAX_TRIS), SCENE_MAX_PRIMS and
 * what the memory budget still holds at per_tri bytes a triangle (*by_memory: that one).
 * Returns the triangle count at those rates, over *cap if nothing fits. */
static long choose_rates(const scene *in, long max_tris, const budget *mem, double per_tri,
                         int *srate, int *trate, long *cap, int *by_memory)
{
    *cap = max_tris > 0 ? max_tris : DISPLACEMAP_MAX_TRIS;
    if (*cap > SCENE_MAX_PRIMS) *cap = SCENE_MAX_PRIMS;
    /* and no more triangles than the memory budget holds with their BVH: the rates come down */
    *by_memory = mem && (mem->limit - mem->used) / per_tri < (double)*cap;
    if (*by_memory) *cap = (long)((mem->limit - mem->used) / per_tri);
    *srate = DISPLACEMAP_SPHERE_RATE;
    *trate = DISPLACEMAP_TRIANGLE_RATE;
    long total = count_tris(in, *srate, *trate);
    while (total > *cap && (*srate > 2 || *trate > 1)) {
        *srate = *srate / 2 < 2 ? 2 : *srate / 2;
        *trate = *trate / 2 < 1 ? 1 : *trate / 2;
        total = count_tris(in, *srate, *trate);
    }
    return total;
}

/* What one displacement works with besides its output: per vertex of a triangle's patch its
 * object point q, its normal before displacement and its valence (patch_verts of each); the
 * welded corner normals cn (3 per input triangle); the patch being made; the border corners. */
typedef struct work {
    vec3 *qv, *nv;
    int *valence;
    long patch_verts;
    vec3 *cn;
    displace_mesh m;
    seam_list seams;
    long total; /* triangles of the result, for messages */
} work;

/* Allocate *w (zeroed by the caller) for scene `in` at triangle rate trate and weld the corner
 * normals; 0, or -1 out of memory (work_free frees what was allocated). */
static int work_alloc(work *w, const scene *in, int trate)
{
    size_t patch_verts = (size_t)(trate + 1) * (size_t)(trate + 2) / 2;
    w->patch_verts = (long)patch_verts;
    w->qv = malloc(patch_verts * sizeof *w->qv);
    w->nv = malloc(patch_verts * sizeof *w->nv);
    w->valence = malloc(patch_verts * sizeof *w->valence);
    w->cn = malloc((size_t)(3 * (in->n_triangles > 0 ? in->n_triangles : 1)) * sizeof *w->cn);
    if (!w->qv || !w->nv || !w->valence || !w->cn) return -1;
    return weld_corner_normals(in, w->cn);
}

static void work_free(work *w)
{
    displace_mesh_free(&w->m);
    free(w->qv);
    free(w->nv);
    free(w->valence);
    free(w->cn);
    free(w->seams.at);
}

/* Sphere sp, whose material mt has displacement map tex, as srate's triangles appended to out
 * (m: the scratch mesh, freed again). */
static int displace_one_sphere(const sphere *sp, const texture *tex, const material *mt, int srate,
                               displace_mesh *m, scene *out, error *err)
{
    height_ctx c = {tex, mt, scene_material_texmapping(mt, 1), sp->center, sp->radius, NULL, NULL,
                    0,   0};
    if (c.mapping == TEXMAPPING_UV) c.mapping = TEXMAPPING_SPHERICAL;
    /* SCALE object units along the unit sphere's normal: SCALE / R in its units */
    double scale = sp->radius > 0 ? mt->displacement_scale / sp->radius : 0.0;
    if (displace_sphere(srate, sphere_height, &c, scale, 0, m, err)) return -1;
    /* a mirroring transform (det < 0) turns the corners clockwise seen from outside: take
     * them in the order 0, 2, 1, as the parser does for triangles (parse_add_triangle), so
     * that e1 x e2 points out (glass decides entering or leaving by it) */
    int mirror = mat4_det3(&sp->xf) < 0;
    for (long t = 0; t < m->n_tris; t++) {
        triangle *o = &out->triangles[out->n_triangles++];
        memset(o, 0, sizeof *o);
        uv2 sph[3];
        for (int k = 0; k < 3; k++) {
            int kk = mirror && k ? 3 - k : k; /* 0, 1, 2 or 0, 2, 1 */
            long v = m->tris[t].v[kk];
            sph[k] = m->tris[t].st[kk];
            o->q[k] = vec3_madd(sp->center, m->p[v], sp->radius); /* c + R p */
            o->p[k] = mat4_point(&sp->xf, o->q[k]);
            o->n[k] = vec3_normalize(mat4_normal(&sp->inv, m->n[v]));
        }
        sphere_corner_st(c.mapping, sph, o->st);
        o->has_normals = o->has_st = o->st_mapped = 1;
        o->material = sp->material;
    }
    displace_mesh_free(m);
    return 0;
}

/* Every sphere of `in` into out: displaced ones as triangles, the others as they are. */
static int displace_spheres(const scene *in, int srate, work *w, scene *out, displacemap_stats *st,
                            error *err)
{
    for (long i = 0; i < in->n_spheres; i++) {
        const sphere *sp = &in->spheres[i];
        const texture *tex = disp_map(in, sp->material);
        if (!tex) {
            out->spheres[out->n_spheres++] = *sp;
            continue;
        }
        if (displace_one_sphere(sp, tex, &in->materials[sp->material], srate, &w->m, out, err))
            return -1;
        st->spheres++;
    }
    return 0;
}

/* Triangle i of `in`, whose material has displacement map tex, as trate's patch appended to
 * out, its border corners collected into w->seams. */
static int displace_one_triangle(const scene *in, long i, const texture *tex, int trate, work *w,
                                 scene *out, error *err)
{
    const triangle *tr = &in->triangles[i];
    const material *mt = &in->materials[tr->material];
    height_ctx c = {
        tex, mt, scene_material_texmapping(mt, 0), {0, 0, 0}, 0, w->qv, w->nv, 0, w->patch_verts};
    /* along its vertex normals, or the welded corner normals (no cracks); NULL for a
     * zero-area triangle without normals, which displace_triangle refuses */
    vec3 fn;
    const vec3 *normals = tr->has_normals ? tr->n : face_normal(tr, &fn) ? NULL : &w->cn[3 * i];
    if (displace_triangle(tr->p, tr->q, normals, tr->st, trate, triangle_height, &c,
                          mt->displacement_scale, 0, &w->m, err))
        return -1;
    const displace_mesh *m = &w->m;
    int q_known = c.n_q == m->n_verts; /* the callback saw every vertex, in index order */
    long first = out->n_triangles;
    for (long t = 0; t < m->n_tris; t++) {
        triangle *o = &out->triangles[out->n_triangles++];
        memset(o, 0, sizeof *o);
        for (int k = 0; k < 3; k++) {
            long v = m->tris[t].v[k];
            o->p[k] = m->p[v];
            o->n[k] = m->n[v];
            o->st[k] = m->tris[t].st[k];
            o->q[k] = q_known ? w->qv[v] : tr->q[0];
        }
        o->has_normals = o->has_st = 1;
        o->material = tr->material;
    }
    if (q_known && seam_collect(m, w->nv, first, w->valence, &w->seams))
        return error_set(err, in->path, 0,
                         "out of memory for the normals of %ld displaced triangles", w->total);
    displace_mesh_free(&w->m);
    return 0;
}

/* Every triangle of `in` into out: displaced ones as patches, the others as they are. */
static int displace_triangles(const scene *in, int trate, work *w, scene *out,
                              displacemap_stats *st, error *err)
{
    for (long i = 0; i < in->n_triangles; i++) {
        const triangle *tr = &in->triangles[i];
        const texture *tex = disp_map(in, tr->material);
        if (!tex) {
            out->triangles[out->n_triangles++] = *tr;
            continue;
        }
        if (displace_one_triangle(in, i, tex, trate, w, out, err)) return -1;
        st->triangles++;
    }
    return 0;
}

int displacemap_apply(const scene *in, long max_tris, budget *mem, scene *out,
                      displacemap_stats *st, error *err)
{
    displacemap_stats dummy;
    if (!st) st = &dummy;
    memset(st, 0, sizeof *st);
    double per_tri = (double)sizeof *out->triangles + bvh_bytes_per_prim();
    int srate, trate, by_memory;
    long cap;
    long total = choose_rates(in, max_tris, mem, per_tri, &srate, &trate, &cap, &by_memory);
    *out = *in; /* shallow: shares materials, textures, lights, envmap */
    out->spheres = NULL;
    out->triangles = NULL;
    out->n_spheres = out->n_triangles = 0;
    if (total > cap && by_memory) /* more than the budget holds: the charge names it */
        return budget_charge(mem, total * per_tri, in->path, 0, err,
                             "even at the lowest rates, "
                             "displacement mapping's %ld triangles and their BVH x %.0f bytes",
                             total, per_tri);
    if (total > cap)
        return error_set(err, in->path, 0,
                         "displacement mapping needs %ld triangles even at the lowest rates, "
                         "more than the limit %ld",
                         total, cap);
    double bytes = (double)total * sizeof *out->triangles; /* fits: the BVH is charged when built */
    if (budget_charge(mem, bytes, in->path, 0, err,
                      "displacement mapping's %ld triangles x %zu "
                      "bytes",
                      total, sizeof *out->triangles))
        return -1;
    st->sphere_rate = srate;
    st->triangle_rate = trate;
    out->spheres = malloc((size_t)(in->n_spheres > 0 ? in->n_spheres : 1) * sizeof *out->spheres);
    out->triangles = malloc((size_t)(total > 0 ? total : 1) * sizeof *out->triangles);
    work w;
    memset(&w, 0, sizeof w);
    w.total = total;
    int rc = -1;
    if (!out->spheres || !out->triangles || work_alloc(&w, in, trate)) {
        error_set(err, in->path, 0, "out of memory for %ld displaced triangles", total);
        goto done;
    }
    if (displace_spheres(in, srate, &w, out, st, err) ||
        displace_triangles(in, trate, &w, out, st, err))
        goto done;
    seam_weld(&w.seams, out);
    st->new_triangles = out->n_triangles;
    rc = 0;
done:
    work_free(&w);
    if (rc) {
        budget_release(mem, bytes);
        displacemap_free(out);
    }
    return rc;
}
