/* quad_series.h: the panels and Chebyshev series of the work-path
 * quadrature leg (quad_series.c), shared with leg_quad.c; internal to
 * src/arch.  Plain structs, nothing allocated: the caller owns them.
 * Units: sigma and s in rad, KE in J, time in s.
 */
#ifndef AQ_ARCH_QUAD_SERIES_H
#define AQ_ARCH_QUAD_SERIES_H

#include <stddef.h>

#define WP_MAX_NODES 32

static const double WP_PI = 3.14159265358979323846;

static const double WP_NEAR_ZERO = 2.0;      /* a zero of KE within this many L is "near" */

static const double WP_NEAR_MIN_SPAN = 0.25; /* sinh map when the minimum's width is within this * L */

/* cos(pi k (j + 1/2) / n) for the current n (node j is row k = 1). */
typedef struct {
  int n;
  double cs[WP_MAX_NODES][WP_MAX_NODES];
  /* integral from -1 of the interpolant of nodal values v: at node j,
   * sum_i iq[j][i] v_i; to +1, sum_i iw[i] v_i (cheb_quad_init) */
  double iq[WP_MAX_NODES][WP_MAX_NODES];
  double iw[WP_MAX_NODES];
} wp_cos;

/* The change of variable of one panel: psi in [-1, 1] -> sigma in [0, L]. */
typedef struct {
  int kind; /* 0 linear, 1 zero behind, 2 zero ahead, 3 both, 4/5 near-zero
              minimum at the start / end (sinh) */
  double L, za, zb, W, u0, u1;
} wp_map;

/* A panel's integrand as a Chebyshev series and its antiderivative. */
typedef struct {
  int n;
  double c[WP_MAX_NODES + 1];  /* integrand series */
  double ci[WP_MAX_NODES + 2]; /* antiderivative series, zero at psi = -1 */
  double total;                /* panel time, s */
  double tail;                 /* |c_{n-1}| + |c_{n-2}| relative to |c_0| */
} wp_cheb;

/* KE along a panel from the integral of dKE/dsigma (see wp_leg). */
typedef struct {
  int on;       /* 0: use eq. (19) as it stands */
  int n;
  double ke_a;  /* KE at the panel start, J */
  double mis;   /* KE at a turning-point end by the series (0 by the end's location), J */
  double L;     /* panel length, rad */
  double total; /* integral of dKE/dpsi over the panel, J */
  double fk[WP_MAX_NODES]; /* dKE/dpsi at the nodes, J */
} wp_kes;

/* Distance to a zero of the quadratic model ke + k1 z + k2/2 z^2 (z >= 0)
 * when ke > 0 and k1 < 0; INFINITY when the model has none. */
double aq_quad_zero_ahead(double ke, double k1, double k2);

/* The change of variable of a panel [0, L] with zeros of KE za behind its
 * start and zb beyond its end (each used when within WP_NEAR_ZERO L). */
void aq_quad_map_init(wp_map *mp, double L, double za, double zb);

/* A near-zero minimum of KE at or just beyond an end, from the quadratic
 * model there: KE ~ KE_m + k2/2 (sigma - sigma_m)^2.  The substitution
 * sigma - sigma_m = h sinh(w), h = sqrt(2 KE_m / k2), makes KE ~ KE_m
 * cosh^2 w cancel the Jacobian h cosh w: the near-singular integrand of a
 * slow passage over a saddle becomes smooth.  Start side first. */
void aq_quad_map_near_min(wp_map *mp, double kea, double k1a, double k2a,
                          double keb, double k1b, double k2b);

/* sigma(psi) and dsigma/dpsi. */
double aq_quad_map_sigma(const wp_map *mp, double psi, double *jac);

/* Chebyshev series helpers: f(x) = sum' c_k T_k(x) (c_0 halved). */
double aq_quad_cheb_eval(const double *c, int n, double x);

/* The cosines of n Chebyshev points of the first kind into t. */
void aq_quad_cheb_cos_init(wp_cos *t, int n);

/* The series of the values g at t's n nodes, and of its antiderivative
 * from psi = -1, into ch. */
void aq_quad_cheb_build(wp_cheb *ch, const wp_cos *t, const double *g, int n);

/* The integration weights of cheb_build's antiderivative at the nodes and
 * at +1, column by column (the map from nodal values is linear). */
void aq_quad_cheb_quad_init(wp_cos *t);

/* KE at psi (sigma = sg) by the series: the start's KE plus the integral
 * of dKE/dpsi, less the mismatch at a turning-point end spread in
 * proportion to sigma (so that KE ~ (L - sigma) stays a smooth product). */
double aq_quad_kes_at(const wp_kes *k, const wp_cos *t, double psi, double sg);

/* psi in [-1, 1] where the time reaches tau (0 <= tau <= total). */
double aq_quad_cheb_solve(const wp_cheb *ch, double tau);

#endif
