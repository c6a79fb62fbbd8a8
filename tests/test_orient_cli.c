/* test_orient_cli.c: ground motions from two horizontal components through
 * the command line: the projection against the test's own, the half turn
 * against --polarity reversed, the worst azimuth of a case built to have a
 * known one, -j, and the refusals. */
#define _POSIX_C_SOURCE 200809L
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"

#define H1 "tests/data/records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"
#define H2 "tests/data/records/RSN6_IMPVALL.I_I-ELC270-hor2.AT2"
#define RAW " --no-filter --detrend none"

static char out[65536], out2[65536], err[16384];

/* Column index of name in the header line of text, or -1. */
static int col_of(const char *text, const char *name)
{
  size_t hl = strcspn(text, "\n"), len = strlen(name);
  int col = 0;
  for (const char *p = text; p < text + hl; col++) {
    size_t w = strcspn(p, "\t\n");
    if (w == len && strncmp(p, name, len) == 0)
      return col;
    p += w;
    if (*p != '\t')
      break;
    p++;
  }
  return -1;
}

/* Cell (row 1-based, column col) into buf. */
static const char *cell(const char *text, size_t row, int col, char *buf, size_t n)
{
  const char *p = text;
  for (size_t r = 0; r < row && p; r++) {
    p = strchr(p, '\n');
    p = p ? p + 1 : NULL;
  }
  buf[0] = '\0';
  for (int c = 0; p && *p && c < col; c++) {
    p += strcspn(p, "\t\n");
    p = *p == '\t' ? p + 1 : NULL;
  }
  if (p)
    snprintf(buf, n, "%.*s", (int)strcspn(p, "\t\n"), p);
  return buf;
}

static double cell_d(const char *text, size_t row, const char *name)
{
  char b[128];
  return strtod(cell(text, row, col_of(text, name), b, sizeof b), NULL);
}

/* 1 if rows ra of a and rb of b agree, as text, in every column but skip[]. */
static int rows_equal(const char *a, size_t ra, const char *b, size_t rb,
                      const char *const *skip, size_t nskip, char *why, size_t nwhy)
{
  char ha[4096];
  snprintf(ha, sizeof ha, "%.*s", (int)strcspn(a, "\n"), a);
  int col = 0;
  char *save = NULL;
  for (char *t = strtok_r(ha, "\t", &save); t; t = strtok_r(NULL, "\t", &save), col++) {
    int skipped = 0;
    for (size_t k = 0; k < nskip; k++)
      skipped |= strcmp(t, skip[k]) == 0;
    if (skipped)
      continue;
    char ca[256], cb[256];
    cell(a, ra, col, ca, sizeof ca);
    cell(b, rb, col_of(b, t), cb, sizeof cb);
    if (strcmp(ca, cb) != 0 || !ca[0]) {
      snprintf(why, nwhy, "%s: \"%s\" and \"%s\"", t, ca, cb);
      return 0;
    }
  }
  snprintf(why, nwhy, "%d columns", col);
  return 1;
}

/* Write a CSV record of n samples at dt_s (time, acceleration in m/s2),
 * sample i being f(i, ctx); 1 on success. */
static int write_series(const char *path, int n, double dt_s,
                        double (*f)(int i, const void *ctx), const void *ctx)
{
  FILE *fp = fopen(path, "w");
  if (!aq_check(fp != NULL, "write %s", path))
    return 0;
  fputs("time,acc (m/s2)\n", fp);
  for (int i = 0; i < n; i++)
    fprintf(fp, "%.3f,%.17g\n", dt_s * i, f(i, ctx));
  return aq_check(fclose(fp) == 0, "close %s", path);
}

/* A rectangular pulse of *ctx m/s2 over samples 20..49. */
static double pulse(int i, const void *ctx)
{
  return i >= 20 && i < 50 ? *(const double *)ctx : 0.0;
}

static double wave(int i, const void *ctx)
{
  return *(const double *)ctx * sin(0.0385 * i);
}

