/* test_dyn_hard.c: hard cases for the dynamic models, each with its stated
 * expectation (issue: threshold pulses, short strong pulses, many impacts,
 * step sizes, thin/thick arches, an inadmissible reverse set, a quiet
 * record, random step lists). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"
#include "arch/stepper.h"
#include "arch_fixture.h"
#include "check.h"
#include "test_dyn_steps.h"
#include "units.h"

/* Run model mdl on explicit steps; history on. */
static int hrun(const aq_arch *a, aq_model mdl, double cor, int momentum,
                const double *t, const double *dt, const double *acc, size_t n,
                aq_result *r)
{
  aq_error e;
  aq_steps s;
  if (aq_steps_from_list(t, dt, acc, n, &s, &e) != AQ_OK)
    return 0;
  int ok = tds_run(a, mdl, cor, momentum, 1e-12, 1, &s, r);
  aq_steps_free(&s);
  return ok;
}

/* A pulse a for dur then free until end, steps of at most dt. */
static int hpulse(const aq_arch *a, aq_model mdl, double cor, int momentum,
                  double acc, double dur, double end, double dt, aq_result *r)
{
  aq_steps s;
  if (!tds_pulse(acc, dur, end, dt, &s))
    return 0;
  int ok = tds_run(a, mdl, cor, momentum, 1e-12, 1, &s, r);
  aq_steps_free(&s);
  return ok;
}

/* 1.0001 lambda0 g for 2 s: the arch leaves rest like an inverted pendulum,
 * s(t) = (F/k) (cosh p t - 1) with F = eps m_T |a1 dx/ds(0)| the net
 * generalised force and k, p from the second derivatives at s = 0; it does
 * not collapse (the shortest collapsing pulse at this ratio is longer). */
AQ_TEST(dyn_hard_threshold_plus_1e4)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  aq_path_point p0;
  p->eval_exact(p->ctx, 0, &p0);
  double a1 = p->act_sign * p->lambda0 * p->g_mps2, eps = 1e-4, T = 2.0;
  double k = -p->mass_kg * (a1 * p0.d2x_m + p->g_mps2 * p0.d2y_m);
  double F = eps * p->mass_kg * fabs(a1 * p0.dx_m);
  double pp = sqrt(k / p0.mgen_kgm2);
  double want = F / k * (cosh(pp * T) - 1);
  for (int mdl = 0; mdl < 2; mdl++) {
    aq_result r;
    if (!hpulse(a, (aq_model)mdl, 0, 0, a1 * (1 + eps), T, T + 10, 0.01, &r))
      continue;
    size_t i = (size_t)(T / 0.01) - 1;
    aq_check_rel(fabs(r.history.rotation_rad[i]), want, 0.01,
                 "model %d: s(2 s) against the linearised closed form", mdl);
    aq_check(!r.collapsed && r.impacts == 1 && r.steps_moving > 0,
             "moves, returns, no collapse (impacts %zu)", r.impacts);
    aq_result_free(&r);
  }
  aq_arch_free(a);
}

/* 10 g for 1 ms: an impulse.  The generalised momentum m_T |dx/ds(0)|
 * (|a| - lambda0 g) T carries the arch to the s where m_T g y(s) equals the
 * kinetic energy it gives (displacement during the 1 ms neglected: 1e-4
 * relative); far from collapse. */
AQ_TEST(dyn_hard_10g_1ms)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  aq_path_point p0, pt;
  p->eval_exact(p->ctx, 0, &p0);
  double acc = 10 * AQ_G0_MPS2, T = 1e-3;
  double mom = p->mass_kg * fabs(p0.dx_m) * (acc - p->lambda0 * p->g_mps2) * T;
  double ke0 = 0.5 * mom * mom / p0.mgen_kgm2;
  double peak[2];
  for (int mdl = 0; mdl < 2; mdl++) {
    aq_result r;
    peak[mdl] = NAN;
    if (!hpulse(a, (aq_model)mdl, 0, 0, p->act_sign * acc, T, 5, 1e-3, &r))
      continue;
    peak[mdl] = r.peak_rotation_rad;
    p->eval_exact(p->ctx, r.peak_rotation_rad, &pt);
    /* the work of the ground in the 1 ms, |a| m_T dx/ds s(T), is the
     * kinetic energy plus the potential energy gained meanwhile: ke0 times
     * |a| / (|a| - lambda0 g) */
    double e_peak = ke0 * acc / (acc - p->lambda0 * p->g_mps2);
    aq_check_rel(p->mass_kg * p->g_mps2 * pt.y_m, e_peak, 0.0005,
                 "model %d: m g y(peak) = energy of the impulse", mdl);
    aq_check(!r.collapsed && r.impacts == 1, "no collapse, one impact");
    aq_result_free(&r);
  }
  aq_check_rel(peak[0], peak[1], 2e-13, "workpath vs ode peak rotation");
  aq_arch_free(a);
}

