/* bvh.c - binned-SAH bounding volume hierarchy (see include/envtex/geometry/bvh.h). */
#include "envtex/geometry/bvh.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "envtex/geometry/sphere.h"
#include "envtex/geometry/triangle.h"

typedef struct build_prim { vec3 lo, hi, c; } build_prim;

/* A box must never cull a hit its primitives' own tests accept.  Triangles accept points up to
 * TRIANGLE_EDGE_EPS (barycentric) outside their edges, and the rounding of both tests grows
 * with the coordinates' size, so each primitive's box is padded by BVH_BOX_PAD_REL times its
 * extent plus its distance from the origin: 1e-9 is far beyond both (1e-12 and ~1e-16
 * relative) and changes no traversal measurably. */
#define BVH_BOX_PAD_REL 1e-9
/* The slab test's own rounding: each t = (lo - o) * (1 / d) is within 2 ulp of the exact
 * value, so the far end of each slab interval is widened by 2 gamma(3) = 6 eps / (1 - 3 eps),
 * eps = 2^-53 (pbrt-v3, section 3.9.2, "robust ray-bounds intersections"). */
#define BVH_SLAB_SLACK (6 * 0x1p-53 / (1 - 3 * 0x1p-53))

static void pad_box(vec3 *lo, vec3 *hi)
{
    double m = fmax(vec3_max_abs(*lo), vec3_max_abs(*hi));
    double pad = BVH_BOX_PAD_REL * (m + vec3_max_abs(vec3_sub(*hi, *lo)));
    *lo = vec3_sub(*lo, vec3_make(pad, pad, pad));
    *hi = vec3_add(*hi, vec3_make(pad, pad, pad));
}

typedef struct builder {
    bvh *b;
    build_prim *bp;
    unsigned *ids;
    long cap_nodes;
} builder;

