/* libFuzzer target: the watertight triangle intersector (core/intersect.c) on one
 * triangle, in a one-mesh scene, against the line-plane crossing in long double; and
 * the leaves' unsaturated test against the saturating one. */
#include <math.h>

#include "check.h"
#include "fixture.h"
#include "oracle.h"
#include "surface.h"

/* Raw scalars straight into the intersector: only "no crash, no UB, no bad t". */
static void raw_ray(fz_bytes *in)
{
    rt_vec3 a = fz_vec_raw(in), b = fz_vec_raw(in), c = fz_vec_raw(in);
    rt_ray ray = {fz_vec_raw(in), fz_vec_raw(in), fz_raw(in), fz_raw(in)};
    rt_ray_setup rs = rt_intersect_prepare(ray);
    rt_prim_hit h;
    if (rt_intersect_triangle(&rs, a, b, c, &h)) fz_check_t(h.t, ray.t_min, ray.t_max);
}

/* A coordinate within RT_TRIANGLE_RANGE's 4096, often at its ends. */
static rt_real range_coordinate(fz_bytes *in)
{
    uint8_t pick = fz_u8(in) % 4;
    return pick == 0 ? RT_C(4096.0) : pick == 1 ? RT_C(-4096.0) : rt_from_double(fz_range(in, -4096, 4096));
}

/* rt_triangle_unsaturated's claim: where it holds, the test without saturation (the
 * fixed build's BVH leaves) crosses exactly where the saturating one does. Vertices and
 * origin within the range, the direction anything (diagonals give the largest sheared
 * coordinates). */
static void unsaturated_agrees(fz_bytes *in)
{
    rt_vec3 p[4];
    rt_real extent = RT_ZERO;
    for (int k = 0; k < 4; k++) {
        p[k] = rt_v3(range_coordinate(in), range_coordinate(in), range_coordinate(in));
        if (k < 3) extent = rt_max(extent, rt_max(rt_max(rt_abs(p[k].x), rt_abs(p[k].y)), rt_abs(p[k].z)));
    }
    rt_vec3 d = fz_vec_raw(in);
    if (fz_u8(in) % 2) d = rt_v3(rt_abs(d.x) == d.x ? RT_ONE : -RT_ONE, rt_abs(d.y) == d.y ? RT_ONE : -RT_ONE, RT_ONE);
    rt_ray ray = {p[3], d, fz_raw(in), fz_raw(in)};
    rt_ray_setup rs = rt_intersect_prepare(ray);
    if (!rt_triangle_unsaturated(&rs, extent)) return;
    rt_triangle_crossing a = {0}, b = {0};
    bool hit_a = rt_triangle_cross(&rs, p[0], p[1], p[2], &a, rs.kx, rs.ky, rs.kz, true);
    bool hit_b = rt_triangle_cross(&rs, p[0], p[1], p[2], &b, rs.kx, rs.ky, rs.kz, false);
    FZ_CHECK(hit_a == hit_b && (!hit_a || (a.t == b.t && a.v == b.v && a.w == b.w && a.det == b.det)),
             "unsaturated triangle test differs: %d / %d, t %.17g / %.17g", hit_a, hit_b, rt_to_double(a.t),
             rt_to_double(b.t));
}

/* Three vertices of size ~2^-8 (2^-2 in the fixed build)..2^8 around a centre up to 64 away, sometimes on a
 * small integer lattice (exact edges, axis-aligned faces) or degenerate. */
static void vertices(fz_bytes *in, rt_vec3 v[3])
{
    uint8_t shape = fz_u8(in);
    rt_vec3 centre = shape & 1 ? fz_vec_range(in, -64, 64) : rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    rt_real size = rt_from_double(fz_pow2(in, FZ_SIZE_LOG2_MIN > -8 ? FZ_SIZE_LOG2_MIN : -8, 8));
    for (int k = 0; k < 3; k++) {
        rt_vec3 p = fz_vec_range(in, -1, 1);
        if (shape & 2)
            p = rt_v3(rt_from_int(fz_below(in, 5)), rt_from_int(fz_below(in, 5)), rt_from_int(fz_below(in, 5)));
        v[k] = rt_v3_add(centre, rt_v3_scale(p, size));
    }
    if (shape % 32 >= 28)
        v[2] = rt_v3_madd(v[0], rt_v3_sub(v[1], v[0]), rt_from_double(fz_range(in, -2, 2))); /* collinear */
    if (shape % 32 == 27) v[2] = v[1];
}