/* COR = 0.3 (and the momentum rule): many impacts of decreasing energy,
 * then rest by the stated criterion; all the energy put in is dissipated. */
AQ_TEST(dyn_hard_cor03_many_impacts)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  size_t imp[2] = {0, 0};
  for (int mom = 0; mom < 2; mom++)
    for (int mdl = 0; mdl < 2; mdl++) {
      aq_result r;
      if (!hpulse(a, (aq_model)mdl, 0.3, mom, p->act_sign * 0.55 * AQ_G0_MPS2,
                  0.45, 30, 0.01, &r))
        continue;
      const aq_history *h = &r.history;
      aq_check(!r.collapsed && r.impacts >= 5 && r.impacts <= 200,
               "%s rule, model %d: %zu impacts", mom ? "momentum" : "cor", mdl,
               r.impacts);
      aq_check(h->set[h->n - 1] == -1, "at rest at the end");
      aq_check_abs(r.energy_in_j - r.energy_dissipated_j, 0,
                   2e-13 * r.energy_in_j, "all energy dissipated at rest");
      if (!mom)
        imp[mdl] = r.impacts;
      aq_result_free(&r);
    }
  aq_check(imp[0] == imp[1], "same impacts in both models: %zu %zu", imp[0],
           imp[1]);
  aq_arch_free(a);
}

/* Steps from 0.05 s to 1e-5 s: a rectangular pulse split into any steps
 * gives the same motion (the work path is exact per step); a half-sine
 * pulse sampled at the step midpoints converges as dt^2. */
AQ_TEST(dyn_hard_time_steps_converge)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  double dts[] = {0.05, 0.01, 1e-3, 1e-4, 1e-5};
  double ref_pk = NAN, ref_x = NAN;
  for (size_t k = 0; k < 5; k++) {
    aq_result r;
    if (!hpulse(a, AQ_MODEL_WORKPATH, 0, 0, p->act_sign * 0.6 * AQ_G0_MPS2,
                0.4, 1.2, dts[k], &r))
      continue;
    if (k == 0) {
      ref_pk = r.peak_rotation_rad;
      ref_x = r.peak_displacement_m;
    }
    aq_check_rel(r.peak_rotation_rad, ref_pk, 1e-12,
                 "rectangular pulse, dt %g: same peak rotation", dts[k]);
    aq_check_rel(r.peak_displacement_m, ref_x, 1e-12, "same peak x");
    aq_result_free(&r);
  }
  /* half-sine, 0.8 s, 0.9 g peak, then free to 2 s */
  double pk[5], Tp = 0.8, A = p->act_sign * 0.6 * AQ_G0_MPS2;
  for (size_t k = 0; k < 5; k++) {
    double dt = dts[k];
    size_t n = (size_t)llround(2.0 / dt);
    double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d),
           *ac = malloc(n * sizeof *ac);
    for (size_t i = 0; i < n; i++) {
      t[i] = (double)i * dt;
      d[i] = dt;
      double tm = t[i] + 0.5 * dt;
      ac[i] = tm < Tp ? A * sin(3.14159265358979323846 * tm / Tp) : 0;
    }
    aq_result r;
    pk[k] = NAN;
    if (hrun(a, AQ_MODEL_WORKPATH, 0, 0, t, d, ac, n, &r)) {
      pk[k] = r.peak_rotation_rad;
      aq_check(!r.collapsed, "half-sine does not collapse the arch");
      aq_result_free(&r);
    }
    free(t);
    free(d);
    free(ac);
  }
  for (size_t k = 0; k + 2 < 5; k++) {
    double e0 = fabs(pk[k] - pk[4]), e1 = fabs(pk[k + 1] - pk[4]);
    aq_check(e1 < 0.2 * e0 || e1 < 1e-9 * pk[4],
             "half-sine: error %.3g at dt %g, %.3g at dt %g", e0, dts[k], e1,
             dts[k + 1]);
  }
  aq_check(!isnan(pk[4]) && pk[4] > 0, "moved");
  aq_arch_free(a);
}

