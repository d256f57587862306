/* Recursive ray tracing; see trace.h and format §9-§10. */
#include "trace.h"

/* The skeleton's refractive index of air (format §10.3). */
#define RT_AIR_INDEX RT_C(1.0003)

static rt_ray make_ray(rt_vec3 origin, rt_vec3 direction, rt_real t_max)
{
    rt_ray r = {origin, direction, RT_HIT_EPSILON, t_max};
    return r;
}

static bool nearest(const rt_tracer *tr, const rt_ray *ray, rt_scene_hit *hit)
{
    rt_ray_setup rs = rt_ray_prepare(*ray);
    return rt_scene_nearest(tr->scene, &rs, tr->use_bvh, hit);
}

/* Light reaching `point` from a light `distance` away along unit `to_light`:
 * 1 when unblocked, 0 behind an opaque surface, and with coloured shadows the
 * product of the transmittance of every surface crossed (format §10.1). */
static rt_vec3 shadow_attenuation(const rt_tracer *tr, rt_vec3 point, rt_vec3 to_light, rt_real distance)
{
    const rt_scene *scene = tr->scene;
    rt_vec3 atten = rt_v3(RT_ONE, RT_ONE, RT_ONE);
    uint32_t mode = scene->camera.trace.shadows;
    if (mode == 0) return atten;
    rt_vec3 origin = point;
    rt_real remaining = distance;
    /* Each crossing moves the origin forward by at least the hit epsilon; the bound
     * only guards against pathological scenes. */
    for (uint32_t crossing = 0; crossing < 1u << 16; crossing++) {
        rt_ray ray = make_ray(origin, to_light, remaining);
        rt_scene_hit hit;
        if (!nearest(tr, &ray, &hit)) return atten;
        if (mode == 1) return rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
        rt_surface s = rt_surface_at(scene, &ray, &hit);
        rt_vec3 kt = rt_channel_at(scene, &scene->materials[s.material].transmittance, s.uv);
        atten = rt_v3_mul(atten, kt);
        if (rt_v3_is_zero(atten)) return atten;
        origin = s.point;
        if (remaining != RT_REAL_MAX) remaining = rt_sub(remaining, hit.hit.t);
    }
    return rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
}

/* 1 / (c + b r + a r^2), at most 1 (and 1 when the denominator is not positive). */
static rt_real distance_attenuation(const rt_light *l, rt_real r)
{
    rt_real denom = rt_add(rt_add(l->atten_const, rt_mul(l->atten_linear, r)), rt_mul(l->atten_quad, rt_mul(r, r)));
    if (!(denom > RT_ONE)) return RT_ONE;
    return rt_div(RT_ONE, denom);
}

typedef struct {
    rt_vec3 kd, ks;
    rt_real shininess;
} lit_material;

/* Ambient plus the shadowed Blinn-Phong term of one light at the surface point. */
static rt_vec3 light_contribution(const rt_tracer *tr, const rt_light *l, rt_vec3 point, rt_vec3 n, rt_vec3 v,
                                  const lit_material *m)
{
    rt_vec3 c = rt_v3_mul(m->kd, l->ambient);
    rt_vec3 to_light;
    rt_real distance, atten;
    if (l->kind == RT_LIGHT_DIRECTIONAL) {
        to_light = l->direction;
        distance = RT_REAL_MAX;
        atten = RT_ONE;
    } else {
        /* Area lights act as point lights at their centre outside Monte Carlo mode. */
        rt_vec3 delta = rt_v3_sub(l->position, point);
        distance = rt_v3_length(delta);
        if (distance == RT_ZERO) return c;
        to_light = rt_v3_scale(delta, rt_div(RT_ONE, distance));
        atten = distance_attenuation(l, distance);
    }
    rt_real n_dot_l = rt_v3_dot(n, to_light);
    if (!(n_dot_l > RT_ZERO)) return c;
    rt_vec3 h = rt_v3_normalize(rt_v3_add(to_light, v));
    rt_real n_dot_h = rt_max(rt_v3_dot(n, h), RT_ZERO);
    rt_real spec = rt_pow(n_dot_h, rt_max(m->shininess, RT_C(1e-5)));
    rt_vec3 brdf = rt_v3_add(rt_v3_scale(m->kd, n_dot_l), rt_v3_scale(m->ks, spec));
    rt_vec3 shadow = shadow_attenuation(tr, point, to_light, distance);
    rt_vec3 light = rt_v3_scale(rt_v3_mul(shadow, l->color), atten);
    return rt_v3_add(c, rt_v3_mul(light, brdf));
}

/* Snell refraction of view vector v through normal n (facing v) with ratio eta;
 * false on total internal reflection. */
static bool refract(rt_vec3 v, rt_vec3 n, rt_real eta, rt_vec3 *out)
{
    rt_real cos_i = rt_v3_dot(n, v);
    rt_real k = rt_sub(RT_ONE, rt_mul(rt_mul(eta, eta), rt_sub(RT_ONE, rt_mul(cos_i, cos_i))));
    if (k < RT_ZERO) return false;
    rt_vec3 t = rt_v3_sub(rt_v3_scale(n, rt_sub(rt_mul(eta, cos_i), rt_sqrt(k))), rt_v3_scale(v, eta));
    *out = rt_v3_normalize(t);
    return !rt_v3_is_zero(*out);
}

rt_vec3 rt_trace(const rt_tracer *tr, rt_ray ray, uint32_t depth)
{
    const rt_scene *scene = tr->scene;
    const rt_trace_settings *set = &scene->camera.trace;
    rt_vec3 black = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    rt_scene_hit hit;
    if (depth > set->max_depth || !nearest(tr, &ray, &hit)) return black;
    rt_surface s = rt_surface_at(scene, &ray, &hit);
    const rt_material *mat = &scene->materials[s.material];
    rt_vec3 v = rt_v3_neg(ray.direction);
    /* The shading normal is turned to face the viewer by its own sign (format §9). */
    bool entering = rt_v3_dot(s.normal, v) > RT_ZERO;
    rt_vec3 n = entering ? s.normal : rt_v3_neg(s.normal);
    lit_material m = {rt_channel_at(scene, &mat->diffuse, s.uv), rt_channel_at(scene, &mat->specular, s.uv),
                      mat->shininess};
    rt_vec3 color = rt_channel_at(scene, &mat->emissive, s.uv);
    for (uint32_t i = 0; i < scene->light_count; i++)
        color = rt_v3_add(color, light_contribution(tr, &scene->lights[i], s.point, n, v, &m));
    if (set->reflections && !rt_v3_is_zero(m.ks)) {
        rt_vec3 r = rt_v3_sub(rt_v3_scale(n, rt_mul(RT_C(2.0), rt_v3_dot(v, n))), v);
        rt_vec3 reflected = rt_trace(tr, make_ray(s.point, rt_v3_normalize(r), RT_REAL_MAX), depth + 1);
        color = rt_v3_add(color, rt_v3_mul(m.ks, reflected));
    }
    rt_vec3 kt = rt_channel_at(scene, &mat->transmittance, s.uv);
    if (set->refractions && !rt_v3_is_zero(kt)) {
        rt_real eta = entering ? rt_div(RT_AIR_INDEX, mat->index_of_refraction)
                               : rt_div(mat->index_of_refraction, RT_AIR_INDEX);
        rt_vec3 t;
        if (refract(v, n, eta, &t)) {
            rt_vec3 transmitted = rt_trace(tr, make_ray(s.point, t, RT_REAL_MAX), depth + 1);
            color = rt_v3_add(color, rt_v3_mul(kt, transmitted));
        }
    }
    return color;
}