/* -1.5 g at sample 300, else 0. */
static double lift_sample(int i, const void *ctx)
{
  (void)ctx;
  return i == 300 ? -1.5 * 9.80665 : 0.0;
}

/* The test's own projection: cos of the angle reduced to [0, 360), the
 * half turn taken out (docs/dynamics.md states the rule). */
static double own_cos_deg(double d)
{
  d = fmod(d, 360.0);
  if (d < 0)
    d += 360.0;
  return d >= 180.0 ? -cos((d - 180.0) * (3.14159265358979323846 / 180.0))
                    : cos(d * (3.14159265358979323846 / 180.0));
}

/* Read the pair H1, H2 (PEER: 5372 and 5346 samples); 1 on success (free
 * both in any case). */
static int read_pair(aq_record *r1, aq_record *r2)
{
  aq_error e;
  memset(r1, 0, sizeof *r1);
  memset(r2, 0, sizeof *r2);
  int ok = aq_record_read(H1, NULL, r1, &e) == AQ_OK && aq_record_read(H2, NULL, r2, &e) == AQ_OK;
  return aq_check(ok && r1->npts == 5372 && r2->npts == 5346, "PEER: 5372 and 5346 samples");
}

/* A CSV of c1 a1 + c2 a2 over the 5346 samples both have; 1 on success. */
static int write_projection(const char *csv, double c1, double c2, const aq_record *r1,
                            const aq_record *r2)
{
  FILE *f = fopen(csv, "w");
  if (!aq_check(f != NULL, "write %s", csv))
    return 0;
  fputs("time,acc (m/s2)\n", f);
  for (size_t i = 0; i < 5346; i++)
    fprintf(f, "%.2f,%.17g\n", 0.01 * (double)i, c1 * r1->acc_mps2[i] + c2 * r2->acc_mps2[i]);
  return aq_check(fclose(f) == 0, "close %s", csv);
}

/* The main job on a CSV of a1 cos(theta - 180) + a2 cos(theta - 270), written
 * here from the two records, equals --components at --azimuth theta to the
 * last digit (processing off: filtering a sum is not bit for bit the sum of
 * the filtered components). */
AQ_TEST(orient_projection_equals_own_csv)
{
  char dir[512], csv[700], args[2048];
  aq_test_tmpdir(dir, sizeof dir);
  aq_record r1, r2;
  int ok = read_pair(&r1, &r2);
  static const double thetas[] = {30, 247.5};
  for (size_t t = 0; ok && t < 2; t++) {
    double th = thetas[t], c1 = own_cos_deg(th - 180), c2 = own_cos_deg(th - 270);
    aq_check(fabs(c1 - cos((th - 180) * 3.14159265358979323846 / 180)) < 1e-15 &&
                 fabs(c2 - cos((th - 270) * 3.14159265358979323846 / 180)) < 1e-15,
             "own rule = plain cos at %g deg", th);
    snprintf(csv, sizeof csv, "%s/elc-%g.csv", dir, th);
    if (!write_projection(csv, c1, c2, &r1, &r2))
      break;
    snprintf(args, sizeof args, "%s --arch arches/thin.cfg --arch arches/oppenheim.cfg "
                                "--scale 0.5,2.2 -j 2" RAW, csv);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    snprintf(args, sizeof args, "--components " H1 "," H2 " --azimuth %g --arch "
                                "arches/thin.cfg --arch arches/oppenheim.cfg "
                                "--scale 0.5,2.2 -j 2" RAW, th);
    int rc2 = aq_test_run(args, out2, sizeof out2, err, sizeof err);
    /* 2 arches x 2 scales x both polarities (one azimuth: the sign is not covered) */
    aq_check(rc == 0 && rc2 == 0 && aq_test_count_lines(out) == 9 &&
                 aq_test_count_lines(out2) == 9,
             "%g deg: 8 rows each (%d %d): %s", th, rc, rc2, err);
    static const char *const skip[] = {"record", "azimuth_deg"};
    int collapsed = 0;
    for (size_t r = 1; r <= 8; r++) {
      char why[600];
      aq_check(rows_equal(out, r, out2, r, skip, 2, why, sizeof why),
               "%g deg row %zu: CSV = --components: %s", th, r, why);
      collapsed += cell_d(out, r, "collapsed") == 1;
    }
    aq_check(cell_d(out2, 1, "azimuth_deg") == th, "azimuth column %g", th);
    if (t == 0)
      aq_check(collapsed > 0 && collapsed < 8, "both verdicts among the rows (%d)", collapsed);
  }
  /* --scale-to-pga scales a motion by the peak of its horizontal vector,
   * the same at every azimuth */
  double peak = 0;
  for (size_t i = 0; ok && i < 5346; i++)
    peak = fmax(peak, sqrt(r1.acc_mps2[i] * r1.acc_mps2[i] + r2.acc_mps2[i] * r2.acc_mps2[i]));
  int rc = aq_test_run("--components " H1 "," H2 " --azimuth all:90 --all-azimuths "
                       "--scale-to-pga 0.5 --arch arches/thin.cfg" RAW,
                       out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && aq_test_count_lines(out) == 5, "--scale-to-pga: 4 azimuths: %s", err);
  for (size_t r = 1; r <= 4; r++)
    aq_check_rel(cell_d(out, r, "scale"), 0.5 * 9.80665 / peak, 1e-15,
                 "row %zu: scale %.17g = 0.5 g / the vector's peak %.17g m/s2", r,
                 cell_d(out, r, "scale"), peak);
  aq_record_free(&r1);
  aq_record_free(&r2);
}

