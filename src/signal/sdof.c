/* sdof.c: one linear oscillator of the response spectra (spectrum_int.h):
 * its transition over a sample interval, its response at the samples, its
 * peak between samples and at PEER's refined samples.
 *
 * The oscillator.  u'' + 2 zeta omega u' + omega^2 u = -a(t), at rest at the
 * first sample, a(t) linear between samples (Nigam & Jennings 1969, BSSA
 * 59(2) 909-922: the exact solution for that input).  It is written here in
 * units that keep every period alike: time theta = omega t, state x = omega^2
 * u (the pseudo-acceleration, m/s^2) and y = omega u' (m/s^2), input a and its
 * slope sigma = da/dtheta.  Then
 *
 *   x' = y,  y' = -x - 2 zeta y - a,  a' = sigma,  sigma' = 0,
 *
 * a linear system z' = Z z with the constant 4x4 matrix Z; over one sample
 * interval (theta_h = omega dt) the state moves by the transition matrix
 * exp(Z theta_h), computed once per oscillator by GSL's scaling and squaring
 * (gsl_linalg_exponential_ss).  This is Nigam and Jennings' recurrence
 * (x, y)_{k+1} = P (x, y)_k + B (a_k, a_{k+1}) without their closed-form
 * coefficients, whose terms of size 2 zeta / (omega dt)^3 cancel to leave
 * O(1) as omega dt -> 0 (at T = 20 s, dt = 0.005 s: 2.6e7 times the
 * rounding); the matrix exponential keeps B to rounding at every omega dt.
 *
 * The peak between samples.  PSA = max |x| over continuous time, not over
 * the samples: at T = 5 dt the sampled peak can be 1 - cos(pi/5) = 19 % low.
 * For each interval a rigorous upper bound of |x| inside it (two, the
 * smaller is taken) decides whether the interval could hold a peak above the
 * best found; only those are searched:
 *   - chord: |x''| <= |a| + kappa sqrt(x^2 + y^2), kappa = sqrt(1 + 4
 *     zeta^2), and d sqrt(x^2 + y^2)/dtheta <= |a| (the energy (x^2 + y^2)/2
 *     has derivative -2 zeta y^2 - a y), so over a width w, |x| <= the larger
 *     end + M w^2 / 8, M = a_max + kappa (|x0| + |y0| + a_max w);
 *   - transient: x = x_p + x_h, x_p = -a + 2 zeta sigma (linear in time), and
 *     the free part's (x_h^2 + y_h^2) never grows (its derivative is
 *     -4 zeta y_h^2), so |x| <= max |x_p| at the ends + |x_h0| + |y_h0|.
 * A searched interval is cut into pieces of width w <= 1 (omega dt / w
 * pieces at short periods), on each of which x is its Taylor series about
 * the piece's start (the derivatives follow from the equations:
 * x^(n) = -x^(n-2) - 2 zeta x^(n-1) for n >= 4; 24 terms reach rounding at
 * w <= 1).  On a piece of width < pi / sqrt(1 - zeta^2), y' is a damped
 * sinusoid and has at most one zero, so y is monotone on at most two parts;
 * a part on which y changes sign holds one extremum of x, found by Newton's
 * method kept inside its bracket, to a step below 1e-9 w: the value there
 * is exact to |x''| (1e-9)^2 / 2, far below AQ_SPECTRUM_PEAK_REL.
 *
 * The peak is taken from the first sample to the last (a processed record
 * carries its zero pads, over which the oscillator swings on freely).  With
 * peaks SAMPLES only the samples count.
 *
 * PEER's refined samples (peaks PEER, the default).  PEER's NGA-West2
 * spectra take the peak at the samples of the record resampled to dt / N,
 * N = ceil(10 dt / T), the acceleration interpolated linearly, through the
 * piecewise-linear recursion at dt / N.  The input linear between samples
 * is the same input at any refinement, so that recursion gives the exact
 * response at the points k dt + j dt / N: here the state at the samples
 * comes from the recursion at dt, and the N - 1 points inside an interval
 * from the recursion at dt / N started from its first sample.  Only an
 * interval whose bound (above) passes the peak found so far can raise it,
 * so only those are refined: the peak is the refined samples' exactly,
 * at the cost of the continuous search.  One component's periods run
 * several at a time, the samples' peaks in one pass and the refined ones in
 * two (spectrum_batch.c), the same values as alone; for RotD the refined
 * points of both components join the samples' points, in the intervals
 * where the two bounds together could pass the smallest angle's peak
 * (spectrum_rotd.c).
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <string.h>

#include "../units.h"
#include "spectrum_int.h"

/* Terms of the Taylor series on a piece of width w <= PIECE_W: the
 * derivatives of order n >= 4 are combinations of the state's, the
 * characteristic roots having modulus 1 in these units, so the terms fall as
 * w^n / n!; the series stops at the first n >= 4 with w^n / n! below
 * TAYLOR_CUT (24 terms at w = 1: 1 / 24! = 1.6e-24; 9 at w = 0.03). */
