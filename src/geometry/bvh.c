/* bvh.c - binned-SAH bounding volume hierarchy in float (see include/envtex/geometry/bvh.h). */
#include "envtex/geometry/bvh.h"

#include <assert.h>
#include <float.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bvh_leaf.h"

/* ---- build -------------------------------------------------------------------------------- */

typedef struct box {
    float lo[3], hi[3];
} box;

typedef struct build_prim { /* a primitive's box and its centre */
    box b;
    float c[3];
} build_prim;

typedef struct builder {
    bvh *b;
    build_prim *bp; /* bp[i]: primitive ids[i]'s (moved with it: the passes read in order) */
    uint32_t *ids;  /* the leaf order, permuted in place as the build partitions */
} builder;

/* From this depth on, a node is split in half by count instead of by the SAH: the 22 levels
 * left before BVH_MAX_DEPTH - 2 hold 2^22 leaves, however the primitives are spread. */
#define BVH_HALVE_DEPTH 40

static box box_empty(void)
{
    return (box){{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
}

static float min_f(float a, float b) { return a < b ? a : b; }
static float max_f(float a, float b) { return a > b ? a : b; }

static void box_grow(box *b, const float lo[3], const float hi[3])
{
    b->lo[0] = min_f(lo[0], b->lo[0]), b->hi[0] = max_f(hi[0], b->hi[0]);
    b->lo[1] = min_f(lo[1], b->lo[1]), b->hi[1] = max_f(hi[1], b->hi[1]);
    b->lo[2] = min_f(lo[2], b->lo[2]), b->hi[2] = max_f(hi[2], b->hi[2]);
}

static double box_area(const box *b)
{
    double e[3];
    for (int a = 0; a < 3; a++) e[a] = (double)b->hi[a] - b->lo[a];
    if (!(e[0] >= 0 && e[1] >= 0 && e[2] >= 0)) return 0;
    return 2 * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
}

/* The double box [lo, hi] padded by BVH_BOX_PAD_REL and rounded outwards to float, and its
 * centre (kept finite for the binning). */
static void prim_box(vec3 lo, vec3 hi, build_prim *p)
{
    double m = fmax(vec3_max_abs(lo), vec3_max_abs(hi));
    double pad = BVH_BOX_PAD_REL * (m + vec3_max_abs(vec3_sub(hi, lo)));
    for (int a = 0; a < 3; a++) {
        double l = vec3_get(lo, a) - pad, h = vec3_get(hi, a) + pad;
        p->b.lo[a] = bvh_float_down(l);
        p->b.hi[a] = bvh_float_up(h);
        p->c[a] = (float)fmin(fmax(0.5 * l + 0.5 * h, -FLT_MAX), FLT_MAX);
    }
}

/* A centre's bin: (c - cmin) k with k = BVH_BINS (1 - BVH_BIN_SHRINK) / (cmax - cmin), so that
 * the largest centre falls in the last bin, not one past it (clamped too, for rounding). */
#define BVH_BIN_SHRINK 1e-9
static int bin_of(float c, double cmin, double k)
{
    int j = (int)((c - cmin) * k);
    return j < 0 ? 0 : j >= BVH_BINS ? BVH_BINS - 1 : j;
}

/* Primitives ids[first, first + count): the box around them, and the box of their centres. */
typedef struct span {
    long first, count;
    box bb, cb;
} span;

static span span_of(const builder *bd, long first, long count)
{
    span s = {first, count, box_empty(), box_empty()};
    for (long i = first; i < first + count; i++) {
        const build_prim *p = &bd->bp[i];
        box_grow(&s.bb, p->b.lo, p->b.hi);
        box_grow(&s.cb, p->c, p->c);
    }
    return s;
}

typedef struct split {
    int axis, bin;  /* bins 0..bin go to the first child; axis -1: no split */
    double cost;    /* C_trav A + A_1 N_1 + A_2 N_2 (A: areas, N: counts) */
    double cmin, k; /* the axis's binning (bin_of) */
} split;

/* The binned SAH's best split of span s (area: of its box), the three axes binned together. */
static split find_split(const builder *bd, const span *s, double area)
{
    split best = {-1, -1, INFINITY, 0, 0};
    double cmin[3], k[3];
    long n[3][BVH_BINS] = {{0}};
    box bins[3][BVH_BINS];
    for (int axis = 0; axis < 3; axis++) {
        cmin[axis] = s->cb.lo[axis];
        double extent = s->cb.hi[axis] - cmin[axis]; /* k = 0: the centres share this axis */
        k[axis] = extent > 0 ? BVH_BINS * (1 - BVH_BIN_SHRINK) / extent : 0;
        for (int j = 0; j < BVH_BINS; j++) bins[axis][j] = box_empty();
    }
    for (long i = s->first; i < s->first + s->count; i++) {
        const build_prim *p = &bd->bp[i];
        for (int axis = 0; axis < 3; axis++) {
            if (k[axis] == 0) continue;
            int j = bin_of(p->c[axis], cmin[axis], k[axis]);
            n[axis][j]++;
            box_grow(&bins[axis][j], p->b.lo, p->b.hi);
        }
    }
    for (int axis = 0; axis < 3; axis++) {
        if (k[axis] == 0) continue;
        /* sweep: the second child's areas and counts from the top, then the first's */
        double area2[BVH_BINS];
        long n2[BVH_BINS];
        box acc = box_empty();
        long m = 0;
        double a2 = 0;
        for (int j = BVH_BINS - 1; j > 0; j--) {
            if (n[axis][j]) { /* (an empty bin changes nothing) */
                box_grow(&acc, bins[axis][j].lo, bins[axis][j].hi);
                m += n[axis][j];
                a2 = box_area(&acc);
            }
            area2[j] = a2;
            n2[j] = m;
        }
        acc = box_empty();
        m = 0;
        for (int j = 0; j < BVH_BINS - 1; j++) {
            /* after an empty bin the split is the one before it, whose equal cost won */
            if (n[axis][j] == 0) continue;
            box_grow(&acc, bins[axis][j].lo, bins[axis][j].hi);
            m += n[axis][j];
            if (n2[j + 1] == 0) continue;
            double cost = BVH_TRAVERSAL_COST * area + box_area(&acc) * (double)m +
                          area2[j + 1] * (double)n2[j + 1];
            if (cost < best.cost) best = (split){axis, j, cost, cmin[axis], k[axis]};
        }
    }
    return best;
}

/* Span s cut by split sp: the primitives of bins 0..sp.bin moved to the front, into *left,
 * the others into *right, each with its bounds (both sides hold some: find_split's counts). */
static void partition(builder *bd, const span *s, split sp, span *left, span *right)
{
    *left = (span){s->first, 0, box_empty(), box_empty()};
    *right = *left;
    long i = s->first, j = s->first + s->count - 1;
    while (i <= j) {
        const build_prim *p = &bd->bp[i];
        span *side = bin_of(p->c[sp.axis], sp.cmin, sp.k) <= sp.bin ? left : right;
        box_grow(&side->bb, p->b.lo, p->b.hi);
        box_grow(&side->cb, p->c, p->c);
        if (side == left) {
            i++;
        } else {
            uint32_t t = bd->ids[i];
            build_prim q = bd->bp[i];
            bd->ids[i] = bd->ids[j], bd->bp[i] = bd->bp[j];
            bd->ids[j] = t, bd->bp[j--] = q;
        }
    }
    left->count = i - s->first;
    right->first = i;
    right->count = s->count - left->count;
    assert(left->count > 0 && right->count > 0);
}

/* Node `node` over span s and, unless it is a leaf, its subtree.  The SAH decides: a leaf
 * when it holds at most BVH_LEAF_MAX and costs no more than its best split. */
static int build_rec(builder *bd, long node, const span *s, int depth)
{
    bvh_node *nd = &bd->b->nodes[node];
    memcpy(nd->box[0], s->bb.lo, sizeof s->bb.lo);
    memcpy(nd->box[1], s->bb.hi, sizeof s->bb.hi);
    if (depth + 1 > bd->b->depth) bd->b->depth = depth + 1;
    span kids[2] = {{0}, {0}};
    int axis = 0;
    if (s->count > 1 && depth < BVH_MAX_DEPTH - 2) {
        double area = box_area(&s->bb);
        split sp = depth < BVH_HALVE_DEPTH ? find_split(bd, s, area) : (split){-1, 0, 0, 0, 0};
        if (s->count <= BVH_LEAF_MAX && !(sp.cost < area * (double)s->count)) sp.axis = -2;
        if (sp.axis >= 0) {
            partition(bd, s, sp, &kids[0], &kids[1]);
            axis = sp.axis;
        } else if (sp.axis == -1 && s->count > BVH_LEAF_MAX) { /* no split: halves by count */
            kids[0] = span_of(bd, s->first, s->count / 2);
            kids[1] = span_of(bd, s->first + s->count / 2, s->count - s->count / 2);
        }
    }
    if (kids[0].count == 0) {
        if (s->count > UINT16_MAX) return -1; /* the depth limit with that many left: no leaf */
        nd->offset = (int32_t)s->first;
        nd->count = (uint16_t)s->count;
        nd->axis = nd->pad = 0;
        return 0;
    }
    if (build_rec(bd, bd->b->n_nodes++, &kids[0], depth + 1)) return -1;
    long second = bd->b->n_nodes++;
    if (build_rec(bd, second, &kids[1], depth + 1)) return -1;
    nd = &bd->b->nodes[node]; /* (the array does not move: reserved up front) */
    nd->offset = (int32_t)second;
    nd->count = 0;
    nd->axis = (uint8_t)axis;
    nd->pad = 0;
    return 0;
}

double bvh_bytes_per_prim(void)
{
    return 2.0 * sizeof(bvh_node) + sizeof(uint32_t) + sizeof(bvh_tri) + sizeof(build_prim);
}

double bvh_bytes(long n, double *scratch)
{
    long m = n > 0 ? n : 1, max_nodes = n > 0 ? 2 * n - 1 : 1;
    if (scratch) *scratch = (double)m * sizeof(build_prim);
    return (double)max_nodes * sizeof(bvh_node) + (double)m * (sizeof(uint32_t) + sizeof(bvh_tri));
}

/* The primitives' padded float boxes, in id order. */
static void prim_boxes(const bvh *b, build_prim *bp)
{
    const bvh_prims *sc = &b->prims_of;
    for (long i = 0; i < b->n_prims; i++) {
        vec3 lo, hi;
        if (i < b->n_spheres) {
            sphere_bounds(&sc->spheres[i], &lo, &hi);
        } else if (i < b->n_surfaces) {
            const triangle *t = &sc->triangles[i - b->n_spheres];
            lo = vec3_min(t->p[0], vec3_min(t->p[1], t->p[2]));
            hi = vec3_max(t->p[0], vec3_max(t->p[1], t->p[2]));
        } else {
            const bvh_quad *q = &b->quads[i - b->n_surfaces];
            vec3 p1 = vec3_add(q->a, q->ab), p2 = vec3_add(p1, q->ac), p3 = vec3_add(q->a, q->ac);
            lo = vec3_min(vec3_min(q->a, p1), vec3_min(p2, p3));
            hi = vec3_max(vec3_max(q->a, p1), vec3_max(p2, p3));
        }
        prim_box(lo, hi, &bp[i]);
        b->prims[i] = (uint32_t)i;
    }
}

/* The float triangles and quads in leaf order (spheres' slots stay unused): p0, e1, e2. */
static void leaf_tris(bvh *b)
{
    for (long i = 0; i < b->n_prims; i++) {
        uint32_t id = b->prims[i];
        if (id < b->n_spheres) continue;
        vec3 v[3];
        if (id < b->n_surfaces) {
            const vec3 *p = b->prims_of.triangles[id - b->n_spheres].p;
            v[0] = p[0], v[1] = vec3_sub(p[1], p[0]), v[2] = vec3_sub(p[2], p[0]);
        } else {
            const bvh_quad *q = &b->quads[id - b->n_surfaces];
            v[0] = q->a, v[1] = q->ab, v[2] = q->ac;
        }
        for (int a = 0; a < 3; a++) {
            b->tris[i].p0[a] = (float)vec3_get(v[0], a);
            b->tris[i].e1[a] = (float)vec3_get(v[1], a);
            b->tris[i].e2[a] = (float)vec3_get(v[2], a);
        }
        /* too far from the origin for its smallest altitude (twice its area over its longest
         * edge): no float filter (a NaN e1: the double test decides) */
        double longest = fmax(fmax(vec3_length(v[1]), vec3_length(v[2])),
                              vec3_length(vec3_sub(v[2], v[1])));
        double altitude = vec3_length(vec3_cross(v[1], v[2])) / longest;
        if (!(vec3_max_abs(v[0]) <= BVH_FILTER_REACH * altitude)) b->tris[i].e1[0] = NAN;
    }
}

int bvh_build(bvh *b, bvh_prims prims, budget *mem, error *err)
{
    memset(b, 0, sizeof *b);
    clock_t t0 = clock();
    long n = prims.n_spheres + prims.n_triangles + prims.n_quads, m = n > 0 ? n : 1;
    if (n > 0x7fffffffL) return error_set(err, prims.name, 0, "too many primitives (%ld)", n);
    double scratch, keep = bvh_bytes(n, &scratch) + (double)prims.n_quads * sizeof(bvh_quad);
    if (budget_charge(mem, keep + scratch, prims.name, 0, err,
                      "the BVH of %ld primitives x %.0f bytes", n, (keep + scratch) / (double)m))
        return -1;
    long max_nodes = 2 * m - 1;
    b->nodes = malloc((size_t)max_nodes * sizeof *b->nodes);
    b->prims = malloc((size_t)m * sizeof *b->prims);
    b->tris = calloc((size_t)m, sizeof *b->tris);
    b->quads = malloc((size_t)(prims.n_quads > 0 ? prims.n_quads : 1) * sizeof *b->quads);
    build_prim *bp = malloc((size_t)m * sizeof *bp);
    int st = -1;
    if (!b->nodes || !b->prims || !b->tris || !b->quads || !bp) goto done;
    if (prims.n_quads) memcpy(b->quads, prims.quads, (size_t)prims.n_quads * sizeof *b->quads);
    prims.quads = b->quads;
    b->prims_of = prims;
    b->n_prims = n;
    b->n_spheres = prims.n_spheres;
    b->n_surfaces = prims.n_spheres + prims.n_triangles;
    prim_boxes(b, bp);
    b->n_nodes = 1;
    b->depth = 1;
    b->is_tree = n > BVH_MIN_PRIMS;
    if (b->is_tree) {
        builder bd = {b, bp, b->prims};
        span all = span_of(&bd, 0, n);
        if (build_rec(&bd, 0, &all, 0)) goto done;
    } else { /* one leaf, no tree (its box, never tested, is all space) */
        bvh_node *all = &b->nodes[0];
        for (int a = 0; a < 3; a++) all->box[0][a] = -INFINITY, all->box[1][a] = INFINITY;
        all->offset = 0;
        all->count = (uint16_t)n;
        all->axis = all->pad = 0;
    }
    leaf_tris(b);
    bvh_node *fit = realloc(b->nodes, (size_t)b->n_nodes * sizeof *b->nodes);
    if (fit) b->nodes = fit;
    st = 0;
done:
    free(bp);
    if (st) {
        int no_memory = !b->nodes || !b->prims || !b->tris || !b->quads || !bp;
        bvh_free(b);
        budget_release(mem, keep + scratch);
        return error_set(err, prims.name, 0,
                         no_memory ? "out of memory building the BVH (%ld primitives)"
                                   : "no BVH fits %ld primitives (too many alike)",
                         n);
    }
    b->bytes = keep - (double)(max_nodes - b->n_nodes) * sizeof(bvh_node);
    budget_release(mem, scratch + (keep - b->bytes));
    b->build_seconds = (double)(clock() - t0) / CLOCKS_PER_SEC;
    return 0;
}

void bvh_free(bvh *b)
{
    free(b->nodes);
    free(b->prims);
    free(b->tris);
    free(b->quads);
    memset(b, 0, sizeof *b);
}

/* ---- traversal ---------------------------------------------------------------------------- */

/* The ray in float for the box and triangle tests: origin, direction, 1 / direction, and which
 * direction components are negative (the near side of each slab). */
typedef struct fray {
    float o[3], o_lo[3], d[3], inv[3], o_near[3], o_far[3];
    int neg[3];
} fray;

static fray fray_make(const ray *r)
{
    fray f;
    for (int a = 0; a < 3; a++) {
        f.d[a] = (float)vec3_get(r->d, a);
        f.inv[a] = 1.0f / f.d[a];
        f.neg[a] = f.inv[a] < 0;
        bvh_float_origin(vec3_get(r->o, a), f.neg[a], &f.o[a], &f.o_lo[a], &f.o_near[a],
                         &f.o_far[a]);
    }
    return f;
}

static inline float max3(float a, float b, float c, float d)
{
    a = b > a ? b : a; /* NaN (0 * inf: a ray in a slab's plane) fails and keeps the bound */
    a = c > a ? c : a;
    return d > a ? d : a;
}

static inline float min3(float a, float b, float c, float d)
{
    a = b < a ? b : a;
    a = c < a ? c : a;
    return d < a ? d : a;
}

/* Slab test: does the ray cross the box for some t in [tmin, tmax]?  Conservative: the far
 * ends are widened by BVH_SLAB_SLACK (the caller widens tmax so too: the near ends' rounding),
 * and the slabs are measured from origins that bracket the double one (fray_make). */
static inline int box_hit(const bvh_node *nd, const fray *f, float tmin, float tmax)
{
    const float(*bx)[3] = nd->box;
    const float grow = 1 + BVH_SLAB_SLACK; /* (a far end below 0 misses anyway) */
    float x0 = (bx[f->neg[0]][0] - f->o_near[0]) * f->inv[0];
    float y0 = (bx[f->neg[1]][1] - f->o_near[1]) * f->inv[1];
    float z0 = (bx[f->neg[2]][2] - f->o_near[2]) * f->inv[2];
    float x1 = (bx[!f->neg[0]][0] - f->o_far[0]) * f->inv[0] * grow;
    float y1 = (bx[!f->neg[1]][1] - f->o_far[1]) * f->inv[1] * grow;
    float z1 = (bx[!f->neg[2]][2] - f->o_far[2]) * f->inv[2] * grow;
    return max3(tmin, x0, y0, z0) <= min3(tmax, x1, y1, z1);
}

/* The float Moller-Trumbore test as a filter: 0 only when the double test cannot hit either
 * (BVH_FILTER_EPS).  A quad is a parallelogram: b1, b2 in [0, 1] each. */
static inline int tri_maybe(const bvh_tri *t, const fray *f, float tmax, int quad)
{
    const float *d = f->d, *e1 = t->e1, *e2 = t->e2;
    float pv[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                   d[0] * e2[1] - d[1] * e2[0]};
    float det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    float s[3] = {(f->o[0] - t->p0[0]) + f->o_lo[0], (f->o[1] - t->p0[1]) + f->o_lo[1],
                  (f->o[2] - t->p0[2]) + f->o_lo[2]};
    /* |det| = |e1| |pv| cos: a grazing ray (cos below ~BVH_GRAZING, L1 norms), or an origin
     * far for the triangle's size (|s| |pv| / |det| beyond BVH_FILTER_REACH_RAY), makes the
     * float barycentrics noise: the double test decides (NaN too) */
    float n1 = fabsf(e1[0]) + fabsf(e1[1]) + fabsf(e1[2]),
          np = fabsf(pv[0]) + fabsf(pv[1]) + fabsf(pv[2]),
          ns = fabsf(s[0]) + fabsf(s[1]) + fabsf(s[2]);
    float graze = BVH_GRAZING * n1, far = ns * (1 / BVH_FILTER_REACH_RAY);
    if (!(fabsf(det) > np * (graze > far ? graze : far))) return 1;
    float inv = 1 / det;
    float b1 = (s[0] * pv[0] + s[1] * pv[1] + s[2] * pv[2]) * inv;
    if (!(b1 >= -BVH_FILTER_EPS && b1 <= 1 + BVH_FILTER_EPS)) return 0;
    float qv[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
                   s[0] * e1[1] - s[1] * e1[0]};
    float b2 = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) * inv;
    if (!(b2 >= -BVH_FILTER_EPS && (quad ? b2 : b1 + b2) <= 1 + BVH_FILTER_EPS)) return 0;
    float tt = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) * inv;
    return tt <= tmax + fabsf(tt) * BVH_FILTER_EPS; /* no lower bound: the double test's */
}

