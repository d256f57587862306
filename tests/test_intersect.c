/* Unit tests of the ray-primitive intersectors (core/intersect.c). */
#include "intersect.h"
#include <criterion/criterion.h>
#include <math.h>

static rt_ray_setup setup(rt_vec3 o, rt_vec3 d)
{
    rt_ray r = {o, rt_v3_normalize(d), RT_HIT_EPSILON, RT_REAL_MAX};
    return rt_intersect_prepare(r);
}

Test(intersect, sphere_front_and_inside)
{
    rt_prim_hit h;
    cr_assert(rt_intersect_sphere(rt_v3(0, 0, 5), rt_v3(0, 0, -1), RT_HIT_EPSILON, RT_REAL_MAX, &h));
    cr_assert_float_eq(h.t, 4.5, 1e-12);
    /* From the centre the ray leaves through the far wall. */
    cr_assert(rt_intersect_sphere(rt_v3(0, 0, 0), rt_v3(1, 0, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h));
    cr_assert_float_eq(h.t, 0.5, 1e-12);
    /* t_max excludes the hit. */
    cr_assert_not(rt_intersect_sphere(rt_v3(0, 0, 5), rt_v3(0, 0, -1), RT_HIT_EPSILON, 4.0, &h));
    /* A miss just outside the silhouette. */
    cr_assert_not(rt_intersect_sphere(rt_v3(0.5001, 0, 5), rt_v3(0, 0, -1), RT_HIT_EPSILON, RT_REAL_MAX, &h));
}

Test(intersect, sphere_ignores_hits_closer_than_epsilon)
{
    rt_prim_hit h;
    /* Starting on the surface, the ray must find the far side, not t = 0. */
    cr_assert(rt_intersect_sphere(rt_v3(0, 0, 0.5), rt_v3(0, 0, -1), RT_HIT_EPSILON, RT_REAL_MAX, &h));
    cr_assert_float_eq(h.t, 1.0, 1e-12);
}

Test(intersect, cylinder_body_and_caps)
{
    rt_prim_hit h;
    cr_assert(rt_intersect_cylinder(rt_v3(3, 0.2, 0), rt_v3(-1, 0, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h));
    cr_assert_float_eq(h.t, 2.5, 1e-12);
    cr_assert_eq(h.part, RT_PART_SURFACE);
    cr_assert(rt_intersect_cylinder(rt_v3(0.1, 4, 0.1), rt_v3(0, -1, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h));
    cr_assert_float_eq(h.t, 3.5, 1e-12);
    cr_assert_eq(h.part, RT_PART_CAP_TOP);
    cr_assert(rt_intersect_cylinder(rt_v3(0.1, -4, 0.1), rt_v3(0, 1, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h));
    cr_assert_eq(h.part, RT_PART_CAP_BOTTOM);
    /* Above the top, aimed sideways: misses the finite body. */
    cr_assert_not(rt_intersect_cylinder(rt_v3(3, 0.6, 0), rt_v3(-1, 0, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h));
    /* Enters through the cap, leaves through the body: the near hit is the cap. */
    cr_assert(rt_intersect_cylinder(rt_v3(0, 1.5, 0), rt_v3(0.5, -2, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h));
    cr_assert_eq(h.part, RT_PART_CAP_TOP);
    cr_assert_float_eq(h.t, 0.5, 1e-12);
}

Test(intersect, triangle_barycentrics)
{
    rt_vec3 a = rt_v3(0, 0, 0), b = rt_v3(1, 0, 0), c = rt_v3(0, 1, 0);
    rt_ray_setup rs = setup(rt_v3(0.25, 0.5, 2), rt_v3(0, 0, -1));
    rt_prim_hit h;
    cr_assert(rt_intersect_triangle(&rs, a, b, c, &h));
    cr_assert_float_eq(h.t, 2.0, 1e-12);
    cr_assert_float_eq(h.b1, 0.25, 1e-12);
    cr_assert_float_eq(h.b2, 0.5, 1e-12);
    /* Both windings hit (no back-face culling). */
    cr_assert(rt_intersect_triangle(&rs, a, c, b, &h));
    rt_ray_setup outside = setup(rt_v3(0.75, 0.5, 2), rt_v3(0, 0, -1));
    cr_assert_not(rt_intersect_triangle(&outside, a, b, c, &h));
}

Test(intersect, shared_edge_is_watertight)
{
    /* Two triangles sharing the diagonal of a square; rays exactly along the diagonal. */
    rt_vec3 p00 = rt_v3(0, 0, 0), p10 = rt_v3(1, 0, 0), p01 = rt_v3(0, 1, 0), p11 = rt_v3(1, 1, 0);
    for (int i = 1; i < 100; i++) {
        rt_real s = i / 100.0;
        rt_ray_setup rs = setup(rt_v3(s - 0.3, 1 - s + 0.2, 1), rt_v3(0.3, -0.2, -1));
        rt_prim_hit h;
        bool hit = rt_intersect_triangle(&rs, p00, p10, p01, &h) || rt_intersect_triangle(&rs, p10, p11, p01, &h);
        cr_assert(hit, "ray %d through the shared edge missed both triangles", i);
    }
}

Test(intersect, aabb_slabs)
{
    rt_aabb box = {{-1, -1, -1}, {1, 1, 1}};
    rt_real t;
    rt_ray_setup rs = setup(rt_v3(0, 0, 5), rt_v3(0, 0, -1));
    cr_assert(rt_intersect_aabb(&rs, &box, RT_REAL_MAX, &t));
    cr_assert_float_eq(t, 4.0, 1e-12);
    rt_ray_setup parallel_outside = setup(rt_v3(2, 0, 5), rt_v3(0, 0, -1));
    cr_assert_not(rt_intersect_aabb(&parallel_outside, &box, RT_REAL_MAX, &t));
    cr_assert_not(rt_intersect_aabb(&rs, &box, 3.0, &t));
}
