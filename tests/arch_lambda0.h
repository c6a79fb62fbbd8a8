/* arch_lambda0.h: lambda0 of a hinge set by the 9x9 equilibrium (eq. (3)),
 * a second way to get it besides the search's virtual work: the tests'
 * brute-force references; and the search's minimum lambda0 of an arch
 * built from parameters, for the tests' bisections on the thickness. */
#ifndef AQ_TESTS_ARCH_LAMBDA0_H
#define AQ_TESTS_ARCH_LAMBDA0_H

#include <math.h>

#include "arch/model.h"

/* lambda0 of hs by the 9x9 equilibrium, of either sign, and *act (if not
 * NULL) the sign of the ground acceleration that drives it; 1 if every
 * hinge opens at first order and every hinge reaction is compressive. */
static inline int aq_test_lambda0_eq_act(const aq_geom *g, const aq_hinge_set *hs, double *l0,
                                         int *act)
{
  aq_mech m;
  aq_mech_state st;
  aq_equil eq;
  aq_error e;
  if (aq_mech_init(&m, g, hs, &e) != AQ_OK || aq_mech_eval(&m, 0.0, &st) != 0)
    return 0;
  int qs = hs->face[0] == 'i' ? 1 : -1;
  double rate[4] = {1, st.phi[1][1] - 1, st.phi[2][1] - st.phi[1][1], -st.phi[2][1]};
  for (int k = 0; k < 4; k++)
    if (!((hs->face[k] == 'i' ? 1 : -1) * qs * rate[k] > 0))
      return 0;
  /* the horizontal load acts in the direction that does work on the
   * mechanism as its hinges open: act_sign * q_sign * sum m dx/dq < 0 */
  double wx = 0;
  for (int b = 0; b < 3; b++)
    wx += m.body[b].mass_kg * st.c[b][1].x;
  if (wx == 0)
    return 0;
  aq_live live = {AQ_LIVE_HORIZONTAL, qs * wx > 0 ? -1 : 1, {0, 0}, 0, 9.80665};
  if (aq_mech_equilibrium(&m, &st, &live, &eq, &e) != AQ_OK)
    return 0;
  for (int k = 0; k < 4; k++)
    if (!(eq.normal[k] > 0))
      return 0;
  *l0 = eq.lambda;
  if (act)
    *act = live.act_sign;
  return 1;
}

static inline int aq_test_lambda0_eq(const aq_geom *g, const aq_hinge_set *hs, double *l0)
{
  return aq_test_lambda0_eq_act(g, hs, l0, NULL);
}

/* The search's minimum lambda0 of the arch p describes (standard gravity),
 * or NAN if its geometry or the search fails. */
static inline double aq_test_min_lambda0(const aq_arch_params *p)
{
  aq_geom g;
  aq_error e;
  aq_hinge_set hs;
  double l0 = NAN;
  if (aq_geom_init(&g, p, &e) != AQ_OK)
    return NAN;
  aq_status st = aq_search_minimum(&g, 9.80665, &hs, &l0, NULL, &e);
  aq_geom_free(&g);
  return st == AQ_OK ? l0 : NAN;
}

/* The thickness t in [lo, hi] at which the minimum lambda0 of the arch
 * make(t, ctx) crosses 0 (lambda0 grows with t), by iters bisections; NAN
 * if an arch fails. */
static inline double aq_test_critical_thickness(aq_arch_params (*make)(double t, const void *ctx),
                                                const void *ctx, double lo, double hi, int iters)
{
  for (int it = 0; it < iters; it++) {
    double mid = 0.5 * (lo + hi);
    aq_arch_params p = make(mid, ctx);
    double l0 = aq_test_min_lambda0(&p);
    if (isnan(l0))
      return NAN;
    if (l0 > 0)
      hi = mid;
    else
      lo = mid;
  }
  return 0.5 * (lo + hi);
}

/* The tests' brute forces: every hinge set of an arch of n >= 3 voussoirs,
 * one per call, into *hs: the 16 face patterns in turn (*pat: faces read
 * as binary digits, e 0 and i 1, so 0 is e e e e and 5 is e i e i), and
 * within each the C(n+1, 4) joint choices in lexicographic order.  Start
 * with *pat = -1; 0 when every set has been given. */
static inline int aq_test_next_set(size_t n, int *pat, aq_hinge_set *hs)
{
  size_t *j = hs->joint;
  int k = 3;
  if (*pat >= 0)
    while (k >= 0 && j[k] == n - (size_t)(3 - k))
      k--;
  if (*pat < 0 || k < 0) {
    if (n < 3 || ++*pat == 16)
      return 0;
    for (int m = 0; m < 4; m++)
      j[m] = (size_t)m;
  } else {
    j[k]++;
    for (int m = k + 1; m < 4; m++)
      j[m] = j[m - 1] + 1;
  }
  for (int m = 0; m < 4; m++)
    hs->face[m] = (*pat >> (3 - m)) & 1 ? 'i' : 'e';
  return 1;
}

#endif
