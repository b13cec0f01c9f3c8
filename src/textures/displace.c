/* displace.c - tessellation and displacement (see include/envtex/textures/displace.h). */
#include "envtex/textures/displace.h"

#include <stdlib.h>
#include <string.h>

static int mesh_alloc(displace_mesh *m, long nv, long nt, error *err)
{
    memset(m, 0, sizeof *m);
    m->p = malloc((size_t)nv * sizeof *m->p);
    m->n = malloc((size_t)nv * sizeof *m->n);
    m->tris = malloc((size_t)nt * sizeof *m->tris);
    if (!m->p || !m->n || !m->tris) {
        displace_mesh_free(m);
        return error_set(err, NULL, 0, "out of memory for a displaced mesh of %ld triangles", nt);
    }
    m->n_verts = nv;
    m->n_tris = nt;
    return 0;
}

void displace_mesh_free(displace_mesh *m)
{
    if (!m) return;
    free(m->p);
    free(m->n);
    free(m->tris);
    memset(m, 0, sizeof *m);
}

/* p += scale h n at every vertex (heights from the callback with the vertex's point: vq[k], or
 * p when vq is NULL, and its st). */
static void displace_vertices(displace_mesh *m, const uv2 *vst, const vec3 *vq,
                              displace_height_fn height, void *ctx, double scale)
{
    /* STEP(displacement): displacement mapping (slide 43 (Displacement Mapping)): move every vertex
     * along its normal by the height there, scaled; the callback and its arguments: displace.h */
    /* STUB: (void)m; (void)vst; (void)vq; (void)height; (void)ctx; (void)scale; */
    for (long k = 0; k < m->n_verts; k++) {
        double h = height ? height(ctx, vq ? vq[k] : m->p[k], m->n[k], vst[k]) : 0.0;
        m->p[k] = vec3_madd(m->p[k], m->n[k], scale * h); /* p' = p + scale h n */
    }
    /* END STEP(displacement) */
}

/* Area-weighted vertex normals; a vertex with a zero sum keeps its old normal. */
static int recompute_normals(displace_mesh *m, error *err)
{
    vec3 *sum = calloc((size_t)m->n_verts, sizeof *sum);
    if (!sum) return error_set(err, NULL, 0, "out of memory for vertex normals");
    for (long i = 0; i < m->n_tris; i++) {
        const long *v = m->tris[i].v;
        /* (b - a) x (c - a): twice the area, along the face normal */
        vec3 f = vec3_cross(vec3_sub(m->p[v[1]], m->p[v[0]]), vec3_sub(m->p[v[2]], m->p[v[0]]));
        for (int k = 0; k < 3; k++) sum[v[k]] = vec3_add(sum[v[k]], f);
    }
    for (long k = 0; k < m->n_verts; k++) {
        vec3 u;
        if (vec3_unit_direction(sum[k], &u) == 0) m->n[k] = u;
    }
    free(sum);
    return 0;
}

/* The common end of a tessellation: move the vertices (displace_vertices), free their st
 * (vst) and callback points (vq, may be NULL), then recompute the normals.  On failure *out is
 * freed. */
static int displace_and_renormalize(displace_mesh *out, uv2 *vst, vec3 *vq,
                                    displace_height_fn height, void *ctx, double scale, error *err)
{
    displace_vertices(out, vst, vq, height, ctx, scale);
    free(vst);
    free(vq);
    if (recompute_normals(out, err)) {
        displace_mesh_free(out);
        return -1;
    }
    return 0;
}

static int check_count(long nt, long max_tris, error *err)
{
    long max = max_tris > 0 && max_tris < DISPLACE_MAX_TRIS ? max_tris : DISPLACE_MAX_TRIS;
    if (nt > max)
        return error_set(err, NULL, 0, "displacement needs %ld triangles, more than the limit %ld",
                         nt, max);
    return 0;
}

/* b0 v0 + b1 v1 + b2 v2, in this order: every interpolated quantity of a grid vertex uses it */
static vec3 bary3(const vec3 v[3], double b0, double b1, double b2)
{
    return vec3_add(vec3_add(vec3_scale(v[0], b0), vec3_scale(v[1], b1)), vec3_scale(v[2], b2));
}

