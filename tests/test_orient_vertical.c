/* test_orient_vertical.c: the vertical ground acceleration (steps'
 * av_mps2): the start threshold against its closed form, the energy balance
 * of a pulse against its closed form, the work path against the ode
 * reference (each on circular arches and on the shaped ones: pointed,
 * elliptical with fill and a point mass, catenary, joints), the lift-off
 * status, and through the command line. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"
#include "arch/eom.h"
#include "arch/stepper.h"
#include "arch_fixture.h"
#include "check.h"
#include "signal/steps.h"
#include "test_dyn_steps.h"
#include "units.h"

/* 1 if amplitude acc (along act_sign of set 0) with constant vertical av
 * for 0.2 s starts the arch. */
static int moves(const aq_arch *a, aq_model mdl, double acc, double av, double k)
{
  aq_steps s;
  if (!tds_pulse(acc, 0.2, 0.4, 0.05, &s))
    return -1;
  double *v = malloc(s.n * sizeof *v);
  aq_error e;
  for (size_t i = 0; v && i < s.n; i++)
    v[i] = av;
  int r = -1;
  if (v && (av == 0 || aq_steps_set_vertical(&s, v, &e) == AQ_OK)) {
    aq_stepper *st = aq_stepper_alloc(aq_arch_path(a, 0), aq_arch_path(a, 1), mdl, &e);
    aq_result res;
    if (st) {
      aq_stepper_set_scale(st, k);
      if (aq_stepper_run(st, &s, &res, &e) == AQ_OK) {
        r = res.first_set >= 0;
        aq_result_free(&res);
      }
    }
    aq_stepper_free(st);
  }
  free(v);
  aq_steps_free(&s);
  return r;
}

/* A constant a_v = c multiplies the start threshold lambda0 g by exactly
 * (1 + c/g): found by bisection on the amplitude, with and without c, and
 * on the stepper's scale (which scales a_v with the motion: k A = lambda0
 * (g + k c), k = lambda0 g / (A - lambda0 c)). */
AQ_TEST(vertical_threshold_scales_by_one_plus_c_over_g)
{
  /* the circles, then the shaped arches: pointed, elliptical with its fill
   * and a point mass (a_v acts on every mass alike), catenary, joints */
  static const char *const arches[] = {"arches/thin.cfg",     "arches/oppenheim.cfg",
                                       "arches/gothic.cfg",   "arches/bridge.cfg",
                                       "arches/catenary.cfg", "arches/vertical.cfg"};
  static const double cs[] = {2.385, -3.1};
  for (size_t ai = 0; ai < sizeof arches / sizeof arches[0]; ai++) {
    aq_arch *a = aq_test_arch_load(arches[ai]);
    if (!a)
      continue;
    const aq_path *p = aq_arch_path(a, 0);
    double g = p->g_mps2, l0 = p->lambda0;
    double thr[3];
    for (int w = 0; w < 3; w++) { /* 0: no a_v, 1, 2: cs[0], cs[1] */
      double c = w ? cs[w - 1] : 0, lo = 0, hi = 3 * l0 * (g + 4);
      for (int it = 0; it < 80; it++) {
        double mid = 0.5 * (lo + hi);
        if (moves(a, AQ_MODEL_WORKPATH, p->act_sign * mid, c, 1) == 1)
          hi = mid;
        else
          lo = mid;
      }
      thr[w] = hi;
    }
    aq_check_rel(thr[0], l0 * g, 1e-13, "%s: threshold %.17g = lambda0 g", arches[ai], thr[0]);
    for (int w = 1; w < 3; w++)
      aq_check_rel(thr[w] / thr[0], 1 + cs[w - 1] / g, 1e-13,
                   "%s: c = %g: ratio %.17g = 1 + c/g", arches[ai], cs[w - 1], thr[w] / thr[0]);
    /* on the scale, A = 1.7 lambda0 g and c = 2.385 */
    double A = 1.7 * l0 * g, c = cs[0], lo = 0, hi = 2;
    for (int it = 0; it < 80; it++) {
      double mid = 0.5 * (lo + hi);
      if (moves(a, AQ_MODEL_WORKPATH, p->act_sign * A, c, mid) == 1)
        hi = mid;
      else
        lo = mid;
    }
    aq_check_rel(hi, l0 * g / (A - l0 * c), 1e-13, "%s: threshold scale %.17g", arches[ai], hi);
    aq_check(moves(a, AQ_MODEL_ODE, p->act_sign * thr[1] * (1 + 1e-9), cs[0], 1) == 1 &&
                 moves(a, AQ_MODEL_ODE, p->act_sign * thr[1] * (1 - 1e-9), cs[0], 1) == 0,
             "%s: the ode starts at the same threshold", arches[ai]);
    aq_arch_free(a);
  }
}

