/* test_select_cli.c: `archquake select` end to end, and the suite it writes
 * run by the main job and capacity (--suite).
 *
 * - The chosen suite's conditions recomputed here with a spectrum of our
 *   own: each record read, its oscillators integrated by the classical
 *   fourth-order Runge-Kutta method on sub-steps of at most 0.04 rad, the
 *   input linear between samples, the peak where the suite file says its
 *   spectra take it: at the samples, at PEER's N = ceil(10 dt / T) points
 *   per interval (the NGA-West2 rule), or over continuous time (between
 *   sub-steps from the cubic through the two ends' displacement and
 *   velocity); the EC8 spectrum written here from EN 1998-1:2004 eqs.
 *   (3.2)-(3.5) and Table 3.2.
 * - A suite run with --suite gives the rows of its records run one by one
 *   at their scales; capacity's scales are then the suite's, its
 *   intensities at collapse the records' own.
 * - The event rule, --best-effort, the results file read back, the range
 *   from a fragility file, directories and globs as the pool, pairs.
 * - Bad input: one line each, nothing written. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "select_fixture.h"
#include "io/record.h"
#include "report/h5_select.h"

#define R "tests/data/records/"
#define G0 9.80665
#define PI 3.14159265358979323846
#define EC8B AQ_TEST_EC8B
enum { BIG = 1 << 20 };

static const char *const pool12 =
    R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2 " R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2 "
    R "RSN763_LOMAP_GIL067.AT2 " R "RSN763_LOMAP_GIL337.AT2 " R "ARL360.at2 "
    R "RSN77_SFERN_PUL164-hor1.AT2 " R "CHY028-N.AT2 " R "TCU052-N.AT2 "
    R "RSN1616_DUZCE_362-E.AT2 " R "RSN4843_CHUETSU_65006NS.AT2 "
    R "RSN4013_SANSIMEO_36258021.AT2 " R "kocaeli.csv";

/* The state's derivative: u' = v, v' = -a - 2 z w v - w^2 u. */
static void deriv(double u, double v, double a, double z, double w, double *du, double *dv)
{
  *du = v;
  *dv = -a - 2 * z * w * v - w * w * u;
}

/* Largest |u| of the cubic through (0, u0, v0) and (h, u1, v1) on [0, h]
 * where its slope vanishes inside. */
static double hermite_peak(double u0, double v0, double u1, double v1, double h)
{
  /* u(s) = u0 + v0 s + c2 s^2 + c3 s^3 */
  double c2 = (3 * (u1 - u0) / h - 2 * v0 - v1) / h;
  double c3 = (2 * (u0 - u1) / h + v0 + v1) / (h * h);
  double A = 3 * c3, B = 2 * c2, C = v0, roots[2];
  int n = 0;
  if (fabs(A) < 1e-300) {
    if (B != 0)
      roots[n++] = -C / B;
  } else {
    double D = B * B - 4 * A * C;
    if (D >= 0) {
      roots[n++] = (-B + sqrt(D)) / (2 * A);
      roots[n++] = (-B - sqrt(D)) / (2 * A);
    }
  }
  double m = 0;
  for (int i = 0; i < n; i++)
    if (roots[i] > 0 && roots[i] < h) {
      double s = roots[i];
      m = fmax(m, fabs(u0 + s * (v0 + s * (c2 + s * c3))));
    }
  return m;
}

/* Where the peak is taken. */
enum { PEAKS_SAMPLES = 0, PEAKS_EXACT, PEAKS_PEER };

/* PSA (m/s^2) at period T of acc (n samples at dt), 5 %: the peak at the
 * samples, over continuous time, or at PEER's N points per interval. */
