/* test_dyn_rules.c: the stepper's event rules (impact, momentum rule, start,
 * rest, collapse time, peaks), each against a value the test computes apart
 * from the stepper: the energy balance KE(s) = -a m x(s) - g m y(s) of the
 * path (docs/dynamics.md) evaluated here, times by GSL's adaptive quadrature
 * of int sqrt(M / 2KE) ds, turning points by bisection on
 * KE(s) = 0.  The work path and the ode share these rules, so comparing the
 * two models cannot check them; these tests do.
 *
 * Each pulse is chosen by its end position s1: the test computes the pulse
 * length that reaches s1 from rest, so the energy at the next impact is the
 * closed form E = -a m x(s1) (the free motion after the pulse is
 * conservative and returns to s = 0 with all of it as kinetic energy). */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "arch/stepper.h"
#include "arch_fixture.h"
#include "check.h"
#include "test_dyn_mech.h"

static const double G_MPS2 = 9.80665; /* the g the test mechanisms are given */
/* Quadrature: relative tolerance asked of qags (after the substitution
 * s = s_end -+ u^2 the integrand is smooth). */
static const double QUAD_REL = 1e-13;

/* KE(s) = e0 - a m x(s) - g m y(s) on path p (J); NAN if p cannot be
 * evaluated at s. */
typedef struct {
  const aq_path *p;
  double e0, a;
} bal;

static double bal_ke(const bal *b, double s, double *mgen)
{
  aq_path_point pt;
  if (b->p->eval_exact(b->p->ctx, s, &pt))
    return NAN;
  if (mgen)
    *mgen = pt.mgen_kgm2;
  return b->e0 - b->a * b->p->mass_kg * pt.x_m -
         b->p->g_mps2 * b->p->mass_kg * pt.y_m;
}

/* sqrt(M / 2KE) at s = base + dir u^2, times ds/du = 2u: the 1/sqrt
 * singularity of a zero of KE at base is removed analytically. */
typedef struct {
  const bal *b;
  double base;
  int dir;
} subst;

static double integrand(double u, void *ctx)
{
  const subst *c = ctx;
  double m = 0, ke = bal_ke(c->b, c->base + c->dir * u * u, &m);
  return ke > 0 ? 2 * u * sqrt(m / (2 * ke)) : 0;
}

/* Time to move from s0 to s1 (s0 < s1) under the balance b, s: two halves,
 * each substituted about its outer end (where KE may vanish). */
static double leg_time(const bal *b, double s0, double s1)
{
  gsl_set_error_handler_off();
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(2000);
  double total = 0, half = sqrt(0.5 * (s1 - s0));
  for (int k = 0; k < 2; k++) {
    subst c = {b, k ? s1 : s0, k ? -1 : 1};
    gsl_function f = {integrand, &c};
    double r = 0, e = 0;
    int st = gsl_integration_qags(&f, 0, half, 0, QUAD_REL, 2000, w, &r, &e);
    if (st && st != GSL_EROUND)
      fprintf(stderr, "leg_time: qags: %s\n", gsl_strerror(st));
    total += r;
  }
  gsl_integration_workspace_free(w);
  return total;
}

/* The zero of KE in (lo, hi) where KE(lo) > 0 >= KE(hi), by bisection to
 * the last bit. */
