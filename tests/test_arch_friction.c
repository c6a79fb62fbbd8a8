/* test_arch_friction.c: the static theorem with friction (friction.c)
 * against what it must agree with: without friction, the kinematic side
 * (the minimum four-hinge multiplier of each direction by a brute force
 * over every set with the 9x9, and the search); at the collapse state, the
 * friction the 9x9 hinge reactions demand (mu_required) against the least
 * friction of the program at lambda0 from below, by bisection on the
 * program's largest load; a published anchor (Cocchetti & Rizzi 2020); and
 * an arch that cannot stand with its friction, refused in one line. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/model.h"
#include "arch_lambda0.h"
#include "check.h"
#include "units.h"

/* The programs' largest load against lambda0 by virtual work (measured
 * 4.1e-14 at worst: round-off) */
#define LP_REL 1e-10
/* lambda0 from below: far enough for the programs with friction rows, whose
 * floating-point optimum GLPK may leave up to 4e-10 (relative) below the
 * exact one within its tolerances (measured on the catenary), near enough
 * that the least friction there is mu_required to 1e-6 (measured 5.6e-8) */
#define BELOW_REL 1e-8

static const char *const shipped[] = {"arches/oppenheim.cfg", "arches/thin.cfg",
                                      "arches/thick.cfg",     "arches/segmental.cfg",
                                      "arches/search.cfg",    "arches/gothic.cfg",
                                      "arches/bridge.cfg",    "arches/catenary.cfg",
                                      "arches/vertical.cfg"};
#define NSHIPPED (sizeof shipped / sizeof shipped[0])

static aq_arch *load(const char *path)
{
  aq_arch *a = NULL;
  aq_error e;
  aq_error_clear(&e);
  aq_arch_options o = {.friction_table = 1};
  aq_check(aq_arch_load_opts(path, &o, &a, &e) == AQ_OK, "%s loads: %s", path, e.message);
  return a;
}

/* The minimum four-hinge set of direction act and its path. */
static aq_workpath *direction_minimum(const aq_geom *g, int act)
{
  aq_hinge_set hs;
  aq_error e;
  aq_workpath *w = NULL;
  if (aq_search_direction(g, 9.80665, act, &hs, NULL, NULL, &e) != AQ_OK ||
      aq_workpath_build(g, &hs, 9.80665, "minimum", &w, &e) != AQ_OK)
    return NULL;
  return w;
}

/* Without friction the program's largest load is the minimum multiplier of
 * each direction: on every shipped arch (every shape; fill, point masses)
 * the search's directional minimum four-hinge set's lambda0 (virtual work,
 * its 9x9 checked by the search). */
AQ_TEST(arch_friction_without_friction_is_lambda0)
{
  gsl_set_error_handler_off();
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *a = load(shipped[f]);
    if (!a)
      continue;
    for (int act = -1; act <= 1; act += 2) {
      aq_workpath *w = direction_minimum(aq_arch_geom(a), act);
      if (!aq_check(w != NULL, "%s: the minimum of act_sign %+d", shipped[f], act))
        continue;
      double l0 = aq_workpath_path(w)->lambda0, lp = NAN;
      aq_error e;
      aq_check(aq_friction_lambda(aq_arch_geom(a), act, INFINITY, &lp, NULL, &e) == AQ_OK,
               "%s: the program: %s", shipped[f], e.message);
      aq_check_rel(lp, l0, LP_REL, "%s act_sign %+d: the program's largest load = lambda0",
                   shipped[f], act);
      aq_check_rel(aq_arch_lambda_static(a, act), l0, LP_REL, "%s: the arch's, kept",
                   shipped[f]);
      aq_workpath_free(w);
    }
    aq_arch_free(a);
  }
}

/* Small arches, every set of every face pattern by the 9x9 (independent of
 * the programs): the largest load equals each direction's minimum, or lies
 * below it where a mechanism with a joint lifting off (no four-hinge set)
 * has a lower multiplier: then it is that mechanism's, as the search
 * reports it (flat, thick arches). */
