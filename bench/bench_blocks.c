/* bench_blocks.c: the block model (src/blocks, docs/blocks.md): its speed,
 * the convergence of its step, and what it sees against the four-hinge
 * models.  Sections (all by default; name some to run only those):
 *
 *   speed  oppenheim (20 voussoirs, every joint free, friction 10) through
 *          each record of records/ (read and processed as the main job
 *          does, scaled to a PGA of 2 lambda0 g), at the default step: the
 *          median time of 3 runs, the steps taken, how many needed Siconos,
 *          and the cost per step per contact (time / (steps x 2 (n + 1)))
 *   conv   the hinge-controlled arch (control fixed) under 2 lambda0 for
 *          0.15 s: voussoir 0's peak rotation against the exact four-hinge
 *          equation of motion (the ode model, rtol 1e-12) as the step
 *          halves, with the ratio of successive errors (the scheme's order)
 *   dt     the step's convergence study: voussoir 0's peak rotation of the
 *          free arch on every shipped arch under 1.5 lambda0 for 0.3 s (in
 *          steps of 0.01 s, as a record's) and oppenheim under the first
 *          AT2 record of records/ at 2 lambda0,
 *          against a step of 1.25e-4 s; the largest step within 1 %
 *   free   the first half-cycle, free against fixed hinges: every shipped
 *          arch under 1.5 lambda0 for 0.3 s, the block model's peak
 *          rotation and its time against the four-hinge model's (workpath),
 *          the hinges that opened and when the mechanism changed
 *   energy e_n = 1, friction 10: oppenheim and thick, hinges fixed and
 *          free, free after a pulse of 1.5 lambda0 for 0.152 s, to 1 s:
 *          the largest drift of the energy (kinetic + potential, the
 *          ground still) from its value at the pulse's end, and of the
 *          energy less the work of friction, as the step halves, under the
 *          global impact law (the model's) and Newton's law per corner (for
 *          comparison); then, for the global law, where the balance goes:
 *          each step's error by kind of step (a late landing closed by the
 *          plastic law, an impact stage, the others), the projection's
 *          change of potential energy, the work at joints that stick
 *          throughout a step and the impact stages' own error; the free
 *          arch under the global law down to 1.5625e-5 s
 *   agree  (only when named; minutes) the verdicts of the block model
 *          against the four-hinge work path's on the AT2 records of a
 *          directory (the argument after agree; default records/): three
 *          shipped arches, each record scaled to a PGA of 1.5, 2 and 3
 *          lambda0 g, friction 10 and 0.6, hinges fixed (the file's) and
 *          free (the file with control = free and no reverse): how often
 *          both say collapse or both say it stands, and what the block
 *          model saw where they differ
 *   abutment  (only when named; minutes) the same for oppenheim at friction
 *          0.6 with the supports' faces running 0, 0.25, 1.25 and 5 m
 *          beyond the springings ([supports] abutment_m; the argument
 *          after it: the records' directory) */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/arch.h"
#include "arch/model.h"
#include "arch/stepper.h"
#include "bench.h"
#include "blocks/blocks.h"
#include "blocks/blocks_run.h"
#include "io/record.h"
#include "job/job.h"
#include "signal/signal.h"
#include "units.h"

static const char *const ARCHES[] = {
    "arches/oppenheim.cfg", "arches/thin.cfg",     "arches/thick.cfg",
    "arches/gothic.cfg",    "arches/catenary.cfg", "arches/segmental.cfg",
    "arches/bridge.cfg",    "arches/search.cfg",   "arches/vertical.cfg"};
enum { NARCH = sizeof ARCHES / sizeof ARCHES[0] };

static aq_arch *load(const char *path)
{
  aq_arch *a = NULL;
  aq_error e;
  if (aq_arch_load(path, &a, &e) != AQ_OK) {
    fprintf(stderr, "bench_blocks: %s: %s\n", path, e.message);
    return NULL;
  }
  return a;
}

/* A rectangular pulse a for T s, then nothing until end, in steps of
 * step_s (a record's sampling: 0.01 s; 1 ms for the histories). */
