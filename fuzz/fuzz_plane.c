/* libFuzzer target: the Plane (the unit square in XY as two triangles sharing a
 * diagonal, rt_builtin_mesh_square) under a fuzzed transform. Besides the intersector
 * invariants, rays through the shared diagonal check watertightness. */
#include <math.h>

#include "builtin_mesh.h"
#include "check.h"
#include "fixture.h"
#include "oracle.h"
#include "surface.h"

static void check_ray(const rt_scene *scene, const fz_trs *trs, rt_ray ray)
{
    rt_ray_setup rs = rt_intersect_prepare(ray);
    rt_scene_hit hit = {0}, brute = {0};
    bool found = rt_scene_nearest(scene, &rs, true, &hit), brute_found = rt_scene_nearest(scene, &rs, false, &brute);
    /* Both sides' hits must be real crossings before they can be compared. */
    bool grazing = (found && fz_grazing(scene, hit.prim, &ray)) || (brute_found && fz_grazing(scene, brute.prim, &ray));
    if (grazing) return;
    FZ_CHECK(found == brute_found, "BVH and brute force disagree on hit or miss");
    if (found) {
        fz_check_t(hit.hit.t, ray.t_min, ray.t_max);
        FZ_CHECK(hit.prim == brute.prim && hit.hit.t == brute.hit.t, "BVH and brute force disagree on the hit");
        FZ_CHECK(hit.hit.b1 >= RT_ZERO && hit.hit.b2 >= RT_ZERO &&
                     rt_to_double(hit.hit.b1) + rt_to_double(hit.hit.b2) <= 1 + 4 * FZ_EPS,
                 "barycentrics %.17g, %.17g outside the triangle", rt_to_double(hit.hit.b1), rt_to_double(hit.hit.b2));
        rt_surface s = rt_surface_at(scene, &ray, &hit, true);
        fz_check_unit(s.normal, "plane normal");
        fz_check_unit(s.geometric_normal, "plane geometric normal");
        FZ_CHECK(rt_v3_dot(s.normal, s.geometric_normal) > RT_ZERO, "shading and geometric normals on opposite sides");
    }
    /* The oracle: where the object-space line meets z = 0, with the first triangle's
     * conditioning (the two share their plane up to rounding). */
    const rt_vec3 *p = scene->positions;
    fz_plane_crossing x;
    if (!fz_triangle_crossing(p[0], p[1], p[2], ray.origin, ray.direction, &x)) return;
    /* The object-space ray from the scene's description (fz_object_ray). */
    fz_v3l o, d;
    fz_object_ray(scene, trs, ray, &o, &d);
    long double t = -o.z / d.z, margin = 2 * x.slack + FZ_MARGIN * (1 + fz_l_len(o));
    fz_v3l q = fz_l_along(o, d, t);
    long double edge = fmaxl(fabsl(q.x), fabsl(q.y));
    fz_crossing c = {t, x.tol_t + FZ_TOL_T * (fz_l_len(o) + 1) / fz_l_len(d), edge < 0.5L - margin};
    fz_check_crossings(&c, edge <= 0.5L + margin, found, hit.hit.t, ray.t_min, ray.t_max);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes in = fz_bytes_of(data, size);
    rt_mesh_desc square = rt_builtin_mesh_square();
    rt_scene scene;
    fz_trs trs;
    fz_scene_one(&scene, RT_SHAPE_MESH, &square, fz_transform_trs(&in, &trs));
    const rt_affine *world = &scene.objects[0].to_world;
    while (in.pos < in.size) {
        uint8_t kind = fz_u8(&in) % 4;
        rt_ray ray;
        if (kind == 0) {
            ray = fz_ray_free(&in, 24);
        } else {
            /* Kind 1: anywhere on the square (and a little beyond); else on the shared
             * diagonal from (-0.5, -0.5) to (0.5, 0.5), exact in object space. */
            rt_real u = rt_from_double(fz_range(&in, -0.55, 0.55));
            rt_vec3 q =
                kind == 1 ? rt_v3(u, rt_from_double(fz_range(&in, -0.55, 0.55)), RT_ZERO) : rt_v3(u, u, RT_ZERO);
            ray = fz_u8(&in) % 2 ? fz_ray_through(&in, rt_affine_point(world, q))
                                 : fz_ray_axis(&in, rt_affine_point(world, q));
        }
        check_ray(&scene, &trs, ray);
    }
    return 0;
}