AQ_TEST(arch_friction_without_friction_brute_force)
{
  gsl_set_error_handler_off();
  static const double embrace_deg[] = {180, 151.3, 97};
  static const double t_over_r[] = {0.31, 0.6};
  int equal = 0, lift = 0;
  for (size_t ie = 0; ie < 3; ie++)
    for (size_t it = 0; it < 2; it++)
      for (size_t n = 8; n <= 11; n += 3) {
        aq_arch_params pp = aq_arch_circular(2.91, 2.91 * t_over_r[it],
                                             embrace_deg[ie] * AQ_DEG_RAD, n, 1913.0, 0.77);
        aq_geom g;
        aq_error e;
        if (!aq_check(aq_geom_init(&g, &pp, &e) == AQ_OK, "geometry"))
          return;
        double best[2] = {HUGE_VAL, HUGE_VAL};
        aq_hinge_set hs = {{0, 0, 0, 0}, {0, 0, 0, 0}};
        for (int pat = -1; aq_test_next_set(n, &pat, &hs);) {
          double l0;
          int act;
          if (aq_test_lambda0_eq_act(&g, &hs, &l0, &act) && l0 > 0 &&
              l0 < best[act > 0])
            best[act > 0] = l0;
        }
        for (int k = 0; k < 2; k++) {
          int act = k ? 1 : -1;
          double lp = NAN;
          aq_hinge_set hs;
          aq_search_info info;
          aq_status sp = aq_friction_lambda(&g, act, INFINITY, &lp, NULL, &e);
          aq_check(sp == AQ_OK, "embrace %g t/R %g n %zu act %+d: the program: %d %s",
                   embrace_deg[ie], t_over_r[it], n, act, sp, e.message);
          aq_status st = aq_search_direction(&g, 9.80665, act, &hs, NULL, &info, &e);
          if (st == AQ_OK && info.liftoff) {
            lift++;
            aq_check(lp < best[k] * (1 - LP_REL), "embrace %g t/R %g n %zu act %+d: a lift-off "
                     "mechanism below the four-hinge minimum (%.12g < %.12g)",
                     embrace_deg[ie], t_over_r[it], n, act, lp, best[k]);
            aq_check_rel(lp, info.liftoff_lambda, LP_REL, "... it is the search's lift-off");
          } else if (isfinite(best[k])) {
            equal++;
            aq_check_rel(lp, best[k], LP_REL, "embrace %g t/R %g n %zu act %+d: = the brute "
                         "force's minimum", embrace_deg[ie], t_over_r[it], n, act);
          }
        }
        aq_geom_free(&g);
      }
  aq_check(equal >= 10 && lift >= 1, "both cases met (%d equal, %d lift-off)", equal, lift);
}

/* The least friction of the program at load lambda in direction act, by
 * bisection on its largest load (another route than aq_friction_least's
 * fractional program). */
static double least_by_bisection(const aq_geom *g, int act, double lambda)
{
  double lo = 1e-3, hi = 10;
  aq_error e;
  for (int it = 0; it < 60; it++) {
    double mid = sqrt(lo * hi), lf;
    int ok = aq_friction_lambda(g, act, mid, &lf, NULL, &e) == AQ_OK && lf >= lambda;
    if (ok)
      hi = mid;
    else
      lo = mid;
  }
  return hi;
}

/* mu_required (the 9x9 hinge reactions and each piece's statics) of each
 * direction's minimum set = the least friction with which the program
 * stands at lambda0 from below, to 1e-6; and what it needs at every
 * joint never exceeds it. */
AQ_TEST(arch_friction_mu_required_is_least)
{
  gsl_set_error_handler_off();
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *a = load(shipped[f]);
    if (!a)
      continue;
    const aq_geom *g = aq_arch_geom(a);
    size_t n = g->p.voussoirs;
    for (int act = -1; act <= 1; act += 2) {
      aq_workpath *w = direction_minimum(g, act);
      if (!w)
        continue;
      double ratio[1001];
      size_t joint;
      double need = aq_workpath_friction(w, ratio, &joint);
      double l0 = aq_workpath_path(w)->lambda0, below = l0 * (1 - BELOW_REL);
      double bis = least_by_bisection(g, act, below), dk = NAN;
      aq_error e;
      aq_check(aq_friction_least(g, act, below, &dk, NULL, &e) == AQ_OK, "least");
      aq_check_rel(bis, need, 1e-6, "%s act %+d: mu_required %.9g (joint %zu) = the "
                   "program's least at lambda0- by bisection", shipped[f], act, need, joint);
      aq_check_rel(dk, need, 1e-6, "%s act %+d: = its least by the fractional program",
                   shipped[f], act);
      int below_max = 1;
      for (size_t j = 0; j <= n; j++)
        below_max &= ratio[j] <= need;
      aq_check(below_max && ratio[joint] == need, "%s: every joint within mu_required",
               shipped[f]);
      aq_workpath_free(w);
    }
    aq_arch_free(a);
  }
}

