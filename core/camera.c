/* Camera rays: pinhole, thin lens and orthographic, and the sub-pixel grid; see camera.h. */
#include "camera.h"
#include "sample.h"

/* The image plane sits Focus Distance ahead (format.md §7.2), which is also the plane in
 * focus (§7.5); these vectors span it, the same for every ray. */
void rt_camera_prepare(rt_camera *cam)
{
    rt_real focus = cam->trace.focus_distance > RT_ZERO ? cam->trace.focus_distance : RT_ONE;
    cam->plane_forward = rt_v3_scale(cam->forward, focus);
    cam->plane_up = rt_v3_scale(cam->up, rt_mul(focus, cam->tan_half_fov));
    cam->plane_right = rt_v3_scale(cam->right, rt_mul(rt_mul(focus, cam->tan_half_fov), cam->aspect));
}

rt_vec3 rt_camera_x_part(const rt_camera *cam, rt_real x)
{
    rt_real sx = rt_sub(rt_mul(RT_C(2.0), x), RT_ONE);
    /* Perspective: the image-plane point's offset from the eye is this plus the y part;
     * orthographic: the origin's offset from the eye over a view Orthographic View Width
     * wide (format.md §7.4). */
    if (cam->perspective) return rt_v3_add(cam->plane_forward, rt_v3_scale(cam->plane_right, sx));
    return rt_v3_scale(cam->right, rt_mul(sx, rt_mul(cam->ortho_width, RT_C(0.5))));
}

rt_vec3 rt_camera_y_part(const rt_camera *cam, rt_real y)
{
    rt_real sy = rt_sub(rt_mul(RT_C(2.0), y), RT_ONE);
    if (cam->perspective) return rt_v3_scale(cam->plane_up, sy);
    return rt_v3_scale(cam->up, rt_mul(sy, rt_div(rt_mul(cam->ortho_width, RT_C(0.5)), cam->aspect)));
}

rt_ray rt_camera_ray(const rt_camera *cam, rt_real x, rt_real y)
{
    return rt_camera_part_ray(cam, rt_camera_x_part(cam, x), rt_camera_y_part(cam, y));
}

rt_ray rt_camera_lens_ray(const rt_camera *cam, rt_real x, rt_real y, rt_vec2 lens)
{
    if (!cam->perspective || !(cam->trace.aperture_size > RT_ZERO)) return rt_camera_ray(cam, x, y);
    rt_vec2 d = rt_sample_disc(lens);
    rt_real radius = rt_mul(cam->trace.aperture_size, RT_C(0.5));
    rt_vec3 shift = rt_v3_add(rt_v3_scale(cam->right, rt_mul(d.u, radius)), rt_v3_scale(cam->up, rt_mul(d.v, radius)));
    /* From a point of the lens towards the same point of the plane in focus. */
    rt_ray ray = {rt_v3_add(cam->eye, shift),
                  rt_v3_normalize(rt_v3_sub(rt_v3_add(rt_camera_x_part(cam, x), rt_camera_y_part(cam, y)), shift)),
                  RT_HIT_EPSILON, RT_REAL_MAX};
    return ray;
}

uint32_t rt_camera_samples(const rt_camera *cam) { return 1u << (2 * cam->trace.samples_per_pixel_index); }

/* The centre of cell i of `side` cells across a pixel, in (0, 1); with one cell 0.5,
 * exactly what the division gives. */
static rt_real cell_centre(uint32_t i, uint32_t side)
{
    return side == 1 ? RT_C(0.5) : rt_div(rt_add(rt_from_int(i), RT_C(0.5)), rt_from_int(side));
}

rt_real rt_camera_grid_x(const rt_camera *cam, uint32_t column, uint32_t a, uint32_t side)
{
    return rt_div(rt_add(rt_from_int(column), cell_centre(a, side)), rt_from_int(cam->width));
}

rt_real rt_camera_grid_y(const rt_camera *cam, uint32_t row, uint32_t b, uint32_t side)
{
    return rt_div(rt_add(rt_from_int(rt_camera_row_from_bottom(cam, row)), cell_centre(b, side)),
                  rt_from_int(cam->height));
}

rt_ray rt_camera_grid_ray(const rt_camera *cam, uint32_t column, uint32_t row, uint32_t a, uint32_t b, uint32_t side)
{
    return rt_camera_ray(cam, rt_camera_grid_x(cam, column, a, side), rt_camera_grid_y(cam, row, b, side));
}

rt_ray rt_camera_pixel_ray(const rt_camera *cam, uint32_t column, uint32_t row, uint32_t sample)
{
    /* 4^n samples on a regular 2^n x 2^n grid of sub-pixel centres (format.md §10.1),
     * numbered row by row from the bottom left. */
    uint32_t side = 1u << cam->trace.samples_per_pixel_index;
    return rt_camera_grid_ray(cam, column, row, sample % side, sample / side, side);
}
