/* Axis-aligned boxes: what the BVH bounds its primitives with. */
#ifndef RT_AABB_H
#define RT_AABB_H

#include "vec.h"

typedef struct {
    rt_vec3 lo, hi;
} rt_aabb;

/* The box that holds nothing: every union with it is the other box. */
static inline rt_aabb rt_aabb_empty(void)
{
    rt_aabb b = {{RT_REAL_MAX, RT_REAL_MAX, RT_REAL_MAX},
                 {rt_neg(RT_REAL_MAX), rt_neg(RT_REAL_MAX), rt_neg(RT_REAL_MAX)}};
    return b;
}

/* Half the surface area: all the SAH needs. */
static inline rt_real rt_aabb_half_area(rt_aabb b)
{
    if (b.lo.x > b.hi.x) return RT_ZERO;
    rt_vec3 e = rt_v3_sub(b.hi, b.lo);
    return rt_add(rt_add(rt_mul(e.x, e.y), rt_mul(e.y, e.z)), rt_mul(e.z, e.x));
}

#endif