static int pulse_steps(double a, double T, double end, double step_s, aq_steps *s)
{
  size_t n = (size_t)llround(end / step_s), n1 = (size_t)llround(T / step_s);
  double *acc = malloc(n * sizeof *acc);
  if (!acc)
    return 0;
  for (size_t i = 0; i < n; i++)
    acc[i] = i < n1 ? a : 0;
  aq_error e;
  int ok = aq_steps_from_samples(acc, n, step_s, 0, 0, s, &e) == AQ_OK;
  free(acc);
  return ok;
}

static int pulse(double a, double T, double end, aq_steps *s)
{
  return pulse_steps(a, T, end, 1e-3, s);
}

/* The process's CPU time, s (the machine may be shared: wall times are
 * printed beside it). */
static double cpu_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* One run of the block model; 0 on failure. */
static int run_blocks(const aq_arch *A, aq_blocks_control c, double mu, double dt,
                      const aq_steps *s, aq_blocks_result *r, double *sec)
{
  aq_error e;
  aq_blocks *B = aq_blocks_alloc(A, &e);
  if (!B)
    return 0;
  int ok = aq_blocks_set_friction(B, mu, &e) == AQ_OK && aq_blocks_set_dt(B, dt, &e) == AQ_OK &&
           (c == AQ_BLOCKS_FREE || aq_blocks_set_control(B, c, &e) == AQ_OK);
  double t0 = aq_bench_now_s();
  ok = ok && aq_blocks_run(B, s, r, &e) == AQ_OK;
  if (sec)
    *sec = aq_bench_now_s() - t0;
  if (!ok)
    fprintf(stderr, "bench_blocks: run: %s\n", e.message);
  aq_blocks_free(B);
  return ok;
}

/* The records of records/, sorted. */
static size_t record_names(char **names, size_t cap)
{
  DIR *dir = opendir("records");
  size_t n = 0;
  struct dirent *de;
  while (dir && (de = readdir(dir)) && n < cap) {
    if (de->d_name[0] == '.' || strstr(de->d_name, ".md"))
      continue;
    names[n++] = strdup(de->d_name);
  }
  if (dir)
    closedir(dir);
  for (size_t i = 0; i < n; i++)
    for (size_t j = i + 1; j < n; j++)
      if (strcmp(names[i], names[j]) > 0) {
        char *t = names[i];
        names[i] = names[j];
        names[j] = t;
      }
  return n;
}

/* The record at path as the main job prepares it, scaled to a PGA of
 * ratio lambda0 g of path p. */
static int record_steps(const char *path, const aq_path *p, double ratio, aq_steps *s)
{
  aq_error e;
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_signal_opts so;
  aq_signal_opts_default(&so);
  aq_signal_ws *ws = aq_signal_ws_alloc();
  aq_subject subj;
  aq_subject_src src = {{path, NULL, NULL}, {NAN, NAN}, path};
  aq_subject_opts o = {.read = &ro, .proc = &so};
  int ok = aq_subject_prepare(&subj, &src, &o, ws, &e) == AQ_OK && subj.pga_g > 0;
  if (ok) {
    aq_scale_rule rule = {NULL, 0, ratio * p->lambda0 * p->g_mps2 / AQ_G0_MPS2, 0};
    double scale = aq_scale_factor(&rule, 0, subj.pga_g), peak;
    ok = aq_subject_steps(&subj, 0, scale, scale, 0, s, &peak, &e) == AQ_OK;
  }
  if (!ok)
    fprintf(stderr, "bench_blocks: skip %s: %s\n", path, e.message);
  aq_subject_free(&subj);
  aq_signal_ws_free(ws);
  return ok;
}

