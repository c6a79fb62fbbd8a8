/* run.h: a run: a subject at a factor (its sign the polarity), an azimuth
 * and an arch, through the arch's stepper, giving an aq_result.
 *
 * A subject's runs share what they can (aq_runs, made once per subject):
 *   - one azimuth, no merging: a view at factor 1, every run giving its
 *     factor to the stepper (no scaled copy, no step list per run);
 *   - one azimuth, merging (--merge-tol), factors known before the arch:
 *     a merged list per (factor, polarity), shared by the arches;
 *   - otherwise each run makes its own list (one azimuth of a motion at a
 *     time, or a factor per arch).
 * Which of them a run used does not change its result, bit for bit (the
 * pinned outputs, tests/pin.sh, hold it).  Units: factors dimensionless,
 * pga_g in g.  Nothing here prints. */
#ifndef AQ_JOB_RUN_H
#define AQ_JOB_RUN_H

#include <stddef.h>

#include "../arch/arch.h"
#include "../arch/result.h"
#include "../arch/stepper.h"
#include "../error.h"
#include "subject.h"

/* A stepper for arch: model, cor (NAN: the arch's own), the arch's impact
 * rule, histories kept or not, and (demand AQ_JOB_DEMAND_FULL) what each
 * run asks of the joints tracked against the arch's friction
 * (docs/demand.md), or (AQ_JOB_DEMAND_MARKS) only whether it slides or,
 * with free hinges, its thrust leaves the section (aq_demand_set_marks_only:
 * the marks to the bit, the maxima partial).  NULL (err) when it cannot be
 * made. */
enum { AQ_JOB_DEMAND_NONE = 0, AQ_JOB_DEMAND_FULL = 1, AQ_JOB_DEMAND_MARKS = 2 };

/* 1 when a run of arch under model can carry a mark (docs/demand.md): a
 * friction given or free hinges, under a four-hinge model that follows the
 * joints' forces (not paper, whose fits carry none, nor blocks). */
int aq_job_marks_apply(const aq_arch *arch, aq_model model);
/* The marks of res, a run of arch (arch/result.h AQ_MARK_*), against the
 * arch's friction and hinge control. */
int aq_job_run_marks(const aq_arch *arch, const aq_result *res);
aq_stepper *aq_job_stepper(const aq_arch *arch, aq_model model, double cor, int history,
                           int demand, aq_error *err);

/* The block model of arch (src/blocks/blocks.h aq_blocks_for_arch: its
 * friction required) at step dt_s, as a stepper (aq_stepper_alloc_delegate):
 * its runs fill an aq_result with the block model's own outputs in
 * res->bodies.  model AQ_MODEL_BLOCKS to aq_job_stepper gives this at the
 * default step.  NULL (err, field named) when it cannot be made. */
aq_stepper *aq_job_stepper_blocks(const aq_arch *arch, double dt_s, int history,
                                  aq_error *err);

/* The dynamics arch's runs use: its impact rule, cor (NAN: the arch's own)
 * over the file's, none (NAN) with the momentum rule. */
aq_arch_dynamics aq_job_dynamics(const aq_arch *arch, double cor);

/* Run st over view v at factor sa (its sign the polarity; the vertical at
 * |sa|).  res as aq_stepper_run's. */
aq_status aq_job_run_view(aq_stepper *st, const aq_view *v, double sa, aq_result *res,
                          aq_error *err);

/* The step lists a subject's runs share. */
typedef struct {
  const aq_subject *s;
  double merge_tol_mps2;
  int unit;              /* 1: view made (one azimuth, no merging) */
  aq_view view;
  aq_status view_st;
  aq_error view_err;
  size_t nlist;          /* merged lists: one per run slot, or 0 */
  aq_steps *list;
  aq_status *list_st;
  aq_error *list_err;
  double *list_pga_g;
} aq_runs;

/* The lists the runs of s will share: with naz == 1 azimuth (theta_deg),
 * a view without merging, else (merge_tol_mps2 > 0) the nslot lists
 * slot_sa[k] (factor and sign), unless per_arch (the factor waits for the
 * arch: nothing shared).  A list that cannot be made fails only its runs
 * (their status says so).  Returns AQ_OK, or AQ_ENOMEM (err). */
aq_status aq_runs_init(aq_runs *R, const aq_subject *s, size_t naz, double theta_deg,
                       double merge_tol_mps2, const double *slot_sa, size_t nslot,
                       int per_arch, aq_error *err);
void aq_runs_free(aq_runs *R);

/* One run: run slot k (its list, when made) at azimuth theta_deg, factor
 * sa (signed), with st (NULL: the arch cannot run).  *pga_g gets the PGA
 * the arch feels (0 when its steps failed).  Returns AQ_OK with res filled;
 * or the steps' failure with *steps_failed = 1;  A factor that is not
 * finite never goes to the stepper (which keeps only finite ones): such a
 * run makes its own list, as every run did before views; or, st NULL, AQ_OK without
 * running (*ran = 0); or the stepper's failure. */
aq_status aq_runs_run(const aq_runs *R, size_t k, double theta_deg, double sa,
                      aq_stepper *st, aq_result *res, double *pga_g, int *steps_failed,
                      int *ran, aq_error *err);

#endif
