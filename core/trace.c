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

/* ---- The debugger's log (no-ops when tr->log is NULL) ---- */

static uint32_t log_begin(const rt_tracer *tr, rt_ray_kind kind, uint32_t parent, uint32_t depth, const rt_ray *ray)
{
    rt_ray_log *log = tr->log;
    if (!log) return RT_NO_PARENT;
    if (log->ray_count >= log->ray_capacity) {
        log->overflow = true;
        return RT_NO_PARENT;
    }
    rt_ray_record zero = {0};
    rt_ray_record *r = &log->rays[log->ray_count];
    *r = zero;
    r->kind = kind;
    r->parent = parent;
    r->depth = depth;
    r->ray = *ray;
    return log->ray_count++;
}

static rt_ray_record *log_ray(const rt_tracer *tr, uint32_t id)
{
    return tr->log && id != RT_NO_PARENT ? &tr->log->rays[id] : 0;
}

static void log_light(const rt_tracer *tr, const rt_light_record *rec)
{
    rt_ray_log *log = tr->log;
    if (!log || rec->ray == RT_NO_PARENT) return;
    if (log->light_count >= log->light_capacity) {
        log->overflow = true;
        return;
    }
    log->lights[log->light_count++] = *rec;
}

/* ---- Shading ---- */

/* Light reaching `point` from a light `distance` away along unit `to_light`:
 * 1 when unblocked, 0 behind an opaque surface, and with coloured shadows the
 * product of the transmittance of every surface crossed (format §10.1). */
static rt_vec3 shadow_attenuation(const rt_tracer *tr, rt_vec3 point, rt_vec3 to_light, rt_real distance,
                                  uint32_t parent, uint32_t depth, uint32_t light)
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
        uint32_t id = log_begin(tr, RT_RAY_SHADOW, parent, depth, &ray);
        rt_ray_record *rec = log_ray(tr, id);
        if (rec) rec->light = light;
        rt_scene_hit hit;
        if (!nearest(tr, &ray, &hit)) {
            if (rec) rec->color = atten;
            return atten;
        }
        rt_surface s = rt_surface_at(scene, &ray, &hit);
        rt_vec3 kt = mode == 1 ? rt_v3(RT_ZERO, RT_ZERO, RT_ZERO)
                               : rt_channel_at(scene, &scene->materials[s.material].transmittance, s.uv);
        atten = rt_v3_mul(atten, kt);
        if (rec) {
            rec->hit = true;
            rec->scene_hit = hit;
            rec->surface = s;
            rec->transmittance = kt;
            rec->color = atten;
        }
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
    rt_vec3 point, n, v; /* hit point, normal facing the viewer, unit vector to the viewer */
    rt_vec3 kd, ks;
    rt_real shininess;
    uint32_t ray, depth; /* the ray being shaded (for the log) */
} shading_point;

