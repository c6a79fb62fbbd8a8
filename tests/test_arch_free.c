/* test_arch_free.c: free hinges in motion, and the polarity a verdict
 * needs.  A mirror-symmetric free arch answers a record and the negated
 * record alike (the mirror image of one motion); the work path follows the
 * ode when the arch rocks from one direction's set onto the other's; the
 * momentum rule between two different sets against the four-bar's velocity
 * fields computed here; and which arches the main job and capacity run one
 * way only (docs/arch-model.md, "Polarity"). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/model.h"
#include "arch/stepper.h"
#include "check.h"
#include "test_dyn_steps.h"

/* The shipped free arches: each its own mirror image. */
static const char *const free_arches[] = {"search", "gothic", "bridge", "catenary", "vertical"};
enum { NFREE = sizeof free_arches / sizeof free_arches[0] };

static aq_arch *load(const char *path)
{
  aq_arch *a = NULL;
  aq_error e;
  aq_check(aq_arch_load(path, &a, &e) == AQ_OK, "%s loads: %s", path, e.message);
  return a;
}

/* The column of a TSV header named name, -1 if none. */
static int column(const char *tsv, const char *name)
{
  size_t len = strlen(name);
  int k = 0;
  for (const char *p = tsv; *p && *p != '\n'; k++) {
    size_t n = strcspn(p, "\t\n");
    if (n == len && strncmp(p, name, len) == 0)
      return k;
    p += n;
    if (*p == '\t')
      p++;
  }
  return -1;
}

static double num(const char *tsv, int row, const char *name)
{
  char buf[64];
  aq_test_tsv_field(tsv, row, column(tsv, name), buf, sizeof buf);
  return strtod(buf, NULL);
}

static const char *str(const char *tsv, int row, const char *name, char *buf, size_t n)
{
  return aq_test_tsv_field(tsv, row, column(tsv, name), buf, n);
}

/* ---- the mirror: a record and its negation -------------------------------- */

/* Four records of the shared set (the runs whose two polarities differed
 * most when all twelve were measured) at 1.2 and 2.5 lambda0 g, with a
 * friction of 0.7 (vertical needs 0.677 at rest: below it the arch is
 * refused), both polarities, on each shipped free arch.  What is
 * independent of the coordinate each set measures its rotation in must be
 * alike: the verdict, status and impacts exactly; the energies to 5e-12 of
 * the energy put in (each set's motion follows its own work-path tables,
 * built to 4.2e-12 at worst: mechanism's table_err; measured 1.05e-12 after
 * 32 impacts); the peak displacement to 5e-12; the times to 1e-9 s
 * (measured 2.6e-13 s); the demand to 1e-7 (each set's own demand tables,
 * built to 1e-8 of the largest normal force; measured 3.4e-8) at the
 * mirror joint n - j.  The peak rotation and its ratio to q_c are not
 * among them: a set's rotation is that of its first body from the left,
 * which the mirror makes another body. */
