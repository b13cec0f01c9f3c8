/* raydiff.c - ray differentials at hits and through mirrors and refraction
 * (see include/envtex/geometry/raydiff.h). */
#include "envtex/geometry/raydiff.h"

static const vec3 zero3 = {0, 0, 0};

/* One offset ray (o + dO, d + dD) meets the plane n . x = n . p at p + result. */
static int offset_hit(vec3 o, vec3 d, vec3 dO, vec3 dD, vec3 p, vec3 n, vec3 *dp)
{
    vec3 oo = vec3_add(o, dO), dd = vec3_add(d, dD);
    double den = vec3_dot(n, dd);
    if (!(fabs(den) > RAYDIFF_MIN_COS * vec3_length(n) * vec3_length(dd))) return 0;
    double t = vec3_dot(n, vec3_sub(p, oo)) / den; /* t_x = n.(p - o') / n.d' */
    *dp = vec3_sub(vec3_madd(oo, dd, t), p);       /* dp/dx = o' + t_x d' - p */
    return vec3_is_finite(*dp);
}

int raydiff_at_hit(const ray *r, const ray_diff *rd, vec3 p, vec3 ng, vec3 *dpdx, vec3 *dpdy)
{
    *dpdx = *dpdy = zero3;
    if (!rd || !rd->has) return 0;
    vec3 d = vec3_normalize(r->d); /* the differentials are of the unit direction */
    if (!offset_hit(r->o, d, rd->dox, rd->ddx, p, ng, dpdx) ||
        !offset_hit(r->o, d, rd->doy, rd->ddy, p, ng, dpdy)) {
        *dpdx = *dpdy = zero3;
        return 0;
    }
    return 1;
}

/* dwi of the mirror direction for one screen axis */
static vec3 reflect_dir(vec3 dd_in, vec3 wo, vec3 n, vec3 dn)
{
    vec3 dwo = vec3_neg(dd_in);
    double dwon = vec3_dot(dwo, n) + vec3_dot(wo, dn); /* d(wo . n) */
    /* dwi = -dwo + 2 ((wo . n) dn + d(wo . n) n) */
    vec3 k = vec3_madd(vec3_scale(dn, vec3_dot(wo, n)), n, dwon);
    return vec3_madd(vec3_neg(dwo), k, 2.0);
}

void raydiff_reflect(const ray_diff *in, vec3 dpdx, vec3 dpdy, vec3 wo, vec3 n, vec3 dndx,
                     vec3 dndy, ray_diff *out)
{
    out->has = 0;
    out->dox = out->doy = out->ddx = out->ddy = zero3;
    if (!in || !in->has) return;
    out->dox = dpdx;
    out->doy = dpdy;
    out->ddx = reflect_dir(in->ddx, wo, n, dndx);
    out->ddy = reflect_dir(in->ddy, wo, n, dndy);
    out->has = vec3_is_finite(out->ddx) && vec3_is_finite(out->ddy);
}

/* dwi of the refracted direction for one screen axis */
static vec3 refract_dir(vec3 dd_in, vec3 wo, vec3 n, vec3 dn, double eta, double cos_i,
                        double cos_t)
{
    vec3 dwo = vec3_neg(dd_in);
    double dcos_i = vec3_dot(dwo, n) + vec3_dot(wo, dn); /* d(wo . n) */
    double mu = eta * cos_i - cos_t;                     /* mu = eta cos_i - cos_t */
    double dmu = (eta - eta * eta * cos_i / cos_t) * dcos_i;
    /* dwi = -eta dwo + mu dn + dmu n */
    return vec3_madd(vec3_madd(vec3_scale(dwo, -eta), dn, mu), n, dmu);
}

int raydiff_refract(const ray_diff *in, vec3 dpdx, vec3 dpdy, vec3 wo, vec3 n, vec3 dndx, vec3 dndy,
                    double eta, vec3 wi, ray_diff *out)
{
    out->has = 0;
    out->dox = out->doy = out->ddx = out->ddy = zero3;
    if (!in || !in->has) return 0;
    double cos_i = vec3_dot(wo, n), cos_t = fabs(vec3_dot(wi, n));
    if (!(cos_t > RAYDIFF_MIN_COS)) return 0; /* grazing: dmu would divide by ~0 */
    out->dox = dpdx;
    out->doy = dpdy;
    out->ddx = refract_dir(in->ddx, wo, n, dndx, eta, cos_i, cos_t);
    out->ddy = refract_dir(in->ddy, wo, n, dndy, eta, cos_i, cos_t);
    out->has = vec3_is_finite(out->ddx) && vec3_is_finite(out->ddy);
    return out->has;
}
