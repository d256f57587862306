/* Area lights in Monte Carlo mode (format.md §5.4, §11.4): the node's unit square in its
 * local XZ plane, a Lambertian emitter towards its local +Y side, sampled by the
 * direct term and seen by camera rays. Outside Monte Carlo mode an area light is a
 * point light at the square's centre and none of this is used. */
#ifndef RT_AREA_LIGHT_H
#define RT_AREA_LIGHT_H

#include "ray.h"
#include "scene.h"

/* What a camera ray that ends on a light's square brings back, in units of the
 * light's Color. The solution's emission is far above 1 (format.md §11.4: partly
 * covered pixels are still white), and any value from about 10 up gives the same
 * image; 64 is the first at which a pixel that one of its 64 samples sees on the light
 * is white, so the square's edges stay hard at the corpus's sample count. */
#define RT_AREA_LIGHT_EMISSION RT_C(64.0)

/* The point (u, v) in [0,1]^2 of the light's square. */
rt_vec3 rt_area_light_point(const rt_light *l, rt_vec2 u);

/* cos(theta_L) towards a point that lies along -to_light (unit) from the light: the
 * light's normal against the direction it emits in, 0 behind the square; 1 for a
 * degenerate square (no normal), which emits to every side. */
rt_real rt_area_light_cosine(const rt_light *l, rt_vec3 to_light);

/* The nearest area light whose square the ray meets from its emitting side within
 * (t_min, t_max), lowest index on ties: true with its index and t. */
bool rt_area_light_seen(const rt_scene *scene, const rt_ray *ray, uint32_t *light, rt_real *t);

#endif
