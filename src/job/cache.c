/* cache.c: prepared subjects kept for the next tasks (cache.h). */
#define _POSIX_C_SOURCE 200809L
#include "cache.h"

#include <pthread.h>
#include <stdlib.h>

enum { CACHE_EMPTY = 0, CACHE_PREPARING, CACHE_READY };

typedef struct {
  int state;
  size_t key;   /* when not CACHE_EMPTY */
  size_t users; /* tasks using it now */
  size_t used;  /* tick of its last release */
} cache_slot;

struct aq_cache {
  aq_cache_cfg cfg;
  pthread_mutex_t lock; /* guards slot and tick */
  pthread_cond_t cond;  /* an item is ready, or a slot is released */
  cache_slot *slot;
  size_t tick;
};

aq_cache *aq_cache_alloc(const aq_cache_cfg *cfg)
{
  aq_cache *c = calloc(1, sizeof *c);
  if (!c)
    return NULL;
  c->cfg = *cfg;
  c->slot = calloc(cfg->nslot ? cfg->nslot : 1, sizeof *c->slot);
  if (!c->slot) {
    free(c);
    return NULL;
  }
  pthread_mutex_init(&c->lock, NULL);
  pthread_cond_init(&c->cond, NULL);
  return c;
}

void aq_cache_free(aq_cache *c)
{
  if (!c)
    return;
  pthread_cond_destroy(&c->cond);
  pthread_mutex_destroy(&c->lock);
  free(c->slot);
  free(c);
}

static void *item_at(const aq_cache *c, size_t k)
{
  return (char *)c->cfg.items + k * c->cfg.item_size;
}

/* The slot key is in (nslot when none), and the least recently released
 * one nobody uses or prepares, for a key not kept (nslot when none).  With
 * a slot per key, key's own. */
static void find(const aq_cache *c, size_t key, size_t *hit, size_t *lru)
{
  size_t n = c->cfg.nslot;
  *hit = *lru = n;
  if (n >= c->cfg.nkey) {
    if (c->slot[key].state != CACHE_EMPTY)
      *hit = key;
    else
      *lru = key;
    return;
  }
  for (size_t k = 0; k < n; k++) {
    const cache_slot *x = &c->slot[k];
    if (x->state != CACHE_EMPTY && x->key == key)
      *hit = k;
    else if (x->users == 0 && x->state != CACHE_PREPARING &&
             (*lru == n || x->used < c->slot[*lru].used))
      *lru = k;
  }
}

void *aq_cache_acquire(aq_cache *c, size_t key)
{
  size_t n = c->cfg.nslot;
  pthread_mutex_lock(&c->lock);
  for (;;) {
    size_t hit, lru;
    find(c, key, &hit, &lru);
    if (hit < n && c->slot[hit].state == CACHE_READY) {
      c->slot[hit].users++;
      pthread_mutex_unlock(&c->lock);
      return item_at(c, hit);
    }
    if (hit == n && lru < n) { /* prepare it here */
      cache_slot *x = &c->slot[lru];
      int had = x->state != CACHE_EMPTY;
      x->state = CACHE_PREPARING;
      x->key = key;
      x->users = 1;
      pthread_mutex_unlock(&c->lock);
      void *item = item_at(c, lru);
      if (had)
        c->cfg.clear(c->cfg.ctx, item);
      c->cfg.prepare(c->cfg.ctx, key, item);
      pthread_mutex_lock(&c->lock);
      x->state = CACHE_READY;
      pthread_cond_broadcast(&c->cond);
      pthread_mutex_unlock(&c->lock);
      return item;
    }
    pthread_cond_wait(&c->cond, &c->lock); /* being prepared, or every slot in use */
  }
}

void aq_cache_release(aq_cache *c, void *item)
{
  size_t k = (size_t)((char *)item - (char *)c->cfg.items) / c->cfg.item_size;
  pthread_mutex_lock(&c->lock);
  c->slot[k].users--;
  c->slot[k].used = ++c->tick;
  pthread_cond_broadcast(&c->cond);
  pthread_mutex_unlock(&c->lock);
}
