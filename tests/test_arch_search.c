/* test_arch_search.c: the mechanism search against random admissible hinge
 * sets and against a brute force that uses the 9x9 equilibrium (a second,
 * independent way to get lambda0) instead of virtual work. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "arch/model.h"
#include "arch_lambda0.h"
#include "check.h"
#include "units.h"

#define TIE_TOL 5e-14 /* relative: lambda0 by two methods agree to round-off (measured 1.6e-15) */

/* lambda0 of hs by the 9x9 equilibrium; 1 if admissible there (hinges open
 * at first order, lambda0 > 0, all hinge reactions compressive). */
static int lambda0_by_equilibrium(const aq_geom *g, const aq_hinge_set *hs, double *l0)
{
  return aq_test_lambda0_eq(g, hs, l0) && *l0 > 0;
}

static void random_set(unsigned *seed, size_t n, aq_hinge_set *hs)
{
  size_t j[4];
  for (;;) {
    for (int k = 0; k < 4; k++) {
      *seed = *seed * 1103515245u + 12345u;
      j[k] = (size_t)((*seed >> 8) % (n + 1));
    }
    /* sort */
    for (int a = 0; a < 4; a++)
      for (int b = a + 1; b < 4; b++)
        if (j[b] < j[a]) {
          size_t t = j[a];
          j[a] = j[b];
          j[b] = t;
        }
    if (j[0] < j[1] && j[1] < j[2] && j[2] < j[3])
      break;
  }
  *seed = *seed * 1103515245u + 12345u;
  int pat = (*seed >> 12) & 1;
  for (int k = 0; k < 4; k++) {
    hs->joint[k] = j[k];
    hs->face[k] = (k + pat) % 2 ? 'i' : 'e';
  }
}

AQ_TEST(arch_search_beats_random_sets)
{
  gsl_set_error_handler_off();
  aq_arch *a = NULL;
  aq_error e;
  if (!aq_check(aq_arch_load("arches/search.cfg", &a, &e) == AQ_OK, "load"))
    return;
  aq_check(aq_arch_searched(a), "primary came from the search");
  const aq_geom *g = aq_arch_geom(a);
  const aq_path *p = aq_arch_path(a, 0);
  double best;
  aq_check(lambda0_by_equilibrium(g, &aq_workpath_mech(aq_arch_workpath(a, 0))->hs, &best),
           "the found set is admissible by the 9x9");
  aq_check_rel(p->lambda0, best, TIE_TOL, "its lambda0 by virtual work = by the 9x9");
  unsigned seed = 20261122u;
  int found = 0, tries = 0, above = 0, outside = 0;
  while (found < 1000 && tries < 200000) {
    aq_hinge_set hs;
    double l0;
    tries++;
    random_set(&seed, g->p.voussoirs, &hs);
    if (!lambda0_by_equilibrium(g, &hs, &l0))
      continue;
    found++;
    /* uniqueness: a set above the minimum cannot keep its line of thrust
     * inside the arch (else its lambda0 would also be a lower bound) */
    if (l0 > p->lambda0 * (1 + 1e-9)) {
      aq_mech m;
      aq_mech_state st;
      aq_equil eq;
      aq_mech_init(&m, g, &hs, &e);
      aq_mech_eval(&m, 0.0, &st);
      double wx = 0;
      for (int b = 0; b < 3; b++)
        wx += m.body[b].mass_kg * st.c[b][1].x;
      aq_live live = {AQ_LIVE_HORIZONTAL, m.open[0] * wx > 0 ? -1 : 1, {0, 0}, 0, 9.80665};
      aq_mech_equilibrium(&m, &st, &live, &eq, &e);
      double ecc[64];
      outside += aq_mech_thrust(&m, &st, &live, &eq, ecc, NULL) > 1.0;
      above++;
    }
    aq_check(p->lambda0 <= l0 * (1 + TIE_TOL), "search %.12g <= random %.12g (%zu %zu %zu %zu %c%c%c%c)",
             p->lambda0, l0, hs.joint[0], hs.joint[1], hs.joint[2], hs.joint[3],
             hs.face[0], hs.face[1], hs.face[2], hs.face[3]);
  }
  aq_check(found == 1000, "1000 random admissible sets (%d tries)", tries);
  aq_check(above > 0 && outside == above, "thrust escapes for all %d sets above the minimum (%d)",
           above, outside);
  aq_check(aq_workpath_thrust0(aq_arch_workpath(a, 0)) <= 1.0, "the minimum keeps it inside");
  aq_arch_free(a);
}

