/* stepper.h: dynamic response of a two-set hinge mechanism to a list of
 * constant-acceleration steps (CVODE-like lifecycle: alloc, set options,
 * run, read counters from the result, free).
 *
 * Models: AQ_MODEL_WORKPATH (default: exact energy balance, docs/method.md
 * sec. 4-9, integrated as time-Taylor series on the path's pieces),
 * AQ_MODEL_WORKPATH_QUAD (the same balance by time quadrature; a second
 * reference), AQ_MODEL_ODE (Lagrangian equation of motion with GSL odeiv2;
 * the reference), AQ_MODEL_PAPER (the paper's printed fits; for comparison
 * only).  Counters (steps, moving steps, sub-steps, path evaluations,
 * impacts, reversals) are in the result.
 * The stepper keeps pointers to the two paths (the arch outlives it).
 * One stepper per thread.  aq_stepper_free accepts NULL. */
#ifndef AQ_ARCH_STEPPER_H
#define AQ_ARCH_STEPPER_H

#include "../error.h"
#include "../signal/steps.h"
#include "path.h"
#include "result.h"

typedef enum {
  AQ_MODEL_WORKPATH = 0,  /* time-Taylor leg on the path's pieces (leg_taylor.c) */
  AQ_MODEL_ODE,           /* GSL rk8pd on the equation of motion (eom.c) */
  AQ_MODEL_PAPER,         /* the paper's printed fits (paper.c) */
  AQ_MODEL_WORKPATH_QUAD, /* time integral by Chebyshev panels (leg_quad.c) */
  AQ_MODEL_BLOCKS         /* rigid voussoirs in frictional contact: not this stepper's
                             (src/blocks/blocks.h runs it; aq_stepper_alloc refuses it) */
} aq_model;

/* The models' names, indexed by aq_model and NULL-terminated ("workpath",
 * "ode", "paper", "workpath-quad", "blocks"): --model's words, the model
 * column. */
extern const char *const aq_model_names[];
/* The name of model m, or "?" outside the enum. */
const char *aq_model_name(aq_model m);

typedef struct aq_stepper aq_stepper;

/* A model run by a stage above this one (the block model,
 * src/blocks/blocks.h), driven through a stepper so that the job layer and
 * its callers (the main job, capacity, archquake-mpi) keep one kind of
 * stepper: run fills res as aq_stepper_run does (steps times scale, the
 * history when asked), rest_since answers aq_stepper_rest_since, free
 * frees ctx (aq_stepper_free calls it). */
typedef struct {
  void *ctx;
  aq_status (*run)(void *ctx, const aq_steps *steps, double scale, int history,
                   aq_result *res, aq_error *err);
  double (*rest_since)(const void *ctx);
  void (*free)(void *ctx);
} aq_stepper_delegate;

/* A stepper whose runs are d's (model names it: AQ_MODEL_BLOCKS); the
 * setters of the four-hinge models (cor, impact, tolerances, demand) do not
 * apply to it and are ignored.  On failure d->free(d->ctx) is called. */
aq_stepper *aq_stepper_alloc_delegate(aq_model model, const aq_stepper_delegate *d,
                                      aq_error *err);

aq_stepper *aq_stepper_alloc(const aq_path *primary, const aq_path *reverse,
                             aq_model model, aq_error *err);
void aq_stepper_free(aq_stepper *st);

void aq_stepper_set_cor(aq_stepper *st, double cor);           /* 0..1, KE ratio */
void aq_stepper_set_impact(aq_stepper *st, int momentum);      /* 1: impulse-momentum rule */
void aq_stepper_set_ode_rtol(aq_stepper *st, double rtol);     /* ode model tolerance */
void aq_stepper_set_history(aq_stepper *st, int on);           /* keep a history (step ends, turning points, events) */
/* Added for the dynamics validations and the bench (all optional): */
void aq_stepper_set_exact_path(aq_stepper *st, int on); /* use eval_exact, not tables */
void aq_stepper_set_wp_tol(aq_stepper *st, double tol);  /* workpath-quad panel tolerance (relative, time) */
void aq_stepper_set_wp_nodes(aq_stepper *st, int n);     /* workpath-quad Chebyshev nodes per panel, 4..32 */
void aq_stepper_set_taylor_tol(aq_stepper *st, double tol); /* workpath series tail / motion (default 1e-14) */
/* Run with every step's acceleration multiplied by scale (default 1; any
 * finite value: a negative scale reverses the polarity), without a scaled
 * copy of the steps. */
void aq_stepper_set_scale(aq_stepper *st, double scale);
void aq_stepper_set_rest_tol(aq_stepper *st, double tol);/* rest: KE <= tol * m_T g y(s_c) after an impact */

/* Track what each run asks of the joints with d (demand.h; the stepper
 * takes it and frees it; NULL: none): every leg's start, end and turning
 * points are its samples.  The paper model has no joint forces: its runs
 * are not tracked. */
typedef struct aq_demand aq_demand;
void aq_stepper_set_demand(aq_stepper *st, aq_demand *d);

/* Run from rest at q = 0.  res is overwritten (free with aq_result_free).
 * Errors name the time in the record ("at t = 12.340 s"). */
aq_status aq_stepper_run(aq_stepper *st, const aq_steps *steps,
                         aq_result *res, aq_error *err);

/* After a successful aq_stepper_run: the record time (s) since which the
 * arch has been at rest (s = 0, no kinetic energy, by the rest criterion of
 * aq_stepper_set_rest_tol or a plastic stop) at the end of the steps; the
 * first step's start if it never moved.  NAN if it was still moving at the
 * end, collapsed, or the run failed. */
double aq_stepper_rest_since(const aq_stepper *st);

#endif
