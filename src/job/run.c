/* run.c: runs of a subject, through the arch's stepper (run.h). */
#include "run.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../arch/demand.h"
#include "../blocks/blocks.h"
#include "../units.h"

/* ---- the block model as a stepper ------------------------------------ */

static aq_status blocks_run(void *ctx, const aq_steps *steps, double scale, int history,
                            aq_result *res, aq_error *err)
{
  aq_blocks *b = ctx;
  aq_blocks_set_scale(b, scale);
  aq_blocks_set_history(b, history);
  aq_blocks_result br;
  memset(res, 0, sizeof *res);
  res->collapse_time_s = NAN;
  aq_status s = aq_blocks_run(b, steps, &br, err);
  if (s != AQ_OK)
    return s;
  aq_result_bodies *x = calloc(1, sizeof *x);
  size_t cap = 24 * (br.nhinges + 1);
  char *hb = malloc(cap), *tb = malloc(cap);
  if (!x || !hb || !tb) {
    free(x);
    free(hb);
    free(tb);
    aq_blocks_result_free(&br);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "blocks", "out of memory");
  }
  aq_blocks_hinges_text(&br, hb, cap, tb, cap);
  *res = br.r; /* the common columns; the history moves with them */
  memset(&br.r, 0, sizeof br.r);
  /* the joints' demand is the four-hinge model's question (docs/demand.md) */
  res->mu_demand = res->thrust_ecc_max = res->thrust_ecc_time_s = res->slide_time_s = NAN;
  *x = (aq_result_bodies){br.max_slip_m, hb, tb, br.mechanism_changed_s, br.steps_siconos,
                          br.steps_loose, br.nvous, br.hist_x_m, br.hist_y_m,
                          br.hist_rot_rad, br.friction_work_j};
  br.hist_x_m = br.hist_y_m = br.hist_rot_rad = NULL;
  res->bodies = x;
  aq_blocks_result_free(&br);
  return AQ_OK;
}

static double blocks_rest(const void *ctx) { return aq_blocks_rest_since(ctx); }
static void blocks_free(void *ctx) { aq_blocks_free(ctx); }

aq_stepper *aq_job_stepper_blocks(const aq_arch *arch, double dt_s, int history,
                                  aq_error *err)
{
  aq_blocks *b = aq_blocks_for_arch(arch, dt_s, err);
  if (!b)
    return NULL;
  aq_blocks_set_history(b, history);
  aq_stepper_delegate d = {b, blocks_run, blocks_rest, blocks_free};
  aq_stepper *st = aq_stepper_alloc_delegate(AQ_MODEL_BLOCKS, &d, err);
  if (st)
    aq_stepper_set_history(st, history);
  return st;
}

int aq_job_marks_apply(const aq_arch *arch, aq_model model)
{
  return model != AQ_MODEL_BLOCKS && model != AQ_MODEL_PAPER &&
         (!isnan(aq_arch_friction(arch)) || aq_arch_control(arch) == AQ_CONTROL_FREE);
}

int aq_job_run_marks(const aq_arch *arch, const aq_result *res)
{
  return aq_result_marks(res->mu_demand, res->thrust_ecc_max, aq_arch_friction(arch),
                         aq_arch_control(arch) == AQ_CONTROL_FREE);
}

aq_stepper *aq_job_stepper(const aq_arch *arch, aq_model model, double cor, int history,
                           int demand, aq_error *err)
{
  if (model == AQ_MODEL_BLOCKS)
    return aq_job_stepper_blocks(arch, AQ_BLOCKS_DT_DEFAULT_S, history, err);
  aq_stepper *st = aq_stepper_alloc(aq_arch_path(arch, 0), aq_arch_path(arch, 1), model, err);
  if (!st)
    return NULL;
  const aq_arch_dynamics *d = aq_arch_dynamics_of(arch);
  aq_stepper_set_cor(st, isnan(cor) ? d->cor : cor);
  aq_stepper_set_impact(st, d->impact == AQ_IMPACT_MOMENTUM);
  aq_stepper_set_history(st, history);
  /* what each run asks of the joints (docs/demand.md), against the arch's
   * friction */
  if (!demand)
    return st;
  aq_demand *dm = aq_arch_demand_tracker(arch, aq_arch_friction(arch), err);
  if (!dm) {
    aq_stepper_free(st);
    return NULL;
  }
  if (demand == AQ_JOB_DEMAND_MARKS)
    aq_demand_set_marks_only(dm, !isnan(aq_arch_friction(arch)),
                             aq_arch_control(arch) == AQ_CONTROL_FREE);
  aq_stepper_set_demand(st, dm);
  return st;
}

