/* Pixels into bytes, region by region; see render.h. */
#include "render.h"
#include "invariant.h"
#include "render_group.h"

uint8_t rt_render_color_byte(rt_real c)
{
    /* NaN would slip through the clamp; it becomes 0. */
    if (!(c > RT_ZERO)) return 0;
    return rt_unit_to_byte(rt_min(c, RT_ONE));
}

void rt_render_region(const rt_tracer *tr, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint8_t *rgb)
{
    rt_rect frame = {0, 0, tr->scene->camera.width, tr->scene->camera.height};
    rt_render_rect(tr, (rt_rect){x0, y0, x1, y1}, frame, rgb);
}

void rt_render_rect(const rt_tracer *tr, rt_rect area, rt_rect held, uint8_t *rgb)
{
    RT_ASSERT(held.x0 <= area.x0 && area.x0 <= area.x1 && area.x1 <= held.x1 && held.x1 <= tr->scene->camera.width);
    RT_ASSERT(held.y0 <= area.y0 && area.y0 <= area.y1 && area.y1 <= held.y1 && held.y1 <= tr->scene->camera.height);
    if (rt_render_groups_apply(tr)) {
        rt_render_rect_groups(tr, area, held, rgb);
        return;
    }
    uint32_t width = held.x1 - held.x0;
    for (uint32_t row = area.y0; row < area.y1; row++)
        for (uint32_t col = area.x0; col < area.x1; col++) {
            rt_vec3 c = rt_render_pixel(tr, col, row);
            uint8_t *p = rgb + ((size_t)(row - held.y0) * width + (col - held.x0)) * 3;
            p[0] = rt_render_color_byte(c.x);
            p[1] = rt_render_color_byte(c.y);
            p[2] = rt_render_color_byte(c.z);
        }
}
