/* pool.h: the one place that makes and joins threads.
 *
 * Workers that run a loop of their own (the main job's scheduler, the MPI
 * farm) are started with aq_pool_start and joined with aq_pool_join;
 * independent tasks numbered 0..n-1 (capacity's jobs, naming the records)
 * run with aq_pool_for, the calling thread taking its share.  fn gets the
 * caller's ctx and a number: the worker's (0..started-1) or the task's.
 * Nothing here prints. */
#ifndef AQ_UTIL_POOL_H
#define AQ_UTIL_POOL_H

#include <stddef.h>

#include "../error.h"

typedef void (*aq_pool_fn)(void *ctx, size_t k);

typedef struct aq_pool aq_pool;

/* Start up to n threads, thread k running fn(ctx, k).  Returns the pool
 * (join it with aq_pool_join), or NULL when not even its memory could be
 * had; *started (may be NULL) gets how many threads run (0 to n: a thread
 * that cannot be created stops the starting). */
aq_pool *aq_pool_start(size_t n, aq_pool_fn fn, void *ctx, size_t *started);

/* Wait for every thread of p to return, and free p (NULL is fine). */
void aq_pool_join(aq_pool *p);

/* Run fn(ctx, k) for every k < ntask on up to threads threads (>= 1), the
 * calling thread included, each taking the next k when free; returns once
 * all are done.  Fewer threads start when the system refuses more (the
 * calling thread then does the rest).  Returns AQ_OK, or AQ_ENOMEM (err)
 * when the pool cannot be made: nothing ran. */
aq_status aq_pool_for(size_t ntask, long threads, aq_pool_fn fn, void *ctx, aq_error *err);

#endif
