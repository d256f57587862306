/* The worker pool of pool.h over POSIX threads. A job set is published by bumping a
 * generation number; workers spin on it briefly, then sleep on a condition variable, so
 * the short serial steps between a build's job sets do not put them to sleep. */
#include "thread/pool.h"

#include "thread/threads.h"
#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdlib.h>

/* Pauses before sleeping: about 40 us on the machine of docs/performance.md, longer than
 * the serial steps between a build's job sets; a sleeping worker takes about as long
 * again to wake there. */
#define SPIN_LIMIT 2048

typedef struct {
    rtp_pool *pool;
    uint32_t index;
} worker_slot;

struct rtp_pool {
    rt_workers workers; /* first, so that run() finds its pool */
    pthread_mutex_t lock;
    pthread_cond_t wake, done;
    /* The job set of the moment: written before generation is bumped. */
    rt_job_fn *job;
    void *arg;
    uint32_t jobs;
    atomic_uint next;       /* the next job index to hand out */
    atomic_uint busy;       /* workers not yet through the job set */
    atomic_uint generation; /* one more for each job set, and for the stop */
    bool stop, launched;
    uint32_t wanted, started; /* extra threads asked for, and running */
    pthread_t *threads;
    worker_slot *slots;
};

static void cpu_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    __asm__ volatile("yield");
#endif
}

static void take_jobs(rtp_pool *p, uint32_t worker)
{
    for (unsigned i; (i = atomic_fetch_add(&p->next, 1)) < p->jobs;) p->job(p->arg, i, worker);
}

/* Waits until the generation differs from seen; returns it. */
static unsigned wait_for_set(rtp_pool *p, unsigned seen)
{
    unsigned g;
    for (int i = 0; i < SPIN_LIMIT; i++) {
        if ((g = atomic_load(&p->generation)) != seen) return g;
        cpu_relax();
    }
    pthread_mutex_lock(&p->lock);
    while ((g = atomic_load(&p->generation)) == seen) pthread_cond_wait(&p->wake, &p->lock);
    pthread_mutex_unlock(&p->lock);
    return g;
}

static void *pool_worker(void *arg)
{
    worker_slot *s = arg;
    rtp_pool *p = s->pool;
    for (unsigned seen = 0;;) {
        seen = wait_for_set(p, seen);
        if (p->stop) return NULL;
        take_jobs(p, s->index);
        if (atomic_fetch_sub(&p->busy, 1) == 1) {
            pthread_mutex_lock(&p->lock);
            pthread_cond_signal(&p->done);
            pthread_mutex_unlock(&p->lock);
        }
    }
}

/* Publishes the job set of the moment (or the stop) to the workers. */
static void publish(rtp_pool *p)
{
    atomic_store(&p->busy, p->started);
    pthread_mutex_lock(&p->lock);
    atomic_fetch_add(&p->generation, 1);
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);
}

/* Starts the extra threads, at the first job set: a scene too small for one needs none. */
static void launch(rtp_pool *p)
{
    p->launched = true;
    for (; p->started < p->wanted; p->started++) {
        p->slots[p->started] = (worker_slot){p, p->started + 1};
        if (pthread_create(&p->threads[p->started], NULL, pool_worker, &p->slots[p->started]) != 0) break;
    }
}

static void pool_run(const rt_workers *w, rt_job_fn *job, void *arg, uint32_t jobs)
{
    rtp_pool *p = (rtp_pool *)w;
    if (!p->launched) launch(p);
    p->job = job;
    p->arg = arg;
    p->jobs = jobs;
    atomic_store(&p->next, 0);
    publish(p);
    take_jobs(p, 0);
    for (int i = 0; i < SPIN_LIMIT && atomic_load(&p->busy) != 0; i++) cpu_relax();
    pthread_mutex_lock(&p->lock);
    while (atomic_load(&p->busy) != 0) pthread_cond_wait(&p->done, &p->lock);
    pthread_mutex_unlock(&p->lock);
}

rtp_pool *rtp_pool_open(uint32_t threads)
{
    uint32_t extra = rtp_threads_count(threads) - 1;
    rtp_pool *p = calloc(1, sizeof *p);
    if (!p) return NULL;
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->wake, NULL);
    pthread_cond_init(&p->done, NULL);
    p->threads = calloc(extra ? extra : 1, sizeof *p->threads);
    p->slots = calloc(extra ? extra : 1, sizeof *p->slots);
    if (!p->threads || !p->slots) {
        rtp_pool_close(p);
        return NULL;
    }
    atomic_init(&p->next, 0);
    atomic_init(&p->busy, 0);
    atomic_init(&p->generation, 0);
    p->wanted = extra;
    p->workers = (rt_workers){extra + 1, pool_run};
    return p;
}

const rt_workers *rtp_pool_workers(const rtp_pool *pool) { return pool ? &pool->workers : NULL; }

void rtp_pool_close(rtp_pool *pool)
{
    if (!pool) return;
    if (pool->started > 0) {
        pool->stop = true;
        publish(pool);
        for (uint32_t i = 0; i < pool->started; i++) pthread_join(pool->threads[i], NULL);
    }
    pthread_cond_destroy(&pool->done);
    pthread_cond_destroy(&pool->wake);
    pthread_mutex_destroy(&pool->lock);
    free(pool->slots);
    free(pool->threads);
    free(pool);
}
