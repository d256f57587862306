/* Camera rays, pixels and tiles: the kernel's entry point for rendering. */
#ifndef RT_RENDER_H
#define RT_RENDER_H

#include "trace.h"

/* The camera ray through image point (x, y) in [0,1]^2, y = 0 at the bottom (format §8). */
rt_ray rt_camera_ray(const rt_camera *cam, rt_real x, rt_real y);
/* The same through the point `lens` ([0,1)^2, mapped to the disc of diameter Aperture
 * Size) of a thin lens focused at Focus Distance (format §8.4); a pinhole without aperture. */
rt_ray rt_lens_ray(const rt_camera *cam, rt_real x, rt_real y, rt_vec2 lens);
/* The ray through the centre of cell (a, b) of a side x side grid over pixel (column, row),
 * row 0 = top, cell (0, 0) at the pixel's bottom left. */
rt_ray rt_grid_ray(const rt_camera *cam, uint32_t column, uint32_t row, uint32_t a, uint32_t b, uint32_t side);

/* 4^(Samples Per Pixel) */
uint32_t rt_samples_per_pixel(const rt_camera *cam);
/* The camera ray of sample `sample` (0 .. samples-1) of pixel (column, row), row 0 = top. */
rt_ray rt_pixel_ray(const rt_camera *cam, uint32_t column, uint32_t row, uint32_t sample);

/* The colour of sample `sample` of pixel (column, row) as the constant sample count
 * draws it: rt_trace of rt_pixel_ray, or in Monte Carlo mode one jittered, lens- and
 * light-sampled path (the debugger's view of one sample). Not clamped. */
rt_vec3 rt_render_sample(const rt_tracer *tr, uint32_t column, uint32_t row, uint32_t sample);

/* The unclamped colour of pixel (column, row), row 0 = top of the image, with the
 * camera's sample count type: constant, adaptive recursive or standard error (§11.1). */
rt_vec3 rt_render_pixel(const rt_tracer *tr, uint32_t column, uint32_t row);

/* Renders columns [x0, x1) of rows [y0, y1) into rgb (width * height * 3 bytes, row 0
 * at the top), each channel quantised as the sample solution does (format §11.3). */
void rt_render_region(const rt_tracer *tr, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint8_t *rgb);

/* One 8-bit channel from an unclamped colour value. */
uint8_t rt_color_to_byte(rt_real c);

#endif
