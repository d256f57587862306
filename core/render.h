/* Pixels and regions: the kernel's entry point for rendering (render.c, render_pixel.c). */
#ifndef RT_RENDER_H
#define RT_RENDER_H

#include "camera.h"
#include "trace.h"

/* The colour of sample `sample` of pixel (column, row) as the constant sample count
 * draws it: rt_trace of rt_camera_pixel_ray, or in Monte Carlo mode one jittered, lens- and
 * light-sampled path (the debugger's view of one sample). Not clamped. */
rt_vec3 rt_render_sample(const rt_tracer *tr, uint32_t column, uint32_t row, uint32_t sample);

/* The unclamped colour of pixel (column, row), row 0 = top of the image, with the
 * camera's sample count type: constant, adaptive recursive or standard error (format.md §10). */
rt_vec3 rt_render_pixel(const rt_tracer *tr, uint32_t column, uint32_t row);

/* Renders columns [x0, x1) of rows [y0, y1) into rgb (width * height * 3 bytes, row 0
 * at the top), each channel quantised as the sample solution does (format.md §10.5). */
void rt_render_region(const rt_tracer *tr, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint8_t *rgb);

/* A half-open pixel rectangle of the frame: columns [x0, x1), rows [y0, y1), row 0 at the top. */
typedef struct {
    uint32_t x0, y0, x1, y1;
} rt_rect;

/* rt_render_region into a buffer that holds only the frame's rectangle `held` (row by row,
 * (held.x1 - held.x0) * 3 bytes a row), which contains `area`: a part of a large frame
 * needs no buffer for the whole frame. */
void rt_render_rect(const rt_tracer *tr, rt_rect area, rt_rect held, uint8_t *rgb);

/* One 8-bit channel from an unclamped colour value. */
uint8_t rt_render_color_byte(rt_real c);

#endif
