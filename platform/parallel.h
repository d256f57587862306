/* Worker threads: the core's job sets (workers.h) and the tile renderer, with an
 * optional progress bar. */
#ifndef RT_PARALLEL_H
#define RT_PARALLEL_H

#include <stdbool.h>
#include <stdint.h>
#include "render.h"

typedef struct {
    uint32_t threads;   /* 0 = one per online CPU */
    uint32_t tile_size; /* pixels per tile side; 0 = 32 */
    bool progress;      /* draw a progress bar on stderr */
    /* Set asynchronously (e.g. by a signal handler) to stop early; checked between tiles. */
    volatile int *cancel;
} rt_parallel_options;

/* Fills rgb (width * height * 3). Returns false if cancelled or a thread could not start
 * (then rgb is incomplete and must not be used). The pixels never depend on the thread
 * count, tile size or scheduling: each pixel is a function of the scene alone. */
bool rt_render_parallel(const rt_tracer *tr, const rt_parallel_options *opt, uint8_t *rgb);

/* The number of threads a request stands for: itself, or one per online CPU for 0. */
uint32_t rt_thread_count(uint32_t requested);

/* Workers for the core's job sets on up to `threads` POSIX threads (0: one per online
 * CPU), the calling thread among them. A thread that cannot start leaves its share to
 * the others, so a job set always completes. */
rt_workers rt_thread_workers(uint32_t threads);

#endif
