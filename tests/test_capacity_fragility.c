/* test_capacity_fragility.c: the lognormal maximum-likelihood fit against
 * its closed form for complete data (median = exp(mean ln x), beta = the
 * population standard deviation of ln x, and the profile interval
 * ln theta_hat +- beta_hat sqrt(exp(chi2/n) - 1)), against a direct
 * maximisation on a grid for censored data, and the interval's coverage
 * against a simulation. */
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "../src/capacity/capacity.h"
#include "check.h"

AQ_TEST(capacity_fragility_complete_data_closed_form)
{
  const double x[] = {0.731, 1.262, 0.948, 2.113, 0.587, 1.574, 0.862, 1.093,
                      0.664, 1.871, 1.329};
  const int c[11] = {0};
  const size_t n = 11;
  double m = 0, v = 0;
  for (size_t i = 0; i < n; i++)
    m += log(x[i]) / n;
  for (size_t i = 0; i < n; i++)
    v += (log(x[i]) - m) * (log(x[i]) - m) / n;
  aq_fragility f;
  aq_error e;
  aq_check(aq_fragility_fit(x, c, n, 0.90, &f, &e) == AQ_OK, "fit ok");
  aq_check_rel(f.median, exp(m), 1e-7, "median = exp(mean ln x)");
  aq_check_rel(f.beta, sqrt(v), 1e-6, "beta = population std of ln x");
  /* profile deviance n ln(1 + (ln theta - m)^2 / v) = chi2_1(0.90) */
  double half = sqrt(v) * sqrt(expm1(gsl_cdf_chisq_Pinv(0.90, 1) / n));
  aq_check_rel(f.median_lo, exp(m - half), 1e-6, "median_lo (profile, closed form)");
  aq_check_rel(f.median_hi, exp(m + half), 1e-6, "median_hi (profile, closed form)");
  aq_check(f.ncensored == 0 && f.n == n, "counts");
  /* a single distinct collapse value cannot be fitted */
  const double one[] = {1.2, 1.2, 3.0};
  const int cone[] = {0, 0, 1};
  aq_check(aq_fragility_fit(one, cone, 3, 0.9, &f, &e) == AQ_OK && isnan(f.median) &&
               isnan(f.beta), "no spread: nan");
  const double bad[] = {1.0, -2.0};
  aq_check(aq_fragility_fit(bad, c, 2, 0.9, &f, &e) == AQ_EVALUE, "x <= 0 refused");
}

AQ_TEST(capacity_fragility_censored_against_a_grid)
{
  /* collapses and records censored at their caps (right-censored) */
  const double x[] = {0.812, 1.414, 0.977, 2.236, 0.655, 1.903, 1.121, 2.5, 2.5,
                      3.1, 1.731, 2.8, 0.904};
  const int c[] = {0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 0, 1, 0};
  const size_t n = 13;
  aq_fragility f;
  aq_error e;
  aq_check(aq_fragility_fit(x, c, n, 0.90, &f, &e) == AQ_OK, "fit ok");
  /* the likelihood written out here, maximised on a coarse then a fine grid */
  double best = INFINITY, bt = 0, bb = 0;
  for (int pass = 0; pass < 2; pass++) {
    double t0 = pass ? bt - 0.02 : -1.0, b0 = pass ? bb - 0.02 : 0.05;
    double h = pass ? 1e-4 : 5e-3;
    int N = pass ? 400 : 600;
    for (int i = 0; i <= N; i++)
      for (int j = 0; j <= N; j++) {
        double lt = t0 + i * h, b = b0 + j * h;
        if (!(b > 0))
          continue;
        double ll = 0;
        for (size_t k = 0; k < n; k++) {
          double z = (log(x[k]) - lt) / b;
          ll += c[k] ? log(gsl_cdf_ugaussian_Q(z))
                     : log(gsl_ran_ugaussian_pdf(z) / (b * x[k]));
        }
        if (-ll < best) {
          best = -ll;
          bt = lt;
          bb = b;
        }
      }
  }
  aq_check_rel(f.median, exp(bt), 3e-4, "censored median against the grid");
  aq_check_rel(f.beta, bb, 5e-4, "censored beta against the grid");
  aq_check_rel(-f.loglik, best, 1e-6, "maximised log-likelihood");
  aq_check(f.ncensored == 4, "censored %zu", f.ncensored);
  aq_check(f.median_lo < f.median && f.median < f.median_hi, "interval holds the median");
  /* censoring pulls the median above the collapses' own (complete) fit */
  double m = 0;
  for (size_t k = 0; k < n; k++)
    if (!c[k])
      m += log(x[k]) / 9;
  aq_check(f.median > exp(m), "censored median %g above the collapses' %g", f.median,
           exp(m));
}

AQ_TEST(capacity_fragility_interval_coverage_by_simulation)
{
  /* lognormal data theta 0.85, beta 0.4, censored at 1.3 (about 15 %):
   * the 90 % profile interval should hold theta in about 90 % of samples */
  const double theta = 0.85, beta = 0.4, cap = 1.3;
  const size_t n = 40, M = 300;
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 20261123);
  double x[40];
  int c[40];
  size_t hit = 0, fitted = 0;
  for (size_t s = 0; s < M; s++) {
    for (size_t i = 0; i < n; i++) {
      double v = theta * exp(beta * gsl_ran_ugaussian(rng));
      c[i] = v > cap;
      x[i] = c[i] ? cap : v;
    }
    aq_fragility f;
    aq_error e;
    if (aq_fragility_fit(x, c, n, 0.90, &f, &e) != AQ_OK || isnan(f.median))
      continue;
    fitted++;
    hit += f.median_lo <= theta && theta <= f.median_hi;
  }
  gsl_rng_free(rng);
  double cov = (double)hit / (double)fitted;
  aq_check(fitted == M, "every sample fitted (%zu of %zu)", fitted, M);
  /* binomial sd sqrt(0.9 0.1 / 300) = 0.017: within 3 sd */
  aq_check_abs(cov, 0.90, 0.052, "coverage of the 90 %% profile interval");
}
