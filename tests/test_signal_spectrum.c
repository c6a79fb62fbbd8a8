/* test_signal_spectrum.c: response spectra (src/signal/spectrum.c) against
 * the oscillator's closed forms derived here, a 256-times finer sampling of
 * the same piecewise-linear input, the rotated input instead of the rotated
 * responses, PEER's displacement (.DT2) and PEER's NGA-West2 flatfile.
 *
 * The oscillator u'' + 2 z w u' + w^2 u = -a(t), at rest at t = 0,
 * w = 2 pi / T, wd = w sqrt(1 - z^2); PSA = w^2 max |u|.  Its free
 * solutions are e^{-z w t} (C1 cos wd t + C2 sin wd t) with C1 = u_h(0),
 * C2 = (u_h'(0) + z w C1) / wd, added to a particular solution u_p chosen so
 * that u_p(0) + C1 = 0 and u_p'(0) + u_h'(0) = 0:
 *   step a = A:          u_p = -A / w^2                        (u_p' = 0)
 *   ramp a = s t:        u_p = -s t / w^2 + 2 z s / w^3         (u_p' = -s / w^2)
 *     (check: 2 z w (-s / w^2) + w^2 (2 z s / w^3) = 0, w^2 (-s t / w^2) = -s t)
 *   sine a = A sin(W t): u_p = P sin W t + Q cos W t with
 *     (w^2 - W^2) P - 2 z w W Q = -A and (w^2 - W^2) Q + 2 z w W P = 0, so
 *     D = (w^2 - W^2)^2 + (2 z w W)^2, P = -A (w^2 - W^2) / D,
 *     Q = 2 z w W A / D; the steady state's amplitude is A / sqrt(D).
 * The step's peak is at wd t = pi: |u| = A / w^2 (1 + e^{-z pi / sqrt(1 -
 * z^2)}); at resonance (W = w) the steady state's PSA is A / (2 z).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"
#include "signal/spectrum.h"

#define PI 3.14159265358979323846
#define G0 9.80665 /* m/s^2 per g, written here, not taken from the code */

/* u(t) = u_p(t) + the free solution fitting u(0) = u'(0) = 0. */
typedef struct {
  double w, z, wd;
  double c1, c2;
} free_part;

static free_part fit_free(double T, double z, double up0, double upd0)
{
  free_part f;
  f.w = 2 * PI / T;
  f.z = z;
  f.wd = f.w * sqrt(1 - z * z);
  f.c1 = -up0;
  f.c2 = (-upd0 + z * f.w * f.c1) / f.wd;
  return f;
}

static double free_at(const free_part *f, double t)
{
  return exp(-f->z * f->w * t) * (f->c1 * cos(f->wd * t) + f->c2 * sin(f->wd * t));
}

static double *alloc_d(size_t n)
{
  double *p = calloc(n ? n : 1, sizeof(double));
  aq_check(p != NULL, "alloc %zu", n);
  return p;
}

/* A ramp is linear between samples, so the recurrence must be exact: every
 * sample of u against the closed form, from T = 0.3 dt (the oscillator
 * turns several times within one interval) to T = 1e4 dt.  Measured:
 * 4e-16 to 1.2e-15 of max |u| up to T = 0.737 s, 8e-15 at 4.1 s, 5e-14 at
 * 100 s (where u, the ground's displacement, is the difference of the
 * closed form's larger terms). */
#define RAMP_REL 1e-12
AQ_TEST(spectrum_ramp_every_sample_closed_form)
{
  const double dt = 0.01, s = 2.385, z = 0.05;
  const size_t n = 3000;
  const double periods[] = {0.003, 0.0213, 0.1, 0.737, 4.1, 100.0};
  double *a = alloc_d(n), *u = alloc_d(n), *v = alloc_d(n);
  for (size_t k = 0; k < n; k++)
    a[k] = s * (double)k * dt;
  for (size_t i = 0; i < sizeof periods / sizeof *periods; i++) {
    double T = periods[i], w = 2 * PI / T;
    aq_error e;
    aq_check(aq_spectrum_response(a, n, dt, z, T, u, v, &e) == AQ_OK,
             "response T = %g", T);
    free_part f = fit_free(T, z, 2 * z * s / (w * w * w), -s / (w * w));
    double err = 0, m = 0;
    for (size_t k = 0; k < n; k++) {
      double t = (double)k * dt;
      double want = -s * t / (w * w) + 2 * z * s / (w * w * w) + free_at(&f, t);
      err = fmax(err, fabs(u[k] - want));
      m = fmax(m, fabs(want));
    }
    aq_check_abs(err / m, 0, RAMP_REL, "ramp, T = %g s: max |u - closed form| "
                 "/ max |u|", T);
  }
  free(a);
  free(u);
  free(v);
}

/* The step's first peak, at wd t = pi, falls between samples for these
 * periods and dt: the continuous peak must be found (PSA = A (1 + e^{-z pi
 * / sqrt(1 - z^2)}) exactly), while the sampled peak is the closed form's
 * largest value at the samples.  Measured: 4e-16 and 2e-16. */