AQ_TEST(arch_free_mirror_answers_the_negated_record_alike)
{
  static const char *const recs =
      "tests/data/records/CHY028-N.AT2 tests/data/records/RSN4013_SANSIMEO_36258021.AT2 "
      "tests/data/records/RSN763_LOMAP_GIL337.AT2 tests/data/records/IELC180.AT2";
  static const char *const k[2] = {"1.2", "2.5"};
  static char out[1 << 17];
  char err[4096], cmd[2048];
  size_t pairs = 0, collapses = 0, marked = 0;
  for (int s = 0; s < 2; s++) {
    size_t len = (size_t)snprintf(cmd, sizeof cmd, "%s --scale-to-lambda0 %s --friction 0.7 "
                                                   "--polarity both -j 2",
                                  recs, k[s]);
    for (size_t a = 0; a < NFREE; a++)
      len += (size_t)snprintf(cmd + len, sizeof cmd - len, " --arch arches/%s.cfg",
                              free_arches[a]);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    size_t rows = aq_test_count_lines(out) - 1;
    if (!aq_check(rc == 0 && rows == 4 * NFREE * 2, "%s lambda0: exit %d, %zu rows: %s", k[s],
                  rc, rows, err))
      continue;
    for (int r = 1; r < (int)rows; r += 2) {
      char an[64], rec[300], p0[16], p1[16], s0[64], s1[64];
      str(out, r, "arch", an, sizeof an);
      str(out, r, "record", rec, sizeof rec);
      str(out, r, "polarity", p0, sizeof p0);
      str(out, r + 1, "polarity", p1, sizeof p1);
      str(out, r, "status", s0, sizeof s0);
      str(out, r + 1, "status", s1, sizeof s1);
      aq_check(!strcmp(p0, "normal") && !strcmp(p1, "reversed"), "rows %d, %d: both ways", r,
               r + 1);
      const char *b = strrchr(rec, '/');
      b = b ? b + 1 : rec;
      aq_check(!strcmp(s0, s1), "%s %s x%s: status %s, reversed %s", an, b, k[s], s0, s1);
      static const char *const same[] = {"collapsed", "impacts"};
      for (int c = 0; c < 2; c++)
        aq_check(num(out, r, same[c]) == num(out, r + 1, same[c]), "%s %s x%s: %s %g and %g", an,
                 b, k[s], same[c], num(out, r, same[c]), num(out, r + 1, same[c]));
      double ein = num(out, r, "energy_in_j");
      static const char *const energies[] = {"max_kinetic_energy_j", "energy_in_j",
                                             "energy_dissipated_j"};
      for (int c = 0; c < 3; c++)
        aq_check_abs(num(out, r + 1, energies[c]), num(out, r, energies[c]), 5e-12 * ein,
                     "%s %s x%s: %s", an, b, k[s], energies[c]);
      aq_check_rel(num(out, r + 1, "peak_displacement_m"), num(out, r, "peak_displacement_m"),
                   5e-12, "%s %s x%s: peak displacement", an, b, k[s]);
      static const char *const times[] = {"collapse_time_s", "thrust_ecc_time_s",
                                          "slide_time_s"};
      for (int c = 0; c < 3; c++) {
        double t0 = num(out, r, times[c]), t1 = num(out, r + 1, times[c]);
        aq_check((isnan(t0) && isnan(t1)) || fabs(t0 - t1) <= 1e-9,
                 "%s %s x%s: %s %.17g and %.17g", an, b, k[s], times[c], t0, t1);
      }
      double m0 = num(out, r, "mu_demand"), m1 = num(out, r + 1, "mu_demand");
      if (isinf(m0) || isinf(m1)) /* a joint pulled apart: which comes first is a tie */
        aq_check(m0 == m1, "%s %s x%s: mu_demand %g and %g", an, b, k[s], m0, m1);
      else {
        aq_check_rel(m1, m0, 1e-7, "%s %s x%s: mu_demand", an, b, k[s]);
        aq_arch *A = NULL;
        char path[128];
        snprintf(path, sizeof path, "arches/%s.cfg", an);
        aq_error e;
        if (aq_arch_load(path, &A, &e) == AQ_OK) {
          double n = (double)aq_arch_geom(A)->p.voussoirs;
          aq_check(num(out, r + 1, "mu_demand_joint") == n - num(out, r, "mu_demand_joint"),
                   "%s %s x%s: at joint %g, reversed at %g (n = %g)", an, b, k[s],
                   num(out, r, "mu_demand_joint"), num(out, r + 1, "mu_demand_joint"), n);
          aq_arch_free(A);
        }
      }
      double e0 = num(out, r, "thrust_ecc_max"), e1 = num(out, r + 1, "thrust_ecc_max");
      if (isinf(e0) || isinf(e1)) /* a joint pulled apart */
        aq_check(e0 == e1, "%s %s x%s: thrust_ecc_max %g and %g", an, b, k[s], e0, e1);
      else
        aq_check_rel(e1, e0, 1e-7, "%s %s x%s: thrust_ecc_max", an, b, k[s]);
      pairs++;
      collapses += num(out, r, "collapsed") == 1;
      marked += strcmp(s0, "ok") != 0;
    }
  }
  aq_check(pairs == 2 * 4 * NFREE && collapses > 0 && collapses < pairs && marked > 0,
           "%zu pairs, %zu collapse, %zu marked: both verdicts and marks among them", pairs,
           collapses, marked);
}

/* ---- the work path against the ode ----------------------------------------- */

