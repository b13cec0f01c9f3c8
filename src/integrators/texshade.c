/* texshade.c - texture maps at a ray hit (see include/envtex/integrators/texshade.h). */
#include "envtex/integrators/texshade.h"

#include "envtex/textures/bump.h"
#include "envtex/geometry/raydiff.h"

static const vec3 zero3 = {0, 0, 0};

int texshade_material_has_maps(const material *m)
{
    return m->diffusemap > 0 || m->specularmap > 0 || m->roughnessmap > 0 || m->emissionmap > 0 ||
           m->bumpmap > 0;
}

int texshade_material_needs_footprint(const material *m)
{
    if (!texshade_material_has_maps(m)) return 0;
    /* nearest and bilinear read one point; bump's finite-difference step is the footprint */
    return m->texfilter == TEXFILTER_TRILINEAR || m->texfilter == TEXFILTER_EWA || m->bumpmap > 0;
}

int texshade_scene_needs_differentials(const scene *sc)
{
    for (int i = 0; i < sc->n_materials; i++)
        if (texshade_material_needs_footprint(&sc->materials[i])) return 1;
    return 0;
}

/* v written as a e1 + b e2 in the plane of e1, e2 (least squares: v's part along the normal is
 * dropped).  Normal equations [e1.e1 e1.e2; e1.e2 e2.e2] [a b]^T = [e1.v e2.v]^T.
 * Returns 0, or -1 (a = b = 0) for a degenerate pair. */
static int plane_coords(vec3 e1, vec3 e2, vec3 v, double *a, double *b)
{
    double a11 = vec3_dot(e1, e1), a12 = vec3_dot(e1, e2), a22 = vec3_dot(e2, e2);
    double det = a11 * a22 - a12 * a12;
    *a = *b = 0;
    if (!(det > TEXSHADE_DEGENERATE_EPS * a11 * a22)) return -1;
    double r1 = vec3_dot(e1, v), r2 = vec3_dot(e2, v);
    *a = (a22 * r1 - a12 * r2) / det;
    *b = (a11 * r2 - a12 * r1) / det;
    return 0;
}

/* The world-space outward normal of the (transformed) sphere through world point P. */
static vec3 sphere_normal_at(const sphere *sp, vec3 P)
{
    vec3 local = vec3_sub(mat4_point(&sp->inv, P), sp->center);
    return vec3_normalize(mat4_normal(&sp->inv, local));
}

/* Interpolated vertex normal of a trinormal triangle at barycentrics (b1, b2). */
static vec3 tri_normal_at(const triangle *tr, double b1, double b2)
{
    double b0 = 1 - b1 - b2;
    vec3 n = vec3_add(vec3_add(vec3_scale(tr->n[0], b0), vec3_scale(tr->n[1], b1)),
                      vec3_scale(tr->n[2], b2));
    return vec3_normalize(n);
}

void texshade_differentials(const scene *sc, const hit *h, const ray *r, const ray_diff *rd,
                            surface *s)
{
    s->has_diff = raydiff_at_hit(r, rd, h->p, h->ng, &s->dpdx, &s->dpdy);
    s->dndx = s->dndy = zero3;
    if (!s->has_diff) return;
    double sign = s->entering ? 1.0 : -1.0; /* dn of s->n, which is +-ns */
    if (h->is_sphere) {
        const sphere *sp = &sc->spheres[h->prim];
        /* dn/dx = N(p + dp/dx) - N(p): forward difference over one pixel step */
        s->dndx = vec3_scale(vec3_sub(sphere_normal_at(sp, vec3_add(h->p, s->dpdx)), h->ns), sign);
        s->dndy = vec3_scale(vec3_sub(sphere_normal_at(sp, vec3_add(h->p, s->dpdy)), h->ns), sign);
        return;
    }
    const triangle *tr = &sc->triangles[h->prim];
    if (!tr->has_normals) return; /* a flat triangle: dn = 0 */
    /* the integrators shade with s->n = s->ng where the interpolated normal faces away from
     * the viewer: that n is the facet's, constant, and a mirror about it has dn = 0 (the vertex
     * normals' change would bend the reflected footprint by a curvature the mirror lacks).
     * s->n follows the normal field when it is at least as close to +-ns as to ng. */
    vec3 ns = vec3_scale(h->ns, sign);
    if (vec3_dot(s->n, ns) < vec3_dot(s->n, s->ng)) return;
    vec3 e1 = vec3_sub(tr->p[1], tr->p[0]), e2 = vec3_sub(tr->p[2], tr->p[0]);
    double bx1, bx2, by1, by2;
    if (plane_coords(e1, e2, s->dpdx, &bx1, &bx2) || plane_coords(e1, e2, s->dpdy, &by1, &by2))
        return;
    double b1 = h->bary.u, b2 = h->bary.v;
    s->dndx = vec3_scale(vec3_sub(tri_normal_at(tr, b1 + bx1, b2 + bx2), h->ns), sign);
    s->dndy = vec3_scale(vec3_sub(tri_normal_at(tr, b1 + by1, b2 + by2), h->ns), sign);
}

