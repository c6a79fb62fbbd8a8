/* test_capacity_points.c: the scanned scales that `archquake capacity -o`
 * keeps in capacity/scan_points (docs/capacity.md).
 *
 * The file is read here with the HDF5 API alone (a compound type of our
 * own, fields matched by name), and every stored run is compared with the
 * main job run at the same scale (`archquake RECORD --arch A --scale
 * LIST`): a second path through the code (record read and processed, steps
 * made, one stepper per run, summary written as text) that shares only the
 * stepper.  The case is San Fernando (RSN77) on the shipped oppenheim arch
 * with COR 0.5, where the arch collapses from 1.94, survives from 3.67 to
 * 3.75 and collapses again (test_capacity_cli.c checks those changes
 * against a brute-force scan). */
#include <hdf5.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#define REC "tests/data/records/RSN77_SFERN_PUL164-hor1.AT2"
#define ARCH "arches/oppenheim.cfg"
#define PROC " --cor 0.5 --detrend mean --taper 0.05 --highpass 0.05"

enum { BIG = 1 << 20, MAXP = 4096 };

/* The main job prints %.17g and both paths run the same stepper on the same
 * samples: agreement is to the last bits (measured 0); this allows the
 * scale being applied to the samples in another order. */
static const double REL_SAME_RUN = 1e-12;

typedef struct {
  int64_t pair, collapsed;
  double scale, peak_rad, peak_qc, t_s;
} point;

/* Field k (0-based) of data row `row` (1-based after the header) of a TSV. */
static const char *field(const char *tsv, int row, int k, char *buf, size_t n)
{
  const char *p = tsv;
  for (int r = 0; r < row && p; r++) {
    p = strchr(p, '\n');
    if (p)
      p++;
  }
  for (int i = 0; i < k && p; i++) {
    p = strpbrk(p, "\t\n");
    p = p && *p == '\t' ? p + 1 : NULL;
  }
  buf[0] = '\0';
  if (!p)
    return buf;
  size_t m = strcspn(p, "\t\n");
  snprintf(buf, n, "%.*s", (int)(m < n ? m : n - 1), p);
  return buf;
}

/* capacity/scan_points of h5 into p[MAXP]; the count, or -1. */
static long read_points(const char *h5, point *p)
{
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    return -1;
  hid_t d = H5Dopen2(f, "capacity/scan_points", H5P_DEFAULT);
  hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
  hssize_t n = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
  hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(point));
  H5Tinsert(t, "pair", HOFFSET(point, pair), H5T_NATIVE_INT64);
  H5Tinsert(t, "collapsed", HOFFSET(point, collapsed), H5T_NATIVE_INT64);
  H5Tinsert(t, "scale", HOFFSET(point, scale), H5T_NATIVE_DOUBLE);
  H5Tinsert(t, "peak_rotation_rad", HOFFSET(point, peak_rad), H5T_NATIVE_DOUBLE);
  H5Tinsert(t, "peak_rotation_over_qc", HOFFSET(point, peak_qc), H5T_NATIVE_DOUBLE);
  H5Tinsert(t, "collapse_time_s", HOFFSET(point, t_s), H5T_NATIVE_DOUBLE);
  long rc = n >= 0 && n <= MAXP &&
                    H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, p) >= 0
                ? (long)n
                : -1;
  H5Tclose(t);
  if (sp >= 0)
    H5Sclose(sp);
  if (d >= 0)
    H5Dclose(d);
  H5Fclose(f);
  return rc;
}