static int run(const aq_arch *a, aq_model m, double k, const aq_steps *s, aq_result *r)
{
  aq_error e;
  aq_stepper *st = aq_stepper_alloc(aq_arch_path(a, 0), aq_arch_path(a, 1), m, &e);
  if (!aq_check(st != NULL, "stepper: %s", e.message))
    return 0;
  aq_stepper_set_cor(st, aq_arch_dynamics_of(a)->cor);
  aq_stepper_set_impact(st, 1); /* the momentum rule: the arch rocks onto the other set */
  aq_stepper_set_ode_rtol(st, 1e-12);
  aq_stepper_set_scale(st, k);
  aq_stepper_set_demand(st, aq_arch_demand_tracker(a, 0.6, &e));
  int ok = aq_stepper_run(st, s, r, &e) == AQ_OK;
  aq_check(ok, "run: %s", ok ? "" : e.message);
  aq_stepper_free(st);
  return ok;
}

/* Random step lists (0.1 ms to 80 ms, up to 2.2 lambda0 g either way, at
 * scales 1 and 1.8), the momentum rule, on each shipped free arch: the
 * work path and the ode (rtol 1e-12) agree on collapse and impacts in every
 * run, and on the energies, collapse time and demand to 1e-4 (measured: to
 * 1e-9 and better in most runs; up to 4e-5 where a rocking run passes
 * close to a set's peak and the two models' round-off tips it apart). */
AQ_TEST(arch_free_workpath_follows_the_ode)
{
  gsl_set_error_handler_off();
  enum { N = 400, RUNS = 10 };
  static double t[N], d[N], acc[N];
  for (size_t f = 0; f < NFREE; f++) {
    char path[128];
    snprintf(path, sizeof path, "arches/%s.cfg", free_arches[f]);
    aq_arch *a = load(path);
    if (!a)
      continue;
    const aq_path *p0 = aq_arch_path(a, 0), *p1 = aq_arch_path(a, 1);
    unsigned long long x = 0x9e3779b97f4a7c15ULL + f;
    size_t bad = 0, moved = 0, collapsed = 0, rocked = 0;
    double worst = 0;
    for (int k = 0; k < 2; k++)
      for (int run_ = 0; run_ < RUNS; run_++) {
        tds_random(&x, p0->lambda0 * p0->g_mps2, p1->lambda0 * p1->g_mps2, t, d, acc, N);
        aq_error e;
        aq_steps s;
        if (aq_steps_from_list(t, d, acc, N, &s, &e) != AQ_OK)
          continue;
        aq_result r[2];
        int ok0 = run(a, AQ_MODEL_WORKPATH, k ? 1.8 : 1, &s, &r[0]);
        int ok1 = ok0 && run(a, AQ_MODEL_ODE, k ? 1.8 : 1, &s, &r[1]);
        if (ok0 && ok1) {
          bad += r[0].collapsed != r[1].collapsed || r[0].impacts != r[1].impacts;
          moved += r[0].steps_moving > 0;
          collapsed += r[0].collapsed;
          rocked += r[0].impacts > 0;
          double ein = fmax(r[0].energy_in_j, 1e-300);
          worst = fmax(worst, fabs(r[0].energy_in_j - r[1].energy_in_j) / ein);
          worst = fmax(worst, fabs(r[0].max_kinetic_energy_j - r[1].max_kinetic_energy_j) / ein);
          worst = fmax(worst, fabs(r[0].energy_dissipated_j - r[1].energy_dissipated_j) / ein);
          if (r[0].collapsed)
            worst = fmax(worst, fabs(r[0].collapse_time_s - r[1].collapse_time_s));
          if (isfinite(r[0].mu_demand) || isfinite(r[1].mu_demand))
            worst = fmax(worst, fabs(r[0].mu_demand - r[1].mu_demand) / r[0].mu_demand);
          if (r[0].thrust_ecc_max > 0)
            worst = fmax(worst, fabs(r[0].thrust_ecc_max - r[1].thrust_ecc_max) /
                                    r[0].thrust_ecc_max);
        }
        if (ok0)
          aq_result_free(&r[0]);
        if (ok1)
          aq_result_free(&r[1]);
        aq_steps_free(&s);
      }
    aq_check(bad == 0 && moved >= RUNS && collapsed > 0 && rocked > 0,
             "%s: %zu of %d runs differ from the ode in collapse or impacts; %zu moved, %zu "
             "collapsed, %zu rocked",
             free_arches[f], bad, 2 * RUNS, moved, collapsed, rocked);
    aq_check(worst <= 1e-4, "%s: energies, collapse time and demand within %.3g of the ode",
             free_arches[f], worst);
    aq_arch_free(a);
  }
}

