/* test_dyn_taylor.c: the default work-path leg (time-Taylor series on the
 * path's pieces, leg_taylor.c) against the ode model at a tight tolerance
 * (an independent integration of the equation of motion) and against the
 * quadrature leg (workpath-quad) on the hard cases; the stepper's scale
 * against a scaled copy of the steps; history samples at turning points.
 * (The rocking block's closed forms run the same leg: test_dyn_block.c,
 * whose block supplies pieces.) */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "arch/arch.h"
#include "arch/stepper.h"
#include "arch_fixture.h"
#include "check.h"
#include "test_dyn_steps.h"
#include "units.h"

static const double ODE_RTOL = 1e-13; /* the reference's tolerance */

/* Run model mdl on the steps (COR cor, history on, scale k). */
static int trun(const aq_arch *a, aq_model mdl, double cor, const aq_steps *s,
                double k, aq_result *r)
{
  return tds_run(a, mdl, cor, 0, ODE_RTOL, k, s, r);
}

typedef struct {
  const char *arch;
  const char *what;
  double ratio;   /* acceleration / (lambda0 g), along act_sign */
  double dur, end, dt, cor;
} tcase;

/* The hard cases: near threshold, an impulse, many impacts, step sizes
 * from 1e-5 to 0.05 s, thin and thick arches, collapse. */
static const tcase CASES[] = {
    {"arches/oppenheim.cfg", "1.0001 lambda0 g for 2 s", 1.0001, 2, 12, 0.01, 0},
    {"arches/oppenheim.cfg", "10 g for 1 ms", -1, 1e-3, 5, 1e-3, 0},
    {"arches/oppenheim.cfg", "COR 0.3, many impacts", -0.55, 0.45, 30, 0.01, 0.3},
    {"arches/oppenheim.cfg", "steps of 1e-5 s", -0.6, 0.4, 1.2, 1e-5, 0.7},
    {"arches/oppenheim.cfg", "steps of 0.05 s", -0.6, 0.4, 1.2, 0.05, 0.7},
    {"arches/oppenheim.cfg", "collapse", -0.5, 0.9, 3, 0.01, 0.7},
    {"arches/thin.cfg", "thin, rocking", 1.2, 0.2, 10, 0.02, 0.7},
    {"arches/thin.cfg", "thin, collapse", 3, 0.5, 3, 0.01, 0.7},
    {"arches/thick.cfg", "thick, rocking", 1.2, 0.2, 10, 0.02, 0.7},
    {"arches/thick.cfg", "thick, collapse", 3, 0.5, 3, 0.01, 0.7},
};

/* The reference's own spread on case s: the ode's peak displacement with
 * the record scaled by 1 +- REF_ULPS units of round-off, relative to the
 * unscaled run's.  It measures the case's conditioning: a well-posed case
 * moves by ~1e-15, while near the threshold (net force 1e-4 of its terms)
 * four ulps of input move the peak by ~1e-11. */
#define REF_ULPS 4.0
static double ode_spread(const aq_arch *a, double cor, const aq_steps *s, double peak)
{
  double spread = 0;
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    aq_result r;
    if (!trun(a, AQ_MODEL_ODE, cor, s, 1.0 + sgn * REF_ULPS * DBL_EPSILON, &r))
      return INFINITY;
    spread = fmax(spread, fabs(r.peak_displacement_m - peak) / fabs(peak));
    aq_result_free(&r);
  }
  return spread;
}

/* Peaks, collapse time and events of the default model against the ode at
 * rtol 1e-13 and against workpath-quad.  The bar is the issue's: within
 * 1e-12 relative, or within the reference's own spread where that is
 * looser (twice ode_spread: the ode's answer moves that much when the
 * record moves by four ulps).  Measured: peak displacement and rotation
 * within 3e-13 relative of the ode, collapse times within 2e-14 s, on
 * every case but the near-threshold one (1.0001 lambda0 g), where the net
 * force is 1e-4 of its terms: there the default is 5.4e-13 from the ode
 * and 1.0e-12 from workpath-quad (both on the Hermite tables), while those
 * two are 8e-12 from the ode on the exact kinematics, and the default
 * 7.5e-12 (docs/dynamics.md); the ode's own spread there is ~1e-11. */
