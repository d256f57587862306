/* Shading shared by both tracers; see shading.h. */
#include "shading.h"
#include "area_light.h"
#include "raylog.h"

/* The skeleton's refractive index of air (format.md §9.4). */
#define RT_AIR_INDEX RT_C(1.0003)

bool rt_shading_nearest(const rt_tracer *tr, const rt_ray *ray, rt_scene_hit *hit)
{
    rt_ray_setup rs = rt_scene_prepare(tr->scene, *ray);
    return rt_scene_nearest(tr->scene, &rs, tr->use_bvh, hit);
}

bool rt_shading_hit(const rt_tracer *tr, const rt_ray *ray, rt_ray_kind kind, uint32_t parent, uint32_t depth,
                    rt_shading_point *p)
{
    const rt_scene *scene = tr->scene;
    p->ray = rt_raylog_begin(tr->log, kind, parent, depth, ray);
    p->depth = depth;
    rt_scene_hit hit;
    const rt_primed *pr = depth == 0 && kind == RT_RAY_CAMERA ? tr->primed : NULL;
    if (pr ? !pr->found : !rt_shading_nearest(tr, ray, &hit)) return false;
    if (pr && pr->point) {
        *p = *pr->point; /* made by this function from the same ray and hit */
        return true;
    }
    if (pr) hit = pr->hit;
    rt_surface s = rt_surface_at(scene, ray, &hit, tr->log != NULL);
    const rt_material *mat = &scene->materials[s.material];
    p->point = s.point;
    p->v = rt_v3_neg(ray->direction);
    /* The shading normal is turned to face the viewer by its own sign (format.md §8). */
    p->entering = rt_v3_dot(s.normal, p->v) > RT_ZERO;
    p->n = p->entering ? s.normal : rt_v3_neg(s.normal);
    p->ke = rt_surface_channel(scene, &mat->emissive, s.uv);
    p->kd = rt_surface_channel(scene, &mat->diffuse, s.uv);
    p->ks = rt_surface_channel(scene, &mat->specular, s.uv);
    p->kt = rt_surface_channel(scene, &mat->transmittance, s.uv);
    p->shininess = mat->shininess;
    p->index_of_refraction = mat->index_of_refraction;
    rt_raylog_hit(tr->log, p->ray, &hit, &s);
    rt_ray_record *rec = rt_raylog_ray(tr->log, p->ray);
    if (rec) {
        rec->normal_used = p->n;
        rec->entering = p->entering;
        rec->emissive = p->ke;
    }
    return true;
}

/* Light reaching `point` from a light `distance` away along unit `to_light`:
 * 1 when unblocked, 0 behind an opaque surface, and with coloured shadows the
 * product of the transmittance of every surface crossed (format.md §9.2). */
