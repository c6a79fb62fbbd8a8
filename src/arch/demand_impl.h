/* demand_impl.h: the tracker's inside, shared by the files that follow a
 * run's demand (demand_track.c: the states of a run that moves;
 * demand_still.c: a run in which the arch never moves).  Private to
 * src/arch. */
#ifndef AQ_ARCH_DEMAND_IMPL_H
#define AQ_ARCH_DEMAND_IMPL_H

#include <stddef.h>
#include <stdint.h>

#include "demand.h"

enum { DM_QUEUE = 64 };

struct aq_demand {
  aq_demand_queue q; /* first: aq_demand_slot reaches it */
  aq_demand_leg_rec qbuf[DM_QUEUE];
  const aq_demand_table *tab[2];
  const aq_demand_table *(*get)(void *ctx, int set);
  void *get_ctx;
  int asked[2];     /* the table of set k was asked for */
  double mu_limit;  /* the friction coefficient, NAN: none */
  size_t iv[2];     /* the interval of each set's last evaluated state */
  double g, ig;     /* the last gravity and its inverse */
  double max[2];
  uint16_t key[2];  /* aq_dg_floor16 of each maximum */
  /* A flush may first find a value v that a later state of the queue has
   * (flush_legs): until that state, one whose quantity is below v cannot
   * change the maximum, its entry or its time (that state raises the
   * maximum past it), only the first time over the limit.  pre[q]: the
   * largest code below v (0: none); eff[q]: the code a state's or a
   * candidate's bound must exceed to be looked at (refresh). */
  uint16_t pre[2], eff[2];
  size_t joint[2];
  double when[2];
  double over_s[2]; /* first time over the limit (mu_limit, 1), NAN: never */
  int moved, failed, done;
  int every;        /* 1: every entry at every state (the reference) */
  /* marks only (aq_demand_set_marks_only): want[q], quantity q's mark can
   * apply; once it has passed its limit (or when it cannot apply), the
   * quantity is no longer looked at, and the run's tracking ends when
   * neither is */
  int marks_only, want[2];
  size_t samples, full, looks;
  aq_demand_least_fn least; /* the statics' least friction, NULL: none */
  void *least_ctx;
  int still;        /* a run at rest throughout: the statics' demand below */
  double still_mu, still_s, still_slide;
  size_t still_joint;
};

#endif
