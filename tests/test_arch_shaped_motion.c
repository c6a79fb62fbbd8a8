/* test_arch_shaped_motion.c: the shaped arches (pointed arches/gothic.cfg,
 * elliptical arches/bridge.cfg with its fill and point mass, catenary
 * arches/catenary.cfg, the joints arch arches/vertical.cfg) under ground
 * motions through the command line: two horizontal components against the
 * test's own projection, and with the vertical, the work path against the
 * ode.  The vertical's closed forms and the library-level work path
 * against the ode on these arches are in test_orient_vertical.c; the MPI
 * program on them in tests/mpi.sh. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define PI 3.14159265358979323846

/* ---- through the command line ----------------------------------------- */

#define H1 "tests/data/records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"
#define H2 "tests/data/records/RSN6_IMPVALL.I_I-ELC270-hor2.AT2"
#define SHAPED_ARGS                                                                           \
  " --arch arches/gothic.cfg --arch arches/bridge.cfg --arch arches/catenary.cfg --arch "    \
  "arches/vertical.cfg --scale 3,9 --no-filter --detrend none"
#define NROWS 8 /* 4 arches x 2 scales */

static char out[65536], out2[65536], err[16384];

/* Column of name in tsv's header, or -1. */
static int column(const char *tsv, const char *name)
{
  char b[128];
  for (int k = 0; k < 64; k++)
    if (!strcmp(aq_test_tsv_field(tsv, 0, k, b, sizeof b), name))
      return k;
  return -1;
}

static double num(const char *tsv, int row, const char *name)
{
  char b[128];
  return strtod(aq_test_tsv_field(tsv, row, column(tsv, name), b, sizeof b), NULL);
}

/* 1 if row r of a and of b agree as text in every column but record and
 * azimuth_deg (the first differing column into why). */
static int same_row(const char *a, const char *b, int r, char *why, size_t nwhy)
{
  char h[128], ca[256], cb[256];
  for (int k = 0; *aq_test_tsv_field(a, 0, k, h, sizeof h); k++) {
    if (!strcmp(h, "record") || !strcmp(h, "azimuth_deg"))
      continue;
    aq_test_tsv_field(a, r, k, ca, sizeof ca);
    aq_test_tsv_field(b, r, column(b, h), cb, sizeof cb);
    if (strcmp(ca, cb) || !ca[0]) {
      snprintf(why, nwhy, "%.60s: \"%.100s\" and \"%.100s\"", h, ca, cb);
      return 0;
    }
  }
  return 1;
}

/* The test's own projection of the pair (azimuths 180 and 270 deg) onto the
 * arch's plane at azimuth theta_deg in [270, 360): a1 cos(theta - 180) +
 * a2 cos(theta - 270) over the 5346 samples both have, written to csv
 * (time, m/s^2).  Both angles lie in [0, 180), where docs/dynamics.md's
 * rule takes the cosine as it is.  1 on success. */
static int write_projection(const char *csv, double theta_deg)
{
  aq_record r1, r2;
  aq_error e;
  memset(&r1, 0, sizeof r1);
  memset(&r2, 0, sizeof r2);
  int ok = aq_record_read(H1, NULL, &r1, &e) == AQ_OK && aq_record_read(H2, NULL, &r2, &e) == AQ_OK;
  ok = aq_check(ok && r1.npts == 5372 && r2.npts == 5346, "PEER pair: 5372 and 5346 samples");
  double c1 = cos((theta_deg - 180) * (PI / 180)), c2 = cos((theta_deg - 270) * (PI / 180));
  FILE *f = ok ? fopen(csv, "w") : NULL;
  if (f) {
    fputs("time,acc (m/s2)\n", f);
    for (size_t i = 0; i < 5346; i++)
      fprintf(f, "%.2f,%.17g\n", 0.01 * (double)i, c1 * r1.acc_mps2[i] + c2 * r2.acc_mps2[i]);
    ok = aq_check(fclose(f) == 0, "close %s", csv);
  }
  aq_record_free(&r1);
  aq_record_free(&r2);
  return ok && f;
}

/* --components H1,H2 --azimuth theta on the shaped arches equals the main
 * job on a CSV of the projection written here, to the last digit (the
 * processing off: filtering a sum is not bit for bit the sum of the
 * filtered components).  At 300 deg the pair is rotated so that the
 * components weigh -0.5 and +0.866. */
