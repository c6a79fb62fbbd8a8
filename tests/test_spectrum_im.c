/* test_spectrum_im.c: the spectral intensity measures (Sa(T), Sa_avg,
 * PGV/PGA) against closed forms and a composition written here, through
 * info, the main job's records table and capacity's fragility ranking;
 * their options' bad input. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "capacity/capacity.h"
#include "check.h"
#include "signal/signal.h"
#include "signal/spectrum.h"

#define G0 9.80665
#define PI 3.14159265358979323846
#define REC "tests/data/records/ARL360.at2"
enum { BIG = 1 << 16 };

/* A constant acceleration a0 from rest at t = 0 (the first sample: the
 * input linear between samples is a step there).  The oscillator's
 * relative displacement is u(t) = -(a0 / w^2) (1 - e^{-z w t} (cos wd t +
 * z / sqrt(1 - z^2) sin wd t)), whose largest |u| is at the first
 * overshoot, t = pi / wd: (a0 / w^2) (1 + exp(-pi z / sqrt(1 - z^2))).  So
 * PSA = a0 (1 + exp(-pi z / sqrt(1 - z^2))) at every period whose first
 * overshoot falls in the record, and Sa_avg, a geometric mean of equal
 * values, is the same: so with --peaks exact.  With the default, PEER's
 * refined samples (N = 1 at these periods, all >= 10 dt), each is the
 * largest |w^2 u| at the samples.  PGV = a0 (n - 1) dt (the trapezoid is
 * exact for a constant), so PGV/PGA = (n - 1) dt. */
AQ_TEST(spectrum_im_step_closed_form)
{
  const double a0 = 2.7, dt = 0.01, z = 0.05;
  const size_t n = 401; /* 4 s: the overshoot of T = 1 s is at 0.5 s */
  aq_processed p;
  memset(&p, 0, sizeof p);
  p.n = p.n_orig = n;
  p.dt_s = dt;
  p.acc_mps2 = malloc(n * sizeof(double));
  if (!aq_check(p.acc_mps2 != NULL, "alloc"))
    return;
  for (size_t i = 0; i < n; i++)
    p.acc_mps2[i] = a0;
  aq_signal_opts_default(&p.used);
  p.used.im_nsa = 3;
  p.used.im_period_s[0] = 0.13;
  p.used.im_period_s[1] = 0.5;
  p.used.im_period_s[2] = 1.7;
  p.used.sa_avg_lo_s = 0.3;
  p.used.sa_avg_hi_s = 2.2;
  aq_im im;
  aq_error e;
  if (aq_check(aq_im_compute(&p, &im, &e) == AQ_OK, "im (peer): %s", e.message)) {
    double T[13] = {0.13, 0.5, 1.7}, sa[13], lsum = 0;
    for (int k = 0; k < 10; k++)
      T[3 + k] = 0.3 + (2.2 - 0.3) * k / 9.0;
    for (int i = 0; i < 13; i++) {
      double w = 2 * PI / T[i], wd = w * sqrt(1 - z * z), m = 0;
      for (size_t k = 0; k < n; k++) {
        double t = (double)k * dt;
        m = fmax(m, fabs(a0 * (1 - exp(-z * w * t) *
                                         (cos(wd * t) + z / sqrt(1 - z * z) * sin(wd * t)))));
      }
      sa[i] = m / G0;
      lsum += i >= 3 ? log(sa[i]) : 0;
    }
    for (size_t k = 0; k < 3; k++)
      aq_check_rel(im.sa_g[k], sa[k], 1e-9, "Sa(%g s) of a step, peak at the samples",
                   im.sa_period_s[k]);
    aq_check_rel(im.sa_avg_g, exp(lsum / 10), 1e-9, "Sa_avg of a step, peaks at the "
                 "samples");
  }
  p.used.peaks = AQ_SPECTRUM_PEAKS_EXACT;
  if (aq_check(aq_im_compute(&p, &im, &e) == AQ_OK, "im: %s", e.message)) {
    double want = a0 * (1 + exp(-PI * z / sqrt(1 - z * z))) / G0;
    aq_check(im.n_sa == 3, "3 Sa(T): %zu", im.n_sa);
    for (size_t k = 0; k < 3; k++) {
      aq_check_rel(im.sa_g[k], want, 1e-9, "Sa(%g s) of a step", im.sa_period_s[k]);
      aq_check_rel(aq_im_spectral_value(&im, k), want, 1e-9, "spectral value %zu", k);
    }
    aq_check_rel(im.sa_avg_g, want, 1e-9, "Sa_avg of a step");
    aq_check_rel(aq_im_spectral_value(&im, 3), want, 1e-9, "spectral value 3 = Sa_avg");
    aq_check_rel(im.pgv_pga_s, (double)(n - 1) * dt, 1e-12, "PGV/PGA of a step");
    char name[64];
    aq_im_spectral_name(&p.used, 1, name, sizeof name);
    aq_check(strcmp(name, "sa_0.5s_g") == 0, "name of Sa(0.5 s): %s", name);
    aq_im_spectral_name(&p.used, 3, name, sizeof name);
    aq_check(strcmp(name, "sa_avg_0.3_2.2s_g") == 0, "name of Sa_avg: %s", name);
    aq_check(aq_im_spectral_count(&p.used) == 4, "4 spectral measures");
  }
  /* none asked: none computed, Sa_avg NAN */
  p.used.im_nsa = 0;
  p.used.sa_avg_lo_s = p.used.sa_avg_hi_s = 0;
  if (aq_check(aq_im_compute(&p, &im, &e) == AQ_OK, "im without spectra"))
    aq_check(im.n_sa == 0 && isnan(im.sa_avg_g) && aq_im_spectral_count(&p.used) == 0,
             "no spectral measure: n_sa %zu, sa_avg %g", im.n_sa, im.sa_avg_g);
  free(p.acc_mps2);
}

