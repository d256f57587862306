/* The passes of the BVH build (bvh.c) for one reference: its box and centre, the bin of
 * the centre on each axis, a bin's box grown by the reference's box, and the centre
 * bounds the partition gathers. Core-internal.
 *
 * The double build sorts references by their padded box rounded outwards to floats, the
 * precision of the stored nodes: a node's stored box is the same either way (rounding
 * outwards is monotonic, so the rounded union is the union of the rounded boxes), and a
 * reference is 32 bytes instead of 56. Its passes work on four float lanes (x, y, z and a
 * lane kept 0) with the compilers' vector extensions: SSE on x86, NEON on aarch64,
 * scalar code elsewhere, the same bits every way (IEEE single operations lane by lane;
 * v4_min and v4_max are rt_min and rt_max). The fixed build keeps its Q32.32 boxes. */
#ifndef RT_BVH_BIN_H
#define RT_BVH_BIN_H

#include "aabb.h"

#define BIN_COUNT 16

#ifndef RT_REAL_FIXED
typedef float v4f __attribute__((vector_size(16)));
typedef int32_t v4i __attribute__((vector_size(16)));
typedef float v4f_load __attribute__((vector_size(16), aligned(4), may_alias));

/* Lane by lane: a where `take` is all ones, b where it is 0. */
static inline v4f v4_select(v4i take, v4f a, v4f b) { return (v4f)((take & (v4i)a) | (~take & (v4i)b)); }

/* a < b ? a : b and a > b ? a : b lane by lane: the later operand on ties and NaN. */
static inline v4f v4_min(v4f a, v4f b)
{
#ifdef __SSE__
    return __builtin_ia32_minps(a, b);
#else
    return v4_select(a < b, a, b);
#endif
}
static inline v4f v4_max(v4f a, v4f b)
{
#ifdef __SSE__
    return __builtin_ia32_maxps(a, b);
#else
    return v4_select(a > b, a, b);
#endif
}

/* A reference: its box's corners in lanes 0-2, the primitive in lo's fourth slot. */
typedef struct {
    float lo[3];
    uint32_t prim;
    float hi[3], zero;
} build_ref;

typedef struct {
    v4f lo, hi;
} bin_box;

typedef double v4d __attribute__((vector_size(32)));
typedef int64_t v4l __attribute__((vector_size(32)));

/* Each coordinate of p (and a fourth lane 0) clamped to the float range, so that the
 * conversion cannot overflow, and rounded to the nearest float (*f); in *inwards, the
 * lanes where that went inwards (below p if up, else above). */
#ifdef __SSE2__
typedef double v2d __attribute__((vector_size(16)));
#ifdef __clang__
#define V4_SHUFFLE(a, b, i, j, k, l) __builtin_shufflevector(a, b, i, j, k, l)
#else
#define V4_SHUFFLE(a, b, i, j, k, l) __builtin_shuffle(a, b, (v4i){i, j, k, l})
#endif

/* Two lanes in an SSE2 register (GCC turns the four-lane double operations of the
 * generic version into scalar comparisons): the floats in lanes 0-1, and in *back, them
 * as doubles. */
static inline v4f v2_nearest(v2d x, v2d *back)
{
    const v2d most = {RT_FLOAT_MAX, RT_FLOAT_MAX};
    /* max and min return their second operand on NaN, which the generic selects keep. */
    v4f f = __builtin_ia32_cvtpd2ps(__builtin_ia32_minpd(most, __builtin_ia32_maxpd(-most, x)));
#ifdef __clang__
    *back = __builtin_convertvector(__builtin_shufflevector(f, f, 0, 1), v2d);
#else
    *back = __builtin_ia32_cvtps2pd(f);
#endif
    return f;
}

static inline void v4_nearest(rt_vec3 p, bool up, v4f *f, v4i *inwards)
{
    v2d xy = {p.x, p.y}, z0 = {p.z, 0.0}, back_xy, back_z0;
    v4f f_xy = v2_nearest(xy, &back_xy), f_z0 = v2_nearest(z0, &back_z0);
    v4i in_xy = (v4i)(up ? back_xy < xy : back_xy > xy), in_z0 = (v4i)(up ? back_z0 < z0 : back_z0 > z0);
    *f = V4_SHUFFLE(f_xy, f_z0, 0, 1, 4, 5);
    *inwards = V4_SHUFFLE(in_xy, in_z0, 0, 2, 4, 6); /* each 64-bit mask's low half */
}
#else
static inline void v4_nearest(rt_vec3 p, bool up, v4f *f, v4i *inwards)
{
    const v4d most = {RT_FLOAT_MAX, RT_FLOAT_MAX, RT_FLOAT_MAX, RT_FLOAT_MAX};
    v4d x = {p.x, p.y, p.z, 0.0};
    v4l above = x > most, below = x < -most;
    v4d in_range = (v4d)((above & (v4l)most) | (below & (v4l)-most) | (~(above | below) & (v4l)x));
    *f = __builtin_convertvector(in_range, v4f);
    v4d back = __builtin_convertvector(*f, v4d);
    *inwards = __builtin_convertvector(up ? back < x : back > x, v4i);
}
#endif

