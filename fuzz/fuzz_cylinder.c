/* libFuzzer target: the capped cylinder intersector (core/intersect.c), reached
 * through a one-cylinder scene under a fuzzed transform, held to the crossings of
 * its side and caps computed independently. */
#include <math.h>

#include "check.h"
#include "fixture.h"
#include "oracle.h"
#include "surface.h"

/* Raw scalars straight into the intersector: no crash, no UB, no t outside the
 * interval, and no hit on a line that passes clear of the cylinder's bounding sphere
 * by more than rounding allows, however large the numbers (long double does not
 * overflow where the kernel does); and a line the BVH leaf's early miss clears misses. */
static void raw_ray(fz_bytes *in)
{
    rt_vec3 o = fz_vec_raw(in), d = fz_vec_raw(in);
    rt_real t_min = fz_raw(in), t_max = fz_raw(in);
    fz_check_cleared_line(o, d, false);
    rt_prim_hit h;
    if (!rt_intersect_cylinder(o, d, t_min, t_max, &h)) return;
    fz_check_t(h.t, t_min, t_max);
    if (!fz_finite3(o) || !fz_finite3(d) || rt_v3_is_zero(d)) return;
    long double o2 = fz_l_dot(fz_l(o), fz_l(o)), slack = fz_quadric_slack(o2, fz_l_dot(fz_l(d), fz_l(d)));
    if (slack < 0) return;
    long double dist = fz_line_distance(fz_l(o), fz_l(d), (fz_v3l){0, 0, 0});
    FZ_CHECK(!(dist * dist > (0.5L + slack) * (1 + FZ_MARGIN)), "hit at t = %.17g on a line %.3Lg from the centre",
             rt_to_double(h.t), dist);
}

/* Crossings of the side x^2 + z^2 = 0.25 with |y| <= 0.5. */
static int side_crossings(fz_v3l o, fz_v3l d, long double s, fz_crossing *c)
{
    fz_v3l o2 = {o.x, 0, o.z}, d2 = {d.x, 0, d.z};
    long double a = fz_l_dot(d2, d2);
    if (a <= 0) return 0;
    long double dist = fz_line_distance(o2, d2, (fz_v3l){0, 0, 0});
    if (dist > 0.5L + FZ_MARGIN * s) return 0;
    bool robust = dist < 0.5L - FZ_MARGIN * s;
    long double tol = FZ_TOL_T * s / sqrtl(a) + (robust ? 0 : sqrtl(2 * FZ_MARGIN * s / a));
    long double t[2];
    if (!fz_quadratic(a, 2 * fz_l_dot(o2, d2), fz_l_dot(o2, o2) - 0.25L, &t[0], &t[1]))
        t[0] = t[1] = -fz_l_dot(o2, d2) / a;
    int n = 0;
    for (int i = 0; i < 2; i++) {
        /* y moves by |d.y| * tol over the root's uncertainty. */
        long double y = fabsl(o.y + t[i] * d.y), slack = FZ_MARGIN * s + fabsl(d.y) * tol;
        if (y > 0.5L + slack) continue;
        c[n++] = (fz_crossing){t[i], tol, robust && y < 0.5L - slack};
    }
    return n;
}

/* Crossings of the caps y = +-0.5 with x^2 + z^2 <= 0.25. */
static int cap_crossings(fz_v3l o, fz_v3l d, long double s, fz_crossing *c)
{
    if (d.y == 0) return 0;
    long double tol = FZ_TOL_T * s / fabsl(d.y), dxz = sqrtl(d.x * d.x + d.z * d.z);
    int n = 0;
    for (int top = 0; top < 2; top++) {
        long double t = ((top ? 0.5L : -0.5L) - o.y) / d.y;
        long double x = o.x + t * d.x, z = o.z + t * d.z, r = sqrtl(x * x + z * z);
        long double slack = FZ_MARGIN * s + dxz * tol;
        if (r > 0.5L + slack) continue;
        c[n++] = (fz_crossing){t, tol, r < 0.5L - slack};
    }
    return n;
}

static void check_ray(const rt_scene *scene, const fz_trs *trs, rt_ray ray)
{
    rt_ray_setup rs = rt_intersect_prepare(ray);
    rt_scene_hit hit = {0};
    bool found = rt_scene_nearest(scene, &rs, true, &hit);
    /* The object-space ray from the scene's description (fz_object_ray). */
    fz_v3l o, d;
    fz_object_ray(scene, trs, ray, &o, &d);
    long double s = fz_l_len(o) + 0.75L;
    fz_crossing c[4];
    int n = side_crossings(o, d, s, c);
    n += cap_crossings(o, d, s, c + n);
    fz_check_crossings(c, n, found, hit.hit.t, ray.t_min, ray.t_max);
    if (!found) return;
    fz_check_t(hit.hit.t, ray.t_min, ray.t_max);
    fz_v3l q = fz_l_along(o, d, rt_to_double(hit.hit.t));
    long double r2 = q.x * q.x + q.z * q.z, tol = FZ_TOL * s * s;
    if (hit.hit.part == RT_PART_SURFACE) {
        FZ_CHECK(fabsl(r2 - 0.25L) <= tol && fabsl(q.y) <= 0.5L + tol, "side hit at r^2 = %.17Lg, y = %.17Lg", r2, q.y);
    } else {
        long double cap = hit.hit.part == RT_PART_CAP_TOP ? 0.5L : -0.5L;
        FZ_CHECK(fabsl(q.y - cap) <= tol && r2 <= 0.25L + tol, "cap hit at r^2 = %.17Lg, y = %.17Lg", r2, q.y);
    }
    rt_surface surf = rt_surface_at(scene, &ray, &hit, true);
    fz_check_unit(surf.normal, "cylinder normal");
    /* Outward: the cylinder is convex and contains its centre. */
    fz_v3l out = fz_l_sub(fz_l(surf.point), fz_l(trs->translation));
    FZ_CHECK(fz_l_dot(fz_l(surf.normal), out) > 0, "cylinder normal points inwards");
}

/* A point on the rims, the caps or the side, where grazing rays are hardest. */
static rt_vec3 boundary_point(fz_bytes *in)
{
    rt_real angle = rt_from_double(fz_range(in, 0, 6.283185307179586));
    rt_real x = rt_mul(RT_C(0.5), rt_cos(angle)), z = rt_mul(RT_C(0.5), rt_sin(angle));
    rt_real y = rt_from_double(fz_range(in, -0.5, 0.5));
    switch (fz_u8(in) % 3) {
    case 0: return rt_v3(x, fz_u8(in) % 2 ? RT_C(0.5) : RT_C(-0.5), z); /* rim */
    case 1: return rt_v3(rt_mul(x, y), RT_C(0.5), rt_mul(z, y));        /* top cap */
    default: return rt_v3(x, y, z);                                     /* side */
    }
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
    fz_scene_one(&scene, RT_SHAPE_CYLINDER, NULL, fz_transform_trs(&in, &trs));
    const rt_affine *world = &scene.objects[0].to_world;
    while (in.pos < in.size) {
        uint8_t kind = fz_u8(&in);
        rt_ray ray;
        if (kind % 4 == 0)
            ray = fz_ray_free(&in, 24);
        else if (kind % 4 == 3)
            ray = fz_ray_through(&in, rt_affine_point(world, boundary_point(&in)));
        else
            ray = fz_ray_through(&in, rt_affine_point(world, fz_vec_range(&in, -0.3, 0.3)));
        check_ray(&scene, &trs, ray);
    }
    return 0;
}
