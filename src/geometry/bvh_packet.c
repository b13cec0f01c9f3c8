/* bvh_packet.c - camera rays traced a packet at a time (see include/envtex/geometry/bvh_packet.h).
 *
 * The tree is bvh.c's and so is the order: depth first, the near child first by the sign of the
 * direction on the split axis, which all the packet's rays share.  An inner node is tested once
 * for the packet (packet_may_cross); a leaf is tested ray by ray, four rays at a time
 * (lanes_cross), and its triangles too (lanes_triangle), with bvh.c's conservative float tests,
 * lane by lane.  The double test decides each hit (bvh_prim_hit).  So each ray meets the leaves
 * it would meet alone, in the same order, with the same tmax: the same hits, bit for bit.
 */
#include "envtex/geometry/bvh_packet.h"

#include <assert.h>

#include "bvh_leaf.h"
#include "envtex/core/simd.h"

#define GROUPS (BVH_PACKET / 4)

/* Four rays of the packet, a ray a lane. */
typedef struct lanes {
    f4 d[3], inv[3];   /* direction and 1 / direction in float, axis by axis */
    f4 tmax, tmax_box; /* the triangle filter's tmax (>= the ray's) and the slab test's */
    const ray *r[4];   /* the rays in double ... */
    double tmax_d[4];  /* ... and their tmax, which shrinks to each hit */
    best_hit best[4];
    int found; /* bit l: ray l has a hit */
} lanes;

typedef struct packet {
    lanes g[GROUPS];
    int n_groups;
    /* what the rays share: the origin in float (bvh_float_origin), tmin, the signs (neg[a]:
     * the rays enter a node's box by its upper corner's plane on axis a) */
    float o[3], o_lo[3], o_near[3], o_far[3], tmin;
    int neg[3];
    float inv_lo[3], inv_hi[3]; /* the smallest and largest 1 / d over the rays, axis by axis */
} packet;

/* Lanes g from rays r[i] (i < n, else r[first]: a last group of fewer than four repeats
 * its first ray).  0 when a ray does not share r[0]'s origin, tmin, tmax and p's direction
 * signs, or a component of its direction is 0 or infinite in float. */
static int lanes_make(const packet *p, lanes *g, const ray *r, int first, int n)
{
    int fits = 1;
    for (int l = 0; l < 4; l++) {
        const ray *rl = &r[first + l < n ? first + l : first];
        g->r[l] = rl;
        g->tmax_d[l] = rl->tmax;
        g->d[0][l] = (float)rl->d.x;
        g->d[1][l] = (float)rl->d.y;
        g->d[2][l] = (float)rl->d.z;
        fits &= rl->o.x == r->o.x && rl->o.y == r->o.y && rl->o.z == r->o.z &&
                rl->tmin == r->tmin && rl->tmax == r->tmax;
    }
    for (int a = 0; a < 3; a++) {
        g->inv[a] = 1 / g->d[a];
        /* the same sign in every lane, and d and 1 / d finite (not 0): no slab is 0 x Inf */
        fits &= f4_mask(g->inv[a] < 0) == (p->neg[a] ? 15 : 0) &&
                f4_mask(f4_abs(g->inv[a]) < INFINITY) == 15 &&
                f4_mask(f4_abs(g->d[a]) < INFINITY) == 15;
    }
    g->tmax = f4_set(bvh_float_up(r->tmax));
    g->tmax_box = g->tmax * (1 + BVH_SLAB_SLACK);
    g->found = 0;
    return fits;
}

