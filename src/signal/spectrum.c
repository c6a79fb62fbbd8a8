/* spectrum.c: elastic response spectra, one component and RotD (spectrum.h).
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
 * several at a time, the samples' peaks in one pass (peaks_batch) and the
 * refined ones in two (refined_batch), the same values as alone.  For RotD the refined points of
 * both components join the samples' points, in the intervals where the
 * two bounds together could pass the smallest angle's peak.
 *
 * RotD (Boore 2010, BSSA 100(4) 1830-1835).  The oscillator is linear, so
 * the response to a1 cos(theta) + a2 sin(theta) is x1 cos(theta) + x2
 * sin(theta): each angle's peak is taken over that combination of the two
 * histories (never from the two peaks).  At the samples, a point whose norm
 * sqrt(x1^2 + x2^2) is below a lower bound L of every angle's peak cannot
 * be any angle's peak; L comes from the four points that peak along 0, 45,
 * 90 and 135 degrees, and only the points above it are projected on every
 * angle.  Between samples the same bounds as above, for the two components
 * together, select the intervals to search in each direction.
 */
#include "spectrum.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"

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

typedef struct {
  double x, y; /* the two components' x, m/s^2 */
} pt2;

struct aq_spectrum_ws {
  size_t cap;            /* samples each array holds */
  double *x1, *y1, *x2, *y2; /* the two components' states at the samples */
  double *rho;           /* per interval: slack of the bound above the ends */
  size_t *pts, *ivs;     /* candidate samples and intervals (RotD) */
  pt2 *pp, *hull;        /* candidate points (cap); their hull (2 cap) */
  size_t cap_ref;        /* points ref and ref_hull hold (PEER's RotD) */
  pt2 *ref, *ref_hull;   /* the hull's vertices and the refined points;
                            their hull (2 cap_ref) */
  size_t cap_steps;
  double *xs1, *xs2;     /* one interval's refined points (cap_steps) */
  size_t cap_angles;
  double *cs, *sn, *sorted; /* cos, sin of each angle; a copy to sort */
};

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

static int ws_reserve(aq_spectrum_ws *ws, size_t n, size_t n_angles)
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

/* Room for n refined points of PEER's RotD (and their hull, 2 n), keeping
 * those held; and for one interval's refined points, steps - 1 of each
 * component.  0 when out of memory. */
static int ref_reserve(aq_spectrum_ws *ws, size_t n)
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

static int steps_reserve(aq_spectrum_ws *ws, size_t steps)
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

/* One oscillator at one sample interval. */
typedef struct {
  int pga;          /* period 0: x = -a, the limit T -> 0 */
  double zeta;      /* damping ratio */
  double kappa;     /* sqrt(1 + 4 zeta^2) */
  double theta;     /* omega dt: the interval in units of 1/omega */
  double inv_theta; /* 1 / theta */
  double p[2][2];   /* (x, y)_{k+1} = p (x, y)_k + b (a_k, a_{k+1}) */
  double b[2][2];
  size_t pieces;    /* pieces of an interval searched between samples */
  double piece_w;   /* their width, theta / pieces (<= PIECE_W) */
  int nterms;       /* Taylor terms on a piece: w^n / n! < TAYLOR_CUT */
} sdof;