/* A small arch, every alternating set by brute force with the 9x9. */
AQ_TEST(arch_search_brute_force)
{
  gsl_set_error_handler_off();
  aq_arch_params pp = aq_arch_circular(2.73, 0.517, 143.0 * AQ_DEG_RAD, 9, 1711.0, 0.63);
  aq_geom g;
  aq_error e;
  aq_check(aq_geom_init(&g, &pp, &e) == AQ_OK, "geometry");
  double best = HUGE_VAL;
  for (int pat = 0; pat < 2; pat++)
    for (size_t a = 0; a <= 9; a++)
      for (size_t b = a + 1; b <= 9; b++)
        for (size_t c = b + 1; c <= 9; c++)
          for (size_t d = c + 1; d <= 9; d++) {
            aq_hinge_set hs = {{a, b, c, d}, {'e', 'i', 'e', 'i'}};
            if (pat)
              hs = (aq_hinge_set){{a, b, c, d}, {'i', 'e', 'i', 'e'}};
            double l0;
            if (lambda0_by_equilibrium(&g, &hs, &l0) && l0 < best)
              best = l0;
          }
  aq_hinge_set found;
  double lsearch = 0;
  aq_check(aq_search_minimum(&g, 9.80665, &found, &lsearch, NULL, &e) == AQ_OK && lsearch > 0,
           "search");
  double l0;
  aq_check(lambda0_by_equilibrium(&g, &found, &l0), "found set admissible");
  aq_check_rel(l0, best, TIE_TOL, "search = brute force");
  aq_geom_free(&g);
}

/* A published case that states every parameter: the minimum thickness of a
 * semicircular arch with radial joints under its own weight, t/R = 0.1075
 * (R the centre-line radius; Milankovitch 1907, as quoted by Heyman, "The
 * Stone Skeleton", 1995, and by Alexakis & Makris, Int. J. Arch. Heritage
 * 2014), with the haunch hinges at 54.5 deg from the crown.  At that
 * thickness the horizontal acceleration that turns the arch into a
 * four-hinge mechanism falls to zero, so the searched lambda0(t/R) crosses
 * zero there.  The crossing is taken by the secant through t/R = 0.109 and
 * 0.110 (60 voussoirs of 3 deg: the hinges sit on joints, so 0.0005 is
 * allowed); lambda0 does not depend on R, density, depth or g, so those are
 * arbitrary here.  Unlike the KCLC case (test_arch_equilibrium.c), nothing
 * was chosen to fit. */
static int searched(double t_over_r, double *lambda0, int joint[4])
{
  char d[512], path[700], cmd[900], out[4096], err[4096];
  aq_test_tmpdir(d, sizeof d);
  snprintf(path, sizeof path, "%s/mt.cfg", d);
  FILE *f = fopen(path, "w");
  if (!f)
    return 0;
  fprintf(f, "[arch]\nname = minthick\nradius_m = 2.385\nthickness_m = %.17g\n"
             "embrace_deg = 180\nvoussoirs = 60\ndensity_kg_m3 = 2137\ndepth_m = 0.71\n",
          t_over_r * 2.385);
  fclose(f);
  snprintf(cmd, sizeof cmd, "mechanism --arch %s", path);
  if (aq_test_run(cmd, out, sizeof out, err, sizeof err) != 0)
    return 0;
  char *row = strchr(out, '\n');
  return row && sscanf(row + 1, "primary\t%d,%d,%d,%d\t%*s\t%lf", &joint[0], &joint[1],
                       &joint[2], &joint[3], lambda0) == 5;
}