static void speed(void)
{
  printf("== speed: oppenheim, every joint free, friction 10, records at a PGA of 2 lambda0 g,"
         " step %g s (median of 3)\n",
         AQ_BLOCKS_DT_DEFAULT_S);
  aq_arch *A = load("arches/oppenheim.cfg");
  if (!A)
    return;
  const aq_path *p = aq_arch_path(A, 0);
  char *names[64];
  size_t nn = record_names(names, 64);
  printf("%-36s %8s %8s %7s %7s %8s %10s %9s %12s\n", "record", "length_s", "moving_s",
         "steps", "siconos", "lps", "median_s", "cpu_s", "us/step/ctc");
  double total = 0, ctotal = 0;
  for (size_t i = 0; i < nn; i++) {
    char path[512];
    snprintf(path, sizeof path, "records/%s", names[i]);
    aq_steps s;
    if (!record_steps(path, p, 2.0, &s))
      continue;
    double t[3], c[3];
    aq_blocks_result r;
    int ok = 1;
    for (int k = 0; k < 3 && ok; k++) {
      double c0 = cpu_s();
      ok = run_blocks(A, AQ_BLOCKS_FREE, 10, AQ_BLOCKS_DT_DEFAULT_S, &s, &r, &t[k]);
      c[k] = cpu_s() - c0;
      if (ok && k < 2)
        aq_blocks_result_free(&r);
    }
    if (ok) {
      double med = aq_bench_median(t, 3), cmed = aq_bench_median(c, 3), len = 0;
      for (size_t k = 0; k < s.n; k++)
        len += aq_steps_t(&s, k) >= 0 ? aq_steps_dt(&s, k) : 0;
      size_t nc = 2 * (aq_arch_geom(A)->p.voussoirs + 1);
      printf("%-36.36s %8.1f %8.1f %7zu %7zu %8zu %10.3f %9.3f %12.3f\n", names[i], len,
             (double)r.steps * AQ_BLOCKS_DT_DEFAULT_S, r.steps, r.steps_siconos, r.statics, med,
             cmed, r.steps ? 1e6 * cmed / ((double)r.steps * (double)nc) : 0);
      total += med;
      ctotal += cmed;
      aq_blocks_result_free(&r);
    }
    aq_steps_free(&s);
  }
  printf("total median %.3f s wall, %.3f s CPU\n", total, ctotal);
  for (size_t i = 0; i < nn; i++)
    free(names[i]);
  aq_arch_free(A);
}

static void conv(void)
{
  /* sampled at the largest step studied, 8 ms (19 samples, 0.152 s), so
   * that each step is taken as asked: a record's step is cut into steps
   * of at most --blocks-dt, never joined */
  printf("== conv: control fixed, friction 10, 2 lambda0 for 0.152 s (sampled at 8 ms): "
         "voussoir 0's peak rotation against the ode (rtol 1e-12)\n");
  static const char *const two[] = {"arches/oppenheim.cfg", "arches/thick.cfg",
                                    "arches/gothic.cfg"};
  printf("%-22s %10s %16s %12s %8s\n", "arch", "dt_s", "peak_rad", "rel_err", "ratio");
  for (size_t k = 0; k < 3; k++) {
    aq_arch *A = load(two[k]);
    if (!A)
      continue;
    const aq_path *p = aq_arch_path(A, 0);
    aq_steps s;
    aq_error e;
    if (!pulse_steps(p->act_sign * 2.0 * p->lambda0 * p->g_mps2, 0.152, 1.504, 8e-3, &s)) {
      aq_arch_free(A);
      continue;
    }
    aq_stepper *st = aq_stepper_alloc(p, aq_arch_path(A, 1), AQ_MODEL_ODE, &e);
    aq_stepper_set_ode_rtol(st, 1e-12);
    aq_result ro;
    if (st && aq_stepper_run(st, &s, &ro, &e) == AQ_OK) {
      printf("%-22s %10s %16.10f\n", two[k], "ode", ro.peak_rotation_rad);
      double prev = NAN;
      for (int i = 0; i < 7; i++) {
        double dt = 8e-3 / (1 << i);
        aq_blocks_result r;
        if (!run_blocks(A, AQ_BLOCKS_FIXED, 10, dt, &s, &r, NULL))
          continue;
        double err = r.r.peak_rotation_rad / ro.peak_rotation_rad - 1;
        printf("%-22s %10.3g %16.10f %12.3e %8.3f\n", two[k], dt, r.r.peak_rotation_rad, err,
               prev / err);
        prev = err;
        aq_blocks_result_free(&r);
      }
      aq_result_free(&ro);
    }
    aq_stepper_free(st);
    aq_steps_free(&s);
    aq_arch_free(A);
  }
}

