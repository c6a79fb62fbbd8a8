/* test_dyn_steps.h: step lists and runs shared by the dynamics tests: a
 * rectangular pulse, pseudo-random records, one run with the history on. */
#ifndef AQ_TEST_DYN_STEPS_H
#define AQ_TEST_DYN_STEPS_H

#include <math.h>
#include <stdlib.h>

#include "arch/arch.h"
#include "arch/stepper.h"
#include "check.h"

/* acc for dur, then 0 until end, in equal steps of at most dt (at least
 * one step each).  1 on success. */
static inline int tds_pulse(double acc, double dur, double end, double dt,
                            aq_steps *s)
{
  size_t n1 = (size_t)ceil(dur / dt - 1e-9), n2 = (size_t)ceil((end - dur) / dt - 1e-9);
  n1 = n1 ? n1 : 1;
  n2 = n2 ? n2 : 1;
  size_t n = n1 + n2;
  double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d),
         *ac = malloc(n * sizeof *ac);
  int ok = t && d && ac;
  for (size_t i = 0; ok && i < n; i++) {
    int first = i < n1;
    double t0 = first ? 0 : dur, span = first ? dur : end - dur;
    size_t k = first ? i : i - n1, m = first ? n1 : n2;
    t[i] = t0 + span * k / m;
    d[i] = t0 + span * (k + 1) / m - t[i];
    ac[i] = first ? acc : 0;
  }
  aq_error e;
  ok = ok && aq_steps_from_list(t, d, ac, n, s, &e) == AQ_OK;
  free(t);
  free(d);
  free(ac);
  return ok;
}

/* Uniform in [0, 1) from a 64-bit LCG state. */
static inline double tds_rng(unsigned long long *x)
{
  *x = *x * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*x >> 11) / 9007199254740992.0;
}

/* n random steps: durations 0.1 ms to 80 ms, accelerations up to amp
 * (0.8..2.2, drawn) times a_neg_mps2 below zero and a_pos_mps2 above. */
static inline void tds_random(unsigned long long *x, double a_neg_mps2,
                              double a_pos_mps2, double *t, double *d,
                              double *acc, size_t n)
{
  double tt = 0, amp = 0.8 + 1.4 * tds_rng(x);
  for (size_t i = 0; i < n; i++) {
    t[i] = tt;
    d[i] = 1e-4 + 0.08 * tds_rng(x) * tds_rng(x);
    tt += d[i];
    double u = 2 * tds_rng(x) - 1;
    acc[i] = u * amp * (u < 0 ? a_neg_mps2 : a_pos_mps2);
  }
}

/* Run model mdl (COR cor, impact rule, ode tolerance rtol, scale k) on the
 * steps with the history on; a failure is a failed check.  1 on success. */
static inline int tds_run(const aq_arch *a, aq_model mdl, double cor,
                          int momentum, double rtol, double k,
                          const aq_steps *s, aq_result *r)
{
  aq_error e;
  aq_stepper *st = aq_stepper_alloc(aq_arch_path(a, 0), aq_arch_path(a, 1),
                                    mdl, &e);
  int ok = st != NULL;
  if (st) {
    aq_stepper_set_cor(st, cor);
    aq_stepper_set_impact(st, momentum);
    aq_stepper_set_ode_rtol(st, rtol);
    aq_stepper_set_history(st, 1);
    aq_stepper_set_scale(st, k);
    ok = aq_stepper_run(st, s, r, &e) == AQ_OK;
  }
  if (!ok)
    aq_check(0, "model %d: %s", (int)mdl, e.message);
  aq_stepper_free(st);
  return ok;
}

#endif
