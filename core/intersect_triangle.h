/* The watertight ray-triangle test, inline so that the BVH's leaf loop compiles it in
 * place (it is most of a leaf visit). Included through intersect.h. */
#ifndef RT_INTERSECT_TRIANGLE_H
#define RT_INTERSECT_TRIANGLE_H

/* A ray's crossing of a triangle's interior, before its barycentrics: its t, and the
 * edge functions v, w and their sum det that give them. */
typedef struct {
    rt_real t, v, w, det;
} rt_triangle_crossing;

/* Whether the triangle test may take its unsaturated operations (real_fixed.h) for this
 * ray and triangles with no coordinate beyond `extent`: origin and vertices within 2^12
 * and |sx|, |sy| <= 1 keep the relative coordinates within 2^13, the sheared ones
 * within 2^14, each product within 2^28 and the determinant below 3 2^29, under the
 * rails (2^31). The double build has no rails. */
static inline bool rt_triangle_unsaturated(const rt_ray_setup *rs, rt_real extent)
{
    rt_real r = RT_C(4096.0);
    rt_vec3 o = rs->ray.origin;
    return extent <= r && rt_abs(o.x) <= r && rt_abs(o.y) <= r && rt_abs(o.z) <= r && rt_abs(rs->sx) <= RT_ONE &&
           rt_abs(rs->sy) <= RT_ONE;
}

/* The edge functions' operations: unsaturated where rt_triangle_unsaturated holds. */
__attribute__((always_inline)) static inline rt_real tri_add(bool bounded, rt_real a, rt_real b)
{
    return bounded ? rt_add_unsaturated(a, b) : rt_add(a, b);
}
__attribute__((always_inline)) static inline rt_real tri_sub(bool bounded, rt_real a, rt_real b)
{
    return bounded ? rt_sub_unsaturated(a, b) : rt_sub(a, b);
}
__attribute__((always_inline)) static inline rt_real tri_mul(bool bounded, rt_real a, rt_real b)
{
    return bounded ? rt_mul_unsaturated(a, b) : rt_mul(a, b);
}
/* An edge function a b - c d, and in *sign a value of its sign: in Q32.32 the sign (-1, 0,
 * 1) of the exact products, taken from the same products (a difference below half an lsb
 * rounds to 0, and would put a ray beyond the edge on it: finding 15 in
 * docs/robustness.md); the rounded value has that sign or is 0 (rounding and saturation
 * are monotonic). In double the value itself. */
__attribute__((always_inline)) static inline rt_real tri_edge_function(bool bounded, rt_real a, rt_real b, rt_real c,
                                                                       rt_real d, rt_real *sign)
{
#ifdef RT_REAL_FIXED
    int exact;
    rt_real e = rt_fx_mul_sub(a, b, c, d, bounded, &exact);
    *sign = exact;
    return e;
#else
    rt_real e = tri_sub(bounded, tri_mul(bounded, a, b), tri_mul(bounded, c, d));
    *sign = e;
    return e;
#endif
}
__attribute__((always_inline)) static inline rt_vec3 tri_v3_sub(bool bounded, rt_vec3 a, rt_vec3 b)
{
    return rt_v3(tri_sub(bounded, a.x, b.x), tri_sub(bounded, a.y, b.y), tri_sub(bounded, a.z, b.z));
}

/* rt_intersect_triangle up to t, with rs's axis permutation passed as kx, ky, kz: a
 * caller that passes constants (the BVH's leaf loop, once per leaf) picks coordinates
 * without branches. `bounded`: rt_triangle_unsaturated holds (the same result). */
__attribute__((always_inline)) static inline bool rt_triangle_cross(const rt_ray_setup *rs, rt_vec3 a, rt_vec3 b,
                                                                    rt_vec3 c, rt_triangle_crossing *x, int kx, int ky,
                                                                    int kz, bool bounded)
{
    /* Translate to the ray origin, permute and shear so the ray runs along +z (Woop,
     * Benthin and Wald's watertight test); the 2D edge functions then decide coverage. */
    rt_vec3 o = rs->ray.origin;
    rt_vec3 pa = tri_v3_sub(bounded, a, o), pb = tri_v3_sub(bounded, b, o), pc = tri_v3_sub(bounded, c, o);
    rt_real az = rt_v3_get(pa, kz), bz = rt_v3_get(pb, kz), cz = rt_v3_get(pc, kz);
    rt_real ax = tri_sub(bounded, rt_v3_get(pa, kx), tri_mul(bounded, rs->sx, az));
    rt_real ay = tri_sub(bounded, rt_v3_get(pa, ky), tri_mul(bounded, rs->sy, az));
    rt_real bx = tri_sub(bounded, rt_v3_get(pb, kx), tri_mul(bounded, rs->sx, bz));
    rt_real by = tri_sub(bounded, rt_v3_get(pb, ky), tri_mul(bounded, rs->sy, bz));
    rt_real cx = tri_sub(bounded, rt_v3_get(pc, kx), tri_mul(bounded, rs->sx, cz));
    rt_real cy = tri_sub(bounded, rt_v3_get(pc, ky), tri_mul(bounded, rs->sy, cz));
    rt_real su, sv, sw;
    rt_real u = tri_edge_function(bounded, cx, by, cy, bx, &su);
    rt_real v = tri_edge_function(bounded, ax, cy, ay, cx, &sv);
    rt_real w = tri_edge_function(bounded, bx, ay, by, ax, &sw);
    /* Signs on both sides: outside. One branch on the combined test, not one per sign,
     * which a triangle's edges make unpredictable. */
    bool negative = (su < RT_ZERO) | (sv < RT_ZERO) | (sw < RT_ZERO);
    bool positive = (su > RT_ZERO) | (sv > RT_ZERO) | (sw > RT_ZERO);
    if (negative & positive) return false;
    rt_real det = tri_add(bounded, tri_add(bounded, u, v), w);
    /* A ray (nearly) in the triangle's plane sees it edge-on: u, v, w and det are then
     * rounding noise of the size of the 2D coordinates squared times 1e-16, and t would be
     * noise too. Such rays miss. */
    rt_real extent_x = tri_add(bounded, tri_add(bounded, rt_magnitude(ax), rt_magnitude(bx)), rt_magnitude(cx));
    rt_real extent_y = tri_add(bounded, tri_add(bounded, rt_magnitude(ay), rt_magnitude(by)), rt_magnitude(cy));
#ifdef RT_REAL_FIXED
    /* In Q32.32 the noise is absolute: each of the six sheared coordinates is off by up
     * to half an lsb and each product rounds by another half, so det is off by at most
     * (extent_x + extent_y + 3) lsb; twice that is noise too (1e-12 would round to 0). */
    rt_real edge_on = rt_add(rt_mul(rt_add(extent_x, extent_y), RT_C(0x1p-31)), RT_C(0x1.8p-30));
#else
    rt_real edge_on = rt_mul(rt_mul(extent_x, extent_y), RT_C(1e-12));
#endif
    if (rt_magnitude(det) <= edge_on) return false;
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
    if (!rt_triangle_cross(rs, a, b, c, &x, kx, ky, kz, false)) return false;
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