AQ_TEST(arch_search_minimum_thickness_semicircle)
{
  double l1, l2;
  int j1[4], j2[4];
  if (!aq_check(searched(0.109, &l1, j1) && searched(0.110, &l2, j2), "mechanism runs"))
    return;
  double zero = 0.109 - l1 * (0.110 - 0.109) / (l2 - l1);
  aq_check_abs(zero, 0.1075, 0.0005, "lambda0 = 0 at t/R (secant through %g, %g)", l1, l2);
  /* joints from the springing at 3 deg each: the haunch hinges */
  double haunch_deg = 90.0 - 3.0 * j1[1], other_deg = 3.0 * j1[3] - 90.0;
  aq_check_abs(haunch_deg, 54.5, 1.5, "first haunch hinge from the crown (joint %d)", j1[1]);
  aq_check_abs(other_deg, 54.5, 1.5, "second haunch hinge from the crown (joint %d)", j1[3]);
  aq_check(j1[2] == 30, "a hinge at the crown (joint %d)", j1[2]);
}

/* Every set on every face pattern (16, not only the alternating two) by
 * brute force with the 9x9: the search's minimum is the brute force's, on
 * arches that stand (embraces 180, 151.3 and 97 deg, t/R 0.15-0.6, 8-11
 * voussoirs), including the flat thick ones where a mechanism with a joint
 * lifting off (not a four-hinge set) has the lowest multiplier and the
 * search branches past it, and those with no admissible four-hinge set at
 * all.  On a symmetric arch the mirror images tie and the search takes the
 * lower face pattern: e i e i. */
AQ_TEST(arch_search_every_face_pattern)
{
  gsl_set_error_handler_off();
  static const double embrace_deg[] = {180, 151.3, 97};
  static const double t_over_r[] = {0.15, 0.31, 0.6};
  int nonalternating = 0, cases = 0, none = 0, liftoff = 0;
  for (size_t ie = 0; ie < 3; ie++)
    for (size_t it = 0; it < 3; it++)
      for (size_t n = 8; n <= 11; n++) {
        aq_arch_params pp = aq_arch_circular(2.91, 2.91 * t_over_r[it], embrace_deg[ie] * AQ_DEG_RAD, n,
                             1913.0, 0.77);
        aq_geom g;
        aq_error e;
        if (!aq_check(aq_geom_init(&g, &pp, &e) == AQ_OK, "geometry"))
          return;
        double best = HUGE_VAL;
        aq_hinge_set arg = {{0, 0, 0, 0}, {0, 0, 0, 0}};
        for (int pat = 0; pat < 16; pat++)
          for (size_t a = 0; a <= n; a++)
            for (size_t b = a + 1; b <= n; b++)
              for (size_t c = b + 1; c <= n; c++)
                for (size_t d = c + 1; d <= n; d++) {
                  aq_hinge_set hs = {{a, b, c, d}, {0, 0, 0, 0}};
                  for (int k = 0; k < 4; k++)
                    hs.face[k] = (pat >> (3 - k)) & 1 ? 'i' : 'e';
                  double l0;
                  if (aq_test_lambda0_eq(&g, &hs, &l0)) {
                    nonalternating += pat != 5 && pat != 10;
                    if (l0 < best * (1 - TIE_TOL)) {
                      best = l0;
                      arg = hs;
                    }
                  }
                }
        aq_hinge_set found;
        double got = 0, eq = 0;
        aq_search_info info;
        aq_status st = aq_search_minimum(&g, 9.80665, &found, &got, &info, &e);
        if (best == HUGE_VAL) { /* no four-hinge set at all (a joint lifts off) */
          aq_check(st == AQ_EINADMISSIBLE, "embrace %.1f, t/R %.2f, %zu voussoirs: no set, and "
                   "the search finds none (status %d)", embrace_deg[ie], t_over_r[it], n, (int)st);
          none++;
          aq_geom_free(&g);
          continue;
        }
        aq_check(st == AQ_OK, "embrace %.1f, t/R %.2f, %zu voussoirs: search", embrace_deg[ie],
                 t_over_r[it], n);
        aq_check(best > 0, "the arch stands (brute-force minimum %.6g)", best);
        aq_check_rel(got, best, TIE_TOL, "embrace %.1f, t/R %.2f, %zu voussoirs: search = brute force",
                     embrace_deg[ie], t_over_r[it], n);
        aq_check(aq_test_lambda0_eq(&g, &found, &eq), "the found set is admissible by the 9x9");
        aq_check_rel(eq, best, TIE_TOL, "its lambda0 by the 9x9");
        /* the brute force keeps the first of the mirror pair it meets, in
         * the order of face patterns (e i e i = 5 before i e i e = 10) */
        char want[64], got_set[64];
        aq_hinge_set_text(&arg, want, sizeof want);
        aq_hinge_set_text(&found, got_set, sizeof got_set);
        aq_check(!strcmp(want, got_set), "the same set, ties to the lower pattern: %s, %s", want,
                 got_set);
        if (info.liftoff) { /* a lift-off mechanism below every four-hinge set */
          liftoff++;
          aq_check(info.liftoff_lambda < got && info.programs > 2,
                   "lift-off %.6g below the minimum %.6g, found by branching (%zu programs)",
                   info.liftoff_lambda, got, info.programs);
        }
        cases++;
        aq_geom_free(&g);
      }
  aq_check(cases + none == 36 && none < 8, "36 arches, %d with no four-hinge set", none);
  aq_check(liftoff > 0 && liftoff < cases, "%d of %d arches where a joint lifting off governs",
           liftoff, cases);
  aq_check(nonalternating > 0, "non-alternating admissible sets exist (%d), so the 16 patterns "
           "were needed", nonalternating);
}

