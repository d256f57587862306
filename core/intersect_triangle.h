/* The watertight ray-triangle test, inline so that the BVH's leaf loop compiles it in
 * place (it is most of a leaf visit). Included through intersect.h. */
#ifndef RT_INTERSECT_TRIANGLE_H
#define RT_INTERSECT_TRIANGLE_H

/* A ray's crossing of a triangle's interior, before its barycentrics: its t, and the
 * edge functions v, w and their sum det that give them. */
typedef struct {
    rt_real t, v, w, det;
} rt_triangle_crossing;

/* rt_intersect_triangle up to t, with rs's axis permutation passed as kx, ky, kz: a
 * caller that passes constants (the BVH's leaf loop, once per leaf) picks coordinates
 * without branches. */
__attribute__((always_inline)) static inline bool rt_triangle_cross(const rt_ray_setup *rs, rt_vec3 a, rt_vec3 b,
                                                                    rt_vec3 c, rt_triangle_crossing *x, int kx, int ky,
                                                                    int kz)
{
    /* Translate to the ray origin, permute and shear so the ray runs along +z (Woop,
     * Benthin and Wald's watertight test); the 2D edge functions then decide coverage. */
    rt_vec3 o = rs->ray.origin;
    rt_vec3 pa = rt_v3_sub(a, o), pb = rt_v3_sub(b, o), pc = rt_v3_sub(c, o);
    rt_real az = rt_v3_get(pa, kz), bz = rt_v3_get(pb, kz), cz = rt_v3_get(pc, kz);
    rt_real ax = rt_sub(rt_v3_get(pa, kx), rt_mul(rs->sx, az));
    rt_real ay = rt_sub(rt_v3_get(pa, ky), rt_mul(rs->sy, az));
    rt_real bx = rt_sub(rt_v3_get(pb, kx), rt_mul(rs->sx, bz));
    rt_real by = rt_sub(rt_v3_get(pb, ky), rt_mul(rs->sy, bz));
    rt_real cx = rt_sub(rt_v3_get(pc, kx), rt_mul(rs->sx, cz));
    rt_real cy = rt_sub(rt_v3_get(pc, ky), rt_mul(rs->sy, cz));
    rt_real u = rt_sub(rt_mul(cx, by), rt_mul(cy, bx));
    rt_real v = rt_sub(rt_mul(ax, cy), rt_mul(ay, cx));
    rt_real w = rt_sub(rt_mul(bx, ay), rt_mul(by, ax));
    /* Signs on both sides: outside. One branch on the combined test, not one per sign,
     * which a triangle's edges make unpredictable. */
    bool negative = (u < RT_ZERO) | (v < RT_ZERO) | (w < RT_ZERO);
    bool positive = (u > RT_ZERO) | (v > RT_ZERO) | (w > RT_ZERO);
    if (negative & positive) return false;
    rt_real det = rt_add(rt_add(u, v), w);
    /* A ray (nearly) in the triangle's plane sees it edge-on: u, v, w and det are then
     * rounding noise of the size of the 2D coordinates squared times 1e-16, and t would be
     * noise too. Such rays miss. */
    rt_real extent_x = rt_add(rt_add(rt_abs(ax), rt_abs(bx)), rt_abs(cx));
    rt_real extent_y = rt_add(rt_add(rt_abs(ay), rt_abs(by)), rt_abs(cy));
#ifdef RT_REAL_FIXED
    /* In Q32.32 the noise is absolute: each of the six sheared coordinates is off by up
     * to half an lsb and each product rounds by another half, so det is off by at most
     * (extent_x + extent_y + 3) lsb; twice that is noise too (1e-12 would round to 0). */
    rt_real edge_on = rt_add(rt_mul(rt_add(extent_x, extent_y), RT_C(0x1p-31)), RT_C(0x1.8p-30));
#else
    rt_real edge_on = rt_mul(rt_mul(extent_x, extent_y), RT_C(1e-12));
#endif
    if (rt_abs(det) <= edge_on) return false;
    rt_real t = rt_dot3_div(u, rt_mul(rs->sz, az), v, rt_mul(rs->sz, bz), w, rt_mul(rs->sz, cz), det);
    /* A saturated t (Q32.32) is an overflow, not a distance, whatever the interval says. */
    if (!(t > rs->ray.t_min && t < rs->ray.t_max) || !rt_is_finite(t)) return false;
    *x = (rt_triangle_crossing){t, v, w, det};
    return true;
}

/* The hit of a crossing. Its two divisions are left for the crossings a leaf keeps. */
__attribute__((always_inline)) static inline void rt_triangle_hit(const rt_triangle_crossing *x, rt_prim_hit *hit)
{
    hit->t = x->t;
    hit->b1 = rt_div(x->v, x->det);
    hit->b2 = rt_div(x->w, x->det);
    hit->part = RT_PART_SURFACE;
}

/* rt_intersect_triangle with rs's axis permutation passed as kx, ky, kz. */
__attribute__((always_inline)) static inline bool rt_intersect_triangle_axes(const rt_ray_setup *rs, rt_vec3 a,
                                                                             rt_vec3 b, rt_vec3 c, rt_prim_hit *hit,
                                                                             int kx, int ky, int kz)
{
    rt_triangle_crossing x;
    if (!rt_triangle_cross(rs, a, b, c, &x, kx, ky, kz)) return false;
    rt_triangle_hit(&x, hit);
    return true;
}

/* Watertight triangle test (edges shared by two triangles are hit by at least one). */
__attribute__((always_inline)) static inline bool rt_intersect_triangle(const rt_ray_setup *rs, rt_vec3 a, rt_vec3 b,
                                                                        rt_vec3 c, rt_prim_hit *hit)
{
    return rt_intersect_triangle_axes(rs, a, b, c, hit, rs->kx, rs->ky, rs->kz);
}

#endif
