/* Scene queries: the nearest hit and whether anything is hit along a ray, through the
 * BVH or (for checking) over every primitive. Nearest-hit ties go to the lower primitive
 * reference, so a query returns the same primitive with or without the BVH. */
#ifndef RT_SCENE_QUERY_H
#define RT_SCENE_QUERY_H

#include "intersect.h"
#include "scene.h"

typedef struct {
    rt_prim_hit hit;
    uint32_t prim; /* primitive reference (see rt_scene) */
} rt_scene_hit;

/* A world-space point or direction in the object's own space (rt_object.to_object), and
 * an object-space normal in the world's; the fixed build skips a rotation-free matrix's
 * zeros, with the same result. */
static inline rt_vec3 rt_object_point(const rt_object *obj, rt_vec3 p)
{
#ifdef RT_REAL_FIXED
    if (obj->to_object_diagonal) return rt_affine_point_diagonal(&obj->to_object, p);
#endif
    return rt_affine_point(&obj->to_object, p);
}
static inline rt_vec3 rt_object_vector(const rt_object *obj, rt_vec3 v)
{
#ifdef RT_REAL_FIXED
    if (obj->to_object_diagonal) return rt_mat3_apply_diagonal(&obj->to_object.linear, v);
#endif
    return rt_affine_vector(&obj->to_object, v);
}
static inline rt_vec3 rt_object_normal_to_world(const rt_object *obj, rt_vec3 n)
{
#ifdef RT_REAL_FIXED
    if (obj->to_object_diagonal) return rt_mat3_apply_diagonal(&obj->normal_to_world, n); /* its transpose */
#endif
    return rt_mat3_apply(&obj->normal_to_world, n);
}

/* rt_intersect_prepare for queries of this scene: without its triangles' shear when it
 * has none. */
static inline rt_ray_setup rt_scene_prepare(const rt_scene *scene, rt_ray ray)
{
    return scene->triangle_count ? rt_intersect_prepare(ray) : rt_intersect_prepare_no_triangles(ray);
}

/* Tests one primitive against the ray. */
bool rt_scene_prim_intersect(const rt_scene *scene, uint32_t prim, const rt_ray_setup *rs, rt_prim_hit *hit);

/* Nearest hit in (t_min, t_max); use_bvh = false tests every primitive (for checking). */
bool rt_scene_nearest(const rt_scene *scene, const rt_ray_setup *rs, bool use_bvh, rt_scene_hit *out);
/* Whether any primitive is hit in (t_min, t_max): true exactly when rt_scene_nearest finds a hit. */
bool rt_scene_any(const rt_scene *scene, const rt_ray_setup *rs, bool use_bvh);
/* Rays traced together in packets by the stream queries below. */
#define RT_PACKET 8

/* The same queries for n rays at once, through the BVH: found[i] and out[i] are what
 * rt_scene_nearest(scene, &rs[i], true, &out[i]) and rt_scene_any(scene, &rs[i], true)
 * give, bit for bit. Rays that share a direction octant and axis permutation (a tile's
 * camera rays, their shadow rays) are traced RT_PACKET at a time where the kernel has
 * packets. */
void rt_scene_nearest_stream(const rt_scene *scene, const rt_ray_setup *rs, uint32_t n, rt_scene_hit *out, bool *found);
void rt_scene_any_stream(const rt_scene *scene, const rt_ray_setup *rs, uint32_t n, bool *found);

/* The mesh object a triangle (an index into rt_scene.triangles) belongs to. */
uint32_t rt_scene_triangle_object(const rt_scene *scene, uint32_t triangle);

#endif
