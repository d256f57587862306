/* How many samples a pixel takes and how they are averaged (format.md §10.2, §11):
 * a constant count, adaptive recursive subdivision, or samples until the mean's
 * standard error is small. */
#include "path_trace.h"
#include "render.h"

/* One Monte Carlo sample: pixel position, lens point and path, with every 2D draw in
 * one of 4^strata_log strata in stratified mode (Monte Carlo 2), uniform otherwise. */
static rt_vec3 random_sample(const rt_tracer *tr, uint32_t column, uint32_t row, uint32_t sample, uint32_t strata_log)
{
    const rt_camera *cam = &tr->scene->camera;
    rt_sampler s = {rt_rng_pixel_key(column, row), sample,
                    cam->trace.monte_carlo == RT_MONTE_CARLO_STRATIFIED ? strata_log : 0};
    rt_vec2 u = rt_sample_2d(&s, 0, RT_PURPOSE_PIXEL);
    uint32_t j = rt_camera_row_from_bottom(cam, row);
    rt_real x = rt_div(rt_add(rt_from_int(column), u.u), rt_from_int(cam->width));
    rt_real y = rt_div(rt_add(rt_from_int(j), u.v), rt_from_int(cam->height));
    return rt_path_trace(tr, &s, rt_camera_lens_ray(cam, x, y, rt_sample_2d(&s, 0, RT_PURPOSE_LENS)));
}

rt_vec3 rt_render_sample(const rt_tracer *tr, uint32_t column, uint32_t row, uint32_t sample)
{
    const rt_camera *cam = &tr->scene->camera;
    if (cam->trace.monte_carlo == RT_MONTE_CARLO_OFF)
        return rt_trace(tr, rt_camera_pixel_ray(cam, column, row, sample), 0);
    return random_sample(tr, column, row, sample, cam->trace.samples_per_pixel_index);
}

static rt_vec3 constant_pixel(const rt_tracer *tr, uint32_t column, uint32_t row)
{
    uint32_t n = rt_camera_samples(&tr->scene->camera);
    rt_vec3 sum = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO);
    for (uint32_t k = 0; k < n; k++) sum = rt_v3_add(sum, rt_render_sample(tr, column, row, k));
    return n == 1 ? sum : rt_v3_div(sum, rt_from_int(n));
}

/* ---- Adaptive recursive (type 1, deterministic mode) ---- */

typedef struct {
    const rt_tracer *tr;
    uint32_t column, j; /* j: buffer row, from the bottom */
    uint32_t min_level, max_level;
    rt_real threshold_squared;
} adaptive;

/* The colour at point (fx, fy) of the pixel, both in [0, 1]. */
static rt_vec3 point_color(const adaptive *a, rt_real fx, rt_real fy)
{
    const rt_camera *cam = &a->tr->scene->camera;
    rt_real x = rt_div(rt_add(rt_from_int(a->column), fx), rt_from_int(cam->width));
    rt_real y = rt_div(rt_add(rt_from_int(a->j), fy), rt_from_int(cam->height));
    return rt_trace(a->tr, rt_camera_ray(cam, x, y), 0);
}

static bool corners_differ(const adaptive *a, const rt_vec3 *c)
{
    for (int i = 0; i < 4; i++)
        for (int k = i + 1; k < 4; k++) {
            rt_vec3 d = rt_v3_sub(c[i], c[k]);
            if (rt_v3_dot(d, d) > a->threshold_squared) return true;
        }
    return false;
}

/* The mean colour of the square at (x0, y0) of side `size` (pixel units) whose corner
 * colours are c (bottom left, bottom right, top left, top right): their average,
 * or the average of its four quadrants while the corners differ. */
static rt_vec3 refine(const adaptive *a, rt_real x0, rt_real y0, rt_real size, const rt_vec3 *c, uint32_t level)
{
    rt_real quarter = RT_C(0.25);
    if (level >= a->max_level || (level >= a->min_level && !corners_differ(a, c)))
        return rt_v3_scale(rt_v3_add(rt_v3_add(c[0], c[1]), rt_v3_add(c[2], c[3])), quarter);
    rt_real h = rt_mul(size, RT_C(0.5));
    rt_real xm = rt_add(x0, h), ym = rt_add(y0, h), x1 = rt_add(x0, size), y1 = rt_add(y0, size);
    rt_vec3 bottom = point_color(a, xm, y0), left = point_color(a, x0, ym), centre = point_color(a, xm, ym);
    rt_vec3 right = point_color(a, x1, ym), top = point_color(a, xm, y1);
    rt_vec3 q0[4] = {c[0], bottom, left, centre}, q1[4] = {bottom, c[1], centre, right};
    rt_vec3 q2[4] = {left, centre, c[2], top}, q3[4] = {centre, right, top, c[3]};
    rt_vec3 sum = rt_v3_add(rt_v3_add(refine(a, x0, y0, h, q0, level + 1), refine(a, xm, y0, h, q1, level + 1)),
                            rt_v3_add(refine(a, x0, ym, h, q2, level + 1), refine(a, xm, ym, h, q3, level + 1)));
    return rt_v3_scale(sum, quarter);
}