static double box_area(vec3 lo, vec3 hi)
{
    vec3 e = vec3_sub(hi, lo);
    if (e.x < 0 || e.y < 0 || e.z < 0) return 0;
    return 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

static long push_node(builder *bd)
{
    /* at most 2 n - 1 nodes, reserved up front: never grows */
    return bd->b->n_nodes++;
}

static void build_rec(builder *bd, long node, long first, long count, int depth)
{
    bvh_node *nd = &bd->b->nodes[node];
    vec3 lo = vec3_make(INFINITY, INFINITY, INFINITY), hi = vec3_neg(lo);
    vec3 clo = lo, chi = hi;
    for (long i = first; i < first + count; i++) {
        const build_prim *p = &bd->bp[bd->ids[i]];
        lo = vec3_min(lo, p->lo);
        hi = vec3_max(hi, p->hi);
        clo = vec3_min(clo, p->c);
        chi = vec3_max(chi, p->c);
    }
    nd->lo = lo;
    nd->hi = hi;
    if (depth + 1 > bd->b->depth) bd->b->depth = depth + 1;
    if (count <= BVH_LEAF_MAX || depth >= BVH_MAX_DEPTH - 2) goto leaf;

    /* Binned SAH: cost(split) = A_left N_left + A_right N_right, against A N for a leaf. */
    int best_axis = -1, best_bin = -1;
    double best_cost = box_area(lo, hi) * (double)count;
    for (int axis = 0; axis < 3; axis++) {
        double cmin = vec3_get(clo, axis), cmax = vec3_get(chi, axis);
        if (!(cmax > cmin)) continue;
        double k = BVH_BINS * (1 - 1e-9) / (cmax - cmin);
        long n[BVH_BINS] = {0};
        vec3 blo[BVH_BINS], bhi[BVH_BINS];
        for (int j = 0; j < BVH_BINS; j++) {
            blo[j] = vec3_make(INFINITY, INFINITY, INFINITY);
            bhi[j] = vec3_neg(blo[j]);
        }
        for (long i = first; i < first + count; i++) {
            const build_prim *p = &bd->bp[bd->ids[i]];
            int j = (int)((vec3_get(p->c, axis) - cmin) * k);
            if (j >= BVH_BINS) j = BVH_BINS - 1;
            n[j]++;
            blo[j] = vec3_min(blo[j], p->lo);
            bhi[j] = vec3_max(bhi[j], p->hi);
        }
        /* sweep: right-side areas from the top, then left side from the bottom */
        double right_area[BVH_BINS];
        long right_n[BVH_BINS];
        vec3 rlo = vec3_make(INFINITY, INFINITY, INFINITY), rhi = vec3_neg(rlo);
        long rn = 0;
        for (int j = BVH_BINS - 1; j > 0; j--) {
            rlo = vec3_min(rlo, blo[j]);
            rhi = vec3_max(rhi, bhi[j]);
            rn += n[j];
            right_area[j] = box_area(rlo, rhi);
            right_n[j] = rn;
        }
        vec3 llo = vec3_make(INFINITY, INFINITY, INFINITY), lhi = vec3_neg(llo);
        long ln = 0;
        for (int j = 0; j < BVH_BINS - 1; j++) {
            llo = vec3_min(llo, blo[j]);
            lhi = vec3_max(lhi, bhi[j]);
            ln += n[j];
            if (ln == 0 || right_n[j + 1] == 0) continue;
            double cost = box_area(llo, lhi) * (double)ln + right_area[j + 1] * (double)right_n[j + 1];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = axis;
                best_bin = j;
            }
        }
    }
    if (best_axis < 0) goto leaf;

    /* partition: bins 0..best_bin go left */
    double cmin = vec3_get(clo, best_axis), cmax = vec3_get(chi, best_axis);
    double k = BVH_BINS * (1 - 1e-9) / (cmax - cmin);
    long i = first, j = first + count - 1;
    while (i <= j) {
        int bin = (int)((vec3_get(bd->bp[bd->ids[i]].c, best_axis) - cmin) * k);
        if (bin >= BVH_BINS) bin = BVH_BINS - 1;
        if (bin <= best_bin) i++;
        else {
            unsigned t = bd->ids[i];
            bd->ids[i] = bd->ids[j];
            bd->ids[j--] = t;
        }
    }
    long nleft = i - first;
    if (nleft == 0 || nleft == count) goto leaf;
    long left = push_node(bd);
    build_rec(bd, left, first, nleft, depth + 1);
    long right = push_node(bd);
    build_rec(bd, right, first + nleft, count - nleft, depth + 1);
    nd = &bd->b->nodes[node];
    nd->first = (int)right;
    nd->count = 0;
    nd->axis = best_axis;
    return;
leaf:
    nd->first = (int)first;
    nd->count = (int)count;
    nd->axis = 0;
}

double bvh_bytes_per_prim(void)
{
    return 2.0 * sizeof(bvh_node) + sizeof(unsigned) + sizeof(bvh_tri) + sizeof(build_prim);
}

double bvh_bytes(long n, double *scratch)
{
    long m = n > 0 ? n : 1, max_nodes = n > 0 ? 2 * n - 1 : 1;
    if (scratch) *scratch = (double)m * sizeof(build_prim);
    return (double)max_nodes * sizeof(bvh_node) + (double)m * (sizeof(unsigned) + sizeof(bvh_tri));
}

