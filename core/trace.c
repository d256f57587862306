/* Recursive ray tracing; see trace.h and format §9-§10. */
#include "shading.h"

static rt_vec3 trace_ray(const rt_tracer *tr, rt_ray ray, uint32_t depth, rt_ray_kind kind, uint32_t parent);

/* Everything a hit sends back: emission, lights, the mirror and the refracted ray. */
static rt_vec3 shade(const rt_tracer *tr, const rt_ray *ray, const rt_surface *s, uint32_t depth, uint32_t id)
{
    const rt_scene *scene = tr->scene;
    const rt_trace_settings *set = &scene->camera.trace;
    rt_shading_point p = rt_shading_point_at(scene, ray, s, id, depth);
    rt_vec3 color = p.ke;
    rt_ray_record *rec = rt_log_ray(tr->log, id);
    if (rec) {
        rec->normal_used = p.n;
        rec->entering = p.entering;
        rec->emissive = color;
    }
    /* Area lights act as point lights at their centre outside Monte Carlo mode. */
    for (uint32_t i = 0; i < scene->light_count; i++)
        color = rt_v3_add(color, rt_light_shade(tr, i, &p, scene->lights[i].position, true));
    if (set->reflections && !rt_v3_is_zero(p.ks)) {
        rt_vec3 reflected = trace_ray(tr, rt_make_ray(s->point, rt_mirror_direction(&p), RT_REAL_MAX), depth + 1,
                                      RT_RAY_REFLECTION, id);
        color = rt_v3_add(color, rt_v3_mul(p.ks, reflected));
    }
    if (set->refractions && !rt_v3_is_zero(p.kt)) {
        rt_vec3 t;
        if (rt_refraction_direction(&p, &t)) {
            rt_vec3 transmitted = trace_ray(tr, rt_make_ray(s->point, t, RT_REAL_MAX), depth + 1, RT_RAY_REFRACTION, id);
            color = rt_v3_add(color, rt_v3_mul(p.kt, transmitted));
        } else if ((rec = rt_log_ray(tr->log, id)) != 0) {
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
    uint32_t id = rt_log_begin(tr->log, kind, parent, depth, &ray);
    rt_scene_hit hit;
    if (!rt_nearest_hit(tr, &ray, &hit)) return black;
    rt_surface s = rt_surface_at(tr->scene, &ray, &hit);
    rt_ray_record *rec = rt_log_ray(tr->log, id);
    if (rec) {
        rec->hit = true;
        rec->scene_hit = hit;
        rec->surface = s;
    }
    rt_vec3 color = shade(tr, &ray, &s, depth, id);
    if ((rec = rt_log_ray(tr->log, id)) != 0) rec->color = color;
    return color;
}

rt_vec3 rt_trace(const rt_tracer *tr, rt_ray ray, uint32_t depth)
{
    return trace_ray(tr, ray, depth, RT_RAY_CAMERA, RT_NO_PARENT);
}
