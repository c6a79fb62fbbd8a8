/* im.c: intensity measures of a processed record (see signal.h).
 *
 * Integration is trapezoidal from rest at the first sample.  Arias intensity
 * I_A = pi/(2g) int a^2 dt (Arias 1970); the significant duration D5-95 is
 * the time between 5 % and 95 % of the normalised Arias curve (Trifunac &
 * Brady 1975), each crossing found by linear interpolation between samples;
 * CAV = int |a| dt (EPRI 1988); the residual limits follow PRISM (Jones et
 * al. 2017): 1 cm/s and 1 cm at the end of the record.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../units.h"
#include "signal.h"
#include "spectrum.h"

void aq_signal_integrate(const double *a_mps2, size_t n, double dt_s,
                         double *v_mps, double *d_m)
{
  if (n == 0)
    return;
  double h = 0.5 * dt_s, v = 0, d = 0;
  v_mps[0] = 0;
  if (d_m)
    d_m[0] = 0;
  for (size_t k = 1; k < n; k++) {
    double vn = v + h * (a_mps2[k - 1] + a_mps2[k]);
    d += h * (v + vn);
    v = vn;
    v_mps[k] = v;
    if (d_m)
      d_m[k] = d;
  }
}

/* Times (s from sample 0) where the cumulative trapezoidal int a^2 dt first
 * reaches lo and hi (lo <= hi), each interpolated linearly between the two
 * samples around it; one pass. */
static void arias_crossings(const double *a, size_t n, double dt_s, double lo,
                            double hi, double *t_lo, double *t_hi)
{
  double cum = 0, h = 0.5 * dt_s;
  size_t k = 1;
  *t_lo = *t_hi = (double)(n - 1) * dt_s;
  for (int which = 0; which < 2; which++) {
    double target = which ? hi : lo;
    for (; k < n; k++) {
      double inc = h * (a[k - 1] * a[k - 1] + a[k] * a[k]);
      if (cum + inc >= target && inc > 0) {
        double t = ((double)(k - 1) + (target - cum) / inc) * dt_s;
        *(which ? t_hi : t_lo) = t;
        break; /* k stays: the next target may lie in the same interval */
      }
      cum += inc;
    }
  }
}

/* The spectral measures p->used asks for: Sa(T) at its periods and Sa_avg
 * over its range, one spectrum of them all (spectrum.h). */
static aq_status spectral(const aq_processed *p, aq_im *im, aq_error *err)
{
  const aq_signal_opts *u = &p->used;
  im->sa_avg_g = NAN;
  size_t nsa = u->im_nsa, navg = u->sa_avg_lo_s > 0 ? AQ_IM_SA_AVG_N : 0;
  if (nsa > AQ_IM_SA_MAX)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "--im-periods",
                        "expected at most %d periods, got %zu", AQ_IM_SA_MAX, nsa);
  if (nsa + navg == 0)
    return AQ_OK;
  double T[AQ_IM_SA_MAX + AQ_IM_SA_AVG_N], psa[AQ_IM_SA_MAX + AQ_IM_SA_AVG_N];
  for (size_t i = 0; i < nsa; i++) {
    T[i] = u->im_period_s[i];
    if (!(T[i] > 0) || !isfinite(T[i]))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "--im-periods",
                          "expected periods > 0 s, got %g", T[i]);
  }
  if (navg && aq_spectrum_avg_periods(u->sa_avg_lo_s, u->sa_avg_hi_s, navg, T + nsa, err) != AQ_OK) {
    snprintf(err->field, sizeof err->field, "--sa-avg");
    return err->status;
  }
  aq_spectrum_ws *ws = aq_spectrum_ws_alloc();
  if (!ws)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "spectrum", "out of memory");
  aq_spectrum_opts so;
  aq_spectrum_opts_default(&so);
  so.peaks = u->peaks;
  aq_status st = aq_spectrum_psa(ws, &so, p->acc_mps2, p->n, p->dt_s, AQ_IM_DAMPING, T,
                                 nsa + navg, psa, err);
  aq_spectrum_ws_free(ws);
  if (st != AQ_OK)
    return st;
  im->n_sa = nsa;
  for (size_t i = 0; i < nsa; i++) {
    im->sa_period_s[i] = T[i];
    im->sa_g[i] = psa[i] / AQ_G0_MPS2;
  }
  if (navg) {
    im->sa_avg_lo_s = u->sa_avg_lo_s;
    im->sa_avg_hi_s = u->sa_avg_hi_s;
    im->sa_avg_g = aq_spectrum_geomean(psa + nsa, navg) / AQ_G0_MPS2;
  }
  return AQ_OK;
}

