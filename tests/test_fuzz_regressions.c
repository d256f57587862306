/* Inputs the fuzzers (fuzz/) found that once broke the kernel or a loader, each
 * reduced to the smallest case that shows the bug. See docs/robustness.md. */
#include <criterion/criterion.h>

#include "intersect.h"

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