/* The packet of rays r[0..n): 0 when they cannot go together (lanes_make). */
static int packet_make(packet *p, const ray *r, int n)
{
    for (int a = 0; a < 3; a++) {
        p->neg[a] = vec3_get(r[0].d, a) < 0;
        bvh_float_origin(vec3_get(r[0].o, a), p->neg[a], &p->o[a], &p->o_lo[a], &p->o_near[a],
                         &p->o_far[a]);
        /* (an origin beyond float's range: one ray at a time) */
        if (!(fabsf(p->o_near[a]) < INFINITY && fabsf(p->o_far[a]) < INFINITY)) return 0;
    }
    p->tmin = bvh_float_down(r[0].tmin);
    p->n_groups = (n + 3) / 4;
    f4 lo[3], hi[3];
    for (int k = 0; k < p->n_groups; k++) {
        lanes *g = &p->g[k];
        if (!lanes_make(p, g, r, 4 * k, n)) return 0;
        for (int a = 0; a < 3; a++) {
            lo[a] = k ? f4_min(g->inv[a], lo[a]) : g->inv[a];
            hi[a] = k ? f4_max(g->inv[a], hi[a]) : g->inv[a];
        }
    }
    for (int a = 0; a < 3; a++) {
        f4 l = f4_min(lo[a], (f4){lo[a][2], lo[a][3], lo[a][0], lo[a][1]});
        f4 h = f4_max(hi[a], (f4){hi[a][2], hi[a][3], hi[a][0], hi[a][1]});
        p->inv_lo[a] = l[0] < l[1] ? l[0] : l[1];
        p->inv_hi[a] = h[0] > h[1] ? h[0] : h[1];
    }
    return 1;
}

/* Can any ray of p cross the node's box for t in [tmin, tmax_hi] (tmax_hi: the largest of the
 * rays' slab tmax)?  Interval arithmetic: with one origin, ray l meets a plane at
 * t_l = B x (1 / d_l), where B = (plane - o) is one float for all the rays; float rounding
 * never reverses an order, so the rays with the smallest and the largest 1 / d bound every
 * t_l.  Only when even the earliest entry comes after the latest exit does every ray miss; the
 * slab test of each ray, lanes_cross, is then false too.  Testing the rays one by one at the
 * leaves alone is enough: a child's box lies inside its parent's, and the slab test is never
 * looser on a smaller box, so a ray that passes a leaf's test passes every ancestor's. */
static inline int packet_may_cross(const packet *p, const bvh_node *nd, float tmax_hi)
{
    const float grow = 1 + BVH_SLAB_SLACK;
    float enter = p->tmin, leave = tmax_hi;
    for (int a = 0; a < 3; a++) {
        float b0 = nd->box[p->neg[a]][a] - p->o_near[a], b1 = nd->box[!p->neg[a]][a] - p->o_far[a];
        float e0 = b0 * p->inv_lo[a], e1 = b0 * p->inv_hi[a];
        float x0 = b1 * p->inv_lo[a] * grow, x1 = b1 * p->inv_hi[a] * grow;
        float e = e0 < e1 ? e0 : e1, x = x0 > x1 ? x0 : x1; /* earliest entry, latest exit */
        enter = e > enter ? e : enter;
        leave = x < leave ? x : leave;
    }
    return enter <= leave;
}

/* bvh.c's slab test (box_hit) for the four rays of g: bit l set when ray l may cross. */
static inline int lanes_cross(const packet *p, const lanes *g, const bvh_node *nd)
{
    f4 enter = f4_set(p->tmin), leave = g->tmax_box;
    for (int a = 0; a < 3; a++) {
        float b0 = nd->box[p->neg[a]][a] - p->o_near[a], b1 = nd->box[!p->neg[a]][a] - p->o_far[a];
        enter = f4_max(b0 * g->inv[a], enter);
        leave = f4_min(b1 * g->inv[a] * (1 + BVH_SLAB_SLACK), leave);
    }
    return f4_mask(enter <= leave);
}

/* bvh.c's float filter of triangle t (tri_maybe) for the four rays of g: bit l clear only
 * when the double test cannot hit it.  With one origin, s = o - p0 and q = s x e1 are shared. */