void texshade_point_at(const scene *sc, const hit *h, const surface *s, texshade_point *tp)
{
    const material *m = &sc->materials[h->material];
    tp->dst_dx = tp->dst_dy = (uv2){0, 0};
    tp->dq_dx = tp->dq_dy = tp->dq_ds = tp->dq_dt = tp->dp_ds = tp->dp_dt = zero3;
    if (h->is_sphere) {
        const sphere *sp = &sc->spheres[h->prim];
        tp->mapping = scene_material_texmapping(m, 1);
        if (tp->mapping == TEXMAPPING_UV) tp->mapping = TEXMAPPING_SPHERICAL;
        tp->q = mat4_point(&sp->inv, h->p); /* P_object = M^-1 P */
        double inv_r = sp->radius > 0 ? 1.0 / sp->radius : 0.0;
        vec3 u = vec3_scale(vec3_sub(tp->q, sp->center), inv_r); /* (P_object - c) / R */
        tp->st = texmapping_point(tp->mapping, u);
        if (s->has_diff) {
            tp->dq_dx = mat4_dir(&sp->inv, s->dpdx);
            tp->dq_dy = mat4_dir(&sp->inv, s->dpdy);
            texmapping_differentials(tp->mapping, u, vec3_scale(tp->dq_dx, inv_r),
                                     vec3_scale(tp->dq_dy, inv_r), &tp->dst_dx, &tp->dst_dy);
        }
        return;
    }
    const triangle *tr = &sc->triangles[h->prim];
    double b1 = h->bary.u, b2 = h->bary.v, b0 = 1 - b1 - b2;
    /* a displaced sphere's triangles carry its mapping in st (triangle.st_mapped) */
    tp->mapping = tr->st_mapped ? TEXMAPPING_UV : scene_material_texmapping(m, 0);
    /* P_object = b0 q0 + b1 q1 + b2 q2 */
    tp->q = vec3_add(vec3_add(vec3_scale(tr->q[0], b0), vec3_scale(tr->q[1], b1)),
                     vec3_scale(tr->q[2], b2));
    double bx1 = 0, bx2 = 0, by1 = 0, by2 = 0;
    int has_db = 0;
    if (s->has_diff) {
        vec3 e1 = vec3_sub(tr->p[1], tr->p[0]), e2 = vec3_sub(tr->p[2], tr->p[0]);
        has_db = plane_coords(e1, e2, s->dpdx, &bx1, &bx2) == 0 &&
                 plane_coords(e1, e2, s->dpdy, &by1, &by2) == 0;
    }
    if (has_db) { /* dP_object = db1 (q1 - q0) + db2 (q2 - q0) */
        vec3 f1 = vec3_sub(tr->q[1], tr->q[0]), f2 = vec3_sub(tr->q[2], tr->q[0]);
        tp->dq_dx = vec3_add(vec3_scale(f1, bx1), vec3_scale(f2, bx2));
        tp->dq_dy = vec3_add(vec3_scale(f1, by1), vec3_scale(f2, by2));
    }
    if (tp->mapping == TEXMAPPING_UV) {
        tp->st = texmapping_uv_interpolate(tr->st, b1, b2); /* st = sum b_i st_i */
        if (has_db) { /* dst = db1 (st1 - st0) + db2 (st2 - st0) */
            double s1 = tr->st[1].u - tr->st[0].u, t1 = tr->st[1].v - tr->st[0].v;
            double s2 = tr->st[2].u - tr->st[0].u, t2 = tr->st[2].v - tr->st[0].v;
            tp->dst_dx = (uv2){bx1 * s1 + bx2 * s2, bx1 * t1 + bx2 * t2};
            tp->dst_dy = (uv2){by1 * s1 + by2 * s2, by1 * t1 + by2 * t2};
        }
        return;
    }
    tp->st = texmapping_point(tp->mapping, tp->q);
    if (has_db)
        texmapping_differentials(tp->mapping, tp->q, tp->dq_dx, tp->dq_dy, &tp->dst_dx,
                                 &tp->dst_dy);
}

