/* The cache of prepared subjects (src/job/cache.h) against a least
 * recently used model worked out by hand: which keys are prepared again,
 * that an item in use is never taken, that threads asking for the same key
 * at once share one preparing, and that with a slot per key each key keeps
 * its own. */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "job/cache.h"

#define NKEY 6

typedef struct {
  size_t key;
  int live; /* 1 between prepare and clear */
} item;

typedef struct {
  pthread_mutex_t lock;
  int prepared[NKEY], cleared;
  long prepare_ns; /* a preparing that takes a while (threads meet in it) */
} counts;

static void pause_ns(long ns)
{
  struct timespec ts = {0, ns};
  nanosleep(&ts, NULL);
}

static void prepare(void *ctx, size_t key, void *it)
{
  counts *n = ctx;
  item *x = it;
  pthread_mutex_lock(&n->lock);
  n->prepared[key]++;
  pthread_mutex_unlock(&n->lock);
  if (n->prepare_ns)
    pause_ns(n->prepare_ns);
  x->key = key;
  x->live = 1;
}

static void clear(void *ctx, void *it)
{
  counts *n = ctx;
  item *x = it;
  n->cleared++;
  x->live = 0;
  x->key = (size_t)-1;
}

static aq_cache *make(counts *n, item *items, size_t nslot)
{
  memset(n, 0, sizeof *n);
  pthread_mutex_init(&n->lock, NULL);
  aq_cache_cfg cfg = {NKEY, nslot, items, sizeof *items, prepare, clear, n};
  return aq_cache_alloc(&cfg);
}

/* Acquire key, check the item holds it, release it. */
static void use(aq_cache *c, size_t key)
{
  item *x = aq_cache_acquire(c, key);
  aq_check(x->live && x->key == key, "acquire %zu: item holds %zu", key, x->key);
  aq_cache_release(c, x);
}

AQ_TEST(job_cache_evicts_the_least_recently_released)
{
  counts n;
  item items[2] = {{0, 0}, {0, 0}};
  aq_cache *c = make(&n, items, 2);
  aq_check(c != NULL, "alloc");
  /* two slots: 0 and 1 kept; 0 used again last, so 2 takes 1's slot;
   * then 1 takes 0's (released before 2), and 0 comes back in 2's */
  size_t seq[] = {0, 0, 1, 0, 2, 1, 0, 0};
  for (size_t k = 0; k < sizeof seq / sizeof *seq; k++)
    use(c, seq[k]);
  aq_check(n.prepared[0] == 2 && n.prepared[1] == 2 && n.prepared[2] == 1,
           "prepared 0, 1, 2: %d %d %d times, expected 2 2 1", n.prepared[0], n.prepared[1],
           n.prepared[2]);
  aq_check(n.cleared == 3, "cleared %d items, expected 3", n.cleared);
  aq_cache_free(c);
}

typedef struct {
  aq_cache *c;
  size_t key;
  item *got;
  volatile int started;
} taker;

static void *take(void *arg)
{
  taker *t = arg;
  t->started = 1;
  t->got = aq_cache_acquire(t->c, t->key);
  return NULL;
}

AQ_TEST(job_cache_never_takes_an_item_in_use)
{
  counts n;
  item items[2] = {{0, 0}, {0, 0}};
  aq_cache *c = make(&n, items, 2);
  item *a = aq_cache_acquire(c, 0), *b = aq_cache_acquire(c, 1);
  taker t = {c, 2, NULL, 0};
  pthread_t th;
  aq_check(pthread_create(&th, NULL, take, &t) == 0, "thread");
  while (!t.started)
    pause_ns(1000000L);
  pause_ns(50000000L); /* room for a wrong cache to take a slot in use */
  aq_check(a->live && a->key == 0 && b->live && b->key == 1,
           "items in use kept their keys (0, 1), got %zu, %zu", a->key, b->key);
  aq_cache_release(c, b); /* now 2 may take 1's slot */
  pthread_join(th, NULL);
  aq_check(t.got == b && b->key == 2, "key 2 in the released slot");
  aq_check(a->key == 0 && n.prepared[0] == 1, "key 0 untouched");
  aq_cache_release(c, a);
  aq_cache_release(c, t.got);
  aq_cache_free(c);
}

AQ_TEST(job_cache_threads_share_one_preparing)
{
  counts n;
  item items[2] = {{0, 0}, {0, 0}};
  aq_cache *c = make(&n, items, 2);
  n.prepare_ns = 20000000L;
  taker t[4];
  pthread_t th[4];
  for (int k = 0; k < 4; k++) {
    t[k] = (taker){c, 3, NULL, 0};
    pthread_create(&th[k], NULL, take, &t[k]);
  }
  for (int k = 0; k < 4; k++)
    pthread_join(th[k], NULL);
  aq_check(n.prepared[3] == 1, "key 3 prepared %d times by 4 threads, expected once",
           n.prepared[3]);
  for (int k = 0; k < 4; k++) {
    aq_check(t[k].got == t[0].got && t[k].got->key == 3, "thread %d shares the item", k);
    aq_cache_release(c, t[k].got);
  }
  aq_cache_free(c);
}

AQ_TEST(job_cache_a_slot_per_key_keeps_every_key)
{
  counts n;
  item items[NKEY];
  memset(items, 0, sizeof items);
  aq_cache *c = make(&n, items, NKEY);
  size_t seq[] = {5, 2, 0, 3, 1, 4, 5, 0, 2, 4};
  for (size_t k = 0; k < sizeof seq / sizeof *seq; k++)
    use(c, seq[k]);
  int once = 1;
  for (size_t k = 0; k < NKEY; k++)
    once &= n.prepared[k] == 1 && items[k].key == k;
  aq_check(once && n.cleared == 0, "each key prepared once, in its own slot, none cleared");
  aq_cache_free(c);
}
