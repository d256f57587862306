/* platform/thread/threads.h and pool.h for WebAssembly, where wasi-libc has no threads:
 * one worker, the calling thread. The browser spreads a render over Web Workers instead
 * (web/app). */
#include "thread/pool.h"
#include "thread/threads.h"

uint32_t rtp_threads_count(uint32_t requested)
{
    (void)requested;
    return 1;
}

/* No threads: no pool, so the core runs each job set in order on the calling thread. */
rtp_pool *rtp_pool_open(uint32_t threads)
{
    (void)threads;
    return NULL;
}

const rt_workers *rtp_pool_workers(const rtp_pool *pool)
{
    (void)pool;
    return NULL;
}

void rtp_pool_close(rtp_pool *pool) { (void)pool; }

bool rtp_threads_render(const rt_tracer *tr, const rtp_threads_options *opt, uint8_t *rgb)
{
    const rt_camera *cam = &tr->scene->camera;
    return rtp_threads_render_region(tr, opt, (rt_rect){0, 0, cam->width, cam->height}, rgb);
}

bool rtp_threads_render_region(const rt_tracer *tr, const rtp_threads_options *opt, rt_rect region, uint8_t *rgb)
{
    uint32_t tile = opt->tile_size ? opt->tile_size : 32;
    for (uint32_t y0 = region.y0; y0 < region.y1; y0 += tile)
        for (uint32_t x0 = region.x0; x0 < region.x1; x0 += tile) {
            if (opt->cancel && *opt->cancel) return false;
            uint32_t x1 = region.x1 - x0 > tile ? x0 + tile : region.x1;
            uint32_t y1 = region.y1 - y0 > tile ? y0 + tile : region.y1;
            rt_render_rect(tr, (rt_rect){x0, y0, x1, y1}, region, rgb);
        }
    return true;
}
