/* Rays and the per-ray constants the intersectors share. */
#ifndef RT_RAY_H
#define RT_RAY_H

#include "vec.h"

/* Hits closer than this along a unit-length ray are ignored, for every kind of ray:
 * the sample solution's effective epsilon (format.md §9.1). */
#define RT_HIT_EPSILON RT_C(1e-3)

typedef struct {
    rt_vec3 origin;
    rt_vec3 direction; /* unit length */
    rt_real t_min, t_max;
} rt_ray;

/* Per-ray values for the watertight triangle test and the slab test. */
typedef struct {
    rt_ray ray;
    int kx, ky, kz;        /* axes permuted so that |direction[kz]| is largest */
    int order;             /* which of the six (kx, ky, kz) it is: 2 kz, plus 1 when d[kz] < 0 swaps kx, ky */
    rt_real sx, sy, sz;    /* shear constants */
    rt_vec3 inv_direction; /* 1/direction; RT_REAL_MAX-signed for zero components */
} rt_ray_setup;

/* A ray from origin along unit direction, starting past the hit epsilon. */
static inline rt_ray rt_ray_make(rt_vec3 origin, rt_vec3 direction, rt_real t_max)
{
    rt_ray r = {origin, direction, RT_HIT_EPSILON, t_max};
    return r;
}

#endif
