/* src/blocks: the arch as rigid voussoirs in frictional contact (docs/blocks.md).
 *
 * blocks.h: the block model's run, with the stepper's lifecycle (alloc,
 * set options, run over aq_steps, read the result, free), so that a job
 * drives it as it drives the four-hinge stepper (src/arch/stepper.h).
 *
 * Every voussoir is a rigid body carrying its fill and point masses (as
 * the arch attaches them); each joint is a unilateral contact at its two
 * ends with Coulomb friction; the springing joints bear on supports that
 * move with the ground.  Impacts follow Newton's law per contact
 * (restitution e_n).  Time stepping is Moreau-Jean (theta-method) with
 * each step's 2-D frictional contact problem solved exactly: directly
 * along the chain of voussoirs for the contact state of the step before
 * (verified, corrected by active-set iterations), else by Siconos
 * Numerics (Lemke's method; opened on first use).  With control fixed
 * every joint but the arch's four mechanical ones is bonded.
 *
 * The arch outlives the aq_blocks made from it; one aq_blocks per
 * thread; aq_blocks_free accepts NULL.  Units: SI; reports through
 * aq_error (run-time trouble names the time in the record). */
#ifndef AQ_BLOCKS_BLOCKS_H
#define AQ_BLOCKS_BLOCKS_H

#include <stddef.h>

#include "../arch/arch.h"
#include "../arch/result.h"
#include "../error.h"
#include "../signal/steps.h"

/* The default step, s (docs/blocks.md: the convergence study). */
#define AQ_BLOCKS_DT_DEFAULT_S 2e-3
/* A joint has opened as a hinge when the rotation of its two sides
 * differs by more than this, rad. */
#define AQ_BLOCKS_HINGE_OPEN_RAD 1e-3

typedef struct aq_blocks aq_blocks;

/* Which joints may open: every joint (free), or only the four of the
 * arch's set 0, every other bonded (fixed: the hinge-controlled arch). */
typedef enum { AQ_BLOCKS_FREE = 0, AQ_BLOCKS_FIXED } aq_blocks_control;

/* One opened hinge: joint, face ('e' or 'i'), first opening time. */
typedef struct {
  size_t joint;
  char face;
  double time_s;
} aq_blocks_hinge;

typedef struct {
  aq_result r;               /* the columns every model has (see below) */
  /* r.peak_rotation_rad: voussoir 0's largest |rotation|; r.peak_displacement_m:
   * the largest displacement of any voussoir's centroid from its place on
   * the ground; r.collapsed, r.collapse_time_s: the collapse rule
   * (docs/blocks.md); r.impacts: steps in which a contact closed with an
   * approach velocity; r.reversals: turning points of the distance from
   * rest; r.energy_in_j: work of the ground's inertia forces;
   * r.energy_dissipated_j: energy in less the kinetic and potential energy
   * at the end; r.history (when asked): voussoir 0's rotation and the
   * whole arch's centroid. */
  double max_slip_m;         /* largest slip of any joint: the tangential offset of its
                                faces (closed: at its closed corner; open: the smaller of
                                its ends'), m (docs/blocks.md) */
  double friction_work_j;    /* the work the joints' friction took from the record's start,
                                J (>= 0; D of the energy balance, docs/blocks.md) */
  size_t nhinges;            /* opened (joint, face) pairs, by joint then face */
  aq_blocks_hinge *hinges;
  double mechanism_changed_s;/* first time the opened set is in neither of the
                                arch's four-hinge sets; NAN if never */
  int spread_collapsed;      /* 1: the arch collapsed while the supports spread */
  /* counters */
  size_t steps;              /* time steps taken (at rest: none) */
  size_t steps_direct;       /* solved along the chain with the state guessed */
  size_t steps_siconos;      /* needing Siconos */
  size_t active_set_iters;   /* chain solves in all */
  size_t siconos_pivots;     /* Lemke pivots (or NSGS sweeps) in all */
  size_t statics;            /* static ranges found (linear programs pairs) */
  size_t steps_loose;        /* steps whose contact problem Siconos solved only to 1e-3 of the
                                step's scales (docs/blocks.md) */
  /* per-voussoir history (when asked): sample i, voussoir k at
   * [i * nvous + k] of each (centroid x, y, m; rotation, rad) */
  size_t nvous;
  double *hist_x_m, *hist_y_m, *hist_rot_rad;
} aq_blocks_result;

