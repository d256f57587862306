/* Whitted-style ray tracing with the sample solution's shading (format §9-§10). */
#ifndef RT_TRACE_H
#define RT_TRACE_H

#include "raylog.h"

typedef struct {
    const rt_scene *scene;
    bool use_bvh;
    rt_ray_log *log; /* NULL except when debugging */
} rt_tracer;

/* The colour a ray brings back; depth 0 for camera rays. Not clamped. */
rt_vec3 rt_trace(const rt_tracer *tr, rt_ray ray, uint32_t depth);

#endif
