/* bench_dyn.c: speed against error of the dynamic models, one table from
 * one run (so that the ratios hold on a noisy machine).
 *
 * Cases: arches/oppenheim.cfg under two rectangular pulses (0.01 s steps)
 * and under the records in records/ (read and processed as the main job
 * does, job/subject.h, scaled to a PGA of 2.5 and of 5 lambda0 g), COR 0.7.
 * Settings: the work path (default: time-Taylor leg; a looser tolerance;
 * records merged with --merge-tol), workpath-quad (Chebyshev panels, two
 * settings), the ode model at several rtol, the paper model.  Reference:
 * ode at rtol 1e-12 on unmerged steps.
 * Reported per case: moving steps, impacts, the reference's and the default's
 * median times, their ratio, the default's errors and the reference's own
 * spread of the collapse time (tighter rtol, the exact path, the
 * record scaled by a few unit round-offs: a collapse after many impacts
 * can amplify round-off a million-fold, so that no model agrees with
 * another closer than that).  Per setting: the
 * sum over cases of the median time per run, the speed ratio to the
 * reference and to ode at 1e-8, the smallest per-case ratio to the
 * reference, the cost per moving step, sub-steps and path evaluations,
 * the largest relative error of the peak displacement, the largest error
 * of the collapse time, how many cases disagree with the reference on
 * collapse, and how many are within the reference's error (peak within
 * 1e-12 relative, collapse time within the reference's spread widened by
 * 1e-12 relative). */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <float.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"
#include "arch/stepper.h"
#include "bench.h"
#include "io/record.h"
#include "job/job.h"
#include "signal/signal.h"
#include "units.h"

enum { MAX_CASES = 24, REPS = 15 };
static const double EQ_REL = 1e-12; /* equal error: relative to the reference */

typedef struct {
  const char *name;
  aq_model model;
  double rtol;     /* ode */
  int nodes;       /* workpath-quad */
  double wtol;     /* workpath-quad */
  double ttol;     /* workpath (Taylor); 0: default */
  double merge_g;  /* merge tolerance for record steps, g */
  int exact;       /* the exact path instead of the tables */
} setting;

typedef struct {
  char name[64];
  int is_record;
  double pulse_a, pulse_dur, pulse_end;
  aq_steps steps[3]; /* merge 0, 0.001 g, 0.01 g (records); [0] for pulses */
} bcase;

static const double MERGES_G[3] = {0, 0.001, 0.01};

static int merge_index(double g)
{
  for (int k = 0; k < 3; k++)
    if (g == MERGES_G[k])
      return k;
  return 0;
}

static int pulse_steps(double a, double dur, double end, double dt, aq_steps *s)
{
  size_t n1 = (size_t)ceil(dur / dt - 1e-9), n2 = (size_t)ceil((end - dur) / dt - 1e-9);
  size_t n = n1 + n2;
  double *t = malloc(n * sizeof *t), *d = malloc(n * sizeof *d),
         *ac = malloc(n * sizeof *ac);
  for (size_t i = 0; i < n; i++) {
    int first = i < n1;
    double t0 = first ? 0 : dur, span = first ? dur : end - dur;
    size_t k = first ? i : i - n1, m = first ? n1 : n2;
    t[i] = t0 + span * k / m;
    d[i] = t0 + span * (k + 1) / m - t[i];
    ac[i] = first ? a : 0;
  }
  aq_error e;
  int ok = aq_steps_from_list(t, d, ac, n, s, &e) == AQ_OK;
  free(t);
  free(d);
  free(ac);
  return ok;
}

static int run(const aq_arch *a, const setting *S, const aq_steps *steps,
               double scale, aq_result *r, double *sec)
{
  aq_error e;
  aq_stepper *st = aq_stepper_alloc(aq_arch_path(a, 0), aq_arch_path(a, 1),
                                    S->model, &e);
  if (!st) {
    fprintf(stderr, "bench_dyn: %s\n", e.message);
    return 0;
  }
  aq_stepper_set_cor(st, 0.7);
  if (S->model == AQ_MODEL_ODE)
    aq_stepper_set_ode_rtol(st, S->rtol);
  if (S->model == AQ_MODEL_WORKPATH_QUAD) {
    aq_stepper_set_wp_nodes(st, S->nodes);
    aq_stepper_set_wp_tol(st, S->wtol);
  }
  if (S->model == AQ_MODEL_WORKPATH && S->ttol > 0)
    aq_stepper_set_taylor_tol(st, S->ttol);
  aq_stepper_set_scale(st, scale);
  aq_stepper_set_exact_path(st, S->exact);
  double t0 = aq_bench_now_s();
  aq_status rc = aq_stepper_run(st, steps, r, &e);
  *sec = aq_bench_now_s() - t0;
  aq_stepper_free(st);
  if (rc != AQ_OK) {
    fprintf(stderr, "bench_dyn: %s: %s\n", S->name, e.message);
    return 0;
  }
  return 1;
}

