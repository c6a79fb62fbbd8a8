/* farm.h: tasks farmed out to other processes (archquake-mpi, src/app/mpi.c)
 * by the commands that can use them: the main job (suite_farm.c, a task per
 * (record, arch)) and capacity (capacity_tasks.c, a task per (subject,
 * arch)).  A task's result travels as a message of bytes; the leader takes
 * every result on one thread and alone writes.  Outside archquake-mpi no
 * farm is set and the commands run here. */
#ifndef AQ_APP_FARM_H
#define AQ_APP_FARM_H

#include <stddef.h>

#include "../error.h"

typedef struct {
  size_t ntask; /* task ids are < ntask */
  long threads; /* tasks a process runs at once (-j, the same on every rank) */
  size_t group; /* tasks t and u share their input when t / group == u / group
                   (a record's arches): a rank gets the next task of its
                   last one's group when it can; 0 or 1: no sharing */
  size_t ahead; /* leader: tasks handed out at most this far (in todo) beyond
                   the first whose result is not taken yet, per running
                   thread (bounds what waits for a slow task); 0: no bound */
  /* Run task t on this process and give its result as a message (*msg
   * malloc'd, *n bytes).  Returns 0, or -1 out of memory.  Called on worker
   * threads, concurrently. */
  int (*run)(void *ctx, size_t t, unsigned char **msg, size_t *n);
  /* Leader: take task t's result (its own or a follower's).  Returns 0, or
   * -1 with err filled when the message is malformed.  Called on one
   * thread at a time. */
  int (*take)(void *ctx, size_t t, const unsigned char *msg, size_t n, aq_error *err);
  void *ctx;
} aq_farm_tasks;

typedef struct {
  void *ctx;
  int follower; /* 1: run what the leader hands out; write nothing */
  /* Leader: run the ntodo tasks todo[] here and on the followers, every
   * result given to T->take, then stop the followers; follower: run the
   * tasks the leader hands out until it stops them.  Returns 0, or -1 with
   * err filled when the exchange failed (then nothing may be written). */
  int (*farm)(void *ctx, const aq_farm_tasks *T, const size_t *todo, size_t ntodo,
              aq_error *err);
} aq_farm;

/* Every later suite and capacity run farms through f: NULL outside
 * archquake-mpi; f->farm NULL under it with one rank (runs here). */
void aq_farm_set(const aq_farm *f);
const aq_farm *aq_farm_get(void);
/* 1 if this process is a follower (it must create no output). */
int aq_farm_is_follower(void);

#endif
