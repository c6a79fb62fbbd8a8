/* test_dyn_cli.c: the pulse and domain commands end to end. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"

static char out[8192], err[8192];

static int count_lines(const char *s, const char *prefix)
{
  int n = 0;
  for (const char *p = s; p && *p;) {
    if (strncmp(p, prefix, strlen(prefix)) == 0)
      n++;
    p = strchr(p, '\n');
    if (p)
      p++;
  }
  return n;
}

/* Field k (0-based) of the second line of a TSV output. */
static double field(const char *tsv, int k)
{
  const char *p = strchr(tsv, '\n');
  if (!p)
    return NAN;
  p++;
  for (int i = 0; i < k && p; i++) {
    p = strchr(p, '\t');
    if (p)
      p++;
  }
  return p ? strtod(p, NULL) : NAN;
}

AQ_TEST(dyn_cli_pulse_row_and_models)
{
  int rc = aq_test_run("pulse --arch arches/oppenheim.cfg --accel-g -0.61 "
                       "--duration 0.43 --end 4 --cor 0.6",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "exit 0, got %d: %s", rc, err);
  const char *hdr = "model\taccel_g\tduration_s\tend_s\tcollapsed\t"
                    "collapse_time_s\tpeak_rotation_rad\tpeak_displacement_m\t"
                    "max_kinetic_energy_j\timpacts\t";
  aq_check(strncmp(out, hdr, strlen(hdr)) == 0, "header: %.80s", out);
  aq_check(strncmp(strchr(out, '\n') + 1, "workpath\t-0.61\t0.43\t4\t0\tnan\t", 27) == 0,
           "row starts with the options: %.60s", strchr(out, '\n') + 1);
  double q_wp = field(out, 6), x_wp = field(out, 7), imp_wp = field(out, 9);
  rc = aq_test_run("pulse --arch arches/oppenheim.cfg --accel-g -0.61 "
                   "--duration 0.43 --end 4 --cor 0.6 --model ode --ode-rtol 1e-12",
                   out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "ode exit 0");
  /* printed whole (the shortest decimal that reads back), they differ by
     2.5e-14 and 2.7e-14 (0 when the row had 12 digits) */
  aq_check_rel(q_wp, field(out, 6), 1e-13, "peak rotation: workpath vs ode");
  aq_check_rel(x_wp, field(out, 7), 1e-13, "peak displacement: workpath vs ode");
  aq_check(imp_wp == field(out, 9) && imp_wp >= 2, "same impacts (%g)", imp_wp);
}

/* The domain's duration brackets the collapse in the pulse command. */
AQ_TEST(dyn_cli_domain_brackets_pulse)
{
  int rc = aq_test_run("domain --arch arches/oppenheim.cfg --ratios 2.37",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "domain exit 0: %s", err);
  double a = field(out, 1), T = field(out, 2);
  char cmd[256];
  snprintf(cmd, sizeof cmd,
           "pulse --arch arches/oppenheim.cfg --accel-g %.12g --duration %.12g "
           "--cor 0 --dt 100",
           a, T * (1 + 1e-7));
  aq_test_run(cmd, out, sizeof out, err, sizeof err);
  aq_check(field(out, 4) == 1, "collapses just above: %s", out);
  snprintf(cmd, sizeof cmd,
           "pulse --arch arches/oppenheim.cfg --accel-g %.12g --duration %.12g "
           "--cor 0 --dt 100",
           a, T * (1 - 1e-7));
  aq_test_run(cmd, out, sizeof out, err, sizeof err);
  aq_check(field(out, 4) == 0, "survives just below: %s", out);
}