/* One step of constant a_x and a_v from rest: at its end, KE = -m_T a_x x(s)
 * - m_T (g + a_v) y(s) (x, y of the path evaluated exactly at the end's s):
 * the energy balance in closed form, on the circle and the shaped arches. */
static void pulse_energy_balance(const char *arch)
{
  aq_arch *a = aq_test_arch_load(arch);
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  double g = p->g_mps2, acc = p->act_sign * 1.9 * p->lambda0 * g;
  static const double avs[] = {-2.385, 0, 1.7};
  static const aq_model mdl[] = {AQ_MODEL_WORKPATH, AQ_MODEL_WORKPATH_QUAD, AQ_MODEL_ODE};
  double ke_prev = NAN;
  for (size_t j = 0; j < 3; j++)
    for (size_t m = 0; m < 3; m++) {
      double t = 0, d = 0.25, av = avs[j];
      aq_steps s;
      aq_error e;
      aq_result r;
      if (!aq_check(aq_steps_from_list(&t, &d, &acc, 1, &s, &e) == AQ_OK &&
                        aq_steps_set_vertical(&s, &av, &e) == AQ_OK,
                    "steps"))
        continue;
      if (tds_run(a, mdl[m], 0.7, 0, 1e-13, 1, &s, &r)) {
        size_t n = r.history.n;
        double q = fabs(r.history.rotation_rad[n - 1]), x = r.history.displacement_m[n - 1];
        aq_path_point pt;
        int bad = aq_eom_eval(p, 1, q, &pt);
        double want = -p->mass_kg * acc * pt.x_m - p->mass_kg * (g + av) * pt.y_m;
        double ke = r.history.kinetic_energy_j[n - 1];
        aq_check(!bad && !r.collapsed && q > 0 && fabs(x - pt.x_m) <= 1e-12 * fabs(pt.x_m),
                 "%s a_v %g model %d: moving at the end (s %.6g, x %.9g)", arch, av,
                 (int)mdl[m], q, x);
        aq_check_abs(ke, want, 1e-11 * p->mass_kg * g * fabs(pt.y_m) + 1e-9 * want,
                     "%s a_v %g model %d: KE %.15g J = closed form %.15g J", arch, av,
                     (int)mdl[m], ke, want);
        double win = -p->mass_kg * (acc * pt.x_m + av * pt.y_m);
        aq_check_rel(r.energy_in_j, win, 1e-9,
                     "%s a_v %g model %d: ground's work %.12g = %.12g", arch, av, (int)mdl[m],
                     r.energy_in_j, win);
        if (m == 0 && j > 0)
          aq_check(ke_prev > ke, "%s: more a_v, less KE: %.9g > %.9g", arch, ke_prev, ke);
        if (m == 0)
          ke_prev = ke;
        aq_result_free(&r);
      }
      aq_steps_free(&s);
    }
  aq_arch_free(a);
}

AQ_TEST(vertical_pulse_energy_balance_closed_form)
{
  static const char *const arches[] = {"arches/oppenheim.cfg", "arches/gothic.cfg",
                                       "arches/bridge.cfg", "arches/catenary.cfg",
                                       "arches/vertical.cfg"};
  for (size_t ai = 0; ai < sizeof arches / sizeof arches[0]; ai++)
    pulse_energy_balance(arches[ai]);
}

/* Pulses with a vertical acceleration that changes every step (the hard
 * cases' shapes: rocking, impacts, collapse, on the circles and on each
 * shaped arch, the bridge with momentum impacts): the work path against
 * the ode reference at rtol 1e-13, to 1e-12. */