/* Thin (t/R = 0.12) and thick (t/R = 0.4) arches: workpath and ode agree on
 * the half-cycle domain to 1e-6 and conserve energy at COR = 1. */
AQ_TEST(dyn_hard_thin_and_thick)
{
  const char *files[] = {"arches/thin.cfg", "arches/thick.cfg"};
  for (int f = 0; f < 2; f++) {
    aq_arch *a = aq_test_arch_load(files[f]);
    if (!a)
      continue;
    const aq_path *p = aq_arch_path(a, 0);
    double rs[] = {1.5, 3};
    for (int k = 0; k < 2; k++) {
      double T[2];
      for (int mdl = 0; mdl < 2; mdl++) {
        aq_error e;
        aq_stepper *st = aq_stepper_alloc(p, aq_arch_path(a, 1), (aq_model)mdl, &e);
        aq_stepper_set_ode_rtol(st, 1e-12);
        double acc = p->act_sign * rs[k] * p->lambda0 * p->g_mps2;
        double lo = 0, hi = 0.01;
        aq_steps s;
        aq_result r;
        /* bracket, then bisect */
        for (;;) {
          double tt[2] = {0, hi}, dd[2] = {hi, 30}, aa[2] = {acc, 0};
          aq_steps_from_list(tt, dd, aa, 2, &s, &e);
          aq_stepper_run(st, &s, &r, &e);
          aq_steps_free(&s);
          int c = r.collapsed;
          aq_result_free(&r);
          if (c || hi > 100)
            break;
          lo = hi;
          hi *= 2;
        }
        while (hi - lo > 1e-10) {
          double mid = 0.5 * (lo + hi);
          double tt[2] = {0, mid}, dd[2] = {mid, 30}, aa[2] = {acc, 0};
          aq_steps_from_list(tt, dd, aa, 2, &s, &e);
          aq_stepper_run(st, &s, &r, &e);
          aq_steps_free(&s);
          if (r.collapsed)
            hi = mid;
          else
            lo = mid;
          aq_result_free(&r);
        }
        T[mdl] = hi;
        aq_stepper_free(st);
      }
      aq_check_rel(T[0], T[1], 1e-15, "%s r = %g: domain workpath vs ode",
                   files[f], rs[k]);
    }
    aq_result r;
    if (hpulse(a, AQ_MODEL_WORKPATH, 1.0, 0,
               p->act_sign * 1.2 * p->lambda0 * p->g_mps2, 0.2, 10, 0.02, &r)) {
      const aq_history *h = &r.history;
      double e0 = h->kinetic_energy_j[9] + h->potential_energy_j[9], dm = 0;
      for (size_t i = 9; i < h->n; i++)
        dm = fmax(dm, fabs(h->kinetic_energy_j[i] + h->potential_energy_j[i] - e0));
      aq_check(!r.collapsed && r.impacts >= 2, "%s: rocks (%zu impacts)",
               files[f], r.impacts);
      /* PE here is m_T g y(s) from the tables' values, KE follows the
       * integral of their slopes (as in the ode model): the two agree to
       * ~1e-12 of E on the thin arch, with no drift (the ode model at rtol
       * 1e-12 shows 3e-12 on this measure); the issue asks 1e-9 per cycle */
      aq_check(dm <= 5e-12 * e0, "%s: energy drift %.3g relative", files[f],
               dm / e0);
      aq_result_free(&r);
    }
    aq_arch_free(a);
  }
}