#define STEP_PEAK_REL 1e-13
AQ_TEST(spectrum_step_peak_between_samples)
{
  const double A = 1.7321, dt = 0.01;
  const double periods[] = {0.0137, 0.0317, 0.1237, 0.7713};
  const double dampings[] = {0.05, 0.02, 0.3};
  const size_t n = 400;
  double *a = alloc_d(n);
  for (size_t k = 0; k < n; k++)
    a[k] = A;
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  aq_check(ws != NULL, "workspace");
  for (size_t d = 0; d < sizeof dampings / sizeof *dampings; d++)
    for (size_t i = 0; i < sizeof periods / sizeof *periods; i++) {
      double T = periods[i], z = dampings[d], w = 2 * PI / T;
      double psa, psa_s;
      aq_spectrum_opts o;
      aq_spectrum_opts_default(&o);
      aq_error e;
      double psa_p;
      aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, &T, 1, &psa_p, &e) == AQ_OK,
               "psa at PEER's refined samples (the default)");
      o.peaks = AQ_SPECTRUM_PEAKS_EXACT;
      aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, &T, 1, &psa, &e) == AQ_OK,
               "psa");
      o.peaks = AQ_SPECTRUM_PEAKS_SAMPLES;
      aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, &T, 1, &psa_s, &e) == AQ_OK,
               "psa at the samples");
      free_part f = fit_free(T, z, -A / (w * w), 0);
      /* PEER's N, written out: 10 dt / T = 7.30, 3.15, 0.81, 0.13 */
      const size_t peer_n[] = {8, 4, 1, 1};
      double ms = 0, mp = 0;
      for (size_t k = 0; k < n; k++)
        ms = fmax(ms, fabs(w * w * (-A / (w * w) + free_at(&f, (double)k * dt))));
      for (size_t k = 0; k < n * peer_n[i]; k++)
        mp = fmax(mp, fabs(w * w * (-A / (w * w) +
                                    free_at(&f, (double)k * dt / (double)peer_n[i]))));
      aq_check_rel(psa_p, mp, STEP_PEAK_REL,
                   "step, T = %g s, z = %g: the peak at dt / %zu", T, z, peer_n[i]);
      aq_check_rel(psa, A * (1 + exp(-z * PI / sqrt(1 - z * z))), STEP_PEAK_REL,
                   "step, T = %g s, z = %g: the peak between samples", T, z);
      aq_check_rel(psa_s, ms, STEP_PEAK_REL,
                   "step, T = %g s, z = %g: the peak at the samples", T, z);
      aq_check(psa_s < psa * (1 - 1e-6), "T = %g s: the sampled peak %.9g is "
               "below the true one %.9g", T, psa_s, psa);
    }
  aq_spectrum_ws_free(ws);
  free(a);
}

/* The step's peaks at wd t = pi, 3 pi, ... shrink slowly at z = 0.002, and
 * with wd dt = 2 pi / 8.667 the first lies dt / 3 after a sample, the
 * second (3 times later) on a sample: the largest sampled value is the
 * second peak, A (1 + e^{-3 z pi / sqrt(1 - z^2)}), which the first,
 * sampled, falls short of (by 1 - cos(wd dt / 3) = 2.9 %) but exceeds in
 * truth.  So the first peak's interval, both of whose ends lie below the
 * largest sample, must still be searched: PSA = A (1 + e^{-z pi / sqrt(1 -
 * z^2)}). */
AQ_TEST(spectrum_peak_in_an_interval_below_the_largest_sample)
{
  const double A = 0.8461, dt = 0.01, z = 0.002;
  const double wd = 2 * PI / (8.0 + 2.0 / 3.0) / dt, w = wd / sqrt(1 - z * z);
  double T = 2 * PI / w, psa, psa_s;
  const size_t n = 60;
  double *a = alloc_d(n);
  for (size_t k = 0; k < n; k++)
    a[k] = A;
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  aq_spectrum_opts o;
  aq_spectrum_opts_default(&o);
  aq_error e;
  o.peaks = AQ_SPECTRUM_PEAKS_EXACT;
  aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, &T, 1, &psa, &e) == AQ_OK, "psa");
  o.peaks = AQ_SPECTRUM_PEAKS_SAMPLES;
  aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, &T, 1, &psa_s, &e) == AQ_OK, "psa");
  double r = sqrt(1 - z * z);
  aq_check_rel(psa_s, A * (1 + exp(-3 * z * PI / r)), 1e-13,
               "the largest sample is the second peak");
  aq_check_rel(psa, A * (1 + exp(-z * PI / r)), 1e-13, "the first peak, "
               "between samples below the second's");
  aq_spectrum_ws_free(ws);
  free(a);
}

/* A sine from rest: every sample against the closed form (transient and
 * steady state) over the first 12 s, and the steady state's amplitude over
 * the last three cycles of 60 s, below, at and above resonance.  The
 * record is the sine at the samples, linear between them, which departs
 * from the sine by up to (W dt)^2 / 8 = 8.3e-6 of A here; the response by
 * as much relative to its own size (measured: 3.1e-6 of max |u|, and 6e-6
 * on the steady amplitude, whose sampled peak also lies (W dt)^2 / 8 low). */
#define SINE_REL 2e-5
AQ_TEST(spectrum_sine_transient_and_steady_state)
{
  const double A = 0.9173, f_in = 1.3, z = 0.05, dt = 0.001;
  const double W = 2 * PI * f_in;
  const double ratios[] = {0.6, 1.0, 1.7}; /* W / w */
  const size_t n = 60000;
  double *a = alloc_d(n), *u = alloc_d(n), *v = alloc_d(n);
  for (size_t k = 0; k < n; k++)
    a[k] = A * sin(W * (double)k * dt);
  for (size_t i = 0; i < sizeof ratios / sizeof *ratios; i++) {
    double w = W / ratios[i], T = 2 * PI / w;
    double D = (w * w - W * W) * (w * w - W * W) + (2 * z * w * W) * (2 * z * w * W);
    double P = -A * (w * w - W * W) / D, Q = 2 * z * w * W * A / D;
    aq_error e;
    aq_check(aq_spectrum_response(a, n, dt, z, T, u, v, &e) == AQ_OK, "response");
    free_part fp = fit_free(T, z, Q, W * P);
    double err = 0, m = 0;
    for (size_t k = 0; k < 12000; k++) {
      double t = (double)k * dt;
      double want = P * sin(W * t) + Q * cos(W * t) + free_at(&fp, t);
      err = fmax(err, fabs(u[k] - want));
      m = fmax(m, fabs(want));
    }
    aq_check_abs(err / m, 0, SINE_REL, "sine, W/w = %g: transient, max |u - "
                 "closed form| / max |u|", ratios[i]);
    double late = 0;
    size_t k0 = n - (size_t)(3 / f_in / dt);
    for (size_t k = k0; k < n; k++)
      late = fmax(late, fabs(u[k]));
    aq_check_rel(w * w * late, w * w * A / sqrt(D), SINE_REL,
                 "sine, W/w = %g: steady-state PSA", ratios[i]);
    if (ratios[i] == 1.0)
      aq_check_rel(w * w * late, A / (2 * z), SINE_REL,
                   "resonance: PSA = A / (2 z)");
  }
  free(a);
  free(u);
  free(v);
}

