/* Camera rays (format.md §7): where each pixel and sample looks from and towards. */
#ifndef RT_CAMERA_H
#define RT_CAMERA_H

#include "ray.h"
#include "scene.h"

/* The image's y counts rows from the bottom (format.md §7), the buffer's from the top. */
static inline uint32_t rt_camera_row_from_bottom(const rt_camera *cam, uint32_t row) { return cam->height - 1 - row; }

/* Fills the camera's plane_* vectors from its other fields (the scene build calls it). */
void rt_camera_prepare(rt_camera *cam);
/* The camera ray through image point (x, y) in [0,1]^2, y = 0 at the bottom (format.md §7). */
rt_ray rt_camera_ray(const rt_camera *cam, rt_real x, rt_real y);
/* The same through the point `lens` ([0,1)^2, mapped to the disc of diameter Aperture
 * Size) of a thin lens focused at Focus Distance (format.md §7.5); a pinhole without aperture. */
rt_ray rt_camera_lens_ray(const rt_camera *cam, rt_real x, rt_real y, rt_vec2 lens);
/* rt_camera_ray(cam, x, y) is rt_camera_part_ray(cam, rt_camera_x_part(cam, x),
 * rt_camera_y_part(cam, y)), the same bits: a part made once serves every ray through
 * its image column or row. */
rt_vec3 rt_camera_x_part(const rt_camera *cam, rt_real x);
rt_vec3 rt_camera_y_part(const rt_camera *cam, rt_real y);
static inline rt_ray rt_camera_part_ray(const rt_camera *cam, rt_vec3 x_part, rt_vec3 y_part)
{
    rt_vec3 offset = rt_v3_add(x_part, y_part);
    rt_ray ray;
    ray.t_min = RT_HIT_EPSILON;
    ray.t_max = RT_REAL_MAX;
    if (!cam->perspective) {
        ray.origin = rt_v3_add(cam->eye, offset);
        ray.direction = cam->forward;
        return ray;
    }
    /* Without a lens the direction does not depend on Focus Distance (up to rounding). */
    ray.origin = cam->eye;
    ray.direction = rt_v3_normalize(offset);
    return ray;
}
/* The ray through the centre of cell (a, b) of a side x side grid over pixel (column, row),
 * row 0 = top, cell (0, 0) at the pixel's bottom left: rt_camera_ray at the image point
 * (rt_camera_grid_x(cam, column, a, side), rt_camera_grid_y(cam, row, b, side)). */
rt_ray rt_camera_grid_ray(const rt_camera *cam, uint32_t column, uint32_t row, uint32_t a, uint32_t b, uint32_t side);
rt_real rt_camera_grid_x(const rt_camera *cam, uint32_t column, uint32_t a, uint32_t side);
rt_real rt_camera_grid_y(const rt_camera *cam, uint32_t row, uint32_t b, uint32_t side);

/* 4^(Samples Per Pixel) */
uint32_t rt_camera_samples(const rt_camera *cam);
/* The camera ray of sample `sample` (0 .. samples-1) of pixel (column, row), row 0 = top. */
rt_ray rt_camera_pixel_ray(const rt_camera *cam, uint32_t column, uint32_t row, uint32_t sample);

#endif