/* bvh_prim_hit, inlined in this file's leaf loop */
static inline int prim_hit(const bvh *b, uint32_t id, const ray *r, double *t, double *b1,
                           double *b2)
{
    *b1 = *b2 = 0;
    if (id < b->n_spheres) return sphere_intersect(&b->prims_of.spheres[id], r, t);
    if (id >= b->n_surfaces) {
        const bvh_quad *q = &b->quads[id - b->n_surfaces];
        return triangle_intersect_parallelogram(q->a, q->ab, q->ac, r, t);
    }
    const vec3 *p = b->prims_of.triangles[id - b->n_spheres].p;
    return triangle_intersect(p[0], p[1], p[2], r, t, b1, b2);
}

int bvh_prim_hit(const bvh *b, uint32_t id, const ray *r, double *t, double *b1, double *b2)
{
    return prim_hit(b, id, r, t, b1, b2);
}

/* The primitives prims[first .. first + count) against ray *r: each hit shrinks r->tmax (and
 * *tmax_f) and is recorded in *best; any = 1 stops at the first hit (shadow rays). */
static int leaf_hits(const bvh *b, const fray *f, ray *r, float *tmax_f, long first, int count,
                     int any, best_hit *best)
{
    int found = 0;
    for (long i = first; i < first + count; i++) {
        uint32_t id = b->prims[i];
        double t, b1, b2;
        if (id >= b->n_spheres && !tri_maybe(&b->tris[i], f, *tmax_f, id >= b->n_surfaces))
            continue; /* the float filter: the double test cannot hit */
        if (!prim_hit(b, id, r, &t, &b1, &b2)) continue;
        if (any) return 1;
        found = 1;
        r->tmax = t; /* closest so far: shrink the ray */
        *tmax_f = bvh_float_up(t);
        *best = (best_hit){id, t, b1, b2};
    }
    return found;
}

