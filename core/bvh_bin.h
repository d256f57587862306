/* The binning pass of the BVH build (bvh.c) for one reference: the bin of its centroid
 * on each axis, and a bin's box grown by the reference's box. In the double build on
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
    a[1] = __builtin_ia32_movsd(__builtin_ia32_maxpd(a[1], b.p[1]), __builtin_ia32_minpd(a[1], b.p[1]));
    a[2] = __builtin_ia32_maxpd(a[2], b.p[2]);
}

/* The bins of b's centroid (lo + hi) 0.5: x and y as one pair, z alone. */
static inline void box_bins(const binning *g, box_value b, int out[3])
{
    const pair_d half = {0.5, 0.5}, zero = {0.0, 0.0}, last = {BIN_COUNT - 1, BIN_COUNT - 1};
    pair_d hi_xy = __builtin_ia32_shufpd(b.p[1], b.p[2], 1);
    pair_d x = ((b.p[0] + hi_xy) * half - *(const pair_d *)g->lo) * *(const pair_d *)g->scale;
    quad_i bins = __builtin_ia32_cvttpd2dq(__builtin_ia32_minpd(__builtin_ia32_maxpd(x, zero), last));
    out[0] = bins[0];
    out[1] = bins[1];
    out[2] = bin_of((b.p[1][0] + b.p[2][1]) * 0.5, g->lo[2], g->scale[2]);
}
#else
typedef rt_aabb box_value;

static inline box_value box_load(const rt_aabb *b) { return *b; }

static inline void box_grow(rt_aabb *acc, box_value b)
{
    acc->lo = rt_v3_min(acc->lo, b.lo);
    acc->hi = rt_v3_max(acc->hi, b.hi);
}

static inline void box_bins(const binning *g, box_value b, int out[3])
{
    rt_vec3 c = rt_v3_scale(rt_v3_add(b.lo, b.hi), RT_C(0.5));
    out[0] = bin_of(c.x, g->lo[0], g->scale[0]);
    out[1] = bin_of(c.y, g->lo[1], g->scale[1]);
    out[2] = bin_of(c.z, g->lo[2], g->scale[2]);
}
#endif

#endif
