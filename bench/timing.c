/* Timing and the chunked parallel loop; see timing.h. */
#include "timing.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

/* Small enough to balance two threads at the end of a pass, large enough that the
 * shared counter is touched rarely. */
#define CHUNK 1024

typedef struct {
    bench_range_fn fn;
    void *ctx;
    uint32_t count;
    atomic_uint next;
} loop;

double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

double bench_cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void *run(void *arg)
{
    loop *l = arg;
    for (;;) {
        uint32_t begin = atomic_fetch_add(&l->next, CHUNK);
        if (begin >= l->count) return NULL;
        uint32_t end = l->count - begin < CHUNK ? l->count : begin + CHUNK;
        l->fn(l->ctx, begin, end);
    }
}

double bench_parallel_for(uint32_t count, uint32_t threads, bench_range_fn fn, void *ctx)
{
    loop l = {fn, ctx, count, 0};
    atomic_init(&l.next, 0);
    pthread_t extra[64];
    uint32_t started = 0;
    double start = bench_now();
    while (started + 1 < threads && started < 64 && pthread_create(&extra[started], NULL, run, &l) == 0) started++;
    run(&l);
    for (uint32_t i = 0; i < started; i++) pthread_join(extra[i], NULL);
    return bench_now() - start;
}

uint32_t bench_cpu_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (uint32_t)n : 1;
}

/* The 1-thread and all-thread passes alternate, so a drift in the host's speed during
 * the measurement touches both and not just one side of the speed-up. */
void bench_time_rays(const char *kernel, const char *name, uint32_t items, uint32_t count, uint32_t repeats,
                     bench_range_fn fn, void *ctx, const uint8_t *hit)
{
    uint32_t cpus = bench_cpu_count();
    double best_1 = 0.0, best_1_cpu = 0.0, best_all = 0.0;
    for (uint32_t r = 0; r < repeats; r++) {
        fprintf(stderr, "  %s: %s rays, 1 and %u threads, %u/%u\n", kernel, name, cpus, r + 1, repeats);
        double cpu = bench_cpu_now();
        double one = bench_parallel_for(items, 1, fn, ctx);
        cpu = bench_cpu_now() - cpu;
        double all = bench_parallel_for(items, cpus, fn, ctx);
        if (r == 0 || one < best_1) best_1 = one;
        if (r == 0 || cpu < best_1_cpu) best_1_cpu = cpu;
        if (r == 0 || all < best_all) best_all = all;
    }
    printf("%s_mrays_1 %.4f\n%s_mrays_1_cpu %.4f\n", name, count / best_1 * 1e-6, name, count / best_1_cpu * 1e-6);
    printf("%s_mrays_all %.4f\n", name, count / best_all * 1e-6);
    uint32_t hits = 0;
    for (uint32_t i = 0; i < count; i++) hits += hit[i];
    printf("%s_rays %u\n%s_hits %u\n", name, count, name, hits);
}