void texshade_tangents(const scene *sc, const hit *h, texshade_point *tp)
{
    if (h->is_sphere) {
        const sphere *sp = &sc->spheres[h->prim];
        double inv_r = sp->radius > 0 ? 1.0 / sp->radius : 0.0;
        vec3 u = vec3_scale(vec3_sub(tp->q, sp->center), inv_r);
        vec3 du_ds, du_dt;
        texmapping_tangents(tp->mapping, u, vec3_normalize(u), &du_ds, &du_dt);
        /* dP_object/ds = R du/ds (u = (P_object - c) / R);  world: M (dP_object/ds) */
        tp->dq_ds = vec3_scale(du_ds, sp->radius);
        tp->dq_dt = vec3_scale(du_dt, sp->radius);
        tp->dp_ds = mat4_dir(&sp->xf, tp->dq_ds);
        tp->dp_dt = mat4_dir(&sp->xf, tp->dq_dt);
        return;
    }
    const triangle *tr = &sc->triangles[h->prim];
    if (tp->mapping == TEXMAPPING_UV) {
        texmapping_triangle_tangents(tr->p, tr->st, &tp->dp_ds, &tp->dp_dt);
        texmapping_triangle_tangents(tr->q, tr->st, &tp->dq_ds, &tp->dq_dt);
        return;
    }
    vec3 f1 = vec3_sub(tr->q[1], tr->q[0]), f2 = vec3_sub(tr->q[2], tr->q[0]);
    vec3 nq = vec3_normalize(vec3_cross(f1, f2));
    texmapping_tangents(tp->mapping, tp->q, nq, &tp->dq_ds, &tp->dq_dt);
    /* object tangent a f1 + b f2  ->  world a e1 + b e2 */
    vec3 e1 = vec3_sub(tr->p[1], tr->p[0]), e2 = vec3_sub(tr->p[2], tr->p[0]);
    double a, b;
    plane_coords(f1, f2, tp->dq_ds, &a, &b);
    tp->dp_ds = vec3_add(vec3_scale(e1, a), vec3_scale(e2, b));
    plane_coords(f1, f2, tp->dq_dt, &a, &b);
    tp->dp_dt = vec3_add(vec3_scale(e1, a), vec3_scale(e2, b));
}

/* each channel max(0, c) (NaN as 0) */
static rgb nonnegative(rgb c) { return rgb_make(fmax(0.0, c.r), fmax(0.0, c.g), fmax(0.0, c.b)); }

void texshade_surface(const scene *sc, const hit *h, const ray *r, const ray_diff *rd, surface *s)
{
    s->has_diff = 0;
    if (rd && rd->has) texshade_differentials(sc, h, r, rd, s);
    const material *m = &sc->materials[h->material];
    if (!texshade_material_has_maps(m)) return;

    texshade_point tp;
    texshade_point_at(sc, h, s, &tp);
    texture_query q = {0};
    q.st = tp.st;
    q.dst_dx = tp.dst_dx;
    q.dst_dy = tp.dst_dy;
    q.p = tp.q;
    q.dp_dx = tp.dq_dx;
    q.dp_dy = tp.dq_dy;
    q.filter = m->texfilter;
    const texture *t;
    /* colours from a map are >= 0 as the parser's are: an HDR image (PFM, EXR) may hold
     * negative texels, which a height map may mean but a reflectance or a radiance cannot */
    if ((t = scene_map(sc, m->diffusemap))) s->kd = nonnegative(texture_eval(t, &q));
    if ((t = scene_map(sc, m->specularmap))) s->ks = nonnegative(texture_eval(t, &q));
    if ((t = scene_map(sc, m->roughnessmap))) s->roughness = fmax(0.0, texture_eval_scalar(t, &q));
    if ((t = scene_map(sc, m->emissionmap))) s->emission = nonnegative(texture_eval(t, &q));
    if ((t = scene_map(sc, m->bumpmap))) {
        texshade_tangents(sc, h, &tp);
        q.dp_ds = tp.dq_ds;
        q.dp_dt = tp.dq_dt;
        double hgt, dh_ds, dh_dt;
        texture_height_derivs(t, &q, &hgt, &dh_ds, &dh_dt);
        /* Blinn's n' on the outward frame (ns, ng), then turned like s->n: seen from behind,
         * the same bumps (the surface's, not the viewer's) */
        vec3 nb;
        bump_normal(h->ns, h->ng, tp.dp_ds, tp.dp_dt, dh_ds, dh_dt, m->bump_strength, &nb);
        s->n = s->entering ? nb : vec3_neg(nb);
    }
}

void texshade_delta_diff(const surface *s, const ray_diff *rd, vec3 wo, vec3 wi, ray_diff *out)
{
    out->has = 0;
    if (!s->has_diff || !rd || !rd->has) return;
    /* reflected or refracted, told apart about the normal the direction was made with: a mirror
     * keeps the side of s->n (wi . n = wo . n), a refraction crosses it.  (The side of ng would
     * take a mirror direction about a bumped n that dips below the surface for a refraction.) */
    if (vec3_dot(wi, s->n) * vec3_dot(wo, s->n) >= 0) {
        raydiff_reflect(rd, s->dpdx, s->dpdy, wo, s->n, s->dndx, s->dndy, out);
        return;
    }
    /* refracted: fresnel.h's eta = n_t / n_i; raydiff's is n_i / n_t */
    double eta_t_over_i = s->entering ? s->ior : 1.0 / s->ior;
    raydiff_refract(rd, s->dpdx, s->dpdy, wo, s->n, s->dndx, s->dndy, 1.0 / eta_t_over_i, wi, out);
}