/* rt_bound_above (up) or rt_bound_below of each coordinate of p, without their branches,
 * which a box's coordinates make unpredictable: rounded to nearest (v4_nearest), then
 * one step outwards where that went inwards. Lane 3 is 0. */
static inline v4f v4_round_outwards(rt_vec3 p, bool up)
{
    v4f f;
    v4i inwards;
    v4_nearest(p, up, &f, &inwards);
    /* The next float outwards: the bits one step from 0 on the outward side, one step
     * towards it on the other (rt_float_step); from 0 the smallest subnormal. */
    int32_t step = up ? 1 : -1;
    v4i bits = (v4i)f, positive = f > 0.0f, negative = f < 0.0f;
    v4i stepped = bits + (positive & step) - (negative & step);
    int32_t least = up ? 1 : INT32_MIN + 1; /* +-0x1p-149f */
    v4f smallest = (v4f)((v4i){0, 0, 0, 0} + least);
    v4f next = v4_select(positive | negative, (v4f)stepped, smallest);
    return v4_select(inwards, next, f);
}

/* Stores prim's reference with its padded box at *r and returns that box as ref_box
 * would read it back. Each half is one 16-byte store: a reload then takes it from the
 * store buffer, which stores of its pieces would stall. */
static inline bin_box ref_store(build_ref *r, rt_aabb padded, uint32_t prim)
{
    const v4i prim_lane = {0, 0, 0, (int32_t)prim};
    v4f lo = v4_round_outwards(padded.lo, false), hi = v4_round_outwards(padded.hi, true);
    *(v4f_load *)r->lo = (v4f)((v4i)lo | prim_lane);
    *(v4f_load *)r->hi = hi;
    return (bin_box){lo, hi};
}

/* Loaded once per pass (the bins' stores could alias it), lo's fourth lane cleared. */
static inline bin_box ref_box(const build_ref *r)
{
    const v4i xyz = {-1, -1, -1, 0};
    return (bin_box){(v4f)((v4i) * (const v4f_load *)r->lo & xyz), *(const v4f_load *)r->hi};
}

static inline bin_box bin_box_empty(void)
{
    const v4f inf = {__builtin_inff(), __builtin_inff(), __builtin_inff(), __builtin_inff()};
    return (bin_box){inf, -inf};
}

static inline void bin_box_grow(bin_box *acc, bin_box b)
{
    acc->lo = v4_min(acc->lo, b.lo);
    acc->hi = v4_max(acc->hi, b.hi);
}

static inline rt_aabb bin_box_aabb(bin_box b)
{
    return (rt_aabb){{b.lo[0], b.lo[1], b.lo[2]}, {b.hi[0], b.hi[1], b.hi[2]}};
}

/* rt_aabb_half_area(bin_box_aabb(b)), the lanes converted together. */
static inline rt_real bin_box_half_area(bin_box b)
{
    if (b.lo[0] > b.hi[0]) return RT_ZERO;
    v4d e = __builtin_convertvector(b.hi, v4d) - __builtin_convertvector(b.lo, v4d);
    return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
}

/* The box centre (lo + hi) / 2, the point the binning sees. */
typedef v4f centre;

static inline centre box_centre(bin_box b)
{
    const v4f half = {0.5f, 0.5f, 0.5f, 0.5f};
    return (b.lo + b.hi) * half;
}

/* How a task's centres map to bins on each axis; a flat axis bins everything into bin
 * 0 (scale 0) and is never priced. */
typedef struct {
    v4f lo, scale;
    bool active[3];
} binning;

static inline binning binning_make(rt_aabb centres)
{
    binning g = {{0}, {0}, {false}};
    for (int axis = 0; axis < 3; axis++) {
        float lo = (float)rt_v3_get(centres.lo, axis), hi = (float)rt_v3_get(centres.hi, axis);
        g.lo[axis] = lo;
        g.active[axis] = hi > lo;
        g.scale[axis] = g.active[axis] ? (float)BIN_COUNT / (hi - lo) : 0.0f;
    }
    return g;
}