AQ_TEST(vertical_workpath_vs_ode)
{
  static const struct {
    const char *arch;
    double ratio, dur, end, dt, av0_g, av1_g, cor;
    int momentum;
  } C[] = {
      {"arches/oppenheim.cfg", 1.6, 0.4, 3, 0.01, 0.3, 0.2, 0.7, 0},
      {"arches/oppenheim.cfg", 2.5, 0.9, 3, 0.01, -0.4, 0.3, 0.7, 0},
      {"arches/thin.cfg", 1.3, 0.2, 6, 0.02, 0.1, 0.5, 0.7, 0},
      {"arches/thin.cfg", 3, 0.5, 3, 0.01, -0.2, 0.4, 0.7, 0},
      {"arches/thick.cfg", 1.4, 0.2, 6, 0.02, -0.3, 0.5, 0.7, 0},
      {"arches/gothic.cfg", 1.5, 0.3, 3, 0.01, 0.3, 0.2, 0.7, 0},
      {"arches/gothic.cfg", 4, 0.8, 2, 0.01, -0.3, 0.4, 0.7, 0},
      {"arches/bridge.cfg", 1.5, 0.3, 3, 0.01, 0.3, 0.2, 0, 1},
      {"arches/bridge.cfg", 4, 0.8, 2, 0.01, -0.3, 0.4, 0, 1},
      {"arches/catenary.cfg", 1.5, 0.3, 3, 0.01, 0.3, 0.2, 0.7, 0},
      {"arches/catenary.cfg", 4, 0.8, 2, 0.01, -0.3, 0.4, 0.7, 0},
      {"arches/vertical.cfg", 1.5, 0.3, 3, 0.01, 0.3, 0.2, 0.7, 0},
      {"arches/vertical.cfg", 4, 0.8, 2, 0.01, -0.3, 0.4, 0.7, 0},
  };
  double worst = 0;
  int collapses = 0, impacts = 0;
  for (size_t c = 0; c < sizeof C / sizeof C[0]; c++) {
    aq_arch *a = aq_test_arch_load(C[c].arch);
    if (!a)
      continue;
    const aq_path *p = aq_arch_path(a, 0);
    aq_steps s;
    aq_error e;
    if (!aq_check(tds_pulse(p->act_sign * C[c].ratio * p->lambda0 * p->g_mps2, C[c].dur,
                            C[c].end, C[c].dt, &s), "steps")) {
      aq_arch_free(a);
      continue;
    }
    double *av = malloc(s.n * sizeof *av);
    for (size_t i = 0; av && i < s.n; i++) /* up to |av0| + |av1| g, every step another */
      av[i] = (C[c].av0_g + C[c].av1_g * sin(2.385 * (double)i)) * AQ_G0_MPS2;
    aq_result r[2];
    int ok = av && aq_steps_set_vertical(&s, av, &e) == AQ_OK;
    ok = ok && tds_run(a, AQ_MODEL_WORKPATH, C[c].cor, C[c].momentum, 1e-13, 1, &s, &r[0]);
    ok = ok && tds_run(a, AQ_MODEL_ODE, C[c].cor, C[c].momentum, 1e-13, 1, &s, &r[1]);
    if (ok) {
      aq_check(r[0].first_set >= 0 && r[0].collapsed == r[1].collapsed &&
                   r[0].impacts == r[1].impacts,
               "case %zu (%s): it moves, the same events (collapsed %d %d, impacts %zu %zu)",
               c, C[c].arch, r[0].collapsed, r[1].collapsed, r[0].impacts, r[1].impacts);
      double e1 = fabs(r[0].peak_rotation_rad / r[1].peak_rotation_rad - 1);
      double e2 = fabs(r[0].peak_displacement_m / r[1].peak_displacement_m - 1);
      double e3 = r[0].collapsed ? fabs(r[0].collapse_time_s - r[1].collapse_time_s) : 0;
      worst = fmax(worst, fmax(e1, fmax(e2, e3)));
      aq_check(e1 <= 1e-12 && e2 <= 1e-12 && e3 <= 1e-12,
               "case %zu (%s): peak rotation %.3g, displacement %.3g (relative), collapse "
               "time %.3g s from the ode", c, C[c].arch, e1, e2, e3);
      collapses += r[0].collapsed;
      impacts += (int)r[0].impacts;
      aq_result_free(&r[0]);
      aq_result_free(&r[1]);
    }
    free(av);
    aq_steps_free(&s);
    aq_arch_free(a);
  }
  aq_check(collapses >= 6 && impacts >= 6, "collapses %d and impacts %d among the cases (worst "
           "difference %.3g)", collapses, impacts, worst);
}

/* A step with g + a_v <= 0 stops the run with AQ_ELIFTOFF, naming the time
 * in the record and the value; a collapse before it is a result. */
AQ_TEST(vertical_liftoff_stops_the_run)
{
  aq_arch *a = aq_test_arch_load("arches/thin.cfg");
  if (!a)
    return;
  double t[4] = {0, 0.5, 1.25, 2}, d[4] = {0.5, 0.75, 0.75, 1}, acc[4] = {0, 0, 0, 0};
  double av[4] = {0, -3, -1.02 * AQ_G0_MPS2, 0};
  aq_steps s;
  aq_error e;
  aq_check(aq_steps_from_list(t, d, acc, 4, &s, &e) == AQ_OK &&
               aq_steps_set_vertical(&s, av, &e) == AQ_OK,
           "steps");
  aq_stepper *st = aq_stepper_alloc(aq_arch_path(a, 0), aq_arch_path(a, 1), AQ_MODEL_WORKPATH, &e);
  aq_result r;
  aq_error_clear(&e);
  aq_status rc = st ? aq_stepper_run(st, &s, &r, &e) : AQ_EINTERNAL;
  aq_check(rc == AQ_ELIFTOFF && strstr(e.message, "t = 1.250 s") &&
               strstr(e.message, "-0.196"),
           "lift-off at 1.25 s, g + a_v = -0.196 m/s^2: %s", e.message);
  aq_steps_free(&s);
  aq_stepper_free(st);
  aq_arch_free(a);
}