static double turning_point(const bal *b, double lo, double hi)
{
  for (int it = 0; it < 200 && hi - lo > 0; it++) {
    double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi)
      break;
    if (bal_ke(b, mid, NULL) > 0)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

static int verbose(void) { return getenv("AQ_TEST_VERBOSE") != NULL; }

/* One run on an explicit step list. */
static int run(const aq_path *p0, const aq_path *p1, aq_model mdl, int momentum,
               double cor, double rest_tol, const double *t, const double *dt,
               const double *a, size_t n, aq_result *res)
{
  gsl_set_error_handler_off();
  aq_error e;
  aq_steps s;
  if (!aq_check(aq_steps_from_list(t, dt, a, n, &s, &e) == AQ_OK, "steps"))
    return 0;
  aq_stepper *st = aq_stepper_alloc(p0, p1, mdl, &e);
  if (!aq_check(st != NULL, "stepper: %s", e.message)) {
    aq_steps_free(&s);
    return 0;
  }
  aq_stepper_set_cor(st, cor);
  aq_stepper_set_impact(st, momentum);
  aq_stepper_set_exact_path(st, 1);
  aq_stepper_set_ode_rtol(st, 1e-13);
  if (rest_tol >= 0)
    aq_stepper_set_rest_tol(st, rest_tol);
  int ok = aq_check(aq_stepper_run(st, &s, res, &e) == AQ_OK, "run: %s", e.message);
  aq_stepper_free(st);
  aq_steps_free(&s);
  return ok;
}

/* A pulse of acceleration a on set 0 from rest to s1: its length (s) and the
 * energy it leaves, E = -a m x(s1) (J). */
static double pulse_to(const aq_path *p, double a, double s1, double *energy)
{
  bal b = {p, 0, a};
  double ke1 = bal_ke(&b, s1, NULL);
  aq_path_point pt;
  p->eval_exact(p->ctx, s1, &pt);
  *energy = ke1 + p->g_mps2 * p->mass_kg * pt.y_m;
  return leg_time(&b, 0, s1);
}

/* Free swing (a = 0) on p with energy e from s = 0: turning point and the
 * time out and back. */
static double free_swing(const aq_path *p, double e, double *sstar)
{
  bal b = {p, e, 0};
  *sstar = turning_point(&b, 0, p->s_c_rad);
  return 2 * leg_time(&b, 0, *sstar);
}

/* The rocking block (Housner 1963): half-width b, half-height h. */
static const double BLK_B = 0.217, BLK_H = 0.913, BLK_M = 1234.5;

/* One impact, energy known in closed form: dissipated = (1 - cor) E with
 * cor the kinetic-energy ratio (eq. 26, docs/dynamics.md); with the momentum
 * rule, (1 - r^2) E with Housner's r = 1 - 3/2 sin^2 alpha. */
AQ_TEST(dyn_rules_one_impact_keeps_cor_times_ke)
{
  tb_block blk[2];
  aq_path path[2];
  tb_block_paths(blk, path, BLK_B, BLK_H, BLK_M, G_MPS2);
  const double alpha = atan(BLK_B / BLK_H); /* Housner's slenderness */
  const double a = -1.3 * G_MPS2 * BLK_B / BLK_H, s1 = 0.12 * alpha;
  double E, sstar;
  double tp = pulse_to(&path[0], a, s1, &E);
  bal back = {&path[0], E, 0};
  sstar = turning_point(&back, s1, alpha);
  double t_back = leg_time(&back, s1, sstar) + leg_time(&back, 0, sstar);
  aq_check(sstar < alpha, "the free swing stays below collapse: %g < %g", sstar, alpha);
  const double housner_r = 1 - 1.5 * sin(alpha) * sin(alpha);
  struct {
    int momentum;
    double cor, kept; /* cor given, fraction of E kept */
  } cs[] = {{0, 0.6, 0.6}, {0, 0.23, 0.23}, {0, 1.5, 1.0} /* clamped to 1 */,
            {1, 0.6, housner_r * housner_r}};
  for (int mdl = 0; mdl < 2; mdl++)
    for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
      double s2, t2 = free_swing(&path[1], cs[k].kept * E, &s2);
      double t[2] = {0, tp}, dt[2] = {tp, t_back + 0.5 * t2}, acc[2] = {a, 0};
      aq_result r;
      if (!run(&path[0], &path[1], (aq_model)mdl, cs[k].momentum, cs[k].cor, -1,
               t, dt, acc, 2, &r))
        continue;
      aq_check(r.impacts == 1, "model %d case %zu: one impact, got %zu", mdl, k,
               r.impacts);
      double want = (1 - cs[k].kept) * E;
      /* measured 3e-16 J (workpath) on E = 45 J; 1e-13 relative to E */
      aq_check_abs(r.energy_dissipated_j, want, 1e-13 * E,
                   "model %d case %zu (cor %g, momentum %d): dissipated = "
                   "(1 - kept) E, E = %.17g J",
                   mdl, k, cs[k].cor, cs[k].momentum, E);
      aq_check_rel(r.energy_in_j, E, 2e-13, "model %d case %zu: energy in = -a m x(s1)",
                   mdl, k);
      aq_check_rel(r.max_kinetic_energy_j, E, 2e-13,
                   "model %d case %zu: largest KE = E, at the impact", mdl, k);
      aq_check_rel(r.peak_rotation_rad, sstar, 2e-13,
                   "model %d case %zu: peak rotation = turning point of the balance",
                   mdl, k);
      aq_result_free(&r);
    }
}

