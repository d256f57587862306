/* Recursive ray tracing; see trace.h and format.md §8-§9. */
#include "raylog.h"
#include "shading.h"

static rt_vec3 trace_ray(const rt_tracer *tr, rt_ray ray, uint32_t depth, rt_ray_kind kind, uint32_t parent)
{
    const rt_scene *scene = tr->scene;
    const rt_trace_settings *set = &scene->camera.trace;
    rt_vec3 color = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    /* A ray past the recursion limit is neither intersected nor logged (format.md §9.5). */
    if (depth > set->max_depth) return color;
    rt_shading_point p;
    if (!rt_shading_hit(tr, &ray, kind, parent, depth, &p)) return color;
    /* Emission, lights, the mirror and the refracted ray. Area lights act as point
     * lights at their centre outside Monte Carlo mode. */
    color = p.ke;
    for (uint32_t i = 0; i < scene->light_count; i++)
        color = rt_v3_add(color, rt_shading_light(tr, i, &p, scene->lights[i].position, false));
    if (set->reflections && !rt_v3_is_zero(p.ks)) {
        rt_vec3 reflected = trace_ray(tr, rt_ray_make(p.point, rt_shading_mirror(&p), RT_REAL_MAX), depth + 1,
                                      RT_RAY_REFLECTION, p.ray);
        color = rt_v3_add(color, rt_v3_mul(p.ks, reflected));
    }
    rt_ray_record *rec;
    if (set->refractions && !rt_v3_is_zero(p.kt)) {
        rt_vec3 t;
        if (rt_shading_refraction(&p, &t)) {
            rt_vec3 transmitted =
                trace_ray(tr, rt_ray_make(p.point, t, RT_REAL_MAX), depth + 1, RT_RAY_REFRACTION, p.ray);
            color = rt_v3_add(color, rt_v3_mul(p.kt, transmitted));
        } else if ((rec = rt_raylog_ray(tr->log, p.ray)) != 0) {
            rec->total_internal_reflection = true;
        }
    }
    rt_raylog_color(tr->log, p.ray, color);
    return color;
}

rt_vec3 rt_trace(const rt_tracer *tr, rt_ray ray, uint32_t depth)
{
    return trace_ray(tr, ray, depth, RT_RAY_CAMERA, RT_NO_PARENT);
}