/* theta + 180 deg is the negated motion: every row equals --polarity
 * reversed at theta (default processing, each component processed once). */
AQ_TEST(orient_half_turn_is_reversed_polarity)
{
  int rc = aq_test_run("--components " H1 "," H2 " --azimuth 215 --arch arches/thin.cfg "
                       "--arch arches/oppenheim.cfg --scale 0.5,2.2 --polarity normal",
                       out, sizeof out, err, sizeof err);
  int rc2 = aq_test_run("--components " H1 "," H2 " --azimuth 35 --polarity reversed "
                        "--arch arches/thin.cfg --arch arches/oppenheim.cfg --scale 0.5,2.2",
                        out2, sizeof out2, err, sizeof err);
  aq_check(rc == 0 && rc2 == 0 && aq_test_count_lines(out) == 5, "runs: %s", err);
  static const char *const skip[] = {"azimuth_deg", "polarity"};
  for (size_t r = 1; r <= 4; r++) {
    char why[600];
    aq_check(rows_equal(out, r, out2, r, skip, 2, why, sizeof why),
             "row %zu: 215 deg = 35 deg reversed: %s", r, why);
  }
}

/* A case with a known worst azimuth: the same rectangular pulse A on both
 * components (azimuths 0 and 90) gives a_x = A (cos theta + sin theta), of
 * largest magnitude sqrt(2) A at 45 deg (positive) and 225 deg (negative).
 * The plain pulse run both ways says which sign is worse; the scan must
 * find that azimuth, the same for every -j. */
