/* fragility.c: a lognormal fragility P(collapse | IM = x) =
 * Phi(ln(x / theta) / beta) fitted to first-collapse intensities by
 * maximum likelihood, with the records that never collapse up to their cap
 * right-censored there.
 *
 *   J. W. Baker, "Efficient analytical fragility function fitting using
 *   dynamic structural analysis", Earthquake Spectra 31(1), 579-599, 2015.
 *
 * Each collapse at x_i contributes the lognormal density, each record
 * censored at c_j the probability of no collapse up to it,
 *   ln L = sum_i ln[phi(z_i) / (beta x_i)] + sum_j ln[1 - Phi(z_j)],
 *   z = ln(x / theta) / beta                               (Baker eq. 7 form)
 * maximised over (ln theta, ln beta) with GSL's Nelder-Mead simplex; the
 * log of the survival probability is GSL's log erfc, exact far in the tail.
 * The interval of the median is the profile likelihood's: every theta with
 *   2 [ln L(theta_hat, beta_hat) - max_beta ln L(theta, beta)] <= chi2_1(ci),
 * its ends found by bracketing and Brent's method (gsl_root), the inner
 * maximisation by Brent's method on ln beta (gsl_min). */
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_multimin.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_erf.h>
#include <math.h>
#include <stdlib.h>

#include "capacity.h"

/* Convergence of the fits (dimensionless: ln theta and ln beta). */
/* simplex size at convergence: near the optimum the nll changes by about
 * 0.5 n size^2, which meets its rounding (1e-16 of it) for size ~ 1e-8 */
static const double FIT_SIMPLEX_SIZE = 1e-7;
static const size_t FIT_MAX_ITER = 20000;
static const double RANK_TIE = 10 * FIT_SIMPLEX_SIZE; /* relative, of beta / power */
static const double PROFILE_LNBETA_TOL = 1e-10; /* inner maximisation over ln beta */
static const double CI_LNTHETA_TOL = 1e-9;      /* ends of the interval, in ln theta */
static const double CI_LNTHETA_SPAN = 30.0;     /* farther than e^30 x theta: unbounded */

double aq_fragility_nll(const double *x, const int *censored, size_t n,
                        double theta, double beta)
{
  const double ln_sqrt_2pi = 0.5 * log(2 * M_PI);
  double nll = 0, lt = log(theta);
  for (size_t i = 0; i < n; i++) {
    double z = (log(x[i]) - lt) / beta;
    if (censored[i]) /* ln(1 - Phi(z)) = ln(erfc(z / sqrt 2) / 2) */
      nll -= gsl_sf_log_erfc(z / M_SQRT2) - M_LN2;
    else
      nll += 0.5 * z * z + ln_sqrt_2pi + log(beta * x[i]);
  }
  return nll;
}

typedef struct {
  const double *x;
  const int *c;
  size_t n;
  double lt; /* ln theta held fixed (profile) */
} data;

static double f_2d(const gsl_vector *v, void *p)
{
  const data *d = p;
  double r = aq_fragility_nll(d->x, d->c, d->n, exp(gsl_vector_get(v, 0)),
                              exp(gsl_vector_get(v, 1)));
  return isfinite(r) ? r : GSL_POSINF;
}

static double f_prof(double lb, void *p)
{
  const data *d = p;
  double r = aq_fragility_nll(d->x, d->c, d->n, exp(d->lt), exp(lb));
  return isfinite(r) ? r : GSL_POSINF;
}

/* min over ln beta of the nll at ln theta = lt, starting near lb0. */
static int profile(data *d, double lt, double lb0, double *nll, double *lb_out)
{
  d->lt = lt;
  /* bracket: walk a coarse grid around lb0 for the lowest point */
  const double step = 0.25;
  const int half = 12; /* +-3 in ln beta around the guess */
  int best = 0;
  double fb = GSL_POSINF;
  for (int k = -half; k <= half; k++) {
    double f = f_prof(lb0 + k * step, d);
    if (f < fb) {
      fb = f;
      best = k;
    }
  }
  if (!isfinite(fb))
    return -1;
  double a = lb0 + (best - 1) * step, b = lb0 + (best + 1) * step;
  double m = lb0 + best * step;
  if (best == -half || best == half) { /* at the grid's end: take it */
    *nll = fb;
    *lb_out = m;
    return 0;
  }
  gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  if (!s)
    return -1;
  gsl_function F = {f_prof, d};
  if (gsl_min_fminimizer_set_with_values(s, &F, m, fb, a, f_prof(a, d), b,
                                         f_prof(b, d)) != GSL_SUCCESS) {
    gsl_min_fminimizer_free(s);
    *nll = fb;
    *lb_out = m;
    return 0;
  }
  for (int it = 0; it < 200; it++) {
    if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS)
      break;
    double lo = gsl_min_fminimizer_x_lower(s), hi = gsl_min_fminimizer_x_upper(s);
    if (gsl_min_test_interval(lo, hi, PROFILE_LNBETA_TOL, 0) == GSL_SUCCESS)
      break;
  }
  *lb_out = gsl_min_fminimizer_x_minimum(s);
  *nll = gsl_min_fminimizer_f_minimum(s);
  gsl_min_fminimizer_free(s);
  return 0;
}