/* Friction only lowers the largest load, monotonically: not above the
 * load without friction, equal to it from mu_required on, never rising as
 * mu falls, and no line at all below the friction needed at rest. */
AQ_TEST(arch_friction_lowers_lambda_monotonically)
{
  gsl_set_error_handler_off();
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *a = load(shipped[f]);
    if (!a)
      continue;
    const aq_geom *g = aq_arch_geom(a);
    size_t jr;
    double rest = aq_arch_mu_rest(a, &jr);
    for (int act = -1; act <= 1; act += 2) {
      double top = aq_arch_lambda_static(a, act), prev = -HUGE_VAL;
      aq_workpath *w = direction_minimum(g, act);
      double need = w ? aq_workpath_friction(w, NULL, NULL) : NAN;
      aq_workpath_free(w);
      int rising = 1, below = 1, flat = 1;
      for (double mu = rest * 1.0001; mu < 2.5; mu *= 1.05) {
        double lf = NAN;
        aq_error e;
        if (!aq_check(aq_friction_lambda(g, act, mu, &lf, NULL, &e) == AQ_OK, "%s mu %g: %s",
                      shipped[f], mu, e.message))
          break;
        rising &= lf >= prev - 1e-12 * top;
        below &= lf <= top * (1 + 1e-12);
        if (mu >= need * (1 + 1e-6))
          flat &= fabs(lf - top) <= 1e-12 * top;
        prev = lf;
      }
      aq_check(rising && below && flat, "%s act %+d: lambda_friction rises with mu (%d), "
               "stays at or below %.9g (%d), reaches it from mu_required %.6g (%d)",
               shipped[f], act, rising, top, below, need, flat);
      double lf;
      aq_error e;
      if (rest < 1e-6)
        continue; /* catenary: its line at rest runs along the joints' normals */
      aq_status st = aq_friction_lambda(g, act, rest * 0.999, &lf, NULL, &e);
      aq_check(st == AQ_EINADMISSIBLE || lf < 0, "%s: below the friction at rest %.6g, no "
               "line stands at lambda >= 0", shipped[f], rest);
    }
    aq_arch_free(a);
  }
}

/* The arch's table of the least friction over the load, against the
 * program at loads between its nodes; lambda_friction(mu) from it, against
 * the program. */
AQ_TEST(arch_friction_table)
{
  gsl_set_error_handler_off();
  double worst_mu = 0, worst_lf = 0;
  unsigned seed = 20261128u;
  for (size_t f = 0; f < NSHIPPED; f++) {
    aq_arch *a = load(shipped[f]);
    if (!a)
      continue;
    const aq_geom *g = aq_arch_geom(a);
    for (int act = -1; act <= 1; act += 2) {
      double top = aq_arch_lambda_static(a, act);
      for (int i = 0; i < 12; i++) {
        seed = seed * 1103515245u + 12345u;
        double lam = top * (double)((seed >> 8) % 100000) / 100000.0, exact = NAN, lf = NAN;
        aq_error e;
        aq_friction_least(g, act, lam, &exact, NULL, &e);
        double got = aq_arch_mu_least(a, act, lam, NULL);
        worst_mu = fmax(worst_mu, fabs(got - exact) / exact);
        /* lambda_friction at that friction: back to lam */
        aq_friction_lambda(g, act, exact, &lf, NULL, &e);
        double back = aq_arch_lambda_friction(a, act, exact);
        worst_lf = fmax(worst_lf, fabs(back - lf) / top);
      }
      aq_check(isinf(aq_arch_mu_least(a, act, top * 1.001, NULL)), "above the top: none");
      aq_check(isnan(aq_arch_mu_least(a, act, -0.01, NULL)), "below 0: NAN");
    }
    aq_arch_free(a);
  }
  aq_arch *plain = NULL;
  aq_error e;
  if (aq_check(aq_arch_load("arches/oppenheim.cfg", &plain, &e) == AQ_OK, "plain load"))
    aq_check(isnan(aq_arch_mu_least(plain, -1, 0.1, NULL)) &&
                 aq_arch_lambda_static(plain, -1) > 0.41,
             "an arch built without the table: NAN, the largest load kept");
  aq_arch_free(plain);
  aq_check(worst_mu <= 1e-4, "table: mu_least within 1e-4 of the program (%.3g)", worst_mu);
  aq_check(worst_lf <= 1e-4, "table: lambda_friction within 1e-4 lambda_top (%.3g)", worst_lf);
}