/* Sa_avg of a real record: the geometric mean (here exp of the mean log)
 * of PSA at ten periods spaced evenly from T1 to T2 inclusive (Eads et
 * al. 2015), the periods and the mean made here. */
AQ_TEST(spectrum_im_sa_avg_composition)
{
  aq_processed p;
  memset(&p, 0, sizeof p);
  size_t n = 3000;
  p.n = p.n_orig = n;
  p.dt_s = 0.01;
  p.acc_mps2 = malloc(n * sizeof(double));
  if (!aq_check(p.acc_mps2 != NULL, "alloc"))
    return;
  for (size_t i = 0; i < n; i++) { /* two tones under a decaying envelope */
    double t = (double)i * p.dt_s;
    p.acc_mps2[i] = exp(-t / 8) * (1.3 * sin(2 * PI * 2.1 * t) + 0.8 * sin(2 * PI * 0.55 * t));
  }
  aq_signal_opts_default(&p.used);
  p.used.im_nsa = 0;
  p.used.sa_avg_lo_s = 0.15;
  p.used.sa_avg_hi_s = 1.8;
  aq_im im;
  aq_error e;
  double T[10], psa[10], lsum = 0;
  for (int i = 0; i < 10; i++)
    T[i] = 0.15 + (1.8 - 0.15) * i / 9.0;
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  if (aq_check(ws && aq_spectrum_psa(ws, NULL, p.acc_mps2, n, p.dt_s, 0.05, T, 10, psa, &e) ==
                         AQ_OK,
               "psa") &&
      aq_check(aq_im_compute(&p, &im, &e) == AQ_OK, "im")) {
    for (int i = 0; i < 10; i++)
      lsum += log(psa[i] / G0);
    aq_check_rel(im.sa_avg_g, exp(lsum / 10), 1e-12, "Sa_avg = geometric mean of ten Sa");
    /* the spread of the ten is wide: a mean of other periods would differ */
    double lo = INFINITY, hi = 0;
    for (int i = 0; i < 10; i++)
      lo = fmin(lo, psa[i]), hi = fmax(hi, psa[i]);
    aq_check(hi > 1.5 * lo, "Sa varies over the range (%g to %g m/s2)", lo, hi);
  }
  aq_spectrum_ws_free(ws);
  free(p.acc_mps2);
}