static int lanes_triangle(const packet *p, const lanes *g, const bvh_tri *t, int quad)
{
    const f4 *d = g->d;
    const float *e1 = t->e1, *e2 = t->e2;
    f4 pv[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                d[0] * e2[1] - d[1] * e2[0]}; /* d x e2 */
    f4 det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    float n1 = fabsf(e1[0]) + fabsf(e1[1]) + fabsf(e1[2]);
    f4 np = f4_abs(pv[0]) + f4_abs(pv[1]) + f4_abs(pv[2]);
    float s[3] = {(p->o[0] - t->p0[0]) + p->o_lo[0], (p->o[1] - t->p0[1]) + p->o_lo[1],
                  (p->o[2] - t->p0[2]) + p->o_lo[2]};
    float ns = fabsf(s[0]) + fabsf(s[1]) + fabsf(s[2]);
    /* grazing, or the origin far for the triangle's size: the double test decides */
    float graze = BVH_GRAZING * n1, far = ns * (1 / BVH_FILTER_REACH_RAY);
    i4 grazing = ~(f4_abs(det) > np * (graze > far ? graze : far));
    f4 inv = 1 / det;
    float q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
                  s[0] * e1[1] - s[1] * e1[0]};
    f4 b1 = (s[0] * pv[0] + s[1] * pv[1] + s[2] * pv[2]) * inv;
    f4 b2 = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    f4 tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
    i4 in = (b1 >= -BVH_FILTER_EPS) & (b1 <= 1 + BVH_FILTER_EPS) & (b2 >= -BVH_FILTER_EPS) &
            ((quad ? b2 : b1 + b2) <= 1 + BVH_FILTER_EPS) &
            (tt <= g->tmax + f4_abs(tt) * BVH_FILTER_EPS);
    return f4_mask(grazing | in);
}

/* The leaf's primitives prims[first .. first + count) against the rays of g in mask m. */
static void lanes_leaf(const bvh *b, const packet *p, lanes *g, long first, int count, int m)
{
    for (long i = first; i < first + count; i++) {
        uint32_t id = b->prims[i];
        int maybe =
            id < b->n_spheres ? m : m & lanes_triangle(p, g, &b->tris[i], id >= b->n_surfaces);
        for (; maybe; maybe &= maybe - 1) {
            int l = __builtin_ctz((unsigned)maybe);
            ray r = *g->r[l];
            r.tmax = g->tmax_d[l];
            double t, b1, b2;
            if (!bvh_prim_hit(b, id, &r, &t, &b1, &b2)) continue;
            g->tmax_d[l] = t; /* closest so far: shrink the ray */
            g->tmax[l] = bvh_float_up(t);
            g->tmax_box[l] = g->tmax[l] * (1 + BVH_SLAB_SLACK);
            g->best[l] = (best_hit){id, t, b1, b2};
            g->found |= 1 << l;
        }
    }
}

/* The largest slab tmax of p's rays. */
static float packet_tmax(const packet *p)
{
    f4 m = p->g[0].tmax_box;
    for (int k = 1; k < p->n_groups; k++) m = f4_max(p->g[k].tmax_box, m);
    m = f4_max(m, (f4){m[2], m[3], m[0], m[1]});
    return m[0] > m[1] ? m[0] : m[1];
}

static void packet_traverse(const bvh *b, packet *p)
{
    int32_t stack[BVH_MAX_DEPTH];
    int sp = 0;
    int32_t node = 0;
    float tmax_hi = packet_tmax(p);
    for (;;) {
        const bvh_node *nd = &b->nodes[node];
        if (packet_may_cross(p, nd, tmax_hi)) {
            if (nd->count == 0) { /* the near child next, the far one later */
                int near_second = p->neg[nd->axis];
                stack[sp++] = near_second ? node + 1 : nd->offset;
                node = near_second ? nd->offset : node + 1;
                continue;
            }
            for (int k = 0; k < p->n_groups; k++) {
                int m = lanes_cross(p, &p->g[k], nd);
                if (m) lanes_leaf(b, p, &p->g[k], nd->offset, nd->count, m);
            }
            tmax_hi = packet_tmax(p);
        }
        if (sp == 0) break;
        node = stack[--sp];
    }
}

void bvh_intersect_packet(const bvh *b, const ray *r, int n, int *got, hit *h)
{
    assert(n >= 0 && n <= BVH_PACKET);
    if (n == 0) return;
    packet p;
    if (!b->is_tree || !packet_make(&p, r, n)) { /* one at a time */
        for (int i = 0; i < n; i++) got[i] = bvh_intersect(b, &r[i], &h[i]);
        return;
    }
    packet_traverse(b, &p);
    for (int i = 0; i < n; i++) {
        const lanes *g = &p.g[i / 4];
        int l = i % 4;
        got[i] = g->found >> l & 1 ? bvh_hit_of(b, &r[i], &g->best[l], &h[i]) : BVH_MISS;
    }
}
