/* Ray-primitive intersection tests; see intersect.h. */
#include "intersect.h"

__attribute__((always_inline)) static inline rt_ray_setup prepare(rt_ray ray, bool shear)
{
    rt_ray_setup rs;
    rs.ray = ray;
    rt_vec3 d = ray.direction;
    rt_real ax = rt_magnitude(d.x), ay = rt_magnitude(d.y), az = rt_magnitude(d.z);
    rs.kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    int next = rs.kz == 2 ? 0 : rs.kz + 1, last = 3 - rs.kz - next; /* the two axes after kz, cyclically */
    rt_real dz = rt_v3_get(d, rs.kz);
    bool swapped = dz < RT_ZERO; /* keeps the triangle winding test's orientation */
    rs.kx = swapped ? last : next;
    rs.ky = swapped ? next : last;
    rs.order = 2 * rs.kz + swapped;
    rs.sx = shear ? rt_div(rt_v3_get(d, rs.kx), dz) : RT_ZERO;
    rs.sy = shear ? rt_div(rt_v3_get(d, rs.ky), dz) : RT_ZERO;
    rs.sz = shear ? rt_div(RT_ONE, dz) : RT_ZERO;
    rt_real inv[3];
    for (int k = 0; k < 3; k++) {
        rt_real c = rt_v3_get(d, k);
        /* 1 / dz is sz, already divided (a division is the dearest operation in Q32.32). */
        inv[k] = c == RT_ZERO ? RT_REAL_MAX : shear && k == rs.kz ? rs.sz : rt_div(RT_ONE, c);
    }
    rs.inv_direction = rt_v3(inv[0], inv[1], inv[2]);
    return rs;
}

rt_ray_setup rt_intersect_prepare(rt_ray ray) { return prepare(ray, true); }

rt_ray_setup rt_intersect_prepare_no_triangles(rt_ray ray) { return prepare(ray, false); }

/* Smallest root of a t^2 + 2 h t + c in (t_min, t_max), given w2 = r^2 - |f|^2 with f the
 * point of closest approach (see closest_approach_w2), so the quarter discriminant
 * h^2 - a c = a w2 without cancellation, and the roots from the cancellation-free pair
 * q / a, c / q. */
static bool nearest_root(rt_real a, rt_real h, rt_real c, rt_real w2, rt_real t_min, rt_real t_max, rt_real *t)
{
    /* NaN must miss too: rt_sqrt_mul would turn it into 0 and report the point of
     * closest approach as a hit. */
    if (!(a > RT_ZERO) || !(w2 >= RT_ZERO)) return false;
    /* One rounding of a * w2, not two: in Q32.32 a small product rounded to 2^-32 before
     * its root would blur a grazing hit by far more than the rest of the solve. */
    rt_real root = rt_sqrt_mul(a, w2);
    rt_real q = rt_neg(h < RT_ZERO ? rt_sub(h, root) : rt_add(h, root));
    if (q == RT_ZERO) return false;
    rt_real t0 = rt_div(q, a), t1 = rt_div(c, q);
    if (t0 > t1) {
        rt_real s = t0;
        t0 = t1;
        t1 = s;
    }
    if (t0 > t_min && t0 < t_max && rt_is_finite(t0)) {
        *t = t0;
        return true;
    }
    if (t1 > t_min && t1 < t_max && rt_is_finite(t1)) {
        *t = t1;
        return true;
    }
    return false;
}

/* r^2 - |f|^2 with f = o - (h/a) d the point of closest approach of |o + t d|^2 = r^2:
 * h^2 and a c are huge and nearly equal for a far origin, f is not. */
static rt_real closest_approach_w2(rt_vec3 o, rt_vec3 d, rt_real a, rt_real h, rt_real r2)
{
    rt_vec3 f = rt_v3_sub(o, rt_v3_scale(d, rt_div(h, a)));
    return rt_sub(r2, rt_v3_dot(f, f));
}