/* The fragility ranking: nine records whose IMs at scale 1 are built so
 * that Sa(T) at collapse spreads least; beta of each measure is the
 * population standard deviation of ln IM at collapse (complete data, the
 * closed form of test_capacity_fragility.c), and the rank orders beta /
 * power, Arias intensity growing as the square of the scale. */
AQ_TEST(spectrum_im_fragility_rank)
{
  enum { NR = 9 };
  static const double zz[NR] = {-1.21, 0.35, 1.72, -0.48, 0.91, -1.65, 0.12, 1.05, -0.77};
  static const double ww[NR] = {0.83, -1.44, 0.27, 1.36, -0.58, 0.64, -1.02, 0.19, -0.25};
  static const double uu[NR] = {-0.31, 0.74, -1.18, 0.52, 1.49, -0.86, 0.08, -0.63, 1.11};
  aq_capacity cap[NR];
  aq_im imv[NR];
  const aq_im *im[NR];
  memset(cap, 0, sizeof cap);
  memset(imv, 0, sizeof imv);
  const double l0 = 0.2;
  /* ln of each measure at collapse, as built: Sa 0.05 z; PGA 0.05 z + 0.1 w;
   * Arias 2 (0.05 z) + 0.04 u; PGV 0.3 u; PGD 0.5 w; CAV 0.2 (z + w) */
  double lx[7][NR];
  for (int r = 0; r < NR; r++) {
    double sa = 0.3 * (1 + 0.2 * r), s = exp(0.05 * zz[r]) / sa; /* collapse scale */
    cap[r] = (aq_capacity){.status = AQ_CAPACITY_OK, .lambda0 = l0, .scale_max = 1e3,
                           .first_collapse_scale = s};
    imv[r].n_sa = 1;
    imv[r].sa_period_s[0] = 0.5;
    imv[r].sa_g[0] = sa;
    imv[r].sa_avg_g = NAN;
    imv[r].pga_g = sa * exp(0.1 * ww[r]);
    imv[r].arias_mps = sa * sa * exp(0.04 * uu[r]);
    imv[r].pgv_mps = exp(0.3 * uu[r]) / s;
    imv[r].pgd_m = exp(0.5 * ww[r]) / s;
    imv[r].cav_mps = exp(0.2 * (zz[r] + ww[r])) / s;
    im[r] = &imv[r];
    lx[0][r] = log(s * imv[r].pga_g);
    lx[1][r] = log(s * imv[r].pgv_mps);
    lx[2][r] = log(s * imv[r].pgd_m);
    lx[3][r] = log(s * s * imv[r].arias_mps);
    lx[4][r] = log(s * imv[r].cav_mps);
    lx[5][r] = log(s * imv[r].pga_g / l0);
    lx[6][r] = log(s * sa);
  }
  double beta[7];
  for (int m = 0; m < 7; m++) {
    double mean = 0, v = 0;
    for (int r = 0; r < NR; r++)
      mean += lx[m][r] / NR;
    for (int r = 0; r < NR; r++)
      v += (lx[m][r] - mean) * (lx[m][r] - mean) / NR;
    beta[m] = sqrt(v);
  }
  /* the design: Sa first, Arias (per power) second, by a margin */
  const double per[7] = {beta[0], beta[1], beta[2], beta[3] / 2, beta[4], beta[5], beta[6]};
  aq_check(per[6] < per[3] && per[3] < 0.97 * per[0] && per[3] < 0.97 * per[1] &&
               per[3] < 0.97 * per[2] && per[3] < 0.97 * per[4],
           "the test's design: %g < %g < the others", per[6], per[3]);
  aq_check(beta[3] > per[0], "Arias unhalved would rank below PGA: %g > %g", beta[3], per[0]);
  aq_fragility fits[AQ_FRAGILITY_NIM + 2];
  aq_error e;
  if (!aq_check(aq_fragility_fit_records_n(cap, NR, 1, 1, im, AQ_FRAGILITY_NIM + 2, 0.9, fits,
                                           &e) == AQ_OK,
                "fit: %s", e.message))
    return;
  for (int m = 0; m < 7; m++)
    aq_check_rel(fits[m].beta, beta[m], 1e-5, "beta of measure %d", m);
  aq_check_rel(fits[6].median, 1.0, 0.1, "Sa at collapse about 1 g: %g", fits[6].median);
  aq_check(fits[6].rank == 1, "Sa(0.5 s) ranks first: %d", fits[6].rank);
  aq_check(fits[3].rank == 2, "Arias intensity (beta halved) ranks second: %d", fits[3].rank);
  aq_check(fits[7].rank == 0 && isnan(fits[7].beta), "no Sa_avg: unranked (%d)", fits[7].rank);
  int seen = 0;
  for (int m = 0; m < 7; m++)
    seen |= 1 << (fits[m].rank - 1);
  aq_check(seen == 0x7f, "ranks 1..7 each once (%#x)", seen);
}

