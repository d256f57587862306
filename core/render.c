/* Camera rays and pixel sampling; see render.h. */
#include "render.h"

rt_ray rt_camera_ray(const rt_camera *cam, rt_real x, rt_real y)
{
    rt_real sx = rt_sub(rt_mul(RT_C(2.0), x), RT_ONE), sy = rt_sub(rt_mul(RT_C(2.0), y), RT_ONE);
    rt_ray ray;
    ray.t_min = RT_HIT_EPSILON;
    ray.t_max = RT_REAL_MAX;
    if (!cam->perspective) {
        /* Parallel rays over a view Orthographic View Width wide (format §8.3). */
        rt_real half_w = rt_mul(cam->ortho_width, RT_C(0.5));
        rt_real half_h = rt_div(half_w, cam->aspect);
        ray.origin = rt_v3_add(cam->eye, rt_v3_add(rt_v3_scale(cam->right, rt_mul(sx, half_w)),
                                                   rt_v3_scale(cam->up, rt_mul(sy, half_h))));
        ray.direction = cam->forward;
        return ray;
    }
    /* The image plane sits Focus Distance ahead; the direction does not depend on it
     * (up to rounding), but the skeleton builds it this way. */
    rt_real focus = cam->trace.focus_distance > RT_ZERO ? cam->trace.focus_distance : RT_ONE;
    rt_vec3 f = rt_v3_scale(cam->forward, focus);
    rt_vec3 u = rt_v3_scale(cam->up, rt_mul(focus, cam->tan_half_fov));
    rt_vec3 r = rt_v3_scale(cam->right, rt_mul(rt_mul(focus, cam->tan_half_fov), cam->aspect));
    rt_vec3 offset = rt_v3_add(rt_v3_add(f, rt_v3_scale(r, sx)), rt_v3_scale(u, sy));
    ray.origin = cam->eye;
    ray.direction = rt_v3_normalize(offset);
    return ray;
}

uint32_t rt_samples_per_pixel(const rt_camera *cam)
{
    return 1u << (2 * cam->trace.samples_per_pixel_index);
}

rt_ray rt_pixel_ray(const rt_camera *cam, uint32_t column, uint32_t row, uint32_t sample)
{
    /* 4^n samples on a regular 2^n x 2^n grid of sub-pixel centres (format §11.1),
     * numbered row by row from the bottom left. */
    uint32_t side = 1u << cam->trace.samples_per_pixel_index;
    uint32_t a = sample % side, b = sample / side;
    uint32_t j = cam->height - 1 - row; /* buffer rows count from the bottom */
    rt_real s = rt_from_int(side);
    rt_real x = rt_div(rt_add(rt_from_int(column), rt_div(rt_add(rt_from_int(a), RT_C(0.5)), s)), rt_from_int(cam->width));
    rt_real y = rt_div(rt_add(rt_from_int(j), rt_div(rt_add(rt_from_int(b), RT_C(0.5)), s)), rt_from_int(cam->height));
    return rt_camera_ray(cam, x, y);
}

rt_vec3 rt_render_pixel(const rt_tracer *tr, uint32_t column, uint32_t row)
{
    const rt_camera *cam = &tr->scene->camera;
    uint32_t n = rt_samples_per_pixel(cam);
    rt_vec3 sum = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    for (uint32_t k = 0; k < n; k++) sum = rt_v3_add(sum, rt_trace(tr, rt_pixel_ray(cam, column, row, k), 0));
    if (n == 1) return sum;
    rt_real count = rt_from_int(n);
    return rt_v3(rt_div(sum.x, count), rt_div(sum.y, count), rt_div(sum.z, count));
}

uint8_t rt_color_to_byte(rt_real c)
{
    /* NaN would slip through the clamp; it becomes 0. */
    if (!(c > RT_ZERO)) return 0;
    return rt_unit_to_byte(rt_min(c, RT_ONE));
}

void rt_render_region(const rt_tracer *tr, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint8_t *rgb)
{
    uint32_t width = tr->scene->camera.width;
    for (uint32_t row = y0; row < y1; row++)
        for (uint32_t col = x0; col < x1; col++) {
            rt_vec3 c = rt_render_pixel(tr, col, row);
            uint8_t *p = rgb + ((size_t)row * width + col) * 3;
            p[0] = rt_color_to_byte(c.x);
            p[1] = rt_color_to_byte(c.y);
            p[2] = rt_color_to_byte(c.z);
        }
}