static void dt_study(void)
{
  printf("== dt: voussoir 0's peak rotation, every joint free, friction 10, against dt = "
         "1.25e-4 s\n");
  static const double dts[] = {1e-2, 8e-3, 5e-3, 4e-3, 2e-3, 1e-3, 5e-4};
  enum { ND = sizeof dts / sizeof dts[0] };
  double worst[ND];
  for (int i = 0; i < ND; i++)
    worst[i] = 0;
  printf("%-34s", "case");
  for (int i = 0; i < ND; i++)
    printf(" %9.2g", dts[i]);
  printf("\n");
  char *names[64];
  size_t nn = record_names(names, 64);
  for (size_t k = 0; k <= NARCH; k++) {
    aq_arch *A = load(k < NARCH ? ARCHES[k] : "arches/oppenheim.cfg");
    if (!A)
      continue;
    const aq_path *p = aq_arch_path(A, 0);
    aq_steps s;
    char label[64];
    int ok;
    if (k < NARCH) {
      ok = pulse_steps(p->act_sign * 1.5 * p->lambda0 * p->g_mps2, 0.3, 2.0, 0.01, &s);
      snprintf(label, sizeof label, "%s 1.5 lambda0 0.3 s", ARCHES[k] + 7);
    } else {
      size_t r = 0;
      while (r < nn && !strstr(names[r], ".AT2"))
        r++;
      char path[512];
      snprintf(path, sizeof path, "records/%s", r < nn ? names[r] : "");
      ok = r < nn && record_steps(path, p, 2.0, &s);
      snprintf(label, sizeof label, "oppenheim %.16s x2", r < nn ? names[r] : "");
    }
    if (!ok) {
      aq_arch_free(A);
      continue;
    }
    aq_blocks_result r;
    if (run_blocks(A, AQ_BLOCKS_FREE, 10, 1.25e-4, &s, &r, NULL)) {
      double ref = r.r.peak_rotation_rad;
      aq_blocks_result_free(&r);
      printf("%-34.34s", label);
      for (int i = 0; i < ND; i++) {
        if (!run_blocks(A, AQ_BLOCKS_FREE, 10, dts[i], &s, &r, NULL)) {
          printf(" %9s", "fail");
          continue;
        }
        double err = fabs(r.r.peak_rotation_rad / ref - 1);
        worst[i] = fmax(worst[i], err);
        printf(" %9.2e", err);
        aq_blocks_result_free(&r);
      }
      printf("\n");
    }
    aq_steps_free(&s);
    aq_arch_free(A);
  }
  printf("%-34s", "largest");
  for (int i = 0; i < ND; i++)
    printf(" %9.2e", worst[i]);
  printf("\n");
  for (size_t i = 0; i < nn; i++)
    free(names[i]);
}

static void free_half_cycle(void)
{
  printf("== free: 1.5 lambda0 for 0.3 s, friction 10, step %g s: voussoir 0's peak rotation, "
         "the block model (every joint free) against the four-hinge work path\n",
         AQ_BLOCKS_DT_DEFAULT_S);
  printf("%-12s %12s %9s %12s %9s %9s %9s  %s\n", "arch", "4hinge_rad", "at_s", "blocks_rad",
         "at_s", "ratio", "changed_s", "hinges (first opening, s)");
  for (size_t k = 0; k < NARCH; k++) {
    aq_arch *A = load(ARCHES[k]);
    if (!A)
      continue;
    const aq_path *p = aq_arch_path(A, 0);
    aq_steps s;
    if (!pulse(p->act_sign * 1.5 * p->lambda0 * p->g_mps2, 0.3, 3.0, &s)) {
      aq_arch_free(A);
      continue;
    }
    aq_error e;
    aq_stepper *st = aq_stepper_alloc(p, aq_arch_path(A, 1), AQ_MODEL_WORKPATH, &e);
    aq_stepper_set_history(st, 1);
    aq_result ro;
    aq_blocks_result r;
    aq_blocks *B = aq_blocks_alloc(A, &e);
    if (st && B && aq_stepper_run(st, &s, &ro, &e) == AQ_OK &&
        aq_blocks_set_friction(B, 10, &e) == AQ_OK) {
      aq_blocks_set_history(B, 1);
      if (aq_blocks_run(B, &s, &r, &e) == AQ_OK) {
        double t4 = NAN, tb = NAN;
        for (size_t i = 0; i < ro.history.n; i++)
          if (fabs(ro.history.rotation_rad[i]) >= ro.peak_rotation_rad * (1 - 1e-12)) {
            t4 = ro.history.time_s[i];
            break;
          }
        for (size_t i = 0; i < r.r.history.n; i++)
          if (fabs(r.r.history.rotation_rad[i]) >= r.r.peak_rotation_rad * (1 - 1e-12)) {
            tb = r.r.history.time_s[i];
            break;
          }
        char hb[512], tbuf[512];
        aq_blocks_hinges_text(&r, hb, sizeof hb, tbuf, sizeof tbuf);
        printf("%-12.12s %12.6g %9.3f %12.6g %9.3f %9.4f %9.3f  %s (%s)%s\n", ARCHES[k] + 7,
               ro.peak_rotation_rad, t4, r.r.peak_rotation_rad, tb,
               r.r.peak_rotation_rad / ro.peak_rotation_rad, r.mechanism_changed_s, hb, tbuf,
               r.r.collapsed || ro.collapsed ? " [collapse]" : "");
        aq_blocks_result_free(&r);
      }
      aq_result_free(&ro);
    }
    aq_blocks_free(B);
    aq_stepper_free(st);
    aq_steps_free(&s);
    aq_arch_free(A);
  }
}