/* The momentum rule across two sets of different generalised mass: the
 * velocity ratio is that of the set the arch arrives on, and the kinetic
 * energy after is 1/2 M_after(0) (r sdot)^2 with sdot = sqrt(2 E / M_before(0)):
 * E r^2 M_after / M_before.  The energy is never created: r^2 M_a/M_b < 1. */
AQ_TEST(dyn_rules_momentum_rule_uses_each_sets_mass)
{
  tb_syn syn[2];
  aq_path path[2];
  tb_syn_paths(syn, path);
  path[0].impact_vel_ratio = 0.71; /* arriving on primary */
  path[1].impact_vel_ratio = 0.83; /* arriving on reverse: the one used here */
  aq_path_point p0, p1;
  path[0].eval_exact(path[0].ctx, 0, &p0);
  path[1].eval_exact(path[1].ctx, 0, &p1);
  const double kept = 0.83 * 0.83 * p1.mgen_kgm2 / p0.mgen_kgm2;
  aq_check(kept < 1, "this impact loses energy: kept %g", kept);
  const double a = -1.37 * path[0].lambda0 * G_MPS2, s1 = 0.2 * path[0].s_c_rad;
  double E;
  double tp = pulse_to(&path[0], a, s1, &E);
  bal back = {&path[0], E, 0};
  double sstar = turning_point(&back, s1, path[0].s_c_rad);
  double t_back = leg_time(&back, s1, sstar) + leg_time(&back, 0, sstar);
  double s2, t2 = free_swing(&path[1], kept * E, &s2);
  aq_check(s2 < path[1].s_c_rad && sstar < path[0].s_c_rad, "no collapse");
  for (int mdl = 0; mdl < 2; mdl++) {
    double t[2] = {0, tp}, dt[2] = {tp, t_back + 0.5 * t2}, acc[2] = {a, 0};
    aq_result r;
    if (!run(&path[0], &path[1], (aq_model)mdl, 1, 0.5, -1, t, dt, acc, 2, &r))
      continue;
    aq_check(r.impacts == 1, "model %d: one impact, got %zu", mdl, r.impacts);
    aq_check_abs(r.energy_dissipated_j, (1 - kept) * E, 1e-13 * E,
                 "model %d: dissipated = (1 - r^2 M_rev/M_pri) E", mdl);
    /* after the impact the reverse set swings to s2 (peak |q| is the larger) */
    aq_check_rel(r.peak_rotation_rad, fmax(sstar, s2), 2e-13,
                 "model %d: peak rotation = larger turning point", mdl);
    aq_result_free(&r);
  }
}

/* Collapse time: from rest under a constant a the block reaches s = alpha at
 * t_c = int_0^alpha sqrt(M / 2KE) ds; the run reports that crossing, not the
 * end of the step. */
AQ_TEST(dyn_rules_collapse_time_is_the_crossing)
{
  tb_block blk[2];
  aq_path path[2];
  tb_block_paths(blk, path, BLK_B, BLK_H, BLK_M, G_MPS2);
  const double alpha = atan(BLK_B / BLK_H), a = -2.9 * G_MPS2 * BLK_B / BLK_H;
  bal b = {&path[0], 0, a};
  aq_check(bal_ke(&b, alpha, NULL) > 0, "the pulse carries the block over");
  double tc = leg_time(&b, 0, alpha);
  for (int mdl = 0; mdl < 2; mdl++) {
    double t = 0.25, dt = 3 * tc, acc = a;
    aq_result r;
    if (!run(&path[0], &path[1], (aq_model)mdl, 0, 0.7, -1, &t, &dt, &acc, 1, &r))
      continue;
    aq_check(r.collapsed == 1, "model %d collapses", mdl);
    aq_check_rel(r.collapse_time_s, 0.25 + tc, 1e-13,
                 "model %d: collapse time = start + int sqrt(M/2KE)", mdl);
    aq_check_rel(r.peak_rotation_rad, alpha, 1e-15, "model %d: peak = alpha", mdl);
    aq_result_free(&r);
  }
}