static double psa_rk4(const double *acc, size_t n, double dt, double T, int mode)
{
  double z = 0.05, w = 2 * PI / T, u = 0, v = 0, peak = 0;
  size_t npeer = (size_t)ceil(10 * dt / T - 1e-9); /* PEER: N = ceil(10 dt / T) */
  if (npeer < 1 || mode != PEAKS_PEER)
    npeer = 1;
  size_t m = (size_t)ceil(w * dt / 0.04);
  m = npeer * ((m + npeer - 1) / npeer); /* the PEER points among the sub-steps */
  size_t every = m / npeer;
  double h = dt / (double)m;
  for (size_t i = 0; i + 1 < n; i++)
    for (size_t j = 0; j < m; j++) {
      double t0 = (double)j / (double)m, t1 = (double)(j + 1) / (double)m, th = 0.5 * (t0 + t1);
      double a0 = acc[i] + t0 * (acc[i + 1] - acc[i]), ah = acc[i] + th * (acc[i + 1] - acc[i]),
             a1 = acc[i] + t1 * (acc[i + 1] - acc[i]);
      double k1u, k1v, k2u, k2v, k3u, k3v, k4u, k4v;
      deriv(u, v, a0, z, w, &k1u, &k1v);
      deriv(u + 0.5 * h * k1u, v + 0.5 * h * k1v, ah, z, w, &k2u, &k2v);
      deriv(u + 0.5 * h * k2u, v + 0.5 * h * k2v, ah, z, w, &k3u, &k3v);
      deriv(u + h * k3u, v + h * k3v, a1, z, w, &k4u, &k4v);
      double un = u + h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
      double vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      if (mode == PEAKS_EXACT) {
        peak = fmax(peak, fabs(un));
        if ((v > 0) != (vn > 0))
          peak = fmax(peak, hermite_peak(u, v, un, vn, h));
      } else if ((j + 1) % every == 0)
        peak = fmax(peak, fabs(un));
      u = un;
      v = vn;
    }
  return w * w * peak;
}

/* The data rows of a suite file: the row of its header, or -1. */
static int header_row(const char *tsv)
{
  char b[64];
  for (int row = 0; row < 200; row++)
    if (!strcmp(aq_test_tsv_field(tsv, row, 0, b, sizeof b), "record"))
      return row;
  return -1;
}

/* The chosen suite meets EC8's conditions by a spectrum of our own: the
 * records as published (--no-filter --detrend none), the scales of the
 * suite file, the grid and misfit of its results file; for each rule of
 * --peaks (the default first). */
static void conditions_by_own_spectrum(const char *peaks)
{
  char dir[256], args[2048], err[8192], b[512];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args, "select %s --target " EC8B " --count 7 --no-filter --detrend "
           "none %s -o %s/s.h5 --text %s/s.tsv", pool12, peaks, dir, dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  if (!aq_check(rc == 0, "exit %d: %s", rc, err))
    return;
  snprintf(b, sizeof b, "%s/s.tsv", dir);
  char *tsv = aq_test_read_file(b, NULL);
  snprintf(b, sizeof b, "%s/s.h5", dir);
  aq_h5_select_file f;
  aq_error e;
  if (!aq_check(tsv && aq_h5_select_read(b, &f, &e) == AQ_OK, "outputs read back: %s",
                e.message))
    return;
  int mode = strstr(tsv, "peaks exact")  ? PEAKS_EXACT
             : strstr(tsv, "peaks peer") ? PEAKS_PEER
                                         : PEAKS_SAMPLES;
  aq_check(mode != PEAKS_SAMPLES || strstr(tsv, "peaks samples"),
           "the file states its peak convention");
  int h = header_row(tsv);
  size_t K = f.nper, N = 0;
  double *mean = calloc(K, sizeof *mean), zero = 0;
  for (int row = h + 1; aq_test_tsv_field(tsv, row, 0, b, sizeof b)[0]; row++, N++) {
    char sc[64];
    double s = strtod(aq_test_tsv_field(tsv, row, 2, sc, sizeof sc), NULL);
    aq_record rec;
    aq_read_opts ro = {0};
    if (!aq_check(aq_record_read(b, &ro, &rec, &e) == AQ_OK, "%s: %s", b, e.message))
      continue;
    double pga = 0;
    for (size_t i = 0; i < rec.npts; i++)
      pga = fmax(pga, fabs(rec.acc_mps2[i]));
    zero += s * pga / G0;
    for (size_t k = 0; k < K; k++)
      mean[k] += s * psa_rk4(rec.acc_mps2, rec.npts, rec.dt_s, f.period_s[k], mode) / G0;
    aq_record_free(&rec);
  }
  aq_check(N == 7, "7 records, got %zu", N);
  double lowest = INFINITY, misfit = 0;
  for (size_t k = 0; k < K; k++) {
    double r = mean[k] / (double)N / aq_test_ec8_b(f.period_s[k]);
    lowest = fmin(lowest, r);
    misfit += log(r) * log(r) / (double)K;
  }
  aq_check(lowest >= 0.9 * (1 - 1e-6), "the mean at least 90 %% of the target: lowest %.6f",
           lowest);
  aq_check(zero / (double)N >= 0.25 * 1.2 * (1 - 1e-9), "mean zero-period value %.5f g >= "
           "a_g S = 0.3 g", zero / (double)N);
  aq_check_rel(misfit, f.misfit, 5e-6, "%s: the suite's misfit by our own spectrum", peaks);
  if (peaks[0])
    aq_check(strstr(tsv, peaks + strlen("--peaks ")) != NULL, "the file says %s", peaks);
  aq_check(f.conditions_hold == 1 && strstr(tsv, "# conditions: all hold"),
           "the files say every condition holds");
  free(mean);
  free(tsv);
  aq_h5_select_file_free(&f);
}

