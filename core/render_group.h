/* The tile renderer's group path (render_group.c), used by rt_render_rect when it
 * applies; the image is the same bytes as the pixel-by-pixel path's. */
#ifndef RT_RENDER_GROUP_H
#define RT_RENDER_GROUP_H

#include "render.h"

/* Whether the group path applies: Whitted tracing with a constant sample count and no
 * ray log. */
bool rt_render_groups_apply(const rt_tracer *tr);

/* rt_render_rect by groups of pixels. */
void rt_render_rect_groups(const rt_tracer *tr, rt_rect area, rt_rect held, uint8_t *rgb);

#endif