static aq_status sdof_init(sdof *o, double period_s, double zeta, double dt_s,
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

/* max and min without fmax's NaN rules (no NaN gets here: the input is
 * checked finite), which GCC would call out of line. */
static inline double dmax(double a, double b)
{
  return a > b ? a : b;
}

static inline double dmin(double a, double b)
{
  return a < b ? a : b;
}

/* Upper bound of |x| over a width w from state (x0, y0) to x1, input a0 to
 * a1 (slope sig per unit theta): the smaller of the chord and transient
 * bounds (top of file). */
static inline double piece_bound(const sdof *o, double w, double x0, double y0,
                                 double x1, double a0, double a1, double sig)
{
  double ax0 = fabs(x0), ax1 = fabs(x1);
  double am = dmax(fabs(a0), fabs(a1));
  double chord = dmax(ax0, ax1) +
                 0.125 * w * w * (am + o->kappa * (ax0 + fabs(y0) + am * w));
  double xp0 = -a0 + 2 * o->zeta * sig, xp1 = -a1 + 2 * o->zeta * sig;
  double trans = dmax(fabs(xp0), fabs(xp1)) + fabs(x0 - xp0) + fabs(y0 + sig);
  return dmin(chord, trans);
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

/* Raise *best to the largest |x| inside the interval from state (x, y),
 * input a0 to a1 over theta (the ends are the caller's). */
static void search_interval(const sdof *o, double x, double y, double a0,
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

static inline double acc_at(const double *a, size_t n, size_t k)
{
  return k < n ? a[k] : 0.0;
}

/* Response at the samples of one component: x, y for k = 0..nt-1 (the
 * input zero past its n samples).  Returns max |x_k|. */
static double respond(const sdof *o, const double *a, size_t n, size_t nt,
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

/* Periods whose peak at the samples is all that is asked (no history kept)
 * run BATCH at a time through one pass over the record: one step of one
 * oscillator waits on its previous step (a product and three sums in a
 * chain, 12 to 16 cycles), so the steps of BATCH independent oscillators
 * fill the wait, and GCC vectorises the loop over them: SSE2 on any x86-64,
 * and a clone for AVX2 chosen at load time where the processor has it
 * (bench_spectrum: 16 at a time with AVX2 is 4 times faster than one at a
 * time; 8 at a time, or SSE2, gains less).  Each oscillator's arithmetic is
 * respond()'s, in the same order (the sums left to right; no fused
 * multiply-add: -std=c11 turns contraction off and the clone does not
 * enable FMA), so its peak is the same to the bit. */
enum { BATCH = 16 };
#if defined(__x86_64__) && defined(__GNUC__) && defined(__GLIBC__)
#define BATCH_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define BATCH_CLONES
#endif

/* The recursion's coefficients (sdof p and b) of o[0..nb) into the lane
 * arrays c[0..8) (p00 p01 p10 p11 b00 b01 b10 b11, BATCH values each): one
 * array per coefficient with a lane per oscillator, so that the loops over
 * the lanes vectorise; the spare lanes repeat the first. */
static inline void lanes_load(double *const c[8], const sdof *const *o, size_t nb)
{
  for (size_t j = 0; j < BATCH; j++) {
    const sdof *s = o[j < nb ? j : 0];
    c[0][j] = s->p[0][0];
    c[1][j] = s->p[0][1];
    c[2][j] = s->p[1][0];
    c[3][j] = s->p[1][1];
    c[4][j] = s->b[0][0];
    c[5][j] = s->b[0][1];
    c[6][j] = s->b[1][0];
    c[7][j] = s->b[1][1];
  }
}

/* max |x_k| of the response at the samples of up to BATCH oscillators
 * (o[0..nb), none the PGA's) to the n samples of a, into m[0..nb). */
BATCH_CLONES
static void peaks_batch(const sdof *const *o, size_t nb, const double *a, size_t n,
                        double *m)
{
  double p00[BATCH], p01[BATCH], p10[BATCH], p11[BATCH];
  double b00[BATCH], b01[BATCH], b10[BATCH], b11[BATCH];
  double x[BATCH], y[BATCH], mx[BATCH];
  lanes_load((double *const[8]){p00, p01, p10, p11, b00, b01, b10, b11}, o, nb);
  for (size_t j = 0; j < BATCH; j++)
    x[j] = y[j] = mx[j] = 0;
  double ak = a[0];
  for (size_t k = 0; k + 1 < n; k++) {
    double an = a[k + 1];
    for (size_t j = 0; j < BATCH; j++) {
      double xn = p00[j] * x[j] + p01[j] * y[j] + b00[j] * ak + b01[j] * an;
      double yn = p10[j] * x[j] + p11[j] * y[j] + b10[j] * ak + b11[j] * an;
      x[j] = xn;
      y[j] = yn;
      double ax = fabs(xn);
      mx[j] = ax > mx[j] ? ax : mx[j];
    }
    ak = an;
  }
  for (size_t j = 0; j < nb; j++)
    m[j] = mx[j];
}

/* The nb (<= BATCH) oscillators o gathered for peaks_batch: their peaks
 * into psa[idx[j]].  Returns 0, the batch's new size. */
static size_t flush_batch(const sdof *const *o, const size_t *idx, size_t nb,
                          const double *a, size_t n, double *psa)
{
  double m[BATCH];
  if (nb)
    peaks_batch(o, nb, a, n, m);
  for (size_t j = 0; j < nb; j++)
    psa[idx[j]] = m[j];
  return 0;
}

/* The chord bound's slack over every interval at once, from the largest
 * |x| and |y| of the history and |a| of the input (top of file). */
static double slack_of(const sdof *o, double xm, double ym, double amax)
{
  double th = o->theta;
  return 0.125 * th * th * (amax + o->kappa * (xm + ym + amax * th));
}

/* The chord bound's slack over every interval at once: theta^2 / 8 times
 * the largest |x''| any interval can reach (top of file). */
static double global_slack(const sdof *o, const double *x, const double *y,
                           size_t nt, double amax)
{
  double xm = 0, ym = 0;
  for (size_t k = 0; k < nt; k++) {
    xm = dmax(xm, fabs(x[k]));
    ym = dmax(ym, fabs(y[k]));
  }
  return slack_of(o, xm, ym, amax);
}

static double abs_max(const double *a, size_t n)
{
  double m = 0;
  for (size_t k = 0; k < n; k++)
    m = dmax(m, fabs(a[k]));
  return m;
}

/* The peak of one component's response, between samples included: best is
 * its peak at the samples, amax the input's. */
static double peak_one(const sdof *o, const double *a, size_t n, size_t nt,
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
      search_interval(o, x[k], y[k], a0, a1, &best);
  }
  return best;
}

/* PEER's refined samples inside one interval: from the state (x, y) at its
 * first sample, input a0 to a1 (linear), the recursion of s (the
 * oscillator over dt / steps) to each of the steps - 1 points between the
 * two samples.  Returns their largest |x|; xs (NULL, or steps - 1 values)
 * receives x at each. */
static double substeps(const sdof *s, size_t steps, double x, double y, double a0,
                       double a1, double *xs)
{
  double m = 0, ak = a0;
  for (size_t j = 1; j < steps; j++) {
    double an = a0 + (a1 - a0) * ((double)j / (double)steps);
    double xn = s->p[0][0] * x + s->p[0][1] * y + s->b[0][0] * ak + s->b[0][1] * an;
    double yn = s->p[1][0] * x + s->p[1][1] * y + s->b[1][0] * ak + s->b[1][1] * an;
    x = xn;
    y = yn;
    ak = an;
    if (xs)
      xs[j - 1] = x;
    m = dmax(m, fabs(x));
  }
  return m;
}

/* The peak of one component at PEER's refined samples: best is its peak at
 * the samples, amax the input's; s the oscillator over dt / steps.  An
 * interval is refined only if its bound (the largest |x| it can reach
 * between samples) passes the peak found so far. */
static double peak_refined(const sdof *o, const sdof *s, size_t steps, const double *a,
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

/* peak_refined() for up to BATCH oscillators o[0..nb) (none the PGA's),
 * s[j] each one's over dt / steps[j] (steps[j] >= 2), with no history
 * kept: a first pass of the recursion gives each one's peak at the samples
 * and largest |y|, so its slack g; a second pass, the same arithmetic so
 * the same states, tests each interval as peak_refined() does, in the same
 * order, and refines those that pass (one oscillator at a time: few do).
 * The peaks into m[0..nb); amax: max |a|.  The same values to the bit. */
BATCH_CLONES
static void refined_batch(const sdof *const *o, const sdof *const *s, const size_t *steps,
                          size_t nb, const double *a, size_t n, double amax, double *m)
{
  double p00[BATCH], p01[BATCH], p10[BATCH], p11[BATCH];
  double b00[BATCH], b01[BATCH], b10[BATCH], b11[BATCH];
  double x[BATCH], y[BATCH], mx[BATCH], my[BATCH], g[BATCH], xo[BATCH], yo[BATCH];
  int hit[BATCH];
  lanes_load((double *const[8]){p00, p01, p10, p11, b00, b01, b10, b11}, o, nb);
  for (size_t j = 0; j < BATCH; j++)
    x[j] = y[j] = mx[j] = my[j] = 0;
  double ak = a[0];
  for (size_t k = 0; k + 1 < n; k++) {
    double an = a[k + 1];
    for (size_t j = 0; j < BATCH; j++) {
      double xn = p00[j] * x[j] + p01[j] * y[j] + b00[j] * ak + b01[j] * an;
      double yn = p10[j] * x[j] + p11[j] * y[j] + b10[j] * ak + b11[j] * an;
      x[j] = xn;
      y[j] = yn;
      double ax = fabs(xn), ay = fabs(yn);
      mx[j] = ax > mx[j] ? ax : mx[j];
      my[j] = ay > my[j] ? ay : my[j];
    }
    ak = an;
  }
  for (size_t j = 0; j < BATCH; j++) {
    g[j] = slack_of(o[j < nb ? j : 0], mx[j], my[j], amax);
    x[j] = y[j] = 0;
  }
  ak = a[0];
  for (size_t k = 0; k + 1 < n; k++) {
    double an = a[k + 1];
    int any = 0;
    for (size_t j = 0; j < BATCH; j++) {
      double xn = p00[j] * x[j] + p01[j] * y[j] + b00[j] * ak + b01[j] * an;
      double yn = p10[j] * x[j] + p11[j] * y[j] + b10[j] * ak + b11[j] * an;
      double ax = fabs(x[j]), axn = fabs(xn);
      hit[j] = (ax > axn ? ax : axn) + g[j] > mx[j];
      any |= hit[j];
      xo[j] = x[j];
      yo[j] = y[j];
      x[j] = xn;
      y[j] = yn;
    }
    for (size_t j = 0; any && j < nb; j++) {
      if (!hit[j])
        continue;
      double sig = (an - ak) * o[j]->inv_theta;
      if (piece_bound(o[j], o[j]->theta, xo[j], yo[j], x[j], ak, an, sig) > mx[j])
        mx[j] = dmax(mx[j], substeps(s[j], steps[j], xo[j], yo[j], ak, an, NULL));
    }
    ak = an;
  }
  for (size_t j = 0; j < nb; j++)
    m[j] = mx[j];
}

/* The nr (<= BATCH) refined oscillators gathered for refined_batch: their
 * peaks into psa[idx[j]].  Returns 0, the batch's new size. */
static size_t flush_refined(const sdof *const *o, const sdof *const *s, const size_t *steps,
                            const size_t *idx, size_t nr, const double *a, size_t n,
                            double amax, double *psa)
{
  double m[BATCH];
  if (nr)
    refined_batch(o, s, steps, nr, a, n, amax, m);
  for (size_t j = 0; j < nr; j++)
    psa[idx[j]] = m[j];
  return 0;
}

/* The oscillator over PEER's refined step dt / steps of period_s (> 0 or
 * 0): *steps = N (1: no refinement).  Errors: "period_s" below dt / 1000. */
static aq_status peer_init(sdof *s, size_t *steps, double period_s, double zeta,
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
  return n > 1 ? sdof_init(s, period_s, zeta, dt_s / (double)n, err) : AQ_OK;
}

static aq_status check_args(const double *acc, size_t n, double dt_s,
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

static aq_status check_peaks(const aq_spectrum_opts *o, aq_error *err)
{
  if (o->peaks != AQ_SPECTRUM_PEAKS_PEER && o->peaks != AQ_SPECTRUM_PEAKS_EXACT &&
      o->peaks != AQ_SPECTRUM_PEAKS_SAMPLES)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "peaks",
                        "expected peer, exact or samples, got %d", (int)o->peaks);
  return AQ_OK;
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
      check_args(acc_mps2, n, dt_s, damping, period_s, n_periods, err);
  if (st == AQ_OK)
    st = check_peaks(opts, err);
  if (st != AQ_OK)
    return st;
  if (!ws_reserve(ws, n, 0))
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "spectrum",
                        "out of memory for %zu samples", n);
  double amax = abs_max(acc_mps2, n);
  /* T = 0: the input's peak; the periods whose peak is at the samples
   * only, BATCH at a time (peaks_batch); the others one by one, their
   * history kept */
  sdof bo[BATCH], ro[BATCH], rs[BATCH];
  const sdof *bp[BATCH], *rp[BATCH], *rsp[BATCH];
  size_t bi[BATCH], nb = 0, ri[BATCH], rn[BATCH], nr = 0;
  for (size_t i = 0; i < n_periods; i++) {
    sdof o;
    st = sdof_init(&o, period_s[i], damping, dt_s, err);
    if (st != AQ_OK)
      return st;
    sdof sub;
    size_t steps = 1;
    if (opts->peaks == AQ_SPECTRUM_PEAKS_PEER) {
      st = peer_init(&sub, &steps, period_s[i], damping, dt_s, err);
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
        nb = flush_batch(bp, bi, nb, acc_mps2, n, psa_mps2);
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
        nr = flush_refined(rp, rsp, rn, ri, nr, acc_mps2, n, amax, psa_mps2);
      continue;
    }
    double m = respond(&o, acc_mps2, n, n, ws->x1, ws->y1);
    if (opts->peaks == AQ_SPECTRUM_PEAKS_EXACT)
      m = peak_one(&o, acc_mps2, n, n, ws->x1, ws->y1, m, amax);
    else if (opts->peaks == AQ_SPECTRUM_PEAKS_PEER)
      m = peak_refined(&o, &sub, steps, acc_mps2, n, n, ws->x1, ws->y1, m, amax);
    psa_mps2[i] = m;
  }
  flush_batch(bp, bi, nb, acc_mps2, n, psa_mps2);
  flush_refined(rp, rsp, rn, ri, nr, acc_mps2, n, amax, psa_mps2);
  return AQ_OK;
}

aq_status aq_spectrum_response(const double *acc_mps2, size_t n, double dt_s,
                               double damping, double period_s, double *u_m,
                               double *v_mps, aq_error *err)
{
  aq_status st = check_args(acc_mps2, n, dt_s, damping, &period_s, 1, err);
  if (st != AQ_OK)
    return st;
  if (!(period_s > 0))
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "period_s",
                        "expected a period > 0 s, got %g", period_s);
  sdof o;
  st = sdof_init(&o, period_s, damping, dt_s, err);
  if (st != AQ_OK)
    return st;
  respond(&o, acc_mps2, n, n, u_m, v_mps);
  double w = 2 * AQ_PI / period_s;
  for (size_t k = 0; k < n; k++) {
    u_m[k] /= w * w; /* x = omega^2 u */
    v_mps[k] /= w;   /* y = omega u' */
  }
  return AQ_OK;
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* cos and sin of angle j of n over [0, 180) degrees, exact at 0 and 90. */
static void angle_cs(size_t j, size_t n, double *c, double *s)
{
  if (j == 0) {
    *c = 1;
    *s = 0;
  } else if (2 * j == n) {
    *c = 0;
    *s = 1;
  } else {
    double th = AQ_PI * (double)j / (double)n;
    *c = cos(th);
    *s = sin(th);
  }
}

static int cmp_pt2(const void *a, const void *b)
{
  const pt2 *p = a, *q = b;
  if (p->x != q->x)
    return (p->x > q->x) - (p->x < q->x);
  return (p->y > q->y) - (p->y < q->y);
}

static inline double cross(pt2 o, pt2 a, pt2 b)
{
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

/* The convex hull's vertices of the m points p (sorted in place) into h
 * (room for 2 m): Andrew's monotone chain.  Returns their number. */
static size_t hull2(pt2 *p, size_t m, pt2 *h)
{
  qsort(p, m, sizeof *p, cmp_pt2);
  if (m < 3) {
    memcpy(h, p, m * sizeof *p);
    return m;
  }
  size_t k = 0;
  for (size_t i = 0; i < m; i++) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0)
      k--;
    h[k++] = p[i];
  }
  for (size_t i = m - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0)
      k--;
    h[k++] = p[i];
  }
  return k - 1;
}

/* Directions of the lower bound of every angle's peak (below): 4, then
 * LO_DIRS. */
enum { LO_DIRS = 16 };

/* The nd directions pi d / nd, d = 0..nd-1: cos into dc, sin into ds. */
static void lo_dirs(int nd, double *dc, double *ds)
{
  for (int d = 0; d < nd; d++) {
    dc[d] = cos(AQ_PI * d / nd);
    ds[d] = sin(AQ_PI * d / nd);
  }
}

/* Both components' responses at the samples, x1, y1 of a1 (n1 samples)
 * and x2, y2 of a2 (n2), k = 0..nt-1, the input zero past its samples:
 * each step respond()'s, the two in one loop (two independent chains, so
 * one's wait is the other's work); and in the same loop the first pass of
 * rotd_peaks(): for each of its 4 first directions, the first sample k
 * where |c x1 + s x2| is largest, into q[4] (any points give a valid
 * lower bound, so q decides only how many points the hull is taken of; the
 * same as rotd_peaks' own scan, so the same work follows).  o is not the
 * PGA's. */
static void respond2(const sdof *o, const double *a1, size_t n1, const double *a2,
                     size_t n2, size_t nt, double *x1, double *y1, double *x2,
                     double *y2, size_t *q)
{
  double dc[4], ds[4], qm[4];
  lo_dirs(4, dc, ds);
  double p00 = o->p[0][0], p01 = o->p[0][1], p10 = o->p[1][0],
         p11 = o->p[1][1];
  double b00 = o->b[0][0], b01 = o->b[0][1], b10 = o->b[1][0],
         b11 = o->b[1][1];
  double xa = 0, ya = 0, xb = 0, yb = 0;
  double aa = acc_at(a1, n1, 0), ab = acc_at(a2, n2, 0);
  x1[0] = y1[0] = x2[0] = y2[0] = 0;
  for (int d = 0; d < 4; d++) {
    qm[d] = fabs(dc[d] * x1[0] + ds[d] * x2[0]);
    q[d] = 0;
  }
  for (size_t k = 0; k + 1 < nt; k++) {
    double na = acc_at(a1, n1, k + 1), nb = acc_at(a2, n2, k + 1);
    double xn = p00 * xa + p01 * ya + b00 * aa + b01 * na;
    double yn = p10 * xa + p11 * ya + b10 * aa + b11 * na;
    double un = p00 * xb + p01 * yb + b00 * ab + b01 * nb;
    double vn = p10 * xb + p11 * yb + b10 * ab + b11 * nb;
    x1[k + 1] = xa = xn;
    y1[k + 1] = ya = yn;
    x2[k + 1] = xb = un;
    y2[k + 1] = yb = vn;
    aa = na;
    ab = nb;
    for (int d = 0; d < 4; d++) {
      double v = fabs(dc[d] * xn + ds[d] * un);
      if (v > qm[d]) {
        qm[d] = v;
        q[d] = k + 1;
      }
    }
  }
}

/* PEER's refined points of both components, in the intervals where the
 * two components' bounds together (|c x1 + s x2| <= sqrt(b1^2 + b2^2))
 * pass lo_all, the smallest angle's peak at the samples, joined to the nh
 * vertices of the samples' hull (ws->hull): every angle's peak over the
 * hull of all.  s steps dt / steps.  0 when out of memory. */
static int rotd_refined(aq_spectrum_ws *ws, const sdof *o, const sdof *s, size_t steps,
                        const double *a1, size_t n1, const double *a2, size_t n2,
                        size_t nt, size_t na, size_t nh, double lo_all, double *peak)
{
  const double *x1 = ws->x1, *x2 = ws->x2, *y1 = ws->y1, *y2 = ws->y2;
  if (!ref_reserve(ws, nh) || !steps_reserve(ws, steps))
    return 0;
  memcpy(ws->ref, ws->hull, nh * sizeof *ws->ref);
  size_t m = nh;
  double lo2 = lo_all * lo_all, th = o->theta;
  for (size_t k = 0; k + 1 < nt; k++) {
    double a10 = acc_at(a1, n1, k), a11 = acc_at(a1, n1, k + 1);
    double a20 = acc_at(a2, n2, k), a21 = acc_at(a2, n2, k + 1);
    double s1 = (a11 - a10) * o->inv_theta, s2 = (a21 - a20) * o->inv_theta;
    double b1 = piece_bound(o, th, x1[k], y1[k], x1[k + 1], a10, a11, s1);
    double b2 = piece_bound(o, th, x2[k], y2[k], x2[k + 1], a20, a21, s2);
    if (b1 * b1 + b2 * b2 <= lo2)
      continue;
    substeps(s, steps, x1[k], y1[k], a10, a11, ws->xs1);
    substeps(s, steps, x2[k], y2[k], a20, a21, ws->xs2);
    if (!ref_reserve(ws, m + steps - 1))
      return 0;
    for (size_t j = 0; j + 1 < steps; j++)
      ws->ref[m++] = (pt2){ws->xs1[j], ws->xs2[j]};
  }
  if (m == nh)
    return 1;
  size_t nr = hull2(ws->ref, m, ws->ref_hull);
  for (size_t j = 0; j < na; j++) {
    double h = 0, c = ws->cs[j], sn = ws->sn[j];
    for (size_t i = 0; i < nr; i++)
      h = dmax(h, fabs(c * ws->ref_hull[i].x + sn * ws->ref_hull[i].y));
    peak[j] = h;
  }
  return 1;
}

/* Peaks of every angle for one period: ws->x1.. hold the two responses at
 * the samples (nt of them); sub and steps: PEER's refined oscillator.
 * 0 when out of memory. */
static int rotd_peaks(aq_spectrum_ws *ws, const sdof *o, const sdof *sub, size_t steps,
                      const double *a1, size_t n1, const double *a2, size_t n2,
                      size_t nt, size_t na, aq_spectrum_peaks peaks, const size_t *q_first,
                      double *peak)
{
  const double *x1 = ws->x1, *x2 = ws->x2, *y1 = ws->y1, *y2 = ws->y2;
  const double *cs = ws->cs, *sn = ws->sn;
  /* At the samples: every angle's peak is at a vertex of the points'
   * convex hull (|projection| on a direction peaks there).  The hull is
   * taken of the points that can reach the smallest peak: a lower bound lo
   * of every angle's peak comes from the points that peak along a few
   * directions (first 4 over all points, then 16 over those above the
   * first bound), and a point of norm below it is no angle's peak.  The
   * first 4 come from respond2 (q_first) unless NULL. */
  double lo = 0;
  size_t np = 0;
  for (int pass = 0; pass < 2; pass++) {
    int nd = pass ? LO_DIRS : 4;
    double dc[LO_DIRS], ds[LO_DIRS], qm[LO_DIRS];
    size_t q[LO_DIRS];
    lo_dirs(nd, dc, ds);
    for (int d = 0; d < nd; d++) {
      qm[d] = -1;
      q[d] = pass || !q_first ? 0 : q_first[d];
    }
    size_t m = pass ? np : nt;
    for (size_t i = 0; i < m && (pass || !q_first); i++) {
      size_t k = pass ? ws->pts[i] : i;
      for (int d = 0; d < nd; d++) {
        double v = fabs(dc[d] * x1[k] + ds[d] * x2[k]);
        if (v > qm[d]) {
          qm[d] = v;
          q[d] = k;
        }
      }
    }
    double l = INFINITY;
    for (size_t j = 0; j < na; j++) {
      double h = 0;
      for (int d = 0; d < nd; d++) {
        double v = fabs(cs[j] * x1[q[d]] + sn[j] * x2[q[d]]);
        h = v > h ? v : h;
      }
      l = h < l ? h : l;
    }
    lo = l > lo ? l : lo;
    double lo2 = lo * lo;
    size_t kept = 0;
    for (size_t i = 0; i < m; i++) {
      size_t k = pass ? ws->pts[i] : i;
      if (x1[k] * x1[k] + x2[k] * x2[k] >= lo2)
        ws->pts[kept++] = k;
    }
    np = kept;
  }
  for (size_t i = 0; i < np; i++) {
    ws->pp[i].x = x1[ws->pts[i]];
    ws->pp[i].y = x2[ws->pts[i]];
  }
  size_t nh = hull2(ws->pp, np, ws->hull);
  double lo_all = INFINITY;
  for (size_t j = 0; j < na; j++) {
    double h = 0, c = cs[j], s = sn[j];
    for (size_t i = 0; i < nh; i++) {
      double v = fabs(c * ws->hull[i].x + s * ws->hull[i].y);
      h = v > h ? v : h;
    }
    peak[j] = h;
    lo_all = h < lo_all ? h : lo_all;
  }
  if (o->pga || peaks == AQ_SPECTRUM_PEAKS_SAMPLES ||
      (peaks == AQ_SPECTRUM_PEAKS_PEER && steps < 2))
    return 1;
  if (peaks == AQ_SPECTRUM_PEAKS_PEER)
    return rotd_refined(ws, o, sub, steps, a1, n1, a2, n2, nt, na, nh, lo_all, peak);
  /* Between samples: an interval can raise an angle's peak only if its
   * larger end's projection plus its slack rho (the chord and transient
   * bounds for both components together: |c u + s v| <= |u| + |v|) passes
   * that peak; first those whose norm could pass the smallest peak. */
  size_t ni = 0;
  double th = o->theta, z2 = 2 * o->zeta;
  for (size_t k = 0; k + 1 < nt; k++) {
    double a10 = acc_at(a1, n1, k), a11 = acc_at(a1, n1, k + 1);
    double a20 = acc_at(a2, n2, k), a21 = acc_at(a2, n2, k + 1);
    double am1 = dmax(fabs(a10), fabs(a11)), am2 = dmax(fabs(a20), fabs(a21));
    double m = am1 + am2 +
               o->kappa * (fabs(x1[k]) + fabs(y1[k]) + fabs(x2[k]) +
                           fabs(y2[k]) + (am1 + am2) * th);
    double s1 = (a11 - a10) * o->inv_theta, s2 = (a21 - a20) * o->inv_theta;
    double rh = fabs(x1[k] + a10 - z2 * s1) + fabs(y1[k] + s1) +
                fabs(x2[k] + a20 - z2 * s2) + fabs(y2[k] + s2);
    double rho = dmin(0.125 * th * th * m, 2 * rh);
    double need = lo_all - rho;
    double r0 = x1[k] * x1[k] + x2[k] * x2[k];
    double r1 = x1[k + 1] * x1[k + 1] + x2[k + 1] * x2[k + 1];
    if (need <= 0 || dmax(r0, r1) > need * need) {
      ws->rho[ni] = rho;
      ws->ivs[ni++] = k;
    }
  }
  for (size_t j = 0; j < na; j++) {
    double c = cs[j], s = sn[j];
    for (size_t i = 0; i < ni; i++) {
      size_t k = ws->ivs[i];
      double p0 = c * x1[k] + s * x2[k], p1 = c * x1[k + 1] + s * x2[k + 1];
      if (dmax(fabs(p0), fabs(p1)) + ws->rho[i] <= peak[j])
        continue;
      double b0 = c * acc_at(a1, n1, k) + s * acc_at(a2, n2, k);
      double b1 = c * acc_at(a1, n1, k + 1) + s * acc_at(a2, n2, k + 1);
      double q0 = c * y1[k] + s * y2[k], sig = (b1 - b0) * o->inv_theta;
      if (piece_bound(o, th, p0, q0, p1, b0, b1, sig) > peak[j])
        search_interval(o, p0, q0, b0, b1, &peak[j]);
    }
  }
  return 1;
}

aq_status aq_spectrum_rotd(aq_spectrum_ws *ws, const aq_spectrum_opts *opts,
                           const double *acc1_mps2, size_t n1,
                           const double *acc2_mps2, size_t n2, double dt_s,
                           double damping, const double *period_s,
                           size_t n_periods, aq_rotd *out,
                           double *angle_peaks_mps2, aq_error *err)
{
  aq_spectrum_opts def;
  if (!opts) {
    aq_spectrum_opts_default(&def);
    opts = &def;
  }
  aq_status st =
      check_args(acc1_mps2, n1, dt_s, damping, period_s, n_periods, err);
  if (st == AQ_OK)
    st = check_args(acc2_mps2, n2, dt_s, damping, period_s, n_periods, err);
  if (st == AQ_OK)
    st = check_peaks(opts, err);
  if (st != AQ_OK)
    return st;
  size_t na = opts->n_angles;
  if (na < 2 || na % 2)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "n_angles",
                        "expected an even number of angles >= 2, got %zu", na);
  size_t n = n1 > n2 ? n1 : n2;
  if (!ws_reserve(ws, n, na))
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "spectrum",
                        "out of memory for %zu samples", n);
  for (size_t j = 0; j < na; j++)
    angle_cs(j, na, &ws->cs[j], &ws->sn[j]);
  for (size_t i = 0; i < n_periods; i++) {
    sdof o, sub;
    size_t steps = 1;
    st = sdof_init(&o, period_s[i], damping, dt_s, err);
    if (st == AQ_OK && opts->peaks == AQ_SPECTRUM_PEAKS_PEER)
      st = peer_init(&sub, &steps, period_s[i], damping, dt_s, err);
    if (st != AQ_OK)
      return st;
    size_t q[4];
    if (o.pga || opts->one_at_a_time) {
      respond(&o, acc1_mps2, n1, n, ws->x1, ws->y1);
      respond(&o, acc2_mps2, n2, n, ws->x2, ws->y2);
    } else {
      respond2(&o, acc1_mps2, n1, acc2_mps2, n2, n, ws->x1, ws->y1, ws->x2, ws->y2, q);
    }
    double *pk = ws->sorted; /* the angles' peaks, then sorted in place */
    if (!rotd_peaks(ws, &o, &sub, steps, acc1_mps2, n1, acc2_mps2, n2, n, na, opts->peaks,
                    o.pga || opts->one_at_a_time ? NULL : q, pk))
      return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "spectrum",
                          "out of memory for the refined points of %zu samples", n);
    if (angle_peaks_mps2)
      memcpy(angle_peaks_mps2 + i * na, pk, na * sizeof *pk);
    aq_rotd *r = &out[i];
    r->psa1_mps2 = pk[0];
    r->psa2_mps2 = pk[na / 2];
    r->geomean_mps2 = sqrt(r->psa1_mps2 * r->psa2_mps2);
    qsort(pk, na, sizeof *pk, cmp_double);
    r->rotd50_mps2 = 0.5 * (pk[na / 2 - 1] + pk[na / 2]);
    r->rotd100_mps2 = pk[na - 1];
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