int main(void)
{
  gsl_set_error_handler_off();
  aq_error e;
  aq_arch *a = NULL;
  if (aq_arch_load("arches/oppenheim.cfg", &a, &e) != AQ_OK) {
    fprintf(stderr, "bench_dyn: %s\n", e.message);
    return 1;
  }
  const aq_path *p = aq_arch_path(a, 0);
  static bcase cs[MAX_CASES];
  size_t nc = 0;
  /* pulses */
  snprintf(cs[nc].name, sizeof cs[nc].name, "pulse 0.6g 0.45s");
  cs[nc].pulse_a = p->act_sign * 0.6 * AQ_G0_MPS2;
  cs[nc].pulse_dur = 0.45;
  cs[nc].pulse_end = 10;
  nc++;
  snprintf(cs[nc].name, sizeof cs[nc].name, "pulse 0.5g 0.9s");
  cs[nc].pulse_a = p->act_sign * 0.5 * AQ_G0_MPS2;
  cs[nc].pulse_dur = 0.9;
  cs[nc].pulse_end = 10;
  nc++;
  for (size_t k = 0; k < nc; k++)
    if (!pulse_steps(cs[k].pulse_a, cs[k].pulse_dur, cs[k].pulse_end, 0.01,
                     &cs[k].steps[0]))
      return 1;
  /* records */
  DIR *dir = opendir("records");
  aq_signal_ws *ws = aq_signal_ws_alloc();
  struct dirent *de;
  char *names[MAX_CASES];
  size_t nn = 0;
  while (dir && (de = readdir(dir)) && nn < MAX_CASES) {
    if (de->d_name[0] == '.' || strstr(de->d_name, ".md"))
      continue;
    names[nn++] = strdup(de->d_name);
  }
  if (dir)
    closedir(dir);
  for (size_t i = 0; i < nn; i++) /* stable order */
    for (size_t j = i + 1; j < nn; j++)
      if (strcmp(names[i], names[j]) > 0) {
        char *t = names[i];
        names[i] = names[j];
        names[j] = t;
      }
  static const double SCALES[2] = {2.5, 5.0}; /* PGA / (lambda0 g) */
  for (size_t ii = 0; ii < 2 * nn && nc < MAX_CASES; ii++) {
    size_t i = ii % nn;
    double pga_ratio = SCALES[ii / nn];
    char path[512];
    snprintf(path, sizeof path, "records/%s", names[i]);
    aq_read_opts ro;
    memset(&ro, 0, sizeof ro);
    aq_signal_opts so;
    aq_signal_opts_default(&so);
    bcase *c = &cs[nc];
    /* the record as the main job prepares it (job/subject.h), scaled to
       pga_ratio lambda0 g as --scale-to-pga would */
    aq_subject subj;
    aq_subject_src src = {{path, NULL, NULL}, {NAN, NAN}, path};
    aq_subject_opts o = {&ro, &so, 0, 0, 0};
    if (aq_subject_prepare(&subj, &src, &o, ws, &e) != AQ_OK || !(subj.pga_g > 0)) {
      fprintf(stderr, "bench_dyn: skip %s: %s\n", path, e.message);
      aq_subject_free(&subj);
      continue;
    }
    aq_scale_rule rule = {NULL, 0, pga_ratio * p->lambda0 * p->g_mps2 / AQ_G0_MPS2, 0};
    double scale = aq_scale_factor(&rule, 0, subj.pga_g);
    c->is_record = 1;
    snprintf(c->name, sizeof c->name, "%.24s x%.1f", names[i], pga_ratio);
    int good = 1;
    for (int k = 0; k < 3; k++) {
      double peak;
      good &= aq_subject_steps(&subj, 0, scale, scale, MERGES_G[k] * AQ_G0_MPS2, &c->steps[k],
                               &peak, &e) == AQ_OK;
    }
    aq_subject_free(&subj);
    if (good)
      nc++;
  }
  for (size_t i = 0; i < nn; i++)
    free(names[i]);
  aq_signal_ws_free(ws);

  static const setting set[] = {
      {"workpath (default: Taylor)", AQ_MODEL_WORKPATH, 0, 0, 0, 0, 0, 0},
      {"workpath Taylor tol 1.1e-16", AQ_MODEL_WORKPATH, 0, 0, 0, 1.1e-16, 0, 0},
      {"workpath default, --merge-tol 0.001 g", AQ_MODEL_WORKPATH, 0, 0, 0, 0, 0.001, 0},
      {"workpath default, --merge-tol 0.01 g", AQ_MODEL_WORKPATH, 0, 0, 0, 0, 0.01, 0},
      {"workpath-quad (12 nodes, tol 1e-12)", AQ_MODEL_WORKPATH_QUAD, 0, 12, 1e-12, 0, 0, 0},
      {"workpath-quad 8 nodes, tol 1e-9", AQ_MODEL_WORKPATH_QUAD, 0, 8, 1e-9, 0, 0, 0},
      {"ode rtol 1e-6", AQ_MODEL_ODE, 1e-6, 0, 0, 0, 0, 0},
      {"ode rtol 1e-8", AQ_MODEL_ODE, 1e-8, 0, 0, 0, 0, 0},
      {"ode rtol 1e-10", AQ_MODEL_ODE, 1e-10, 0, 0, 0, 0, 0},
      {"ode rtol 1e-12 (reference)", AQ_MODEL_ODE, 1e-12, 0, 0, 0, 0, 0},
      {"paper (as printed)", AQ_MODEL_PAPER, 0, 0, 0, 0, 0, 0},
  };
  enum { NS = sizeof set / sizeof set[0], REF = 9, ODE8 = 7, QUAD = 4 };
  static const struct {
    setting s;
    double scale;
  } conv[] = {
      {{"ode rtol 1e-13", AQ_MODEL_ODE, 1e-13, 0, 0, 0, 0, 0}, 1},
      {{"ode rtol 1e-14", AQ_MODEL_ODE, 1e-14, 0, 0, 0, 0, 0}, 1},
      {{"ode rtol 1e-13, exact path", AQ_MODEL_ODE, 1e-13, 0, 0, 0, 0, 1}, 1},
      {{"ode rtol 1e-12", AQ_MODEL_ODE, 1e-12, 0, 0, 0, 0, 0}, 1 + 4 * DBL_EPSILON},
      {{"ode rtol 1e-12", AQ_MODEL_ODE, 1e-12, 0, 0, 0, 0, 0}, 1 - 4 * DBL_EPSILON},
  };
  static double tlo[MAX_CASES], thi[MAX_CASES]; /* the reference's spread */
  static double tmed[NS][MAX_CASES], peak[NS][MAX_CASES], tc[NS][MAX_CASES];
  static int coll[NS][MAX_CASES];
  static size_t evals[NS][MAX_CASES], moving[NS][MAX_CASES], subs[NS][MAX_CASES],
      impacts[NS][MAX_CASES];
  for (size_t c = 0; c < nc; c++) {
    /* interleave the settings in each repetition: same machine state */
    double ts[NS][REPS];
    for (int rep = 0; rep < REPS; rep++)
      for (size_t k = 0; k < NS; k++) {
        const aq_steps *st = &cs[c].steps[cs[c].is_record ? merge_index(set[k].merge_g) : 0];
        aq_result r;
        if (!run(a, &set[k], st, 1.0, &r, &ts[k][rep]))
          return 1;
        peak[k][c] = r.peak_displacement_m;
        coll[k][c] = r.collapsed;
        tc[k][c] = r.collapse_time_s;
        evals[k][c] = r.evals;
        moving[k][c] = r.steps_moving;
        subs[k][c] = r.substeps;
        impacts[k][c] = r.impacts;
        aq_result_free(&r);
      }
    for (size_t k = 0; k < NS; k++)
      tmed[k][c] = aq_bench_median(ts[k], REPS);
    /* the reference's own convergence of the collapse time: tighter rtol,
     * and the input scaled by a few unit round-offs (once each, untimed) */
    tlo[c] = thi[c] = tc[REF][c];
    for (size_t k = 0; k < sizeof conv / sizeof conv[0] && coll[REF][c]; k++) {
      aq_result r;
      double sec;
      if (!run(a, &conv[k].s, &cs[c].steps[0], conv[k].scale, &r, &sec))
        return 1;
      tlo[c] = r.collapsed ? fmin(tlo[c], r.collapse_time_s) : -INFINITY;
      thi[c] = r.collapsed ? fmax(thi[c], r.collapse_time_s) : INFINITY;
      aq_result_free(&r);
    }
  }
  printf("Cases (%zu), reference = ode rtol 1e-12; COR 0.7; records scaled to "
         "PGA 2.5 and 5 lambda0 g:\n", nc);
  printf("  %-32s %6s %6s %5s %-9s %10s %9s %7s %9s %9s %9s %9s\n", "case", "steps",
         "moving", "imp", "ref", "ode12_ms", "wp_ms", "x_ode12", "err_peak",
         "err_tc_s", "tc_conv_s", "quad_ms");
  size_t cmin = 0;
  for (size_t c = 0; c < nc; c++) {
    double ep = fabs(peak[0][c] / peak[REF][c] - 1);
    double et = coll[0][c] && coll[REF][c] ? fabs(tc[0][c] - tc[REF][c]) : 0;
    if (tmed[REF][c] / tmed[0][c] < tmed[REF][cmin] / tmed[0][cmin])
      cmin = c;
    printf("  %-32s %6zu %6zu %5zu %-9s %10.3f %9.3f %7.1f %9.2g %9.2g %9.2g %9.3f\n",
           cs[c].name, cs[c].steps[0].n, moving[REF][c], impacts[0][c],
           coll[REF][c] ? "collapses" : "survives", 1e3 * tmed[REF][c],
           1e3 * tmed[0][c], tmed[REF][c] / tmed[0][c], ep, et,
           coll[REF][c] ? thi[c] - tlo[c] : 0.0,
           1e3 * tmed[QUAD][c]);
  }
  double t8 = 0, t12 = 0;
  for (size_t c = 0; c < nc; c++) {
    t8 += tmed[ODE8][c];
    t12 += tmed[REF][c];
  }
  printf("\n%-40s %8s %7s %6s %7s %7s %8s %8s %10s %10s %4s %5s\n", "setting", "time_ms",
         "x_ode12", "x_ode8", "min_x12", "us/step", "substeps", "evals",
         "err_peak_x", "err_tc_s", "flag", "equal");
  for (size_t k = 0; k < NS; k++) {
    double tt = 0, ep = 0, et = 0, rmin = INFINITY;
    size_t ev = 0, mv = 0, sb = 0;
    int fd = 0, eq = 0;
    for (size_t c = 0; c < nc; c++) {
      tt += tmed[k][c];
      ev += evals[k][c];
      mv += moving[k][c];
      sb += subs[k][c];
      rmin = fmin(rmin, tmed[REF][c] / tmed[k][c]);
      ep = fmax(ep, fabs(peak[k][c] / peak[REF][c] - 1));
      if (coll[k][c] != coll[REF][c])
        fd++;
      else if (coll[k][c])
        et = fmax(et, fabs(tc[k][c] - tc[REF][c]));
      /* equal error: peak within EQ_REL, collapse time within the
       * reference's own spread widened by EQ_REL */
      double tw = EQ_REL * tc[REF][c];
      eq += coll[k][c] == coll[REF][c] &&
            fabs(peak[k][c] / peak[REF][c] - 1) <= EQ_REL &&
            (!coll[k][c] || (tc[k][c] >= tlo[c] - tw && tc[k][c] <= thi[c] + tw));
    }
    printf("%-40s %8.3f %7.2f %6.2f %7.2f %7.3f %8zu %8zu %10.3g %10.3g %4d %2d/%-2zu\n",
           set[k].name, 1e3 * tt, t12 / tt, t8 / tt, rmin,
           mv ? 1e6 * tt / (double)mv : 0.0, sb, ev, ep, et, fd, eq, nc);
  }
  printf("(time_ms: sum over cases of the median of %d runs; x_ode12, x_ode8: "
         "speed relative to ode at 1e-12 and 1e-8; min_x12: smallest per-case "
         "ratio to ode 1e-12; us/step: time per moving step; substeps: "
         "integrator steps (Taylor sub-steps, panels; 0 for the ode, whose "
         "rk8pd steps GSL keeps); evals: path evaluations and table pieces "
         "fetched; err_peak_x: largest relative error of the peak "
         "displacement; err_tc_s: largest collapse-time error where both "
         "collapse; flag: cases whose collapse flag differs; tc_conv_s: the "
         "reference's own spread of the collapse time (max - min over ode at "
         "rtol 1e-12, 1e-13 and 1e-14, on the exact path at 1e-13, and with the "
         "record scaled by 1 +- 4 unit round-offs); equal: cases within the "
         "reference's error, peak within %.0e relative and collapse time "
         "within the spread widened by %.0e relative)\n",
         REPS, EQ_REL, EQ_REL);
  printf("default: smallest per-case ratio to ode 1e-12: %.1f (%s)\n",
         tmed[REF][cmin] / tmed[0][cmin], cs[cmin].name);
  for (size_t c = 0; c < nc; c++) {
    for (int k = 0; k < 3; k++)
      aq_steps_free(&cs[c].steps[k]);
  }
  aq_arch_free(a);
  return 0;
}