void aq_blocks_result_free(aq_blocks_result *r);

/* The block model of arch (every voussoir a body: free control).
 * Opens Siconos Numerics (AQ_EUNSUPPORTED if it cannot). */
aq_blocks *aq_blocks_alloc(const aq_arch *arch, aq_error *err);
/* The block model as the arch asks for it: its friction (required:
 * AQ_EVALUE, field "friction", without one), [contact] e_n, [supports]
 * spread_m and abutment_m, its hinge control (fixed: the arch's sets' joints free, every
 * other bonded), the step dt_s.  Errors name the field (not the file). */
aq_blocks *aq_blocks_for_arch(const aq_arch *arch, double dt_s, aq_error *err);
void aq_blocks_free(aq_blocks *b);

/* Options; each returns AQ_EVALUE (field named) for a value out of range. */
aq_status aq_blocks_set_friction(aq_blocks *b, double mu, aq_error *err); /* > 0, finite; required */
aq_status aq_blocks_set_restitution(aq_blocks *b, double e_n, aq_error *err); /* [0, 1], default 0 */
aq_status aq_blocks_set_dt(aq_blocks *b, double dt_s, aq_error *err);      /* > 0 */
/* The supports move apart by spread_m (quasi-statically, before the
 * record starts): 0 <= spread_m < the span's limit (aq_blocks_spread_max). */
aq_status aq_blocks_set_spread(aq_blocks *b, double spread_m, aq_error *err);
double aq_blocks_spread_max(const aq_blocks *b);
/* The arch's limit of the spread (what aq_blocks_spread_max gives its
 * model), and the check aq_blocks_set_spread makes of spread_m against it,
 * without a model (no Siconos): for the commands to refuse an arch whose
 * supports the block model could never span before any run. */
double aq_blocks_spread_reach(const aq_arch *arch);
aq_status aq_blocks_check_spread(const aq_arch *arch, double spread_m, aq_error *err);
aq_status aq_blocks_set_control(aq_blocks *b, aq_blocks_control c, aq_error *err);
/* How far each support's face runs beyond both ends of the springing joint
 * it bears, m (>= 0, finite; default 0: the springing joint as drawn).  On
 * test bodies, every face of the ground.  AQ_EVALUE (field "abutment_m"). */
aq_status aq_blocks_set_abutment(aq_blocks *b, double abutment_m, aq_error *err);
void aq_blocks_set_history(aq_blocks *b, int on);
/* Every step's acceleration times scale (its sign the polarity; the
 * vertical at |scale|), default 1. */
void aq_blocks_set_scale(aq_blocks *b, double scale);
/* Test and bench switches: 0 turns off the skipping of steps at rest (every
 * step then solved), the direct chain solve (every step by Siconos), the
 * projection of closed joints after each step. */
void aq_blocks_set_rest_skip(aq_blocks *b, int on);
void aq_blocks_set_direct(aq_blocks *b, int on);
void aq_blocks_set_projection(aq_blocks *b, int on);

/* Run from rest (after the spread, if any).  res is overwritten (free with
 * aq_blocks_result_free).  AQ_EVALUE when no friction was set or steps
 * holds none; AQ_ENUMERIC when a contact problem could not be solved ("at
 * t = ... s") or the linear program of the static range at rest failed;
 * AQ_ENOMEM.  A step with g + the vertical acceleration <= 0 is no error:
 * the arch is not held at rest then, and the step is solved as any other
 * (the voussoirs may leave their supports). */
aq_status aq_blocks_run(aq_blocks *b, const aq_steps *steps, aq_blocks_result *res,
                        aq_error *err);

/* After a run: the record time since which the arch has been at rest at
 * the end (the first step's start if it never moved); NAN if it was
 * moving at the end, collapsed or failed. */
double aq_blocks_rest_since(const aq_blocks *b);

/* "0e,6i,12e,19i" of the opened hinges into buf[n] (times: NULL, or
 * their first opening times "0.113,0.113,..." into tbuf[tn]). */
void aq_blocks_hinges_text(const aq_blocks_result *r, char *buf, size_t n, char *tbuf,
                           size_t tn);

#endif