AQ_TEST(orient_scan_finds_known_worst_and_is_deterministic)
{
  char dir[512], p1[700], p2[700], args[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(p1, sizeof p1, "%s/pulse-a.csv", dir);
  snprintf(p2, sizeof p2, "%s/pulse-b.csv", dir);
  double amp = 2.385 * sqrt(2.0);
  if (!write_series(p1, 600, 0.01, pulse, &amp))
    return;
  /* the plain pulse of amplitude sqrt(2) A, both ways */
  snprintf(args, sizeof args, "%s --arch arches/thin.cfg --polarity both" RAW, p1);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && aq_test_count_lines(out) == 3, "pulse both ways: %s", err);
  double tn = cell_d(out, 1, "collapse_time_s"), tr = cell_d(out, 2, "collapse_time_s");
  double qn = cell_d(out, 1, "peak_rotation_over_qc"), qr = cell_d(out, 2, "peak_rotation_over_qc");
  int rev_worse = (isnan(tn) && !isnan(tr)) || (!isnan(tn) && !isnan(tr) && tr < tn) ||
                  (isnan(tn) && isnan(tr) && qr > qn);
  double want = rev_worse ? 225 : 45;
  /* half the pulse: the components are A each, so the 45 deg projection is
   * sqrt(2) A */
  amp = 2.385;
  if (!write_series(p1, 600, 0.01, pulse, &amp) || !write_series(p2, 600, 0.01, pulse, &amp))
    return;
  static char first[65536];
  for (int j = 1; j <= 3; j++) {
    snprintf(args, sizeof args, "--components %s,%s --azimuths 0,90 --azimuth all "
                                "--arch arches/thin.cfg --arch arches/oppenheim.cfg -j %d" RAW,
             p1, p2, j);
    rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 0 && aq_test_count_lines(out) == 3, "-j %d: one row per arch (%zu lines): %s",
             j, aq_test_count_lines(out), err);
    double az = cell_d(out, 1, "azimuth_deg");
    if (j == 1) {
      aq_check(az == want, "thin: worst azimuth %g deg, expected %g (%s worse)", az, want,
               rev_worse ? "negative" : "positive");
      snprintf(first, sizeof first, "%s", out);
    } else {
      aq_check(strcmp(out, first) == 0, "-j %d: the same TSV as -j 1", j);
    }
  }
  /* --all-azimuths: 72 rows per arch, the worst row among them */
  snprintf(args, sizeof args, "--components %s,%s --azimuths 0,90 --azimuth all "
                              "--all-azimuths --arch arches/thin.cfg --arch "
                              "arches/oppenheim.cfg -j 2" RAW, p1, p2);
  rc = aq_test_run(args, out2, sizeof out2, err, sizeof err);
  aq_check(rc == 0 && aq_test_count_lines(out2) == 1 + 2 * 72, "72 rows per arch: %zu",
           aq_test_count_lines(out2));
  size_t r = 1 + (size_t)(want / 5);
  char why[600];
  aq_check(rows_equal(first, 1, out2, r, NULL, 0, why, sizeof why),
           "the worst row is row %zu of the scan: %s", r, why);
  /* the results file keeps every azimuth's run, the TSV only the worst */
  char h5[700];
  snprintf(h5, sizeof h5, "%s/scan.h5", dir);
  snprintf(args, sizeof args, "--components %s,%s --azimuths 0,90 --azimuth all:10 "
                              "--arch arches/thin.cfg -o %s" RAW, p1, p2, h5);
  rc = aq_test_run(args, out2, sizeof out2, err, sizeof err);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = rc == 0 ? H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT) : -1;
  hid_t d = f >= 0 ? H5Dopen2(f, "/summary", H5P_DEFAULT) : -1;
  hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
  hssize_t n = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
  hid_t t = d >= 0 ? H5Dget_type(d) : -1;
  aq_check(n == 36 && t >= 0 && H5Tget_member_index(t, "azimuth_deg") >= 0 &&
               aq_test_count_lines(out2) == 2,
           "HDF5: 36 summary rows with azimuth_deg (%lld), TSV one row: %s", (long long)n, err);
  if (t >= 0)
    H5Tclose(t);
  if (sp >= 0)
    H5Sclose(sp);
  if (d >= 0)
    H5Dclose(d);
  if (f >= 0)
    H5Fclose(f);
}