/* The arch at path with its [hinges] control made free (a reverse line
 * dropped, control = free added), friction mu. */
static aq_arch *load_free(const char *path, double mu)
{
  size_t n = 0;
  FILE *f = fopen(path, "rb");
  if (!f)
    return NULL;
  char *text = malloc(1 << 20), *out = malloc((1 << 20) + 64);
  if (text && out)
    n = fread(text, 1, (1 << 20) - 1, f);
  fclose(f);
  aq_arch *a = NULL;
  if (text && out) {
    text[n] = '\0';
    size_t k = 0;
    int hinges = 0;
    for (char *line = text; *line;) {
      char *end = strchr(line, '\n');
      size_t len = end ? (size_t)(end - line + 1) : strlen(line);
      if (!strncmp(line, "reverse", 7)) {
        line += len;
        continue;
      }
      memcpy(out + k, line, len);
      k += len;
      if (!strncmp(line, "[hinges]", 8)) {
        k += (size_t)sprintf(out + k, "control = free\n");
        hinges = 1;
      }
      line += len;
    }
    if (!hinges)
      k += (size_t)sprintf(out + k, "[hinges]\ncontrol = free\n");
    aq_arch_options o = {.friction = mu};
    aq_error e;
    if (aq_arch_load_string_opts(out, k, path, &o, &a, &e) != AQ_OK)
      fprintf(stderr, "bench_blocks: %s free: %s\n", path, e.message);
  }
  free(text);
  free(out);
  return a;
}

/* The bodies' kinetic + potential energy (frame of the ground), J. */
static double body_energy_j(const aq_bodies *s, const double *q, const double *v)
{
  double e = 0;
  for (size_t b = 0; b < s->nb; b++) {
    const double *w = v + 3 * b;
    e += 0.5 * s->body[b].mass_kg * (w[0] * w[0] + w[1] * w[1]) +
         0.5 * s->body[b].inertia_kgm2 * w[2] * w[2] +
         s->body[b].mass_kg * s->g_mps2 * (q[3 * b + 1] - s->body[b].c0.y);
  }
  return e;
}