/* ---- the momentum rule between two sets ------------------------------------ */

typedef struct {
  double x, y;
} pt;

static pt sub(pt a, pt b) { return (pt){a.x - b.x, a.y - b.y}; }
static double dot(pt a, pt b) { return a.x * b.x + a.y * b.y; }

/* Where lines p + t u and q + s v meet. */
static pt meet(pt p, pt u, pt q, pt v)
{
  double det = u.x * (-v.y) - u.y * (-v.x);
  pt w = sub(q, p);
  double t = (w.x * (-v.y) - w.y * (-v.x)) / det;
  return (pt){p.x + t * u.x, p.y + t * u.y};
}

/* The velocity field of set k at rest (s = 0) per unit sdot: each
 * voussoir's centroid velocity u[i] and angular velocity w[i] (0 for a
 * voussoir that does not move), from the four-bar's instant centres: body 1
 * turns about H1 at q_sign, body 3 about H4, body 2 about the meeting of
 * lines H1 H2 and H4 H3, at the rates that give H2 and H3 one velocity
 * each. */
static void field(const aq_arch_drawing *dr, const aq_hinge_set *hs, int q_sign, pt *u, double *w)
{
  pt h[4];
  for (int k = 0; k < 4; k++) {
    const double *j = dr->joints + 4 * hs->joint[k];
    h[k] = hs->face[k] == 'i' ? (pt){j[0], j[1]} : (pt){j[2], j[3]};
  }
  pt c = meet(h[0], sub(h[1], h[0]), h[3], sub(h[2], h[3]));
  double w1 = q_sign;
  double w2 = w1 * dot(sub(h[1], h[0]), sub(h[1], c)) / dot(sub(h[1], c), sub(h[1], c));
  double w3 = w2 * dot(sub(h[2], c), sub(h[2], h[3])) / dot(sub(h[2], h[3]), sub(h[2], h[3]));
  for (size_t i = 0; i < dr->voussoirs; i++) {
    pt ctr = {0, 0}, g = {dr->parts[4 * i + 1], dr->parts[4 * i + 2]};
    double om = 0;
    if (i >= hs->joint[0] && i < hs->joint[1])
      ctr = h[0], om = w1;
    else if (i >= hs->joint[1] && i < hs->joint[2])
      ctr = c, om = w2;
    else if (i >= hs->joint[2] && i < hs->joint[3])
      ctr = h[3], om = w3;
    w[i] = om;
    u[i] = (pt){-om * (g.y - ctr.y), om * (g.x - ctr.x)};
  }
}

/* The momentum rule's ratio computed here for both ways of an arch whose
 * two sets are admissible: want[b], arriving on set 1 - b and leaving on
 * set b, is the projection of the arriving motion (the field of the set
 * arrived on, backwards) onto the field of the set left on, by the masses
 * and inertias: -sum(m u_a . u_b + I w_a w_b) / sum(m |u_b|^2 + I w_b^2),
 * the impulse-momentum balance about the new set's hinges; m[k] is set k's
 * sum(m |u_k|^2 + I w_k^2).  0 if a set is not admissible. */
static int ratios(const aq_arch *a, double want[2], double m[2])
{
  aq_arch_drawing dr;
  aq_arch_drawing_of(a, &dr);
  size_t n = dr.voussoirs;
  pt *u = malloc(2 * n * sizeof *u);
  double *w = malloc(2 * n * sizeof *w);
  const aq_path *p[2] = {aq_arch_path(a, 0), aq_arch_path(a, 1)};
  int ok = u && w && p[0]->admissible && p[1]->admissible;
  if (ok) {
    for (int k = 0; k < 2; k++)
      field(&dr, aq_arch_hinge_set(a, k), p[k]->q_sign, u + k * n, w + k * n);
    for (int k = 0; k < 2; k++) {
      m[k] = 0;
      for (size_t i = 0; i < n; i++)
        m[k] += dr.parts[4 * i] * dot(u[k * n + i], u[k * n + i]) +
                dr.parts[4 * i + 3] * w[k * n + i] * w[k * n + i];
    }
    for (int b = 0; b < 2; b++) {
      int aa = 1 - b;
      double cross = 0;
      for (size_t i = 0; i < n; i++)
        cross += dr.parts[4 * i] * dot(u[aa * n + i], u[b * n + i]) +
                 dr.parts[4 * i + 3] * w[aa * n + i] * w[b * n + i];
      want[b] = -cross / m[b];
    }
  }
  free(u);
  free(w);
  return ok;
}