/* PGA and PGA/lambda0 are proportional within an arch, so their beta is
 * the same number; the fit finds each to its simplex size only, so the
 * ranking must not order them by the optimiser's noise: measures whose
 * beta / power agree within the fit's resolution take the declared order,
 * pga_g just before pga_lambda0, whatever lambda0 is. */
AQ_TEST(spectrum_im_fragility_rank_ties)
{
  enum { NR = 9, NL = 40 };
  static const double zz[NR] = {-1.21, 0.35, 1.72, -0.48, 0.91, -1.65, 0.12, 1.05, -0.77};
  static const double ww[NR] = {0.83, -1.44, 0.27, 1.36, -0.58, 0.64, -1.02, 0.19, -0.25};
  int bad = 0;
  for (int k = 0; k < NL; k++) {
    const double l0 = 0.05 + 0.0731 * k;
    aq_capacity cap[NR];
    aq_im imv[NR];
    const aq_im *im[NR];
    memset(cap, 0, sizeof cap);
    memset(imv, 0, sizeof imv);
    for (int r = 0; r < NR; r++) {
      double s = exp(0.3 * zz[r]);
      cap[r] = (aq_capacity){.status = AQ_CAPACITY_OK, .lambda0 = l0, .scale_max = 1e3,
                             .first_collapse_scale = s};
      imv[r].sa_avg_g = NAN;
      imv[r].pga_g = 0.3 * exp(0.2 * ww[r]);
      imv[r].pgv_mps = 0.2 * exp(0.5 * ww[r] + 0.1 * zz[r]);
      imv[r].pgd_m = 0.05 * exp(0.7 * zz[r]);
      imv[r].arias_mps = 0.4 * exp(0.9 * ww[r]);
      imv[r].cav_mps = 1.1 * exp(0.6 * ww[r] - 0.4 * zz[r]);
      im[r] = &imv[r];
    }
    aq_fragility fits[AQ_FRAGILITY_NIM];
    aq_error e;
    if (!aq_check(aq_fragility_fit_records(cap, NR, 1, 1, im, 0.9, fits, &e) == AQ_OK,
                  "fit: %s", e.message))
      return;
    aq_check_rel(fits[5].beta, fits[0].beta, 1e-5, "lambda0 %g: equal beta", l0);
    bad += fits[5].rank != fits[0].rank + 1;
    if (fits[5].rank != fits[0].rank + 1)
      fprintf(stderr, "  lambda0 %g: pga_g rank %d (beta %.17g), pga_lambda0 rank %d (beta %.17g)\n", l0,
              fits[0].rank, fits[0].beta, fits[5].rank, fits[5].beta);
  }
  aq_check(bad == 0, "pga_lambda0 ranks just after pga_g at every lambda0: %d of %d not", bad,
           NL);
}

static int col_of(const char *header, const char *name)
{
  char b[128];
  for (int k = 0; k < 64; k++) {
    const char *f = aq_test_tsv_field(header, 0, k, b, sizeof b);
    if (!f)
      return -1;
    if (strcmp(b, name) == 0)
      return k;
  }
  return -1;
}

static double num(const char *tsv, int row, int k)
{
  char b[128];
  const char *f = aq_test_tsv_field(tsv, row, k, b, sizeof b);
  return f ? strtod(b, NULL) : NAN;
}

/* info: a column per --im-periods period and one for --sa-avg, named with
 * them, equal to the spectrum command's PSA at 5 % of the record processed
 * alike (the spectrum's own code path; the periods of Sa_avg and their
 * geometric mean made here); PGV/PGA from info's own PGV and PGA. */
