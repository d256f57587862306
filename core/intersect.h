/* Ray-primitive intersection: the sphere and cylinder in object space, triangles in
 * world space. Each test reports the nearest hit with t_min < t < t_max, or false. */
#ifndef RT_INTERSECT_H
#define RT_INTERSECT_H

#include "ray.h"
#include "scene.h"

/* The per-ray constants of the triangle and box tests. */
rt_ray_setup rt_intersect_prepare(rt_ray ray);
/* The same for a scene without triangles: the triangle test's shear (sx, sy, sz) is left
 * 0, sparing two of its five divisions (see rt_scene_prepare). */
rt_ray_setup rt_intersect_prepare_no_triangles(rt_ray ray);

/* Which surface of a primitive was hit. */
typedef enum { RT_PART_SURFACE, RT_PART_CAP_BOTTOM, RT_PART_CAP_TOP } rt_part;

typedef struct {
    rt_real t;
    rt_real b1, b2; /* triangle: barycentric weights of v[1] and v[2] */
    rt_part part;
} rt_prim_hit;

/* Unit sphere of radius 0.5 at the origin; origin/direction in object space
 * (direction not normalised, so t is the caller's world-space parameter). */
bool rt_intersect_sphere(rt_vec3 origin, rt_vec3 direction, rt_real t_min, rt_real t_max, rt_prim_hit *hit);
/* Capped cylinder: axis Y, radius 0.5, y in [-0.5, 0.5]; object space as above. */
bool rt_intersect_cylinder(rt_vec3 origin, rt_vec3 direction, rt_real t_min, rt_real t_max, rt_prim_hit *hit);
/* True when the line o + s d passes so far outside the ball |p|^2 <= r2 that neither
 * test above can hit a shape inside it (r2 = 0.25 for the sphere, 0.5 for the
 * cylinder): an early miss before their square root and divisions. False when unsure.
 * The line's squared distance from the origin is |o x d|^2 / |d|^2, compared with
 * r2 (1 + 1/16) without the division. In Q32.32, with |o_i| < 256 and
 * 2^-16 <= |d|^2 <= 256, |o x d|^2 comes within about 2^-21 |d| of exact and |d|^2
 * within 2^-31, so a true answer means a squared distance above r2 + 2^-7, while the
 * tests, solving with d normalised, find a hit only within about 2^-20 of the shape
 * (tests/test_precision.c tries lines on both sides of the margin; double errs far
 * less). Outside those ranges, or on NaN, it answers false and the full test runs. */
static inline bool rt_line_clears_ball(rt_vec3 o, rt_vec3 d, rt_real r2)
{
    const rt_real o_limit = RT_C(256.0);
    if (!(rt_abs(o.x) < o_limit && rt_abs(o.y) < o_limit && rt_abs(o.z) < o_limit)) return false;
    rt_real dd = rt_v3_dot(d, d);
    if (!(dd >= RT_C(0x1p-16) && dd <= RT_C(256.0))) return false;
    rt_vec3 c = rt_v3_cross(o, d);
    return rt_v3_dot(c, c) > rt_mul(rt_mul(r2, RT_C(1.0625)), dd);
}

/* Slab test; returns the entry distance in *t_enter. */
bool rt_intersect_aabb(const rt_ray_setup *rs, const rt_aabb *box, rt_real t_max, rt_real *t_enter);

#include "intersect_triangle.h"

#endif
