/* bench_arch.c: building an arch (geometry, both work paths with their
 * tables and the Taylor leg's pieces) at 20 and 60 voussoirs, with given hinges and with the mechanism
 * search, and the cost of one path evaluation (tables vs exact); then
 * every shape: loading each shipped arch (its search included) and a
 * bridge arch of 1000 voussoirs with its fill, and the cost per moving
 * step of the workpath model against the ode reference (rtol 1e-12) under
 * a pulse of 1.5 lambda0 for 0.1 s then 1.9 s free (rocking, impacts, no
 * collapse), with the workpath's error in peak rotation against the
 * ode's; last, each shipped arch under that pulse with cor and with
 * momentum impacts (the cost of a step follows its impacts). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>

#include "arch/arch.h"
#include "arch/model.h"
#include "arch/stepper.h"
#include "bench.h"
#include "signal/steps.h"
#include "units.h"

#define REPS 21

static double build_ms(size_t nv, int search, size_t *table_n, double *table_err,
                       size_t *piece_n)
{
  double t[REPS];
  aq_arch_params p = aq_arch_circular(5.0, 1.25, AQ_PI, nv, 2000.0, 1.0);
  /* the oppenheim mechanism scaled to nv voussoirs */
  aq_hinge_set hs = {{0, 6 * nv / 20, 12 * nv / 20, 19 * nv / 20}, {'e', 'i', 'e', 'i'}};
  for (int r = 0; r < REPS; r++) {
    aq_arch *a = NULL;
    aq_error e;
    double t0 = aq_bench_now_s();
    if (aq_arch_build(&p, search ? NULL : &hs, NULL, NULL, "bench", &a, &e) != AQ_OK) {
      fprintf(stderr, "bench_arch: %s\n", e.message);
      return -1;
    }
    t[r] = aq_bench_now_s() - t0;
    if (r == 0) {
      table_n[0] = aq_workpath_table_size(aq_arch_workpath(a, 0));
      table_n[1] = aq_workpath_table_size(aq_arch_workpath(a, 1));
      table_err[0] = aq_workpath_table_error(aq_arch_workpath(a, 0));
      table_err[1] = aq_workpath_table_error(aq_arch_workpath(a, 1));
      piece_n[0] = aq_workpath_piece_count(aq_arch_workpath(a, 0));
      piece_n[1] = aq_workpath_piece_count(aq_arch_workpath(a, 1));
    }
    aq_arch_free(a);
  }
  return 1e3 * aq_bench_median(t, REPS);
}

static double search_ms(size_t nv)
{
  double t[REPS];
  aq_arch_params p = aq_arch_circular(5.0, 1.25, AQ_PI, nv, 2000.0, 1.0);
  aq_geom g;
  aq_error e;
  if (aq_geom_init(&g, &p, &e) != AQ_OK)
    return -1;
  for (int r = 0; r < REPS; r++) {
    aq_hinge_set hs;
    double t0 = aq_bench_now_s();
    aq_search_minimum(&g, AQ_G0_MPS2, &hs, NULL, NULL, &e);
    t[r] = aq_bench_now_s() - t0;
  }
  aq_geom_free(&g);
  return 1e3 * aq_bench_median(t, REPS);
}

/* Median ms to load path (its search included); -1 on error. */
static double load_ms(const char *path, int reps)
{
  double t[REPS];
  for (int r = 0; r < reps; r++) {
    aq_arch *a = NULL;
    aq_error e;
    double t0 = aq_bench_now_s();
    aq_status st = aq_arch_load(path, &a, &e);
    t[r] = aq_bench_now_s() - t0;
    aq_arch_free(a);
    if (st != AQ_OK) {
      fprintf(stderr, "bench_arch: %s\n", e.message);
      return -1;
    }
  }
  return 1e3 * aq_bench_median(t, (size_t)reps);
}

/* One run of arch a under steps by model m, with the arch file's impact
 * rule (momentum -1) or cor (0) or momentum (1) impacts: *us per moving
 * step (median of reps), *peak the peak rotation, *moving the moving
 * steps, *impacts (if not NULL) the impacts; 0 on error. */