/* Read a shipped record or fail the test. */
static int read_rec(const char *path, aq_record *r)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_error e;
  int ok = aq_record_read(path, &ro, r, &e) == AQ_OK;
  aq_check(ok, "read %s: %s", path, e.message);
  return ok;
}

#define ELC180 "tests/data/records/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"
#define ELC270 "tests/data/records/RSN6_IMPVALL.I_I-ELC270-hor2.AT2"

/* The same input, linear between samples, sampled 256 times finer (every
 * fine sample lies on the coarse input's lines): the fine response at its
 * samples is exact, so its largest value is a lower bound of the true peak
 * within (w dt / 256)^2 / 8 * max |u''| of it.  The spectrum must lie
 * between, at periods from 1.1 dt (several turns per interval) to 1 s. */
AQ_TEST(spectrum_peak_against_a_finer_sampling)
{
  aq_record r;
  if (!read_rec(ELC180, &r))
    return;
  const size_t m = 256, n = 1500; /* the first 15 s, the strong part */
  const size_t nf = (n - 1) * m + 1;
  double *af = alloc_d(nf), *u = alloc_d(nf), *v = alloc_d(nf);
  double pga = 0;
  for (size_t k = 0; k + 1 < n; k++)
    for (size_t j = 0; j < m; j++)
      af[k * m + j] = r.acc_mps2[k] +
                      (r.acc_mps2[k + 1] - r.acc_mps2[k]) * ((double)j / (double)m);
  af[nf - 1] = r.acc_mps2[n - 1];
  for (size_t k = 0; k < n; k++)
    pga = fmax(pga, fabs(r.acc_mps2[k]));
  const double periods[] = {0.011, 0.017, 0.029, 0.05, 0.1, 0.31, 1.0};
  const double z = 0.05, dt = r.dt_s;
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  for (size_t i = 0; i < sizeof periods / sizeof *periods; i++) {
    double T = periods[i], w = 2 * PI / T, psa, psa_s;
    aq_spectrum_opts o;
    aq_spectrum_opts_default(&o);
    aq_error e;
    o.peaks = AQ_SPECTRUM_PEAKS_EXACT;
    aq_check(aq_spectrum_psa(ws, &o, r.acc_mps2, n, dt, z, &T, 1, &psa, &e) == AQ_OK,
             "psa");
    o.peaks = AQ_SPECTRUM_PEAKS_SAMPLES;
    aq_check(aq_spectrum_psa(ws, &o, r.acc_mps2, n, dt, z, &T, 1, &psa_s, &e) == AQ_OK,
             "psa at samples");
    aq_check(aq_spectrum_response(af, nf, dt / (double)m, z, T, u, v, &e) == AQ_OK,
             "fine response");
    double fine = 0, vmax = 0;
    for (size_t k = 0; k < nf; k++) {
      fine = fmax(fine, w * w * fabs(u[k]));
      vmax = fmax(vmax, w * fabs(v[k]));
    }
    /* |w^2 u''| / w^2 = |x''| <= |a| + sqrt(1 + 4 z^2) sqrt(x^2 + (w u')^2) */
    double th = w * dt / (double)m;
    double slack = th * th / 8 * (pga + sqrt(1 + 4 * z * z) * (fine + vmax) * 1.01);
    aq_check(psa >= fine * (1 - 1e-13), "T = %g s: PSA %.12g >= the fine "
             "sampling's %.12g", T, psa, fine);
    aq_check(psa <= fine + slack, "T = %g s: PSA %.12g <= the fine sampling's "
             "%.12g + %.3g", T, psa, fine, slack);
    aq_check(psa_s <= psa, "T = %g s: sampled %.9g <= continuous %.9g", T,
             psa_s, psa);
    if (getenv("AQ_TEST_VERBOSE"))
      printf("  T = %g s: PSA %.9g, finer %.9g (slack %.2g), sampled %.9g (%.2f %% low)\n",
             T, psa, fine, slack, psa_s, 100 * (1 - psa_s / psa));
  }
  aq_spectrum_ws_free(ws);
  aq_record_free(&r);
  free(af);
  free(u);
  free(v);
}

/* T -> 0: PSA(0) is PGA exactly, and PSA(T) -> PGA: the response is then
 * the input's quasi-static part x_p = -a + 2 z sigma (sigma = da/d(w t),
 * at most max|da| / (w dt)) plus a transient each slope change starts, of
 * size up to 2 max sigma sqrt(1 + 4 z^2), which decays by e^{-z w dt} per
 * sample: |PSA - PGA| <= (2 z + 2 sqrt(1 + 4 z^2) / (1 - e^{-z w dt})) max
 * sigma. */
AQ_TEST(spectrum_zero_period_is_pga)
{
  aq_record r;
  if (!read_rec(ELC180, &r))
    return;
  double pga = 0, dmax = 0, z = 0.05, dt = r.dt_s;
  for (size_t k = 0; k < r.npts; k++) {
    pga = fmax(pga, fabs(r.acc_mps2[k]));
    if (k)
      dmax = fmax(dmax, fabs(r.acc_mps2[k] - r.acc_mps2[k - 1]));
  }
  const double periods[] = {0, 1e-3, 1e-4, 1e-5};
  double psa[4];
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  aq_error e;
  aq_check(aq_spectrum_psa(ws, NULL, r.acc_mps2, r.npts, dt, z, periods, 4, psa,
                           &e) == AQ_OK, "psa");
  aq_check_rel(psa[0], pga, 1e-15, "PSA(0) = PGA");
  aq_check_rel(psa[0] / G0, 0.2808, 0.5e-4 / 0.2808,
               "PGA as PROVENANCE.md states it (0.2808 g)");
  double prev = INFINITY;
  for (int i = 1; i < 4; i++) {
    double th = 2 * PI / periods[i] * dt, sig = dmax / th;
    double bound = (2 * z + 2 * sqrt(1 + 4 * z * z) / (1 - exp(-z * th))) * sig;
    double d = fabs(psa[i] - pga);
    aq_check(d <= bound, "T = %g s: |PSA - PGA| = %.3g <= %.3g", periods[i], d,
             bound);
    aq_check(d <= prev, "T = %g s: closer to PGA than at the longer period", periods[i]);
    prev = d;
  }
  aq_spectrum_ws_free(ws);
  aq_record_free(&r);
}