AQ_TEST(dyn_cli_pulse_history)
{
  char dir[512], cmd[1024], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/h.csv", dir);
  snprintf(cmd, sizeof cmd,
           "pulse --arch arches/oppenheim.cfg --accel-g -0.55 --duration 0.5 "
           "--end 2.5 --dt 0.02 --cor 1 --history %s",
           path);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "exit 0: %s", err);
  FILE *f = fopen(path, "r");
  aq_check(f != NULL, "history written");
  if (!f)
    return;
  char line[512];
  int rows = 0;
  double t = 0, e0 = NAN, emax = 0;
  int extra = 0;
  aq_check(fgets(line, sizeof line, f) &&
               strcmp(line, "time_s,rotation_rad,displacement_m,"
                            "kinetic_energy_j,potential_energy_j,set\n") == 0,
           "csv header");
  while (fgets(line, sizeof line, f)) {
    double q, x, ke, pe;
    int set;
    if (sscanf(line, "%lf,%lf,%lf,%lf,%lf,%d", &t, &q, &x, &ke, &pe, &set) != 6)
      break;
    if (fabs(t / 0.02 - round(t / 0.02)) > 1e-6) {
      extra++; /* a turning point or an impact between step ends */
      continue;
    }
    rows++;
    if (rows == 25)
      e0 = ke + pe;
    if (rows > 25)
      emax = fmax(emax, fabs(ke + pe - e0) / e0);
  }
  fclose(f);
  aq_check(rows == 125, "one row per 0.02 s step: %d", rows);
  aq_check(extra > 0, "rows at turning points and impacts too: %d", extra);
  aq_check_abs(t, 2.5, 5e-15, "last row at --end");
  aq_check(emax < 1e-9, "COR 1: KE + PE constant in the file (%.3g)", emax);
}

AQ_TEST(dyn_cli_bad_options)
{
  int rc = aq_test_run("pulse --accel-g x --duration -1 --model foo --cor 2 "
                       "--bogus",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 2, "usage exit 2, got %d", rc);
  aq_check(out[0] == '\0', "nothing on stdout");
  aq_check(strstr(err, "--accel-g") && strstr(err, "--duration") &&
               strstr(err, "--model") && strstr(err, "--cor") &&
               strstr(err, "--bogus") && strstr(err, "--arch"),
           "every bad option named: %s", err);
  aq_check(count_lines(err, "archquake: ") >= 6, "one line each: %s", err);

  rc = aq_test_run("domain --arch arches/oppenheim.cfg --ratios 0.5,2 --cor -1",
                   out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--ratios") && strstr(err, "--cor"),
           "domain: ratios <= 1 and cor < 0 refused: %s", err);
  rc = aq_test_run("domain --help", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(out, "usage: archquake domain"), "domain --help");
  rc = aq_test_run("pulse --help", out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(out, "usage: archquake pulse"), "pulse --help");
  rc = aq_test_run("pulse --arch tests/no-such.cfg --accel-g 1 --duration 1",
                   out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "no-such.cfg"), "missing arch file: %s", err);
}

/* A history that cannot be written: exit 3, no row printed, no file left. */
AQ_TEST(dyn_cli_history_unwritable)
{
  char dir[512], cmd[1024];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(cmd, sizeof cmd,
           "pulse --arch arches/oppenheim.cfg --accel-g -0.6 --duration 0.3 "
           "--history %s/missing/h.csv",
           dir);
  int rc = aq_test_run(cmd, out, sizeof out, err, sizeof err);
  aq_check(rc == 3, "exit 3, got %d", rc);
  aq_check(out[0] == '\0', "no row printed");
  snprintf(cmd, sizeof cmd, "%s/missing", dir);
  aq_check(access(cmd, F_OK) != 0, "nothing created");
}

/* Default end (no --end): a COR 0 pulse rests after one impact.  The end is
 * the first duration + k s after the rest that an explicit long run's
 * history shows, and the row is that of the long run (and exactly that of
 * --end end_s). */