/* An arch whose largest load is a lift-off mechanism's: the parabola of
 * span 10 m, t 0.6 m, rise 0.9 m, 20 voussoirs (joint 0 or 20 lifts off
 * at lambda 8.2818).  Its least friction grows as c / (lambda_top -
 * lambda) towards the top, so its table ends where the least friction
 * passes 1e3 (the largest friction an arch may be given) and gives inf
 * beyond.  Checked against the programs solved directly: the least
 * friction at loads from 1e-1 to 1e-8 (relative) below the table's end
 * and between its nodes (to 1e-4 of the larger of the value and 1,
 * measured 6.7e-6 near the end, 2.8e-5 over the range); every load
 * beyond the end needing at least 1e3; the least friction itself, by the
 * other program (lambda_friction at that friction is the load); and
 * lambda_friction(0.6) read from the table. */
#define CAP 1e3
AQ_TEST(arch_friction_table_liftoff)
{
  gsl_set_error_handler_off();
  char path[700];
  if (!aq_test_tmpfile(path, sizeof path, "flat.cfg",
                       "[arch]\nshape = parabolic\nspan_m = 10\nrise_m = 0.9\nthickness_m = 0.6\n"
                       "voussoirs = 20\ndensity_kg_m3 = 2000\ndepth_m = 1\n"))
    return;
  aq_arch *a = load(path);
  if (!a)
    return;
  const aq_geom *g = aq_arch_geom(a);
  aq_error e;
  double worst_top = 0, worst_range = 0;
  for (int act = -1; act <= 1; act += 2) {
    double top = aq_arch_lambda_static(a, act), lo = 0, hi = top;
    aq_check_rel(top, 8.2818, 1e-4, "the lift-off's load");
    for (int it = 0; it < 100; it++) { /* the table's end: the last finite value */
      double mid = 0.5 * (lo + hi);
      if (isfinite(aq_arch_mu_least(a, act, mid, NULL)))
        lo = mid;
      else
        hi = mid;
    }
    double end = lo, ex = NAN;
    aq_check(end > 0.999 * top && end < top, "the table ends just below the top (%.9g of %.9g)",
             end, top);
    aq_friction_least(g, act, end, &ex, NULL, &e);
    /* (the programs there: lambda's relative distance to the pole, 6.5e-5, amplifies
       their round-off to about 1e-5) */
    aq_check(ex >= CAP * (1 - 1e-4) && ex < CAP * (1 + 1e-4), "at its end the least friction "
             "is the cap: %.9g", ex);
    for (int i = 0; i <= 70; i++) {
      double lam = end * (1 - pow(10, -1 - i / 10.0)), got = aq_arch_mu_least(a, act, lam, NULL);
      aq_friction_least(g, act, lam, &ex, NULL, &e);
      worst_top = fmax(worst_top, fabs(got - ex) / fmax(ex, 1));
    }
    for (int i = 0; i < 200; i++) {
      double lam = end * (i + 0.37) / 200, got = aq_arch_mu_least(a, act, lam, NULL);
      aq_friction_least(g, act, lam, &ex, NULL, &e);
      worst_range = fmax(worst_range, fabs(got - ex) / fmax(ex, 1));
      if (i % 20 == 7 && lam > 0.8 * top) { /* the least friction, by lambda_friction */
        double above = NAN, below = NAN;
        aq_friction_lambda(g, act, ex * (1 + 1e-6), &above, NULL, &e);
        aq_friction_lambda(g, act, ex * (1 - 1e-4), &below, NULL, &e);
        aq_check(above >= lam * (1 - 1e-9) && below < lam, "%.6g at lambda %.6g is the least: "
                 "lambda_friction %.9g just above it, %.9g just below", ex, lam, above, below);
      }
    }
    for (int i = 1; i <= 8; i++) { /* beyond the end: inf, and more than the cap */
      double lam = end + (top - end) * (1 - pow(0.25, i));
      aq_friction_least(g, act, lam, &ex, NULL, &e);
      aq_check(isinf(aq_arch_mu_least(a, act, lam, NULL)) && !(ex < CAP),
               "beyond the end, %.12g: inf (the program: %.6g)", lam, ex);
    }
    double lf = NAN;
    aq_friction_lambda(g, act, 0.6, &lf, NULL, &e);
    aq_check(fabs(aq_arch_lambda_friction(a, act, 0.6) - lf) <= 1e-6 * top,
             "lambda_friction(0.6) from the table %.9g, the program %.9g",
             aq_arch_lambda_friction(a, act, 0.6), lf);
    aq_check(isnan(aq_arch_lambda_friction(a, act, 2 * CAP)), "above the cap: not known");
  }
  aq_arch_free(a);
  aq_check(worst_top <= 1e-4, "near the end within 1e-4 (%.3g)", worst_top);
  aq_check(worst_range <= 1e-4, "over the range within 1e-4 (%.3g)", worst_range);
}