/* Start from rest (Housner): the block moves only when |a| > g b/h. */
AQ_TEST(dyn_rules_block_starts_above_g_b_over_h)
{
  tb_block blk[2];
  aq_path path[2];
  tb_block_paths(blk, path, BLK_B, BLK_H, BLK_M, G_MPS2);
  const double thr = G_MPS2 * BLK_B / BLK_H;
  for (int mdl = 0; mdl < 2; mdl++)
    for (int side = -1; side <= 1; side += 2) {
      double t = 0, dt = 0.7, below = side * 0.999 * thr, above = side * 1.001 * thr;
      aq_result r;
      if (run(&path[0], &path[1], (aq_model)mdl, 0, 0.7, -1, &t, &dt, &below, 1, &r)) {
        aq_check(r.peak_rotation_rad == 0 && r.steps_moving == 0,
                 "model %d: |a| = 0.999 g b/h (sign %d) does not move it", mdl, side);
        aq_result_free(&r);
      }
      if (run(&path[0], &path[1], (aq_model)mdl, 0, 0.7, -1, &t, &dt, &above, 1, &r)) {
        aq_check(r.peak_rotation_rad > 0, "model %d: 1.001 g b/h (sign %d) moves it",
                 mdl, side);
        aq_result_free(&r);
      }
    }
}

/* Rest: each impact keeps cor KE, so after n impacts cor^n E is left; the
 * motion ends at the first impact where that is <= rest_tol m g y(s_c), and
 * then every joule that came in has been dissipated. */
AQ_TEST(dyn_rules_rest_after_the_counted_impacts)
{
  tb_block blk[2];
  aq_path path[2];
  tb_block_paths(blk, path, BLK_B, BLK_H, BLK_M, G_MPS2);
  const double alpha = atan(BLK_B / BLK_H), R = hypot(BLK_B, BLK_H);
  const double a = -1.3 * G_MPS2 * BLK_B / BLK_H, s1 = 0.12 * alpha;
  const double e_ref = BLK_M * G_MPS2 * (R - BLK_H); /* m g y(alpha) */
  double E, tp = pulse_to(&path[0], a, s1, &E);
  struct {
    double cor, rest_tol;
  } cs[] = {{0.5, 1e-6}, {0.3, 1e-9}};
  for (size_t k = 0; k < sizeof cs / sizeof cs[0]; k++) {
    size_t n = 1;
    while (pow(cs[k].cor, (double)n) * E > cs[k].rest_tol * e_ref)
      n++;
    double margin = log(cs[k].rest_tol * e_ref / E) / log(cs[k].cor);
    aq_check(fabs(margin - floor(margin + 0.5)) > 0.05,
             "case %zu: the count %.3f is not at an integer (test design)", k, margin);
    double t[2] = {0, tp}, dt[2] = {tp, 30}, acc[2] = {a, 0};
    aq_result r;
    if (!run(&path[0], &path[1], AQ_MODEL_WORKPATH, 0, cs[k].cor, cs[k].rest_tol, t,
             dt, acc, 2, &r))
      continue;
    aq_check(r.impacts == n, "case %zu: %zu impacts to rest (cor %g), got %zu", k, n,
             cs[k].cor, r.impacts);
    aq_check_rel(r.energy_dissipated_j, E, 2e-13,
                 "case %zu: at rest, all the energy put in is dissipated", k);
    aq_result_free(&r);
  }
}

/* A test path whose centroid displacement x(s) = X sin(w s) peaks inside the
 * swing: the peak displacement is X exactly, and the peak rotation is the
 * turning point s* of the energy balance. */
typedef struct {
  double X, w, Y, sc, M0;
  int sd;
} hump;

static int hump_eval(const void *ctx, double s, aq_path_point *p)
{
  const hump *k = ctx;
  if (!(s >= 0) || s > k->sc)
    return 1;
  double X = k->sd * k->X;
  memset(p, 0, sizeof *p);
  p->x_m = X * sin(k->w * s);
  p->dx_m = X * k->w * cos(k->w * s);
  p->d2x_m = -X * k->w * k->w * sin(k->w * s);
  p->y_m = k->Y * (s - s * s / (2 * k->sc));
  p->dy_m = k->Y * (1 - s / k->sc);
  p->d2y_m = -k->Y / k->sc;
  p->mgen_kgm2 = k->M0 * (1 + 0.4 * s);
  p->dmgen_kgm2 = 0.4 * k->M0;
  p->lambda = fabs(p->dy_m / p->dx_m);
  return 0;
}

