/* quad_series.c: the Chebyshev series of the work-path quadrature leg
 * (leg_quad.c, quad_series.h): the change of variable of a panel that
 * takes the 1/sqrt singularities at zeros of KE out of the time integrand,
 * and the interpolation at Chebyshev points of the first kind, its exact
 * integral, KE from the integral of dKE/dpsi, and the position where the
 * integral reaches a time.
 */
#include <float.h>
#include <math.h>

#include "quad_series.h"

/* Distance to a zero of the quadratic model ke + k1 z + k2/2 z^2 (z >= 0)
 * when ke > 0 and k1 < 0; INFINITY when the model has none. */
double aq_quad_zero_ahead(double ke, double k1, double k2)
{
  if (ke <= 0)
    return 0;
  if (!(k1 < 0))
    return INFINITY;
  double disc = k1 * k1 - 2 * k2 * ke;
  if (disc < 0)
    return INFINITY;
  return 2 * ke / (-k1 + sqrt(disc));
}

void aq_quad_map_init(wp_map *mp, double L, double za, double zb)
{
  mp->L = L;
  int near_a = za <= WP_NEAR_ZERO * L, near_b = zb <= WP_NEAR_ZERO * L;
  mp->za = near_a ? za : 0;
  mp->zb = near_b ? zb : 0;
  if (near_a && near_b) {
    mp->kind = 3;
    mp->W = za + L + zb;
    mp->u0 = 2 * asin(fmin(1.0, sqrt(za / mp->W)));
    mp->u1 = 2 * asin(fmin(1.0, sqrt((za + L) / mp->W)));
  } else if (near_a) {
    mp->kind = 1;
    mp->u0 = sqrt(za);
    mp->u1 = sqrt(za + L);
  } else if (near_b) {
    mp->kind = 2;
    mp->u0 = sqrt(L + zb);
    mp->u1 = sqrt(zb);
  } else {
    mp->kind = 0;
    mp->u0 = 0;
    mp->u1 = L;
  }
}

/* A near-zero minimum of KE at or just beyond an end, from the quadratic
 * model there: KE ~ KE_m + k2/2 (sigma - sigma_m)^2.  The substitution
 * sigma - sigma_m = h sinh(w), h = sqrt(2 KE_m / k2), makes KE ~ KE_m
 * cosh^2 w cancel the Jacobian h cosh w: the near-singular integrand of a
 * slow passage over a saddle becomes smooth.  Start side first. */
void aq_quad_map_near_min(wp_map *mp, double kea, double k1a, double k2a,
                          double keb, double k1b, double k2b)
{
  double L = mp->L;
  if (kea > 0 && k2a > 0 && k1a >= 0) {
    double sm = -k1a / k2a, km = kea - k1a * k1a / (2 * k2a);
    if (km > 0) {
      double h = sqrt(2 * km / k2a);
      if (-sm + h < WP_NEAR_MIN_SPAN * L) {
        mp->kind = 4;
        mp->W = h;
        mp->za = sm; /* centre, relative to the start (<= 0) */
        mp->u0 = asinh(-sm / h);
        mp->u1 = asinh((L - sm) / h);
        return;
      }
    }
  }
  if (keb > 0 && k2b > 0 && k1b <= 0) {
    double sm = -k1b / k2b, km = keb - k1b * k1b / (2 * k2b);
    if (km > 0) {
      double h = sqrt(2 * km / k2b);
      if (sm + h < WP_NEAR_MIN_SPAN * L) {
        mp->kind = 5;
        mp->W = h;
        mp->zb = sm; /* centre, beyond the end (>= 0) */
        mp->u0 = asinh((L + sm) / h);
        mp->u1 = asinh(sm / h);
      }
    }
  }
}

/* sigma(psi) and dsigma/dpsi. */
double aq_quad_map_sigma(const wp_map *mp, double psi, double *jac)
{
  double h = 0.5 * (mp->u1 - mp->u0);
  double u = mp->u0 + h * (psi + 1);
  double sg;
  switch (mp->kind) {
  case 3: {
    double sn = sin(0.5 * u);
    sg = -mp->za + mp->W * sn * sn;
    *jac = 0.5 * mp->W * sin(u) * h;
    break;
  }
  case 1:
    sg = u * u - mp->za;
    *jac = 2 * u * h;
    break;
  case 2:
    sg = mp->L + mp->zb - u * u;
    *jac = -2 * u * h;
    break;
  case 4:
    sg = mp->za + mp->W * sinh(u);
    *jac = mp->W * cosh(u) * h;
    break;
  case 5:
    sg = mp->L + mp->zb - mp->W * sinh(u);
    *jac = -mp->W * cosh(u) * h;
    break;
  default:
    sg = u;
    *jac = h;
  }
  if (sg < 0)
    sg = 0;
  if (sg > mp->L)
    sg = mp->L;
  return sg;
}

