/* test_dyn_block.c: the stepper against closed forms of the rocking block
 * and against the ode model on one constant step (test-local mechanisms,
 * tests/test_dyn_mech.h). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "arch/stepper.h"
#include "check.h"
#include "test_dyn_mech.h"

static const double G = 9.80665;

/* Run one model on an explicit step list; returns the status. */
static aq_status run_list(const aq_path *pp, const aq_path *pr, aq_model mdl,
                          const double *t, const double *dt, const double *a,
                          size_t n, double cor, double rtol, aq_result *res)
{
  gsl_set_error_handler_off();
  aq_error e;
  aq_steps s;
  if (aq_steps_from_list(t, dt, a, n, &s, &e) != AQ_OK)
    return e.status;
  aq_stepper *st = aq_stepper_alloc(pp, pr, mdl, &e);
  if (!st) {
    aq_steps_free(&s);
    return e.status;
  }
  aq_stepper_set_cor(st, cor);
  aq_stepper_set_ode_rtol(st, rtol);
  aq_stepper_set_history(st, 1);
  aq_status rc = aq_stepper_run(st, &s, res, &e);
  if (rc != AQ_OK)
    fprintf(stderr, "run: %s\n", e.message);
  aq_stepper_free(st);
  aq_steps_free(&s);
  return rc;
}

/* Slender block, constant step from rest: the linearised equation
 * s'' = p^2 (s - beta), p^2 = 3 g / (4 R), beta = alpha + a/g (a < 0), has
 * s(t) = beta (1 - cosh p t).  alpha = 0.02 rad: neglected terms are
 * O(alpha^2) relative. */
AQ_TEST(dyn_block_linearised_step_from_rest)
{
  tb_block blk[2];
  aq_path path[2];
  double b = 0.0237, h = 0.0237 / tan(0.02);
  tb_block_paths(blk, path, b, h, 1234.5, G);
  double alpha = blk[0].alpha, R = blk[0].R;
  double a = -1.7 * G * tan(alpha);
  double p = sqrt(3 * G / (4 * R)), beta = alpha + a / G;
  double T = 0.6 / p * 2.0; /* s reaches about 0.8 alpha */
  double t0 = 0.0, dt = T, aa = a;
  for (int mdl = 0; mdl < 2; mdl++) {
    aq_result r;
    aq_check(run_list(&path[0], &path[1], (aq_model)mdl, &t0, &dt, &aa, 1, 0,
                      1e-11, &r) == AQ_OK,
             "run model %d", mdl);
    double want = beta * (1 - cosh(p * T));
    aq_check(r.history.n == 1, "one history row");
    aq_check_rel(-r.history.rotation_rad[0], want, 2e-3,
                 "model %d: s(T) against beta (1 - cosh pT)", mdl);
    /* energy: KE = -a m dx - g m dy exactly */
    double s = -r.history.rotation_rad[0];
    double ke = -a * 1234.5 * (R * sin(alpha) - R * sin(alpha - s)) -
                G * 1234.5 * (R * cos(alpha - s) - R * cos(alpha));
    aq_check_rel(r.history.kinetic_energy_j[0], ke, mdl == 0 ? 1e-12 : 5e-11,
                 "model %d: KE(s) by the energy balance", mdl);
    aq_check(!r.collapsed && r.impacts == 0, "no event");
    aq_result_free(&r);
  }
}

/* Free rocking at COR = 1 (linearised, slender block): after a pulse that
 * gives the block the velocity v0 at s = 0, the time from s = 0 to the
 * turning point is (1/p) artanh(v0 / (p alpha)) and the swing is
 * symmetric, so impacts come every 2 of those times. */
