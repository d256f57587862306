/* Whitted renders with a constant sample count, a group of pixels at a time. A camera
 * ray is made of a part that depends on its image column and one that depends on its row
 * (camera.h), so the group makes each part once. Where the kernel has packets, the
 * group's camera rays go through the stream query together, then the shadow rays of
 * their hits, light by light; then each sample is traced as rt_trace traces it, with
 * those first queries' results and the hits' shading frames handed in (rt_primed).
 * The stream queries give every ray exactly what the one-ray queries give it, and a
 * pixel sums its samples in the same order as rt_render_pixel, so the image is the same
 * bytes. See render_group.h. */
#include "render_group.h"
#include "bvh.h"
#include "camera.h"
#include "shading.h"

/* Pixels are taken in groups of GROUP_W x GROUP_H (packets of neighbours), each pixel's
 * samples in order; BATCH samples are traced together. */
#define GROUP_W 8
#define GROUP_H 8
#define BATCH 64

bool rt_render_groups_apply(const rt_tracer *tr)
{
    const rt_trace_settings *set = &tr->scene->camera.trace;
    return !tr->log && !tr->primed && set->monte_carlo == 0 && set->sample_count_type == 0;
}

/* The camera rays' parts of a group whose top left pixel is (x0, y0), with 2^side_log
 * cells across a pixel: cell a of column x0 + c at x_part[(c << side_log) + a], cell b
 * of row y0 + r at y_part[(r << side_log) + b]. */
typedef struct {
    uint32_t x0, y0, side_log;
    rt_vec3 x_part[GROUP_W << RT_MAX_SPP_INDEX], y_part[GROUP_H << RT_MAX_SPP_INDEX];
} ray_parts;

static void make_parts(const rt_camera *cam, rt_rect group, ray_parts *parts)
{
    uint32_t log = parts->side_log, side = 1u << log;
    parts->x0 = group.x0;
    parts->y0 = group.y0;
    for (uint32_t x = group.x0; x < group.x1; x++)
        for (uint32_t a = 0; a < side; a++)
            parts->x_part[((x - group.x0) << log) + a] = rt_camera_x_part(cam, rt_camera_grid_x(cam, x, a, side));
    for (uint32_t y = group.y0; y < group.y1; y++)
        for (uint32_t b = 0; b < side; b++)
            parts->y_part[((y - group.y0) << log) + b] = rt_camera_y_part(cam, rt_camera_grid_y(cam, y, b, side));
}

/* rt_camera_pixel_ray(cam, column, row, sample), from the group's parts. */
static rt_ray sample_ray(const rt_camera *cam, const ray_parts *parts, uint32_t column, uint32_t row, uint32_t sample)
{
    uint32_t log = parts->side_log;
    return rt_camera_part_ray(cam, parts->x_part[((column - parts->x0) << log) + (sample & ((1u << log) - 1))],
                              parts->y_part[((row - parts->y0) << log) + (sample >> log)]);
}

/* The colours of n <= BATCH camera rays, each as rt_trace gives it, traced in packets. */
static void trace_packets(const rt_tracer *tr, const rt_ray *ray, uint32_t n, rt_vec3 *color)
{
    const rt_scene *scene = tr->scene;
    rt_ray_setup rs[BATCH], shadow[BATCH];
    rt_scene_hit shadow_hit[BATCH];
    bool found[BATCH];
    uint32_t owner[BATCH];
    rt_primed primed[BATCH];
    rt_shading_point p[BATCH];
    rt_tracer with = *tr;
    for (uint32_t i = 0; i < n; i++) rs[i] = rt_scene_prepare(scene, ray[i]);
    rt_scene_hit hit[BATCH];
    rt_scene_nearest_stream(scene, rs, n, hit, found);
    for (uint32_t i = 0; i < n; i++) {
        primed[i].found = found[i];
        primed[i].hit = hit[i];
        primed[i].point = NULL;
        for (int l = 0; l < RT_PRIMED_LIGHTS; l++) primed[i].shadow[l] = 0;
        /* The shading point as the trace would make it (no query: the hit is known); the
         * trace then takes it as it is. */
        with.primed = &primed[i];
        if (found[i] && rt_shading_hit(&with, &ray[i], RT_RAY_CAMERA, RT_NO_PARENT, 0, &p[i])) primed[i].point = &p[i];
    }
    uint32_t lights = scene->light_count < RT_PRIMED_LIGHTS ? scene->light_count : RT_PRIMED_LIGHTS;
    bool opaque = scene->camera.trace.shadows == 1;
    for (uint32_t l = 0; l < lights; l++) {
        uint32_t m = 0;
        for (uint32_t i = 0; i < n; i++) {
            rt_ray r;
            if (!found[i] || !rt_shading_shadow_ray(tr, l, &p[i], scene->lights[l].position, &r)) continue;
            shadow[m] = rt_scene_prepare(scene, r);
            owner[m++] = i;
        }
        bool blocked[BATCH];
        if (opaque)
            rt_scene_any_stream(scene, shadow, m, blocked);
        else
            rt_scene_nearest_stream(scene, shadow, m, shadow_hit, blocked);
        for (uint32_t j = 0; j < m; j++) {
            primed[owner[j]].shadow[l] = blocked[j] ? 2 : 1;
            if (blocked[j] && !opaque) primed[owner[j]].shadow_hit[l] = shadow_hit[j];
        }
    }
    for (uint32_t i = 0; i < n; i++) {
        with.primed = &primed[i];
        /* A camera ray that hits nothing brings back black, as its trace would. */
        color[i] = found[i] ? rt_trace(&with, ray[i], 0) : rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    }
}