enum { TAYLOR_N = 24 };
#define TAYLOR_CUT 1e-20
#define PIECE_W 1.0
/* Newton's step, relative to the piece width, below which an extremum's
 * time is taken as found (its value is then exact to |x''| 1e-18 w^2 / 2). */
#define ROOT_STEP_REL 1e-9
#define ROOT_MAX_ITER 100

aq_status aq_sdof_init(aq_sdof *o, double period_s, double zeta, double dt_s,
                       aq_error *err)
{
  memset(o, 0, sizeof *o);
  o->zeta = zeta;
  o->kappa = sqrt(1 + 4 * zeta * zeta);
  if (period_s == 0) {
    o->pga = 1;
    return AQ_OK;
  }
  double th = 2 * AQ_PI / period_s * dt_s;
  o->theta = th;
  o->inv_theta = 1 / th;
  double zd[16] = {0, th, 0, 0, -th, -2 * zeta * th, -th, 0,
                   0, 0,  0, th, 0,   0,              0,   0};
  double ed[16];
  gsl_matrix_view z = gsl_matrix_view_array(zd, 4, 4);
  gsl_matrix_view e = gsl_matrix_view_array(ed, 4, 4);
  int rc = gsl_linalg_exponential_ss(&z.matrix, &e.matrix, GSL_PREC_DOUBLE);
  if (rc != GSL_SUCCESS)
    return aq_error_set(err, AQ_ENUMERIC, NULL, -1, -1, "period_s",
                        "transition matrix of T = %g s, dt = %g s: %s",
                        period_s, dt_s, gsl_strerror(rc));
  for (int r = 0; r < 2; r++) {
    o->p[r][0] = ed[4 * r + 0];
    o->p[r][1] = ed[4 * r + 1];
    /* a_k weighs column 2 (input) minus column 3 (slope) / theta */
    o->b[r][1] = ed[4 * r + 3] / th;
    o->b[r][0] = ed[4 * r + 2] - o->b[r][1];
  }
  double np = ceil(th / PIECE_W);
  o->pieces = np < 1 ? 1 : (size_t)np;
  o->piece_w = th / (double)o->pieces;
  double term = 1;
  o->nterms = TAYLOR_N;
  for (int k = 1; k < TAYLOR_N; k++) {
    term *= o->piece_w / k;
    if (term < TAYLOR_CUT && k >= 4) {
      o->nterms = k + 1;
      break;
    }
  }
  return AQ_OK;
}

static inline double horner(const double *c, int n, double t)
{
  double s = c[n - 1];
  for (int i = n - 2; i >= 0; i--)
    s = s * t + c[i];
  return s;
}

/* The root of the polynomial f (nf coefficients, derivative g) in [l, r],
 * where f(l) = fl and f(r) = fr have opposite signs: Newton's method from
 * the secant's root, bisecting whenever a step would leave the bracket. */
static double root_in(const double *f, int nf, const double *g, double l,
                      double r, double fl, double fr, double w)
{
  double t = l + (r - l) * (fl / (fl - fr));
  if (!(t > l && t < r))
    t = 0.5 * (l + r);
  for (int it = 0; it < ROOT_MAX_ITER; it++) {
    double ft = horner(f, nf, t);
    if (ft == 0)
      return t;
    if ((ft < 0) == (fl < 0))
      l = t;
    else
      r = t;
    double gt = horner(g, nf - 1, t);
    double tn = gt != 0 ? t - ft / gt : 0.5 * (l + r);
    if (!(tn > l && tn < r))
      tn = 0.5 * (l + r);
    if (fabs(tn - t) <= ROOT_STEP_REL * w || r - l <= ROOT_STEP_REL * w)
      return tn;
    t = tn;
  }
  return t;
}