/* Shallow parabolic arches just above the flat limit (span 10 m, t 0.6 m,
 * 20 voussoirs, rise 0.75-0.8 m): a joint lifting off governs, and the
 * four-way branching past inadmissible sets reaches the same branch (set of
 * excluded rows) by many orders of exclusion.  The search must settle on
 * the brute force's minimum over every set and face pattern (16 x 5985
 * sets, 9x9), within its budget of programs. */
AQ_TEST(arch_search_shallow_parabolic_settles)
{
  gsl_set_error_handler_off();
  static const double rises[] = {0.75, 0.8};
  for (size_t ir = 0; ir < 2; ir++) {
    aq_arch_params pp = aq_arch_circular(1, 0.6, 3.14159265358979, 20, 2000, 1);
    pp.shape = AQ_SHAPE_PARABOLIC;
    pp.span_m = 10;
    pp.rise_m = rises[ir];
    aq_geom g;
    aq_error e;
    if (!aq_check(aq_geom_init(&g, &pp, &e) == AQ_OK, "geometry, rise %.2f", rises[ir]))
      return;
    size_t n = 20;
    double best = HUGE_VAL;
    for (int pat = 0; pat < 16; pat++)
      for (size_t a = 0; a <= n; a++)
        for (size_t b = a + 1; b <= n; b++)
          for (size_t c = b + 1; c <= n; c++)
            for (size_t d = c + 1; d <= n; d++) {
              aq_hinge_set hs = {{a, b, c, d}, {0, 0, 0, 0}};
              for (int k = 0; k < 4; k++)
                hs.face[k] = (pat >> (3 - k)) & 1 ? 'i' : 'e';
              double l0;
              if (aq_test_lambda0_eq(&g, &hs, &l0) && l0 < best)
                best = l0;
            }
    aq_hinge_set found;
    double got = 0;
    aq_search_info info;
    aq_status st = aq_search_minimum(&g, 9.80665, &found, &got, &info, &e);
    if (aq_check(st == AQ_OK, "rise %.2f: the search settles (%zu programs): %s", rises[ir],
                 info.programs, st == AQ_OK ? "" : e.message))
      aq_check_rel(got, best, 1e-9, "rise %.2f: search = brute force over 16 x 5985 sets",
                   rises[ir]);
    aq_geom_free(&g);
  }
}
