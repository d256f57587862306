/* libFuzzer target: the Cube (rt_builtin_mesh_cube: 12 triangles, 24 vertices) under a
 * fuzzed transform, against slab tests of the box grown and shrunk by a margin.
 * A closed mesh: rays from outside through its edges and corners towards the
 * inside must hit it (watertightness). */
#include <math.h>

#include "builtin_mesh.h"
#include "check.h"
#include "fixture.h"
#include "oracle.h"
#include "surface.h"

static void check_hit(const rt_scene *scene, const fz_trs *trs, const rt_ray *ray, const rt_scene_hit *hit,
                      long double lo, long double hi)
{
    fz_check_t(hit->hit.t, ray->t_min, ray->t_max);
    FZ_CHECK(hit->hit.b1 >= RT_ZERO && hit->hit.b2 >= RT_ZERO &&
                 rt_to_double(hit->hit.b1) + rt_to_double(hit->hit.b2) <= 1 + 4 * FZ_EPS,
             "barycentrics %.17g, %.17g outside the triangle", rt_to_double(hit->hit.b1), rt_to_double(hit->hit.b2));
    const rt_triangle *tri = &scene->triangles[hit->prim];
    const rt_vec3 *p = scene->positions;
    fz_plane_crossing x;
    long double t = rt_to_double(hit->hit.t);
    if (fz_triangle_crossing(p[tri->v[0]], p[tri->v[1]], p[tri->v[2]], ray->origin, ray->direction, &x))
        FZ_CHECK(t >= lo - x.tol_t && t <= hi + x.tol_t, "hit at t = %.17Lg, the box surface lies in [%.17Lg, %.17Lg]",
                 t, lo, hi);
    rt_surface s = rt_surface_at(scene, ray, hit, true);
    fz_check_unit(s.normal, "cube normal");
    fz_check_unit(s.geometric_normal, "cube geometric normal");
    /* The Cube's normals face out of the box; the flat faces make both normals agree. */
    fz_v3l out = fz_l_sub(fz_l(s.point), fz_l(trs->translation));
    FZ_CHECK(fz_l_dot(fz_l(s.normal), out) > 0, "cube normal points inwards");
    FZ_CHECK(rt_v3_dot(s.normal, s.geometric_normal) > RT_ZERO, "shading and geometric normals on opposite sides");
}

static void check_ray(const rt_scene *scene, const fz_trs *trs, rt_ray ray)
{
    rt_ray_setup rs = rt_intersect_prepare(ray);
    rt_scene_hit hit = {0}, brute = {0};
    bool found = rt_scene_nearest(scene, &rs, true, &hit), brute_found = rt_scene_nearest(scene, &rs, false, &brute);
    /* Both sides' hits must be real crossings before they can be compared. */
    bool grazing = (found && fz_grazing(scene, hit.prim, &ray)) || (brute_found && fz_grazing(scene, brute.prim, &ray));
    if (grazing) return;
    FZ_CHECK(found == brute_found, "BVH and brute force disagree on hit or miss");
    FZ_CHECK(!found || (hit.prim == brute.prim && hit.hit.t == brute.hit.t), "BVH and brute force disagree on the hit");
    /* Slab tests in object space against the box grown and shrunk by the margin: the
     * surface's first crossing lies between the two boxes' (both are convex). */
    /* The object-space ray from the scene's description (fz_object_ray). */
    fz_v3l o, d;
    fz_object_ray(scene, trs, ray, &o, &d);
    long double m = FZ_MARGIN * (1 + fz_l_len(o)), tol = FZ_TOL_T * (1 + fz_l_len(o)) / fz_l_len(d);
    long double lo = rt_to_double(ray.t_min), hi = rt_to_double(ray.t_max);
    long double grow_in, grow_out, shrink_in, shrink_out;
    if (!fz_slab(o, d, 0.5L + m, &grow_in, &grow_out) || grow_out < lo - tol || grow_in > hi + tol) {
        FZ_CHECK(!found, "hit at t = %.17g, but the line passes clear of the box", rt_to_double(hit.hit.t));
        return;
    }
    /* The entry crossing lies in [grow_in, shrink_in], the exit in [shrink_out, grow_out];
     * a line that misses the shrunk box may graze the surface anywhere in between. */
    bool deep = fz_slab(o, d, 0.5L - m, &shrink_in, &shrink_out);
    bool entry = deep && grow_in > lo + tol && shrink_in < hi - tol;
    bool exit = deep && shrink_in < lo - tol && shrink_out > lo + tol && grow_out < hi - tol;
    if (entry || exit) FZ_CHECK(found, "missed the box: it lies in [%.17Lg, %.17Lg] along the ray", grow_in, grow_out);
    if (!found) return;
    if (entry)
        check_hit(scene, trs, &ray, &hit, grow_in, shrink_in);
    else if (exit)
        check_hit(scene, trs, &ray, &hit, shrink_out, grow_out);
    else
        check_hit(scene, trs, &ray, &hit, grow_in, grow_out);
}

/* A point on the cube's boundary in object space, exact: on one of its 12 edges, 8
 * corners or 6 face diagonals (the edge each face's two triangles share). */
static rt_vec3 edge_point(fz_bytes *in)
{
    rt_real c[3];
    for (int k = 0; k < 3; k++) c[k] = fz_u8(in) % 2 ? RT_C(0.5) : RT_C(-0.5);
    rt_real u = rt_from_double(fz_range(in, -0.5, 0.5));
    uint8_t kind = fz_u8(in) % 3, axis = fz_u8(in) % 3;
    if (kind == 1) c[axis] = u;                                                        /* along an edge */
    if (kind == 2) c[(axis + 1) % 3] = c[(axis + 2) % 3] == RT_C(0.5) ? u : rt_neg(u); /* face diagonal */
    return rt_v3(c[0], c[1], c[2]);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes in = fz_bytes_of(data, size);
    rt_mesh_desc cube = rt_builtin_mesh_cube();
    rt_scene scene;
    fz_trs trs;
    fz_scene_one(&scene, RT_SHAPE_MESH, &cube, fz_transform_trs(&in, &trs));
    const rt_affine *world = &scene.objects[0].to_world;
    while (in.pos < in.size) {
        uint8_t kind = fz_u8(&in) % 4;
        rt_ray ray;
        if (kind == 0) {
            ray = fz_ray_free(&in, 24);
        } else if (kind == 1) {
            ray = fz_ray_through(&in, rt_affine_point(world, fz_vec_range(&in, -0.55, 0.55)));
        } else if (kind == 2) {
            ray = fz_ray_axis(&in, rt_affine_point(world, edge_point(&in)));
        } else {
            /* From outside, through a boundary point p, on towards an inside point q. */
            rt_vec3 p = edge_point(&in), q = fz_vec_range(&in, -0.4, 0.4);
            rt_vec3 o = rt_v3_madd(p, rt_v3_sub(p, q), rt_from_double(fz_pow2(&in, -3, 5)));
            fz_ray_interval(&in, &ray);
            ray.origin = rt_affine_point(world, o);
            ray.direction = rt_v3_normalize(rt_v3_sub(rt_affine_point(world, q), ray.origin));
        }
        check_ray(&scene, &trs, ray);
    }
    return 0;
}