void rt_render_rect_groups(const rt_tracer *tr, rt_rect area, rt_rect held, uint8_t *rgb)
{
    const rt_camera *cam = &tr->scene->camera;
    uint32_t x0 = area.x0, y0 = area.y0, x1 = area.x1, y1 = area.y1, held_width = held.x1 - held.x0;
    uint32_t spp = rt_camera_samples(cam);
    bool packets = tr->use_bvh && rt_bvh_packets(&tr->scene->bvh);
    ray_parts parts;
    parts.side_log = cam->trace.samples_per_pixel_index;
    for (uint32_t gy = y0; gy < y1; gy += GROUP_H)
        for (uint32_t gx = x0; gx < x1; gx += GROUP_W) {
            rt_rect group = {gx, gy, gx + GROUP_W < x1 ? gx + GROUP_W : x1, gy + GROUP_H < y1 ? gy + GROUP_H : y1};
            make_parts(cam, group, &parts);
            /* The group's pixels, in blocks of 4 x 2 so that neighbours share a packet. */
            uint32_t col[GROUP_W * GROUP_H], row[GROUP_W * GROUP_H], pixels = 0;
            for (uint32_t by = gy; by < group.y1; by += 2)
                for (uint32_t bx = gx; bx < group.x1; bx += 4)
                    for (uint32_t y = by; y < by + 2 && y < y1; y++)
                        for (uint32_t x = bx; x < bx + 4 && x < x1; x++) col[pixels] = x, row[pixels++] = y;
            rt_vec3 sum[GROUP_W * GROUP_H];
            for (uint32_t i = 0; i < pixels; i++) sum[i] = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
            /* Samples pixel by pixel, each pixel's in order, BATCH at a time. */
            rt_ray ray[BATCH];
            uint32_t owner[BATCH], n = 0;
            rt_vec3 color[BATCH];
            for (uint32_t i = 0; i < pixels; i++)
                for (uint32_t k = 0; k < spp; k++) {
                    ray[n] = sample_ray(cam, &parts, col[i], row[i], k);
                    owner[n++] = i;
                    if (n < BATCH && !(i == pixels - 1 && k == spp - 1)) continue;
                    if (packets)
                        trace_packets(tr, ray, n, color);
                    else
                        for (uint32_t j = 0; j < n; j++) color[j] = rt_trace(tr, ray[j], 0);
                    for (uint32_t j = 0; j < n; j++) sum[owner[j]] = rt_v3_add(sum[owner[j]], color[j]);
                    n = 0;
                }
            for (uint32_t i = 0; i < pixels; i++) {
                rt_vec3 c = spp == 1 ? sum[i] : rt_v3_div(sum[i], rt_from_int(spp));
                uint8_t *px = rgb + ((size_t)(row[i] - held.y0) * held_width + (col[i] - held.x0)) * 3;
                px[0] = rt_render_color_byte(c.x);
                px[1] = rt_render_color_byte(c.y);
                px[2] = rt_render_color_byte(c.z);
            }
        }
}
