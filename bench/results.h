/* Each ray's answer, as a kernel gave it, in a file per kernel (`rtk-bench run
 * --results`, `embree-harness --results`), and their comparison (`rtk-bench agree`):
 * the bench's check that rtk and Embree answer the same rays the same way. */
#ifndef BENCH_RESULTS_H
#define BENCH_RESULTS_H

#include "workload.h"
#include <stdbool.h>
#include <stdint.h>

#define BENCH_MISS UINT32_MAX

typedef struct {
    uint32_t primary_count, shadow_count;
    uint8_t *primary_hit;    /* camera ray i hit something */
    uint32_t *primary_prim;  /* the triangle it hit, or BENCH_MISS */
    uint8_t *shadow_blocked; /* shadow ray i is blocked */
} bench_results;

/* Zeroed arrays for w's rays; false (and a line on stderr) when memory runs out. */
bool bench_results_alloc(const bench_workload *w, bench_results *r);
void bench_results_free(bench_results *r);
bool bench_results_write(const char *path, const bench_results *r);

/* Compares two result files of the workload: prints "<set>_agree PERCENT" and
 * "<set>_differ COUNT" on stdout for the camera and the shadow rays, lists the first
 * rays that differ (with their pixel) on stderr, and returns 0, or 1 when either set
 * agrees on fewer than min_percent of its rays (2: unreadable files). With neighbours,
 * camera rays whose two triangles share a vertex (a ray through their common edge,
 * rounded to either side by float and by double) count as agreeing for that verdict;
 * they are printed apart either way. */
int bench_agree(const char *workload, const char *path_a, const char *path_b, double min_percent, bool neighbours);

#endif