AQ_TEST(select_cli_conditions_by_own_spectrum)
{
  conditions_by_own_spectrum("");
  conditions_by_own_spectrum("--peaks exact");
  conditions_by_own_spectrum("--peaks samples");
}

/* --suite: the rows of the suite's records run one by one at their scales,
 * and a scale list multiplies them; capacity's scales are the suite's. */
AQ_TEST(select_cli_suite_runs)
{
  char dir[256], args[4096], err[8192], b[512], sc[64];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args, "select %s --target " EC8B " --count 3 --text %s/s.tsv", pool12,
           dir);
  if (!aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "select: %s", err))
    return;
  snprintf(b, sizeof b, "%s/s.tsv", dir);
  char *tsv = aq_test_read_file(b, NULL);
  char *all = malloc(BIG), *one = malloc(BIG), *both = malloc(BIG);
  snprintf(args, sizeof args, "--suite %s/s.tsv --arch arches/oppenheim.cfg --arch "
           "arches/thin.cfg --polarity normal", dir);
  int rc = aq_test_run(args, all, BIG, err, sizeof err);
  aq_check(rc == 0, "the main job with --suite: exit %d: %s", rc, err);
  snprintf(args, sizeof args, "--suite %s/s.tsv --arch arches/oppenheim.cfg --arch "
           "arches/thin.cfg --scale 0.5,2 --polarity normal", dir);
  rc = aq_test_run(args, both, BIG, err, sizeof err);
  aq_check(rc == 0, "--suite with --scale: exit %d: %s", rc, err);
  int h = header_row(tsv);
  size_t line = 1;
  for (int row = h + 1; aq_test_tsv_field(tsv, row, 0, b, sizeof b)[0]; row++) {
    aq_test_tsv_field(tsv, row, 2, sc, sizeof sc);
    snprintf(args, sizeof args, "%s --scale %s --arch arches/oppenheim.cfg --arch "
             "arches/thin.cfg --polarity normal", b, sc);
    rc = aq_test_run(args, one, BIG, err, sizeof err);
    aq_check(rc == 0, "%s at %s: exit %d", b, sc, rc);
    for (size_t a = 0; a < 2; a++, line++) {
      /* the same row, byte for byte */
      const char *p = all;
      for (size_t k = 0; k < line && p; k++)
        p = strchr(p, '\n'), p = p ? p + 1 : NULL;
      const char *q = strchr(one, '\n');
      for (size_t k = 0; k < a && q; k++)
        q = strchr(q + 1, '\n');
      size_t lp = p ? strcspn(p, "\n") : 0, lq = q ? strcspn(q + 1, "\n") : 0;
      aq_check(p && q && lp == lq && !memcmp(p, q + 1, lp), "%s, arch %zu: the suite's row "
               "equals the record's at --scale %s", b, a, sc);
    }
    /* --scale 0.5,2 multiplies the suite's scale */
    double s = strtod(sc, NULL);
    char got[64];
    size_t r0 = 1 + 4 * (size_t)(row - h - 1);
    aq_check_rel(strtod(aq_test_tsv_field(both, (int)r0, 3, got, sizeof got), NULL), 0.5 * s,
                 1e-15, "%s: scale 0.5 x the suite's", b);
    aq_check_rel(strtod(aq_test_tsv_field(both, (int)r0 + 1, 3, got, sizeof got), NULL), 2 * s,
                 1e-15, "%s: scale 2 x the suite's", b);
  }
  aq_check(line == 7, "3 records x 2 arches, got %zu rows", line - 1);
  /* capacity: the first collapse scale relative to the suite, the PGA at
   * collapse the record's own */
  int row = h + 1;
  aq_test_tsv_field(tsv, row, 0, b, sizeof b);
  double s = strtod(aq_test_tsv_field(tsv, row, 2, sc, sizeof sc), NULL);
  snprintf(args, sizeof args, "capacity --suite %s/s.tsv --arch arches/oppenheim.cfg "
           "--polarity normal", dir);
  rc = aq_test_run(args, all, BIG, err, sizeof err);
  aq_check(rc == 0, "capacity --suite: exit %d: %s", rc, err);
  snprintf(args, sizeof args, "capacity %s --arch arches/oppenheim.cfg --polarity normal", b);
  rc = aq_test_run(args, one, BIG, err, sizeof err);
  aq_check(rc == 0, "capacity of the record: exit %d: %s", rc, err);
  char x[64], y[64];
  double fs = strtod(aq_test_tsv_field(all, 1, 5, x, sizeof x), NULL);
  double fr = strtod(aq_test_tsv_field(one, 1, 5, y, sizeof y), NULL);
  aq_check_rel(fs * s, fr, 3e-6, "first collapse: %g x the suite's %g = the record's %g", fs,
               s, fr); /* both bisected to 1e-6 */
  aq_check_rel(strtod(aq_test_tsv_field(all, 1, 6, x, sizeof x), NULL),
               strtod(aq_test_tsv_field(one, 1, 6, y, sizeof y), NULL), 3e-6,
               "the PGA at first collapse, g, is the record's");
  free(tsv);
  free(all);
  free(one);
  free(both);
}