AQ_TEST(orient_refusals)
{
  char dir[512], a[700], b[700], args[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(a, sizeof a, "%s/a.csv", dir);
  snprintf(b, sizeof b, "%s/b.csv", dir);
  double amp = 0.3;
  if (!write_series(a, 300, 0.01, wave, &amp) || !write_series(b, 300, 0.02, wave, &amp))
    return;
  snprintf(args, sizeof args, "--components %s,%s --arch arches/thin.cfg", a, b);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "--azimuths") && strstr(err, "H1"),
           "no azimuths: refused (%d): %s", rc, err);
  snprintf(args, sizeof args, "--components %s,%s --azimuths 0,80 --arch arches/thin.cfg", a, b);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "orthogonal") && strstr(err, "80"),
           "80 deg apart: refused (%d): %s", rc, err);
  snprintf(args, sizeof args, "--components %s,%s --azimuths 0,90 --arch arches/thin.cfg", a, b);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strstr(err, b) && strstr(err, "dt") && strstr(err, "0.02"),
           "dt 0.01 and 0.02: refused naming the file (%d): %s", rc, err);
  char st[64];
  aq_check(col_of(out, "status") >= 0 &&
               strncmp(cell(out, 1, col_of(out, "status"), st, sizeof st), "read:", 5) == 0,
           "its row has no verdict: %s", st);
  snprintf(args, sizeof args, "--components %s,%s --azimuths 0,90 --arch arches/thin.cfg "
                              "--text %s", a, b, b);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  char *kept = aq_test_read_file(b, NULL);
  aq_check(rc == 2 && strstr(err, "inputs") && kept && strncmp(kept, "time,", 5) == 0,
           "--text onto a component refused, the file kept (%d): %s", rc, err);
  free(kept);
  rc = aq_test_run("--components " H1 "," H2 " --all-azimuths --arch arches/thin.cfg", out,
                   sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--all-azimuths"), "--all-azimuths alone (%d): %s", rc, err);
  rc = aq_test_run(H1 " --azimuth 30 --arch arches/thin.cfg", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--azimuth"), "--azimuth without --components: %s", err);
  rc = aq_test_run("--components " H1 " --arch arches/thin.cfg", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "H1,H2"), "one component: %s", err);
  rc = aq_test_run("--components " H1 "," H1 " --arch arches/thin.cfg", out, sizeof out, err,
                   sizeof err);
  aq_check(rc == 2 && strstr(err, "distinct"), "the same file twice: %s", err);
  rc = aq_test_run("--azimuths 0,90 --components " H1 "," H2 " --arch arches/thin.cfg", out,
                   sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--azimuths"), "--azimuths before --components: %s", err);
  /* a vertical given without --vertical is ignored, and the output says so */
  snprintf(args, sizeof args, "--components " H1 "," H2 ",%s --arch arches/thin.cfg", a);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strstr(err, "ignored") && strstr(err, a) && aq_test_count_lines(out) == 3,
           "V without --vertical ignored with a warning (%d): %s", rc, err);
}

/* The vertical through the command line: ignored without --vertical (the
 * TSV byte-identical to the pair's), run with it, and a sample with
 * g + a_v <= 0 stops the run with run:eliftoff naming the time. */
