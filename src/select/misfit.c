/* misfit.c: the scale rule, the misfit and the checks of a suite
 * (misfit.h). */
#include "misfit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Relative slack of the scale range's upper bound against the rounding of
 * f max_i s_i (f is found so that the conditions just hold). */
#define SCALE_HI_SLACK 1e-12

double aq_select_scale(const double *psa_mps2, const double *target_mps2, size_t nper,
                       double lo, double hi)
{
  double sum = 0;
  for (size_t k = 0; k < nper; k++)
    sum += log(target_mps2[k]) - log(psa_mps2[k]);
  double s = exp(sum / (double)nper);
  return s < lo ? lo : s > hi ? hi : s;
}

double aq_select_misfit_one(const double *psa_mps2, double f, const double *target_mps2,
                            size_t nper)
{
  double sum = 0, lf = log(f);
  for (size_t k = 0; k < nper; k++) {
    double d = lf + log(psa_mps2[k]) - log(target_mps2[k]);
    sum += d * d;
  }
  return sum / (double)nper;
}

aq_status aq_select_prepare(const aq_select_problem *p, aq_select_prepared *q, aq_error *err)
{
  memset(q, 0, sizeof *q);
  q->p = p;
  q->ln_band = log(p->band);
  q->scale = malloc((p->nrec ? p->nrec : 1) * sizeof *q->scale);
  q->y = malloc((p->nrec * p->nper > 0 ? p->nrec * p->nper : 1) * sizeof *q->y);
  q->z = p->target0_mps2 > 0 ? malloc((p->nrec ? p->nrec : 1) * sizeof *q->z) : NULL;
  if (!q->scale || !q->y || (p->target0_mps2 > 0 && !q->z)) {
    aq_select_prepared_free(q);
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
  }
  for (size_t i = 0; i < p->nrec; i++) {
    const double *a = p->psa_mps2 + i * p->nper;
    double s = aq_select_scale(a, p->target_mps2, p->nper, p->scale_lo, p->scale_hi);
    q->scale[i] = s;
    for (size_t k = 0; k < p->nper; k++)
      q->y[i * p->nper + k] = s * a[k] / p->target_mps2[k];
    if (q->z)
      q->z[i] = s * p->pga_mps2[i] / p->target0_mps2;
  }
  return AQ_OK;
}

void aq_select_prepared_free(aq_select_prepared *q)
{
  free(q->scale);
  free(q->y);
  free(q->z);
  q->scale = q->y = q->z = NULL;
}

void aq_select_evaluate_sums(const aq_select_prepared *q, size_t n, const double *sum_y,
                             double sum_z, double max_s, aq_select_eval *e)
{
  const aq_select_problem *p = q->p;
  size_t nper = p->nper;
  double inv = 1.0 / (double)n, s1 = 0, s2 = 0, dmin = INFINITY;
  size_t kmin = 0;
  for (size_t k = 0; k < nper; k++) {
    double d = log(sum_y[k] * inv); /* ln (m_k / S_k) */
    s1 += d;
    s2 += d * d;
    if (d < dmin) {
      dmin = d;
      kmin = k;
    }
  }
  /* ln f: the least raise that puts m_k >= band S_k everywhere and the
   * mean zero-period value at its bound */
  double lf = q->ln_band - dmin;
  e->zero_ratio = NAN;
  if (q->z) {
    e->zero_ratio = sum_z * inv;
    double lz = -log(e->zero_ratio);
    if (lz > lf)
      lf = lz;
  }
  if (lf < 0)
    lf = 0;
  /* mean_k (d_k + lf)^2 = s2/K + 2 lf s1/K + lf^2 */
  double K = (double)nper;
  double m = s2 / K + 2 * lf * s1 / K + lf * lf;
  e->misfit = m > 0 ? m : 0;
  e->factor = exp(lf);
  e->min_ratio = exp(dmin);
  e->min_k = kmin;
  e->max_scale = max_s;
  double over = e->factor * max_s / p->scale_hi;
  e->feasible = over <= 1 + SCALE_HI_SLACK;
  e->excess = e->feasible ? 0 : log(over);
}

void aq_select_evaluate(const aq_select_prepared *q, const size_t *idx, size_t n,
                        aq_select_eval *e)
{
  const aq_select_problem *p = q->p;
  double *sum = calloc(p->nper ? p->nper : 1, sizeof *sum);
  double sz = 0, ms = 0;
  if (!sum) { /* no memory: call it infeasible */
    memset(e, 0, sizeof *e);
    e->misfit = e->excess = INFINITY;
    return;
  }
  for (size_t j = 0; j < n; j++) {
    const double *y = q->y + idx[j] * p->nper;
    for (size_t k = 0; k < p->nper; k++)
      sum[k] += y[k];
    if (q->z)
      sz += q->z[idx[j]];
    if (q->scale[idx[j]] > ms)
      ms = q->scale[idx[j]];
  }
  aq_select_evaluate_sums(q, n, sum, sz, ms, e);
  free(sum);
}

int aq_select_better(const aq_select_eval *a, const aq_select_eval *b)
{
  if (a->feasible != b->feasible)
    return a->feasible;
  if (!a->feasible && a->excess != b->excess)
    return a->excess < b->excess;
  return a->misfit < b->misfit;
}

int aq_select_events_ok(const aq_select_problem *p, const size_t *idx, size_t n)
{
  for (size_t j = 0; p->recording && j < n; j++)
    for (size_t i = j + 1; i < n; i++)
      if (p->recording[idx[j]] >= 0 && p->recording[idx[j]] == p->recording[idx[i]])
        return 0;
  if (!p->event || p->max_per_event == 0)
    return 1;
  for (size_t j = 0; j < n; j++) {
    int ev = p->event[idx[j]];
    if (ev < 0)
      continue;
    size_t c = 0;
    for (size_t i = 0; i < n; i++)
      c += p->event[idx[i]] == ev;
    if (c > p->max_per_event)
      return 0;
  }
  return 1;
}