static void energy(void)
{
  static const char *const arches[] = {"arches/oppenheim.cfg", "arches/thick.cfg"};
  static const char *const laws[] = {"global", "newton"};
  const double T = 0.152, end = 1.0;
  printf("== energy: e_n = 1, friction 10, 1.5 lambda0 for %g s, then free to %g s: the "
         "largest |E - E0| / E0 and |E - D - E0| / E0 after the pulse (E kinetic + "
         "potential, E0 at the pulse's end, D the work of friction), the ratio of "
         "successive balances, D / E0, steps with an impact, impact stages\n",
         T, end);
  printf("%-10s %-6s %-6s %10s %11s %11s %7s %10s %8s %7s %7s\n", "arch", "hinges", "law",
         "dt_s", "E_drift", "balance", "ratio", "D/E0", "impacts", "stages", "cpu_s");
  char why[40][176];
  size_t nwhy = 0;
  for (size_t a = 0; a < 2; a++)
    for (int mode = 0; mode < 2; mode++)
      for (int law = 0; law < 2; law++) {
        aq_arch *A = mode ? load_free(arches[a], 10) : load(arches[a]);
        if (!A)
          continue;
        const aq_path *p = aq_arch_path(A, 0);
        double acc = p->act_sign * 1.5 * p->lambda0 * p->g_mps2, prev = NAN;
        /* the free arch under the global law down to 1/256 of the first
         * step (its order over the whole range) */
        for (int i = 0; i < (mode && !law ? 9 : 6); i++) {
          double h = 4e-3 / (1 << i);
          aq_error e;
          aq_blocks *B = aq_blocks_alloc(A, &e);
          if (!B || (!mode && aq_blocks_set_control(B, AQ_BLOCKS_FIXED, &e) != AQ_OK)) {
            aq_blocks_free(B);
            continue;
          }
          aq_moreau *m = aq_blocks_moreau(B);
          const aq_bodies *s = aq_blocks_bodies(B);
          aq_moreau_set_law(m, law ? AQ_IMPACT_NEWTON : AQ_IMPACT_GLOBAL);
          aq_moreau_set(m, 10, 1, 0.5, 1, 1);
          aq_moreau_reset(m);
          size_t n = (size_t)llround(end / h), n1 = (size_t)llround(T / h), imp = 0, st = 0;
          double gx[2] = {0, 0}, e0 = NAN, d = 0, drift = 0, bal = 0, c0 = cpu_s();
          double eprev = 0, en_last = NAN, part[3] = {0, 0, 0}, proj = 0, stick = 0, imp_err = 0;
          size_t nkind[3] = {0, 0, 0};
          int ok = 1;
          for (size_t j = 0; j < n && ok; j++) {
            aq_step_info info;
            ok = aq_moreau_step(m, h, j < n1 ? acc : 0, 0, gx, &info, &e) == AQ_OK;
            double en = body_energy_j(s, aq_moreau_q(m), aq_moreau_v(m));
            if (j + 1 == n1)
              e0 = en;
            if (!ok || j + 1 <= n1) {
              eprev = en;
              continue;
            }
            imp += info.impact != 0;
            st += (size_t)info.stage;
            d += info.friction_j;
            /* the balance's parts: the steps' errors by kind */
            double de = en - eprev - info.friction_j;
            int kind = info.late_plastic ? 0 : info.stage > 0 ? 1 : 2;
            part[kind] += de;
            nkind[kind]++;
            proj += info.proj_pe_j;
            stick += info.stick_j;
            imp_err += info.stage_err_j;
            drift = fmax(drift, fabs(en / e0 - 1));
            bal = fmax(bal, fabs((en - d) / e0 - 1));
            eprev = en_last = en;
          }
          if (!law && ok && nwhy < sizeof why / sizeof why[0])
            snprintf(why[nwhy++], sizeof why[0],
                     "%-10.10s %-6s %10.4g %11.3e %6zu %11.3e %6zu %11.3e %6zu %11.3e %11.3e "
                     "%11.3e %11.3e\n",
                     arches[a] + 7, mode ? "free" : "fixed", h, (en_last - d) / e0 - 1,
                     nkind[0], part[0] / e0, nkind[1], part[1] / e0, nkind[2],
                     part[2] / e0, proj / e0, stick / e0, imp_err / e0);
          if (!ok)
            printf("%-10.10s %-6s %-6s %10.4g failed: %s\n", arches[a] + 7,
                   mode ? "free" : "fixed", laws[law], h, e.message);
          else
            printf("%-10.10s %-6s %-6s %10.4g %11.3e %11.3e %7.3f %10.3e %8zu %7zu %7.2f\n",
                   arches[a] + 7, mode ? "free" : "fixed", laws[law], h, drift, bal,
                   prev / bal, d / e0, imp, st, cpu_s() - c0);
          fflush(stdout);
          prev = ok ? bal : NAN;
          aq_blocks_free(B);
        }
        aq_arch_free(A);
      }
  printf("== energy: the global law's balance E - D - E0 at the end, over E0, and its "
         "parts: the error of the steps where a late landing took the plastic law, of "
         "the steps with an impact stage, of the others (count, sum), and three of their "
         "terms: the projection's change of potential energy, the work at joints that "
         "stick throughout a step (the scheme's error), the impact stages' change of "
         "kinetic energy less their friction's work (0 by the law)\n");
  printf("%-10s %-6s %10s %11s %6s %11s %6s %11s %6s %11s %11s %11s %11s\n", "arch",
         "hinges", "dt_s", "balance", "late", "late_err", "stage", "stage_err", "other",
         "other_err", "proj_pe", "stick", "impact");
  for (size_t i = 0; i < nwhy; i++)
    fputs(why[i], stdout);
}