/* Splits the pixel into quadrants, recursively, while the corner colours of a square
 * differ by more than Difference Threshold: at least 4^min and at most 4^(max+1)
 * squares (the Minimum and Maximum Samples indices). */
static rt_vec3 adaptive_pixel(const rt_tracer *tr, uint32_t column, uint32_t row)
{
    const rt_camera *cam = &tr->scene->camera;
    adaptive a = {tr,
                  column,
                  rt_camera_row_from_bottom(cam, row),
                  cam->trace.min_samples_index,
                  cam->trace.max_samples_index + 1,
                  rt_mul(cam->trace.difference_threshold, cam->trace.difference_threshold)};
    if (a.min_level > a.max_level) a.min_level = a.max_level;
    rt_vec3 c[4] = {point_color(&a, RT_ZERO, RT_ZERO), point_color(&a, RT_ONE, RT_ZERO),
                    point_color(&a, RT_ZERO, RT_ONE), point_color(&a, RT_ONE, RT_ONE)};
    return refine(&a, RT_ZERO, RT_ZERO, RT_ONE, c, 0);
}

/* ---- Standard error (type 2) ---- */

/* Samples until the standard error of the mean is below Std. Error Threshold in every
 * channel, between 4^min and 4^(max+1) samples. Sample k takes stratum permute(k) of
 * a grid with one cell per allowed sample, so every prefix spreads over the pixel. */
static rt_vec3 std_error_pixel(const rt_tracer *tr, uint32_t column, uint32_t row)
{
    const rt_camera *cam = &tr->scene->camera;
    uint32_t grid_log = cam->trace.max_samples_index + 1, side = 1u << grid_log, most = side * side;
    uint32_t least = 1u << (2 * cam->trace.min_samples_index);
    if (least > most) least = most;
    rt_real t2 = rt_mul(cam->trace.std_error_threshold, cam->trace.std_error_threshold);
    uint64_t key = rt_rng_pixel_key(column, row);
    rt_vec3 sum = rt_v3(RT_ZERO, RT_ZERO, RT_ZERO), sum_sq = sum;
    uint32_t n = 0;
    while (n < most) {
        rt_vec3 c;
        if (cam->trace.monte_carlo != RT_MONTE_CARLO_OFF) {
            c = random_sample(tr, column, row, n, grid_log);
        } else {
            uint32_t cell = rt_rng_permute(n, 2 * grid_log, key);
            c = rt_trace(tr, rt_camera_grid_ray(cam, column, row, cell & (side - 1), cell >> grid_log, side), 0);
        }
        sum = rt_v3_add(sum, c);
        sum_sq = rt_v3_add(sum_sq, rt_v3_mul(c, c));
        n++;
        if (n < least || n < 2) continue;
        /* Squared standard error per channel: (sum_sq - sum^2 / n) / ((n - 1) n). */
        rt_real count = rt_from_int(n), scale = rt_mul(count, rt_from_int(n - 1));
        rt_vec3 spread = rt_v3_sub(sum_sq, rt_v3_div(rt_v3_mul(sum, sum), count));
        rt_vec3 se2 = rt_v3_div(spread, scale);
        if (rt_max(rt_max(se2.x, se2.y), se2.z) < t2) break;
    }
    return rt_v3_div(sum, rt_from_int(n));
}

rt_vec3 rt_render_pixel(const rt_tracer *tr, uint32_t column, uint32_t row)
{
    const rt_trace_settings *set = &tr->scene->camera.trace;
    if (set->sample_count_type == RT_SAMPLES_STD_ERROR) return std_error_pixel(tr, column, row);
    /* The skeleton turns adaptive recursion off in Monte Carlo mode (format.md §10.2). */
    if (set->sample_count_type == RT_SAMPLES_ADAPTIVE && set->monte_carlo == RT_MONTE_CARLO_OFF)
        return adaptive_pixel(tr, column, row);
    return constant_pixel(tr, column, row);
}