static rt_vec3 shadow_attenuation(const rt_tracer *tr, rt_vec3 point, rt_vec3 to_light, rt_real distance,
                                  uint32_t parent, uint32_t depth, uint32_t light)
{
    const rt_scene *scene = tr->scene;
    rt_vec3 atten = rt_v3(RT_ONE, RT_ONE, RT_ONE);
    rt_shadow_mode mode = scene->camera.trace.shadows;
    if (mode == RT_SHADOWS_NONE) return atten;
    /* The first query, when the packets made it (see rt_primed). */
    uint8_t primed = depth == 0 && tr->primed && light < RT_PRIMED_LIGHTS ? tr->primed->shadow[light] : 0;
    /* Opaque shadows need only whether anything blocks (any hit), unless the debugger
     * records which hit did. */
    if (mode == RT_SHADOWS_OPAQUE && !tr->log) {
        bool blocked = primed == 2;
        if (!primed) {
            rt_ray_setup rs = rt_scene_prepare(scene, rt_ray_make(point, to_light, distance));
            blocked = rt_scene_any(scene, &rs, tr->use_bvh);
        }
        return blocked ? rt_v3(RT_ZERO, RT_ZERO, RT_ZERO) : atten;
    }
    rt_vec3 origin = point;
    rt_real remaining = distance;
    /* Each crossing moves the origin forward by at least the hit epsilon, or it stops
     * below; the bound only guards against pathological scenes. */
    for (uint32_t crossing = 0; crossing < 1u << 16; crossing++) {
        rt_ray ray = rt_ray_make(origin, to_light, remaining);
        uint32_t id = rt_raylog_begin(tr->log, RT_RAY_SHADOW, parent, depth, &ray);
        rt_ray_record *rec = rt_raylog_ray(tr->log, id);
        if (rec) rec->light = light;
        rt_scene_hit hit;
        bool known = crossing == 0 && primed;
        if (known ? primed == 1 : !rt_shading_nearest(tr, &ray, &hit)) {
            rt_raylog_color(tr->log, id, atten);
            return atten;
        }
        if (known) hit = tr->primed->shadow_hit[light];
        rt_surface s = rt_surface_at(scene, &ray, &hit, tr->log != NULL);
        rt_vec3 kt = mode == RT_SHADOWS_OPAQUE
                         ? rt_v3(RT_ZERO, RT_ZERO, RT_ZERO)
                         : rt_surface_channel(scene, &scene->materials[s.material].transmittance, s.uv);
        rt_vec3 before = atten;
        atten = rt_v3_mul(atten, kt);
        rt_raylog_hit(tr->log, id, &hit, &s);
        rt_raylog_color(tr->log, id, atten);
        if (rec) rec->transmittance = kt;
        if (rt_v3_is_zero(atten)) return atten;
        /* Light that a surface scales (by a transmittance other than 1), yet unchanged:
         * the attenuation is at the arithmetic's floor (a few lsb in Q32.32, the least
         * subnormal in double) and can fall no further, or, under a transmittance above
         * 1, at its ceiling (Q32.32's largest value, infinity in double), however many
         * crossings follow (up to 65,536 queries per shadow ray): it counts as blocked,
         * as the loop's bound would have it. */
        if (rt_v3_equal(atten, before) && (atten.x == RT_ZERO || kt.x != RT_ONE) &&
            (atten.y == RT_ZERO || kt.y != RT_ONE) && (atten.z == RT_ZERO || kt.z != RT_ONE))
            break;
        /* A hit point that rounds to the origin (coordinates like 1e120, where t = 0.5 is
         * below their rounding) would be found again at every crossing, 65,536 times:
         * the ray cannot get past it, so it counts as blocked. */
        if (rt_v3_equal(s.point, origin)) break;
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

/* The unit vector from p towards light l (placed at `position` unless directional) and
 * its distance; false when p is at the light. */
static bool towards_light(const rt_light *l, const rt_shading_point *p, rt_vec3 position, rt_vec3 *to_light,
                          rt_real *distance)
{
    if (l->kind == RT_LIGHT_DIRECTIONAL) {
        *to_light = l->direction;
        *distance = RT_REAL_MAX;
        return true;
    }
    rt_vec3 delta = rt_v3_sub(position, p->point);
    *distance = rt_v3_length(delta);
    if (*distance == RT_ZERO) return false;
    *to_light = rt_v3_scale(delta, rt_div(RT_ONE, *distance));
    return true;
}

bool rt_shading_shadow_ray(const rt_tracer *tr, uint32_t index, const rt_shading_point *p, rt_vec3 position,
                           rt_ray *out)
{
    rt_vec3 to_light;
    rt_real distance;
    if (tr->scene->camera.trace.shadows == RT_SHADOWS_NONE ||
        !towards_light(&tr->scene->lights[index], p, position, &to_light, &distance))
        return false;
    if (!(rt_v3_dot(p->n, to_light) > RT_ZERO)) return false;
    *out = rt_ray_make(p->point, to_light, distance);
    return true;
}

rt_vec3 rt_shading_light(const rt_tracer *tr, uint32_t index, const rt_shading_point *p, rt_vec3 position,
                         bool lambertian)
{
    const rt_light *l = &tr->scene->lights[index];
    rt_vec3 ambient = rt_v3_mul(p->kd, l->ambient);
    /* Terms the light does not reach stay zero. */
    rt_light_record rec = {.ray = p->ray,
                           .light = index,
                           .ambient = ambient,
                           .distance_attenuation = RT_ONE,
                           .light_cosine = RT_ONE,
                           .shadow_attenuation = rt_v3(RT_ONE, RT_ONE, RT_ONE),
                           .contribution = ambient};
    rt_vec3 to_light;
    rt_real distance;
    if (!towards_light(l, p, position, &to_light, &distance)) {
        rt_raylog_light(tr->log, &rec);
        return rec.contribution;
    }
    if (l->kind != RT_LIGHT_DIRECTIONAL) {
        rec.distance_attenuation = distance_attenuation(l, distance);
        if (lambertian) rec.light_cosine = rt_area_light_cosine(l, to_light);
    }
    rec.n_dot_l = rt_v3_dot(p->n, to_light);
    /* Behind a Lambertian emitter (cosine 0) only the ambient term is left. */
    if (rec.n_dot_l > RT_ZERO && rec.light_cosine > RT_ZERO) {
        /* The power of a cosine (at most a few ulps above 1) to a shininess below 1e15 is
         * finite and not negative, so a zero ks times 0 is the same bits as times the power
         * (-0 included): the half vector, its root and the power's log and exp are spared
         * unless ks or the debugger's log reads them. */
        bool specular = !rt_v3_is_zero(p->ks) || !(p->shininess < RT_C(1e15));
        if (specular || tr->log) {
            rt_vec3 h = rt_v3_normalize(rt_v3_add(to_light, p->v));
            rec.n_dot_h = rt_max(rt_v3_dot(p->n, h), RT_ZERO);
        }
        rec.diffuse = rt_v3_scale(p->kd, rec.n_dot_l);
        rt_real power = specular ? rt_pow(rec.n_dot_h, rt_max(p->shininess, RT_C(1e-5))) : RT_ZERO;
        rec.specular = rt_v3_scale(p->ks, power);
        rec.shadow_attenuation = shadow_attenuation(tr, p->point, to_light, distance, p->ray, p->depth, index);
        /* A cosine of exactly 1 (point-like lights) leaves the product unchanged in both builds. */
        rt_vec3 light = rt_v3_scale(rt_v3_mul(rec.shadow_attenuation, l->color),
                                    rt_mul(rec.distance_attenuation, rec.light_cosine));
        rec.contribution = rt_v3_add(rec.ambient, rt_v3_mul(light, rt_v3_add(rec.diffuse, rec.specular)));
    }
    rt_raylog_light(tr->log, &rec);
    return rec.contribution;
}

rt_vec3 rt_shading_mirror(const rt_shading_point *p)
{
    return rt_v3_normalize(rt_v3_sub(rt_v3_scale(p->n, rt_mul(RT_C(2.0), rt_v3_dot(p->v, p->n))), p->v));
}

bool rt_shading_refraction(const rt_shading_point *p, rt_vec3 *out)
{
    rt_real eta =
        p->entering ? rt_div(RT_AIR_INDEX, p->index_of_refraction) : rt_div(p->index_of_refraction, RT_AIR_INDEX);
    /* Snell's law with n facing v (format.md §9.4). */
    rt_real cos_i = rt_v3_dot(p->n, p->v);
    rt_real k = rt_sub(RT_ONE, rt_mul(rt_mul(eta, eta), rt_sub(RT_ONE, rt_mul(cos_i, cos_i))));
    if (k < RT_ZERO) return false;
    rt_vec3 t = rt_v3_sub(rt_v3_scale(p->n, rt_sub(rt_mul(eta, cos_i), rt_sqrt(k))), rt_v3_scale(p->v, eta));
    *out = rt_v3_normalize(t);
    return !rt_v3_is_zero(*out);
}
