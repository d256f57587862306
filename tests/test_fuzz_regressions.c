/* Inputs the fuzzers (fuzz/) found that once broke the kernel or a loader, each
 * reduced to the smallest case that shows the bug. See docs/robustness.md. */
#include <criterion/criterion.h>

#include "intersect.h"

/* The inputs below are double values far beyond the Q32.32 range; the fixed build's own
 * cases are in test_precision.c. */
#ifndef RT_REAL_FIXED

/* fuzz_bvh, then fuzz_sphere: with huge coordinates b*b and 4ac both overflowed, the
 * discriminant became NaN, rt_sqrt turned it into 0, and the sphere reported the
 * point of closest approach of a line that passes 1e200 away as a hit. */
Test(fuzz_regressions, sphere_overflowing_discriminant_misses)
{
    rt_prim_hit h;
    cr_assert_not(rt_intersect_sphere(rt_v3(1e200, 1e200, 0), rt_v3(-1, 0, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h));
}

/* fuzz_cylinder: the same NaN through the side's quadratic. */
Test(fuzz_regressions, cylinder_overflowing_discriminant_misses)
{
    rt_prim_hit h;
    cr_assert_not(rt_intersect_cylinder(rt_v3(1e200, 0, 1e200), rt_v3(-1, 0, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h));
}

/* fuzz_bvh with raw coordinates: seen from 1e8 away, c = o.o - r^2 cancelled and a line
 * passing 0.5 beyond a radius-0.5 sphere was reported as a hit. The discriminant now
 * comes from the point of closest approach. */
Test(fuzz_regressions, far_origin_does_not_hit_a_sphere_it_passes)
{
    rt_prim_hit h;
    for (int k = 1; k <= 64; k++) {
        double miss = 0.5 + k * 1e-3; /* the line passes this far from the centre */
        cr_assert_not(rt_intersect_sphere(rt_v3(1e8, miss, 0), rt_v3(-1, 0, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h),
                      "phantom hit for a line %.4f from the centre", miss);
        cr_assert_not(rt_intersect_cylinder(rt_v3(1e8, 0, miss), rt_v3(-1, 0, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h),
                      "phantom cylinder hit for a line %.4f from the axis", miss);
    }
    cr_assert(rt_intersect_sphere(rt_v3(1e8, 0.49, 0), rt_v3(-1, 0, 0), RT_HIT_EPSILON, RT_REAL_MAX, &h));
}

/* fuzz_plane (corpus file grazing-phantom): a ray lying in a triangle's plane sees it
 * edge-on; rounding left the edge functions and det as noise and t arbitrary, for a line
 * that passes outside the triangle. The triangle below is one of 2771 such phantoms in
 * 3 million random in-plane rays (parallel to edge ab, on the side away from c) that the
 * old test reported; it now reports none of them. */
Test(fuzz_regressions, ray_in_a_triangles_plane_misses)
{
    rt_vec3 a = rt_v3(-5.034924836155783, 0.66251386848517235, 5.4441398806626378);
    rt_vec3 b = rt_v3(-1.9735040489108275, 1.8308188071747704, 6.8615438228205718);
    rt_vec3 c = rt_v3(-5.4306868742194458, -8.0044660475592799, -7.4541306332037527);
    rt_vec3 ab = rt_v3_sub(b, a), ac = rt_v3_sub(c, a);
    rt_ray r = {rt_v3_add(rt_v3_add(a, rt_v3_scale(ac, -0.3)), rt_v3_scale(ab, -5)), rt_v3_normalize(ab),
                RT_HIT_EPSILON, RT_REAL_MAX};
    rt_ray_setup rs = rt_intersect_prepare(r);
    rt_prim_hit h;
    cr_assert_not(rt_intersect_triangle(&rs, a, b, c, &h), "phantom hit at t %g", h.t);
}

#endif
