/* test_dyn_arch.c: the dynamic models on the shipped arches (arches/NAME.cfg):
 * energy conservation (paper section 4.2), the half-cycle domain (section
 * 4.1) from two independent integrations, its limits, and hard cases. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"
#include "arch/stepper.h"
#include "arch_fixture.h"
#include "check.h"
#include "units.h"

static aq_stepper *stepper(const aq_arch *a, aq_model m, double cor,
                           double rtol)
{
  aq_error e;
  aq_stepper *st = aq_stepper_alloc(aq_arch_path(a, 0), aq_arch_path(a, 1), m,
                                    &e);
  aq_check(st != NULL, "stepper: %s", st ? "" : e.message);
  if (st) {
    aq_stepper_set_cor(st, cor);
    aq_stepper_set_ode_rtol(st, rtol);
  }
  return st;
}

/* Pulse a for dur, then free until end, in steps of at most dt. */
static int run_pulse(aq_stepper *st, double a, double dur, double end,
                     double dt, int hist, aq_result *r)
{
  size_t n1 = (size_t)ceil(dur / dt - 1e-9), n2 = (size_t)ceil((end - dur) / dt - 1e-9);
  if (n1 < 1)
    n1 = 1;
  if (n2 < 1)
    n2 = 1;
  size_t n = n1 + n2;
  double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d),
         *acc = malloc(n * sizeof *acc);
  for (size_t i = 0; i < n1; i++) {
    t[i] = dur * i / n1;
    d[i] = dur * (i + 1) / n1 - t[i];
    acc[i] = a;
  }
  for (size_t i = 0; i < n2; i++) {
    t[n1 + i] = dur + (end - dur) * i / n2;
    d[n1 + i] = dur + (end - dur) * (i + 1) / n2 - t[n1 + i];
    acc[n1 + i] = 0;
  }
  aq_steps s;
  aq_error e;
  int ok = aq_steps_from_list(t, d, acc, n, &s, &e) == AQ_OK;
  free(t);
  free(d);
  free(acc);
  if (!ok)
    return 0;
  aq_stepper_set_history(st, hist);
  ok = aq_stepper_run(st, &s, r, &e) == AQ_OK;
  if (!ok)
    aq_check(0, "run: %s", e.message);
  aq_steps_free(&s);
  return ok;
}

/* Shortest collapsing pulse of a by bisection to tol (seconds). */
static double min_duration(aq_stepper *st, double a, double tol)
{
  double lo = 0, hi = 0.01;
  aq_result r;
  for (;;) {
    if (!run_pulse(st, a, hi, hi + 30, 1e9, 0, &r))
      return NAN;
    int c = r.collapsed;
    aq_result_free(&r);
    if (c)
      break;
    lo = hi;
    hi *= 2;
    if (hi > 1000)
      return INFINITY;
  }
  while (hi - lo > tol) {
    double mid = 0.5 * (lo + hi);
    if (!run_pulse(st, a, mid, mid + 30, 1e9, 0, &r))
      return NAN;
    if (r.collapsed)
      hi = mid;
    else
      lo = mid;
    aq_result_free(&r);
  }
  return hi;
}

/* Section 4.2: COR = 1, 0.55 g for 0.5 s opening the primary set, then 20 s
 * of free motion at 0.02 s steps.  Total mechanical energy KE + m g y must
 * stay constant: the work path to round-off (README quotes 3e-15 per cycle;
 * the paper lost 0.4 % per cycle), the ode model to its tolerance. */
AQ_TEST(dyn_arch_energy_conservation_oppenheim)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  double acc = p->act_sign * 0.55 * AQ_G0_MPS2;
  for (int mdl = 0; mdl < 2; mdl++) {
    aq_stepper *st = stepper(a, (aq_model)mdl, 1.0, 1e-12);
    aq_result r;
    if (!st || !run_pulse(st, acc, 0.5, 20.5, 0.02, 1, &r)) {
      aq_stepper_free(st);
      continue;
    }
    const aq_history *h = &r.history;
    size_t i0 = 24; /* end of the pulse */
    double e0 = h->kinetic_energy_j[i0] + h->potential_energy_j[i0], dmax = 0;
    for (size_t i = i0; i < h->n; i++) {
      double e = h->kinetic_energy_j[i] + h->potential_energy_j[i];
      dmax = fmax(dmax, fabs(e - e0) / e0);
    }
    double cycles = 0.5 * (double)r.impacts;
    aq_check(!r.collapsed && r.impacts >= 10, "%s: rocks without collapse: "
             "%zu impacts, %.1f cycles in 20 s", mdl ? "ode" : "workpath",
             r.impacts, cycles);
    /* measured 3.2e-15 (workpath) and 1.3e-14 (ode) per cycle */
    aq_check(dmax / fmax(cycles, 1) <= (mdl ? 5e-13 : 1e-13),
             "%s: energy drift %.3g relative over %.1f cycles (%.3g per cycle)",
             mdl ? "ode" : "workpath", dmax, cycles, dmax / fmax(cycles, 1));
    aq_check_rel(r.energy_in_j - r.energy_dissipated_j, e0, 2e-13,
                 "energy in - dissipated = energy after the pulse");
    aq_result_free(&r);
    aq_stepper_free(st);
  }
  aq_arch_free(a);
}