/* Cocchetti & Rizzi 2020 ("Analytical and numerical analysis on the
 * collapse modes of least-thickness circular masonry arches at decreasing
 * friction", Frattura ed Integrita Strutturale 51, 356-375): the complete
 * semicircular arch with radial joints at its least thickness under its
 * own weight (t/R = 0.107426, R the centre-line radius) collapses by
 * rotation alone (five hinges) only if mu > 0.395832, where its shoulders
 * (the springings) would slide.  Here with 120 voussoirs: the thickness
 * where the minimum lambda0 crosses 0 (bisection), and there the friction
 * of the minimum set's collapse state (9x9) and the program's least at
 * rest. */
static aq_arch_params semicircle(double t, const void *ctx)
{
  (void)ctx;
  return aq_arch_circular(3.0, t, 180.0 * AQ_DEG_RAD, 120, 2100.0, 1.0);
}

AQ_TEST(arch_friction_cocchetti_rizzi)
{
  gsl_set_error_handler_off();
  double t = aq_test_critical_thickness(semicircle, NULL, 0.105 * 3.0, 0.110 * 3.0, 40);
  aq_check_rel(t / 3.0, 0.107426, 0.005, "least thickness t/R with 120 voussoirs");
  aq_arch_params p = semicircle(t * (1 + 1e-9), NULL);
  aq_geom g;
  aq_error e;
  if (!aq_check(aq_geom_init(&g, &p, &e) == AQ_OK, "geometry"))
    return;
  aq_hinge_set hs;
  double l0;
  aq_check(aq_search_minimum(&g, 9.80665, &hs, &l0, NULL, &e) == AQ_OK && l0 >= 0 && l0 < 1e-6,
           "at the least thickness lambda0 ~ 0: %g", l0);
  aq_mech m;
  aq_mech_state st;
  aq_equil eq;
  aq_live live = {AQ_LIVE_HORIZONTAL, aq_search_act_sign(&g, &hs), {0, 0}, 0, 9.80665};
  double ecc[121], ratio[121], need = NAN;
  size_t joint = 0;
  if (aq_mech_init(&m, &g, &hs, &e) == AQ_OK && aq_mech_eval(&m, 0.0, &st) == 0 &&
      aq_mech_equilibrium(&m, &st, &live, &eq, &e) == AQ_OK)
    need = aq_mech_friction(&m, &st, &live, &eq, ecc, ratio, &joint);
  aq_check_rel(need, 0.395832, 0.005, "the collapse state needs %.6g (published 0.395832)",
               need);
  aq_check(joint == 0 || joint == 120, "at a springing (joint %zu)", joint);
  double rest = NAN;
  size_t jr;
  aq_check(aq_friction_least(&g, -1, 0.0, &rest, &jr, &e) == AQ_OK, "least at rest");
  aq_check_rel(rest, 0.395832, 0.005, "the program's least friction at rest %.6g", rest);
  aq_check(jr == 0 || jr == 120, "at a springing (joint %zu)", jr);
  aq_geom_free(&g);
}