/* --max-per-event 1 on a pool with two components of three events: the
 * suite takes one of each; the event column names it. */
AQ_TEST(select_cli_events)
{
  char *out = malloc(BIG), err[8192], b[512];
  int rc = aq_test_run("select " R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2 "
                       R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2 " R "RSN763_LOMAP_GIL067.AT2 "
                       R "RSN763_LOMAP_GIL337.AT2 " R "CHY028-N.AT2 " R "TCU052-N.AT2 "
                       "--target " EC8B " --count 3 --max-per-event 1 --scale-range 0.1,10",
                       out, BIG, err, sizeof err);
  aq_check(rc == 0, "exit %d: %s", rc, err);
  int h = header_row(out);
  int seen[3] = {0, 0, 0};
  for (int row = h + 1; aq_test_tsv_field(out, row, 0, b, sizeof b)[0]; row++) {
    aq_test_tsv_field(out, row, 4, b, sizeof b);
    seen[0] += strstr(b, "Imperial Valley-02") != NULL;
    seen[1] += strstr(b, "Loma Prieta") != NULL;
    seen[2] += strstr(b, "CHI-CHI") != NULL;
  }
  aq_check(seen[0] == 1 && seen[1] == 1 && seen[2] == 1, "one of each event: %d %d %d",
           seen[0], seen[1], seen[2]);
  aq_check(strstr(out, "check events: holds") != NULL, "the events check holds");
  /* one per event asked of a pool of four events: no suite of 7 */
  rc = aq_test_run("select " R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2 "
                   R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2 " R "RSN763_LOMAP_GIL067.AT2 "
                   R "RSN763_LOMAP_GIL337.AT2 " R "CHY028-N.AT2 " R "TCU052-N.AT2 "
                   R "ARL360.at2 --target " EC8B " --count 7 --max-per-event 1",
                   out, BIG, err, sizeof err);
  aq_check(rc == 1 && out[0] == '\0' && strstr(err, "at most 1 records of one event") &&
               aq_test_count_lines(err) == 1,
           "no suite of 7 with 1 per event: exit %d, one line: %s", rc, err);
  free(out);
}

/* No suite meets the conditions within a narrow scale range: one line
 * saying by how much the best falls short and where; nothing written;
 * --best-effort writes the closest, says which condition fails, exit 1. */
