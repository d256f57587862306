/* Worker threads for the tile renderer, with an optional progress bar (the core's job
 * sets run on pool.h). */
#ifndef RTP_THREADS_H
#define RTP_THREADS_H

#include "render.h"
#include <stdbool.h>
#include <stdint.h>

typedef struct {
    uint32_t threads;   /* 0 = one per online CPU */
    uint32_t tile_size; /* pixels per tile side; 0 = 32 */
    bool progress;      /* draw a progress bar on stderr */
    /* Set asynchronously (e.g. by a signal handler) to stop early; checked between tiles. */
    volatile int *cancel;
} rtp_threads_options;

/* Fills rgb (width * height * 3). Returns false if cancelled or a thread could not start
 * (then rgb is incomplete and must not be used). The pixels never depend on the thread
 * count, tile size or scheduling: each pixel is a function of the scene alone. */
bool rtp_threads_render(const rt_tracer *tr, const rtp_threads_options *opt, uint8_t *rgb);
/* The same for one rectangle of the frame: rgb holds only its pixels (a part of a
 * distributed render). */
bool rtp_threads_render_region(const rt_tracer *tr, const rtp_threads_options *opt, rt_rect region, uint8_t *rgb);

/* The number of threads a request stands for: itself, or one per online CPU for 0. */
uint32_t rtp_threads_count(uint32_t requested);

#endif
