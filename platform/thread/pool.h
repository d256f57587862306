/* A pool of worker threads for the core's job sets (workers.h): started once, woken for
 * each job set, so a build of many job sets does not pay a thread's start and join for
 * each (115-215 us apiece on the VM of docs/performance.md). */
#ifndef RTP_POOL_H
#define RTP_POOL_H

#include "workers.h"
#include <stdint.h>

typedef struct rtp_pool rtp_pool;

/* A pool of `threads` workers (0: one per online CPU), the calling thread among them;
 * the other threads start with the first job set. A thread that cannot start leaves its
 * jobs to the others, so a job set always completes. NULL (no memory) is a pool of one,
 * the calling thread. */
rtp_pool *rtp_pool_open(uint32_t threads);
/* The pool's workers for the core, or NULL (run the jobs on the calling thread). Only
 * the thread that opened the pool may run job sets on it, one at a time. */
const rt_workers *rtp_pool_workers(const rtp_pool *pool);
/* Stops and joins the workers; NULL is allowed. */
void rtp_pool_close(rtp_pool *pool);

#endif
