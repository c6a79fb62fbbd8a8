/* cache.h: prepared subjects (read, processed, their step lists made) kept
 * for the next tasks that need them, shared by threads: the one cache of
 * the main job's and capacity's tasks farmed out to other processes
 * (src/app/suite_farm.c, src/app/capacity_tasks.c, archquake-mpi), where a
 * process runs the tasks of a subject's arches one after another.
 *
 * A task acquires the item of key i (a subject's index): kept and ready, it
 * is shared; being prepared by another thread, the task waits for it; else
 * the task prepares it itself, outside the lock, in the least recently
 * released slot that no task uses (cleared first), waiting while every
 * slot is in use.  With a slot for every key (nslot >= nkey), key i lives
 * in slot i and nothing is evicted.
 *
 * The items are the caller's: an array of nslot items of item_size bytes,
 * zeroed, that the cache never frees (the caller clears them after
 * aq_cache_free).  Nothing here prints. */
#ifndef AQ_JOB_CACHE_H
#define AQ_JOB_CACHE_H

#include <stddef.h>

typedef struct {
  size_t nkey;      /* keys are < nkey */
  size_t nslot;     /* items kept at most (>= 1) */
  void *items;      /* nslot items of item_size bytes */
  size_t item_size;
  /* Fill item for key (the thread that acquires it, outside the lock). */
  void (*prepare)(void *ctx, size_t key, void *item);
  /* Free what an item holds before it is prepared for another key. */
  void (*clear)(void *ctx, void *item);
  void *ctx;
} aq_cache_cfg;

typedef struct aq_cache aq_cache;

/* A cache over cfg's items (cfg is copied).  Returns NULL out of memory. */
aq_cache *aq_cache_alloc(const aq_cache_cfg *cfg);

/* The item of key, prepared, with a use counted (release it). */
void *aq_cache_acquire(aq_cache *c, size_t key);

/* End a use of item (as acquire returned it). */
void aq_cache_release(aq_cache *c, void *item);

/* Free the cache (NULL is fine), not the items. */
void aq_cache_free(aq_cache *c);

#endif