/* Largest |x| inside one piece of width w (the ends are the caller's), the
 * n Taylor coefficients of x about its start in cx. */
static double piece_extremum(const double *cx, int n, double w)
{
  double cy[TAYLOR_N - 1], cq[TAYLOR_N - 2], cr[TAYLOR_N - 3];
  for (int i = 0; i < n - 1; i++)
    cy[i] = (i + 1) * cx[i + 1]; /* y = x' */
  for (int i = 0; i < n - 2; i++)
    cq[i] = (i + 1) * cy[i + 1]; /* y' */
  for (int i = 0; i < n - 3; i++)
    cr[i] = (i + 1) * cq[i + 1]; /* y'' */
  double cut[3] = {0, w, w};
  int nc = 2;
  double q0 = cq[0], qw = horner(cq, n - 2, w);
  double best = 0;
  if ((q0 < 0) != (qw < 0) && q0 != 0 && qw != 0) {
    /* y turns once inside: split there (and the turning point's own x
     * covers extrema too close to it to bracket) */
    double tt = root_in(cq, n - 2, cr, 0, w, q0, qw, w);
    cut[1] = tt;
    nc = 3;
    best = fabs(horner(cx, n, tt));
  }
  for (int k = 0; k + 1 < nc; k++) {
    double l = cut[k], r = cut[k + 1];
    double yl = horner(cy, n - 1, l), yr = horner(cy, n - 1, r);
    if ((yl < 0) == (yr < 0) || yl == 0 || yr == 0)
      continue;
    double t = root_in(cy, n - 1, cq, l, r, yl, yr, w);
    double v = fabs(horner(cx, n, t));
    best = v > best ? v : best;
  }
  return best;
}

/* The n Taylor coefficients of x about a point with state (x, y), input a,
 * slope sig: x^(2) = -x - 2 zeta y - a, x^(3) = -y - 2 zeta x^(2) - sig,
 * then x^(k) = -x^(k-2) - 2 zeta x^(k-1). */
static void taylor(double zeta, double x, double y, double a, double sig,
                   int n, double *c)
{
  double d[TAYLOR_N];
  d[0] = x;
  d[1] = y;
  d[2] = -x - 2 * zeta * y - a;
  d[3] = -y - 2 * zeta * d[2] - sig;
  for (int k = 4; k < n; k++)
    d[k] = -d[k - 2] - 2 * zeta * d[k - 1];
  double f = 1;
  for (int k = 0; k < n; k++) {
    if (k > 1)
      f *= k;
    c[k] = d[k] / f;
  }
}

void aq_sdof_search_interval(const aq_sdof *o, double x, double y, double a0,
                             double a1, double *best)
{
  double sig = (a1 - a0) * o->inv_theta, w = o->piece_w;
  double c[TAYLOR_N], cy[TAYLOR_N - 1];
  int n = o->nterms;
  for (size_t j = 0; j < o->pieces; j++) {
    double a = j == 0 ? a0 : a0 + (a1 - a0) * ((double)j / (double)o->pieces);
    double ae = j + 1 == o->pieces
                    ? a1
                    : a0 + (a1 - a0) * ((double)(j + 1) / (double)o->pieces);
    taylor(o->zeta, x, y, a, sig, n, c);
    for (int i = 0; i < n - 1; i++)
      cy[i] = (i + 1) * c[i + 1];
    double xe = horner(c, n, w), ye = horner(cy, n - 1, w);
    if (piece_bound(o, w, x, y, xe, a, ae, sig) > *best) {
      double v = piece_extremum(c, n, w);
      *best = v > *best ? v : *best;
    }
    if (j + 1 < o->pieces && fabs(xe) > *best)
      *best = fabs(xe);
    x = xe;
    y = ye;
  }
}