/* floor((c - lo) scale) clamped to the bins on every axis: clamped first (v4_max takes 0
 * over NaN), then truncated. */
static inline v4i centre_bins(const binning *g, centre c)
{
    const v4f zero = {0.0f, 0.0f, 0.0f, 0.0f}, last = {BIN_COUNT - 1, BIN_COUNT - 1, BIN_COUNT - 1, BIN_COUNT - 1};
    return __builtin_convertvector(v4_min(v4_max((c - g->lo) * g->scale, zero), last), v4i);
}

static inline void box_bins(const binning *g, bin_box b, int out[3])
{
    v4i k = centre_bins(g, box_centre(b));
    out[0] = k[0];
    out[1] = k[1];
    out[2] = k[2];
}

/* The bin of c on one axis: a lane of centre_bins, so the partition agrees with the bins. */
static inline int centre_bin(const binning *g, centre c, int axis) { return centre_bins(g, c)[axis]; }

typedef bin_box centre_bounds;

static inline centre_bounds centre_bounds_empty(void) { return bin_box_empty(); }

static inline void centre_grow(centre_bounds *a, centre c) { bin_box_grow(a, (bin_box){c, c}); }

static inline rt_aabb centre_bounds_aabb(centre_bounds a) { return bin_box_aabb(a); }
#else
/* The fixed build: the padded Q32.32 box as it is. */
typedef struct {
    rt_aabb bounds;
    uint32_t prim;
} build_ref;

typedef rt_aabb bin_box;

static inline bin_box ref_store(build_ref *r, rt_aabb padded, uint32_t prim)
{
    *r = (build_ref){padded, prim};
    return padded;
}

static inline bin_box ref_box(const build_ref *r) { return r->bounds; }

static inline bin_box bin_box_empty(void) { return rt_aabb_empty(); }

static inline void bin_box_grow(bin_box *acc, bin_box b)
{
    acc->lo = rt_v3_min(acc->lo, b.lo);
    acc->hi = rt_v3_max(acc->hi, b.hi);
}

static inline rt_aabb bin_box_aabb(bin_box b) { return b; }

static inline rt_real bin_box_half_area(bin_box b) { return rt_aabb_half_area(b); }

typedef rt_vec3 centre;

static inline centre box_centre(bin_box b)
{
    rt_vec3 sum = rt_v3_add(b.lo, b.hi);
    return rt_v3(rt_half(sum.x), rt_half(sum.y), rt_half(sum.z));
}

typedef struct {
    rt_real lo[3], scale[3];
    bool active[3];
} binning;

static inline binning binning_make(rt_aabb centres)
{
    binning g;
    for (int axis = 0; axis < 3; axis++) {
        g.lo[axis] = rt_v3_get(centres.lo, axis);
        rt_real hi = rt_v3_get(centres.hi, axis);
        g.active[axis] = hi > g.lo[axis];
        g.scale[axis] = g.active[axis] ? rt_div(rt_from_int(BIN_COUNT), rt_sub(hi, g.lo[axis])) : RT_ZERO;
    }
    return g;
}

/* floor(rt_mul(c - lo, scale)) clamped to the bins, from the exact product: a product
 * not above 0 is bin 0, and for a positive one p the floor of rt_mul's rounding
 * (p + 2^31) / 2^32 is (p + 2^31) / 2^64 (a saturated rt_mul lands in the last bin
 * either way): one product and its top word, without rt_mul's rounding and rails. */
static inline int centre_bin(const binning *g, centre c, int axis)
{
    rt_real x = rt_sub(rt_v3_get(c, axis), g->lo[axis]), s = g->scale[axis];
    if (x == RT_ZERO || s == RT_ZERO || (x < RT_ZERO) != (s < RT_ZERO)) return 0;
    uint64_t lo, hi = rt_fx_umul128(rt_fx_mag(x), rt_fx_mag(s), &lo);
    hi += lo + (UINT64_C(1) << 31) < lo;
    return hi < BIN_COUNT - 1 ? (int)hi : BIN_COUNT - 1;
}

static inline void box_bins(const binning *g, bin_box b, int out[3])
{
    centre c = box_centre(b);
    for (int axis = 0; axis < 3; axis++) out[axis] = centre_bin(g, c, axis);
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