bool rt_intersect_sphere(rt_vec3 o, rt_vec3 d, rt_real t_min, rt_real t_max, rt_prim_hit *hit)
{
    rt_real a = rt_v3_dot(d, d);
    if (a == RT_ZERO) return false;
    rt_real h = rt_v3_dot(o, d);
    rt_real c = rt_sub(rt_v3_dot(o, o), RT_C(0.25));
    rt_real t;
    if (!nearest_root(a, h, c, closest_approach_w2(o, d, a, h, RT_C(0.25)), t_min, t_max, &t)) return false;
    hit->t = t;
    hit->b1 = hit->b2 = RT_ZERO;
    hit->part = RT_PART_SURFACE;
    return true;
}

bool rt_intersect_cylinder(rt_vec3 o, rt_vec3 d, rt_real t_min, rt_real t_max, rt_prim_hit *hit)
{
    bool found = false;
    rt_real best = t_max;
    /* The side: x^2 + z^2 = 0.25 with |y| <= 0.5. Both roots matter: the near one may
     * lie beyond a cap while the far one is on the body. */
    rt_vec3 o_xz = rt_v3(o.x, RT_ZERO, o.z), d_xz = rt_v3(d.x, RT_ZERO, d.z);
    rt_real a = rt_v3_dot(d_xz, d_xz);
    rt_real h = rt_v3_dot(o_xz, d_xz);
    rt_real c = rt_sub(rt_v3_dot(o_xz, o_xz), RT_C(0.25));
    rt_real w2 = a == RT_ZERO ? rt_neg(RT_ONE) : closest_approach_w2(o_xz, d_xz, a, h, RT_C(0.25));
    rt_real lo = t_min, t;
    for (int root = 0; root < 2 && nearest_root(a, h, c, w2, lo, best, &t); root++) {
        rt_real y = rt_add(o.y, rt_mul(t, d.y));
        if (y >= RT_C(-0.5) && y <= RT_C(0.5)) {
            best = t;
            found = true;
            hit->part = RT_PART_SURFACE;
            break;
        }
        lo = t;
    }
    /* The caps: discs at y = -0.5 and y = +0.5. */
    if (d.y != RT_ZERO) {
        for (int top = 0; top < 2; top++) {
            rt_real y = top ? RT_C(0.5) : RT_C(-0.5), rise = rt_sub(y, o.y);
            /* A cap not ahead (rise and d.y not of one sign) gives t <= 0 <= t_min: no division. */
            bool ahead = (rise > RT_ZERO && d.y > RT_ZERO) || (rise < RT_ZERO && d.y < RT_ZERO);
            if (t_min >= RT_ZERO && !ahead) continue;
            t = rt_div(rise, d.y);
            if (!(t > t_min && t < best) || !rt_is_finite(t)) continue;
            rt_real x = rt_add(o.x, rt_mul(t, d.x)), z = rt_add(o.z, rt_mul(t, d.z));
            if (rt_add(rt_mul(x, x), rt_mul(z, z)) <= RT_C(0.25)) {
                best = t;
                found = true;
                hit->part = top ? RT_PART_CAP_TOP : RT_PART_CAP_BOTTOM;
            }
        }
    }
    if (found) {
        hit->t = best;
        hit->b1 = hit->b2 = RT_ZERO;
    }
    return found;
}

bool rt_intersect_aabb(const rt_ray_setup *rs, const rt_aabb *box, rt_real t_max, rt_real *t_enter)
{
    rt_real t0 = rs->ray.t_min, t1 = t_max;
    for (int k = 0; k < 3; k++) {
        rt_real o = rt_v3_get(rs->ray.origin, k), lo = rt_v3_get(box->lo, k), hi = rt_v3_get(box->hi, k);
        if (rt_v3_get(rs->ray.direction, k) == RT_ZERO) {
            if (o < lo || o > hi) return false;
            continue;
        }
        rt_real inv = rt_v3_get(rs->inv_direction, k);
        rt_real ta = rt_mul(rt_sub(lo, o), inv), tb = rt_mul(rt_sub(hi, o), inv);
        if (ta > tb) {
            rt_real s = ta;
            ta = tb;
            tb = s;
        }
        t0 = rt_max(t0, ta);
        t1 = rt_min(t1, tb);
        if (t0 > t1) return false;
    }
    *t_enter = t0;
    return true;
}