AQ_TEST(orient_vertical_cli)
{
  char dir[512], v[700], lift[700], args[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(v, sizeof v, "%s/up.csv", dir);
  snprintf(lift, sizeof lift, "%s/lift.csv", dir);
  double amp = 4.0;
  if (!write_series(v, 5346, 0.01, wave, &amp) || !write_series(lift, 5346, 0.01, lift_sample, NULL))
    return;
  static char base[65536];
  int rc = aq_test_run("--components " H1 "," H2 " --azimuth 30 --arch arches/thin.cfg "
                       "--arch arches/oppenheim.cfg --scale 0.5,2.2" RAW,
                       base, sizeof base, err, sizeof err);
  snprintf(args, sizeof args, "--components " H1 "," H2 ",%s --azimuth 30 --arch "
                              "arches/thin.cfg --arch arches/oppenheim.cfg --scale 0.5,2.2" RAW, v);
  int rc2 = aq_test_run(args, out, sizeof out, err, sizeof err);
  static const char *const skip_rec[] = {"record"};
  int same = aq_test_count_lines(out) == 9; /* 2 arches x 2 scales x both polarities */
  char why[600] = "";
  for (size_t r = 1; same && r <= 8; r++)
    same = rows_equal(base, r, out, r, skip_rec, 1, why, sizeof why);
  aq_check(rc == 0 && rc2 == 0 && same && strstr(err, "ignored") && strstr(err, v),
           "V without --vertical: the pair's rows (%s), and a warning: %s", why, err);
  char args_v[2100];
  snprintf(args_v, sizeof args_v, "%s --vertical", args);
  rc = aq_test_run(args_v, out2, sizeof out2, err, sizeof err);
  aq_check(rc == 0 && aq_test_count_lines(out2) == 9 && strcmp(out2, base) != 0 &&
               !strstr(err, "ignored"),
           "with --vertical: run, and other results (%d): %s", rc, err);
  int differ = 0;
  for (size_t r = 1; r <= 8; r++)
    differ += cell_d(out2, r, "peak_rotation_rad") != cell_d(base, r, "peak_rotation_rad");
  aq_check(differ >= 2, "the vertical changes the peaks of %d of 8 runs", differ);
  snprintf(args, sizeof args, "--components " H1 "," H2 ",%s --vertical --azimuth 30 --arch "
                              "arches/oppenheim.cfg --scale 0.9" RAW, lift);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  char st[64];
  aq_check(rc == 1 && strcmp(cell(out, 1, col_of(out, "status"), st, sizeof st), "run:eliftoff") == 0 &&
               strstr(err, "t = 3.000 s") && strstr(err, "leaves the ground"),
           "lift-off: status %s, exit %d: %s", st, rc, err);
}

/* ---- archquake capacity with ground motions ------------------------------- */

#define CAP_RES " --resolution 0.05 --tol 1e-5"

/* capacity --components at --azimuth theta equals capacity on a CSV of the
 * test's own projection, in every column of the record's table. */
AQ_TEST(orient_capacity_equals_own_csv)
{
  char dir[512], csv[700], args[2048];
  aq_record r1, r2;
  int ok = read_pair(&r1, &r2);
  aq_test_tmpdir(dir, sizeof dir);
  for (double th = 30; ok && th < 360; th += 217.5) { /* 30 and 247.5 deg */
    snprintf(csv, sizeof csv, "%s/cap-%g.csv", dir, th);
    if (!write_projection(csv, own_cos_deg(th - 180), own_cos_deg(th - 270), &r1, &r2))
      break;
    snprintf(args, sizeof args, "capacity %s --arch arches/thin.cfg -j 2" CAP_RES RAW, csv);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    snprintf(args, sizeof args, "capacity --components " H1 "," H2 " --azimuth %g --arch "
                                "arches/thin.cfg -j 2" CAP_RES RAW, th);
    int rc2 = aq_test_run(args, out2, sizeof out2, err, sizeof err);
    aq_check(rc == 0 && rc2 == 0 && aq_test_count_lines(out) == 3 &&
                 aq_test_count_lines(out2) == 3,
             "%g deg: 2 rows each (%d %d): %s", th, rc, rc2, err);
    static const char *const skip[] = {"record"};
    for (size_t r = 1; r <= 2; r++) {
      char why[600];
      aq_check(rows_equal(out, r, out2, r, skip, 1, why, sizeof why),
               "%g deg row %zu: capacity on the CSV = --components: %s", th, r, why);
    }
    double fc = cell_d(out2, 1, "first_collapse_scale");
    aq_check(fc > 0 && cell_d(out2, 1, "azimuth_deg") == th &&
                 cell_d(out2, 1, "first_collapse_scale_min") == fc &&
                 cell_d(out2, 1, "first_collapse_scale_max") == fc,
             "%g deg: first collapse %.17g, one azimuth: its own range", th, fc);
  }
  aq_record_free(&r1);
  aq_record_free(&r2);
}

/* --azimuth all:STEP: each row is the azimuth of the lowest first collapse
 * among separate --azimuth runs, with their range (reversed polarity: its
 * worst azimuth is not the scan's first). */
AQ_TEST(orient_capacity_scan_is_min_of_single_runs)
{
  char args[1024];
  int rc = aq_test_run("capacity --components " H1 "," H2 " --azimuth all:60 --polarity "
                       "reversed --arch arches/thin.cfg -j 2" CAP_RES RAW,
                       out2, sizeof out2, err, sizeof err);
  aq_check(rc == 0 && aq_test_count_lines(out2) == 2, "scan: one row (%d): %s", rc, err);
  double lo = INFINITY, hi = -INFINITY, at = NAN;
  for (int z = 0; z < 6; z++) {
    snprintf(args, sizeof args, "capacity --components " H1 "," H2 " --azimuth %d --polarity "
                                "reversed --arch arches/thin.cfg -j 2" CAP_RES RAW, 60 * z);
    rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    double f = cell_d(out, 1, "first_collapse_scale");
    aq_check(rc == 0 && f > 0, "%d deg: first collapse %.17g: %s", 60 * z, f, err);
    if (f < lo) {
      lo = f;
      at = 60 * z;
    }
    hi = fmax(hi, f);
  }
  if (getenv("AQ_TEST_VERBOSE"))
    fprintf(stderr, "  first collapse over 0..300 deg: %.6g (at %g deg) to %.6g\n", lo, at, hi);
  aq_check(lo < hi, "the azimuth matters: %.17g to %.17g", lo, hi);
  aq_check(cell_d(out2, 1, "first_collapse_scale") == lo &&
               cell_d(out2, 1, "azimuth_deg") == at &&
               cell_d(out2, 1, "first_collapse_scale_min") == lo &&
               cell_d(out2, 1, "first_collapse_scale_max") == hi,
           "worst row %.17g at %g deg = min of the runs %.17g at %g; max %.17g = %.17g",
           cell_d(out2, 1, "first_collapse_scale"), cell_d(out2, 1, "azimuth_deg"), lo, at,
           cell_d(out2, 1, "first_collapse_scale_max"), hi);
}

/* A constant vertical c (scaled with the motion) moves the threshold to
 * lambda0 (g + s c): the move scale s_v = s_0 (1 + s_v c / g). */
AQ_TEST(orient_capacity_constant_vertical)
{
  char dir[512], v[700], args[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(v, sizeof v, "%s/const.csv", dir);
  double c = 1.5;
  FILE *f = fopen(v, "w");
  if (!aq_check(f != NULL, "write %s", v))
    return;
  fputs("time,acc (m/s2)\n", f);
  for (int i = 0; i < 5346; i++)
    fprintf(f, "%.2f,%.17g\n", 0.01 * i, c);
  fclose(f);
  int rc = aq_test_run("capacity --components " H1 "," H2 " --azimuth 30 --polarity normal "
                       "--arch arches/thin.cfg" CAP_RES RAW, out, sizeof out, err, sizeof err);
  snprintf(args, sizeof args, "capacity --components " H1 "," H2 ",%s --vertical --azimuth 30 "
                              "--polarity normal --arch arches/thin.cfg" CAP_RES RAW, v);
  int rc2 = aq_test_run(args, out2, sizeof out2, err, sizeof err);
  double s0 = cell_d(out, 1, "move_scale"), sv = cell_d(out2, 1, "move_scale");
  aq_check(rc == 0 && rc2 == 0 && s0 > 0 && sv > s0, "move scales %.17g, %.17g: %s", s0, sv, err);
  aq_check_rel(sv / s0, 1 + sv * c / 9.80665, 1e-13, "s_v / s_0 = %.17g, 1 + s_v c / g = %.17g",
               sv / s0, 1 + sv * c / 9.80665);
  rc = aq_test_run("capacity --components " H1 "," H2 " --azimuth all --all-azimuths --arch "
                   "arches/thin.cfg", out, sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--all-azimuths"), "--all-azimuths refused: %s", err);
  rc = aq_test_run("capacity --components " H1 "," H2 " -o x.h5 --arch arches/thin.cfg", out,
                   sizeof out, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "-o"), "-o with --components refused: %s", err);
}