AQ_TEST(dyn_taylor_hard_cases_vs_ode)
{
  const double TOL_REL = 1e-12, TOL_TC_S = 1e-12;
  for (size_t c = 0; c < sizeof CASES / sizeof CASES[0]; c++) {
    const tcase *k = &CASES[c];
    aq_arch *a = aq_test_arch_load(k->arch);
    if (!a)
      continue;
    const aq_path *p = aq_arch_path(a, 0);
    /* ratio < 0: -ratio in g (not lambda0 g) */
    double acc = p->act_sign * (k->ratio > 0 ? k->ratio * p->lambda0 * p->g_mps2
                                             : -k->ratio * AQ_G0_MPS2);
    if (k->ratio == -1)
      acc = p->act_sign * 10 * AQ_G0_MPS2;
    aq_steps s;
    if (!aq_check(tds_pulse(acc, k->dur, k->end, k->dt, &s), "%s: steps", k->what)) {
      aq_arch_free(a);
      continue;
    }
    aq_result r[3];
    static const aq_model mdl[3] = {AQ_MODEL_WORKPATH, AQ_MODEL_ODE,
                                    AQ_MODEL_WORKPATH_QUAD};
    int ok = 1;
    for (int m = 0; m < 3; m++)
      ok &= trun(a, mdl[m], k->cor, &s, 1, &r[m]);
    if (ok) {
      double spread = ode_spread(a, k->cor, &s, r[1].peak_displacement_m);
      const double TOL_PEAK = fmax(TOL_REL, 2 * spread);
      if (getenv("AQ_TEST_VERBOSE"))
        fprintf(stderr, "%s %s: ode spread %.2e, peak tol %.2e, default-ode %.2e, "
                        "default-quad %.2e\n", k->arch, k->what, spread, TOL_PEAK,
                fabs(r[0].peak_displacement_m / r[1].peak_displacement_m - 1),
                fabs(r[0].peak_displacement_m / r[2].peak_displacement_m - 1));
      for (int m = 1; m < 3; m++) {
        const char *ref = m == 1 ? "ode" : "workpath-quad";
        aq_check_rel(r[0].peak_displacement_m, r[m].peak_displacement_m, TOL_PEAK,
                     "%s %s: peak displacement vs %s", k->arch, k->what, ref);
        aq_check_rel(r[0].peak_rotation_rad, r[m].peak_rotation_rad, TOL_PEAK,
                     "%s %s: peak rotation vs %s", k->arch, k->what, ref);
        aq_check(r[0].collapsed == r[m].collapsed && r[0].impacts == r[m].impacts &&
                     r[0].reversals == r[m].reversals,
                 "%s %s: collapse %d/%d, impacts %zu/%zu, reversals %zu/%zu vs %s",
                 k->arch, k->what, r[0].collapsed, r[m].collapsed, r[0].impacts,
                 r[m].impacts, r[0].reversals, r[m].reversals, ref);
        if (r[0].collapsed && r[m].collapsed)
          aq_check_abs(r[0].collapse_time_s, r[m].collapse_time_s, TOL_TC_S,
                       "%s %s: collapse time vs %s", k->arch, k->what, ref);
      }
      aq_check(r[0].substeps > 0 && r[0].steps_moving > 0, "%s %s: %zu sub-steps",
               k->arch, k->what, r[0].substeps);
    }
    for (int m = 0; m < 3; m++)
      if (ok)
        aq_result_free(&r[m]);
    aq_steps_free(&s);
    aq_arch_free(a);
  }
}

/* aq_stepper_set_scale(k) gives exactly the run on a copy of the steps
 * multiplied by k (k = 2.5, and -1.7: reversed polarity); k = 0 never
 * moves.  Steps: a pseudo-random record (fixed LCG) of 0.005 s. */
AQ_TEST(dyn_stepper_scale_equals_scaled_copy)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  enum { N = 1200 };
  double t[N], d[N], ac[N], ak[N];
  unsigned long x = 12345;
  for (size_t i = 0; i < N; i++) {
    x = (x * 1103515245UL + 12345UL) & 0x7fffffffUL;
    t[i] = 0.005 * (double)i;
    d[i] = 0.005;
    /* up to 1.3 lambda0 g in a 0.4 s burst */
    double env = i > 100 && i < 180 ? 1.3 : 0.3;
    ac[i] = env * p->lambda0 * p->g_mps2 * (2.0 * (double)x / 0x7fffffff - 1);
  }
  static const double K[3] = {2.5, -1.7, 0};
  for (int j = 0; j < 3; j++) {
    for (size_t i = 0; i < N; i++)
      ak[i] = K[j] * ac[i];
    aq_error e;
    aq_steps s1, s2;
    aq_result r1, r2;
    if (aq_steps_from_list(t, d, ac, N, &s1, &e) != AQ_OK ||
        aq_steps_from_list(t, d, ak, N, &s2, &e) != AQ_OK) {
      aq_check(0, "steps: %s", e.message);
      continue;
    }
    if (trun(a, AQ_MODEL_WORKPATH, 0.7, &s1, K[j], &r1)) {
      if (trun(a, AQ_MODEL_WORKPATH, 0.7, &s2, 1, &r2)) {
        aq_check(r1.peak_rotation_rad == r2.peak_rotation_rad &&
                     r1.peak_displacement_m == r2.peak_displacement_m &&
                     r1.impacts == r2.impacts && r1.collapsed == r2.collapsed &&
                     r1.history.n == r2.history.n,
                 "scale %g: peak %.17g vs %.17g on the scaled copy, impacts %zu %zu",
                 K[j], r1.peak_rotation_rad, r2.peak_rotation_rad, r1.impacts,
                 r2.impacts);
        if (K[j] != 0)
          aq_check(r1.impacts > 0, "scale %g: the arch rocks", K[j]);
        else
          aq_check(r1.steps_moving == 0 && r1.peak_rotation_rad == 0,
                   "scale 0: never moves");
        aq_result_free(&r2);
      }
      aq_result_free(&r1);
    }
    aq_steps_free(&s1);
    aq_steps_free(&s2);
  }
  aq_arch_free(a);
}