int displace_triangle(const vec3 p[3], const vec3 q[3], const vec3 n[3], const uv2 st[3], int rate,
                      displace_height_fn height, void *ctx, double scale, long max_tris,
                      displace_mesh *out, error *err)
{
    memset(out, 0, sizeof *out);
    if (rate < 1 || rate > DISPLACE_MAX_RATE)
        return error_set(err, NULL, 0, "displacement rate must be in [1, %d], got %d",
                         DISPLACE_MAX_RATE, rate);
    long N = rate;
    if (check_count(N * N, max_tris, err)) return -1;
    vec3 ng = vec3_make(0, 0, 1);
    if (!n && vec3_unit_direction(vec3_cross(vec3_sub(p[1], p[0]), vec3_sub(p[2], p[0])), &ng))
        return error_set(err, NULL, 0, "cannot displace a zero-area triangle without normals");
    long nv = (N + 1) * (N + 2) / 2;
    uv2 *vst = malloc((size_t)nv * sizeof *vst);
    vec3 *vq = q ? malloc((size_t)nv * sizeof *vq) : NULL;
    if (!vst || (q && !vq)) {
        free(vst);
        free(vq);
        return error_set(err, NULL, 0, "out of memory for a displaced mesh");
    }
    if (mesh_alloc(out, nv, N * N, err)) {
        free(vst);
        free(vq);
        return -1;
    }
    /* vertex (i, j): b1 = i / N, b2 = j / N; index = j (N + 1) - j (j - 1) / 2 + i */
#define IDX(i, j) ((j) * (N + 1) - (j) * ((j)-1) / 2 + (i))
    for (long j = 0; j <= N; j++)
        for (long i = 0; i + j <= N; i++) {
            double b1 = (double)i / N, b2 = (double)j / N, b0 = 1.0 - b1 - b2;
            long k = IDX(i, j);
            /* p = b0 p0 + b1 p1 + b2 p2, likewise q, st and n */
            out->p[k] = bary3(p, b0, b1, b2);
            if (vq) vq[k] = bary3(q, b0, b1, b2);
            vst[k] = (uv2){b0 * st[0].u + b1 * st[1].u + b2 * st[2].u,
                           b0 * st[0].v + b1 * st[1].v + b2 * st[2].v};
            vec3 nk = ng;
            if (n && vec3_unit_direction(bary3(n, b0, b1, b2), &nk))
                nk = vec3_normalize(n[0]); /* opposite normals cancelled: take a corner's */
            out->n[k] = nk;
        }
    long t = 0;
    for (long j = 0; j < N; j++)
        for (long i = 0; i + j < N; i++) {
            long a = IDX(i, j), b = IDX(i + 1, j), c = IDX(i, j + 1);
            out->tris[t++] = (displace_tri){{a, b, c}, {vst[a], vst[b], vst[c]}};
            if (i + j < N - 1) {
                long d = IDX(i + 1, j + 1);
                out->tris[t++] = (displace_tri){{b, d, c}, {vst[b], vst[d], vst[c]}};
            }
        }
#undef IDX
    return displace_and_renormalize(out, vst, vq, height, ctx, scale, err);
}

int displace_sphere(int rate, displace_height_fn height, void *ctx, double scale, long max_tris,
                    displace_mesh *out, error *err)
{
    memset(out, 0, sizeof *out);
    if (rate < 2 || rate > DISPLACE_MAX_RATE)
        return error_set(err, NULL, 0, "sphere displacement rate must be in [2, %d], got %d",
                         DISPLACE_MAX_RATE, rate);
    long N = rate, M = 2 * N; /* N bands in theta, M segments in phi */
    long nt = 2 * M * (N - 1);
    if (check_count(nt, max_tris, err)) return -1;
    long nv = 2 + (N - 1) * M;
    uv2 *vst = malloc((size_t)nv * sizeof *vst);
    if (!vst) return error_set(err, NULL, 0, "out of memory for a displaced sphere");
    if (mesh_alloc(out, nv, nt, err)) {
        free(vst);
        return -1;
    }
    /* vertex 0 the north pole, 1 the south pole, ring i (1..N-1) segment j at 2 + (i-1) M + j */
#define RING(i, j) (2 + ((i)-1) * M + ((j) % M))
    out->p[0] = vec3_make(0, 0, 1);
    out->p[1] = vec3_make(0, 0, -1);
    vst[0] = (uv2){0, 1};
    vst[1] = (uv2){0, 0};
    for (long i = 1; i < N; i++) {
        double theta = M_PI * (double)i / N;
        for (long j = 0; j < M; j++) {
            double phi = 2 * M_PI * (double)j / M;
            long k = RING(i, j);
            out->p[k] = vec3_make(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
            vst[k] = (uv2){(double)j / M, 1.0 - (double)i / N}; /* s = phi/2pi, t = 1 - theta/pi */
        }
    }
    for (long k = 0; k < nv; k++) out->n[k] = out->p[k]; /* the unit sphere's normal is p */
    long t = 0;
    for (long j = 0; j < M; j++) {
        /* corner st: s of segment j runs j/M .. (j+1)/M (up to 1 at the seam, not back to 0) */
        double s0 = (double)j / M, s1 = (double)(j + 1) / M, sm = (j + 0.5) / M;
        double tt = 1.0 - 1.0 / N, tb = 1.0 / N;
        out->tris[t++] =
            (displace_tri){{0, RING(1, j), RING(1, j + 1)}, {{sm, 1}, {s0, tt}, {s1, tt}}};
        for (long i = 1; i < N - 1; i++) {
            long a0 = RING(i, j), a1 = RING(i, j + 1), b0 = RING(i + 1, j), b1 = RING(i + 1, j + 1);
            double ta = 1.0 - (double)i / N, tl = 1.0 - (double)(i + 1) / N;
            out->tris[t++] = (displace_tri){{a0, b0, b1}, {{s0, ta}, {s0, tl}, {s1, tl}}};
            out->tris[t++] = (displace_tri){{a0, b1, a1}, {{s0, ta}, {s1, tl}, {s1, ta}}};
        }
        out->tris[t++] =
            (displace_tri){{1, RING(N - 1, j + 1), RING(N - 1, j)}, {{sm, 0}, {s1, tb}, {s0, tb}}};
    }
#undef RING
    return displace_and_renormalize(out, vst, NULL, height, ctx, scale, err);
}