/* Segmental arch: its face-swapped reverse set is inadmissible.  At the
 * return to s = 0 the arch stops (plastic stop: all kinetic energy is lost,
 * even at COR = 1), and an acceleration that would open only the reverse
 * set never moves it. */
AQ_TEST(dyn_hard_inadmissible_reverse)
{
  aq_arch *a = aq_test_arch_load("arches/segmental.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  aq_check(!aq_arch_path(a, 1)->admissible, "reverse set inadmissible");
  aq_result r;
  if (hpulse(a, AQ_MODEL_WORKPATH, 1.0, 0,
             p->act_sign * 1.1 * p->lambda0 * p->g_mps2, 0.2, 10, 0.01, &r)) {
    const aq_history *h = &r.history;
    aq_check(!r.collapsed && r.impacts == 1 && r.reversals == 1,
             "one swing, one impact: %zu %zu", r.impacts, r.reversals);
    aq_check_rel(r.energy_dissipated_j, r.energy_in_j, 1e-13,
                 "all energy lost at the plastic stop");
    aq_check(h->set[h->n - 1] == -1, "rests");
    aq_result_free(&r);
  }
  if (hpulse(a, AQ_MODEL_WORKPATH, 1.0, 0, -p->act_sign * 5 * AQ_G0_MPS2, 0.5,
             2, 0.01, &r)) {
    aq_check(r.steps_moving == 0 && r.evals == 0 && r.impacts == 0,
             "opposite direction never moves (%zu moving steps)",
             r.steps_moving);
    aq_result_free(&r);
  }
  aq_arch_free(a);
}

/* A long record that never exceeds the thresholds: nothing moves and the
 * quiet index skips it: no step is integrated, no path is evaluated. */
AQ_TEST(dyn_hard_quiet_record)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p0 = aq_arch_path(a, 0), *p1 = aq_arch_path(a, 1);
  enum { N = 200000 };
  double *acc = malloc(N * sizeof *acc);
  double lo = -p0->lambda0 * p0->g_mps2, hi = p1->lambda0 * p1->g_mps2;
  for (size_t i = 0; i < N; i++) {
    double v = sin(0.0123 * (double)i) * sin(0.00077 * (double)i + 0.3);
    acc[i] = v < 0 ? 0.97 * v * -lo : 0.97 * v * hi;
  }
  acc[N / 2] = lo; /* exactly at the threshold: no motion (strict >) */
  aq_steps s;
  aq_error e;
  aq_check(aq_steps_from_samples(acc, N, 0.005, 0, 0, &s, &e) == AQ_OK, "steps");
  for (int mdl = 0; mdl < 2; mdl++) {
    aq_stepper *st = aq_stepper_alloc(p0, p1, (aq_model)mdl, &e);
    aq_result r;
    aq_check(aq_stepper_run(st, &s, &r, &e) == AQ_OK, "run");
    aq_check(r.steps_total == N && r.steps_moving == 0 && r.evals == 0 &&
                 r.impacts == 0 && r.peak_rotation_rad == 0,
             "model %d: %zu steps, %zu moving, %zu evals", mdl, r.steps_total,
             r.steps_moving, r.evals);
    aq_result_free(&r);
    aq_stepper_free(st);
  }
  aq_steps_free(&s);
  free(acc);
  aq_arch_free(a);
}

/* Random step lists (fixed seed): amplitudes up to 2.2 lambda0 g of either
 * sign, durations 1e-4..0.08 s, random COR and impact rule.  Never NaN,
 * never negative KE, |q| within q_c, always returns; workpath and ode agree
 * on collapse, impacts and peak rotation. */
