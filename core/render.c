/* Pixels into bytes, region by region; see render.h. */
#include "render.h"

uint8_t rt_render_color_byte(rt_real c)
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
            p[0] = rt_render_color_byte(c.x);
            p[1] = rt_render_color_byte(c.y);
            p[2] = rt_render_color_byte(c.z);
        }
}