/* An arch that cannot stand with its friction is refused in one line,
 * nothing written; the figures quoted for oppenheim; the help names every column. */
AQ_TEST(arch_friction_cli)
{
  char out[16384], err[4096];
  int rc = aq_test_run("mechanism --arch arches/oppenheim.cfg --friction 0.3", out, sizeof out,
                       err, sizeof err);
  aq_check(rc == 1 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
               strstr(err, "archquake: arches/oppenheim.cfg: friction: expected an arch that "
                           "stands with friction 0.3, got one that cannot: it needs 0.309 at "
                           "rest, joint 0"),
           "oppenheim at 0.3 refused: %d \"%s\"", rc, err);
  /* in the file, on its line; the main job runs nothing and writes nothing */
  char dir[512], cfg[600], h5[600], args[2048];
  aq_test_tmpdir(dir, sizeof dir);
  aq_test_edited_copy("arches/oppenheim.cfg", "[dynamics]", "[contact]\nfriction = 0.25\n[dynamics]",
                      dir, "slip.cfg", cfg, sizeof cfg);
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  snprintf(args, sizeof args, "records/RSN1616_DUZCE_362-E.AT2 --arch %s --no-cache -o %s", cfg,
           h5);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && out[0] == '\0' && strstr(err, ": friction: expected an arch that stands "
                                                    "with friction 0.25") &&
               strstr(err, "slip.cfg:"),
           "the main job refuses it, naming the file and line: %d %s", rc, err);
  aq_check(aq_test_count_names(dir, "r.h5") == 0, "no results file");
  /* oppenheim's figures quoted before: 0.686 at the springing, lambda 0.412 -> 0.331 at 0.6 */
  rc = aq_test_run("mechanism --arch arches/oppenheim.cfg --friction 0.6", out, sizeof out, err,
                   sizeof err);
  char cell[64];
  double mu = atof(aq_test_tsv_field(out, 1, 17, cell, sizeof cell));
  int joint = atoi(aq_test_tsv_field(out, 1, 18, cell, sizeof cell));
  double lf = atof(aq_test_tsv_field(out, 1, 19, cell, sizeof cell));
  double l0 = atof(aq_test_tsv_field(out, 1, 3, cell, sizeof cell));
  aq_check(rc == 0 && fabs(mu - 0.686) < 0.0005 && joint == 0, "primary needs 0.686 at joint 0 "
           "(%g at %d)", mu, joint);
  aq_check(fabs(l0 - 0.412) < 0.0005 && fabs(lf - 0.331) < 0.0005, "lambda0 0.412, with 0.6: "
           "0.331 (%g, %g)", l0, lf);
  /* the help names every column the command prints */
  static char help[1 << 14];
  rc = aq_test_run("mechanism --help", help, sizeof help, err, sizeof err);
  char *cols = strstr(help, "Columns: "), *end = cols ? strstr(cols, "Table columns:") : NULL;
  if (!aq_check(rc == 0 && cols && end, "mechanism --help has its Columns: (exit %d)", rc))
    return;
  *end = '\0';
  char *nl = strchr(out, '\n');
  if (nl)
    *nl = '\0';
  for (char *c = strtok(out, "\t"); c; c = strtok(NULL, "\t")) {
    int found = 0;
    size_t n = strlen(c);
    for (const char *p = strstr(cols, c); p && !found; p = strstr(p + 1, c))
      found = (p[-1] == ' ') && (p[n] == ' ' || p[n] == '\n');
    aq_check(found, "mechanism --help names the column %s", c);
  }
}