/* Depth first, the near child first (the first child along the split axis unless the ray runs
 * towards smaller coordinates).  any = 1: stop at the first hit (shadow rays). */
static int traverse(const bvh *b, const ray *r0, int any, best_hit *best)
{
    ray r = *r0;
    fray f = fray_make(&r);
    float tmin_f = bvh_float_down(r.tmin), tmax_f = bvh_float_up(r.tmax);
    /* no tree (a few primitives): the one leaf's box is all space, so no slab test */
    if (!b->is_tree) return leaf_hits(b, &f, &r, &tmax_f, 0, (int)b->n_prims, any, best);
    int32_t stack[BVH_MAX_DEPTH];
    int sp = 0, found = 0;
    int32_t node = 0;
    float tmax_box = tmax_f * (1 + BVH_SLAB_SLACK);
    for (;;) {
        const bvh_node *nd = &b->nodes[node];
        if (box_hit(nd, &f, tmin_f, tmax_box)) {
            if (nd->count == 0) {
                int near_second = f.neg[nd->axis];
                stack[sp++] = near_second ? node + 1 : nd->offset;
                node = near_second ? nd->offset : node + 1;
                continue;
            }
            if (leaf_hits(b, &f, &r, &tmax_f, nd->offset, nd->count, any, best)) {
                if (any) return 1;
                found = 1;
                tmax_box = tmax_f * (1 + BVH_SLAB_SLACK);
            }
        }
        if (sp == 0) break;
        node = stack[--sp];
    }
    return found;
}

int bvh_intersect(const bvh *b, const ray *r, hit *h)
{
    best_hit bh;
    if (b->n_prims == 0 || !traverse(b, r, 0, &bh)) return BVH_MISS;
    return bvh_hit_of(b, r, &bh, h);
}

int bvh_hit_of(const bvh *b, const ray *r, const best_hit *bh, hit *h)
{
    long id = bh->id;
    h->t = bh->t;
    h->prim = id < b->n_spheres ? id : id < b->n_surfaces ? id - b->n_spheres : id - b->n_surfaces;
    if (id >= b->n_surfaces) return BVH_QUAD;
    h->is_sphere = id < b->n_spheres;
    if (h->is_sphere) {
        sphere_hit(&b->prims_of.spheres[id], r, bh->t, h);
        h->material = b->prims_of.spheres[id].material;
    } else {
        triangle_hit(&b->prims_of.triangles[h->prim], bh->b1, bh->b2, h);
        h->material = b->prims_of.triangles[h->prim].material;
    }
    return BVH_SURFACE;
}

int bvh_occluded(const bvh *b, const ray *r)
{
    best_hit bh;
    return b->n_prims > 0 && traverse(b, r, 1, &bh);
}