int bvh_build(bvh *b, bvh_prims prims, budget *mem, error *err)
{
    memset(b, 0, sizeof *b);
    b->prims_of = prims;
    const bvh_prims *sc = &b->prims_of;
    clock_t t0 = clock();
    long n = sc->n_spheres + sc->n_triangles;
    b->n_spheres = sc->n_spheres;
    b->n_prims = n;
    if (n > 0x7fffffffL) return error_set(err, sc->name, 0, "too many primitives (%ld)", n);
    double scratch, keep = bvh_bytes(n, &scratch);
    double each = (keep + scratch) / (n > 0 ? n : 1);
    if (budget_charge(mem, keep + scratch, sc->name, 0, err, "the BVH of %ld primitives x %.0f "
                      "bytes", n, each))
        return -1;
    long max_nodes = n > 0 ? 2 * n - 1 : 1;
    b->nodes = calloc((size_t)max_nodes, sizeof *b->nodes);
    b->prims = malloc((size_t)(n > 0 ? n : 1) * sizeof *b->prims);
    b->tris = malloc((size_t)(n > 0 ? n : 1) * sizeof *b->tris);
    build_prim *bp = malloc((size_t)(n > 0 ? n : 1) * sizeof *bp);
    if (!b->nodes || !b->prims || !b->tris || !bp) {
        free(bp);
        bvh_free(b);
        budget_release(mem, keep + scratch);
        return error_set(err, sc->name, 0, "out of memory building the BVH (%ld primitives)", n);
    }
    for (long i = 0; i < n; i++) {
        build_prim *p = &bp[i];
        if (i < sc->n_spheres) {
            sphere_bounds(&sc->spheres[i], &p->lo, &p->hi);
        } else {
            const triangle *t = &sc->triangles[i - sc->n_spheres];
            p->lo = vec3_min(t->p[0], vec3_min(t->p[1], t->p[2]));
            p->hi = vec3_max(t->p[0], vec3_max(t->p[1], t->p[2]));
        }
        pad_box(&p->lo, &p->hi);
        p->c = vec3_scale(vec3_add(p->lo, p->hi), 0.5);
        b->prims[i] = (unsigned)i;
    }
    builder bd = {b, bp, b->prims, max_nodes};
    b->n_nodes = 1;
    if (n <= BVH_MIN_PRIMS) {
        /* one leaf, no tree */
        bvh_node *nd = &b->nodes[0];
        nd->lo = vec3_make(-INFINITY, -INFINITY, -INFINITY);
        nd->hi = vec3_make(INFINITY, INFINITY, INFINITY);
        nd->first = 0;
        nd->count = (int)n;
        b->depth = 1;
    } else {
        b->is_tree = 1;
        build_rec(&bd, 0, 0, n, 0);
    }
    for (long i = 0; i < n; i++) {
        unsigned id = b->prims[i];
        if (id >= (unsigned)sc->n_spheres) {
            const triangle *t = &sc->triangles[id - sc->n_spheres];
            b->tris[i] = (bvh_tri){t->p[0], t->p[1], t->p[2]};
        }
    }
    free(bp);
    budget_release(mem, scratch);
    b->build_seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    return 0;
}

void bvh_free(bvh *b)
{
    free(b->nodes);
    free(b->prims);
    free(b->tris);
    memset(b, 0, sizeof *b);
}

/* Slab test: does the ray cross the box for some t in (tmin, tmax)?  Conservative: the far
 * end of each slab is widened by BVH_SLAB_SLACK, so rounding never culls a ray through a face. */
static inline int box_hit(const bvh_node *nd, vec3 o, vec3 inv, double tmin, double tmax)
{
    double t0 = (nd->lo.x - o.x) * inv.x, t1 = (nd->hi.x - o.x) * inv.x;
    if (t0 > t1) { double t = t0; t0 = t1; t1 = t; }
    t1 += fabs(t1) * BVH_SLAB_SLACK;
    tmin = t0 > tmin ? t0 : tmin;
    tmax = t1 < tmax ? t1 : tmax;
    t0 = (nd->lo.y - o.y) * inv.y; t1 = (nd->hi.y - o.y) * inv.y;
    if (t0 > t1) { double t = t0; t0 = t1; t1 = t; }
    t1 += fabs(t1) * BVH_SLAB_SLACK;
    tmin = t0 > tmin ? t0 : tmin;
    tmax = t1 < tmax ? t1 : tmax;
    t0 = (nd->lo.z - o.z) * inv.z; t1 = (nd->hi.z - o.z) * inv.z;
    if (t0 > t1) { double t = t0; t0 = t1; t1 = t; }
    t1 += fabs(t1) * BVH_SLAB_SLACK;
    tmin = t0 > tmin ? t0 : tmin;
    tmax = t1 < tmax ? t1 : tmax;
    /* NaN (0 * inf for a ray in a slab's plane) fails both compares and keeps the old bound */
    return tmin <= tmax;
}

/* The primitives prims[first .. first + count) against ray *r: each hit shrinks r->tmax (the
 * closest so far) and records it; any = 1 stops at the first hit (shadow rays). */
