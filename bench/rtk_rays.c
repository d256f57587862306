/* Benchmark rays from an rtk scene; see rtk_rays.h. */
#include "rtk_rays.h"

#include "render.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bench_ray to_bench(rt_ray r)
{
    bench_ray b = {{rt_to_double(r.origin.x), rt_to_double(r.origin.y), rt_to_double(r.origin.z)},
                   {rt_to_double(r.direction.x), rt_to_double(r.direction.y), rt_to_double(r.direction.z)},
                   rt_to_double(r.t_min),
                   r.t_max == RT_REAL_MAX ? INFINITY : rt_to_double(r.t_max)};
    return b;
}

/* The light the shadow rays aim at: the first point light, else the first directional one. */
static const rt_light *pick_light(const rt_scene *scene)
{
    for (uint32_t i = 0; i < scene->light_count; i++)
        if (scene->lights[i].kind == RT_LIGHT_POINT) return &scene->lights[i];
    for (uint32_t i = 0; i < scene->light_count; i++)
        if (scene->lights[i].kind == RT_LIGHT_DIRECTIONAL) return &scene->lights[i];
    return NULL;
}

/* The ray from `point` to the light, as rtk's shader shoots it; false if it has no direction. */
static bool shadow_ray(const rt_light *light, rt_vec3 point, rt_ray *out)
{
    out->origin = point;
    out->t_min = RT_HIT_EPSILON;
    if (light->kind == RT_LIGHT_DIRECTIONAL) {
        out->direction = light->direction;
        out->t_max = RT_REAL_MAX;
        return true;
    }
    rt_vec3 delta = rt_v3_sub(light->position, point);
    rt_real distance = rt_v3_length(delta);
    if (distance == RT_ZERO) return false;
    out->direction = rt_v3_scale(delta, rt_div(RT_ONE, distance));
    out->t_max = distance;
    return true;
}

static bool copy_triangles(const rt_scene *scene, bench_workload *w)
{
    w->vertex_count = scene->vertex_count;
    w->triangle_count = scene->triangle_count;
    w->positions = malloc(3 * (size_t)scene->vertex_count * sizeof(double) + 1);
    w->indices = malloc(3 * (size_t)scene->triangle_count * sizeof(uint32_t) + 1);
    if (!w->positions || !w->indices) return false;
    for (uint32_t v = 0; v < scene->vertex_count; v++) {
        w->positions[3 * v + 0] = rt_to_double(scene->positions[v].x);
        w->positions[3 * v + 1] = rt_to_double(scene->positions[v].y);
        w->positions[3 * v + 2] = rt_to_double(scene->positions[v].z);
    }
    for (uint32_t t = 0; t < scene->triangle_count; t++)
        for (int k = 0; k < 3; k++) w->indices[3 * t + k] = scene->triangles[t].v[k];
    return true;
}

bool bench_make_workload(const char *path, const rt_scene *scene, uint32_t width, uint32_t height, bench_workload *w)
{
    memset(w, 0, sizeof *w);
    if (scene->prim_count != scene->triangle_count || scene->triangle_count == 0) {
        fprintf(stderr, "rtk-bench: %s: the ray benchmark scene must hold triangles only (no spheres or cylinders)\n",
                path);
        return false;
    }
    const rt_light *light = pick_light(scene);
    if (!light) {
        fprintf(stderr, "rtk-bench: %s: the ray benchmark scene needs a point or directional light\n", path);
        return false;
    }
    size_t n = (size_t)width * height;
    w->width = width;
    w->height = height;
    w->primary = malloc(n * sizeof(bench_ray));
    w->shadow = malloc(n * sizeof(bench_ray));
    w->shadow_source = malloc(n * sizeof(uint32_t));
    if (!w->primary || !w->shadow || !w->shadow_source || !copy_triangles(scene, w)) {
        fprintf(stderr, "rtk-bench: out of memory for the workload\n");
        bench_workload_free(w);
        return false;
    }
    rt_real fw = rt_from_int(width), fh = rt_from_int(height), half = RT_C(0.5);
    for (uint32_t row = 0; row < height; row++) {
        uint32_t j = height - 1 - row; /* camera y counts from the bottom (format.md §7.3) */
        rt_real y = rt_div(rt_add(rt_from_int(j), half), fh);
        for (uint32_t col = 0; col < width; col++) {
            rt_real x = rt_div(rt_add(rt_from_int(col), half), fw);
            rt_ray ray = rt_camera_ray(&scene->camera, x, y);
            w->primary[w->primary_count++] = to_bench(ray);
            rt_ray_setup rs = rt_intersect_prepare(ray);
            rt_scene_hit hit;
            if (!rt_scene_nearest(scene, &rs, true, &hit)) continue;
            rt_ray sr;
            if (!shadow_ray(light, rt_v3_madd(ray.origin, ray.direction, hit.hit.t), &sr)) continue;
            w->shadow_source[w->shadow_count] = w->primary_count - 1;
            w->shadow[w->shadow_count++] = to_bench(sr);
        }
    }
    return true;
}