AQ_TEST(capacity_points_match_main_job)
{
  char *out = malloc(BIG), *main_out = malloc(BIG), *args = malloc(MAXP * 26 + 512);
  point *p = malloc(MAXP * sizeof *p);
  char dir[512], h5[600], cell[8192];
  if (!out || !main_out || !args || !p)
    goto done;
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/cap.h5", dir);
  snprintf(args, 2048, "capacity " REC " --arch " ARCH PROC
           " --polarity normal --scale-max 4 -j 2 -o %s", h5);
  int rc = aq_test_run(args, out, BIG, NULL, 0);
  aq_check(rc == 0, "capacity exit %d", rc);
  long n = read_points(h5, p);
  long runs = atol(field(out, 1, 10, cell, sizeof cell));
  double move = strtod(field(out, 1, 4, cell, sizeof cell), NULL);
  double smax = strtod(field(out, 1, 11, cell, sizeof cell), NULL);
  aq_check(n > 100 && n == runs, "scan_points: %ld rows, runs %ld", n, runs);
  if (n <= 0)
    goto done;

  /* one row per run, increasing scale in (move_scale, scale_max], and the
     verdicts those the intervals (TSV) were built from */
  double iv[2][16];
  size_t niv = 0;
  const char *s = field(out, 1, 8, cell, sizeof cell);
  while (*s && *s != '-' && niv < 16) {
    char *end;
    iv[0][niv] = strtod(s, &end);
    iv[1][niv++] = strtod(end + 1, &end);
    s = *end == ';' ? end + 1 : "";
  }
  aq_check(niv == 2, "two collapse intervals (%zu)", niv);
  size_t bad_order = 0, bad_verdict = 0, resurrected = 0;
  for (long i = 0; i < n; i++) {
    int in = 0;
    for (size_t k = 0; k < niv; k++)
      in |= p[i].scale >= iv[0][k] && p[i].scale <= iv[1][k];
    bad_verdict += p[i].collapsed != in || p[i].pair != 0;
    bad_order += i ? !(p[i].scale > p[i - 1].scale) : !(p[i].scale > move);
    resurrected += !p[i].collapsed && p[i].scale > iv[0][0];
  }
  aq_check(bad_order == 0 && p[n - 1].scale == smax,
           "scales increase from move_scale %.9g to the cap %.9g (last %.9g; %zu out of "
           "order)", move, smax, p[n - 1].scale, bad_order);
  aq_check(bad_verdict == 0, "%zu rows disagree with the intervals", bad_verdict);
  aq_check(resurrected >= 2, "%zu survived runs above the first collapse", resurrected);

  /* the main job at every stored scale */
  size_t k = (size_t)snprintf(args, 512, REC " --arch " ARCH PROC " -j 2 --scale ");
  for (long i = 0; i < n; i++)
    k += (size_t)snprintf(args + k, 26, "%s%.17g", i ? "," : "", p[i].scale);
  rc = aq_test_run(args, main_out, BIG, NULL, 0);
  aq_check(rc == 0, "main job exit %d", rc);
  double worst = 0, worst_t = 0;
  size_t mismatch = 0;
  for (long i = 0; i < n; i++) {
    int r = (int)i + 1;
    double sc = strtod(field(main_out, r, 3, cell, sizeof cell), NULL);
    int col = atoi(field(main_out, r, 6, cell, sizeof cell));
    double t = strtod(field(main_out, r, 7, cell, sizeof cell), NULL);
    double pk = strtod(field(main_out, r, 8, cell, sizeof cell), NULL);
    double qc = strtod(field(main_out, r, 16, cell, sizeof cell), NULL);
    mismatch += sc != p[i].scale || col != p[i].collapsed ||
                isnan(t) != isnan(p[i].t_s) || !(pk > 0);
    worst = fmax(worst, fabs(pk - p[i].peak_rad) / pk);
    worst = fmax(worst, fabs(qc - p[i].peak_qc) / qc);
    if (col)
      worst_t = fmax(worst_t, fabs(t - p[i].t_s) / t);
  }
  aq_check(mismatch == 0, "%zu runs differ in scale, verdict or collapse", mismatch);
  aq_check(worst <= REL_SAME_RUN, "peak rotation and peak / q_c against the main job: "
           "worst relative difference %.3g over %ld runs", worst, n);
  aq_check(worst_t <= REL_SAME_RUN, "collapse times: worst relative difference %.3g",
           worst_t);
  /* collapsed runs end at q_c */
  for (long i = 0; i < n; i++)
    if (p[i].collapsed) {
      aq_check_rel(p[i].peak_qc, 1.0, REL_SAME_RUN, "a collapse peaks at q_c (scale %.9g)",
                   p[i].scale);
      break;
    }
done:
  free(out);
  free(main_out);
  free(args);
  free(p);
}

AQ_TEST(capacity_points_none_when_never_moves)
{
  /* a cap below the scale at which the arch first moves: no run, no row */
  char *out = malloc(BIG), dir[512], h5[600], args[1200];
  point p[4];
  if (!out)
    return;
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/cap.h5", dir);
  snprintf(args, sizeof args, "capacity " REC " --arch " ARCH PROC
           " --polarity normal --scale-max 0.2 -o %s", h5);
  int rc = aq_test_run(args, out, BIG, NULL, 0);
  char cell[64];
  aq_check(rc == 0 && strcmp(field(out, 1, 3, cell, sizeof cell), "never_moves") == 0,
           "exit %d, status %s", rc, cell);
  aq_check(read_points(h5, p) == 0, "scan_points is empty");
  free(out);
}
