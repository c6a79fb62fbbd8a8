/* blocks_run.h: the run's state behind blocks.h (internal to src/blocks,
 * shared by blocks.c and events.c; tests reach the bodies and the stepper
 * through aq_blocks_bodies and aq_blocks_moreau). */
#ifndef AQ_BLOCKS_RUN_H
#define AQ_BLOCKS_RUN_H

#include "blocks.h"
#include "model.h"

/* ---- events.c: what a run reports ----------------------------------- */

typedef struct {
  const aq_bodies *s;
  const aq_hinge_set *set; /* the arch's two four-hinge sets, or NULL */
  int history;
  double *q0;              /* configuration at the record's start */
  double *qprev;           /* at the end of the step before */
  aq_vec2 *c0;             /* voussoir (or body) centroids at the record's start */
  double pe0;              /* potential energy then, J */
  double dv_floor_j;       /* the collapse rule's rise above pe0, J */
  double *open_t;          /* first opening time per joint and face (2 nj: e, i) */
  int started;             /* the record has started */
  double peak_rot, peak_disp, max_ke, energy_in, max_slip, mech_changed;
  double friction_work;    /* the friction's work since the record started, J (>= 0) */
  size_t impacts, reversals;
  int away;                /* the distance from rest grew in the step before */
  int armed;               /* the collapse rule was off in the step before */
  int collapsed;
  double collapse_t;
  int first_set, peak_set;
  double peak_set_rot[2];
} aq_events;

aq_status aq_events_init(aq_events *e, const aq_bodies *s, aq_error *err);
void aq_events_free(aq_events *e);
/* A new run (the spread, if any, not yet done); sets: the arch's two
 * four-hinge sets (NULL: none); dv_floor_j: the collapse rule's floor. */
void aq_events_reset(aq_events *e, aq_moreau *m, const aq_hinge_set *sets, int history,
                     double dv_floor_j, aq_blocks_result *res);
/* The record starts at t0 from the present configuration. */
void aq_events_start(aq_events *e, aq_moreau *m, double t0);
/* After a time step ending at t (h long, under ax, ay; the stepper's
 * report of it, info): peaks, hinges, energy, the friction's work, the
 * collapse rule (record 0: the spread, only the collapse
 * rule).  Returns 1 when the arch fell (collapsed at t), 2 when it is at
 * the top of the hill it climbs (the caller decides: aq_events_collapse),
 * else 0. */
int aq_events_step(aq_events *e, aq_moreau *m, double t, double h, double ax, double ay,
                   const aq_step_info *info, int record);
void aq_events_collapse(aq_events *e, double t);
/* 1 if a body has turned by more than COLLAPSE_ROT_RAD or a joint parted
 * (opened by more than its width, or its faces no longer overlap). */
int aq_events_fallen(const aq_events *e, aq_moreau *m);
/* 1 if the bodies move away from where they stood at the start. */
int aq_events_away(const aq_events *e, aq_moreau *m);
/* 1 if every velocity is zero to rounding (of g h). */
int aq_events_still(const aq_events *e, aq_moreau *m, double h);
/* A history sample at t (when asked).  AQ_ENOMEM. */
aq_status aq_events_sample(aq_events *e, aq_moreau *m, double t, aq_blocks_result *res);
/* The result's fields at the end of the run. */
void aq_events_finish(aq_events *e, aq_moreau *m, aq_blocks_result *res);

/* ---- blocks.c ------------------------------------------------------- */

struct aq_blocks {
  const aq_arch *arch;     /* NULL: test bodies */
  aq_hinge_set set[2];
  int have_set[2];
  aq_bodies bodies;
  aq_moreau *m;
  aq_events ev;
  double mu, e_n, dt_s, spread_m, spread_max, scale;
  double abutment_m;       /* the supports' faces beyond the springings (NAN: as made) */
  aq_blocks_control control;
  int history, rest_skip, direct, projection;
  aq_impact_law law;
  int at_rest;
  double rest_since;
  double dv_floor_j;       /* the collapse rule's floor, J */
  double *qstat;           /* the configuration of the static range */
  unsigned char *closed;   /* its closed corners (2 nj) */
  int stat_valid, stat_ok;
  double stat_lo, stat_hi;
  struct {
    size_t steps, direct, siconos, iters, pivots, statics, ahead, loose;
  } counters;
};

/* A model of explicit bodies (model.h aq_bodies_init's arguments), for
 * tests: a single block, a stack. */
aq_blocks *aq_blocks_alloc_bodies(const aq_body *body, size_t nb, const aq_vec2 (*ends)[2],
                                  size_t nj, double g_mps2, aq_error *err);
aq_moreau *aq_blocks_moreau(aq_blocks *b);
/* The impact law at e_n > 0 (model.h; default AQ_IMPACT_GLOBAL): for
 * tests and the bench's comparison. */
void aq_blocks_set_impact_law(aq_blocks *b, aq_impact_law law);
const aq_bodies *aq_blocks_bodies(const aq_blocks *b);

#endif