/* Read the values of a PEER .DT2 (4 header lines, 5 values a line), cm. */
static double dt2_peak_cm(const char *path)
{
  FILE *f = fopen(path, "r");
  aq_check(f != NULL, "open %s", path);
  if (!f)
    return NAN;
  char line[256];
  for (int i = 0; i < 4; i++)
    if (!fgets(line, sizeof line, f))
      break;
  double v, m = 0;
  while (fscanf(f, "%lf", &v) == 1)
    m = fmax(m, fabs(v));
  fclose(f);
  return m;
}

/* T -> infinity: the mass stays still and u -> -(ground displacement), so
 * SD = PSA / w^2 -> PGD, while PSA -> 0.  At T = 1e7 s the spring and the
 * damper change u by (w t)^2 / 2 and z w t of it over the 43 s record
 * (1e-11, 1.4e-6).  References: the exact double integral of the input
 * linear between samples (d_{k+1} = d_k + v_k dt + (2 a_k + a_{k+1})
 * dt^2 / 6), and PEER's own displacement, whose peak PROVENANCE.md gives as
 * 8.2944 cm and whose integration differs from a trapezoidal one by up to
 * 1.4e-3 cm. */
AQ_TEST(spectrum_long_period_displacement_is_pgd)
{
  aq_record r;
  if (!read_rec("tests/data/records/RSN1616_DUZCE_362-E.AT2", &r))
    return;
  double T = 1e7, w = 2 * PI / T, z = 0.05, dt = r.dt_s, psa;
  aq_error e;
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  aq_check(aq_spectrum_psa(ws, NULL, r.acc_mps2, r.npts, dt, z, &T, 1, &psa,
                           &e) == AQ_OK, "psa");
  double d = 0, vel = 0, pgd = 0;
  for (size_t k = 0; k + 1 < r.npts; k++) {
    double a0 = r.acc_mps2[k], a1 = r.acc_mps2[k + 1];
    d += vel * dt + (2 * a0 + a1) * dt * dt / 6;
    vel += (a0 + a1) * dt / 2;
    pgd = fmax(pgd, fabs(d));
  }
  double sd = psa / (w * w);
  aq_check_rel(sd, pgd, 5e-6, "SD(1e7 s) = PGD of the exact double integral");
  double peer_cm = dt2_peak_cm("tests/data/records/RSN1616_DUZCE_362-E.DT2");
  aq_check_rel(peer_cm, 8.2944, 1e-5, "PEER's PGD as PROVENANCE.md states it");
  aq_check_rel(100 * sd, peer_cm, 3e-4, "SD(1e7 s) = PEER's PGD (measured "
               "1.8e-4: PEER's integration)");
  aq_check(psa < 1e-12 * G0, "PSA(1e7 s) = %.3g m/s^2 -> 0", psa);
  aq_spectrum_ws_free(ws);
  aq_record_free(&r);
}

/* RotD: each angle's peak from the rotated responses must equal the
 * one-component spectrum of the rotated input a1 cos + a2 sin (another
 * path through the code: the oscillator's linearity is what RotD rests
 * on); RotD50 is then the median of those (mean of the middle two of 180)
 * and RotD100 their largest, both found here by sorting; RotD100 >= each
 * component's own PSA >= ... and RotD50 <= RotD100.  The shorter record
 * (ELC270, 26 samples fewer) counts as zero after its end. */
AQ_TEST(spectrum_rotd_from_rotated_inputs)
{
  aq_record r1, r2;
  if (!read_rec(ELC180, &r1) || !read_rec(ELC270, &r2))
    return;
  size_t n = r1.npts > r2.npts ? r1.npts : r2.npts;
  const double periods[] = {0, 0.013, 0.05, 0.2, 0.7, 3.0};
  const size_t np = sizeof periods / sizeof *periods, na = 180;
  aq_rotd out[6];
  double *peaks = alloc_d(np * na), *rot = alloc_d(n), psa[6], psa1[6], psa2[6];
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  aq_error e;
  for (int mode = 0; mode < 3; mode++) {
    aq_spectrum_opts o;
    aq_spectrum_opts_default(&o);
    o.peaks = (aq_spectrum_peaks)mode;
    aq_check(aq_spectrum_rotd(ws, &o, r1.acc_mps2, r1.npts, r2.acc_mps2, r2.npts,
                              r1.dt_s, 0.05, periods, np, out, peaks, &e) == AQ_OK,
             "rotd");
    aq_check(aq_spectrum_psa(ws, &o, r1.acc_mps2, r1.npts, r1.dt_s, 0.05, periods,
                             np, psa1, &e) == AQ_OK, "psa 1");
    aq_check(aq_spectrum_psa(ws, &o, r2.acc_mps2, r2.npts, r2.dt_s, 0.05, periods,
                             np, psa2, &e) == AQ_OK, "psa 2");
    double worst = 0;
    for (size_t j = 0; j < na; j++) {
      double th = PI * (double)j / (double)na, c = cos(th), s = sin(th);
      for (size_t k = 0; k < n; k++)
        rot[k] = c * (k < r1.npts ? r1.acc_mps2[k] : 0) +
                 s * (k < r2.npts ? r2.acc_mps2[k] : 0);
      aq_check(aq_spectrum_psa(ws, &o, rot, n, r1.dt_s, 0.05, periods, np, psa,
                               &e) == AQ_OK, "rotated psa");
      for (size_t i = 0; i < np; i++)
        worst = fmax(worst, fabs(peaks[i * na + j] - psa[i]) / psa[i]);
    }
    aq_check_abs(worst, 0, 1e-13, "peaks %s: each angle's peak = the rotated input's "
                 "PSA (worst relative difference)", aq_spectrum_peaks_names[mode]);
    for (size_t i = 0; i < np; i++) {
      double *p = peaks + i * na, srt[180];
      memcpy(srt, p, sizeof srt);
      for (size_t a = 1; a < na; a++) /* insertion sort */
        for (size_t b = a; b > 0 && srt[b - 1] > srt[b]; b--) {
          double t = srt[b];
          srt[b] = srt[b - 1];
          srt[b - 1] = t;
        }
      aq_check_rel(out[i].rotd50_mps2, 0.5 * (srt[89] + srt[90]), 1e-15,
                   "T = %g: RotD50 = the median", periods[i]);
      aq_check_rel(out[i].rotd100_mps2, srt[179], 1e-15, "T = %g: RotD100 = the "
                   "largest", periods[i]);
      aq_check_rel(out[i].psa1_mps2, psa1[i], 1e-13, "T = %g: angle 0 = "
                   "component 1", periods[i]);
      aq_check_rel(out[i].psa2_mps2, psa2[i], 1e-13, "T = %g: angle 90 = "
                   "component 2", periods[i]);
      aq_check_rel(out[i].geomean_mps2, sqrt(psa1[i] * psa2[i]), 1e-13,
                   "T = %g: the geometric mean", periods[i]);
      aq_check(out[i].rotd100_mps2 >= psa1[i] && out[i].rotd100_mps2 >= psa2[i],
               "T = %g: RotD100 >= each component", periods[i]);
      aq_check(out[i].rotd50_mps2 <= out[i].rotd100_mps2, "T = %g: RotD50 <= "
               "RotD100", periods[i]);
    }
  }
  aq_spectrum_ws_free(ws);
  free(peaks);
  free(rot);
  aq_record_free(&r1);
  aq_record_free(&r2);
}

