/* The per-ray box tests of the general BVH walk (scene_query.c): a ray's slab set-up, and
 * the test of a node's eight children in the double build with SSE2, in the fixed build
 * with integer bounds, and one by one otherwise. (Most rays of the double build on x86
 * take the float walk of bvh_float.h instead.) Included by scene_query.c only. */
#ifndef RT_BVH_SLAB_H
#define RT_BVH_SLAB_H

#include "bvh.h"
#include "scene_query.h"

/* The double build tests a node's eight children two at a time with SSE2 (x86-64's
 * baseline), the fixed build with integer bounds (below); other targets and unusual
 * rays test them one by one. The SSE2 operations are the compilers' own builtins (the
 * core includes no intrinsics header). */
#if defined(__SSE2__) && !defined(RT_REAL_FIXED)
#define SLAB_SSE2 1
typedef double v2df __attribute__((vector_size(16)));
typedef float v4sf __attribute__((vector_size(16), aligned(4), may_alias));
typedef uint32_t v4su __attribute__((vector_size(16), aligned(4), may_alias));

/* Lanes 0, 1 (lo) or 2, 3 (hi) of four floats, as doubles: one cvtps2pd either way. */
static inline v2df v2df_from_lo(v4sf a)
{
#ifdef __clang__
    return __builtin_convertvector(__builtin_shufflevector(a, a, 0, 1), v2df);
#else
    return __builtin_ia32_cvtps2pd(a);
#endif
}
static inline v2df v2df_from_hi(v4sf a)
{
#ifdef __clang__
    return __builtin_convertvector(__builtin_shufflevector(a, a, 2, 3), v2df);
#else
    return __builtin_ia32_cvtps2pd(__builtin_ia32_movhlps(a, a));
#endif
}

#else
#define SLAB_SSE2 0
#endif

#ifdef RT_REAL_FIXED
/* The fixed build's box test in plain 64-bit integers: each plane's distance bounded from
 * below (near) or above (far) in a per-ray unit, one subtraction and one multiply per
 * plane, (b - o) m; why the bounds are conservative: docs/box-tests.md, "The fixed build". */
typedef struct {
    int64_t near_o[3], near_m[3], far_o[3], far_m[3]; /* a plane's bound is (b - o) m */
    int64_t t_min_u;                                  /* t_min in units, rounded down */
    int to_units;                                     /* a Q32.32 value times 2^to_units is in units */
    bool usable;
} fixed_slab;

/* floor(x / 2^s) for 0 <= s <= 63, by the magnitude (no signed right shift). */
__attribute__((always_inline)) static inline int64_t floor_shift(int64_t x, int s)
{
    uint64_t mag = rt_fx_mag(x), q = mag >> s;
    bool rest = (mag & ((UINT64_C(1) << s) - 1)) != 0;
    return x < 0 ? -(int64_t)(q + rest) : (int64_t)q;
}

/* x * 2^s for s >= 0, saturated to +-INT64_MAX. */
__attribute__((always_inline)) static inline int64_t saturating_scale(int64_t x, int s)
{
    int64_t most = INT64_MAX >> s;
    return x > most ? INT64_MAX : x < -most ? -INT64_MAX : x * ((int64_t)1 << s);
}

/* x * 2^s rounded down (up = false) or up, saturated; -63 <= s <= 62. */
__attribute__((always_inline)) static inline int64_t scale_bound(int64_t x, int s, bool up)
{
    if (s >= 0) return saturating_scale(x, s);
    return up ? -floor_shift(-x, -s) : floor_shift(x, -s);
}

/* The number of bits of v (0 for 0). */
static int bit_length(uint64_t v) { return v ? 64 - __builtin_clzll(v) : 0; }

/* Origins up to 2^FIXED_SLAB_REACH grid units (2^(FIXED_SLAB_REACH - 31) times the
 * scene's largest coordinate) take the integer test; beyond, the general one. */
#define FIXED_SLAB_REACH 45

