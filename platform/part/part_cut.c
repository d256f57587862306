/* rtp_part_cut; see part_cut.h. */
#include "part/part_cut.h"

#include "mem/mem.h"
#include "raylog.h"
#include "thread/pool.h"

/* Rays and light terms one estimated sample may log; past that it counts as this many. */
#define RTP_CUT_LOG_CAPACITY 4096u

typedef struct {
    const rt_scene *scene;
    uint32_t step_x, step_y; /* grid pitch in pixels */
    uint64_t *band_cost;     /* per grid row: the summed cost of its pixels */
    rt_ray_log *logs;        /* one per worker */
} estimate;

/* Job: the cost of grid row `index`, sampled at the middle of each step. */
static void estimate_row(void *arg, uint32_t index, uint32_t worker)
{
    estimate *e = arg;
    const rt_camera *cam = &e->scene->camera;
    rt_ray_log *log = &e->logs[worker];
    rt_tracer tracer = {.scene = e->scene, .use_bvh = true, .log = log};
    uint32_t y0 = index * e->step_y, y1 = cam->height - y0 > e->step_y ? y0 + e->step_y : cam->height;
    uint32_t row = y0 + (y1 - y0) / 2;
    uint64_t cost = 0;
    for (uint32_t x0 = 0; x0 < cam->width; x0 += e->step_x) {
        uint32_t x1 = cam->width - x0 > e->step_x ? x0 + e->step_x : cam->width;
        log->ray_count = log->light_count = 0;
        log->overflow = false;
        rt_render_sample(&tracer, x0 + (x1 - x0) / 2, row, 0);
        cost += 1 + log->ray_count;
    }
    e->band_cost[index] = cost;
}

static uint32_t ceil_div(uint32_t a, uint32_t b) { return a / b + (a % b != 0); }

/* Splits the rows by cumulative cost: band i starts at the first row where the cost
 * before it reaches i/count of the total, each band keeping at least one row. */
static void cut_rows(const estimate *e, uint32_t height, uint32_t count, uint32_t *starts)
{
    uint64_t total = 0; /* every row costs its grid row's estimate */
    for (uint32_t row = 0; row < height; row++) total += e->band_cost[row / e->step_y];
    starts[0] = 0;
    uint64_t before = 0; /* cost of the rows above `row` */
    uint32_t row = 0;
    for (uint32_t i = 1; i < count; i++) {
        while (row < height && before * count < total * i) before += e->band_cost[row++ / e->step_y];
        uint32_t start = row;
        if (start < starts[i - 1] + 1) start = starts[i - 1] + 1;
        if (start > height - (count - i)) start = height - (count - i);
        starts[i] = start;
    }
    starts[count] = height;
}

bool rtp_part_cut(const rt_scene *scene, uint32_t count, uint32_t threads, uint32_t *starts)
{
    const rt_camera *cam = &scene->camera;
    estimate e = {scene, ceil_div(cam->width, RTP_CUT_COLUMNS), ceil_div(cam->height, RTP_CUT_ROWS), NULL, NULL};
    uint32_t bands = ceil_div(cam->height, e.step_y);
    rtp_pool *pool = rtp_pool_open(threads);
    const rt_workers *workers = rtp_pool_workers(pool);
    uint32_t n = rt_workers_count(workers);
    e.band_cost = rtp_mem_calloc(bands, sizeof *e.band_cost, "the cut's estimate");
    e.logs = rtp_mem_calloc(n, sizeof *e.logs, "the cut's ray logs");
    bool ok = e.band_cost && e.logs;
    for (uint32_t w = 0; ok && w < n; w++) {
        e.logs[w].rays = rtp_mem_alloc(RTP_CUT_LOG_CAPACITY * sizeof *e.logs[w].rays, "the cut's ray logs");
        e.logs[w].lights = rtp_mem_alloc(RTP_CUT_LOG_CAPACITY * sizeof *e.logs[w].lights, "the cut's ray logs");
        e.logs[w].ray_capacity = e.logs[w].light_capacity = RTP_CUT_LOG_CAPACITY;
        ok = e.logs[w].rays && e.logs[w].lights;
    }
    if (ok) {
        rt_workers_run(workers, estimate_row, &e, bands);
        cut_rows(&e, cam->height, count, starts);
    }
    for (uint32_t w = 0; e.logs && w < n; w++) {
        rtp_mem_free(e.logs[w].rays);
        rtp_mem_free(e.logs[w].lights);
    }
    rtp_mem_free(e.logs);
    rtp_mem_free(e.band_cost);
    rtp_pool_close(pool);
    return ok;
}

rt_rect rtp_part_band(const rt_scene *scene, const uint32_t *starts, uint32_t index)
{
    return (rt_rect){0, starts[index], scene->camera.width, starts[index + 1]};
}
