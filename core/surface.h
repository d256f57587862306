/* What a renderer needs to know about a hit: point, normals, uv and material. */
#ifndef RT_SURFACE_H
#define RT_SURFACE_H

#include "scene_query.h"

typedef struct {
    rt_vec3 point;
    rt_vec3 normal;           /* shading normal as the primitive gives it (unit, not flipped) */
    rt_vec3 geometric_normal; /* the facet's (or quadric's) true normal (unit, not flipped) */
    rt_vec2 uv;               /* (0, 0) on a quadric whose material has no texture, unless asked for */
    uint32_t material;
    uint32_t object;
} rt_surface;

/* The hit's attributes. A quadric's uv (an atan2 and an asin) is computed only when its
 * material reads a texture or when all_uv asks for it (the debugger shows it). */
rt_surface rt_surface_at(const rt_scene *scene, const rt_ray *ray, const rt_scene_hit *hit, bool all_uv);
/* True when any channel of m reads a texture. */
bool rt_material_textured(const rt_material *m);
/* A material channel's value at uv: its solid colour or its texture's texel blend. */
rt_vec3 rt_surface_channel(const rt_scene *scene, const rt_channel *ch, rt_vec2 uv);
rt_vec3 rt_surface_texel(const rt_texture *tex, rt_vec2 uv);

#endif
