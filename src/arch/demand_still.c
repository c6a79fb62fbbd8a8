/* demand_still.c: the demand of a run in which the arch never moves: the
 * statics' least friction at the record's peak (demand.h,
 * docs/demand.md, "A run that never moves"). */
#include <math.h>
#include <stddef.h>

#include "demand.h"
#include "demand_impl.h"

void aq_demand_set_least(aq_demand *d, aq_demand_least_fn least, void *ctx)
{
  d->least = least;
  d->least_ctx = ctx;
}

/* Step i's load of direction sgn: sgn a / (g + a_v), a and a_v scaled. */
static double still_load(const aq_steps *st, size_t i, double scale, double vscale,
                         double g, int sgn)
{
  double gv = st->av_mps2 ? g + vscale * st->av_mps2[i] : g;
  return sgn * scale * st->a_mps2[i] / gv;
}

/* The first step i < n_end whose load of direction sgn is at least lam
 * (n_end: none).  Without a vertical acceleration the quiet index skips
 * the steps below a bound loosened by 1e-12 (relative) and the exact load
 * decides. */
static size_t still_first(const aq_steps *st, size_t n_end, double scale, double vscale,
                          double g, int sgn, double lam)
{
  size_t i = 0;
  int index = !st->av_mps2 && scale != 0 && lam > 0;
  double c = lam * g / (sgn * scale) * (1 - 1e-12);
  double lo = sgn * scale > 0 ? -INFINITY : c, hi = sgn * scale > 0 ? c : INFINITY;
  for (; i < n_end; i++) {
    if (index && (i = aq_steps_next_outside(st, i, lo, hi)) >= n_end)
      break;
    if (still_load(st, i, scale, vscale, g, sgn) >= lam)
      return i;
  }
  return n_end;
}

void aq_demand_still(aq_demand *d, const aq_steps *steps, size_t n_end, double scale,
                     double vscale, double g_mps2)
{
  if (d->moved || !d->least || n_end == 0 || n_end > steps->n)
    return;
  /* each direction's peak load and its first step */
  double lam[2] = {0, 0};
  if (!steps->av_mps2 && steps->nblock) { /* from the quiet index */
    double hi = -INFINITY, lo = INFINITY;
    for (size_t b = 0; b < steps->nblock; b++) {
      hi = fmax(hi, steps->block_max_mps2[b]);
      lo = fmin(lo, steps->block_min_mps2[b]);
    }
    lam[1] = fmax(scale * (scale >= 0 ? hi : lo) / g_mps2, 0);
    lam[0] = fmax(-scale * (scale >= 0 ? lo : hi) / g_mps2, 0);
  } else {
    for (size_t i = 0; i < n_end; i++)
      for (int k = 0; k < 2; k++)
        lam[k] = fmax(lam[k], still_load(steps, i, scale, vscale, g_mps2, 2 * k - 1));
  }
  double mu = NAN, t_s = NAN;
  size_t joint = 0;
  for (int k = 0; k < 2; k++) {
    size_t j = 0;
    double m = d->least(d->least_ctx, 2 * k - 1, lam[k], &j);
    if (isnan(m))
      return;
    size_t i = lam[k] > 0 ? still_first(steps, n_end, scale, vscale, g_mps2, 2 * k - 1, lam[k])
                          : 0;
    double t = aq_steps_t(steps, i < n_end ? i : 0);
    if (isnan(mu) || m > mu || (m == mu && t < t_s))
      mu = m, t_s = t, joint = j;
  }
  d->still = 1;
  d->still_mu = mu;
  d->still_joint = joint;
  d->still_s = t_s;
  d->still_slide = NAN;
  if (!(mu > d->mu_limit))
    return;
  /* the first step whose load needs more than the limit: in each direction
   * the least load that does (the least friction is nondecreasing in the
   * load), found by bisection, then the first step that reaches it */
  for (int k = 0; k < 2; k++) {
    double lo = 0, hi = lam[k];
    if (!(d->least(d->least_ctx, 2 * k - 1, hi, NULL) > d->mu_limit))
      continue;
    if (d->least(d->least_ctx, 2 * k - 1, 0, NULL) > d->mu_limit)
      hi = 0; /* at rest already */
    for (int it = 0; it < 200 && hi > 0 && lo < hi; it++) {
      double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi)
        break;
      if (d->least(d->least_ctx, 2 * k - 1, mid, NULL) > d->mu_limit)
        hi = mid;
      else
        lo = mid;
    }
    size_t i = hi > 0 ? still_first(steps, n_end, scale, vscale, g_mps2, 2 * k - 1, hi) : 0;
    if (i < n_end) {
      double t = aq_steps_t(steps, i);
      if (isnan(d->still_slide) || t < d->still_slide)
        d->still_slide = t;
    }
  }
}

