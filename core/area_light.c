/* Area lights in Monte Carlo mode; see area_light.h. The square is corner + u edge_u +
 * v edge_v, u, v in [0,1], and its normal is the unit normalize(edge_v x edge_u). */
#include "area_light.h"

rt_vec3 rt_area_light_point(const rt_light *l, rt_vec2 u)
{
    return rt_v3_add(l->corner, rt_v3_add(rt_v3_scale(l->edge_u, u.u), rt_v3_scale(l->edge_v, u.v)));
}

rt_real rt_area_light_cosine(const rt_light *l, rt_vec3 to_light)
{
    if (rt_v3_is_zero(l->normal)) return RT_ONE;
    return rt_max(rt_neg(rt_v3_dot(l->normal, to_light)), RT_ZERO);
}

/* Where the ray crosses the square's plane from the emitting side, if inside the square. */
static bool square_hit(const rt_light *l, const rt_ray *ray, rt_real *t)
{
    rt_real facing = rt_v3_dot(l->normal, ray->direction);
    /* A degenerate square (zero normal) has no area to meet. */
    if (!(facing < RT_ZERO)) return false;
    rt_real along = rt_div(rt_v3_dot(l->normal, rt_v3_sub(l->corner, ray->origin)), facing);
    if (!(along > ray->t_min && along < ray->t_max)) return false;
    rt_vec3 w = rt_v3_sub(rt_v3_madd(ray->origin, ray->direction, along), l->corner);
    /* w = u edge_u + v edge_v: n.(edge_v x w) = u area, n.(w x edge_u) = v area. */
    rt_real area = rt_v3_dot(l->normal, rt_v3_cross(l->edge_v, l->edge_u));
    rt_real u = rt_v3_dot(l->normal, rt_v3_cross(l->edge_v, w));
    rt_real v = rt_v3_dot(l->normal, rt_v3_cross(w, l->edge_u));
    if (!(u >= RT_ZERO && u <= area && v >= RT_ZERO && v <= area)) return false;
    *t = along;
    return true;
}

bool rt_area_light_seen(const rt_scene *scene, const rt_ray *ray, uint32_t *light, rt_real *t)
{
    bool seen = false;
    for (uint32_t i = 0; i < scene->light_count; i++) {
        rt_real ti;
        if (scene->lights[i].kind != RT_LIGHT_AREA || !square_hit(&scene->lights[i], ray, &ti)) continue;
        if (seen && !(ti < *t)) continue;
        seen = true;
        *light = i;
        *t = ti;
    }
    return seen;
}
