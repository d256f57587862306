/* Hit-point attributes and material lookups; see surface.h. */
#include "surface.h"

static rt_vec2 v2(rt_real u, rt_real v)
{
    rt_vec2 r = {u, v};
    return r;
}

static rt_surface triangle_surface(const rt_scene *scene, const rt_scene_hit *hit, rt_surface s)
{
    const rt_triangle *tri = &scene->triangles[hit->prim];
    rt_real b1 = hit->hit.b1, b2 = hit->hit.b2, b0 = rt_sub(rt_sub(RT_ONE, b1), b2);
    const rt_vec3 *p = scene->positions;
    rt_vec3 pa = p[tri->v[0]], pb = p[tri->v[1]], pc = p[tri->v[2]];
    /* Each edge is scaled by a power of two first: the normal's direction is the same (and
     * exactly so in double), where in Q32.32 a sliver's cross product could round to 0. */
    int ka, kb;
    rt_vec3 e1 = rt_v3_rescale(rt_v3_sub(pb, pa), &ka), e2 = rt_v3_rescale(rt_v3_sub(pc, pa), &kb);
    s.geometric_normal = rt_v3_normalize(rt_v3_cross(e1, e2));
    const rt_vec3 *n = scene->normals;
    rt_vec3 interpolated = rt_v3_add(rt_v3_add(rt_v3_scale(n[tri->v[0]], b0), rt_v3_scale(n[tri->v[1]], b1)),
                                     rt_v3_scale(n[tri->v[2]], b2));
    s.normal = rt_v3_is_zero(interpolated) ? s.geometric_normal : rt_v3_normalize(interpolated);
    /* Without uvs every vertex reads (0, 0), and so does any blend of them. */
    s.uv = v2(RT_ZERO, RT_ZERO);
    const rt_vec2 *uv = scene->uvs;
    if (uv) {
        rt_vec2 ua = uv[tri->v[0]], ub = uv[tri->v[1]], uc = uv[tri->v[2]];
        s.uv = v2(rt_add(rt_add(rt_mul(ua.u, b0), rt_mul(ub.u, b1)), rt_mul(uc.u, b2)),
                  rt_add(rt_add(rt_mul(ua.v, b0), rt_mul(ub.v, b1)), rt_mul(uc.v, b2)));
    }
    s.object = rt_scene_triangle_object(scene, hit->prim);
    return s;
}

bool rt_material_textured(const rt_material *m)
{
    return m->diffuse.texture != RT_NO_TEXTURE || m->specular.texture != RT_NO_TEXTURE ||
           m->emissive.texture != RT_NO_TEXTURE || m->transmittance.texture != RT_NO_TEXTURE;
}

/* A quadric's texture coordinates at object-space point q (format.md §5.5, §5.6). */
static rt_vec2 quadric_uv(const rt_object *obj, rt_part part, rt_vec3 q)
{
    rt_real two_pi = rt_mul(RT_C(2.0), RT_PI);
    if (obj->kind == RT_SHAPE_SPHERE) {
        rt_real y = rt_clamp(rt_mul(q.y, RT_C(2.0)), rt_neg(RT_ONE), RT_ONE);
        return v2(rt_add(RT_C(0.5), rt_div(rt_atan2(q.z, q.x), two_pi)), rt_sub(RT_C(0.5), rt_div(rt_asin(y), RT_PI)));
    }
    if (part == RT_PART_SURFACE) return v2(rt_div(rt_atan2(q.z, q.x), two_pi), rt_sub(RT_C(0.5), q.y));
    return v2(rt_add(RT_C(0.5), q.x), rt_sub(RT_C(0.5), q.z));
}

