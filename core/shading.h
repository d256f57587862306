/* What the Whitted and the Monte Carlo tracers share: the shading frame at a hit,
 * the direct light of one light (format.md §8, shadows §9.2) and the mirror and
 * refracted directions (format.md §9.3-§9.4). */
#ifndef RT_SHADING_H
#define RT_SHADING_H

#include "raylog.h"
#include "trace.h"

typedef struct rt_shading_point {
    rt_vec3 point, n, v; /* hit point, shading normal facing the viewer, unit vector to the viewer */
    bool entering;       /* the viewer is on the shading normal's side */
    rt_vec3 ke, kd, ks, kt;
    rt_real shininess, index_of_refraction;
    uint32_t ray, depth; /* the ray being shaded (for the log) */
} rt_shading_point;

/* The nearest hit along ray (t_min, t_max). */
bool rt_shading_nearest(const rt_tracer *tr, const rt_ray *ray, rt_scene_hit *hit);

/* Traces ray (recorded in the log as `kind`, spawned by ray `parent`) to its nearest
 * hit and fills p with the frame and material values there; false on a miss. */
bool rt_shading_hit(const rt_tracer *tr, const rt_ray *ray, rt_ray_kind kind, uint32_t parent, uint32_t depth,
                    rt_shading_point *p);

/* Ambient plus the shadowed Blinn-Phong term of light `index` as if it sat at
 * `position` (point and area lights; directional lights use their direction).
 * lambertian (an area light's sampled point, Monte Carlo mode, format.md §11.4): the
 * term is multiplied by the cosine at the light, and points behind it get the
 * ambient term only. */
rt_vec3 rt_shading_light(const rt_tracer *tr, uint32_t index, const rt_shading_point *p, rt_vec3 position,
                         bool lambertian);

/* The first shadow ray rt_shading_light traces towards light `index` as if it sat at
 * `position` (lambertian = false, as Whitted tracing calls it), or false when it traces none. */
bool rt_shading_shadow_ray(const rt_tracer *tr, uint32_t index, const rt_shading_point *p, rt_vec3 position,
                           rt_ray *out);

/* The mirror direction of the view vector about the shading normal. */
rt_vec3 rt_shading_mirror(const rt_shading_point *p);
/* The refracted direction into (or out of) the surface; false on total internal reflection. */
bool rt_shading_refraction(const rt_shading_point *p, rt_vec3 *out);

#endif