static int step_cost_rule(const aq_arch *a, aq_model m, int momentum, const aq_steps *steps,
                          int reps, double *us, double *peak, size_t *moving, size_t *impacts)
{
  double t[REPS];
  for (int r = 0; r < reps; r++) {
    aq_error e;
    aq_result res;
    aq_stepper *st = aq_stepper_alloc(aq_arch_path(a, 0), aq_arch_path(a, 1), m, &e);
    if (!st) {
      fprintf(stderr, "bench_arch: %s\n", e.message);
      return 0;
    }
    const aq_arch_dynamics *dyn = aq_arch_dynamics_of(a);
    aq_stepper_set_impact(st, momentum < 0 ? dyn->impact == AQ_IMPACT_MOMENTUM : momentum);
    aq_stepper_set_cor(st, dyn->cor);
    if (m == AQ_MODEL_ODE)
      aq_stepper_set_ode_rtol(st, 1e-12);
    double t0 = aq_bench_now_s();
    aq_status rc = aq_stepper_run(st, steps, &res, &e);
    t[r] = aq_bench_now_s() - t0;
    aq_stepper_free(st);
    if (rc != AQ_OK) {
      fprintf(stderr, "bench_arch: %s\n", e.message);
      return 0;
    }
    *peak = res.peak_rotation_rad;
    *moving = res.steps_moving;
    if (impacts)
      *impacts = res.impacts;
    t[r] /= res.steps_moving ? (double)res.steps_moving : 1.0;
  }
  *us = 1e6 * aq_bench_median(t, (size_t)reps);
  return 1;
}

static int step_cost(const aq_arch *a, aq_model m, const aq_steps *steps, int reps, double *us,
                     double *peak, size_t *moving)
{
  return step_cost_rule(a, m, -1, steps, reps, us, peak, moving, NULL);
}

/* The steps of the shapes' table: a pulse of 1.5 lambda0 g for 0.1 s,
 * then 1.9 s free, at 0.01 s.  1 on success. */
static int pulse_steps(const aq_arch *a, aq_steps *steps)
{
  const aq_path *p = aq_arch_path(a, 0);
  enum { NS = 200 };
  double acc[NS];
  for (int i = 0; i < NS; i++)
    acc[i] = i < 10 ? p->act_sign * 1.5 * p->lambda0 * aq_arch_dynamics_of(a)->g_mps2 : 0;
  aq_error e;
  return aq_steps_from_samples(acc, NS, 0.01, 0, 0, steps, &e) == AQ_OK;
}

/* Where the bridge's steps go: each shipped arch under the same pulse with
 * cor impacts (kinetic-energy ratio as its file says, 0 for all) and with
 * momentum impacts, the workpath model: moving steps, impacts, and the
 * cost per run and per moving step. */
static int impact_rules(void)
{
  static const char *const names[] = {"oppenheim", "gothic", "bridge", "catenary", "vertical"};
  printf("\narch\timpact\tmoving_steps\timpacts\twp_us_per_run\twp_us_per_step\n");
  for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
    char path[64];
    snprintf(path, sizeof path, "arches/%s.cfg", names[k]);
    aq_arch *a = NULL;
    aq_error e;
    aq_steps steps;
    if (aq_arch_load(path, &a, &e) != AQ_OK || !pulse_steps(a, &steps)) {
      aq_arch_free(a);
      return 0;
    }
    for (int mom = 0; mom < 2; mom++) {
      double us = 0, peak = 0;
      size_t mv = 0, imp = 0;
      if (!step_cost_rule(a, AQ_MODEL_WORKPATH, mom, &steps, REPS, &us, &peak, &mv, &imp)) {
        aq_steps_free(&steps);
        aq_arch_free(a);
        return 0;
      }
      printf("%s\t%s\t%zu\t%zu\t%.2f\t%.2f\n", names[k], mom ? "momentum" : "cor", mv, imp,
             us * (double)mv, us);
    }
    aq_steps_free(&steps);
    aq_arch_free(a);
  }
  return 1;
}

