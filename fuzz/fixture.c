/* Scenes and rays for the intersector targets; see fixture.h. */
#include "fixture.h"

#include <math.h>

#include "check.h"
#include "oracle.h"

static uint8_t arena_memory[8u << 20];

rt_status fz_build(const rt_scene_desc *desc, rt_scene *out, rt_build_error *err)
{
    rt_arena arena;
    rt_arena_init(&arena, arena_memory, sizeof arena_memory);
    return rt_scene_build(desc, &arena, NULL, out, err);
}

rt_camera_desc fz_camera(void)
{
    rt_camera_desc c = {0};
    c.world = rt_affine_identity();
    c.fov_degrees = RT_C(60.0);
    c.perspective = true;
    c.width = c.height = 4;
    return c;
}

void fz_scene_one(rt_scene *out, rt_shape_kind kind, const rt_mesh_desc *mesh, rt_affine world)
{
    static const rt_material material = {.diffuse = {.texture = RT_NO_TEXTURE},
                                         .specular = {.texture = RT_NO_TEXTURE},
                                         .emissive = {.texture = RT_NO_TEXTURE},
                                         .transmittance = {.texture = RT_NO_TEXTURE},
                                         .index_of_refraction = RT_C(1.0)};
    rt_object_desc object = {.kind = kind, .world = world};
    rt_scene_desc desc = {0};
    desc.materials = &material;
    desc.material_count = 1;
    desc.meshes = mesh;
    desc.mesh_count = mesh ? 1 : 0;
    desc.objects = &object;
    desc.object_count = 1;
    desc.camera = fz_camera();
    rt_build_error err;
    rt_status st = fz_build(&desc, out, &err);
    FZ_CHECK(st == RT_OK, "rt_scene_build refused a valid one-object scene: %s", err.what);
}

void fz_object_ray(const rt_scene *scene, const fz_trs *trs, rt_ray ray, fz_v3l *o, fz_v3l *d)
{
    const rt_affine *to_object = &scene->objects[0].to_object;
    fz_v3l want_o = fz_trs_point_to_object(trs, ray.origin), want_d = fz_trs_vector_to_object(trs, ray.direction);
    fz_v3l got_o = fz_l(rt_affine_point(to_object, ray.origin)),
           got_d = fz_l(rt_affine_vector(to_object, ray.direction));
    /* Rounding of the forward matrix grows by the inverse's norm squared (1/smallest scale);
     * Q32.32's inverse carries a few absolute lsb per entry. Its angles add their own: each
     * is d pi/180 with the constant rounded to half an lsb, up to (|d| + 1) 2^-33 rad off,
     * which turns the object-space ray by up to k times their sum (finding 19). */
    fz_v3l s = fz_l(trs->scale), deg = fz_l(trs->rotation_degrees);
    long double k = fmaxl(1, 1 / fminl(fminl(s.x, s.y), s.z));
    long double reach = fz_l_len(fz_l(ray.origin)) + fz_l_len(fz_l(trs->translation));
    long double unit = FZ_ABS > 0 ? 256 * FZ_ABS * k * k : 1e3L * FZ_EPS * k;
    long double turn = k * (fabsl(deg.x) + fabsl(deg.y) + fabsl(deg.z) + 3) * FZ_ABS / 2;
    long double off_o = fz_l_len(fz_l_sub(got_o, want_o)), off_d = fz_l_len(fz_l_sub(got_d, want_d));
    long double len_d = fz_l_len(fz_l(ray.direction));
    FZ_CHECK(off_o <= unit * (reach + 1) + turn * reach && off_d <= unit * (len_d + 1) + turn * len_d,
             "to_object is %.3Lg (point) and %.3Lg (direction) off the description's inverse (k %.3Lg, reach %.3Lg)",
             off_o, off_d, k, reach);
    *o = FZ_ABS > 0 ? got_o : want_o;
    *d = FZ_ABS > 0 ? got_d : want_d;
}

rt_affine fz_transform_trs(fz_bytes *in, fz_trs *described)
{
    rt_vec3 zero = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    *described = (fz_trs){zero, zero, rt_v3(RT_ONE, RT_ONE, RT_ONE)};
    if (fz_u8(in) % 4 == 0) return rt_affine_identity();
    described->translation = fz_vec_range(in, -8, 8);
    described->rotation_degrees = fz_vec_range(in, -180, 180);
    double sx = fz_pow2(in, -4, 4), sy = fz_pow2(in, -4, 4), sz = fz_pow2(in, -4, 4);
    described->scale = rt_v3(rt_from_double(sx), rt_from_double(sy), rt_from_double(sz));
    return rt_affine_trs(described->translation, described->rotation_degrees, described->scale);
}

rt_affine fz_transform(fz_bytes *in)
{
    fz_trs unused;
    return fz_transform_trs(in, &unused);
}

void fz_ray_interval(fz_bytes *in, rt_ray *ray)
{
    uint8_t k = fz_u8(in);
    ray->t_min = k % 8 == 0 ? RT_ZERO : RT_HIT_EPSILON;
    ray->t_max = k / 8 % 8 == 0 ? rt_from_double(fz_pow2(in, -2, 7)) : RT_REAL_MAX;
}

rt_ray fz_ray_through(fz_bytes *in, rt_vec3 target)
{
    rt_vec3 away = fz_unit_vector(in);
    rt_ray ray;
    ray.origin = rt_v3_madd(target, away, rt_from_double(fz_pow2(in, -3, 7)));
    ray.direction = rt_v3_normalize(rt_v3_sub(target, ray.origin));
    if (rt_v3_is_zero(ray.direction)) ray.direction = rt_v3_neg(away);
    fz_ray_interval(in, &ray);
    return ray;
}

rt_ray fz_ray_axis(fz_bytes *in, rt_vec3 target)
{
    uint8_t k = fz_u8(in);
    rt_real sign = k & 1 ? RT_ONE : rt_neg(RT_ONE);
    rt_ray ray;
    ray.direction =
        rt_v3(k / 2 % 3 == 0 ? sign : RT_ZERO, k / 2 % 3 == 1 ? sign : RT_ZERO, k / 2 % 3 == 2 ? sign : RT_ZERO);
    ray.origin = rt_v3_madd(target, ray.direction, rt_neg(rt_from_int(1 << fz_below(in, 8))));
    fz_ray_interval(in, &ray);
    return ray;
}

rt_ray fz_ray_free(fz_bytes *in, double r)
{
    rt_ray ray;
    ray.origin = fz_vec_range(in, -r, r);
    ray.direction = fz_unit_vector(in);
    fz_ray_interval(in, &ray);
    return ray;
}

bool fz_grazing(const rt_scene *scene, uint32_t prim, const rt_ray *ray)
{
    if (prim >= scene->triangle_count) return false;
    const rt_triangle *tri = &scene->triangles[prim];
    const rt_vec3 *p = scene->positions;
    fz_plane_crossing x;
    return !fz_triangle_crossing(p[tri->v[0]], p[tri->v[1]], p[tri->v[2]], ray->origin, ray->direction, &x);
}