AQ_TEST(dyn_block_free_rocking_half_period)
{
  tb_block blk[2];
  aq_path path[2];
  double b = 0.0311, h = 0.0311 / tan(0.015);
  tb_block_paths(blk, path, b, h, 987.0, G);
  double alpha = blk[0].alpha, R = blk[0].R, m = 987.0;
  double p = sqrt(3 * G / (4 * R));
  double a = -2.3 * G * tan(alpha), tp = 0.35 / p;
  /* Run the pulse alone, read the state, then the free motion. */
  double t[2] = {0, tp}, dt[2] = {tp, 40.0 / p}, acc[2] = {a, 0};
  aq_result r;
  aq_check(run_list(&path[0], &path[1], AQ_MODEL_WORKPATH, t, dt, acc, 2, 1.0,
                    1e-10, &r) == AQ_OK,
           "run");
  /* energy after the pulse = KE at the first impact */
  double s1 = -r.history.rotation_rad[0], ke1 = r.history.kinetic_energy_j[0];
  double e = ke1 + m * G * (R * cos(alpha - s1) - R * cos(alpha));
  double M = 4.0 / 3.0 * m * R * R, v0 = sqrt(2 * e / M);
  double quarter = atanh(v0 / (p * alpha)) / p;
  size_t want = (size_t)floor((40.0 / p - (quarter * 2 - (0))) / (2 * quarter));
  (void)want;
  /* the number of impacts in the free 40/p s: each swing is 2 quarters
   * (nonlinear terms O(alpha^2) shift this slightly; allow 1) */
  double n_est = 40.0 / p / (2 * quarter);
  aq_check(fabs((double)r.impacts - n_est) <= 1.5, "impacts %zu vs %.2f",
           r.impacts, n_est);
  aq_check(r.reversals == r.impacts || r.reversals == r.impacts + 1,
           "one turning point per swing: %zu reversals, %zu impacts",
           r.reversals, r.impacts);
  aq_check_abs(r.energy_dissipated_j, 0, 1e-15 * e, "no loss at COR = 1");
  double e_end = r.history.kinetic_energy_j[1] +
                 r.history.potential_energy_j[1];
  aq_check_rel(e_end, e, 1e-11, "energy after 40/p s of rocking");
  aq_result_free(&r);
}

/* One constant step, work path against ode at rtol 1e-12, on the
 * synthetic mechanism with non-constant M: from rest, and from motion
 * (a second step with a different acceleration). */
AQ_TEST(dyn_step_workpath_vs_ode)
{
  tb_syn syn[2];
  aq_path path[2];
  tb_syn_paths(syn, path);
  double lam = path[0].lambda0;
  struct {
    double a1, t1, a2, t2;
  } cs[] = {
      {-1.37 * lam * G, 0.213, 0, 0},        /* from rest */
      {-1.37 * lam * G, 0.113, -0.61 * G, 0.173}, /* from motion, decelerating */
      {-2.11 * lam * G, 0.057, -0.93 * lam * G, 0.391},
  };
  for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
    double t[2] = {0, cs[k].t1}, dt[2] = {cs[k].t1, cs[k].t2 > 0 ? cs[k].t2 : 1},
           a[2] = {cs[k].a1, cs[k].a2};
    size_t n = cs[k].t2 > 0 ? 2 : 1;
    aq_result rw, ro;
    aq_check(run_list(&path[0], &path[1], AQ_MODEL_WORKPATH, t, dt, a, n, 0,
                      1e-12, &rw) == AQ_OK, "workpath");
    aq_check(run_list(&path[0], &path[1], AQ_MODEL_ODE, t, dt, a, n, 0, 1e-13,
                      &ro) == AQ_OK, "ode");
    size_t i = n - 1;
    aq_check(rw.history.set[i] == ro.history.set[i], "same set");
    aq_check_rel(rw.history.rotation_rad[i], ro.history.rotation_rad[i], 2e-13,
                 "case %zu: q at step end", k);
    aq_check_rel(rw.history.kinetic_energy_j[i], ro.history.kinetic_energy_j[i],
                 1e-13, "case %zu: KE at step end", k);
    aq_result_free(&rw);
    aq_result_free(&ro);
  }
}