double aq_sdof_respond(const aq_sdof *o, const double *a, size_t n, size_t nt,
                       double *x, double *y)
{
  if (o->pga) {
    double m = 0;
    for (size_t k = 0; k < nt; k++) {
      x[k] = -acc_at(a, n, k);
      y[k] = 0;
      m = fabs(x[k]) > m ? fabs(x[k]) : m;
    }
    return m;
  }
  double p00 = o->p[0][0], p01 = o->p[0][1], p10 = o->p[1][0],
         p11 = o->p[1][1];
  double b00 = o->b[0][0], b01 = o->b[0][1], b10 = o->b[1][0],
         b11 = o->b[1][1];
  double xk = 0, yk = 0, m = 0, ak = acc_at(a, n, 0);
  x[0] = y[0] = 0;
  for (size_t k = 0; k + 1 < nt; k++) {
    double an = acc_at(a, n, k + 1);
    double xn = p00 * xk + p01 * yk + b00 * ak + b01 * an;
    double yn = p10 * xk + p11 * yk + b10 * ak + b11 * an;
    x[k + 1] = xn;
    y[k + 1] = yn;
    double ax = fabs(xn);
    m = ax > m ? ax : m;
    xk = xn;
    yk = yn;
    ak = an;
  }
  return m;
}

/* The chord bound's slack over every interval at once: theta^2 / 8 times
 * the largest |x''| any interval can reach (top of file). */
static double global_slack(const aq_sdof *o, const double *x, const double *y,
                           size_t nt, double amax)
{
  double xm = 0, ym = 0;
  for (size_t k = 0; k < nt; k++) {
    xm = dmax(xm, fabs(x[k]));
    ym = dmax(ym, fabs(y[k]));
  }
  return slack_of(o, xm, ym, amax);
}

double aq_sdof_peak_one(const aq_sdof *o, const double *a, size_t n, size_t nt,
                        const double *x, const double *y, double best,
                        double amax)
{
  if (o->pga)
    return best;
  double g = global_slack(o, x, y, nt, amax);
  for (size_t k = 0; k + 1 < nt; k++) {
    if (dmax(fabs(x[k]), fabs(x[k + 1])) + g <= best)
      continue; /* the interval's own bounds are smaller still */
    double a0 = acc_at(a, n, k), a1 = acc_at(a, n, k + 1);
    double sig = (a1 - a0) * o->inv_theta;
    if (piece_bound(o, o->theta, x[k], y[k], x[k + 1], a0, a1, sig) > best)
      aq_sdof_search_interval(o, x[k], y[k], a0, a1, &best);
  }
  return best;
}

double aq_sdof_peak_refined(const aq_sdof *o, const aq_sdof *s, size_t steps, const double *a,
                            size_t n, size_t nt, const double *x, const double *y,
                            double best, double amax)
{
  if (o->pga || steps < 2)
    return best;
  double g = global_slack(o, x, y, nt, amax);
  for (size_t k = 0; k + 1 < nt; k++) {
    if (dmax(fabs(x[k]), fabs(x[k + 1])) + g <= best)
      continue;
    double a0 = acc_at(a, n, k), a1 = acc_at(a, n, k + 1);
    double sig = (a1 - a0) * o->inv_theta;
    if (piece_bound(o, o->theta, x[k], y[k], x[k + 1], a0, a1, sig) > best)
      best = dmax(best, substeps(s, steps, x[k], y[k], a0, a1, NULL));
  }
  return best;
}

aq_status aq_sdof_peer_init(aq_sdof *s, size_t *steps, double period_s, double zeta,
                            double dt_s, aq_error *err)
{
  *steps = 1;
  if (period_s == 0)
    return AQ_OK;
  size_t n = aq_spectrum_peer_steps(dt_s, period_s);
  if (n == 0)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "period_s",
                        "expected a period >= %g s (dt / %d) with peaks peer (ceil(10 dt / T) "
                        "steps in every sample interval), got %g",
                        10 * dt_s / AQ_SPECTRUM_PEER_STEPS_MAX,
                        AQ_SPECTRUM_PEER_STEPS_MAX / 10, period_s);
  *steps = n;
  return n > 1 ? aq_sdof_init(s, period_s, zeta, dt_s / (double)n, err) : AQ_OK;
}
