/* spectrum.c: elastic response spectra (spectrum.h): the peak rules'
 * names, the options, the workspace and the checks of the arguments, and
 * the spectrum of one component, its periods run one at a time (their
 * history kept: sdof.c) or several in one pass (spectrum_batch.c).  RotD:
 * spectrum_rotd.c; the method: sdof.c's and spectrum_rotd.c's top
 * comments. */
#include "spectrum.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "spectrum_int.h"

const double aq_spectrum_peer_periods_s[AQ_SPECTRUM_PEER_N] = {
    0.01,  0.02,  0.022, 0.025, 0.029, 0.03,  0.032, 0.035, 0.036, 0.04,
    0.042, 0.044, 0.045, 0.046, 0.048, 0.05,  0.055, 0.06,  0.065, 0.067,
    0.07,  0.075, 0.08,  0.085, 0.09,  0.095, 0.1,   0.11,  0.12,  0.13,
    0.133, 0.14,  0.15,  0.16,  0.17,  0.18,  0.19,  0.2,   0.22,  0.24,
    0.25,  0.26,  0.28,  0.29,  0.3,   0.32,  0.34,  0.35,  0.36,  0.38,
    0.4,   0.42,  0.44,  0.45,  0.46,  0.48,  0.5,   0.55,  0.6,   0.65,
    0.667, 0.7,   0.75,  0.8,   0.85,  0.9,   0.95,  1.0,   1.1,   1.2,
    1.3,   1.4,   1.5,   1.6,   1.7,   1.8,   1.9,   2.0,   2.2,   2.4,
    2.5,   2.6,   2.8,   3.0,   3.2,   3.4,   3.5,   3.6,   3.8,   4.0,
    4.2,   4.4,   4.6,   4.8,   5.0,   5.5,   6.0,   6.5,   7.0,   7.5,
    8.0,   8.5,   9.0,   9.5,   10.0,  11.0,  12.0,  13.0,  14.0,  15.0,
    20.0};

const char *const aq_spectrum_peaks_names[] = {"peer", "exact", "samples", NULL};

int aq_spectrum_peaks_parse(const char *name)
{
  for (int i = 0; aq_spectrum_peaks_names[i]; i++)
    if (strcmp(name, aq_spectrum_peaks_names[i]) == 0)
      return i;
  return strcmp(name, "continuous") == 0 ? AQ_SPECTRUM_PEAKS_EXACT : -1;
}

const char *aq_spectrum_peaks_text(aq_spectrum_peaks peaks)
{
  switch (peaks) {
  case AQ_SPECTRUM_PEAKS_PEER:
    return "peer: each peak at the samples and at N - 1 points between them, N = "
           "ceil(10 dt / T), as PEER's NGA-West2 spectra";
  case AQ_SPECTRUM_PEAKS_EXACT:
    return "exact: each peak over continuous time, the input linear between samples";
  case AQ_SPECTRUM_PEAKS_SAMPLES:
    return "samples: each peak at the samples only";
  }
  return "unknown";
}

size_t aq_spectrum_peer_steps(double dt_s, double period_s)
{
  double r = 10 * dt_s / period_s, w = nearbyint(r);
  if (!(r <= AQ_SPECTRUM_PEER_STEPS_MAX + 1.0))
    return 0;
  if (fabs(r - w) <= AQ_SPECTRUM_PEER_RATIO_TOL * w)
    r = w;
  size_t n = (size_t)ceil(r);
  if (n > AQ_SPECTRUM_PEER_STEPS_MAX)
    return 0;
  return n < 1 ? 1 : n;
}

void aq_spectrum_opts_default(aq_spectrum_opts *o)
{
  o->n_angles = AQ_SPECTRUM_ANGLES_DEFAULT;
  o->peaks = AQ_SPECTRUM_PEAKS_PEER;
  o->one_at_a_time = 0;
}

aq_spectrum_ws *aq_spectrum_ws_alloc(void)
{
  return calloc(1, sizeof(aq_spectrum_ws));
}

void aq_spectrum_ws_free(aq_spectrum_ws *ws)
{
  if (!ws)
    return;
  free(ws->x1);
  free(ws->y1);
  free(ws->x2);
  free(ws->y2);
  free(ws->rho);
  free(ws->pts);
  free(ws->ivs);
  free(ws->pp);
  free(ws->hull);
  free(ws->cs);
  free(ws->sn);
  free(ws->sorted);
  free(ws->ref);
  free(ws->ref_hull);
  free(ws->xs1);
  free(ws->xs2);
  free(ws);
}