/* Two steps, A1 = R cos 30 deg and A2 = R sin 30 deg: the input rotated by
 * theta is a step of R cos(theta - 30 deg), so each angle's peak is
 * |R cos(theta - 30 deg)| (1 + e^{-z pi / sqrt(1 - z^2)}), all between the
 * samples at these periods (the last, at z = 0.002, as in
 * spectrum_peak_in_an_interval_below_the_largest_sample); RotD100 is R (1 +
 * ...) (30 deg is an angle of the grid), RotD50 the median of the 180.  Measured: 1e-15 R and
 * 5.8e-15 R. */
AQ_TEST(spectrum_rotd_of_two_steps)
{
  const double R = 1.3, dt = 0.01;
  const double A1 = R * cos(PI / 6), A2 = R * sin(PI / 6);
  const size_t n = 300, na = 180;
  /* the last: as spectrum_peak_in_an_interval_below_the_largest_sample */
  const double dampings[] = {0.05, 0.05, 0.002};
  const double periods[] = {0.0137, 0.1237,
                            sqrt(1 - 0.002 * 0.002) * (8.0 + 2.0 / 3.0) * dt};
  double *a1 = alloc_d(n), *a2 = alloc_d(n), peaks[180], want[180];
  for (size_t k = 0; k < n; k++) {
    a1[k] = A1;
    a2[k] = A2;
  }
  aq_rotd out[1];
  aq_error e;
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  aq_spectrum_opts o;
  aq_spectrum_opts_default(&o);
  o.peaks = AQ_SPECTRUM_PEAKS_EXACT;
  for (int i = 0; i < 3; i++) {
    double z = dampings[i];
    aq_check(aq_spectrum_rotd(ws, &o, a1, n, a2, n, dt, z, &periods[i], 1, out,
                              peaks, &e) == AQ_OK, "rotd");
    double amp = 1 + exp(-z * PI / sqrt(1 - z * z));
    double worst = 0;
    for (size_t j = 0; j < na; j++) {
      want[j] = fabs(R * cos(PI * (double)j / (double)na - PI / 6)) * amp;
      worst = fmax(worst, fabs(peaks[j] - want[j]));
    }
    aq_check_abs(worst / R, 0, 1e-13, "T = %g s: every angle's peak, the "
                 "worst error / R", periods[i]);
    for (size_t a = 1; a < na; a++)
      for (size_t b = a; b > 0 && want[b - 1] > want[b]; b--) {
        double t = want[b];
        want[b] = want[b - 1];
        want[b - 1] = t;
      }
    aq_check_rel(out[0].rotd100_mps2, R * amp, 1e-13, "T = %g s: RotD100",
                 periods[i]);
    aq_check_rel(out[0].rotd50_mps2, 0.5 * (want[89] + want[90]), 1e-13,
                 "T = %g s: RotD50", periods[i]);
  }
  aq_spectrum_ws_free(ws);
  free(a1);
  free(a2);
}

/* RotD100 >= each component and RotD50 <= RotD100 on every pair shipped
 * and PEER's 111 periods, both peak definitions. */
AQ_TEST(spectrum_rotd_orders_on_every_pair)
{
  static const char *pairs[][2] = {
      {ELC180, ELC270},
      {"tests/data/records/RSN763_LOMAP_GIL067.AT2",
       "tests/data/records/RSN763_LOMAP_GIL337.AT2"},
      {"tests/data/records/AOM0170806140843.NS",
       "tests/data/records/AOM0170806140843.EW"},
  };
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  const size_t np = AQ_SPECTRUM_PEER_N;
  aq_rotd *out = malloc(np * sizeof *out);
  double *p1 = alloc_d(np), *p2 = alloc_d(np);
  for (size_t q = 0; q < sizeof pairs / sizeof *pairs; q++) {
    aq_record r1, r2;
    if (!read_rec(pairs[q][0], &r1))
      continue;
    if (!read_rec(pairs[q][1], &r2)) {
      aq_record_free(&r1);
      continue;
    }
    for (int mode = 0; mode < 3; mode++) {
      aq_spectrum_opts o;
      aq_spectrum_opts_default(&o);
      o.peaks = (aq_spectrum_peaks)mode;
      aq_error e;
      aq_check(aq_spectrum_rotd(ws, &o, r1.acc_mps2, r1.npts, r2.acc_mps2, r2.npts,
                                r1.dt_s, 0.05, aq_spectrum_peer_periods_s, np,
                                out, NULL, &e) == AQ_OK, "rotd %s", pairs[q][0]);
      aq_check(aq_spectrum_psa(ws, &o, r1.acc_mps2, r1.npts, r1.dt_s, 0.05,
                               aq_spectrum_peer_periods_s, np, p1, &e) == AQ_OK, "p1");
      aq_check(aq_spectrum_psa(ws, &o, r2.acc_mps2, r2.npts, r2.dt_s, 0.05,
                               aq_spectrum_peer_periods_s, np, p2, &e) == AQ_OK, "p2");
      size_t bad = 0;
      for (size_t i = 0; i < np; i++)
        bad += !(out[i].rotd100_mps2 >= p1[i] && out[i].rotd100_mps2 >= p2[i] &&
                 out[i].rotd50_mps2 <= out[i].rotd100_mps2 && out[i].rotd50_mps2 > 0);
      aq_check(bad == 0, "%s (peaks %s): %zu periods out of order", pairs[q][0],
               aq_spectrum_peaks_names[mode], bad);
    }
    aq_record_free(&r1);
    aq_record_free(&r2);
  }
  free(out);
  free(p1);
  free(p2);
  aq_spectrum_ws_free(ws);
}