static int shapes(void)
{
  static const char *const names[] = {"oppenheim", "gothic", "bridge", "catenary", "vertical"};
  printf("\narch\tshape\tvoussoirs\tload_ms\tmoving_steps\twp_us_per_step\t"
         "ode_us_per_step\tode_over_wp\tpeak_rot_rad\tpeak_rot_rel_err\n");
  for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
    char path[64];
    snprintf(path, sizeof path, "arches/%s.cfg", names[k]);
    double ms = load_ms(path, 5);
    aq_arch *a = NULL;
    aq_error e;
    if (ms < 0 || aq_arch_load(path, &a, &e) != AQ_OK)
      return 0;
    aq_steps steps;
    int ok = pulse_steps(a, &steps);
    double us[2] = {0, 0}, peak[2] = {0, 0};
    size_t mv[2] = {0, 0};
    ok = ok && step_cost(a, AQ_MODEL_WORKPATH, &steps, REPS, &us[0], &peak[0], &mv[0]) &&
         step_cost(a, AQ_MODEL_ODE, &steps, 5, &us[1], &peak[1], &mv[1]);
    aq_arch_drawing d;
    aq_arch_drawing_of(a, &d);
    if (ok)
      printf("%s\t%s\t%zu\t%.2f\t%zu\t%.2f\t%.2f\t%.1f\t%.4g\t%.1e\n", names[k],
             d.shape, d.voussoirs, ms, mv[0], us[0], us[1], us[1] / us[0], peak[1],
             fabs(peak[0] - peak[1]) / peak[1]);
    aq_steps_free(&steps);
    aq_arch_free(a);
    if (!ok)
      return 0;
  }
  /* 1000 voussoirs: the bound is 1 s, search included */
  FILE *f = fopen("build/bench/elliptical1000.cfg", "w");
  if (!f)
    return 0;
  fprintf(f, "[arch]\nname = elliptical1000\nshape = elliptical\nspan_m = 12\nrise_m = 4.2\n"
             "thickness_m = 0.8\nvoussoirs = 1000\ndensity_kg_m3 = 2200\ndepth_m = 4\n"
             "[fill]\nlevel_m = 5.3\ndensity_kg_m3 = 1800\n");
  fclose(f);
  double ms = load_ms("build/bench/elliptical1000.cfg", 5);
  if (ms < 0)
    return 0;
  printf("elliptical1000\telliptical\t1000\t%.1f\t-\t-\t-\t-\t-\t-\n", ms);
  return 1;
}

int main(void)
{
  gsl_set_error_handler_off();
  printf("voussoirs\thinges\tbuild_ms\tsearch_ms\tsets\ttable_n_primary\ttable_n_reverse\t"
         "table_err_primary\ttable_err_reverse\tpieces_primary\tpieces_reverse\n");
  static const size_t nvs[] = {20, 60};
  for (int k = 0; k < 2; k++) {
    for (int search = 0; search < 2; search++) {
      size_t tn[2] = {0, 0}, pn[2] = {0, 0}, nsets = 16 * (nvs[k] + 1) * nvs[k] * (nvs[k] - 1) * (nvs[k] - 2) / 24;
      double te[2] = {0, 0};
      double b = build_ms(nvs[k], search, tn, te, pn);
      double s = search ? search_ms(nvs[k]) : 0;
      printf("%zu\t%s\t%.3f\t%.3f\t%zu\t%zu\t%zu\t%.2g\t%.2g\t%zu\t%zu\n", nvs[k],
             search ? "search" : "given", b, s, nsets, tn[0], tn[1], te[0], te[1],
             pn[0], pn[1]);
    }
  }
  /* one evaluation: tables vs exact, oppenheim primary */
  aq_arch *a = NULL;
  aq_error e;
  if (aq_arch_load("arches/oppenheim.cfg", &a, &e) != AQ_OK) {
    fprintf(stderr, "bench_arch: %s\n", e.message);
    return 1;
  }
  const aq_path *p = aq_arch_path(a, 0);
  enum { NE = 200000 };
  double te[REPS], tx[REPS], sink = 0;
  for (int r = 0; r < REPS; r++) {
    aq_path_point pt;
    double t0 = aq_bench_now_s();
    for (int i = 0; i < NE; i++) {
      p->eval(p->ctx, p->s_c_rad * (i % 997) / 997.0, &pt);
      sink += pt.x_m;
    }
    te[r] = (aq_bench_now_s() - t0) / NE;
    t0 = aq_bench_now_s();
    for (int i = 0; i < NE / 10; i++) {
      p->eval_exact(p->ctx, p->s_c_rad * (i % 997) / 997.0, &pt);
      sink += pt.x_m;
    }
    tx[r] = (aq_bench_now_s() - t0) / (NE / 10);
  }
  double me = aq_bench_median(te, REPS), mx = aq_bench_median(tx, REPS);
  printf("\neval\tns_per_call\tratio_to_table\n");
  printf("table\t%.1f\t1.00\nexact\t%.1f\t%.2f\n", 1e9 * me, 1e9 * mx, mx / me);
  aq_arch_free(a);
  if (!shapes() || !impact_rules())
    return 1;
  return sink == 12345.678 ? 1 : 0;
}