static fixed_slab fixed_slab_prepare(rt_vec3 origin, rt_vec3 inv, rt_real t_min, int grid)
{
    fixed_slab f;
    rt_real o[3] = {origin.x, origin.y, origin.z}, iv[3] = {inv.x, inv.y, inv.z};
    int64_t o_lo[3];
    /* The bits of the largest |inv| and of the largest |o_lo|, from the magnitudes or'ed. */
    int steepest = bit_length(rt_fx_mag(iv[0]) | rt_fx_mag(iv[1]) | rt_fx_mag(iv[2]));
    uint64_t o_bits = 0;
    for (int k = 0; k < 3; k++) {
        o_lo[k] = floor_shift(o[k], grid);
        o_bits |= rt_fx_mag(o_lo[k]);
    }
    int reach = bit_length(o_bits);
    f.usable = t_min >= RT_ZERO && reach <= FIXED_SLAB_REACH;
    /* |b - o_lo| < 2^(r + 1) with r = max(reach, 32), so m of 61 - r bits on the steepest
     * axis (29 for origins within 2^32 units) keeps every product below 2^62: e = 61 - r -
     * steepest. A distance is d' g inv with the grid unit g = 2^(grid - 32) and inv =
     * inv_q 2^-32 (inv_q the Q32.32 count), so the unit is 2^(grid - 64 - e), and a Q32.32
     * t (t_q 2^-32) is t_q 2^(e + 32 - grid) units. */
    int r = reach < 32 ? 32 : reach > FIXED_SLAB_REACH ? FIXED_SLAB_REACH : reach; /* keeps unused rays' shifts legal */
    int e = 61 - r - steepest;
    f.to_units = e + 32 - grid;
    f.t_min_u = scale_bound(t_min, f.to_units, false);
    for (int k = 0; k < 3; k++) {
        int64_t m = e >= 0 ? iv[k] * ((int64_t)1 << e) : floor_shift(iv[k], -e);
        bool up = m >= 0;
        f.near_o[k] = o_lo[k] + up;
        f.near_m[k] = m + !up;
        f.far_o[k] = o_lo[k] + !up;
        f.far_m[k] = m + up;
    }
    return f;
}
#endif

/* The slab test of rt_intersect_aabb on a child's stored box, with the per-axis branches
 * decided once per ray: for a non-zero direction component the near plane is lo when it
 * is positive and hi when negative (the products are monotonic in the plane, so this is
 * the swap the general test makes), and without NaN the three axes can be clamped before
 * the one comparison. Rays with a zero component, a non-finite reciprocal or origin keep
 * the general test, whose zero-direction and NaN cases differ. */
typedef struct {
    rt_vec3 origin, inv;
    rt_real t_min;
    int near[3], far[3]; /* each axis' near and far plane: a row of rt_bvh_node.box */
    int grid;
    bool general;
    const rt_ray_setup *rs;
    const rt_bvh *bvh;
#if SLAB_SSE2
    v2df origin2[3], inv2[3], t_min2; /* each value in both lanes */
#endif
#ifdef RT_REAL_FIXED
    fixed_slab fx;
#endif
} slab_ray;

static slab_ray slab_prepare(const rt_ray_setup *rs, const rt_bvh *bvh)
{
    rt_vec3 d = rs->ray.direction, o = rs->ray.origin, inv = rs->inv_direction;
    slab_ray r;
    r.origin = o;
    r.inv = inv;
    r.t_min = rs->ray.t_min;
    r.rs = rs;
    r.bvh = bvh;
    r.grid = bvh->grid;
    for (int k = 0; k < 3; k++) {
        bool neg = rt_v3_get(d, k) < RT_ZERO;
        r.near[k] = neg ? 3 + k : k;
        r.far[k] = neg ? k : 3 + k;
#if SLAB_SSE2
        r.origin2[k] = (v2df){rt_v3_get(o, k), rt_v3_get(o, k)};
        r.inv2[k] = (v2df){rt_v3_get(inv, k), rt_v3_get(inv, k)};
#endif
    }
#if SLAB_SSE2
    r.t_min2 = (v2df){r.t_min, r.t_min};
#endif
    r.general = d.x == RT_ZERO || d.y == RT_ZERO || d.z == RT_ZERO || !rt_is_finite(inv.x) || !rt_is_finite(inv.y) ||
                !rt_is_finite(inv.z) || !rt_is_finite(o.x) || !rt_is_finite(o.y) || !rt_is_finite(o.z);
#ifdef RT_REAL_FIXED
    r.fx = fixed_slab_prepare(o, inv, r.t_min, bvh->grid);
    r.general = r.general || !r.fx.usable;
#endif
    return r;
}