/* On every shipped arch, fixed and free: arriving at rest on one set and
 * leaving on the other, the post-impact sdot over the pre-impact |sdot| is
 * ratios()'s projection, to 1e-11 (the mass M_b(0) comes from the work
 * path's tables, 4e-12).  On these arches it is positive and the kinetic
 * energy kept, ratio^2 M_b / M_a, is at most 1. */
AQ_TEST(arch_free_impact_rule_between_two_sets)
{
  gsl_set_error_handler_off();
  static const char *const all[] = {"oppenheim", "thin",     "thick",   "segmental", "search",
                                    "gothic",    "bridge", "catenary", "vertical"};
  size_t checked = 0;
  for (size_t f = 0; f < sizeof all / sizeof all[0]; f++) {
    char path[128];
    snprintf(path, sizeof path, "arches/%s.cfg", all[f]);
    aq_arch *a = load(path);
    if (!a)
      continue;
    double want[2], m[2];
    if (ratios(a, want, m))
      for (int b = 0; b < 2; b++) { /* arriving on 1 - b, leaving on b */
        int aa = 1 - b;
        aq_check_rel(aq_arch_path(a, b)->impact_vel_ratio, want[b], 1e-11,
                     "%s: from set %d onto set %d", all[f], aa, b);
        aq_check(want[b] > 0 && want[b] * want[b] * m[b] <= m[aa] * (1 + 1e-12),
                 "%s: onto set %d: ratio %.6g, kinetic energy kept %.6g", all[f], b, want[b],
                 want[b] * want[b] * m[b] / m[aa]);
        checked++;
      }
    aq_arch_free(a);
  }
  aq_check(checked == 16, "16 impacts checked, both ways on each arch but segmental, whose "
                          "reverse set is not admissible (%zu)", checked);
}

/* A flat arch's two sets can have fields that point against each other:
 * the projection of the arriving motion onto the set left on is negative
 * (parabolic span 10 m, rise 1.2 m, t 0.6 m, free: -0.909 and -0.685, here
 * from ratios()).  No impulse at the new set's hinges can open it, and the
 * set arrived on cannot reopen (the projection on its own field is
 * -|sdot|): the arch stops at that impact, its kinetic energy all lost.
 * From a pulse in each direction: one impact, no motion on the other set,
 * every joule put in dissipated, and no motion after the impact.  The same
 * pulses on a shipped free arch (positive ratios) rock it onto the other
 * set: the test tells the two rules apart. */