AQ_TEST(arch_shaped_components_equal_own_projection)
{
  char dir[512], csv[700], args[2048];
  aq_test_tmpdir(dir, sizeof dir);
  const double th = 300;
  snprintf(csv, sizeof csv, "%s/proj.csv", dir);
  if (!write_projection(csv, th))
    return;
  snprintf(args, sizeof args, "%s -j 2" SHAPED_ARGS, csv);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  snprintf(args, sizeof args, "--components " H1 "," H2 " --azimuth %g -j 2" SHAPED_ARGS, th);
  int rc2 = aq_test_run(args, out2, sizeof out2, err, sizeof err);
  aq_check(rc == 0 && rc2 == 0 && aq_test_count_lines(out) == NROWS + 1 &&
               aq_test_count_lines(out2) == NROWS + 1,
           "%d rows each (%d %d): %s", NROWS, rc, rc2, err);
  int collapsed = 0, moved = 0;
  for (int r = 1; r <= NROWS; r++) {
    char why[600], arch[64];
    aq_test_tsv_field(out, r, column(out, "arch"), arch, sizeof arch);
    aq_check(same_row(out, out2, r, why, sizeof why), "row %d (%s): CSV = --components: %s",
             r, arch, why);
    collapsed += num(out2, r, "collapsed") == 1;
    moved += num(out2, r, "peak_rotation_rad") > 0;
    aq_check(num(out2, r, "azimuth_deg") == th, "row %d: azimuth column %g", r, th);
  }
  aq_check(collapsed > 0 && moved > collapsed, "rows that collapse (%d) and that rock (%d)",
           collapsed, moved - collapsed);
}

/* --vertical on the shaped arches through the command line: the work path
 * against --model ode on the same runs (the same events; peak rotation to
 * 5e-14 and largest kinetic energy to 5e-11 relative, collapse times to
 * 1e-12 s; measured 4.4e-16, 5.9e-13, 1.3e-14 s), and the vertical
 * changes the results. */
AQ_TEST(arch_shaped_vertical_cli_workpath_vs_ode)
{
  char dir[512], v[700], args[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(v, sizeof v, "%s/up.csv", dir);
  FILE *f = fopen(v, "w");
  if (!aq_check(f != NULL, "write %s", v))
    return;
  fputs("time,acc (m/s2)\n", f); /* up to 0.8 m/s^2, 7.2 at scale 9: g + a_v > 0 */
  for (int i = 0; i < 5346; i++)
    fprintf(f, "%.2f,%.17g\n", 0.01 * i, 0.8 * sin(0.0385 * i));
  if (!aq_check(fclose(f) == 0, "close %s", v))
    return;
  static char base[65536];
  int rc0 = aq_test_run("--components " H1 "," H2 " --azimuth 300 -j 2" SHAPED_ARGS, base,
                        sizeof base, err, sizeof err);
  snprintf(args, sizeof args, "--components " H1 "," H2 ",%s --vertical --azimuth 300 -j 2"
                              SHAPED_ARGS, v);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  char args_ode[2100];
  snprintf(args_ode, sizeof args_ode, "%s --model ode", args);
  int rc2 = aq_test_run(args_ode, out2, sizeof out2, err, sizeof err);
  aq_check(rc0 == 0 && rc == 0 && rc2 == 0 && aq_test_count_lines(out) == NROWS + 1 &&
               aq_test_count_lines(out2) == NROWS + 1 && aq_test_count_lines(base) == NROWS + 1,
           "%d rows each (%d %d %d): %s", NROWS, rc0, rc, rc2, err);
  double worst_q = 0, worst_t = 0, worst_ke = 0;
  int differ = 0, collapsed = 0;
  for (int r = 1; r <= NROWS; r++) {
    char arch[64];
    aq_test_tsv_field(out, r, column(out, "arch"), arch, sizeof arch);
    int c = (int)num(out, r, "collapsed");
    aq_check(c == (int)num(out2, r, "collapsed") &&
                 num(out, r, "impacts") == num(out2, r, "impacts"),
             "row %d (%s): the ode's events (collapsed %d, impacts %g %g)", r, arch, c,
             num(out, r, "impacts"), num(out2, r, "impacts"));
    double q = num(out, r, "peak_rotation_rad"), qo = num(out2, r, "peak_rotation_rad");
    double ke = num(out, r, "max_kinetic_energy_j"), keo = num(out2, r, "max_kinetic_energy_j");
    double eq = qo > 0 ? fabs(q / qo - 1) : fabs(q), eke = keo > 0 ? fabs(ke / keo - 1) : fabs(ke);
    double et = c ? fabs(num(out, r, "collapse_time_s") - num(out2, r, "collapse_time_s")) : 0;
    worst_q = fmax(worst_q, eq), worst_ke = fmax(worst_ke, eke), worst_t = fmax(worst_t, et);
    aq_check(eq <= 5e-14 && eke <= 5e-11 && et <= 1e-12,
             "row %d (%s): from the ode: peak rotation %.3g, max KE %.3g (relative), collapse "
             "time %.3g s", r, arch, eq, eke, et);
    collapsed += c;
    differ += num(base, r, "max_kinetic_energy_j") != ke;
  }
  if (getenv("AQ_TEST_VERBOSE"))
    fprintf(stderr, "  --vertical, work path vs ode: rotation %.3g, KE %.3g, collapse %.3g s\n",
            worst_q, worst_ke, worst_t);
  aq_check(collapsed >= 2 && collapsed < NROWS && differ >= NROWS - 1,
           "collapses %d of %d; the vertical changes %d of them", collapsed, NROWS, differ);
}