static rt_surface quadric_surface(const rt_scene *scene, const rt_ray *ray, const rt_scene_hit *hit, bool all_uv,
                                  rt_surface s)
{
    s.object = scene->quadric_objects[hit->prim - scene->triangle_count];
    const rt_object *obj = &scene->objects[s.object];
    /* The object-space point, from the object-space ray (as the intersector saw it). */
    rt_vec3 o = rt_object_point(obj, ray->origin);
    rt_vec3 d = rt_object_vector(obj, ray->direction);
    rt_vec3 q = rt_v3_madd(o, d, hit->hit.t);
    rt_vec3 n_obj;
    if (obj->kind == RT_SHAPE_SPHERE)
        n_obj = q;
    else if (hit->hit.part == RT_PART_SURFACE)
        n_obj = rt_v3(q.x, RT_ZERO, q.z);
    else
        n_obj = rt_v3(RT_ZERO, hit->hit.part == RT_PART_CAP_TOP ? RT_ONE : rt_neg(RT_ONE), RT_ZERO);
    s.normal = rt_v3_normalize(rt_object_normal_to_world(obj, n_obj));
    s.geometric_normal = s.normal;
    /* uv costs an atan2 and an asin; untextured materials never read it. */
    bool want_uv = all_uv || rt_material_textured(&scene->materials[obj->material]);
    s.uv = want_uv ? quadric_uv(obj, hit->hit.part, q) : v2(RT_ZERO, RT_ZERO);
    return s;
}

rt_surface rt_surface_at(const rt_scene *scene, const rt_ray *ray, const rt_scene_hit *hit, bool all_uv)
{
    rt_surface s;
    s.point = rt_v3_madd(ray->origin, ray->direction, hit->hit.t);
    if (hit->prim < scene->triangle_count)
        s = triangle_surface(scene, hit, s);
    else
        s = quadric_surface(scene, ray, hit, all_uv, s);
    s.material = scene->objects[s.object].material;
    return s;
}

/* Column or row index wrapped into [0, n) with a true modulo (n <= 65536, checked at build). */
static uint32_t wrap(int32_t i, uint32_t n)
{
    int32_t m = i % (int32_t)n;
    return (uint32_t)(m < 0 ? m + (int32_t)n : m);
}

static uint32_t next(uint32_t i, uint32_t n) { return i + 1 == n ? 0 : i + 1; }

static rt_vec3 texel(const rt_texture *tex, uint32_t x, uint32_t y)
{
    const uint8_t *p = tex->rgb + ((size_t)y * tex->width + x) * 3;
    rt_real full = rt_from_int(255);
    return rt_v3(rt_div(rt_from_int(p[0]), full), rt_div(rt_from_int(p[1]), full), rt_div(rt_from_int(p[2]), full));
}

static rt_vec3 lerp(rt_vec3 a, rt_vec3 b, rt_real t) { return rt_v3_add(a, rt_v3_scale(rt_v3_sub(b, a), t)); }

rt_vec3 rt_surface_texel(const rt_texture *tex, rt_vec2 uv)
{
    /* Texel (i, j) sits exactly at uv (i/W, j/H); v = 0 is the top row (format.md §4.6). */
    uint32_t w = tex->width, h = tex->height;
    rt_real px = rt_mul(uv.u, rt_from_int(w)), py = rt_mul(uv.v, rt_from_int(h));
    if (!tex->bilinear)
        return texel(tex, wrap(rt_floor_int(rt_add(px, RT_C(0.5))), w), wrap(rt_floor_int(rt_add(py, RT_C(0.5))), h));
    int32_t ix = rt_floor_int(px), iy = rt_floor_int(py);
    rt_real fx = rt_sub(px, rt_from_int(ix)), fy = rt_sub(py, rt_from_int(iy));
    uint32_t x0 = wrap(ix, w), y0 = wrap(iy, h), x1 = next(x0, w), y1 = next(y0, h);
    rt_vec3 top = lerp(texel(tex, x0, y0), texel(tex, x1, y0), fx);
    rt_vec3 bottom = lerp(texel(tex, x0, y1), texel(tex, x1, y1), fx);
    return lerp(top, bottom, fy);
}

rt_vec3 rt_surface_channel(const rt_scene *scene, const rt_channel *ch, rt_vec2 uv)
{
    return ch->texture == RT_NO_TEXTURE ? ch->color : rt_surface_texel(&scene->textures[ch->texture], uv);
}