/* The AT2 records of dir, sorted (names[0..*nn), strdup'd; at most 64). */
static size_t agree_records(const char *dir, char **names)
{
  DIR *d = opendir(dir);
  size_t nn = 0;
  struct dirent *de;
  while (d && (de = readdir(d)) && nn < 64) {
    size_t l = strlen(de->d_name);
    if (l > 4 && (!strcmp(de->d_name + l - 4, ".AT2") || !strcmp(de->d_name + l - 4, ".at2")))
      names[nn++] = strdup(de->d_name);
  }
  if (d)
    closedir(d);
  for (size_t i = 0; i < nn; i++)
    for (size_t j = i + 1; j < nn; j++)
      if (strcmp(names[i], names[j]) > 0) {
        char *t = names[i];
        names[i] = names[j];
        names[j] = t;
      }
  return nn;
}

static void agree_header(void)
{
  printf("(agree: the arch's own impact rule; agree_m: the momentum rule)\n");
  printf("%-12s %-6s %5s %6s %5s %6s %6s %6s %6s %8s %8s %6s %10s\n", "arch", "hinges", "mu",
         "abut_m", "runs", "agree", "both_c", "4h_only", "bk_only", "agree_m", "failed",
         "loose", "blocks_s");
}

/* One row of agree: arch (its file, hinges fixed or free: mode), friction
 * mu, the supports' faces abut m beyond the springings, over the records. */
static void agree_row(const char *dir, char *const *names, size_t nn, const char *arch,
                      int mode, double mu, double abut)
{
  static const double ratios[] = {1.5, 2.0, 3.0};
  aq_arch_options o = {.friction = mu};
  aq_arch *A = NULL;
  aq_error e;
  if (mode == 0) {
    if (aq_arch_load_opts(arch, &o, &A, &e) != AQ_OK)
      A = NULL;
  } else {
    A = load_free(arch, mu);
  }
  if (!A)
    return;
  const aq_path *p = aq_arch_path(A, 0);
  size_t runs = 0, same = 0, both = 0, only4 = 0, onlyb = 0, failed = 0, agreem = 0, loose = 0;
  double secs = 0;
  char diffs[8192];
  size_t dk = 0;
  diffs[0] = 0;
  for (size_t r = 0; r < nn; r++)
    for (size_t k = 0; k < 3; k++) {
      char path[1024];
      snprintf(path, sizeof path, "%s/%s", dir, names[r]);
      aq_steps s;
      if (!record_steps(path, p, ratios[k], &s))
        continue;
      aq_stepper *st = aq_job_stepper(A, AQ_MODEL_WORKPATH, NAN, 0, 0, &e);
      aq_result ro, rm;
      aq_blocks_result rb;
      double sec = 0;
      int ok4 = st && aq_stepper_run(st, &s, &ro, &e) == AQ_OK;
      /* the momentum rule: Housner's, which Newton's e_n = 0 gives a
       * rocking mechanism */
      int okm = 0;
      if (ok4) {
        aq_stepper_set_impact(st, 1);
        okm = aq_stepper_run(st, &s, &rm, &e) == AQ_OK;
      }
      aq_blocks *B = aq_blocks_alloc(A, &e);
      int okb = B && aq_blocks_set_friction(B, mu, &e) == AQ_OK &&
                (mode || aq_blocks_set_control(B, AQ_BLOCKS_FIXED, &e) == AQ_OK) &&
                aq_blocks_set_abutment(B, abut, &e) == AQ_OK;
      double t0 = aq_bench_now_s();
      okb = okb && aq_blocks_run(B, &s, &rb, &e) == AQ_OK;
      sec = aq_bench_now_s() - t0;
      runs++;
      secs += sec;
      if (!ok4 || !okb || !okm) {
        failed++;
        if (!okb)
          fprintf(stderr, "bench_blocks: %s x%.1f: %s\n", names[r], ratios[k], e.message);
      } else {
        loose += rb.steps_loose;
        agreem += rm.collapsed == rb.r.collapsed;
        int c4 = ro.collapsed, cb = rb.r.collapsed;
        same += c4 == cb;
        both += c4 && cb;
        only4 += c4 && !cb;
        onlyb += cb && !c4;
        if (c4 != cb && dk + 600 < sizeof diffs) {
          char hb[256];
          aq_blocks_hinges_text(&rb, hb, sizeof hb, NULL, 0);
          dk += (size_t)snprintf(
              diffs + dk, sizeof diffs - dk,
              "    %s x%.1f: 4-hinge %s (peak %.4g rad; momentum rule: %s), blocks %s at "
              "%.3g s (peak %.4g rad, slip %.3g m, changed %.3g s, hinges %s)\n",
              names[r], ratios[k], c4 ? "collapses" : "stands", ro.peak_rotation_rad,
              okm && rm.collapsed ? "collapses" : "stands", cb ? "collapses" : "stands",
              rb.r.collapse_time_s, rb.r.peak_rotation_rad, rb.max_slip_m,
              rb.mechanism_changed_s, hb);
        }
      }
      if (ok4)
        aq_result_free(&ro);
      if (okm)
        aq_result_free(&rm);
      if (okb)
        aq_blocks_result_free(&rb);
      aq_blocks_free(B);
      aq_stepper_free(st);
      aq_steps_free(&s);
    }
  printf("%-12.12s %-6s %5g %6g %5zu %6zu %6zu %6zu %6zu %8zu %8zu %6zu %10.1f\n%s",
         arch + 7, mode ? "free" : "fixed", mu, abut, runs, same, both, only4, onlyb, agreem,
         failed, loose, secs, diffs);
  fflush(stdout);
  aq_arch_free(A);
}