/* PEER's NGA-West2 flatfile, RSN6 (Imperial Valley-02, El Centro Array #9),
 * RotD50 at 5 %, g, as printed: PGA 0.23349; PSA(0.1 s) 0.42696, (0.2 s)
 * 0.57773, (0.5 s) 0.629952, (1 s) 0.351286, (2 s) 0.215745.  PEER takes
 * each oscillator's peak at the samples (refined only below T = 10 dt =
 * 0.1 s): the files as published, peaks at PEER's refined samples, the
 * default, must agree within half a unit of the last printed digit.
 * Measured (archquake - flatfile, g): +2.6e-6, -4.5e-7, -1.9e-7, +2.2e-7,
 * -3.4e-8, +2.1e-7.  The continuous peaks lie above by +2.5e-3 (0.58 %),
 * +5.3e-3 (0.91 %), +6.4e-4, +2.2e-6, +2.1e-5 g. */
AQ_TEST(spectrum_rotd50_nga_west2_flatfile_rsn6)
{
  aq_record r1, r2;
  if (!read_rec(ELC180, &r1) || !read_rec(ELC270, &r2))
    return;
  const double periods[] = {0, 0.1, 0.2, 0.5, 1.0, 2.0};
  const double flat_g[] = {0.23349, 0.42696, 0.57773, 0.629952, 0.351286, 0.215745};
  const double half_unit[] = {5e-6, 5e-6, 5e-6, 5e-7, 5e-7, 5e-7};
  aq_rotd out[6];
  aq_spectrum_opts o;
  aq_spectrum_opts_default(&o); /* PEER's refined samples: at dt = 0.01 s and
                                   these periods, N = 1, the samples */
  aq_error e;
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  aq_check(aq_spectrum_rotd(ws, &o, r1.acc_mps2, r1.npts, r2.acc_mps2, r2.npts,
                            r1.dt_s, 0.05, periods, 6, out, NULL, &e) == AQ_OK,
           "rotd");
  for (int i = 0; i < 6; i++)
    aq_check_abs(out[i].rotd50_mps2 / G0, flat_g[i], half_unit[i],
                 "RSN6 RotD50 at T = %g s (g)", periods[i]);
  aq_spectrum_ws_free(ws);
  aq_record_free(&r1);
  aq_record_free(&r2);
}

/* Many periods in one call, in any order, with T = 0 and periods PEER
 * refines (T < 10 dt) among them: the peaks at the samples run several
 * oscillators at a time (spectrum.c), so each period's PSA at the samples
 * must equal max_k w^2 |u_k| of its own response history
 * (aq_spectrum_response, checked against closed forms above) to the
 * rounding of u = x / w^2 and back (2 ulps: 1e-15 is the bound), PEER's at
 * N = 1 must be the samples' to the bit, and every PSA must be the one the
 * period gets alone in a call, and with one_at_a_time (each oscillator's
 * own loop, as before the grouping), to the bit.  37 periods: two full groups and
 * a part one, whatever the group size up to 16. */
