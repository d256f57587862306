/* libFuzzer target: the sphere intersector (core/intersect.c), reached through a
 * one-sphere scene under a fuzzed transform, held to its analytic crossings. */
#include <math.h>

#include "check.h"
#include "fixture.h"
#include "oracle.h"
#include "surface.h"

/* Raw scalars straight into the intersector: no crash, no UB, no t outside the
 * interval, and no hit on a line that passes clear of the sphere's bounding sphere
 * by more than rounding allows, however large the numbers (long double does not
 * overflow where the kernel does); and a line the BVH leaf's early miss clears misses. */
static void raw_ray(fz_bytes *in)
{
    rt_vec3 o = fz_vec_raw(in), d = fz_vec_raw(in);
    rt_real t_min = fz_raw(in), t_max = fz_raw(in);
    fz_check_cleared_line(o, d, true);
    rt_prim_hit h;
    if (!rt_intersect_sphere(o, d, t_min, t_max, &h)) return;
    fz_check_t(h.t, t_min, t_max);
    if (!fz_finite3(o) || !fz_finite3(d) || rt_v3_is_zero(d)) return;
    long double o2 = fz_l_dot(fz_l(o), fz_l(o)), slack = fz_quadric_slack(o2, fz_l_dot(fz_l(d), fz_l(d)));
    if (slack < 0) return;
    long double dist = fz_line_distance(fz_l(o), fz_l(d), (fz_v3l){0, 0, 0});
    FZ_CHECK(!(dist * dist > (0.25L + slack) * (1 + FZ_MARGIN)), "hit at t = %.17g on a line %.3Lg from the centre",
             rt_to_double(h.t), dist);
}

/* The crossings of the object-space line o + t d with the sphere |p| = 0.5. */
static int crossings(fz_v3l o, fz_v3l d, fz_crossing c[2])
{
    long double s = fz_l_len(o) + 0.5L, dl = fz_l_len(d);
    long double dist = fz_line_distance(o, d, (fz_v3l){0, 0, 0});
    if (dist > 0.5L + FZ_MARGIN * s) return 0;
    bool robust = dist < 0.5L - FZ_MARGIN * s;
    /* Grazing lines: the crossings lie within the chord the margin allows. */
    long double tol = FZ_TOL_T * s / dl + (robust ? 0 : sqrtl(2 * FZ_MARGIN * s) / dl);
    long double t0, t1;
    if (!fz_quadratic(fz_l_dot(d, d), 2 * fz_l_dot(o, d), fz_l_dot(o, o) - 0.25L, &t0, &t1))
        t0 = t1 = -fz_l_dot(o, d) / fz_l_dot(d, d);
    c[0] = (fz_crossing){t0, tol, robust};
    c[1] = (fz_crossing){t1, tol, robust};
    return 2;
}

static void check_ray(const rt_scene *scene, const fz_trs *trs, rt_ray ray)
{
    rt_ray_setup rs = rt_intersect_prepare(ray);
    rt_scene_hit hit = {0};
    bool found = rt_scene_nearest(scene, &rs, true, &hit);
    /* The object-space ray from the scene's description (fz_object_ray). */
    fz_v3l o, d;
    fz_object_ray(scene, trs, ray, &o, &d);
    long double s = fz_l_len(o) + 0.5L;
    fz_crossing c[2];
    fz_check_crossings(c, crossings(o, d, c), found, hit.hit.t, ray.t_min, ray.t_max);
    if (!found) return;
    fz_check_t(hit.hit.t, ray.t_min, ray.t_max);
    fz_v3l q = fz_l_along(o, d, rt_to_double(hit.hit.t));
    long double off = fabsl(fz_l_dot(q, q) - 0.25L);
    FZ_CHECK(off <= FZ_TOL * s * s, "hit point is %.3Lg off the sphere (scale %.3Lg)", off, s);
    rt_surface surf = rt_surface_at(scene, &ray, &hit, true);
    fz_check_unit(surf.normal, "sphere normal");
    /* Outward: the normal leaves the centre's side of the tangent plane. */
    fz_v3l out = fz_l_sub(fz_l(surf.point), fz_l(trs->translation));
    FZ_CHECK(fz_l_dot(fz_l(surf.normal), out) > 0, "sphere normal points inwards");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes in = fz_bytes_of(data, size);
    uint8_t mode = fz_u8(&in);
    if (mode % 8 == 0) {
        raw_ray(&in);
        return 0;
    }
    rt_scene scene;
    fz_trs trs;
    fz_scene_one(&scene, RT_SHAPE_SPHERE, NULL, fz_transform_trs(&in, &trs));
    const rt_affine *world = &scene.objects[0].to_world;
    while (in.pos < in.size) {
        uint8_t kind = fz_u8(&in);
        rt_ray ray;
        if (kind % 4 == 0) {
            ray = fz_ray_free(&in, 24);
        } else {
            /* Inside the sphere (kind 1, 2) or on it (kind 3: grazing and tangent rays). */
            rt_vec3 p = kind % 4 == 3 ? rt_v3_scale(fz_unit_vector(&in), RT_C(0.5)) : fz_vec_range(&in, -0.28, 0.28);
            ray = fz_ray_through(&in, rt_affine_point(world, p));
        }
        check_ray(&scene, &trs, ray);
    }
    return 0;
}