AQ_TEST(dyn_rules_peaks_are_the_turning_points)
{
  hump hm[2] = {{0.8, 3.5, 0.35, 0.9, 2100.0, 1}, {0.8, 3.5, 0.35, 0.9, 2100.0, -1}};
  aq_path path[2];
  for (int k = 0; k < 2; k++)
    path[k] = (aq_path){.name = k ? "reverse" : "primary",
                        .eval = hump_eval,
                        .eval_exact = hump_eval,
                        .ctx = &hm[k],
                        .mass_kg = 1700.0,
                        .g_mps2 = G_MPS2,
                        .lambda0 = hm[k].Y / (hm[k].X * hm[k].w),
                        .s_c_rad = hm[k].sc,
                        .act_sign = k ? 1 : -1,
                        .q_sign = k ? -1 : 1,
                        .admissible = 1,
                        .impact_vel_ratio = 0.9};
  const double peak_s = M_PI / (2 * 3.5); /* where x = X */
  int right_of_node = 0;
  for (int c = 0; c < 3; c++) {
    const double a = -(1.95 + 0.1 * c) * path[0].lambda0 * G_MPS2, s1 = 0.2;
    double E, tp = pulse_to(&path[0], a, s1, &E);
    bal back = {&path[0], E, 0};
    double sstar = turning_point(&back, s1, path[0].s_c_rad);
    double t_out = leg_time(&back, s1, sstar);
    aq_check(sstar > peak_s && sstar < path[0].s_c_rad,
             "case %d: the swing passes the peak of x: %g in (%g, %g)", c, sstar, peak_s,
             path[0].s_c_rad);
    /* the stepper samples [0, s*] at 32 points: is the peak right of the
     * nearest one (where a search that only looks left would miss it)? */
    double node = sstar * floor(32 * peak_s / sstar + 0.5) / 32;
    right_of_node += peak_s > node;
    for (int mdl = 0; mdl < 2; mdl++) {
      /* stop at half the way back: one turning point, no impact */
      double t[2] = {0, tp}, dt[2] = {tp, t_out + 0.5 * leg_time(&back, 0, sstar)},
             acc[2] = {a, 0};
      aq_result r;
      if (!run(&path[0], &path[1], (aq_model)mdl, 0, 0.0, -1, t, dt, acc, 2, &r))
        continue;
      aq_check(r.impacts == 0 && r.reversals == 1, "case %d model %d: one turning point",
               c, mdl);
      aq_check_rel(r.peak_rotation_rad, sstar, mdl ? 1e-12 : 1e-13,
                   "case %d model %d: peak rotation = zero of KE(s)", c, mdl);
      aq_check_rel(r.peak_displacement_m, 0.8, 1e-15,
                   "case %d model %d: peak displacement = X", c, mdl);
      if (verbose())
        fprintf(stderr, "  case %d model %d: s* %.17g, peak x %.17g\n", c, mdl,
                r.peak_rotation_rad, r.peak_displacement_m);
      aq_result_free(&r);
    }
  }
  aq_check(right_of_node > 0, "a case puts the peak right of its nearest node");
}

/* The same on a shipped arch, with its exact kinematics evaluated here: a
 * pulse to s1, then the free swing to the turning point of the balance. */
AQ_TEST(dyn_rules_arch_peak_rotation_is_the_turning_point)
{
  aq_arch *arch = aq_test_arch_load("arches/oppenheim.cfg");
  if (!arch)
    return;
  const aq_path *p = aq_arch_path(arch, 0), *q = aq_arch_path(arch, 1);
  const double a = p->act_sign * 1.6 * p->lambda0 * p->g_mps2, s1 = 0.15 * p->s_c_rad;
  double E, tp = pulse_to(p, a, s1, &E);
  bal back = {p, E, 0};
  double sstar = turning_point(&back, s1, p->s_c_rad);
  double t_out = leg_time(&back, s1, sstar), t_in = leg_time(&back, 0, sstar);
  for (int mdl = 0; mdl < 2; mdl++) {
    double t[2] = {0, tp}, dt[2] = {tp, t_out + 0.5 * t_in}, acc[2] = {a, 0};
    aq_result r;
    if (!run(p, q, (aq_model)mdl, 0, 0.7, -1, t, dt, acc, 2, &r))
      continue;
    aq_check_rel(r.peak_rotation_rad, sstar, 1e-10,
                 "model %d: oppenheim peak rotation = zero of KE(s)", mdl);
    aq_check_rel(r.energy_in_j, E, 1e-10, "model %d: energy in = -a m x(s1)", mdl);
    aq_result_free(&r);
  }
  aq_arch_free(arch);
}