/* Chebyshev series helpers: f(x) = sum' c_k T_k(x) (c_0 halved). */
double aq_quad_cheb_eval(const double *c, int n, double x)
{
  double b1 = 0, b2 = 0;
  for (int k = n - 1; k >= 1; k--) {
    double b0 = 2 * x * b1 - b2 + c[k];
    b2 = b1;
    b1 = b0;
  }
  return x * b1 - b2 + 0.5 * c[0];
}

void aq_quad_cheb_cos_init(wp_cos *t, int n)
{
  t->n = n;
  for (int k = 0; k < n; k++)
    for (int j = 0; j < n; j++)
      t->cs[k][j] = cos(WP_PI * k * (j + 0.5) / n);
}

void aq_quad_cheb_build(wp_cheb *ch, const wp_cos *t, const double *g, int n)
{
  ch->n = n;
  for (int k = 0; k < n; k++) {
    double sum = 0;
    for (int j = 0; j < n; j++)
      sum += g[j] * t->cs[k][j];
    ch->c[k] = 2.0 * sum / n;
  }
  ch->c[n] = 0;
  /* antiderivative: C_k = (c_{k-1} - c_{k+1}) / (2k), c_0 taken whole */
  for (int k = 1; k <= n; k++) {
    double cm = k == 1 ? ch->c[0] : ch->c[k - 1];
    double cp = k + 1 <= n ? ch->c[k + 1] : 0;
    ch->ci[k] = (cm - cp) / (2.0 * k);
  }
  ch->ci[0] = 0;
  double at_m1 = aq_quad_cheb_eval(ch->ci, n + 1, -1.0);
  ch->ci[0] = -2 * at_m1;
  ch->total = aq_quad_cheb_eval(ch->ci, n + 1, 1.0);
  double mean = fabs(ch->c[0]) > 0 ? fabs(ch->c[0]) : 1;
  ch->tail = (fabs(ch->c[n - 1]) + fabs(ch->c[n - 2])) / mean;
}

/* The integration weights of cheb_build's antiderivative at the nodes and
 * at +1, column by column (the map from nodal values is linear). */
void aq_quad_cheb_quad_init(wp_cos *t)
{
  const int n = t->n;
  double e[WP_MAX_NODES] = {0};
  wp_cheb ch;
  for (int i = 0; i < n; i++) {
    e[i] = 1;
    aq_quad_cheb_build(&ch, t, e, n);
    e[i] = 0;
    for (int j = 0; j < n; j++)
      t->iq[j][i] = aq_quad_cheb_eval(ch.ci, n + 1, t->cs[1][j]);
    t->iw[i] = ch.total;
  }
}

/* KE at psi (sigma = sg) by the series: the start's KE plus the integral
 * of dKE/dpsi, less the mismatch at a turning-point end spread in
 * proportion to sigma (so that KE ~ (L - sigma) stays a smooth product). */
double aq_quad_kes_at(const wp_kes *k, const wp_cos *t, double psi, double sg)
{
  wp_cheb f;
  aq_quad_cheb_build(&f, t, k->fk, k->n);
  return k->ke_a + aq_quad_cheb_eval(f.ci, k->n + 1, psi) - k->mis * (sg / k->L);
}

/* psi in [-1, 1] where the time reaches tau (0 <= tau <= total). */
double aq_quad_cheb_solve(const wp_cheb *ch, double tau)
{
  double lo = -1, hi = 1;
  double x = -1 + 2 * tau / ch->total;
  for (int it = 0; it < 100; it++) {
    double f = aq_quad_cheb_eval(ch->ci, ch->n + 1, x) - tau;
    if (f > 0)
      hi = x;
    else
      lo = x;
    double d = aq_quad_cheb_eval(ch->c, ch->n, x);
    double xn = d > 0 ? x - f / d : 0.5 * (lo + hi);
    if (!(xn > lo && xn < hi))
      xn = 0.5 * (lo + hi);
    if (fabs(xn - x) <= 4 * DBL_EPSILON)
      return xn;
    x = xn;
    if (hi - lo <= 1e-16)
      break;
  }
  return x;
}