aq_arch_dynamics aq_job_dynamics(const aq_arch *arch, double cor)
{
  aq_arch_dynamics used = *aq_arch_dynamics_of(arch);
  used.cor = used.impact == AQ_IMPACT_MOMENTUM ? NAN : isnan(cor) ? used.cor : cor;
  return used;
}

aq_status aq_job_run_view(aq_stepper *st, const aq_view *v, double sa, aq_result *res,
                          aq_error *err)
{
  /* the stepper starts every run afresh (the ode model's step size
   * included), so results do not depend on which runs it did before */
  aq_stepper_set_scale(st, sa);
  aq_status s = aq_stepper_run(st, &v->steps, res, err);
  aq_stepper_set_scale(st, 1.0);
  return s;
}

void aq_runs_free(aq_runs *R)
{
  if (R->unit && R->view_st == AQ_OK)
    aq_view_free(&R->view);
  for (size_t k = 0; R->list_st && k < R->nlist; k++)
    if (R->list_st[k] == AQ_OK)
      aq_steps_free(&R->list[k]);
  free(R->list);
  free(R->list_st);
  free(R->list_err);
  free(R->list_pga_g);
  memset(R, 0, sizeof *R);
}

aq_status aq_runs_init(aq_runs *R, const aq_subject *s, size_t naz, double theta_deg,
                       double merge_tol_mps2, const double *slot_sa, size_t nslot,
                       int per_arch, aq_error *err)
{
  memset(R, 0, sizeof *R);
  R->s = s;
  R->merge_tol_mps2 = merge_tol_mps2;
  R->unit = naz == 1 && merge_tol_mps2 == 0;
  if (R->unit) {
    R->view_st = aq_view_make(&R->view, s, theta_deg, &R->view_err);
    return AQ_OK;
  }
  if (naz != 1 || per_arch)
    return AQ_OK;
  R->list = calloc(nslot ? nslot : 1, sizeof *R->list);
  R->list_st = calloc(nslot ? nslot : 1, sizeof *R->list_st);
  R->list_err = calloc(nslot ? nslot : 1, sizeof *R->list_err);
  R->list_pga_g = calloc(nslot ? nslot : 1, sizeof *R->list_pga_g);
  if (!R->list || !R->list_st || !R->list_err || !R->list_pga_g) {
    aq_runs_free(R);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  }
  R->nlist = nslot;
  for (size_t k = 0; k < nslot; k++) {
    double peak = 0, sa = slot_sa[k];
    aq_error_clear(&R->list_err[k]);
    R->list_st[k] = aq_subject_steps(s, theta_deg, sa, fabs(sa), merge_tol_mps2, &R->list[k], &peak,
                                     &R->list_err[k]);
    R->list_pga_g[k] = peak / AQ_G0_MPS2;
  }
  return AQ_OK;
}

aq_status aq_runs_run(const aq_runs *R, size_t k, double theta_deg, double sa,
                      aq_stepper *st, aq_result *res, double *pga_g, int *steps_failed,
                      int *ran, aq_error *err)
{
  aq_steps own;
  const aq_steps *steps = NULL;
  aq_status s;
  int have_own = 0;
  *steps_failed = 0;
  *ran = 0;
  int view = R->unit && isfinite(sa);
  if (view) { /* the view at factor 1, sa given to the stepper */
    s = R->view_st;
    *pga_g = s == AQ_OK ? fabs(sa) * R->view.peak_mps2 / AQ_G0_MPS2 : 0;
    if (s != AQ_OK)
      *err = R->view_err;
  } else if (k < R->nlist) { /* the merged list of this slot */
    s = R->list_st[k];
    steps = &R->list[k];
    *pga_g = R->list_pga_g[k];
    if (s != AQ_OK)
      *err = R->list_err[k];
  } else { /* made for this run */
    double peak = 0;
    aq_error_clear(err);
    s = aq_subject_steps(R->s, theta_deg, sa, fabs(sa), R->merge_tol_mps2, &own, &peak, err);
    *pga_g = peak / AQ_G0_MPS2;
    have_own = s == AQ_OK;
    steps = &own;
  }
  if (s != AQ_OK) {
    *steps_failed = 1;
    return s;
  }
  if (st) {
    aq_error_clear(err);
    memset(res, 0, sizeof *res);
    *ran = 1;
    s = view ? aq_job_run_view(st, &R->view, sa, res, err)
                : aq_stepper_run(st, steps, res, err);
  }
  if (have_own)
    aq_steps_free(&own);
  return s;
}