AQ_TEST(dyn_cli_pulse_default_end_rests)
{
  static char out2[8192];
  char dir[512], cmd[1024], path[600];
  const double dur = 0.371, dt = 0.01;
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/long.csv", dir);
  int rc = aq_test_run("pulse --arch arches/oppenheim.cfg --accel-g -0.587 "
                       "--duration 0.371 --cor 0",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && err[0] == '\0', "exit 0, no note: %d %s", rc, err);
  double end = field(out, 3);
  aq_check(field(out, 4) == 0 && field(out, 9) == 1, "survives, 1 impact: %s",
           out);
  snprintf(cmd, sizeof cmd,
           "pulse --arch arches/oppenheim.cfg --accel-g -0.587 --duration 0.371 "
           "--cor 0 --end 40 --history %s",
           path);
  rc = aq_test_run(cmd, out2, sizeof out2, err, sizeof err);
  aq_check(rc == 0, "long run exit 0: %s", err);
  for (int k = 6; k <= 12; k++)
    if (k != 10 && k != 11)
      aq_check_rel(field(out, k), field(out2, k), 1e-15, "column %d as --end 40", k);
  aq_check(field(out, 9) == field(out2, 9), "impacts as --end 40");
  /* the first step end at rest after the last one in motion */
  FILE *f = fopen(path, "r");
  aq_check(f != NULL, "history written");
  if (!f)
    return;
  char line[512];
  double t, q, x, ke, pe, t_rest = NAN;
  int set, prev = -1;
  while (fgets(line, sizeof line, f))
    if (sscanf(line, "%lf,%lf,%lf,%lf,%lf,%d", &t, &q, &x, &ke, &pe, &set) == 6) {
      if (set == -1 && prev != -1)
        t_rest = t;
      prev = set;
    }
  fclose(f);
  aq_check(t_rest > dur && prev == -1, "the long run rests at %g", t_rest);
  double k = end - dur;
  aq_check_abs(k, round(k), 1e-15, "end_s = duration + whole seconds (%g)", end);
  aq_check(end >= t_rest - dt && end - 1 < t_rest,
           "end_s %g: the first duration + k s at rest (rest in (%g, %g])", end,
           t_rest - dt, t_rest);
  snprintf(cmd, sizeof cmd,
           "pulse --arch arches/oppenheim.cfg --accel-g -0.587 --duration 0.371 "
           "--cor 0 --end %.9g",
           end);
  rc = aq_test_run(cmd, out2, sizeof out2, err, sizeof err);
  aq_check(rc == 0 && strcmp(out, out2) == 0, "row = that of --end %g:\n%s%s",
           end, out, out2);
  /* collapse: the end is the first duration + k s after the collapse */
  rc = aq_test_run("pulse --arch arches/oppenheim.cfg --accel-g -0.5 "
                   "--duration 0.9 --cor 0",
                   out, sizeof out, err, sizeof err);
  double tc = field(out, 5);
  end = field(out, 3);
  aq_check(rc == 0 && field(out, 4) == 1 && tc > 0.9, "collapses: %s", out);
  aq_check(end >= tc && end - 1 < tc, "end_s %g just after collapse %g", end, tc);
}

/* Default end, COR 1: the motion never rests; the cap stops it with a
 * one-line note, exit 0, and the row is that of --end cap. */
AQ_TEST(dyn_cli_pulse_default_end_cap)
{
  static char out2[8192];
  int rc = aq_test_run("pulse --arch arches/oppenheim.cfg --accel-g -0.587 "
                       "--duration 0.371 --cor 1 --max-end 13.7",
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "exit 0 at the cap, got %d", rc);
  aq_check(count_lines(err, "archquake: ") == 1 && strstr(err, "cap") &&
               strchr(err, '\n') == err + strlen(err) - 1,
           "one-line note: %s", err);
  aq_check(field(out, 3) == 13.7 && field(out, 4) == 0 && field(out, 9) >= 10,
           "ends at the cap, still rocking: %s", out);
  rc = aq_test_run("pulse --arch arches/oppenheim.cfg --accel-g -0.587 "
                   "--duration 0.371 --cor 1 --end 13.7",
                   out2, sizeof out2, err, sizeof err);
  aq_check(rc == 0 && err[0] == '\0' && strcmp(out, out2) == 0,
           "row = that of --end 13.7:\n%s%s", out, out2);
  rc = aq_test_run("pulse --arch arches/oppenheim.cfg --accel-g -0.587 "
                   "--duration 0.371 --end 3 --max-end 0.2",
                   out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--max-end") && out[0] == '\0',
           "--max-end with --end, or below --duration: usage: %s", err);
}