AQ_TEST(spectrum_im_info_columns)
{
  char *out = malloc(BIG), *sp = malloc(BIG), err[2048];
  if (!out || !sp)
    return;
  int rc = aq_test_run("info " REC " --im-periods 0.25,1.3 --sa-avg 0.2,2", out, BIG, err,
                       sizeof err);
  char per[256] = "0.25,1.3";
  for (int i = 0; i < 10; i++) {
    size_t k = strlen(per);
    snprintf(per + k, sizeof per - k, ",%.17g", 0.2 + (2 - 0.2) * i / 9.0);
  }
  char args[512];
  snprintf(args, sizeof args, "spectrum " REC " --periods %s", per);
  int rs = aq_test_run(args, sp, BIG, NULL, 0);
  if (aq_check(rc == 0 && rs == 0, "info exit %d (%s), spectrum exit %d", rc, err, rs)) {
    int c1 = col_of(out, "sa_0.25s_g"), c2 = col_of(out, "sa_1.3s_g"),
        ca = col_of(out, "sa_avg_0.2_2s_g"), cr = col_of(out, "pgv_pga_s"),
        cv = col_of(out, "pgv_m_s"), cg = col_of(out, "pga_g");
    aq_check(c1 > 0 && c2 > 0 && ca > 0 && cr > 0, "columns %d %d %d %d", c1, c2, ca, cr);
    /* spectrum rows: header, then one per period, psa_g column 4 */
    aq_check_rel(num(out, 1, c1), num(sp, 1, 4), 1e-5, "Sa(0.25 s) = spectrum's");
    aq_check_rel(num(out, 1, c2), num(sp, 2, 4), 1e-5, "Sa(1.3 s) = spectrum's");
    double l = 0;
    for (int i = 0; i < 10; i++)
      l += log(num(sp, 3 + i, 4)) / 10;
    aq_check_rel(num(out, 1, ca), exp(l), 1e-5, "Sa_avg = geometric mean of the ten");
    aq_check_rel(num(out, 1, cr), num(out, 1, cv) / (num(out, 1, cg) * G0), 1e-4,
                 "PGV/PGA (s)");
  }
  /* none: no spectral column */
  rc = aq_test_run("info " REC " --im-periods none --sa-avg none", out, BIG, err, sizeof err);
  aq_check(rc == 0 && !strstr(out, "sa_") && strstr(out, "pgv_pga_s"),
           "--im-periods none --sa-avg none: exit %d, %.200s", rc, out);
  free(out);
  free(sp);
}