AQ_TEST(dyn_hard_random_steps)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p0 = aq_arch_path(a, 0), *p1 = aq_arch_path(a, 1);
  unsigned long long x = 0x9e3779b97f4a7c15ULL;
  enum { N = 300, RUNS = 12 };
  double t[N], d[N], acc[N];
  int agree = 0;
  for (int run = 0; run < RUNS; run++) {
    tds_random(&x, p0->lambda0 * p0->g_mps2, p1->lambda0 * p1->g_mps2, t, d,
               acc, N);
    double cor = tds_rng(&x);
    int mom = tds_rng(&x) < 0.3;
    aq_result r[2];
    int ok = 1;
    for (int mdl = 0; mdl < 2; mdl++) {
      ok &= hrun(a, (aq_model)mdl, cor, mom, t, d, acc, N, &r[mdl]);
      if (!ok)
        break;
      const aq_history *h = &r[mdl].history;
      int bad = 0;
      for (size_t i = 0; i < h->n; i++)
        bad |= !isfinite(h->rotation_rad[i]) || !isfinite(h->kinetic_energy_j[i]) ||
               h->kinetic_energy_j[i] < 0 ||
               fabs(h->rotation_rad[i]) > fmax(p0->s_c_rad, p1->s_c_rad) * (1 + 1e-12);
      aq_check(!bad, "run %d model %d: finite, KE >= 0, |q| <= q_c", run, mdl);
    }
    if (!ok)
      continue;
    aq_check(r[0].collapsed == r[1].collapsed && r[0].impacts == r[1].impacts &&
                 r[0].reversals == r[1].reversals,
             "run %d: same collapse (%d %d), impacts (%zu %zu), reversals "
             "(%zu %zu)", run, r[0].collapsed, r[1].collapsed, r[0].impacts,
             r[1].impacts, r[0].reversals, r[1].reversals);
    aq_check_rel(r[0].peak_rotation_rad, r[1].peak_rotation_rad, 5e-8,
                 "run %d: peak rotation", run);
    aq_check_rel(r[0].max_kinetic_energy_j, r[1].max_kinetic_energy_j, 2e-7,
                 "run %d: peak kinetic energy", run);
    if (r[0].collapsed && r[1].collapsed)
      aq_check_rel(r[0].collapse_time_s, r[1].collapse_time_s, 5e-11,
                   "run %d: collapse time", run);
    agree += r[0].steps_moving > 0;
    aq_result_free(&r[0]);
    aq_result_free(&r[1]);
  }
  aq_check(agree >= RUNS / 2, "most runs moved (%d)", agree);
  aq_arch_free(a);
}

/* A stepper reused for many runs (as domain does) gives each run exactly
 * what a fresh stepper gives: no state carried between runs. */
AQ_TEST(dyn_hard_runs_independent)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  double t[3] = {0, 0.37, 0.52}, d[3] = {0.37, 0.15, 6}, acc[3];
  acc[0] = p->act_sign * 0.71 * AQ_G0_MPS2;
  acc[1] = -acc[0] * 0.9;
  acc[2] = 0;
  double t2[2] = {0, 0.9}, d2[2] = {0.9, 3}, acc2[2] = {acc[0] * 0.8, 0};
  aq_steps s, s2;
  aq_error e;
  aq_steps_from_list(t, d, acc, 3, &s, &e);
  aq_steps_from_list(t2, d2, acc2, 2, &s2, &e);
  for (int mdl = 0; mdl < 3; mdl++) {
    aq_stepper *fresh = aq_stepper_alloc(p, aq_arch_path(a, 1), (aq_model)mdl, &e);
    aq_stepper *used = aq_stepper_alloc(p, aq_arch_path(a, 1), (aq_model)mdl, &e);
    aq_result r1, r2, rx;
    aq_stepper_set_cor(fresh, 0.6);
    aq_stepper_set_cor(used, 0.6);
    aq_check(aq_stepper_run(used, &s2, &rx, &e) == AQ_OK, "warm-up run");
    aq_result_free(&rx);
    aq_check(aq_stepper_run(fresh, &s, &r1, &e) == AQ_OK &&
                 aq_stepper_run(used, &s, &r2, &e) == AQ_OK,
             "runs");
    aq_check(r1.peak_rotation_rad == r2.peak_rotation_rad &&
                 r1.max_kinetic_energy_j == r2.max_kinetic_energy_j &&
                 r1.impacts == r2.impacts && r1.evals == r2.evals,
             "model %d: identical after another run (%.17g %.17g)", mdl,
             r1.peak_rotation_rad, r2.peak_rotation_rad);
    aq_result_free(&r1);
    aq_result_free(&r2);
    aq_stepper_free(fresh);
    aq_stepper_free(used);
  }
  aq_steps_free(&s);
  aq_steps_free(&s2);
  aq_arch_free(a);
}