static inline int leaf_hits(const bvh *b, ray *r, int first, int count, int any,
                            long *best_i, double *best_t, double *bb1, double *bb2)
{
    int found = 0;
    for (int i = first; i < first + count; i++) {
        unsigned id = b->prims[i];
        double t, b1 = 0, b2 = 0;
        int h;
        if (id < (unsigned)b->n_spheres) h = sphere_intersect(&b->prims_of.spheres[id], r, &t);
        else {
            const bvh_tri *tr = &b->tris[i];
            h = triangle_intersect(tr->p0, tr->p1, tr->p2, r, &t, &b1, &b2);
        }
        if (h) {
            if (any) return 1;
            found = 1;
            r->tmax = t; /* closest so far: shrink the ray */
            *best_i = id;
            *best_t = t;
            *bb1 = b1;
            *bb2 = b2;
        }
    }
    return found;
}

/* Shared traversal.  any = 1: stop at the first hit (shadow rays). */
static int traverse(const bvh *b, const ray *r0, int any, long *best_i,
                    double *best_t, double *bb1, double *bb2)
{
    ray r = *r0;
    /* no tree (a few primitives): the one leaf's box is all space, so no slab test */
    if (!b->is_tree) return leaf_hits(b, &r, 0, (int)b->n_prims, any, best_i, best_t, bb1, bb2);
    vec3 inv = vec3_make(1.0 / r.d.x, 1.0 / r.d.y, 1.0 / r.d.z);
    int stack[BVH_MAX_DEPTH];
    int sp = 0, node = 0, found = 0;
    for (;;) {
        const bvh_node *nd = &b->nodes[node];
        if (box_hit(nd, r.o, inv, r.tmin, r.tmax)) {
            if (nd->count == 0) {
                /* visit the nearer child first: left holds the smaller coordinates */
                int left = node + 1, right = nd->first;
                if (vec3_get(r.d, nd->axis) < 0) { node = right; stack[sp++] = left; }
                else { node = left; stack[sp++] = right; }
                continue;
            }
            if (leaf_hits(b, &r, nd->first, nd->count, any, best_i, best_t, bb1, bb2)) {
                if (any) return 1;
                found = 1;
            }
        }
        if (sp == 0) break;
        node = stack[--sp];
    }
    return found;
}

int bvh_intersect(const bvh *b, const ray *r, hit *h)
{
    const bvh_prims *sc = &b->prims_of;
    long id = -1;
    double t = 0, b1 = 0, b2 = 0;
    if (b->n_prims == 0 || !traverse(b, r, 0, &id, &t, &b1, &b2)) return 0;
    h->t = t;
    if (id < b->n_spheres) {
        const sphere *s = &sc->spheres[id];
        sphere_hit(s, r, t, h);
        h->prim = id;
        h->is_sphere = 1;
        h->material = s->material;
        return 1;
    }
    const triangle *tr = &sc->triangles[id - b->n_spheres];
    double b0 = 1 - b1 - b2;
    /* p = b0 p0 + b1 p1 + b2 p2 : the barycentric interpolation of the lecture */
    h->p = vec3_add(vec3_add(vec3_scale(tr->p[0], b0), vec3_scale(tr->p[1], b1)), vec3_scale(tr->p[2], b2));
    h->ng = vec3_normalize(vec3_cross(vec3_sub(tr->p[1], tr->p[0]), vec3_sub(tr->p[2], tr->p[0])));
    if (tr->has_normals) {
        vec3 n = vec3_add(vec3_add(vec3_scale(tr->n[0], b0), vec3_scale(tr->n[1], b1)), vec3_scale(tr->n[2], b2));
        h->ns = vec3_normalize(n);
        /* the given normals define the outside: turn the winding's normal to agree with them */
        if (vec3_dot(h->ns, h->ng) < 0) h->ng = vec3_neg(h->ng);
    } else {
        h->ns = h->ng;
    }
    h->bary = (uv2){b1, b2};
    h->prim = id - b->n_spheres;
    h->is_sphere = 0;
    h->material = tr->material;
    return 1;
}

int bvh_occluded(const bvh *b, const ray *r)
{
    long id;
    double t, b1, b2;
    return b->n_prims > 0 && traverse(b, r, 1, &id, &t, &b1, &b2);
}
