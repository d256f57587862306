/* A record of every ray traced for one sample, for `rtk debug`. The tracer fills it
 * when given one; normal renders pass none and pay one pointer test per ray. */
#ifndef RT_RAYLOG_H
#define RT_RAYLOG_H

#include "surface.h"

#define RT_NO_PARENT UINT32_MAX

/* RT_RAY_GLOSSY: the reflection branch of Monte Carlo mode, about a sampled half vector (format.md §11.6). */
typedef enum {
    RT_RAY_CAMERA,
    RT_RAY_REFLECTION,
    RT_RAY_REFRACTION,
    RT_RAY_SHADOW,
    RT_RAY_DIFFUSE,
    RT_RAY_GLOSSY
} rt_ray_kind;

typedef struct {
    rt_ray_kind kind;
    uint32_t parent; /* index of the ray whose hit spawned it, or RT_NO_PARENT */
    uint32_t depth;
    uint32_t light; /* shadow rays: the light they test; on_light: the light seen */
    rt_ray ray;     /* on_light: t_max is where the ray meets the light's square */
    bool on_light;  /* a Monte Carlo camera ray that ends on an area light's square (format.md §11.4) */
    /* Glossy rays: the sampled half vector, and whether the direction about it fell
     * below the surface, so that the ray took the mirror direction instead. */
    rt_vec3 half_vector;
    bool mirror_fallback;
    bool hit;
    rt_scene_hit scene_hit;
    rt_surface surface;  /* when hit */
    rt_vec3 normal_used; /* the shading normal turned towards the viewer */
    bool entering;       /* the viewer is on the shading normal's side */
    bool total_internal_reflection;
    rt_vec3 emissive; /* k_e at the hit */
    /* Shadow rays: the transmittance of the surface crossed (0 for opaque mode). */
    rt_vec3 transmittance;
    /* What the ray brings back: its colour (shadow rays: the attenuation so far; on_light:
     * the light's emission). */
    rt_vec3 color;
} rt_ray_record;

/* The terms of one light at one surface hit (format.md §8). */
typedef struct {
    uint32_t ray; /* the ray whose hit this lights */
    uint32_t light;
    rt_vec3 ambient; /* k_d * ambient */
    rt_real n_dot_l, n_dot_h;
    rt_vec3 diffuse;  /* k_d * N.L (0 when gated) */
    rt_vec3 specular; /* k_s * (N.H)^n_s (0 when gated) */
    rt_real distance_attenuation;
    rt_real light_cosine; /* an area light's cos(theta_L) in Monte Carlo mode (format.md §11.4); else 1 */
    rt_vec3 shadow_attenuation;
    rt_vec3 contribution; /* ambient + shadow * A_dist * cos_L * I_L * (diffuse + specular) */
} rt_light_record;

typedef struct rt_ray_log {
    rt_ray_record *rays;
    uint32_t ray_count, ray_capacity;
    rt_light_record *lights;
    uint32_t light_count, light_capacity;
    bool overflow; /* set when a record did not fit */
} rt_ray_log;

/* Recording, for the tracers; each is a no-op when log is NULL. */
/* Starts a record for a ray; returns its index, or RT_NO_PARENT when not recorded. */
uint32_t rt_raylog_begin(rt_ray_log *log, rt_ray_kind kind, uint32_t parent, uint32_t depth, const rt_ray *ray);
/* The record of ray id, or NULL when there is none: for the fields only one tracer sets. */
rt_ray_record *rt_raylog_ray(rt_ray_log *log, uint32_t id);
/* Records that ray id hit `hit`, on surface s. */
void rt_raylog_hit(rt_ray_log *log, uint32_t id, const rt_scene_hit *hit, const rt_surface *s);
/* Records the colour ray id brings back (a shadow ray: its attenuation so far). */
void rt_raylog_color(rt_ray_log *log, uint32_t id, rt_vec3 color);
/* Appends the light terms of a recorded ray's hit. */
void rt_raylog_light(rt_ray_log *log, const rt_light_record *rec);

#endif