int aq_spectrum_ws_reserve(aq_spectrum_ws *ws, size_t n, size_t n_angles)
{
  if (n > ws->cap) {
    double **d[] = {&ws->x1, &ws->y1, &ws->x2, &ws->y2, &ws->rho};
    for (size_t i = 0; i < sizeof d / sizeof *d; i++) {
      double *p = realloc(*d[i], n * sizeof(double));
      if (!p)
        return 0;
      *d[i] = p;
    }
    size_t **z[] = {&ws->pts, &ws->ivs};
    for (size_t i = 0; i < sizeof z / sizeof *z; i++) {
      size_t *p = realloc(*z[i], n * sizeof(size_t));
      if (!p)
        return 0;
      *z[i] = p;
    }
    pt2 *pp = realloc(ws->pp, n * sizeof *pp);
    if (!pp)
      return 0;
    ws->pp = pp;
    pt2 *hh = realloc(ws->hull, 2 * n * sizeof *hh);
    if (!hh)
      return 0;
    ws->hull = hh;
    ws->cap = n;
  }
  if (n_angles > ws->cap_angles) {
    double **d[] = {&ws->cs, &ws->sn, &ws->sorted};
    for (size_t i = 0; i < sizeof d / sizeof *d; i++) {
      double *p = realloc(*d[i], n_angles * sizeof(double));
      if (!p)
        return 0;
      *d[i] = p;
    }
    ws->cap_angles = n_angles;
  }
  return 1;
}

int aq_spectrum_ws_reserve_ref(aq_spectrum_ws *ws, size_t n)
{
  if (n <= ws->cap_ref)
    return 1;
  size_t cap = n > 2 * ws->cap_ref ? n : 2 * ws->cap_ref;
  pt2 *r = realloc(ws->ref, cap * sizeof *r);
  if (!r)
    return 0;
  ws->ref = r;
  pt2 *h = realloc(ws->ref_hull, 2 * cap * sizeof *h);
  if (!h)
    return 0;
  ws->ref_hull = h;
  ws->cap_ref = cap;
  return 1;
}

int aq_spectrum_ws_reserve_steps(aq_spectrum_ws *ws, size_t steps)
{
  if (steps <= ws->cap_steps)
    return 1;
  double *a = realloc(ws->xs1, steps * sizeof *a);
  if (!a)
    return 0;
  ws->xs1 = a;
  double *b = realloc(ws->xs2, steps * sizeof *b);
  if (!b)
    return 0;
  ws->xs2 = b;
  ws->cap_steps = steps;
  return 1;
}

aq_status aq_spectrum_check_args(const double *acc, size_t n, double dt_s,
                                 double damping, const double *period_s,
                                 size_t n_periods, aq_error *err)
{
  if (n == 0 || !acc)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "npts",
                        "expected a record with samples, got none");
  if (!(dt_s > 0) || !isfinite(dt_s))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "dt",
                        "expected a finite sample interval > 0 s, got %g",
                        dt_s);
  if (!(damping > 0 && damping < 1))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "damping",
                        "expected a damping ratio in (0, 1), got %g", damping);
  for (size_t i = 0; i < n_periods; i++)
    if (!(period_s[i] >= 0) || !isfinite(period_s[i]))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "period_s",
                          "expected a finite period >= 0 s, got %g",
                          period_s[i]);
  for (size_t k = 0; k < n; k++)
    if (!isfinite(acc[k]))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "samples",
                          "expected finite accelerations, got %g at sample %zu",
                          acc[k], k);
  return AQ_OK;
}

aq_status aq_spectrum_check_peaks(const aq_spectrum_opts *o, aq_error *err)
{
  if (o->peaks != AQ_SPECTRUM_PEAKS_PEER && o->peaks != AQ_SPECTRUM_PEAKS_EXACT &&
      o->peaks != AQ_SPECTRUM_PEAKS_SAMPLES)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "peaks",
                        "expected peer, exact or samples, got %d", (int)o->peaks);
  return AQ_OK;
}

enum { BATCH = AQ_SPECTRUM_BATCH };

static double abs_max(const double *a, size_t n)
{
  double m = 0;
  for (size_t k = 0; k < n; k++)
    m = dmax(m, fabs(a[k]));
  return m;
}

