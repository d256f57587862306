/* Wall-clock timing and a chunked parallel loop, shared by the rtk and Embree harnesses
 * so that both kernels are driven by the same scheduling code. */
#ifndef BENCH_TIMING_H
#define BENCH_TIMING_H

#include <stdint.h>

/* Monotonic seconds. */
double bench_now(void);
/* CPU seconds used so far by all threads of this process. For single-threaded work it
 * is the wall time minus what other processes took, so 1-thread ratios stay usable on a
 * busy machine. */
double bench_cpu_now(void);

/* Work on items [begin, end); called concurrently from several threads. */
typedef void (*bench_range_fn)(void *ctx, uint32_t begin, uint32_t end);

/* Runs fn over [0, count) in fixed-size chunks handed out to `threads` threads (the
 * calling thread is one of them); returns the wall time in seconds. */
double bench_parallel_for(uint32_t count, uint32_t threads, bench_range_fn fn, void *ctx);

/* Online CPUs, at least 1. */
uint32_t bench_cpu_count(void);

/* Times fn over `items` work items (single rays, or packets) holding `rays` rays, with 1
 * thread and with all threads, the two alternating, best of `repeats` each (progress on
 * stderr, labelled `kernel`), and prints "<name>_mrays_1", "<name>_mrays_1_cpu" (by CPU
 * time), "<name>_mrays_all", "<name>_rays" and "<name>_hits" (the sum of hit[0 .. rays),
 * which fn fills) on stdout. */
void bench_time_rays(const char *kernel, const char *name, uint32_t items, uint32_t rays, uint32_t repeats,
                     bench_range_fn fn, void *ctx, const uint8_t *hit);

#endif
