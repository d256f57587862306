/* The tile scheduler over POSIX threads; see threads.h. */
#include "thread/threads.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

typedef struct {
    const rt_tracer *tracer;
    uint8_t *rgb;
    rt_rect region;
    uint32_t tile, tiles_x, tile_count;
    atomic_uint next_tile;
    atomic_uint done_tiles;
    volatile int *cancel;
} job;

static void *worker(void *arg)
{
    job *j = arg;
    const rt_rect *r = &j->region;
    for (;;) {
        if (j->cancel && *j->cancel) break;
        unsigned t = atomic_fetch_add(&j->next_tile, 1);
        if (t >= j->tile_count) break;
        uint32_t x0 = r->x0 + (t % j->tiles_x) * j->tile, y0 = r->y0 + (t / j->tiles_x) * j->tile;
        uint32_t x1 = r->x1 - x0 > j->tile ? x0 + j->tile : r->x1;
        uint32_t y1 = r->y1 - y0 > j->tile ? y0 + j->tile : r->y1;
        rt_render_rect(j->tracer, (rt_rect){x0, y0, x1, y1}, *r, j->rgb);
        atomic_fetch_add(&j->done_tiles, 1);
    }
    return NULL;
}

static double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static void draw_progress(unsigned done, unsigned total, double elapsed)
{
    int width = 40, filled = total ? (int)((uint64_t)done * width / total) : width;
    char bar[64];
    for (int i = 0; i < width; i++) bar[i] = i < filled ? '#' : '.';
    bar[width] = 0;
    double left = done > 0 ? elapsed * (total - done) / done : 0.0;
    fprintf(stderr, "\r[%s] %3u%%  %.1fs elapsed, ~%.1fs left ", bar, total ? done * 100 / total : 100, elapsed, left);
    fflush(stderr);
}

uint32_t rtp_threads_count(uint32_t requested)
{
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    return requested ? requested : cpus > 0 ? (uint32_t)cpus : 1;
}

bool rtp_threads_render(const rt_tracer *tr, const rtp_threads_options *opt, uint8_t *rgb)
{
    const rt_camera *cam = &tr->scene->camera;
    return rtp_threads_render_region(tr, opt, (rt_rect){0, 0, cam->width, cam->height}, rgb);
}

bool rtp_threads_render_region(const rt_tracer *tr, const rtp_threads_options *opt, rt_rect region, uint8_t *rgb)
{
    job j;
    j.tracer = tr;
    j.rgb = rgb;
    j.region = region;
    j.tile = opt->tile_size ? opt->tile_size : 32;
    j.tiles_x = (j.region.x1 - j.region.x0 + j.tile - 1) / j.tile;
    j.tile_count = j.tiles_x * ((j.region.y1 - j.region.y0 + j.tile - 1) / j.tile);
    atomic_init(&j.next_tile, 0);
    atomic_init(&j.done_tiles, 0);
    j.cancel = opt->cancel;
    uint32_t n = rtp_threads_count(opt->threads);
    if (n > j.tile_count) n = j.tile_count ? j.tile_count : 1;
    pthread_t *threads = calloc(n, sizeof *threads);
    if (!threads) return false;
    uint32_t started = 0;
    while (started < n && pthread_create(&threads[started], NULL, worker, &j) == 0) started++;
    if (started == 0) worker(&j); /* no thread could start: render on this one */
    double start = seconds_now();
    while (opt->progress && atomic_load(&j.done_tiles) < j.tile_count && !(j.cancel && *j.cancel)) {
        draw_progress(atomic_load(&j.done_tiles), j.tile_count, seconds_now() - start);
        usleep(100000);
    }
    for (uint32_t i = 0; i < started; i++) pthread_join(threads[i], NULL);
    free(threads);
    if (opt->progress) {
        draw_progress(atomic_load(&j.done_tiles), j.tile_count, seconds_now() - start);
        fputc('\n', stderr);
    }
    return atomic_load(&j.done_tiles) == j.tile_count;
}
