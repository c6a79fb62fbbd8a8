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
        aq_hinge_set hs = {{0, 0, 0, 0}, {0, 0, 0, 0}};
        for (int pat = -1; aq_test_next_set(n, &pat, &hs);) {
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
 * 20 voussoirs, rise 0.7-0.9 m): a joint lifting off governs, and the
 * four-way branching past inadmissible sets reaches the same branch (set of
 * excluded rows) by many orders of exclusion; at 0.9 m no budget of
 * programs settles it.  The search must settle on the brute force's
 * minimum over every set and face pattern (16 x 5985 sets, 9x9).  At 0.7
 * m `mechanism` prints that minimum and warns once of the lift-off. */
AQ_TEST(arch_search_shallow_parabolic_settles)
{
  gsl_set_error_handler_off();
  static const double rises[] = {0.7, 0.75, 0.8, 0.9};
  for (size_t ir = 0; ir < 4; ir++) {
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
    aq_hinge_set hs = {{0, 0, 0, 0}, {0, 0, 0, 0}};
    for (int pat = -1; aq_test_next_set(n, &pat, &hs);) {
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
    if (ir == 0) { /* mechanism: the minimum, and one line naming the lift-off below it */
      char d[512], path[700], cmd[900], out[8192], err[4096];
      aq_test_tmpdir(d, sizeof d);
      snprintf(path, sizeof path, "%s/flat.cfg", d);
      FILE *f = fopen(path, "w");
      if (!aq_check(f != NULL, "write %s", path))
        return;
      fprintf(f, "[arch]\nname = flat\nshape = parabolic\nspan_m = 10\nrise_m = %g\n"
                 "thickness_m = 0.6\nvoussoirs = 20\ndensity_kg_m3 = 2000\ndepth_m = 1\n",
              rises[ir]);
      fclose(f);
      snprintf(cmd, sizeof cmd, "mechanism --arch %s", path);
      int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
      double l0 = 0, ll = 0, lw = 0;
      int joints[4];
      char *row = strstr(out, "\nminimum\t");
      aq_check(rc == 0 && row && sscanf(row + 1, "minimum\t%d,%d,%d,%d\t%*s\t%lf", &joints[0],
                                        &joints[1], &joints[2], &joints[3], &l0) == 5,
               "rise %.2f: mechanism runs and prints the minimum (%d): %s", rises[ir], rc, err);
      aq_check_rel(l0, best, 1e-9, "rise %.2f: mechanism's minimum = brute force", rises[ir]);
      const char *w = strstr(err, "lifts off has lambda = ");
      int lines = 0;
      for (const char *c = err; (c = strstr(c, "lifts off")) != NULL; c++)
        lines++;
      aq_check(lines == 1 && w && sscanf(w, "lifts off has lambda = %lf, below every four-hinge "
                                            "set's (%lf)", &ll, &lw) == 2 &&
                   strstr(w, "--model blocks") && ll < best && fabs(lw - best) <= 1e-5 * best,
               "rise %.2f: one warning line names the lift-off below the minimum and --model "
               "blocks: %s", rises[ir], err);
    }
    aq_geom_free(&g);
  }
}

/* The lowest lambda0 over every set of every face pattern by the 9x9
 * (arch_lambda0.h), for each direction (act_sign -1: [0], +1: [1]);
 * HUGE_VAL where a direction has none.  Independent of the search: no
 * linear program, no virtual work, no screen. */
static void brute_minima(const aq_geom *g, double best[2])
{
  size_t n = g->p.voussoirs;
  best[0] = best[1] = HUGE_VAL;
  aq_hinge_set hs = {{0, 0, 0, 0}, {0, 0, 0, 0}};
  for (int pat = -1; aq_test_next_set(n, &pat, &hs);) {
    double l0;
    int act;
    if (aq_test_lambda0_eq_act(g, &hs, &l0, &act) && l0 < best[act > 0])
      best[act > 0] = l0;
  }
}

/* The largest eccentricity of the line of thrust of hs at s = 0 under its
 * own lambda0 (> 1: it leaves the section at a joint that is not a hinge). */
static double thrust_ecc(const aq_geom *g, const aq_hinge_set *hs)
{
  aq_mech m;
  aq_mech_state st;
  aq_equil eq;
  aq_error e;
  double ecc[256];
  if (g->p.voussoirs >= 256 || aq_mech_init(&m, g, hs, &e) != AQ_OK ||
      aq_mech_eval(&m, 0.0, &st) != 0)
    return NAN;
  double wx = 0;
  for (int b = 0; b < 3; b++)
    wx += m.body[b].mass_kg * st.c[b][1].x;
  aq_live live = {AQ_LIVE_HORIZONTAL, m.open[0] * wx > 0 ? -1 : 1, {0, 0}, 0, 9.80665};
  if (aq_mech_equilibrium(&m, &st, &live, &eq, &e) != AQ_OK)
    return NAN;
  return aq_mech_thrust(&m, &st, &live, &eq, ecc, NULL);
}

/* Flat arches over a sweep of rises near the flat limit, (t/2)(1 + cos
 * phi) (docs/arch-model.md): parabolic (span 10 m, t 0.6 m, from 0.62 m),
 * segmental circular (R 10 m, t 0.6 m, embraces 41-70 deg: rises 0.63-1.8
 * m) and elliptical (span 10 m, t 0.6 m, rises 1.25-2.5 m: vertical
 * springings, so no strut ever fits; 1.22 m is where its faces fold), 12
 * voussoirs, and 13 with 800 kg on voussoir 3 (the directions differ), all
 * standing under their own weight.  Each direction's search (and the arch's
 * minimum) equals the 9x9 brute force over 16 x C(n + 1, 4) sets; where a
 * lift-off mechanism is reported below the four-hinge minimum, that
 * minimum's line of thrust leaves the section (no four-hinge set is then
 * statically admissible); both the branch and bound and the enumeration
 * that takes over when it runs out are exercised. */
AQ_TEST(arch_search_flat_sweep)
{
  gsl_set_error_handler_off();
  struct {
    aq_shape shape;
    double a, t; /* span (or radius), thickness */
    double rise[6]; /* rise (or embrace, deg) */
  } fam[] = {
      {AQ_SHAPE_PARABOLIC, 10, 0.6, {0.62, 0.7, 0.8, 0.9, 1.0, 1.2}},
      {AQ_SHAPE_CIRCULAR, 10, 0.6, {41, 45, 50, 55, 60, 70}},
      {AQ_SHAPE_ELLIPTICAL, 10, 0.6, {1.25, 1.4, 1.6, 1.8, 2.0, 2.5}},
  };
  int arches = 0, enumerated = 0, by_programs = 0, liftoff = 0, none = 0, asym = 0;
  for (size_t f = 0; f < 3; f++)
    for (size_t i = 0; i < 6; i++)
      for (size_t n = 12; n <= 13; n++) {
        aq_arch_params p = aq_arch_circular(fam[f].a, fam[f].t, fam[f].rise[i] * AQ_DEG_RAD, n,
                                            2000, 1);
        if (fam[f].shape != AQ_SHAPE_CIRCULAR) {
          p.shape = fam[f].shape;
          p.span_m = fam[f].a;
          p.rise_m = fam[f].rise[i];
        }
        aq_geom g;
        aq_error e;
        aq_point_mass pm = {"load", 3, {0, 0}, 800};
        if (n == 13 && aq_geom_init(&g, &p, &e) == AQ_OK) { /* 800 kg on voussoir 3: asymmetric */
          aq_vec2 a = aq_geom_joint_point(&g, 3, 'i'), b = aq_geom_joint_point(&g, 4, 'e');
          pm.p = (aq_vec2){0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
          p.nmass = 1;
          p.mass = &pm;
          aq_geom_free(&g);
        }
        if (!aq_check(aq_geom_init(&g, &p, &e) == AQ_OK, "%s %g, %zu voussoirs: geometry: %s",
                      aq_shape_names[fam[f].shape], fam[f].rise[i], n, e.message))
          continue;
        if (!aq_check(aq_geom_check_strut(&g, &e) == AQ_OK, "%s %g: not too flat: %s",
                      aq_shape_names[fam[f].shape], fam[f].rise[i], e.message)) {
          aq_geom_free(&g);
          continue;
        }
        arches++;
        double best[2];
        brute_minima(&g, best);
        asym += fabs(best[0] - best[1]) > 1e-6 * best[0];
        aq_check(fmin(best[0], best[1]) > 0, "%s %g, %zu voussoirs: stands (%g)",
                 aq_shape_names[fam[f].shape], fam[f].rise[i], n, fmin(best[0], best[1]));
        for (int d = 0; d < 3; d++) { /* act_sign -1, +1, then the arch's minimum */
          aq_hinge_set hs;
          double got = NAN, want = d < 2 ? best[d] : fmin(best[0], best[1]);
          aq_search_info info;
          memset(&info, 0, sizeof info);
          aq_status st = d < 2 ? aq_search_direction(&g, 9.80665, d ? 1 : -1, &hs, &got, &info, &e)
                               : aq_search_minimum(&g, 9.80665, &hs, &got, &info, &e);
          if (want == HUGE_VAL) {
            aq_check(st == AQ_EINADMISSIBLE, "%s %g, %zu voussoirs, %d: no set, none found (%d)",
                     aq_shape_names[fam[f].shape], fam[f].rise[i], n, d, (int)st);
            none++;
            continue;
          }
          if (!aq_check(st == AQ_OK, "%s %g, %zu voussoirs, %d: settles: %s",
                        aq_shape_names[fam[f].shape], fam[f].rise[i], n, d, e.message))
            continue;
          aq_check_rel(got, want, 1e-9, "%s %g, %zu voussoirs, %d: search = brute force (%zu "
                       "programs%s)", aq_shape_names[fam[f].shape], fam[f].rise[i], n, d,
                       info.programs, info.enumerated ? ", enumerated" : "");
          double l0;
          aq_check(aq_test_lambda0_eq(&g, &hs, &l0) && fabs(l0 - want) <= 1e-9 * fabs(want),
                   "the found set is admissible by the 9x9 with that lambda0");
          enumerated += info.enumerated;
          by_programs += !info.enumerated;
          if (info.liftoff && info.liftoff_lambda < got) {
            liftoff++;
            double ecc = thrust_ecc(&g, &hs);
            aq_check(ecc > 1, "%s %g, %zu voussoirs, %d: lift-off %.6g below the four-hinge "
                     "minimum %.6g, whose thrust leaves the section (ecc %.4g)",
                     aq_shape_names[fam[f].shape], fam[f].rise[i], n, d, info.liftoff_lambda,
                     got, ecc);
          }
        }
        aq_geom_free(&g);
      }
  aq_check(arches == 36 && asym >= 12, "36 arches (%d), %d whose directions differ", arches,
           asym);
  aq_check(enumerated > 0 && by_programs > 0 && liftoff > 0,
           "searches settled by enumeration %d, by the programs alone %d; lift-off below the "
           "four-hinge minimum %d; directions with no set %d", enumerated, by_programs, liftoff,
           none);
}

/* Flat arches whose work paths the tables refused before, for more than
 * 20000 intervals (docs/arch-model.md, "Tables"): the parabola of span 10
 * m, t 0.6 m at rise 0.7 m with 12 voussoirs (its primary) and at 0.85 m
 * with 20 (its reverse, act_sign +1).  They are built now; their Hermite
 * tables agree with the exact evaluation at 2000 random s to 1e-10 of each
 * quantity's largest magnitude on the path (what arch_tables_vs_exact asks
 * of the shipped arches), 1e-8 for the derivatives of interpolants
 * (d2x/ds2, d2y/ds2, dM/ds: measured 3e-9, round-off of the exact slopes
 * over h; the rise 0.85 m primary, tabled before too, has 3.4e-10), and a
 * pulse of either sign that collapses each arch gives the same collapse
 * time and peak rotation under the workpath model (the Taylor pieces,
 * fitted to the exact kinematics) as under the ode reference (which reads
 * the Hermite tables), to 1e-9. */
AQ_TEST(arch_flat_paths_tabled)
{
  gsl_set_error_handler_off();
  struct {
    double rise;
    int n;
    double accel_g, duration_s;
  } c[] = {{0.7, 12, 100, 0.05}, {0.85, 20, 40, 0.08}};
  unsigned seed = 20261129u;
  for (size_t i = 0; i < 2; i++) {
    char d[512], path[700], cmd[1024], out[4096], err[4096];
    aq_test_tmpdir(d, sizeof d);
    snprintf(path, sizeof path, "%s/flat%zu.cfg", d, i);
    FILE *f = fopen(path, "w");
    if (!aq_check(f != NULL, "write %s", path))
      return;
    fprintf(f, "[arch]\nname = flat\nshape = parabolic\nspan_m = 10\nrise_m = %g\n"
               "thickness_m = 0.6\nvoussoirs = %d\ndensity_kg_m3 = 2000\ndepth_m = 1\n",
            c[i].rise, c[i].n);
    fclose(f);
    aq_arch *a = NULL;
    aq_error e;
    if (!aq_check(aq_arch_load(path, &a, &e) == AQ_OK, "rise %g, %d voussoirs: built: %s",
                  c[i].rise, c[i].n, e.message))
      continue;
    for (int set = 0; set < 2; set++) {
      const aq_path *p = aq_arch_path(a, set);
      if (!aq_check(p->admissible, "rise %g set %d admissible", c[i].rise, set))
        continue;
      double sc[8] = {0}, worst[8] = {0};
      for (int k = 0; k <= 400; k++) {
        aq_path_point E;
        p->eval_exact(p->ctx, p->s_c_rad * k / 400.0, &E);
        double v[8] = {E.x_m, E.y_m, E.dx_m, E.dy_m, E.d2x_m, E.d2y_m, E.mgen_kgm2,
                       E.dmgen_kgm2};
        for (int q = 0; q < 8; q++)
          sc[q] = fmax(sc[q], fabs(v[q]));
      }
      for (int k = 0; k < 2000; k++) {
        seed = seed * 1103515245u + 12345u;
        double s = p->s_c_rad * (double)(seed >> 8) / 16777216.0;
        aq_path_point X, T;
        if (!aq_check(p->eval_exact(p->ctx, s, &X) == 0 && p->eval(p->ctx, s, &T) == 0,
                      "evaluates at s = %g", s))
          break;
        double dv[8] = {T.x_m - X.x_m, T.y_m - X.y_m, T.dx_m - X.dx_m, T.dy_m - X.dy_m,
                        T.d2x_m - X.d2x_m, T.d2y_m - X.d2y_m, T.mgen_kgm2 - X.mgen_kgm2,
                        T.dmgen_kgm2 - X.dmgen_kgm2};
        for (int q = 0; q < 8; q++)
          worst[q] = fmax(worst[q], fabs(dv[q]) / sc[q]);
      }
      for (int q = 0; q < 8; q++) /* d2x/ds2, d2y/ds2, dM/ds: derivatives of interpolants */
        aq_check(worst[q] <= (q == 4 || q == 5 || q == 7 ? 1e-8 : 1e-10),
                 "rise %g set %d quantity %d: table error %.3g", c[i].rise, set, q, worst[q]);
    }
    aq_arch_free(a);
    for (int sign = -1; sign <= 1; sign += 2) {
      int col[2] = {0, 0};
      double tc[2] = {0, 0}, peak[2] = {0, 0};
      for (int m = 0; m < 2; m++) {
        snprintf(cmd, sizeof cmd, "pulse --arch %s --accel-g %g --duration %g --model %s", path,
                 sign * c[i].accel_g, c[i].duration_s, m ? "ode" : "workpath");
        char *row = NULL;
        if (aq_test_run(cmd, out, sizeof out, err, sizeof err) == 0)
          row = strchr(out, '\n');
        aq_check(row && sscanf(row + 1, "%*s\t%*s\t%*s\t%*s\t%d\t%lf\t%lf", &col[m], &tc[m],
                               &peak[m]) == 3, "%s: %s", cmd, err);
      }
      aq_check(col[0] && col[1], "rise %g, %+g g: both models collapse", c[i].rise,
               sign * c[i].accel_g);
      aq_check_rel(tc[0], tc[1], 1e-9, "rise %g, %+g g: collapse time, workpath = ode",
                   c[i].rise, sign * c[i].accel_g);
      aq_check_rel(peak[0], peak[1], 1e-9, "rise %g, %+g g: peak rotation, workpath = ode",
                   c[i].rise, sign * c[i].accel_g);
    }
  }
}