/* Section 4.1 domain: work path and ode (rtol 1e-12) agree to 1e-6 at every
 * default ratio, both by bisection to 1e-9 s through the CLI. */
AQ_TEST(dyn_arch_domain_workpath_vs_ode)
{
  static char o1[4096], o2[4096], e1[4096];
  int rc1 = aq_test_run("domain --arch arches/oppenheim.cfg", o1, sizeof o1,
                        e1, sizeof e1);
  int rc2 = aq_test_run("domain --arch arches/oppenheim.cfg --model ode "
                        "--ode-rtol 1e-12",
                        o2, sizeof o2, e1, sizeof e1);
  aq_check(rc1 == 0 && rc2 == 0, "domain runs: %d %d %s", rc1, rc2, e1);
  aq_check(strncmp(o1, "ratio\taccel_g\tmin_duration_s\tstatus\n", 36) == 0,
           "header: %.40s", o1);
  char *l1 = strchr(o1, '\n'), *l2 = strchr(o2, '\n');
  int rows = 0;
  double prev = INFINITY;
  while (l1 && l2) {
    double r1, a1, t1, r2, a2, t2;
    if (sscanf(l1 + 1, "%lf %lf %lf", &r1, &a1, &t1) != 3 ||
        sscanf(l2 + 1, "%lf %lf %lf", &r2, &a2, &t2) != 3)
      break;
    rows++;
    aq_check(r1 == r2 && a1 == a2, "same ratio row");
    aq_check_rel(t1, t2, 1e-15, "r = %g: workpath vs ode min duration", r1);
    aq_check(t1 < prev, "duration decreases with r (%g: %g)", r1, t1);
    prev = t1;
    l1 = strchr(l1 + 1, '\n');
    l2 = strchr(l2 + 1, '\n');
  }
  aq_check(rows == 7, "7 default ratios, got %d", rows);
}

/* Very short pulses: the pulse acts as an impulse.  The generalised
 * momentum it gives, M(0) sdot = m_T |a| |dx/ds(0)| T, must carry the arch
 * over the potential barrier: 1/2 M(0) sdot^2 = m_T g y(s_c), so
 *   |a| T -> sqrt(2 M(0) g y(s_c) / m_T) / |dx/ds(0)|   as r -> infinity,
 * with an error O(1/r) (gravity's share of the impulse). */
AQ_TEST(dyn_arch_domain_impulse_limit)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  aq_path_point p0, pc;
  p->eval_exact(p->ctx, 0, &p0);
  p->eval_exact(p->ctx, p->s_c_rad, &pc);
  double lim = sqrt(2 * p0.mgen_kgm2 * p->g_mps2 * pc.y_m / p->mass_kg) /
               fabs(p0.dx_m);
  aq_stepper *st = stepper(a, AQ_MODEL_WORKPATH, 0, 1e-10);
  double rs[] = {25, 50, 100, 200}, err_prev = INFINITY;
  for (size_t k = 0; k < 4 && st; k++) {
    double acc = rs[k] * p->lambda0 * p->g_mps2;
    double T = min_duration(st, p->act_sign * acc, 1e-12);
    double err = fabs(acc * T / lim - 1);
    aq_check(err < 0.6 * err_prev, "r = %g: |a|T = %.6g, limit %.6g, rel %.3g "
             "(shrinking like 1/r)", rs[k], acc * T, lim, err);
    aq_check(err < 1.5 / rs[k], "r = %g: within 1.5/r of the impulse limit",
             rs[k]);
    err_prev = err;
  }
  aq_stepper_free(st);
  aq_arch_free(a);
}

/* r -> 1: the arch leaves s = 0 like an inverted pendulum, s ~ (r - 1)
 * (cosh p t - 1) with p^2 = -m_T (a x''(0) + g y''(0)) / M(0), so each
 * decade of (r - 1) adds ln(10) / p to the shortest collapsing pulse: the
 * duration grows without bound, logarithmically. */