aq_status aq_spectrum_psa(aq_spectrum_ws *ws, const aq_spectrum_opts *opts,
                          const double *acc_mps2, size_t n, double dt_s,
                          double damping, const double *period_s,
                          size_t n_periods, double *psa_mps2, aq_error *err)
{
  aq_spectrum_opts def;
  if (!opts) {
    aq_spectrum_opts_default(&def);
    opts = &def;
  }
  aq_status st =
      aq_spectrum_check_args(acc_mps2, n, dt_s, damping, period_s, n_periods, err);
  if (st == AQ_OK)
    st = aq_spectrum_check_peaks(opts, err);
  if (st != AQ_OK)
    return st;
  if (!aq_spectrum_ws_reserve(ws, n, 0))
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "spectrum",
                        "out of memory for %zu samples", n);
  double amax = abs_max(acc_mps2, n);
  /* T = 0: the input's peak; the periods whose peak is at the samples
   * only, BATCH at a time (spectrum_batch.c); the others one by one, their
   * history kept */
  aq_sdof bo[BATCH], ro[BATCH], rs[BATCH];
  const aq_sdof *bp[BATCH], *rp[BATCH], *rsp[BATCH];
  size_t bi[BATCH], nb = 0, ri[BATCH], rn[BATCH], nr = 0;
  for (size_t i = 0; i < n_periods; i++) {
    aq_sdof o;
    st = aq_sdof_init(&o, period_s[i], damping, dt_s, err);
    if (st != AQ_OK)
      return st;
    aq_sdof sub;
    size_t steps = 1;
    if (opts->peaks == AQ_SPECTRUM_PEAKS_PEER) {
      st = aq_sdof_peer_init(&sub, &steps, period_s[i], damping, dt_s, err);
      if (st != AQ_OK)
        return st;
    }
    if (o.pga && !opts->one_at_a_time) {
      psa_mps2[i] = amax; /* x = -a, its peak the same under every rule */
      continue;
    }
    int at_samples = opts->peaks == AQ_SPECTRUM_PEAKS_SAMPLES ||
                     (opts->peaks == AQ_SPECTRUM_PEAKS_PEER && steps < 2);
    if (!o.pga && at_samples && !opts->one_at_a_time) {
      bo[nb] = o;
      bp[nb] = &bo[nb];
      bi[nb++] = i;
      if (nb == BATCH)
        nb = aq_spectrum_batch_peaks(bp, bi, nb, acc_mps2, n, psa_mps2);
      continue;
    }
    if (!o.pga && !opts->one_at_a_time && opts->peaks == AQ_SPECTRUM_PEAKS_PEER) {
      ro[nr] = o;
      rs[nr] = sub;
      rp[nr] = &ro[nr];
      rsp[nr] = &rs[nr];
      rn[nr] = steps;
      ri[nr++] = i;
      if (nr == BATCH)
        nr = aq_spectrum_batch_refined(rp, rsp, rn, ri, nr, acc_mps2, n, amax, psa_mps2);
      continue;
    }
    double m = aq_sdof_respond(&o, acc_mps2, n, n, ws->x1, ws->y1);
    if (opts->peaks == AQ_SPECTRUM_PEAKS_EXACT)
      m = aq_sdof_peak_one(&o, acc_mps2, n, n, ws->x1, ws->y1, m, amax);
    else if (opts->peaks == AQ_SPECTRUM_PEAKS_PEER)
      m = aq_sdof_peak_refined(&o, &sub, steps, acc_mps2, n, n, ws->x1, ws->y1, m, amax);
    psa_mps2[i] = m;
  }
  aq_spectrum_batch_peaks(bp, bi, nb, acc_mps2, n, psa_mps2);
  aq_spectrum_batch_refined(rp, rsp, rn, ri, nr, acc_mps2, n, amax, psa_mps2);
  return AQ_OK;
}

aq_status aq_spectrum_response(const double *acc_mps2, size_t n, double dt_s,
                               double damping, double period_s, double *u_m,
                               double *v_mps, aq_error *err)
{
  aq_status st = aq_spectrum_check_args(acc_mps2, n, dt_s, damping, &period_s, 1, err);
  if (st != AQ_OK)
    return st;
  if (!(period_s > 0))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "period_s",
                        "expected a period > 0 s, got %g", period_s);
  aq_sdof o;
  st = aq_sdof_init(&o, period_s, damping, dt_s, err);
  if (st != AQ_OK)
    return st;
  aq_sdof_respond(&o, acc_mps2, n, n, u_m, v_mps);
  double w = 2 * AQ_PI / period_s;
  for (size_t k = 0; k < n; k++) {
    u_m[k] /= w * w; /* x = omega^2 u */
    v_mps[k] /= w;   /* y = omega u' */
  }
  return AQ_OK;
}

aq_status aq_spectrum_avg_periods(double t_lo_s, double t_hi_s, size_t n_avg,
                                  double *periods_s, aq_error *err)
{
  if (n_avg < 2)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "sa_avg",
                        "expected at least 2 periods, got %zu", n_avg);
  if (!(t_lo_s > 0 && t_hi_s > t_lo_s) || !isfinite(t_hi_s))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "sa_avg",
                        "expected periods 0 < T1 < T2, got %g, %g", t_lo_s,
                        t_hi_s);
  for (size_t i = 0; i < n_avg; i++)
    periods_s[i] =
        t_lo_s + (t_hi_s - t_lo_s) * ((double)i / (double)(n_avg - 1));
  periods_s[n_avg - 1] = t_hi_s;
  return AQ_OK;
}

double aq_spectrum_geomean(const double *v, size_t n)
{
  double s = 0;
  for (size_t i = 0; i < n; i++) {
    if (!(v[i] > 0))
      return 0;
    s += log(v[i]);
  }
  return n ? exp(s / (double)n) : 0;
}