typedef struct {
  data *d;
  double nll_min, crit, lb_hat, lt_hat;
} ci_ctx;

/* profile deviance minus the critical value at ln theta = lt */
static double dev(double lt, void *p)
{
  ci_ctx *c = p;
  double nll, lb;
  /* start the inner search where the complete-data profile would put it */
  double dl = lt - c->lt_hat, b0 = exp(c->lb_hat);
  if (profile(c->d, lt, 0.5 * log(b0 * b0 + dl * dl), &nll, &lb) != 0)
    return GSL_NAN;
  return 2 * (nll - c->nll_min) - c->crit;
}

/* The end of the interval on side dir (+1 upper, -1 lower), in ln theta. */
static double ci_end(ci_ctx *c, double dir)
{
  double inner = c->lt_hat, step = 0.05 * exp(c->lb_hat), outer = inner;
  double fo = -c->crit;
  while (fo < 0) {
    outer = c->lt_hat + dir * step;
    if (step > CI_LNTHETA_SPAN)
      return dir * INFINITY;
    fo = dev(outer, c);
    if (isnan(fo))
      return GSL_NAN;
    if (fo < 0)
      inner = outer;
    step *= 2;
  }
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!s)
    return GSL_NAN;
  gsl_function F = {dev, c};
  double lo = fmin(inner, outer), hi = fmax(inner, outer), r = 0.5 * (lo + hi);
  if (gsl_root_fsolver_set(s, &F, lo, hi) == GSL_SUCCESS) {
    for (int it = 0; it < 200; it++) {
      if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS)
        break;
      r = gsl_root_fsolver_root(s);
      if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s),
                                 gsl_root_fsolver_x_upper(s), CI_LNTHETA_TOL,
                                 0) == GSL_SUCCESS)
        break;
    }
  }
  gsl_root_fsolver_free(s);
  return r;
}

aq_status aq_fragility_fit(const double *x, const int *censored, size_t n,
                           double ci, aq_fragility *out, aq_error *err)
{
  *out = (aq_fragility){n, 0, NAN, NAN, NAN, NAN, NAN, 0, 0};
  double sum = 0, sum2 = 0, xmin = INFINITY, xmax = -INFINITY;
  size_t nc = 0;
  for (size_t i = 0; i < n; i++) {
    if (!(x[i] > 0 && isfinite(x[i])))
      return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "fragility",
                          "value %zu: expected a finite intensity > 0, got %g", i, x[i]);
    if (censored[i]) {
      out->ncensored++;
      continue;
    }
    double l = log(x[i]);
    sum += l;
    sum2 += l * l;
    xmin = fmin(xmin, x[i]);
    xmax = fmax(xmax, x[i]);
    nc++;
  }
  if (!(ci > 0 && ci < 1))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "fragility",
                        "confidence level: expected 0 < ci < 1, got %g", ci);
  if (nc < 2 || !(xmax > xmin))
    return AQ_OK; /* no spread to fit */
  /* start at the complete-data estimate of the collapses */
  double mu = sum / (double)nc, var = sum2 / (double)nc - mu * mu;
  double b0 = sqrt(fmax(var, 1e-6));
  data d = {x, censored, n, 0};
  gsl_multimin_fminimizer *s =
      gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, 2);
  gsl_vector *v = gsl_vector_alloc(2), *step = gsl_vector_alloc(2);
  if (!s || !v || !step) {
    gsl_multimin_fminimizer_free(s);
    gsl_vector_free(v);
    gsl_vector_free(step);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "fragility", "out of memory");
  }
  gsl_vector_set(v, 0, mu);
  gsl_vector_set(v, 1, log(b0));
  gsl_vector_set_all(step, 0.3);
  gsl_multimin_function F = {f_2d, 2, &d};
  int rc = gsl_multimin_fminimizer_set(s, &F, v, step);
  size_t it = 0;
  for (; rc == GSL_SUCCESS && it < FIT_MAX_ITER; it++) {
    rc = gsl_multimin_fminimizer_iterate(s);
    if (rc == GSL_ENOPROG) { /* no simplex move improves: converged as far as it can */
      rc = GSL_SUCCESS;
      break;
    }
    if (rc != GSL_SUCCESS)
      break;
    if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(s), FIT_SIMPLEX_SIZE) ==
        GSL_SUCCESS)
      break;
  }
  double lt = gsl_vector_get(s->x, 0), lb = gsl_vector_get(s->x, 1);
  double fmin_ = s->fval;
  gsl_multimin_fminimizer_free(s);
  gsl_vector_free(v);
  gsl_vector_free(step);
  if (rc != GSL_SUCCESS || it >= FIT_MAX_ITER || !isfinite(fmin_))
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "fragility",
                        "the likelihood maximisation did not converge (%s)",
                        rc != GSL_SUCCESS ? gsl_strerror(rc) : "iteration limit");
  out->median = exp(lt);
  out->beta = exp(lb);
  out->loglik = -fmin_;
  ci_ctx c = {&d, fmin_, gsl_cdf_chisq_Pinv(ci, 1), lb, lt};
  double lo = ci_end(&c, -1), hi = ci_end(&c, +1);
  out->median_lo = exp(lo);
  out->median_hi = exp(hi);
  return AQ_OK;
}

