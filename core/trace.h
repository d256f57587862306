/* Whitted-style ray tracing with the sample solution's shading (format.md §8-§9). */
#ifndef RT_TRACE_H
#define RT_TRACE_H

#include "scene_query.h"

/* The debugger's ray log (raylog.h); the tracer only carries a pointer to it. */
typedef struct rt_ray_log rt_ray_log;
/* The shading frame at a hit (shading.h). */
typedef struct rt_shading_point rt_shading_point;

/* What a camera ray's trace finds at depth 0, known beforehand because the ray and the
 * shadow rays of its hit were traced in packets (render_group.c): the nearest hit, its
 * shading frame, and for each of the first RT_PRIMED_LIGHTS lights the first query of its
 * shadow ray. */
#define RT_PRIMED_LIGHTS 8
typedef struct {
    bool found;
    rt_scene_hit hit;
    const rt_shading_point *point; /* the hit's frame, or NULL while it is being made */
    /* 0: not traced beforehand (query it); 1: nothing in the way; 2: shadow_hit is the
     * nearest hit (coloured shadows) or something blocks (opaque shadows). */
    uint8_t shadow[RT_PRIMED_LIGHTS];
    rt_scene_hit shadow_hit[RT_PRIMED_LIGHTS];
} rt_primed;

typedef struct {
    const rt_scene *scene;
    bool use_bvh;
    rt_ray_log *log;         /* NULL except when debugging */
    const rt_primed *primed; /* NULL except for a camera ray traced in a packet */
} rt_tracer;

/* The colour a ray brings back; depth 0 for camera rays. Not clamped. */
rt_vec3 rt_trace(const rt_tracer *tr, rt_ray ray, uint32_t depth);

#endif
