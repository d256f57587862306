/* The passes of the BVH build (bvh.c) for one reference: its centre, the bin of it on
 * each axis, a bin's box grown by the reference's box, and the centre bounds the
 * partition gathers. In the double build on
 * x86, two coordinates per SSE2 operation; elsewhere by the rt_ ops one at a time. Both
 * compute the same bits: addpd, subpd and mulpd round each lane as addsd, subsd and
 * mulsd do, and minpd(a, b) and maxpd(a, b) are, lane by lane, a < b ? a : b and
 * a > b ? a : b (the second operand on ties and NaN), exactly rt_min and rt_max.
 * Core-internal. */
#ifndef RT_BVH_BIN_H
#define RT_BVH_BIN_H

#include "aabb.h"

#define BIN_COUNT 16

/* How a task's centroids map to bins on each axis; a flat axis bins everything into
 * bin 0 (scale 0) and is never priced. */
typedef struct {
    rt_real lo[3], scale[3];
    bool active[3];
} binning;

/* floor((c - lo) scale) clamped to the bins, without a branch: clamped first (rt_max
 * takes 0 over NaN), then converted. */
static inline int bin_of(rt_real c, rt_real lo, rt_real scale)
{
    rt_real x = rt_min(rt_max(rt_mul(rt_sub(c, lo), scale), RT_ZERO), rt_from_int(BIN_COUNT - 1));
    return (int)rt_floor_nonneg(x);
}

#if defined(__SSE2__) && !defined(RT_REAL_FIXED)
typedef double pair_d __attribute__((vector_size(16), aligned(8), may_alias));
typedef int32_t quad_i __attribute__((vector_size(16)));
/* A box as three pairs: lo.x lo.y | lo.z hi.x | hi.y hi.z. */
typedef struct {
    pair_d p[3];
} box_value;

static inline box_value box_load(const rt_aabb *b)
{
    const pair_d *p = (const pair_d *)b;
    return (box_value){{p[0], p[1], p[2]}};
}

static inline void box_grow(rt_aabb *acc, box_value b)
{
    pair_d *a = (pair_d *)acc;
    a[0] = __builtin_ia32_minpd(a[0], b.p[0]);
    pair_d mixed = __builtin_ia32_maxpd(a[1], b.p[1]); /* lo.z takes the min */
    mixed[0] = __builtin_ia32_minpd(a[1], b.p[1])[0];
    a[1] = mixed;
    a[2] = __builtin_ia32_maxpd(a[2], b.p[2]);
}

/* A box's centre (lo + hi) 0.5, the point the binning sees: x and y as one pair. */
typedef struct {
    pair_d xy;
    double z;
} centre;

static inline centre box_centre(box_value b)
{
    const pair_d half = {0.5, 0.5};
    pair_d hi_xy = __builtin_ia32_shufpd(b.p[1], b.p[2], 1);
    return (centre){(b.p[0] + hi_xy) * half, (b.p[1][0] + b.p[2][1]) * 0.5};
}

static inline rt_real centre_axis(centre c, int axis) { return axis == 2 ? c.z : c.xy[axis]; }

/* The bins of b's centre: x and y from one pair. */
static inline void box_bins(const binning *g, box_value b, int out[3])
{
    const pair_d zero = {0.0, 0.0}, last = {BIN_COUNT - 1, BIN_COUNT - 1};
    centre c = box_centre(b);
    pair_d x = (c.xy - *(const pair_d *)g->lo) * *(const pair_d *)g->scale;
    quad_i bins = __builtin_ia32_cvttpd2dq(__builtin_ia32_minpd(__builtin_ia32_maxpd(x, zero), last));
    out[0] = bins[0];
    out[1] = bins[1];
    out[2] = bin_of(c.z, g->lo[2], g->scale[2]);
}

/* The bounds of centres, as an rt_aabb grown by points would be. */
typedef struct {
    pair_d lo_xy, hi_xy;
    double lo_z, hi_z;
} centre_bounds;

static inline centre_bounds centre_bounds_empty(void)
{
    return (centre_bounds){{RT_REAL_MAX, RT_REAL_MAX}, {-RT_REAL_MAX, -RT_REAL_MAX}, RT_REAL_MAX, -RT_REAL_MAX};
}

static inline void centre_grow(centre_bounds *a, centre c)
{
    a->lo_xy = __builtin_ia32_minpd(a->lo_xy, c.xy);
    a->hi_xy = __builtin_ia32_maxpd(a->hi_xy, c.xy);
    a->lo_z = rt_min(a->lo_z, c.z);
    a->hi_z = rt_max(a->hi_z, c.z);
}

static inline rt_aabb centre_bounds_aabb(centre_bounds a)
{
    return (rt_aabb){{a.lo_xy[0], a.lo_xy[1], a.lo_z}, {a.hi_xy[0], a.hi_xy[1], a.hi_z}};
}
#else
typedef rt_aabb box_value;

static inline box_value box_load(const rt_aabb *b) { return *b; }

static inline void box_grow(rt_aabb *acc, box_value b)
{
    acc->lo = rt_v3_min(acc->lo, b.lo);
    acc->hi = rt_v3_max(acc->hi, b.hi);
}

typedef rt_vec3 centre;

static inline centre box_centre(box_value b) { return rt_v3_scale(rt_v3_add(b.lo, b.hi), RT_C(0.5)); }

static inline rt_real centre_axis(centre c, int axis) { return rt_v3_get(c, axis); }

static inline void box_bins(const binning *g, box_value b, int out[3])
{
    centre c = box_centre(b);
    out[0] = bin_of(c.x, g->lo[0], g->scale[0]);
    out[1] = bin_of(c.y, g->lo[1], g->scale[1]);
    out[2] = bin_of(c.z, g->lo[2], g->scale[2]);
}

typedef rt_aabb centre_bounds;

static inline centre_bounds centre_bounds_empty(void) { return rt_aabb_empty(); }

static inline void centre_grow(centre_bounds *a, centre c)
{
    a->lo = rt_v3_min(a->lo, c);
    a->hi = rt_v3_max(a->hi, c);
}

static inline rt_aabb centre_bounds_aabb(centre_bounds a) { return a; }
#endif

#endif