/* Ambient plus the shadowed Blinn-Phong term of one light at the surface point. */
static rt_vec3 light_contribution(const rt_tracer *tr, uint32_t index, const shading_point *p)
{
    const rt_light *l = &tr->scene->lights[index];
    rt_vec3 black = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    rt_light_record rec = {p->ray, index, rt_v3_mul(p->kd, l->ambient), RT_ZERO, RT_ZERO, black, black, RT_ONE,
                           rt_v3(RT_ONE, RT_ONE, RT_ONE), black};
    rec.contribution = rec.ambient;
    rt_vec3 to_light;
    rt_real distance;
    if (l->kind == RT_LIGHT_DIRECTIONAL) {
        to_light = l->direction;
        distance = RT_REAL_MAX;
    } else {
        /* Area lights act as point lights at their centre outside Monte Carlo mode. */
        rt_vec3 delta = rt_v3_sub(l->position, p->point);
        distance = rt_v3_length(delta);
        if (distance == RT_ZERO) {
            log_light(tr, &rec);
            return rec.contribution;
        }
        to_light = rt_v3_scale(delta, rt_div(RT_ONE, distance));
        rec.distance_attenuation = distance_attenuation(l, distance);
    }
    rec.n_dot_l = rt_v3_dot(p->n, to_light);
    if (rec.n_dot_l > RT_ZERO) {
        rt_vec3 h = rt_v3_normalize(rt_v3_add(to_light, p->v));
        rec.n_dot_h = rt_max(rt_v3_dot(p->n, h), RT_ZERO);
        rec.diffuse = rt_v3_scale(p->kd, rec.n_dot_l);
        rec.specular = rt_v3_scale(p->ks, rt_pow(rec.n_dot_h, rt_max(p->shininess, RT_C(1e-5))));
        rec.shadow_attenuation = shadow_attenuation(tr, p->point, to_light, distance, p->ray, p->depth, index);
        rt_vec3 light = rt_v3_scale(rt_v3_mul(rec.shadow_attenuation, l->color), rec.distance_attenuation);
        rec.contribution = rt_v3_add(rec.ambient, rt_v3_mul(light, rt_v3_add(rec.diffuse, rec.specular)));
    }
    log_light(tr, &rec);
    return rec.contribution;
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

static rt_vec3 trace_ray(const rt_tracer *tr, rt_ray ray, uint32_t depth, rt_ray_kind kind, uint32_t parent);

/* Everything a hit sends back: emission, lights, the mirror and the refracted ray. */
static rt_vec3 shade(const rt_tracer *tr, const rt_ray *ray, const rt_surface *s, uint32_t depth, uint32_t id)
{
    const rt_scene *scene = tr->scene;
    const rt_trace_settings *set = &scene->camera.trace;
    const rt_material *mat = &scene->materials[s->material];
    shading_point p;
    p.point = s->point;
    p.v = rt_v3_neg(ray->direction);
    /* The shading normal is turned to face the viewer by its own sign (format §9). */
    bool entering = rt_v3_dot(s->normal, p.v) > RT_ZERO;
    p.n = entering ? s->normal : rt_v3_neg(s->normal);
    p.kd = rt_channel_at(scene, &mat->diffuse, s->uv);
    p.ks = rt_channel_at(scene, &mat->specular, s->uv);
    p.shininess = mat->shininess;
    p.ray = id;
    p.depth = depth;
    rt_vec3 color = rt_channel_at(scene, &mat->emissive, s->uv);
    rt_ray_record *rec = log_ray(tr, id);
    if (rec) {
        rec->normal_used = p.n;
        rec->entering = entering;
        rec->emissive = color;
    }
    for (uint32_t i = 0; i < scene->light_count; i++) color = rt_v3_add(color, light_contribution(tr, i, &p));
    if (set->reflections && !rt_v3_is_zero(p.ks)) {
        rt_vec3 r = rt_v3_sub(rt_v3_scale(p.n, rt_mul(RT_C(2.0), rt_v3_dot(p.v, p.n))), p.v);
        rt_vec3 reflected = trace_ray(tr, make_ray(s->point, rt_v3_normalize(r), RT_REAL_MAX), depth + 1,
                                      RT_RAY_REFLECTION, id);
        color = rt_v3_add(color, rt_v3_mul(p.ks, reflected));
    }
    rt_vec3 kt = rt_channel_at(scene, &mat->transmittance, s->uv);
    if (set->refractions && !rt_v3_is_zero(kt)) {
        rt_real eta = entering ? rt_div(RT_AIR_INDEX, mat->index_of_refraction)
                               : rt_div(mat->index_of_refraction, RT_AIR_INDEX);
        rt_vec3 t;
        if (refract(p.v, p.n, eta, &t)) {
            rt_vec3 transmitted = trace_ray(tr, make_ray(s->point, t, RT_REAL_MAX), depth + 1, RT_RAY_REFRACTION, id);
            color = rt_v3_add(color, rt_v3_mul(kt, transmitted));
        } else if ((rec = log_ray(tr, id)) != 0) {
            rec->total_internal_reflection = true;
        }
    }
    return color;
}

static rt_vec3 trace_ray(const rt_tracer *tr, rt_ray ray, uint32_t depth, rt_ray_kind kind, uint32_t parent)
{
    rt_vec3 black = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    /* A ray past the recursion limit is neither intersected nor logged (format §10.5). */
    if (depth > tr->scene->camera.trace.max_depth) return black;
    uint32_t id = log_begin(tr, kind, parent, depth, &ray);
    rt_scene_hit hit;
    if (!nearest(tr, &ray, &hit)) return black;
    rt_surface s = rt_surface_at(tr->scene, &ray, &hit);
    rt_ray_record *rec = log_ray(tr, id);
    if (rec) {
        rec->hit = true;
        rec->scene_hit = hit;
        rec->surface = s;
    }
    rt_vec3 color = shade(tr, &ray, &s, depth, id);
    if ((rec = log_ray(tr, id)) != 0) rec->color = color;
    return color;
}

rt_vec3 rt_trace(const rt_tracer *tr, rt_ray ray, uint32_t depth)
{
    return trace_ray(tr, ray, depth, RT_RAY_CAMERA, RT_NO_PARENT);
}