static void check_hit(const rt_scene *scene, const rt_ray *ray, const rt_scene_hit *hit)
{
    const rt_vec3 *p = scene->positions;
    rt_prim_hit h = hit->hit;
    fz_check_t(h.t, ray->t_min, ray->t_max);
    FZ_CHECK(h.b1 >= RT_ZERO && h.b2 >= RT_ZERO && rt_to_double(h.b1) + rt_to_double(h.b2) <= 1 + 4 * FZ_EPS,
             "barycentrics %.17g, %.17g outside the triangle", rt_to_double(h.b1), rt_to_double(h.b2));
    fz_v3l a = fz_l(p[0]), n = fz_l_cross(fz_l_sub(fz_l(p[1]), a), fz_l_sub(fz_l(p[2]), a));
    long double l2 = fmaxl(fz_l_dot(fz_l_sub(fz_l(p[1]), a), fz_l_sub(fz_l(p[1]), a)),
                           fz_l_dot(fz_l_sub(fz_l(p[2]), a), fz_l_sub(fz_l(p[2]), a)));
    if (!(fz_l_dot(n, n) > 1e-12L * l2 * l2)) return; /* degenerate: no normal to speak of */
    rt_surface s = rt_surface_at(scene, ray, hit, true);
    fz_check_unit(s.normal, "triangle normal");
    fz_check_unit(s.geometric_normal, "triangle geometric normal");
    /* Not flipped: on the side of cross(b - a, c - a). */
    FZ_CHECK(fz_l_dot(fz_l(s.geometric_normal), n) > 0, "geometric normal against the winding");
    FZ_CHECK(fz_l_dot(fz_l(s.normal), n) > 0, "shading normal against the winding");
}

static void check_ray(const rt_scene *scene, rt_ray ray)
{
    rt_ray_setup rs = rt_intersect_prepare(ray);
    rt_scene_hit hit = {0};
    bool found = rt_scene_nearest(scene, &rs, true, &hit);
    if (found) check_hit(scene, &ray, &hit);
    const rt_vec3 *p = scene->positions;
    fz_plane_crossing x;
    if (!fz_triangle_crossing(p[0], p[1], p[2], ray.origin, ray.direction, &x)) return;
    long double b0 = 1 - x.b1 - x.b2, lowest = fminl(b0, fminl(x.b1, x.b2));
    fz_crossing c = {x.t, x.tol_t, lowest > x.slack};
    fz_check_crossings(&c, lowest >= -x.slack, found, hit.hit.t, ray.t_min, ray.t_max);
    if (!found) return;
    long double db1 = fabsl(rt_to_double(hit.hit.b1) - x.b1), db2 = fabsl(rt_to_double(hit.hit.b2) - x.b2);
    FZ_CHECK(db1 <= x.slack && db2 <= x.slack, "barycentrics off by %.3Lg, %.3Lg (slack %.3Lg)", db1, db2, x.slack);
}

/* A world point with barycentric weights from the bytes; on an edge or a vertex
 * when `boundary`, else strictly inside. */
static rt_vec3 surface_point(fz_bytes *in, const rt_vec3 v[3], bool boundary)
{
    rt_real u = rt_from_double(fz_range(in, 0, 1)), w = rt_from_double(fz_range(in, 0, 1));
    if (rt_add(u, w) > RT_ONE) {
        u = rt_sub(RT_ONE, u);
        w = rt_sub(RT_ONE, w);
    }
    if (boundary) {
        uint8_t which = fz_u8(in) % 6;
        if (which == 0)
            u = RT_ZERO;
        else if (which == 1)
            w = RT_ZERO;
        else if (which == 2)
            w = rt_sub(RT_ONE, u);
        else
            return v[which - 3];
    }
    return rt_v3_add(v[0], rt_v3_add(rt_v3_scale(rt_v3_sub(v[1], v[0]), u), rt_v3_scale(rt_v3_sub(v[2], v[0]), w)));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_bytes in = fz_bytes_of(data, size);
    uint8_t mode = fz_u8(&in) % 8;
    if (mode == 0) {
        raw_ray(&in);
        return 0;
    }
    if (mode == 7) {
        unsaturated_agrees(&in);
        return 0;
    }
    rt_vec3 v[3];
    vertices(&in, v);
    static const uint32_t indices[3] = {0, 1, 2};
    rt_mesh_desc mesh = {v, NULL, NULL, 3, indices, 1};
    rt_scene scene;
    fz_scene_one(&scene, RT_SHAPE_MESH, &mesh, rt_affine_identity());
    rt_vec3 centre = rt_v3_scale(rt_v3_add(rt_v3_add(v[0], v[1]), v[2]), rt_div(RT_ONE, rt_from_int(3)));
    while (in.pos < in.size) {
        uint8_t kind = fz_u8(&in) % 4;
        rt_ray ray = kind == 0 ? fz_ray_free(&in, 4) : fz_ray_through(&in, surface_point(&in, v, kind == 3));
        if (kind == 0) ray.origin = rt_v3_add(ray.origin, centre);
        check_ray(&scene, ray);
    }
    return 0;
}