AQ_TEST(arch_free_impact_negative_ratio_stops)
{
  gsl_set_error_handler_off();
  char path[700];
  if (!aq_test_tmpfile(path, sizeof path, "flat.cfg",
                       "[arch]\nname = flat\nshape = parabolic\nspan_m = 10\nrise_m = 1.2\n"
                       "thickness_m = 0.6\nvoussoirs = 20\ndensity_kg_m3 = 2000\n"
                       "depth_m = 1.0\n[dynamics]\nimpact = momentum\n"))
    return;
  static const char *const files[2] = {NULL, "arches/search.cfg"};
  for (int c = 0; c < 2; c++) {
    aq_arch *a = load(c ? files[c] : path);
    if (!a)
      continue;
    double want[2], m[2];
    if (!aq_check(ratios(a, want, m), "%s: both sets admissible", c ? files[c] : "flat"))
      goto next;
    for (int k = 0; k < 2; k++) { /* a pulse that drives set k, arriving back on it */
      const aq_path *p = aq_arch_path(a, k);
      int other = 1 - k;
      aq_check(c ? want[other] > 0 : want[other] < 0, "%s: onto set %d, ratio %.6g",
               c ? files[c] : "flat", other, want[other]);
      aq_check_rel(aq_arch_path(a, other)->impact_vel_ratio, want[other], 1e-11,
                   "%s: onto set %d: the arch's ratio", c ? files[c] : "flat", other);
      /* 1.3 lambda0 g for the longest of these durations that moves the
       * arch without collapsing it */
      static const double durs[] = {0.2, 0.1, 0.05, 0.02, 0.01, 0.005};
      int done = 0;
      for (size_t d = 0; d < sizeof durs / sizeof durs[0] && !done; d++) {
        aq_steps s;
        if (!tds_pulse(p->act_sign * 1.3 * p->lambda0 * p->g_mps2, durs[d], durs[d] + 3.0, 1e-3,
                       &s))
          continue;
        aq_result r;
        if (run(a, AQ_MODEL_WORKPATH, 1, &s, &r)) {
          if (!r.collapsed && r.impacts > 0) {
            done = 1;
            const char *nm = c ? files[c] : "flat";
            aq_check(r.peak_rotation_set_rad[k] > 0, "%s set %d, %g s: moved", nm, k, durs[d]);
            if (c)
              aq_check(r.peak_rotation_set_rad[other] > 0 && r.impacts > 1,
                       "%s set %d, %g s: rocks onto set %d (%zu impacts)", nm, k, durs[d],
                       other, r.impacts);
            else {
              aq_check(r.impacts == 1 && r.peak_rotation_set_rad[other] == 0,
                       "%s set %d, %g s: stops at its first impact (%zu impacts, %g rad on "
                       "set %d)",
                       nm, k, durs[d], r.impacts, r.peak_rotation_set_rad[other], other);
              aq_check_rel(r.energy_dissipated_j, r.energy_in_j, 1e-9,
                           "%s set %d: everything put in is dissipated", nm, k);
            }
          }
          aq_result_free(&r);
        }
        aq_steps_free(&s);
      }
      aq_check(done, "%s set %d: a pulse that moves it and brings it back", c ? files[c] : "flat",
               k);
    }
  next:
    aq_arch_free(a);
  }
}

/* ---- which arches need one polarity ---------------------------------------- */

static const char gothic_masses[] =
    "[arch]\nname = masses\nshape = pointed\nspan_m = 5.0\nrise_m = 4.330127019\n"
    "thickness_m = 0.5\nvoussoirs = 24\ndensity_kg_m3 = 2300\ndepth_m = 0.6\n"
    "[masses]\nleft = 5 1.9 2.6 200\nright = 18 %s 2.6 200\n%s";

static aq_arch *masses_arch(const char *dir, const char *name, const char *x_right,
                            const char *more, char *path, size_t cap)
{
  snprintf(path, cap, "%s/%s.cfg", dir, name);
  FILE *f = fopen(path, "w");
  if (!f)
    return NULL;
  fprintf(f, gothic_masses, x_right, more);
  fclose(f);
  return load(path);
}

/* One polarity is enough only for a free arch that is its own mirror image
 * to 1e-9 of its size: the shipped free arches and an arch with two point
 * masses placed as mirror images; not the same arch with one mass 1e-6 m
 * (2e-7 of the span) off its place, which 1e-12 m leaves symmetric; not
 * the symmetric arch with fixed hinges; not the fixed shipped arches. */
AQ_TEST(arch_free_one_polarity_only_for_a_mirror_image)
{
  gsl_set_error_handler_off();
  static const char *const fixed[] = {"oppenheim", "thin", "thick", "segmental"};
  for (size_t f = 0; f < NFREE + 4; f++) {
    char path[128];
    snprintf(path, sizeof path, "arches/%s.cfg", f < NFREE ? free_arches[f] : fixed[f - NFREE]);
    aq_arch *a = load(path);
    if (a)
      aq_check(aq_arch_one_polarity(a) == (f < NFREE), "%s: one polarity %d", path,
               aq_arch_one_polarity(a));
    aq_arch_free(a);
  }
  char dir[512], path[700];
  aq_test_tmpdir(dir, sizeof dir);
  static const struct {
    const char *x, *more;
    int sym, one;
  } c[] = {{"-1.9", "", 1, 1},
           {"-1.900000000001", "", 1, 1},
           {"-1.900001", "", 0, 0},
           {"-1.9", "[hinges]\ncontrol = fixed\nprimary = 0e 6i 12e 18i\n", 1, 0}};
  for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
    char name[16];
    snprintf(name, sizeof name, "m%zu", k);
    aq_arch *a = masses_arch(dir, name, c[k].x, c[k].more, path, sizeof path);
    if (!a)
      continue;
    aq_check(aq_arch_mirror_symmetric(a) == c[k].sym && aq_arch_one_polarity(a) == c[k].one,
             "right mass at x = %s%s: symmetric %d, one polarity %d", c[k].x,
             c[k].more[0] ? ", fixed" : "", aq_arch_mirror_symmetric(a), aq_arch_one_polarity(a));
    aq_arch_free(a);
  }
}

