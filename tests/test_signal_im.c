/* test_signal_im.c: intensity measures against closed forms for a windowed
 * sine, and against PEER's own velocity and displacement (.VT2/.DT2). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "signal/signal.h"
#include "units.h"

/* The windowed sine: a(t) = A sin(w (t - t1)) on [t1, t1 + T], T = N cycles
 * of f, zero elsewhere.  With tau = t - t1 and w = 2 pi f:
 *   int a^2 dt       = A^2 T / 2                         (whole cycles)
 *   Arias            = pi / (2 g) * A^2 T / 2
 *   CAV = int |a| dt = 2N half-cycles * 2A/w = 2 A N / (pi f)
 *   v(tau) = A/w (1 - cos w tau): PGV = 2A/w, v_end = 0
 *   d(tau) = A/w (tau - sin(w tau)/w): PGD = d_end = A T / w
 *   cumulative int a^2 = A^2/2 (tau - sin(2 w tau)/(2 w)); its 5 % and 95 %
 *   points solve tau - sin(2 w tau)/(2 w) = q T, and by symmetry
 *   tau95 = T - tau5, so D5-95 = T - 2 tau5 (tau5 found by bisection below). */
static double frac_arias(double tau, double w, double T)
{
  return (tau - sin(2 * w * tau) / (2 * w)) / T;
}

/* Discretisation at dt = 0.002 s, f = 1.25 Hz: (w dt)^2 = 2.5e-4.  The
 * trapezoidal rule is exact for sin^2 over whole periods; linear
 * interpolation of |sin| errs by ~ (w dt)^2 / 12 = 2e-5 relative; peaks of
 * v and d sampled on the grid err by ~ (w dt)^2 / 8; D5-95's interpolation
 * errs by ~ dt (w dt)^2. */
#define IM_ARIAS_REL 1e-10
#define IM_CAV_REL 5e-5
#define IM_PEAK_REL 1e-4
#define IM_D595_ABS_S 1e-5

AQ_TEST(signal_im_windowed_sine_closed_forms)
{
  const double A = 2.385, f = 1.25, dt = 0.002, t1 = 3.0;
  const int ncyc = 6;
  const double T = ncyc / f, w = 2 * AQ_PI * f;
  const size_t n = 6000, i1 = (size_t)lround(t1 / dt),
               i2 = i1 + (size_t)lround(T / dt);
  aq_processed p;
  memset(&p, 0, sizeof p);
  p.n = p.n_orig = n;
  p.dt_s = dt;
  p.acc_mps2 = calloc(n, sizeof(double));
  aq_check(p.acc_mps2 != NULL, "alloc");
  for (size_t i = i1; i <= i2; i++)
    p.acc_mps2[i] = A * sin(w * (double)(i - i1) * dt);
  aq_im im;
  aq_error e;
  aq_check(aq_im_compute(&p, &im, &e) == AQ_OK, "im");

  double lo = 0, hi = T / 2;
  for (int it = 0; it < 200; it++) {
    double mid = 0.5 * (lo + hi);
    if (frac_arias(mid, w, T) < 0.05)
      lo = mid;
    else
      hi = mid;
  }
  double d595 = T - 2 * 0.5 * (lo + hi);

  aq_check_rel(im.pga_g, A / AQ_G0_MPS2, 1e-12, "PGA (the peak is on the grid)");
  aq_check_rel(im.arias_mps, AQ_PI / (2 * AQ_G0_MPS2) * A * A * T / 2,
               IM_ARIAS_REL, "Arias intensity");
  aq_check_rel(im.cav_mps, 2 * A * ncyc / (AQ_PI * f), IM_CAV_REL, "CAV");
  aq_check_abs(im.d5_95_s, d595, IM_D595_ABS_S, "D5-95");
  aq_check_rel(im.pgv_mps, 2 * A / w, IM_PEAK_REL, "PGV");
  aq_check_rel(im.pgd_m, A * T / w, IM_PEAK_REL, "PGD");
  aq_check_rel(im.d_end_m, A * T / w, IM_PEAK_REL, "residual displacement");
  aq_check_abs(im.v_end_mps, 0, IM_PEAK_REL * 2 * A / w, "residual velocity");
  aq_check(im.residual_warn == AQ_IM_WARN_DEND, "warns of the displacement "
           "only: %d", im.residual_warn);
  free(p.acc_mps2);
}

/* ---- PEER .AT2 / .VT2 / .DT2: a parser of their own, independent of io --- */

/* Read a PEER NGA file: 4 header lines (NPTS= and DT= on the 4th), then
 * values.  Returns a malloc'd array of *npts values, or NULL. */