aq_status aq_im_compute(const aq_processed *p, aq_im *im, aq_error *err)
{
  memset(im, 0, sizeof *im);
  if (!p || p->n == 0 || !p->acc_mps2)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "npts",
                        "expected a processed record with samples, got none");
  if (!(p->dt_s > 0) || !isfinite(p->dt_s))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "dt",
                        "expected a finite sample interval > 0 s, got %g",
                        p->dt_s);
  const double *a = p->acc_mps2;
  size_t n = p->n;
  double h = 0.5 * p->dt_s;
  double pga = fabs(a[0]), pgv = 0, pgd = 0, v = 0, d = 0, a2 = 0, cav = 0;
  for (size_t k = 1; k < n; k++) {
    double a0 = a[k - 1], a1 = a[k];
    double vn = v + h * (a0 + a1);
    d += h * (v + vn);
    v = vn;
    a2 += h * (a0 * a0 + a1 * a1);
    if (a0 * a1 >= 0) {
      cav += h * (fabs(a0) + fabs(a1));
    } else {
      /* |a| along the linear interpolant: two triangles split at the zero */
      cav += h * (a0 * a0 + a1 * a1) / (fabs(a0) + fabs(a1));
    }
    double fa = fabs(a1), fv = fabs(v), fd = fabs(d);
    pga = fa > pga ? fa : pga;
    pgv = fv > pgv ? fv : pgv;
    pgd = fd > pgd ? fd : pgd;
  }
  im->pga_g = pga / AQ_G0_MPS2;
  im->pgv_mps = pgv;
  im->pgd_m = pgd;
  im->arias_mps = AQ_PI / (2.0 * AQ_G0_MPS2) * a2;
  im->cav_mps = cav;
  im->v_end_mps = v;
  im->d_end_m = d;
  if (a2 > 0) {
    double t5, t95;
    arias_crossings(a, n, p->dt_s, 0.05 * a2, 0.95 * a2, &t5, &t95);
    im->d5_95_s = t95 - t5;
  }
  im->residual_warn = (fabs(v) > AQ_IM_VEND_LIMIT_MPS ? AQ_IM_WARN_VEND : 0) |
                      (fabs(d) > AQ_IM_DEND_LIMIT_M ? AQ_IM_WARN_DEND : 0);
  im->pgv_pga_s = pga > 0 ? pgv / pga : NAN;
  return spectral(p, im, err);
}

size_t aq_im_spectral_count(const aq_signal_opts *u)
{
  return u->im_nsa + (u->sa_avg_lo_s > 0);
}

void aq_im_spectral_name(const aq_signal_opts *u, size_t k, char *buf, size_t n)
{
  if (k < u->im_nsa)
    snprintf(buf, n, "sa_%gs_g", u->im_period_s[k]);
  else
    snprintf(buf, n, "sa_avg_%g_%gs_g", u->sa_avg_lo_s, u->sa_avg_hi_s);
}

double aq_im_spectral_value(const aq_im *im, size_t k)
{
  return k < im->n_sa ? im->sa_g[k] : im->sa_avg_g;
}

int aq_im_residual_warning(const aq_im *im, char *buf, size_t n)
{
  if (n)
    buf[0] = '\0';
  if (!im->residual_warn || n == 0)
    return 0;
  int w = 0;
  if (im->residual_warn & AQ_IM_WARN_VEND)
    w = snprintf(buf, n, "residual velocity %.3g m/s exceeds %g m/s",
                 im->v_end_mps, AQ_IM_VEND_LIMIT_MPS);
  if (im->residual_warn & AQ_IM_WARN_DEND) {
    size_t k = w > 0 && (size_t)w < n ? (size_t)w : 0;
    snprintf(buf + k, n - k, "%sresidual displacement %.3g m exceeds %g m",
             k ? "; " : "", im->d_end_m, AQ_IM_DEND_LIMIT_M);
  }
  return 1;
}
