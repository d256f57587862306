/* The worker pool (platform/thread/pool.c): every job of every job set runs once, on a
 * worker index below the pool's count, and the set is done when run returns. */
#include "thread/pool.h"
#include <criterion/criterion.h>
#include <stdatomic.h>

enum { MAX_JOBS = 64, MAX_WORKERS = 8 };

typedef struct {
    atomic_uint runs[MAX_JOBS];
    atomic_uint bad_worker;
    uint32_t workers;
} tally;

static void count_job(void *arg, uint32_t index, uint32_t worker)
{
    tally *t = arg;
    atomic_fetch_add(&t->runs[index], 1);
    if (worker >= t->workers) atomic_fetch_add(&t->bad_worker, 1);
}

static void run_sets(rtp_pool *pool, uint32_t expected_workers)
{
    const rt_workers *w = rtp_pool_workers(pool);
    cr_assert_eq(rt_workers_count(w), expected_workers);
    /* Many sets in a row, with fewer, as many and more jobs than workers. */
    for (uint32_t set = 0; set < 2000; set++) {
        uint32_t jobs = set % MAX_JOBS + 1;
        tally t = {.workers = expected_workers};
        for (uint32_t j = 0; j < MAX_JOBS; j++) atomic_init(&t.runs[j], 0);
        atomic_init(&t.bad_worker, 0);
        rt_workers_run(w, count_job, &t, jobs);
        for (uint32_t j = 0; j < MAX_JOBS; j++)
            cr_assert_eq(atomic_load(&t.runs[j]), j < jobs ? 1u : 0u, "set %u, job %u of %u", set, j, jobs);
        cr_assert_eq(atomic_load(&t.bad_worker), 0, "set %u: a worker index past the pool's count", set);
    }
}

Test(pool, runs_every_job_once_in_every_set)
{
    for (uint32_t threads = 1; threads <= MAX_WORKERS; threads++) {
        rtp_pool *pool = rtp_pool_open(threads);
        cr_assert_not_null(pool);
        run_sets(pool, threads);
        rtp_pool_close(pool);
    }
}

/* Closing a pool that never ran a job set stops its sleeping workers. */
Test(pool, closes_without_work)
{
    rtp_pool_close(rtp_pool_open(4));
    rtp_pool_close(NULL);
}