/* Bad values: one line naming the option, exit 2, nothing on stdout. */
AQ_TEST(spectrum_im_bad_options)
{
  static const char *const bad[][2] = {
      {"--im-periods 0,1", "--im-periods"},
      {"--im-periods -0.5", "--im-periods"},
      {"--im-periods 0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9", "--im-periods"},
      {"--sa-avg 1,0.5", "--sa-avg"},
      {"--sa-avg 0.5", "--sa-avg"},
      {"--sa-avg 0,1", "--sa-avg"},
      {"--peaks continuous", "--peaks"},
      {"--peaks samples --sampled-peaks", "--sampled-peaks"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    char args[256], out[1024], err[1024];
    snprintf(args, sizeof args, "info %s " REC, bad[i][0]);
    int rc = aq_test_run(args, out, sizeof out, err, sizeof err);
    aq_check(rc == 2 && aq_test_count_lines(err) == 1 && strstr(err, bad[i][1]) && !out[0],
             "%s: exit %d, stderr %s", args, rc, err);
  }
}

/* The main job's records table: the spectral columns, in g, as info gives
 * them for the same record and options. */
AQ_TEST(spectrum_im_records_table)
{
  char dir[512], h5[600], args[1400], err[2048];
  char *out = malloc(BIG);
  if (!out)
    return;
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(h5, sizeof h5, "%s/r.h5", dir);
  snprintf(args, sizeof args,
           "--arch arches/oppenheim.cfg " REC " --scale 0.1 --im-periods 0.4 --sa-avg 0.1,1 "
           "-o %s >/dev/null",
           h5);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  int ri = aq_test_run("info " REC " --im-periods 0.4", out, BIG, NULL, 0);
  if (aq_check(rc == 0 && ri == 0, "run exit %d (%s), info %d", rc, err, ri)) {
    hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f >= 0 ? H5Dopen2(f, "/records", H5P_DEFAULT) : -1;
    double got[3] = {NAN, NAN, NAN};
    static const char *const names[3] = {"sa_0.4s_g", "sa_avg_0.1_1s_g", "pgv_pga_s"};
    for (int k = 0; k < 3 && d >= 0; k++) {
      hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(double));
      H5Tinsert(t, names[k], 0, H5T_NATIVE_DOUBLE);
      if (H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, &got[k]) < 0)
        got[k] = NAN;
      H5Tclose(t);
    }
    if (d >= 0)
      H5Dclose(d);
    if (f >= 0)
      H5Fclose(f);
    for (int k = 0; k < 3; k++)
      aq_check_rel(got[k], num(out, 1, col_of(out, names[k])), 1e-5, "/records %s = info's",
                   names[k]);
  }
  /* unnamed, the main job computes no spectral measure (info does) */
  snprintf(h5, sizeof h5, "%s/plain.h5", dir);
  snprintf(args, sizeof args, "--arch arches/oppenheim.cfg " REC " --scale 0.1 -o %s", h5);
  rc = aq_test_run(args, out, BIG, err, sizeof err);
  if (aq_check(rc == 0, "plain run: exit %d (%s)", rc, err)) {
    aq_check(!strstr(out, "sa_"), "no sa_ column in the main job's table: %.300s", out);
    hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t d = f >= 0 ? H5Dopen2(f, "/records", H5P_DEFAULT) : -1;
    hid_t t = d >= 0 ? H5Dget_type(d) : -1;
    aq_check(t >= 0 && H5Tget_member_index(t, "sa_0.2s_g") < 0 &&
                 H5Tget_member_index(t, "sa_avg_0.1_1s_g") < 0 &&
                 H5Tget_member_index(t, "pgv_pga_s") >= 0,
             "/records: pgv_pga_s but no spectral column");
    if (t >= 0)
      H5Tclose(t);
    if (d >= 0)
      H5Dclose(d);
    if (f >= 0)
      H5Fclose(f);
  }
  rc = aq_test_run("info " REC, out, BIG, NULL, 0);
  aq_check(rc == 0 && col_of(out, "sa_0.2s_g") > 0 && col_of(out, "sa_avg_0.1_1s_g") > 0,
           "info's defaults keep Sa(0.2 s) and Sa_avg: %.200s", out);
  free(out);
}

/* Column name of the first row of /records in the results file h5 (NAN if
 * absent), and the root attribute peaks into buf. */
static double records_value(const char *h5, const char *name, char *peaks, size_t n)
{
  double v = NAN;
  peaks[0] = '\0';
  hid_t f = H5Fopen(h5, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t d = f >= 0 ? H5Dopen2(f, "/records", H5P_DEFAULT) : -1;
  if (d >= 0) {
    hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(double));
    H5Tinsert(t, name, 0, H5T_NATIVE_DOUBLE);
    if (H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v) < 0)
      v = NAN;
    H5Tclose(t);
    H5Dclose(d);
  }
  hid_t a = f >= 0 && H5Aexists(f, "peaks") > 0 ? H5Aopen(f, "peaks", H5P_DEFAULT) : -1;
  hid_t at = a >= 0 ? H5Aget_type(a) : -1;
  if (at >= 0 && H5Tget_size(at) < n && H5Aread(a, at, peaks) < 0)
    peaks[0] = '\0';
  if (at >= 0)
    H5Tclose(at);
  if (a >= 0)
    H5Aclose(a);
  if (f >= 0)
    H5Fclose(f);
  return v;
}

/* --peaks reaches the main job's /records (and its root attribute), and is
 * part of the disk cache's key: the same record, the same options but the
 * rule, run one after the other into one cache directory, gives each
 * rule's own Sa (at 0.013 s, below 10 dt = 0.2 s of ARL360, the three
 * differ: samples < peer < exact), equal to info's under that rule.  With
 * the rule left out of the key the second run would read the first's
 * entry and repeat its value. */