AQ_TEST(select_cli_short_of_the_conditions)
{
  char dir[256], args[2048], err[8192], b[512];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args, "select %s --target ec8:type=1,ground=D,ag=0.6 --count 7 "
           "--scale-range 0.9,1.1 -o %s/s.h5 --text %s/s.tsv", pool12, dir, dir);
  char *out = malloc(BIG);
  int rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 1 && aq_test_count_lines(err) == 1 && strstr(err, "band:") &&
               strstr(err, "lowest") && strstr(err, "nothing written"),
           "exit %d, one line naming the shortfall: %s", rc, err);
  aq_check(aq_test_count_names(dir, "s.") == 0, "nothing written");
  snprintf(args, sizeof args, "select %s --target ec8:type=1,ground=D,ag=0.6 --count 7 "
           "--scale-range 0.9,1.1 --best-effort --text %s/s.tsv", pool12, dir);
  rc = aq_test_run(args, out, BIG, err, sizeof err);
  snprintf(b, sizeof b, "%s/s.tsv", dir);
  char *tsv = aq_test_read_file(b, NULL);
  aq_check(rc == 1 && tsv && strstr(tsv, "check band: FAILS") &&
               strstr(tsv, "# conditions: NOT ALL HOLD"),
           "--best-effort: exit %d, the file says the band fails", rc);
  free(tsv);
  free(out);
}

/* The pool as a directory and as a quoted glob: the same suite as the
 * files named one by one; a file that is not a record is named and left
 * out (exit 1, the suite still written). */
AQ_TEST(select_cli_directory_and_glob)
{
  char dir[256], args[2048], err[8192], b[600];
  aq_test_tmpdir(dir, sizeof dir);
  const char *f[] = {"RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "RSN763_LOMAP_GIL067.AT2",
                     "ARL360.at2", "CHY028-N.AT2", "RSN4843_CHUETSU_65006NS.AT2"};
  for (size_t i = 0; i < 5; i++) {
    snprintf(b, sizeof b, "cp " R "%s %s/", f[i], dir);
    aq_check(system(b) == 0, "%s", b);
  }
  char *a = malloc(BIG), *g = malloc(BIG), *d = malloc(BIG);
  snprintf(args, sizeof args, "select %s/%s %s/%s %s/%s %s/%s %s/%s --target " EC8B
           " --count 3 --scale-range 0.1,10", dir, f[0], dir, f[1], dir, f[2], dir, f[3], dir,
           f[4]);
  aq_check(aq_test_run(args, a, BIG, err, sizeof err) == 0, "files: %s", err);
  snprintf(args, sizeof args, "select '%s/*.[Aa][Tt]2' --target " EC8B " --count 3 "
           "--scale-range 0.1,10", dir);
  aq_check(aq_test_run(args, g, BIG, err, sizeof err) == 0, "glob: %s", err);
  snprintf(b, sizeof b, "%s/notes.txt", dir);
  FILE *n = fopen(b, "w");
  fputs("not a record\n", n);
  fclose(n);
  snprintf(args, sizeof args, "select %s --target " EC8B " --count 3 --scale-range 0.1,10",
           dir);
  int rc = aq_test_run(args, d, BIG, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "notes.txt") && strstr(err, "left out of the pool") &&
               aq_test_count_lines(err) == 1,
           "directory: exit %d, the stray file named: %s", rc, err);
  /* the same records (rows in pool order: the named order, or by name) */
  int ha = header_row(a), hg = header_row(g), hd = header_row(d);
  for (int k = 1; k <= 3; k++) {
    char x[600], y[600];
    aq_test_tsv_field(a, ha + k, 0, x, sizeof x);
    int in_g = 0, in_d = 0;
    for (int j = 1; j <= 3; j++) {
      in_g += !strcmp(x, aq_test_tsv_field(g, hg + j, 0, y, sizeof y));
      in_d += !strcmp(x, aq_test_tsv_field(d, hd + j, 0, y, sizeof y));
    }
    aq_check(x[0] && in_g == 1 && in_d == 1, "%s chosen from the glob and the directory too",
             x);
  }
  free(a);
  free(g);
  free(d);
}