/* The history samples turning points: its largest |rotation| is the
 * run's peak (and the ode's, to its convergence), which step ends of
 * 0.05 s alone miss; samples are in time order; KE = 0 at the turning
 * points, the pre-impact KE at impacts. */
AQ_TEST(dyn_history_samples_turning_points)
{
  aq_arch *a = aq_test_arch_load("arches/oppenheim.cfg");
  if (!a)
    return;
  const aq_path *p = aq_arch_path(a, 0);
  aq_steps s;
  if (!tds_pulse(p->act_sign * 0.55 * AQ_G0_MPS2, 0.45, 6, 0.05, &s)) {
    aq_arch_free(a);
    return;
  }
  aq_result r, ro;
  if (trun(a, AQ_MODEL_WORKPATH, 0.7, &s, 1, &r)) {
    if (trun(a, AQ_MODEL_ODE, 0.7, &s, 1, &ro)) {
      const aq_history *h = &r.history;
      double hmax = 0, emax = 0;
      size_t turns = 0, order_bad = 0;
      for (size_t i = 0; i < h->n; i++) {
        hmax = fmax(hmax, fabs(h->rotation_rad[i]));
        if (i > 0 && h->time_s[i] < h->time_s[i - 1])
          order_bad++;
        double k = h->time_s[i] / 0.05;
        if (fabs(k - round(k)) < 1e-9)
          emax = fmax(emax, fabs(h->rotation_rad[i]));
        else if (h->kinetic_energy_j[i] == 0 && h->rotation_rad[i] != 0)
          turns++;
      }
      aq_check_rel(hmax, r.peak_rotation_rad, 1e-15, "history peak = run's peak");
      aq_check_rel(hmax, ro.peak_rotation_rad, 1e-12, "history peak = ode's peak");
      aq_check(emax < (1 - 1e-4) * hmax, "step ends alone miss it: %.9g < %.9g",
               emax, hmax);
      aq_check(turns == r.reversals && order_bad == 0,
               "%zu turning-point samples for %zu reversals; %zu out of order",
               turns, r.reversals, order_bad);
      aq_check(h->n == s.n + r.reversals + r.impacts, "%zu samples: %zu steps, "
               "%zu reversals, %zu impacts", h->n, s.n, r.reversals, r.impacts);
      aq_result_free(&ro);
    }
    aq_result_free(&r);
  }
  aq_steps_free(&s);
  aq_arch_free(a);
}

/* Random step lists (0.1 ms to 80 ms, up to 2.2 lambda0 g either way, any
 * COR, either impact rule) on the thick arch and on the searched one,
 * where a sub-step could start at a piece's end, dip into the piece and
 * come back through that same end (once a leg without progress): every
 * run completes and agrees with the ode on collapse and impacts. */
AQ_TEST(dyn_taylor_random_steps_vs_ode)
{
  const char *files[] = {"arches/thick.cfg", "arches/search.cfg"};
  enum { N = 400, RUNS = 40 };
  static double t[N], d[N], acc[N];
  for (int f = 0; f < 2; f++) {
    aq_arch *a = aq_test_arch_load(files[f]);
    if (!a)
      continue;
    const aq_path *p0 = aq_arch_path(a, 0), *p1 = aq_arch_path(a, 1);
    double l1 = p1->admissible ? p1->lambda0 * p1->g_mps2 : p0->lambda0 * p0->g_mps2;
    unsigned long long x = 0x2545f4914f6cdd1dULL + (unsigned long long)f;
    int bad = 0, moved = 0;
    for (int run = 0; run < RUNS; run++) {
      tds_random(&x, p0->lambda0 * p0->g_mps2, l1, t, d, acc, N);
      double cor = tds_rng(&x);
      int mom = tds_rng(&x) < 0.3;
      aq_error e;
      aq_steps s;
      if (aq_steps_from_list(t, d, acc, N, &s, &e) != AQ_OK)
        continue;
      aq_result r[2];
      int ok[2];
      for (int m = 0; m < 2; m++)
        ok[m] = tds_run(a, m ? AQ_MODEL_ODE : AQ_MODEL_WORKPATH, cor, mom,
                        1e-12, 1, &s, &r[m]);
      if (ok[0] && ok[1]) {
        bad += r[0].collapsed != r[1].collapsed || r[0].impacts != r[1].impacts;
        moved += r[0].steps_moving > 0;
      }
      for (int m = 0; m < 2; m++)
        if (ok[m])
          aq_result_free(&r[m]);
      aq_steps_free(&s);
    }
    aq_check(bad == 0 && moved >= RUNS / 2,
             "%s: %d of %d runs differ from the ode in collapse or impacts; %d moved",
             files[f], bad, RUNS, moved);
    aq_arch_free(a);
  }
}
