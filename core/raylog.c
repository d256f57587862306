/* Filling the debugger's ray log; see raylog.h. */
#include "raylog.h"
#include "invariant.h"

uint32_t rt_raylog_begin(rt_ray_log *log, rt_ray_kind kind, uint32_t parent, uint32_t depth, const rt_ray *ray)
{
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

rt_ray_record *rt_raylog_ray(rt_ray_log *log, uint32_t id)
{
    if (!log || id == RT_NO_PARENT) return 0;
    RT_ASSERT(id < log->ray_count);
    return &log->rays[id];
}

void rt_raylog_hit(rt_ray_log *log, uint32_t id, const rt_scene_hit *hit, const rt_surface *s)
{
    rt_ray_record *r = rt_raylog_ray(log, id);
    if (!r) return;
    r->hit = true;
    r->scene_hit = *hit;
    r->surface = *s;
}

void rt_raylog_color(rt_ray_log *log, uint32_t id, rt_vec3 color)
{
    rt_ray_record *r = rt_raylog_ray(log, id);
    if (r) r->color = color;
}

void rt_raylog_light(rt_ray_log *log, const rt_light_record *rec)
{
    if (!log || rec->ray == RT_NO_PARENT) return;
    if (log->light_count >= log->light_capacity) {
        log->overflow = true;
        return;
    }
    log->lights[log->light_count++] = *rec;
}
