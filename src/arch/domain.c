/* domain.c: the half-cycle collapse domain (see domain.h). */
#include <math.h>
#include <string.h>

#include "domain.h"

static const double FREE_TAIL_S = 30;  /* free motion after the pulse, s */
static const double FIRST_DUR_S = 0.01; /* first duration tried, s */

/* 1 if a pulse of a_mps2 for dur_s collapses the arch, 0 if not, -1 on
 * error; a collapsing run's result into *keep (not NULL), replacing it. */
static int collapses(aq_stepper *st, double a_mps2, double dur_s, aq_result *keep,
                     aq_error *err)
{
  double t[2] = {0, dur_s}, dt[2] = {dur_s, FREE_TAIL_S}, a[2] = {a_mps2, 0};
  aq_steps s;
  if (aq_steps_from_list(t, dt, a, 2, &s, err) != AQ_OK)
    return -1;
  aq_result r;
  aq_status rc = aq_stepper_run(st, &s, &r, err);
  aq_steps_free(&s);
  if (rc != AQ_OK)
    return -1;
  int c = r.collapsed;
  if (c && keep) {
    aq_result_free(keep);
    *keep = r;
  } else {
    aq_result_free(&r);
  }
  return c;
}

aq_status aq_domain_min_duration(aq_stepper *st, const aq_path *primary,
                                 double ratio, double tol_s, double tmax_s,
                                 double *accel_mps2, double *dur_s,
                                 aq_error *err)
{
  return aq_domain_min_duration_run(st, primary, ratio, tol_s, tmax_s, accel_mps2, dur_s,
                                    NULL, err);
}

aq_status aq_domain_min_duration_run(aq_stepper *st, const aq_path *primary, double ratio,
                                     double tol_s, double tmax_s, double *accel_mps2,
                                     double *dur_s, aq_result *run, aq_error *err)
{
  if (run)
    memset(run, 0, sizeof *run);
  double a = primary->act_sign * ratio * primary->lambda0 * primary->g_mps2;
  double lo = 0, hi = FIRST_DUR_S;
  int ch;
  *accel_mps2 = a;
  *dur_s = INFINITY;
  while ((ch = collapses(st, a, hi, run, err)) == 0 && hi < tmax_s) {
    lo = hi;
    hi = fmin(2 * hi, tmax_s);
  }
  if (ch < 0)
    return err ? err->status : AQ_EINTERNAL;
  if (ch == 0)
    return AQ_OK;
  while (hi - lo > tol_s) {
    double mid = 0.5 * (lo + hi);
    if ((ch = collapses(st, a, mid, run, err)) < 0)
      return err ? err->status : AQ_EINTERNAL;
    if (ch)
      hi = mid;
    else
      lo = mid;
  }
  *dur_s = hi;
  return AQ_OK;
}
