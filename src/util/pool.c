/* pool.c: threads (pool.h). */
#include "pool.h"

#include <pthread.h>
#include <stdlib.h>

typedef struct {
  aq_pool *pool;
  size_t k;
} pool_arg;

struct aq_pool {
  aq_pool_fn fn;
  void *ctx;
  size_t started;
  pthread_t *tid;
  pool_arg *arg;
};

static void *pool_main(void *v)
{
  pool_arg *a = v;
  a->pool->fn(a->pool->ctx, a->k);
  return NULL;
}

aq_pool *aq_pool_start(size_t n, aq_pool_fn fn, void *ctx, size_t *started)
{
  aq_pool *p = calloc(1, sizeof *p);
  if (p) {
    p->tid = calloc(n ? n : 1, sizeof *p->tid);
    p->arg = calloc(n ? n : 1, sizeof *p->arg);
  }
  if (!p || !p->tid || !p->arg) {
    if (p) {
      free(p->tid);
      free(p->arg);
    }
    free(p);
    if (started)
      *started = 0;
    return NULL;
  }
  p->fn = fn;
  p->ctx = ctx;
  for (size_t k = 0; k < n; k++) {
    p->arg[k] = (pool_arg){p, k};
    if (pthread_create(&p->tid[k], NULL, pool_main, &p->arg[k]) != 0)
      break;
    p->started++;
  }
  if (started)
    *started = p->started;
  return p;
}

void aq_pool_join(aq_pool *p)
{
  if (!p)
    return;
  for (size_t k = 0; k < p->started; k++)
    pthread_join(p->tid[k], NULL);
  free(p->tid);
  free(p->arg);
  free(p);
}

typedef struct {
  size_t ntask, next;
  aq_pool_fn fn;
  void *ctx;
  pthread_mutex_t lock;
} task_queue;

static void take_tasks(void *v, size_t worker)
{
  (void)worker;
  task_queue *q = v;
  for (;;) {
    pthread_mutex_lock(&q->lock);
    size_t k = q->next < q->ntask ? q->next++ : q->ntask;
    pthread_mutex_unlock(&q->lock);
    if (k >= q->ntask)
      return;
    q->fn(q->ctx, k);
  }
}

aq_status aq_pool_for(size_t ntask, long threads, aq_pool_fn fn, void *ctx, aq_error *err)
{
  task_queue q = {ntask, 0, fn, ctx, PTHREAD_MUTEX_INITIALIZER};
  size_t nt = threads < 1 ? 1 : (size_t)threads;
  if (nt > ntask)
    nt = ntask ? ntask : 1;
  aq_pool *p = NULL;
  if (nt > 1 && !(p = aq_pool_start(nt - 1, take_tasks, &q, NULL)))
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "threads", "out of memory");
  take_tasks(&q, nt - 1); /* the calling thread works too */
  aq_pool_join(p);
  pthread_mutex_destroy(&q.lock);
  return AQ_OK;
}