/* Child c of `node`: entered before t_max, at *t_enter? */
static inline bool slab_hit(const slab_ray *r, const rt_bvh_node *node, int c, rt_real t_max, rt_real *t_enter)
{
    if (r->general) {
        rt_aabb box = rt_bvh_child_box(r->bvh, node, c);
        return rt_intersect_aabb(r->rs, &box, t_max, t_enter);
    }
    const rt_bound(*b)[RT_BVH_WIDTH] = node->box;
    int g = r->grid;
    rt_real x0 = rt_mul(rt_sub(rt_bound_value(b[r->near[0]][c], g), r->origin.x), r->inv.x);
    rt_real x1 = rt_mul(rt_sub(rt_bound_value(b[r->far[0]][c], g), r->origin.x), r->inv.x);
    rt_real y0 = rt_mul(rt_sub(rt_bound_value(b[r->near[1]][c], g), r->origin.y), r->inv.y);
    rt_real y1 = rt_mul(rt_sub(rt_bound_value(b[r->far[1]][c], g), r->origin.y), r->inv.y);
    rt_real z0 = rt_mul(rt_sub(rt_bound_value(b[r->near[2]][c], g), r->origin.z), r->inv.z);
    rt_real z1 = rt_mul(rt_sub(rt_bound_value(b[r->far[2]][c], g), r->origin.z), r->inv.z);
    rt_real t0 = rt_max(rt_max(rt_max(r->t_min, x0), y0), z0);
    rt_real t1 = rt_min(rt_min(rt_min(t_max, x1), y1), z1);
    *t_enter = t0;
    return !(t0 > t1);
}

#if SLAB_SSE2
#define SLAB_PAIRS (RT_BVH_WIDTH / 2)
typedef struct {
    v2df t0[SLAB_PAIRS], t1[SLAB_PAIRS]; /* entry and exit distances of children 2i, 2i + 1 */
} slab_pairs;

/* One axis of slab_hit for all the children, two per register: the same IEEE
 * operations in the same order, so the same distances (maxpd and minpd are rt_max and
 * rt_min: a > b ? a : b and a < b ? a : b). */
__attribute__((always_inline)) static inline void slab_axis_sse2(const slab_ray *r, const rt_bvh_node *node, int k,
                                                                 slab_pairs *s)
{
    v2df o = r->origin2[k], inv = r->inv2[k];
    for (int q = 0; q < RT_BVH_WIDTH / 4; q++) {
        v4sf near = *(const v4sf *)&node->box[r->near[k]][4 * q], far = *(const v4sf *)&node->box[r->far[k]][4 * q];
        s->t0[2 * q] = __builtin_ia32_maxpd(s->t0[2 * q], (v2df_from_lo(near) - o) * inv);
        s->t0[2 * q + 1] = __builtin_ia32_maxpd(s->t0[2 * q + 1], (v2df_from_hi(near) - o) * inv);
        s->t1[2 * q] = __builtin_ia32_minpd(s->t1[2 * q], (v2df_from_lo(far) - o) * inv);
        s->t1[2 * q + 1] = __builtin_ia32_minpd(s->t1[2 * q + 1], (v2df_from_hi(far) - o) * inv);
    }
}