AQ_TEST(dyn_arch_domain_near_threshold)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  aq_path_point p0;
  p->eval_exact(p->ctx, 0, &p0);
  double a1 = p->act_sign * p->lambda0 * p->g_mps2;
  double k = -p->mass_kg * (a1 * p0.d2x_m + p->g_mps2 * p0.d2y_m);
  double pp = sqrt(k / p0.mgen_kgm2);
  aq_stepper *st = stepper(a, AQ_MODEL_WORKPATH, 0, 1e-10);
  double T[3], eps[3] = {1e-2, 1e-3, 1e-4};
  for (int i = 0; i < 3 && st; i++) {
    T[i] = min_duration(st, a1 * (1 + eps[i]), 1e-9);
    aq_check(isfinite(T[i]), "r = 1 + %g: finite duration %g", eps[i], T[i]);
  }
  aq_check(T[0] < T[1] && T[1] < T[2], "grows as r -> 1: %g %g %g", T[0],
           T[1], T[2]);
  aq_check_rel(T[2] - T[1], log(10) / pp, 0.02,
               "decade increment vs ln(10)/p (p = %.6g rad/s)", pp);
  aq_check_rel(T[1] - T[0], log(10) / pp, 0.005, "previous decade");
  aq_stepper_free(st);
  aq_arch_free(a);
}

/* A pulse just above the shortest collapsing one: the arch creeps over the
 * saddle of the potential near q_c with almost no kinetic energy.  The work
 * path maps that near-double zero of KE analytically (sinh substitution):
 * its collapse time agrees with ode and it stays cheap (counters). */
AQ_TEST(dyn_arch_marginal_collapse)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  double acc = p->act_sign * 2.0 * p->lambda0 * p->g_mps2;
  aq_stepper *sw = stepper(a, AQ_MODEL_WORKPATH, 0, 1e-10);
  aq_stepper *so = stepper(a, AQ_MODEL_ODE, 0, 1e-13);
  double T = sw ? min_duration(sw, acc, 1e-12) : NAN;
  for (int k = 0; k < 3 && sw && so; k++) {
    double dur = T * (1 + 1e-8 * pow(100, k)); /* 1e-8, 1e-6, 1e-4 above */
    aq_result rw, ro;
    if (!run_pulse(sw, acc, dur, dur + 30, 1e9, 0, &rw))
      break;
    if (!run_pulse(so, acc, dur, dur + 30, 1e9, 0, &ro)) {
      aq_result_free(&rw);
      break;
    }
    aq_check(rw.collapsed && ro.collapsed, "collapses %g above", 1e-8 * pow(100, k));
    aq_check_rel(rw.collapse_time_s, ro.collapse_time_s, 1e-6,
                 "collapse time %g above the threshold", 1e-8 * pow(100, k));
    aq_check(rw.evals < 800, "work path stays cheap: %zu evaluations (ode %zu)",
             rw.evals, ro.evals);
    aq_result_free(&rw);
    aq_result_free(&ro);
  }
  aq_stepper_free(sw);
  aq_stepper_free(so);
  aq_arch_free(a);
}

/* A constant pulse and the free swing after it, step by step (0.01 s): the
 * work path follows the ode model at rtol 1e-12 on the exact kinematics
 * (an independent integration of the equation of motion) to round-off at
 * every step end: 1.0e-15 rad apart.  (The work path's pieces fit the exact
 * kinematics, not the ode's Hermite tables, whose 4e-12 table error puts
 * the two 1.1e-14 rad apart.)  Eq. (19) taken literally, x(s) - x(s1) of
 * table values each ~1e-15 m, drifted steadily: 4.7e-12 rad apart over
 * this run. */
AQ_TEST(dyn_arch_pulse_no_drift)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  const double acc = p->act_sign * 0.5873 * AQ_G0_MPS2;
  aq_result r[2];
  int ok = 1;
  for (int k = 0; k < 2; k++) {
    aq_stepper *st = stepper(a, k ? AQ_MODEL_ODE : AQ_MODEL_WORKPATH, 0.7, 1e-12);
    if (st && k)
      aq_stepper_set_exact_path(st, 1);
    ok &= st && run_pulse(st, acc, 0.4371, 1.6, 0.01, 1, &r[k]);
    aq_stepper_free(st);
  }
  if (ok) {
    /* the work path's history also samples turning points and impacts:
     * compare the step ends (the samples at multiples of 0.01 s) */
    double dq = 0, qmax = 0;
    size_t n = 0, i0 = 0;
    for (size_t i = 0; i < r[1].history.n; i++) {
      double t = r[1].history.time_s[i];
      while (i0 < r[0].history.n && r[0].history.time_s[i0] < t - 1e-9)
        i0++;
      if (i0 >= r[0].history.n)
        break;
      n++;
      dq = fmax(dq, fabs(r[0].history.rotation_rad[i0] - r[1].history.rotation_rad[i]));
      qmax = fmax(qmax, fabs(r[1].history.rotation_rad[i]));
    }
    aq_check(r[0].impacts == r[1].impacts && r[0].reversals >= 1 && n > 150,
             "same motion: %zu impacts, %zu reversals", r[0].impacts,
             r[0].reversals);
    aq_check(dq <= 3e-15, "step ends agree to %.3g rad (peak %.3g rad)", dq, qmax);
    aq_result_free(&r[0]);
    aq_result_free(&r[1]);
  }
  aq_arch_free(a);
}