/* The range from capacity's fragility fits: the best-ranked spectral
 * measure's (Sa(0.5 s): 0.1 to 1 s; Sa_avg 0.2 to 1.5 s when it ranks
 * first); a file of another kind, or an arch it lacks, refused. */
AQ_TEST(select_cli_fragility_range)
{
  char dir[256], args[2048], err[8192], b[512];
  aq_test_tmpdir(dir, sizeof dir);
  char *out = malloc(BIG);
  for (int v = 0; v < 2; v++) {
    snprintf(b, sizeof b, "%s/frag%d.tsv", dir, v);
    FILE *f = fopen(b, "w");
    fprintf(f, "arch\tim\trecords\tcensored\tmedian\tbeta\tmedian_lo\tmedian_hi\trank\n"
               "oppenheim\tpga_g\t12\t0\t1.1\t0.3\t1\t1.2\t%d\n"
               "oppenheim\tsa_0.5s_g\t12\t0\t2.1\t0.25\t1.9\t2.3\t%d\n"
               "oppenheim\tsa_avg_0.2_1.5s_g\t12\t0\t1.5\t0.28\t1.3\t1.7\t%d\n",
            v ? 2 : 1, v ? 3 : 2, v ? 1 : 3);
    fclose(f);
    snprintf(args, sizeof args, "select %s --target " EC8B " --count 7 --fragility %s",
             pool12, b);
    int rc = aq_test_run(args, out, BIG, err, sizeof err);
    aq_check(rc == 0, "exit %d: %s", rc, err);
    const char *want = v ? "range: 0.2 to 1.5 s (the range of sa_avg_0.2_1.5s_g"
                         : "range: 0.1 to 1 s (the range of sa_0.5s_g";
    aq_check(strstr(out, want) != NULL, "the suite file says \"%s\"", want);
  }
  snprintf(args, sizeof args, "select %s --target " EC8B " --count 7 --fragility %s/frag0.tsv "
           "--fragility-arch thick --text %s/s.tsv", pool12, dir, dir);
  int rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--fragility-arch") && strstr(err, "thick") &&
               aq_test_count_lines(err) == 1 && aq_test_count_names(dir, "s.tsv") == 0,
           "an arch the file lacks: exit %d: %s", rc, err);
  snprintf(args, sizeof args, "select %s --target " EC8B " --count 7 --fragility " R
           "ARL360.at2", pool12);
  rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--fragility") && aq_test_count_lines(err) == 1,
           "not a fragility file: exit %d: %s", rc, err);
  free(out);
}

/* Pairs: --components of two components each, an ASCE 7-22 target (the
 * pair's RotD100), the suite file's record column "H1,H2", run by the main
 * job as the same --components motion. */
AQ_TEST(select_cli_pairs)
{
  char dir[256], args[2048], err[8192], b[512];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args, "select --components " R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2,"
           R "RSN6_IMPVALL.I_I-ELC270-hor2.AT2 --components " R "RSN763_LOMAP_GIL067.AT2,"
           R "RSN763_LOMAP_GIL337.AT2 --target asce7:sds=0.8,sd1=0.45,tl=8 --count 1 "
           "--scale-range 0.1,10 --best-effort --text %s/s.tsv", dir);
  char *out = malloc(BIG), *one = malloc(BIG);
  int rc = aq_test_run(args, out, BIG, err, sizeof err);
  snprintf(b, sizeof b, "%s/s.tsv", dir);
  char *tsv = aq_test_read_file(b, NULL);
  /* one pair is fewer than ASCE 7-22's 11: the count check fails, written with --best-effort */
  aq_check(rc == 1 && tsv && strstr(tsv, "pairs RotD100") && strstr(tsv, "check count: FAILS"),
           "exit %d: %s", rc, err);
  int h = tsv ? header_row(tsv) : -1;
  char rec[512], sc[64];
  aq_test_tsv_field(tsv ? tsv : "", h + 1, 0, rec, sizeof rec);
  aq_test_tsv_field(tsv ? tsv : "", h + 1, 2, sc, sizeof sc);
  aq_check(strchr(rec, ',') != NULL, "the record column names the pair: %s", rec);
  snprintf(args, sizeof args, "--suite %s --arch arches/oppenheim.cfg", b);
  rc = aq_test_run(args, out, BIG, err, sizeof err);
  aq_check(rc == 0, "--suite of a pair: exit %d: %s", rc, err);
  snprintf(args, sizeof args, "--components %s --scale %s --arch arches/oppenheim.cfg", rec, sc);
  rc = aq_test_run(args, one, BIG, err, sizeof err);
  aq_check(rc == 0 && !strcmp(out, one), "the pair's row equals --components %s --scale %s",
           rec, sc);
  free(tsv);
  free(out);
  free(one);
}