static double *peer_read(const char *path, size_t *npts, double *dt_s)
{
  FILE *f = fopen(path, "r");
  if (!f)
    return NULL;
  char line[512];
  for (int k = 0; k < 4; k++)
    if (!fgets(line, sizeof line, f)) {
      fclose(f);
      return NULL;
    }
  char *np = strstr(line, "NPTS="), *dp = strstr(line, "DT=");
  if (!np || !dp) {
    fclose(f);
    return NULL;
  }
  long n = strtol(np + 5, NULL, 10);
  *dt_s = strtod(dp + 3, NULL);
  double *v = n > 0 ? malloc((size_t)n * sizeof *v) : NULL;
  size_t k = 0;
  while (v && k < (size_t)n && fscanf(f, "%lf", &v[k]) == 1)
    k++;
  fclose(f);
  if (!v || k != (size_t)n) {
    free(v);
    return NULL;
  }
  *npts = k;
  return v;
}

/* relative RMS difference: sqrt(sum (x - ref)^2 / sum ref^2) */
static double rel_rms(const double *x, const double *ref, size_t n)
{
  double num = 0, den = 0;
  for (size_t i = 0; i < n; i++) {
    num += (x[i] - ref[i]) * (x[i] - ref[i]);
    den += ref[i] * ref[i];
  }
  return sqrt(num / den);
}

#define PEER_REL_RMS 1e-3 /* issue 3 */

AQ_TEST(signal_im_integration_matches_peer_vt2_dt2)
{
  static const char *const names[] = {"RSN1616_DUZCE_362-E",
                                      "RSN4843_CHUETSU_65006NS",
                                      "RSN4013_SANSIMEO_36258021"};
  for (size_t r = 0; r < 3; r++) {
    char path[256];
    size_t na = 0, nv = 0, nd = 0;
    double dta = 0, dtv = 0, dtd = 0;
    snprintf(path, sizeof path, "tests/data/records/%s.AT2", names[r]);
    double *a_g = peer_read(path, &na, &dta);
    snprintf(path, sizeof path, "tests/data/records/%s.VT2", names[r]);
    double *v_ref = peer_read(path, &nv, &dtv);
    snprintf(path, sizeof path, "tests/data/records/%s.DT2", names[r]);
    double *d_ref = peer_read(path, &nd, &dtd);
    if (!aq_check(a_g && v_ref && d_ref && na == nv && na == nd &&
                      dta == dtv && dta == dtd,
                  "%s: AT2/VT2/DT2 read and consistent", names[r])) {
      free(a_g);
      free(v_ref);
      free(d_ref);
      continue;
    }
    /* the record as read: --no-filter --detrend none; cm/s^2 in, so the
     * integrals come out in cm/s and cm like PEER's */
    aq_record rec;
    memset(&rec, 0, sizeof rec);
    rec.path = path;
    rec.npts = na;
    rec.dt_s = dta;
    rec.acc_mps2 = a_g;
    for (size_t i = 0; i < na; i++)
      a_g[i] *= AQ_G0_MPS2 * 100.0;
    aq_signal_opts o;
    aq_signal_opts_default(&o);
    o.filter = 0;
    o.detrend = AQ_DETREND_NONE;
    aq_processed p;
    aq_error e;
    double *v = malloc(na * sizeof *v), *d = malloc(na * sizeof *d);
    if (aq_check(v && d && aq_signal_process(&rec, &o, NULL, &p, &e) == AQ_OK &&
                     p.n == na && p.pad_front == 0,
                 "%s: processed as read", names[r])) {
      aq_signal_integrate(p.acc_mps2, p.n, p.dt_s, v, d);
      double ev = rel_rms(v, v_ref, na), ed = rel_rms(d, d_ref, na);
      aq_check(ev < PEER_REL_RMS, "%s: velocity rel RMS %.3g", names[r], ev);
      aq_check(ed < PEER_REL_RMS, "%s: displacement rel RMS %.3g", names[r],
               ed);
      aq_im im;
      aq_check(aq_im_compute(&p, &im, &e) == AQ_OK, "im");
      double pgv = 0;
      for (size_t i = 0; i < na; i++)
        pgv = fmax(pgv, fabs(v_ref[i]));
      aq_check_rel(im.pgv_mps, pgv, 2e-3, "%s: PGV against VT2's peak",
                   names[r]);
      aq_processed_free(&p);
    }
    free(v);
    free(d);
    free(a_g);
    free(v_ref);
    free(d_ref);
  }
}