AQ_TEST(spectrum_many_periods_in_one_call)
{
  const double dt = 0.005, z = 0.05;
  const size_t n = 3000;
  const double periods[] = {2.7,  0.0,   0.013, 0.33, 0.05,  1.9,  0.071, 0.6,  0.21, 4.0,
                            0.11, 0.032, 0.9,   0.45, 0.08,  0.15, 3.3,   0.06, 1.2,  0.27,
                            0.5,  0.095, 0.75,  2.2,  0.017, 0.38, 1.5,   0.12, 0.3,  0.057,
                            6.0,  0.19,  1.05,  0.66, 0.24,  0.09, 0.41};
  enum { NP = sizeof periods / sizeof *periods };
  double *a = alloc_d(n), *u = alloc_d(n), *v = alloc_d(n);
  for (size_t k = 0; k < n; k++) {
    double t = (double)k * dt;
    a[k] = (t < 3 ? t / 3 : exp(-(t - 3) / 5)) *
           (1.3 * sin(2 * PI * 0.7 * t) + 0.8 * sin(2 * PI * 3.1 * t + 1) +
            0.4 * sin(2 * PI * 11.3 * t + 2) + 0.2 * sin(2 * PI * 37 * t));
  }
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  aq_check(ws != NULL, "workspace");
  aq_spectrum_opts o;
  aq_error e;
  double smp[NP], peer[NP], sep[2][NP], one;
  aq_spectrum_opts_default(&o);
  o.peaks = AQ_SPECTRUM_PEAKS_SAMPLES;
  aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, periods, NP, smp, &e) == AQ_OK, "samples");
  o.peaks = AQ_SPECTRUM_PEAKS_PEER;
  aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, periods, NP, peer, &e) == AQ_OK, "peer");
  o.one_at_a_time = 1;
  aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, periods, NP, sep[1], &e) == AQ_OK, "peer");
  o.peaks = AQ_SPECTRUM_PEAKS_SAMPLES;
  aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, periods, NP, sep[0], &e) == AQ_OK, "samples");
  o.one_at_a_time = 0;
  for (size_t i = 0; i < NP; i++) {
    double T = periods[i], want = 0;
    if (T > 0) {
      double w = 2 * PI / T;
      aq_check(aq_spectrum_response(a, n, dt, z, T, u, v, &e) == AQ_OK, "response");
      for (size_t k = 0; k < n; k++)
        want = fmax(want, w * w * fabs(u[k]));
    } else {
      for (size_t k = 0; k < n; k++)
        want = fmax(want, fabs(a[k]));
    }
    aq_check_rel(smp[i], want, 1e-15, "T = %g s: PSA at the samples against the "
                 "response history's peak", T);
    if (10 * dt <= T)
      aq_check(peer[i] == smp[i], "T = %g s: peer (N = 1) %.17g is the samples' %.17g",
               T, peer[i], smp[i]);
    else if (T > 0)
      aq_check(peer[i] > smp[i], "T = %g s: peer (N > 1) %.17g above the samples' %.17g",
               T, peer[i], smp[i]);
    aq_check(sep[0][i] == smp[i] && sep[1][i] == peer[i], "T = %g s: one at a time "
             "%.17g, %.17g; grouped %.17g, %.17g", T, sep[0][i], sep[1][i], smp[i], peer[i]);
    for (int m = 0; m < 2; m++) {
      o.peaks = m ? AQ_SPECTRUM_PEAKS_PEER : AQ_SPECTRUM_PEAKS_SAMPLES;
      aq_check(aq_spectrum_psa(ws, &o, a, n, dt, z, &T, 1, &one, &e) == AQ_OK, "alone");
      aq_check(one == (m ? peer[i] : smp[i]), "T = %g s, %s: alone %.17g, among %d "
               "periods %.17g", T, aq_spectrum_peaks_names[o.peaks], one, (int)NP,
               m ? peer[i] : smp[i]);
    }
  }
  /* RotD's angles 0 and 90 degrees project on each component alone
   * (1 x1 + 0 x2 = x1): its H1 and H2 at the samples are the components'
   * own PSA at the samples, to the bit (the two responses run in one loop,
   * spectrum.c's respond2) */
  double *b = alloc_d(n), smp2[NP];
  for (size_t k = 0; k < n; k++)
    b[k] = 0.7 * a[n - 1 - k] + 0.3 * a[(7 * k) % n];
  aq_rotd rd[NP];
  o.peaks = AQ_SPECTRUM_PEAKS_SAMPLES;
  aq_check(aq_spectrum_psa(ws, &o, b, n, dt, z, periods, NP, smp2, &e) == AQ_OK, "psa 2");
  aq_check(aq_spectrum_rotd(ws, &o, a, n, b, n, dt, z, periods, NP, rd, NULL, &e) == AQ_OK,
           "rotd");
  for (size_t i = 0; i < NP; i++)
    aq_check(rd[i].psa1_mps2 == smp[i] && rd[i].psa2_mps2 == smp2[i],
             "T = %g s: RotD's H1, H2 %.17g, %.17g; alone %.17g, %.17g", periods[i],
             rd[i].psa1_mps2, rd[i].psa2_mps2, smp[i], smp2[i]);
  /* and every RotD value as with each component in its own loop */
  aq_rotd rs[NP];
  for (int m = 0; m < 3; m++) {
    o.peaks = (aq_spectrum_peaks)m;
    o.one_at_a_time = 0;
    aq_check(aq_spectrum_rotd(ws, &o, a, n, b, n - 400, dt, z, periods, NP, rd, NULL, &e) ==
                 AQ_OK, "rotd");
    o.one_at_a_time = 1;
    aq_check(aq_spectrum_rotd(ws, &o, a, n, b, n - 400, dt, z, periods, NP, rs, NULL, &e) ==
                 AQ_OK, "rotd one at a time");
    for (size_t i = 0; i < NP; i++)
      aq_check(rd[i].rotd50_mps2 == rs[i].rotd50_mps2 &&
                   rd[i].rotd100_mps2 == rs[i].rotd100_mps2 &&
                   rd[i].psa1_mps2 == rs[i].psa1_mps2 && rd[i].psa2_mps2 == rs[i].psa2_mps2,
               "T = %g s, %s: RotD50 %.17g, RotD100 %.17g; one at a time %.17g, %.17g",
               periods[i], aq_spectrum_peaks_names[m], rd[i].rotd50_mps2,
               rd[i].rotd100_mps2, rs[i].rotd50_mps2, rs[i].rotd100_mps2);
  }
  o.one_at_a_time = 0;
  free(b);
  /* PEER's refined periods, several at a time too: the same samples at
   * dt = 0.02 s, where 14 of the periods have N = ceil(10 dt / T) > 1:
   * each PSA against max w^2 |u| of the record resampled here (linearly)
   * at dt / N (the piecewise-linear recursion run at dt / N reaches the
   * same points by another path: 1e-10, measured 4e-14 at most), and
   * against one_at_a_time to the bit */
  const double dt2 = 0.02;
  double pr[NP], pr1[NP];
  o.peaks = AQ_SPECTRUM_PEAKS_PEER;
  aq_check(aq_spectrum_psa(ws, &o, a, n, dt2, z, periods, NP, pr, &e) == AQ_OK, "peer");
  o.one_at_a_time = 1;
  aq_check(aq_spectrum_psa(ws, &o, a, n, dt2, z, periods, NP, pr1, &e) == AQ_OK, "peer");
  o.one_at_a_time = 0;
  size_t refined = 0;
  for (size_t i = 0; i < NP; i++) {
    double T = periods[i];
    aq_check(pr[i] == pr1[i], "dt = 0.02 s, T = %g s: peer %.17g, one at a time %.17g", T,
             pr[i], pr1[i]);
    size_t N = T > 0 ? (size_t)ceil(10 * dt2 / T - 1e-9) : 1;
    if (N < 2)
      continue;
    refined++;
    size_t nf = (n - 1) * N + 1;
    double *f = alloc_d(nf), *uf = alloc_d(nf), *vf = alloc_d(nf), w = 2 * PI / T, want = 0;
    for (size_t k = 0; k + 1 < n; k++)
      for (size_t j = 0; j < N; j++)
        f[k * N + j] = a[k] + (a[k + 1] - a[k]) * ((double)j / (double)N);
    f[nf - 1] = a[n - 1];
    aq_check(aq_spectrum_response(f, nf, dt2 / (double)N, z, T, uf, vf, &e) == AQ_OK,
             "response at dt / N");
    for (size_t k = 0; k < nf; k++)
      want = fmax(want, w * w * fabs(uf[k]));
    aq_check_rel(pr[i], want, 1e-10, "dt = 0.02 s, T = %g s: peer (N = %zu) against the "
                 "record resampled at dt / N", T, N);
    free(f);
    free(uf);
    free(vf);
  }
  aq_check(refined == 14, "%zu refined periods at dt = 0.02 s (want 14)", refined);
  aq_spectrum_ws_free(ws);
  free(a);
  free(u);
  free(v);
}