AQ_TEST(spectrum_im_peaks_through_the_cache)
{
  static const char *const rule[3] = {"peer", "exact", "samples"};
  char dir[512], h5[600], args[1600], err[2048], peaks[32];
  char *out = malloc(BIG);
  if (!out)
    return;
  aq_test_tmpdir(dir, sizeof dir);
  double sa[3];
  for (int m = 0; m < 3; m++) {
    snprintf(h5, sizeof h5, "%s/p%d.h5", dir, m);
    snprintf(args, sizeof args,
             "--arch arches/oppenheim.cfg " REC " --scale 0.1 --im-periods 0.013 --peaks %s "
             "--cache-dir %s/cache -o %s >/dev/null", rule[m], dir, h5);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "--peaks %s: exit %d (%s)", rule[m], rc, err);
    sa[m] = records_value(h5, "sa_0.013s_g", peaks, sizeof peaks);
    aq_check(strcmp(peaks, rule[m]) == 0, "root attribute peaks: \"%s\" (want %s)", peaks,
             rule[m]);
    snprintf(args, sizeof args, "info " REC " --im-periods 0.013 --sa-avg none --peaks %s",
             rule[m]);
    rc = aq_test_run(args, out, BIG, NULL, 0);
    aq_check(rc == 0, "info --peaks %s", rule[m]);
    aq_check_rel(sa[m], num(out, 1, col_of(out, "sa_0.013s_g")), 1e-5,
                 "--peaks %s: /records = info's", rule[m]);
  }
  aq_check(sa[2] < sa[0] && sa[0] < sa[1], "samples %.9g < peer %.9g < exact %.9g", sa[2],
           sa[0], sa[1]);
  aq_check(aq_test_count_names(dir, "cache") == 1, "the cache directory was used");
  free(out);
}

/* capacity --fragility: a row per spectral measure, each arch's ranks
 * 1..n once over its fitted measures, PGV/PGA never among them (it does
 * not grow with the scale). */
AQ_TEST(spectrum_im_capacity_fragility_rows)
{
  char dir[512], tsv[600], args[1400], err[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(tsv, sizeof tsv, "%s/f.tsv", dir);
  snprintf(args, sizeof args,
           "capacity --arch arches/oppenheim.cfg tests/data/records/ARL360.at2 "
           "tests/data/records/IELC180.AT2 tests/data/records/RSN6_IMPVALL.I_I-ELC270-hor2.AT2 "
           "--im-periods 0.3,1 --fragility %s >/dev/null",
           tsv);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  char *f = aq_test_read_file(tsv, NULL);
  if (!aq_check(rc == 0 && f, "capacity exit %d: %s", rc, err)) {
    free(f);
    return;
  }
  int crank = col_of(f, "rank"), cim = col_of(f, "im"), cb = col_of(f, "beta");
  aq_check(crank > 0 && cim > 0 && cb > 0, "columns im, beta, rank");
  int rows = 0, spectral = 0, seen = 0, nfit = 0;
  char b[128];
  for (int r = 1; r < 1000 && aq_test_tsv_field(f, r, 0, b, sizeof b)[0]; r++) {
    rows++;
    aq_test_tsv_field(f, r, cim, b, sizeof b);
    spectral += !strncmp(b, "sa_", 3);
    aq_check(strcmp(b, "pgv_pga_s") != 0, "PGV/PGA is not a fragility measure");
    double beta = num(f, r, cb), rank = num(f, r, crank);
    if (isfinite(beta)) {
      nfit++;
      if (rank >= 1 && rank <= 30)
        seen |= 1 << ((int)rank - 1);
    } else {
      aq_check(isnan(rank), "unfitted %s unranked", b);
    }
  }
  aq_check(rows == AQ_FRAGILITY_NIM + 3 && spectral == 3,
           "%d rows (want %d), %d spectral (want 3)", rows, AQ_FRAGILITY_NIM + 3, spectral);
  aq_check(seen == (1 << nfit) - 1, "ranks 1..%d each once (%#x)", nfit, seen);
  free(f);
}