/* slab_hit on all the children at once. */
__attribute__((always_inline)) static inline unsigned slab_hit_sse2(const slab_ray *r, const rt_bvh_node *node,
                                                                    rt_real t_max, rt_real t_enter[RT_BVH_WIDTH])
{
    v2df limit = {t_max, t_max};
    slab_pairs s;
    for (int i = 0; i < SLAB_PAIRS; i++) s.t0[i] = r->t_min2, s.t1[i] = limit;
    slab_axis_sse2(r, node, 0, &s);
    slab_axis_sse2(r, node, 1, &s);
    slab_axis_sse2(r, node, 2, &s);
    unsigned hits = 0, unused = 0;
    for (int i = 0; i < SLAB_PAIRS; i++) {
        t_enter[2 * i] = s.t0[i][0];
        t_enter[2 * i + 1] = s.t0[i][1];
        hits |= (unsigned)__builtin_ia32_movmskpd(__builtin_ia32_cmplepd(s.t0[i], s.t1[i])) << (2 * i);
    }
    for (int q = 0; q < RT_BVH_WIDTH / 4; q++) {
        v4su none = *(const v4su *)&node->count[4 * q] == RT_BVH_NO_CHILD;
        unused |= (unsigned)__builtin_ia32_movmskps((v4sf)none) << (4 * q);
    }
    return hits & ~unused;
}
#endif

#ifdef RT_REAL_FIXED
/* Child c's plane in `row` (a row of the node's boxes): its bound in units (see fixed_slab). */
__attribute__((always_inline)) static inline int64_t fixed_plane(const rt_bound *row, int c, int64_t o, int64_t m)
{
    return ((int64_t)row[c] - o) * m;
}

/* All the children with fixed_slab's bounds, against limit_u (units): a superset of the
 * exact test's hits, and entry distances in units at or below the exact ones. */
__attribute__((always_inline)) static inline unsigned slab_hit_fixed(const slab_ray *r, const rt_bvh_node *node,
                                                                     int64_t limit_u, int64_t t_enter[RT_BVH_WIDTH])
{
    const fixed_slab *f = &r->fx;
    const rt_bound *nx = node->box[r->near[0]], *ny = node->box[r->near[1]], *nz = node->box[r->near[2]];
    const rt_bound *fx = node->box[r->far[0]], *fy = node->box[r->far[1]], *fz = node->box[r->far[2]];
    unsigned hits = 0;
#pragma GCC unroll 4
    for (int c = 0; c < RT_BVH_WIDTH; c++) {
        if (node->count[c] == RT_BVH_NO_CHILD) continue;
        int64_t t0 = rt_max(f->t_min_u, fixed_plane(nx, c, f->near_o[0], f->near_m[0]));
        t0 = rt_max(t0, fixed_plane(ny, c, f->near_o[1], f->near_m[1]));
        t0 = rt_max(t0, fixed_plane(nz, c, f->near_o[2], f->near_m[2]));
        int64_t t1 = rt_min(limit_u, fixed_plane(fx, c, f->far_o[0], f->far_m[0]));
        t1 = rt_min(t1, fixed_plane(fy, c, f->far_o[1], f->far_m[1]));
        t1 = rt_min(t1, fixed_plane(fz, c, f->far_o[2], f->far_m[2]));
        if (t0 > t1) continue;
        hits |= 1u << c;
        t_enter[c] = t0;
    }
    return hits;
}
#endif

/* The walk's measure of a distance t: t itself, or for the fixed build's integer test t
 * in its units rounded up, so that a box whose entry in units is beyond key(t) is entered
 * beyond t (the walk then never converts an entry back). Monotonic in t. */
static inline rt_real slab_key(const slab_ray *r, rt_real t)
{
#ifdef RT_REAL_FIXED
    if (!r->general) return scale_bound(t, r->fx.to_units, true);
#endif
    (void)r;
    return t;
}

/* Tests every child of `node`: bit c of the result is set when child c may be entered
 * before the distance whose key (slab_key) is limit, and t_enter[c] is then at most the
 * key of its entry distance. Unused slots never are. */
__attribute__((always_inline)) static inline unsigned slab_hit_children(const slab_ray *r, const rt_bvh_node *node,
                                                                        rt_real limit, rt_real t_enter[RT_BVH_WIDTH])
{
#if SLAB_SSE2
    if (!r->general) return slab_hit_sse2(r, node, limit, t_enter);
#endif
#ifdef RT_REAL_FIXED
    if (!r->general) return slab_hit_fixed(r, node, limit, t_enter);
#endif
    unsigned hits = 0;
    for (int c = 0; c < RT_BVH_WIDTH; c++)
        if (node->count[c] != RT_BVH_NO_CHILD && slab_hit(r, node, c, limit, &t_enter[c])) hits |= 1u << c;
    return hits;
}

#endif