static void agree(const char *dir)
{
  static const char *const arches[] = {"arches/oppenheim.cfg", "arches/gothic.cfg",
                                       "arches/thick.cfg"};
  static const double mus[] = {10, 0.6};
  printf("== agree: the AT2 records of %s at 1.5, 2 and 3 lambda0 g, step %g s: collapse "
         "verdicts, four-hinge work path against the block model\n",
         dir, AQ_BLOCKS_DT_DEFAULT_S);
  char *names[64];
  size_t nn = agree_records(dir, names);
  agree_header();
  for (size_t a = 0; a < 3; a++)
    for (int mode = 0; mode < 2; mode++)
      for (int m = 0; m < 2; m++)
        agree_row(dir, names, nn, arches[a], mode, mus[m], 0);
  for (size_t i = 0; i < nn; i++)
    free(names[i]);
}

/* The abutment's extent: oppenheim at friction 0.6, hinges fixed and free,
 * with the supports' faces as drawn (0) and running on beyond the
 * springings by 0.25, 1.25 (the ring's thickness) and 5 m. */
static void abutment_study(const char *dir)
{
  static const double abut[] = {0, 0.25, 1.25, 5};
  printf("== abutment: the AT2 records of %s at 1.5, 2 and 3 lambda0 g, step %g s: "
         "oppenheim, friction 0.6, the supports' faces beyond the springings\n",
         dir, AQ_BLOCKS_DT_DEFAULT_S);
  char *names[64];
  size_t nn = agree_records(dir, names);
  agree_header();
  for (int mode = 0; mode < 2; mode++)
    for (size_t i = 0; i < sizeof abut / sizeof abut[0]; i++)
      agree_row(dir, names, nn, "arches/oppenheim.cfg", mode, 0.6, abut[i]);
  for (size_t i = 0; i < nn; i++)
    free(names[i]);
}

int main(int argc, char **argv)
{
  gsl_set_error_handler_off();
  int all = argc < 2;
  for (int i = 1; i < argc; i++)
    if (!strcmp(argv[i], "agree"))
      agree(i + 1 < argc ? argv[i + 1] : "records");
    else if (!strcmp(argv[i], "abutment"))
      abutment_study(i + 1 < argc ? argv[i + 1] : "records");
  for (int pass = 0; pass < 5; pass++) {
    static const char *const names[] = {"speed", "conv", "dt", "free", "energy"};
    int want = all;
    for (int i = 1; i < argc; i++)
      want |= !strcmp(argv[i], names[pass]);
    if (!want)
      continue;
    if (pass == 0)
      speed();
    else if (pass == 1)
      conv();
    else if (pass == 2)
      dt_study();
    else if (pass == 3)
      free_half_cycle();
    else
      energy();
  }
  return 0;
}