/* The main job and capacity run both polarities unless told, or unless
 * every arch is a free mirror image, or every subject is a ground motion
 * whose azimuths come in opposite pairs. */
AQ_TEST(arch_free_polarity_default)
{
  char dir[512], path[700], asym[700], cmd[2048], err[4096], buf[64];
  static char out[1 << 16];
  aq_test_tmpdir(dir, sizeof dir);
  aq_arch_free(masses_arch(dir, "asym", "-1.900001", "", asym, sizeof asym));
  aq_arch_free(masses_arch(dir, "sym", "-1.9", "", path, sizeof path));
  const char *rec = "tests/data/records/IELC180.AT2";
  static const struct {
    const char *args;
    int rows;
    const char *first, *second;
  } c[] = {
      {"--arch arches/gothic.cfg --arch arches/search.cfg", 2, "normal", "normal"},
      {"--arch @S", 1, "normal", NULL},
      {"--arch @A", 2, "normal", "reversed"},
      {"--arch arches/oppenheim.cfg", 2, "normal", "reversed"},
      {"--arch arches/gothic.cfg --arch arches/thin.cfg", 4, "normal", "reversed"},
      {"--arch arches/oppenheim.cfg --polarity normal", 1, "normal", NULL},
      {"--arch arches/gothic.cfg --polarity reversed", 1, "reversed", NULL},
      {"--arch arches/gothic.cfg --polarity both", 2, "normal", "reversed"},
  };
  for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
    char args[700];
    snprintf(args, sizeof args, "%s", c[k].args);
    char *at = strstr(args, "@S") ? strstr(args, "@S") : strstr(args, "@A");
    if (at)
      snprintf(at, sizeof args - (size_t)(at - args), "%s", at[1] == 'S' ? path : asym);
    for (int cap = 0; cap < 2; cap++) {
      snprintf(cmd, sizeof cmd, "%s%s %s %s", cap ? "capacity " : "", rec, args,
               cap ? "--resolution 0.2 --scale-max 2" : "--scale 2");
      int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
      size_t rows = aq_test_count_lines(out) - 1;
      aq_check(rc == 0 && (int)rows == c[k].rows, "%s: exit %d, %zu rows (want %d): %s", cmd,
               rc, rows, c[k].rows, err);
      aq_check(!strcmp(str(out, 1, "polarity", buf, sizeof buf), c[k].first), "%s: row 1 %s",
               cmd, buf);
      if (c[k].second)
        aq_check(!strcmp(str(out, 2, "polarity", buf, sizeof buf), c[k].second),
                 "%s: row 2 %s", cmd, buf);
    }
  }
  /* ground motions: azimuths in opposite pairs run each motion both ways;
     not a plain record beside them (REC2: its two rows, the motion's two) */
#define REC2 "tests/data/records/ARL360.at2"
  static const struct {
    const char *az;
    int rows;
  } m[] = {{"--azimuth all", 1},   {"--azimuth all:90 --all-azimuths", 4},
           {"--azimuth all:180", 1}, {"--azimuth all:7", 2},
           {"--azimuth 30", 2},      {"--azimuth all " REC2, 4}};
  for (size_t k = 0; k < sizeof m / sizeof m[0]; k++) {
    snprintf(cmd, sizeof cmd,
             "--components tests/data/records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2,"
             "tests/data/records/RSN6_IMPVALL.I_I-ELC270-hor2.AT2 %s --arch arches/thin.cfg "
             "--scale 1",
             m[k].az);
    int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
    size_t rows = aq_test_count_lines(out) - 1;
    aq_check(rc == 0 && (int)rows == m[k].rows, "%s: exit %d, %zu rows (want %d): %s", m[k].az,
             rc, rows, m[k].rows, err);
  }
}