/* The momentum rule on every shipped arch: the velocity ratio is positive
 * (the motion goes on, on the other set; unlike a single block's it may
 * exceed 1, the generalised masses differing) and the energy kept,
 * r^2 M_after(0) / M_before(0), is at most 1 (an impact never creates
 * energy). */
AQ_TEST(dyn_rules_arch_impacts_never_create_energy)
{
  static const char *const files[] = {"arches/oppenheim.cfg", "arches/thin.cfg",
                                      "arches/thick.cfg", "arches/search.cfg"};
  for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
    aq_arch *arch = aq_test_arch_load(files[f]);
    if (!arch)
      continue;
    for (int k = 0; k < 2; k++) {
      const aq_path *to = aq_arch_path(arch, k), *from = aq_arch_path(arch, 1 - k);
      if (!to->admissible || !from->admissible)
        continue;
      aq_path_point pa, pb;
      to->eval_exact(to->ctx, 0, &pa);
      from->eval_exact(from->ctx, 0, &pb);
      double r = to->impact_vel_ratio, kept = r * r * pa.mgen_kgm2 / pb.mgen_kgm2;
      aq_check(r > 0, "%s set %d: velocity ratio %.17g > 0", files[f], k, r);
      aq_check(kept <= 1, "%s set %d: energy kept %.17g <= 1", files[f], k, kept);
    }
    aq_arch_free(arch);
  }
}

/* Rest under a constant acceleration below the threshold: after a small
 * pulse a1, a step of a2 = -0.995 g b/h keeps the motion conservative on
 * each set (potential a2 m x + g m y), so the k-th impact arrives with
 * cor^(k-1) E', E' = (a2 - a1) m x(s1); the block rests at the first impact
 * where cor^n E' <= rest_tol m g y(alpha), and a2, below g b/h, must not
 * start it again within the step.  (A2 leaves a barrier of only about
 * 1/2 m g R (0.005 sin alpha)^2 cos alpha on the primary set, so the pulse
 * is small.) */
AQ_TEST(dyn_rules_rest_holds_under_a_subthreshold_step)
{
  tb_block blk[2];
  aq_path path[2];
  tb_block_paths(blk, path, BLK_B, BLK_H, BLK_M, G_MPS2);
  const double alpha = atan(BLK_B / BLK_H), R = hypot(BLK_B, BLK_H);
  const double thr = G_MPS2 * BLK_B / BLK_H;
  const double a1 = -1.3 * thr, a2 = -0.995 * thr, s1 = 6e-6;
  const double cor = 0.5, rest_tol = 1e-6;
  const double e_ref = BLK_M * G_MPS2 * (R - BLK_H);
  double E, tp = pulse_to(&path[0], a1, s1, &E);
  aq_path_point pt;
  path[0].eval_exact(path[0].ctx, s1, &pt);
  const double e1 = (a2 - a1) * BLK_M * pt.x_m;
  /* the barrier of a2 on the primary set: max of a2 m x + g m y */
  bal v = {&path[0], 0, a2};
  double barrier = 0;
  for (int k = 1; k <= 20000; k++)
    barrier = fmax(barrier, -bal_ke(&v, alpha * k / 20000.0 * 0.01, NULL));
  aq_check(e1 < 0.8 * barrier, "test design: E' %g J below the barrier %g J", e1, barrier);
  size_t n = 1;
  while (pow(cor, (double)n) * e1 > rest_tol * e_ref)
    n++;
  double t[2] = {0, tp}, dt[2] = {tp, 30}, acc[2] = {a1, a2};
  for (int mdl = 0; mdl < 2; mdl++) {
    aq_result r;
    if (!run(&path[0], &path[1], (aq_model)mdl, 0, cor, rest_tol, t, dt, acc, 2, &r))
      continue;
    aq_check(!r.collapsed && r.impacts == n,
             "model %d: rests after %zu impacts under 0.995 g b/h, got %zu", mdl, n,
             r.impacts);
    aq_result_free(&r);
  }
}
