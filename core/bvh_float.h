/* The double build's box tests for most rays on x86 (SSE2, its baseline): a node's eight
 * children are tested in single precision, four or eight per register, against bounds that make
 * the test conservative. Rays it cannot take (see float_slab_prepare) walk with the
 * general test of bvh_slab.h. Included by scene_query.c, the stream queries
 * (bvh_stream.c) and each kernel's walks (bvh_kernel_*.c). */
#ifndef RT_BVH_FLOAT_H
#define RT_BVH_FLOAT_H

#include "bvh_leaf.h"
#include "invariant.h"

#if defined(__SSE2__) && !defined(RT_REAL_FIXED)
#define FLOAT_WALK 1

/* The double build's float box test: origins rounded to the safe side, reciprocals
 * shrunk (near planes) or grown (far planes) by 2^-21, so a child the exact double test
 * enters is entered no later; the argument and its range: docs/box-tests.md, "The float
 * walk". Rays outside that range take the double test. */
typedef struct {
    float o_near[3], o_far[3], inv_near[3], inv_far[3];
    float t_min, t_max; /* rounded down and up */
} float_slab;

/* The float at or above (up) or at or below x, for |x| <= 2^100 or x = +-RT_REAL_MAX
 * (which go to +-infinity): x moved outwards by 2^-23 |x| + 2^-126, then rounded to
 * nearest, which moves it back by at most half a float step (2^-24 |x|, or 2^-150 below
 * 2^-126). Unlike rt_bound_above and rt_bound_below, no branch. */
static inline float float_outward(double x, bool up)
{
    double pad = rt_magnitude(x) * 0x1p-23 + 0x1p-126;
    return (float)(up ? x + pad : x - pad);
}

/* Axis k of float_slab_prepare; returns whether the float bounds can take it. Without a
 * branch: `&` in place of `&&`, and the pad's sign in place of a choice. */
__attribute__((always_inline)) static inline bool float_slab_axis(rt_real o, rt_real iv, rt_real extent, int k,
                                                                  float_slab *f)
{
    rt_real mag = rt_magnitude(iv), o_mag = rt_magnitude(o);
    /* (p - o') inv <= (p - o) inv needs o' >= o for inv > 0, o' <= o for inv < 0: the near
     * planes' origin moves outwards (float_outward) along inv's sign, the far planes'
     * against it. */
    rt_real pad = __builtin_copysign(o_mag * 0x1p-23 + 0x1p-126, iv);
    f->o_near[k] = (float)(o + pad);
    f->o_far[k] = (float)(o - pad);
    f->inv_near[k] = (float)(iv * (1.0 - 0x1p-21));
    f->inv_far[k] = (float)(iv * (1.0 + 0x1p-21));
    return (mag >= 0x1p-100) & (mag <= 0x1p100) & (o_mag <= 0x1p100) & ((extent + o_mag) * mag <= 0x1p120);
}

/* Fills *f for the ray and returns true, or false if the ray must take the double test. */
static inline bool float_slab_prepare(const rt_ray_setup *rs, rt_real extent, float_slab *f)
{
    rt_vec3 o = rs->ray.origin, iv = rs->inv_direction;
    rt_real t_min = rs->ray.t_min;
    bool usable = float_slab_axis(o.x, iv.x, extent, 0, f) & float_slab_axis(o.y, iv.y, extent, 1, f) &
                  float_slab_axis(o.z, iv.z, extent, 2, f);
    f->t_min = float_outward(t_min, false);
    f->t_max = float_outward(rs->ray.t_max, true);
    return usable & (t_min >= 0x1p-100) & (t_min <= 0x1p100);
}

/* The one-ray walks (bvh_walk.h): rt_scene_nearest (any: rt_scene_any) for a ray the float
 * bounds take, with f from float_slab_prepare; the avx2 kernel's (the avx512 kernel's
 * too) is the same code compiled for AVX2. */
bool rt_bvh_walk_sse2(const rt_scene *scene, const rt_ray_setup *rs, const float_slab *f, bool any, rt_scene_hit *out);
bool rt_bvh_walk_avx2(const rt_scene *scene, const rt_ray_setup *rs, const float_slab *f, bool any, rt_scene_hit *out);

/* The packet walks (bvh_packet.h): rt_scene_nearest (any: rt_scene_any) for each of the
 * n <= RT_PACKET rays rs[i], which share their direction's octant and axis permutation,
 * into out[i] and found[i] (false on entry), for the rays the float bounds can take
 * (float_slab_prepare); returns those as a bit set. */
unsigned rt_bvh_packet_sse2(const rt_scene *scene, const rt_ray_setup *const *rs, uint32_t n, bool any,
                            rt_scene_hit *out, bool *found);
unsigned rt_bvh_packet_avx2(const rt_scene *scene, const rt_ray_setup *const *rs, uint32_t n, bool any,
                            rt_scene_hit *out, bool *found);
unsigned rt_bvh_packet_avx512(const rt_scene *scene, const rt_ray_setup *const *rs, uint32_t n, bool any,
                              rt_scene_hit *out, bool *found);
#else
#define FLOAT_WALK 0
#endif

#endif
