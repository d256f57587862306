/* The tile renderer's packet path (render_packet.c), used by rt_render_rect when it
 * applies; the image is the same bytes as the pixel-by-pixel path's. */
#ifndef RT_RENDER_PACKET_H
#define RT_RENDER_PACKET_H

#include "render.h"

/* Whether the packet path applies: Whitted tracing with a constant sample count through
 * the BVH, no ray log, and a kernel with packets. */
bool rt_render_packets_apply(const rt_tracer *tr);

/* rt_render_rect by packets. */
void rt_render_rect_packets(const rt_tracer *tr, rt_rect area, rt_rect held, uint8_t *rgb);

#endif