/* Every bad argument is refused, naming its field. */
AQ_TEST(spectrum_bad_arguments)
{
  double a[4] = {0.1, -0.2, 0.3, 0.05}, T = 0.5, out;
  aq_rotd rd;
  aq_error e;
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  struct {
    double dt, z, T;
    size_t n;
    const char *field;
  } cases[] = {
      {0.01, 0.0, 0.5, 4, "damping"},  {0.01, 1.0, 0.5, 4, "damping"},
      {0.01, -0.05, 0.5, 4, "damping"}, {0.01, NAN, 0.5, 4, "damping"},
      {0.01, 0.05, -0.5, 4, "period_s"}, {0.01, 0.05, NAN, 4, "period_s"},
      {0.01, 0.05, INFINITY, 4, "period_s"}, {0.0, 0.05, 0.5, 4, "dt"},
      {-0.01, 0.05, 0.5, 4, "dt"},      {0.01, 0.05, 0.5, 0, "npts"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    T = cases[i].T;
    aq_status st = aq_spectrum_psa(ws, NULL, a, cases[i].n, cases[i].dt,
                                   cases[i].z, &T, 1, &out, &e);
    aq_check(st == AQ_EVALUE && strcmp(e.field, cases[i].field) == 0,
             "case %zu: status %d field \"%s\" (want %s)", i, st, e.field,
             cases[i].field);
  }
  T = 0.5;
  a[2] = NAN;
  aq_check(aq_spectrum_psa(ws, NULL, a, 4, 0.01, 0.05, &T, 1, &out, &e) ==
                   AQ_EVALUE && strcmp(e.field, "samples") == 0 &&
               strstr(e.message, "sample 2"),
           "a NaN sample is named: %s", e.message);
  a[2] = 0.3;
  aq_spectrum_opts o;
  aq_spectrum_opts_default(&o);
  o.n_angles = 179;
  aq_check(aq_spectrum_rotd(ws, &o, a, 4, a, 3, 0.01, 0.05, &T, 1, &rd, NULL,
                            &e) == AQ_EVALUE && strcmp(e.field, "n_angles") == 0,
           "an odd number of angles is refused");
  aq_spectrum_opts_default(&o);
  o.peaks = (aq_spectrum_peaks)3;
  aq_check(aq_spectrum_psa(ws, &o, a, 4, 0.01, 0.05, &T, 1, &out, &e) == AQ_EVALUE &&
               strcmp(e.field, "peaks") == 0,
           "an unknown peak rule is refused (psa)");
  aq_check(aq_spectrum_rotd(ws, &o, a, 4, a, 4, 0.01, 0.05, &T, 1, &rd, NULL, &e) ==
                   AQ_EVALUE && strcmp(e.field, "peaks") == 0,
           "an unknown peak rule is refused (rotd)");
  /* PEER's rule below dt / 1000 (1e-5 s at 0.01 s): 10 dt / T steps past
   * 10^4 are refused; dt / 1000 itself is 10^4 steps, taken */
  aq_spectrum_opts_default(&o);
  T = 0.99e-5;
  aq_check(aq_spectrum_psa(ws, &o, a, 4, 0.01, 0.05, &T, 1, &out, &e) == AQ_EVALUE &&
               strcmp(e.field, "period_s") == 0 && strstr(e.message, "peer"),
           "T = 0.99e-5 s at dt = 0.01 s under peer: %s", e.message);
  aq_check(aq_spectrum_rotd(ws, &o, a, 4, a, 4, 0.01, 0.05, &T, 1, &rd, NULL, &e) ==
                   AQ_EVALUE && strcmp(e.field, "period_s") == 0,
           "the same for rotd");
  T = 1e-5;
  aq_check(aq_spectrum_psa(ws, &o, a, 4, 0.01, 0.05, &T, 1, &out, &e) == AQ_OK,
           "T = 1e-5 s at dt = 0.01 s under peer: %s", e.message);
  o.peaks = AQ_SPECTRUM_PEAKS_EXACT;
  T = 1e-7;
  aq_check(aq_spectrum_psa(ws, &o, a, 4, 0.01, 0.05, &T, 1, &out, &e) == AQ_OK,
           "T = 1e-7 s under exact");
  T = 0.5;
  aq_check(aq_spectrum_response(a, 4, 0.01, 0.05, 0, a, a, &e) == AQ_EVALUE,
           "a response history needs T > 0");
  double p[3];
  aq_check(aq_spectrum_avg_periods(1.0, 0.5, 3, p, &e) == AQ_EVALUE,
           "Sa_avg range reversed");
  aq_check(aq_spectrum_avg_periods(0.2, 1.5, 1, p, &e) == AQ_EVALUE,
           "Sa_avg of one period");
  aq_spectrum_ws_free(ws);
}

/* Sa_avg's periods are spaced evenly and include both ends; the geometric
 * mean of 2, 8 is 4, and of (1, 10, 100) is 10. */
AQ_TEST(spectrum_sa_avg_periods_and_geomean)
{
  double p[10];
  aq_error e;
  aq_check(aq_spectrum_avg_periods(0.2, 1.5, 10, p, &e) == AQ_OK, "periods");
  for (int i = 0; i < 10; i++)
    aq_check_rel(p[i], 0.2 + 1.3 * i / 9.0, 1e-15, "period %d", i);
  double v2[] = {2, 8}, v3[] = {1, 10, 100}, v0[] = {3, 0};
  aq_check_rel(aq_spectrum_geomean(v2, 2), 4, 1e-15, "geomean 2, 8");
  aq_check_rel(aq_spectrum_geomean(v3, 3), 10, 1e-15, "geomean 1, 10, 100");
  aq_check(aq_spectrum_geomean(v0, 2) == 0, "a zero gives 0");
}