const char *const aq_fragility_im_names[AQ_FRAGILITY_NIM] = {
    "pga_g", "pgv_m_s", "pgd_m", "arias_m_s", "cav_m_s", "pga_lambda0"};
const char *const aq_fragility_im_units[AQ_FRAGILITY_NIM] = {"g",   "m/s", "m",
                                                             "m/s", "m/s", "1"};

double aq_fragility_im_at(const aq_im *im, double lambda0, int which,
                          double scale)
{
  switch (which) {
  case 0:
    return scale * im->pga_g;
  case 1:
    return scale * im->pgv_mps;
  case 2:
    return scale * im->pgd_m;
  case 3: /* pi/(2g) int (s a)^2 dt */
    return scale * scale * im->arias_mps;
  case 4:
    return scale * im->cav_mps;
  case 5:
    return scale * im->pga_g / lambda0;
  default:
    return which > 5 && (size_t)(which - AQ_FRAGILITY_NIM) <= im->n_sa
               ? scale * aq_im_spectral_value(im, (size_t)(which - AQ_FRAGILITY_NIM))
               : NAN;
  }
}

int aq_fragility_im_power(int which)
{
  return which == 3 ? 2 : 1;
}

aq_status aq_fragility_fit_records(const aq_capacity *cap, size_t nrec, size_t stride,
                                   size_t npol, const aq_im *const *im, double ci,
                                   aq_fragility *fits, aq_error *err)
{
  return aq_fragility_fit_records_n(cap, nrec, stride, npol, im, AQ_FRAGILITY_NIM, ci, fits,
                                    err);
}

aq_status aq_fragility_fit_records_n(const aq_capacity *cap, size_t nrec, size_t stride,
                                     size_t npol, const aq_im *const *im, int nim,
                                     double ci, aq_fragility *fits, aq_error *err)
{
  double *x = malloc((nrec ? nrec : 1) * sizeof *x);
  int *cen = malloc((nrec ? nrec : 1) * sizeof *cen);
  aq_status st = AQ_OK;
  for (int m = 0; m < nim; m++)
    fits[m] = (aq_fragility){0, 0, NAN, NAN, NAN, NAN, NAN, 0, 0};
  if (!x || !cen) {
    free(x);
    free(cen);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "fragility", "out of memory");
  }
  for (int m = 0; m < nim; m++) {
    size_t n = 0, nmarked = 0;
    for (size_t r = 0; r < nrec; r++) {
      if (!im[r])
        continue;
      double s = INFINITY, top = NAN, l0 = NAN;
      int bad = 0, marked = 0, any_marked = 0;
      for (size_t p = 0; p < npol; p++) { /* the worse polarity governs */
        const aq_capacity *c = &cap[r * stride + p];
        bad |= c->status == AQ_CAPACITY_FAILED;
        any_marked |= c->marks != 0;
        if (!isnan(c->first_collapse_scale) && c->first_collapse_scale < s) {
          s = c->first_collapse_scale;
          marked = c->marks != 0;
        }
        top = c->scale_max;
        l0 = c->lambda0;
      }
      if (bad)
        continue;
      cen[n] = !isfinite(s);
      x[n] = aq_fragility_im_at(im[r], l0, m, cen[n] ? top : s);
      if (x[n] > 0 && isfinite(x[n])) { /* a record of zeros has no intensity */
        n++;
        nmarked += cen[n - 1] ? any_marked : marked;
      }
    }
    aq_error e;
    aq_status s = aq_fragility_fit(x, cen, n, ci, &fits[m], &e);
    fits[m].nmarked = nmarked;
    if (s != AQ_OK) {
      fits[m].median = fits[m].beta = fits[m].median_lo = fits[m].median_hi = NAN;
      if (st == AQ_OK) {
        st = s;
        if (err)
          *err = e;
      }
    }
  }
  free(x);
  free(cen);
  /* rank: 1 + the measures of smaller beta / power.  The simplex finds
   * ln beta to FIT_SIMPLEX_SIZE only, so betas within RANK_TIE of each
   * other are not told apart: they take the declared order (PGA and
   * PGA/lambda0, proportional within an arch, have the same beta, and
   * the optimiser's last digits must not decide which comes first). */
  for (int m = 0; m < nim; m++)
    if (isfinite(fits[m].beta)) {
      double bm = fits[m].beta / aq_fragility_im_power(m);
      fits[m].rank = 1;
      for (int j = 0; j < nim; j++) {
        if (j == m || !isfinite(fits[j].beta))
          continue;
        double bj = fits[j].beta / aq_fragility_im_power(j);
        int tie = fabs(bj - bm) <= RANK_TIE * fmax(bj, bm);
        fits[m].rank += tie ? j < m : bj < bm;
      }
    }
  return st;
}