/* Bad input: one line each, naming what is wrong; nothing written. */
AQ_TEST(select_cli_bad_input)
{
  char dir[256], args[4096], err[8192];
  aq_test_tmpdir(dir, sizeof dir);
  static const struct {
    const char *opts;
    int rc;
    const char *says;
  } bad[] = {
      {"--target ec8:type=1,ground=B --count 7", 2, "ag=a_gR in g"},
      {"--target ec8:type=1,ground=B,ag=0.2,zone=3 --count 7", 2, "unknown \"zone\""},
      {"--target ec8:type=1,ground=B,ag=-0.25 --count 7", 2, "got \"-0.25\""},
      {"--target asce7:sds=1,sd1=0.5,tl=-8 --count 7", 2, "tl"},
      {"--target ec8:type=1,ground=B,ag=0.25 --count 7 --periods 1,0.5", 2, "T1 < T2"},
      {"--target ec8:type=1,ground=B,ag=0.25 --count 7 --periods 1,5", 2, "within the target's"},
      {"--target ec8:type=1,ground=B,ag=0.25 --count 13", 2, "at least 13 records, got 12"},
      {"--target ec8:type=1,ground=B,ag=0.25 --count 7 --scale-range 2,1", 2, "LO <= HI"},
      {"--target ec8:type=1,ground=B,ag=0.25 --count 7 --period-grid 2,3", 2, "--period-grid"},
      {"--target no-such-target.csv --count 7", 2, "no-such-target.csv"},
      {"--count 7", 2, "--target"},
      {"--target ec8:type=1,ground=B,ag=0.25", 2, "--count"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    snprintf(args, sizeof args, "select %s %s -o %s/s.h5 --text %s/s.tsv", pool12, bad[i].opts,
             dir, dir);
    char out[256];
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == bad[i].rc && strstr(err, bad[i].says) && aq_test_count_lines(err) == 1 &&
                 out[0] == '\0',
             "%s: exit %d, one line saying \"%s\": %s", bad[i].opts, rc, bad[i].says, err);
    aq_check(aq_test_count_names(dir, "s.") == 0, "%s: nothing written", bad[i].opts);
  }
  /* fewer usable records than N: the unusable named, nothing written */
  char stray[512];
  snprintf(stray, sizeof stray, "%s/stray.txt", dir);
  FILE *f = fopen(stray, "w");
  fputs("not a record\n", f);
  fclose(f);
  snprintf(args, sizeof args, "select " R "ARL360.at2 " R "CHY028-N.AT2 %s --target " EC8B
           " --count 3 --text %s/s.tsv", stray, dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "stray.txt") && strstr(err, "at least 3 usable records") &&
               aq_test_count_lines(err) == 2 && aq_test_count_names(dir, "s.") == 0,
           "too few usable: exit %d: %s", rc, err);
  /* a suite file that is not one */
  snprintf(args, sizeof args, "--suite " R "ARL360.at2 --arch arches/oppenheim.cfg");
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "ARL360.at2") && strstr(err, "header") &&
               aq_test_count_lines(err) == 1,
           "--suite of a record: exit %d: %s", rc, err);
  snprintf(args, sizeof args, "--suite %s --arch arches/oppenheim.cfg " R "ARL360.at2", stray);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--suite") && aq_test_count_lines(err) >= 1,
           "--suite with a RECORD: exit %d: %s", rc, err);
  snprintf(args, sizeof args, "--suite %s --arch arches/oppenheim.cfg --scale-to-pga 0.3",
           stray);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--scale-to-pga") && strstr(err, "--suite"),
           "--suite with --scale-to-pga: exit %d: %s", rc, err);
}
