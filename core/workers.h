/* How the core spreads independent jobs over a caller's threads without knowing about
 * threads (the platform supplies them, as Box2D v3's task callbacks do). Jobs write
 * disjoint memory and the core merges their results in job order, so what a job set
 * computes never depends on how many workers ran it or in what order. */
#ifndef RT_WORKERS_H
#define RT_WORKERS_H

#include <stdint.h>

/* One job: index < the set's job count; worker < the workers' count, for per-worker scratch. */
typedef void rt_job_fn(void *arg, uint32_t index, uint32_t worker);

typedef struct rt_workers {
    uint32_t count; /* workers the jobs may run on at once (1 or more) */
    /* Calls job(arg, i, worker) once for every i < jobs, on any of the workers in any
     * order, and returns when every call has returned. */
    void (*run)(const struct rt_workers *w, rt_job_fn *job, void *arg, uint32_t jobs);
} rt_workers;

static inline uint32_t rt_workers_count(const rt_workers *w) { return w && w->count > 1 ? w->count : 1; }

/* Runs the jobs on w, or here in index order when w is NULL or has one worker. */
static inline void rt_workers_run(const rt_workers *w, rt_job_fn *job, void *arg, uint32_t jobs)
{
    if (rt_workers_count(w) > 1 && jobs > 1) {
        w->run(w, job, arg, jobs);
        return;
    }
    for (uint32_t i = 0; i < jobs; i++) job(arg, i, 0);
}

#endif
