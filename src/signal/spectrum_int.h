/* spectrum_int.h: the inside of the response spectra (spectrum.h), shared
 * by their files and by no one else:
 *   spectrum.c        the peak rules' names, options, workspace and checks,
 *                     and the spectrum of one component (aq_spectrum_psa)
 *   sdof.c            one oscillator: its transition over a sample interval,
 *                     response at the samples, peak between samples, PEER's
 *                     refined samples (the method: sdof.c's top comment)
 *   spectrum_batch.c  several oscillators in one pass (vectorised)
 *   spectrum_rotd.c   RotD of two horizontal components
 * The state x = omega^2 u, y = omega u' (m/s^2) of every oscillator here
 * is in units of the pseudo-acceleration (sdof.c). */
#ifndef AQ_SIGNAL_SPECTRUM_INT_H
#define AQ_SIGNAL_SPECTRUM_INT_H

#include <math.h>
#include <stddef.h>

#include "spectrum.h"

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

/* Room for n samples of both components (states, RotD's candidates) and
 * n_angles angles, keeping what fits.  0 when out of memory. */
int aq_spectrum_ws_reserve(aq_spectrum_ws *ws, size_t n, size_t n_angles);

/* Room for n refined points of PEER's RotD (and their hull, 2 n), keeping
 * those held.  0 when out of memory. */
int aq_spectrum_ws_reserve_ref(aq_spectrum_ws *ws, size_t n);

/* Room for one interval's refined points of PEER's RotD, steps - 1 of
 * each component.  0 when out of memory. */
int aq_spectrum_ws_reserve_steps(aq_spectrum_ws *ws, size_t steps);

/* The arguments of a spectrum: samples (finite), dt_s, damping and the
 * periods; AQ_EVALUE naming the field when one is not as expected. */
aq_status aq_spectrum_check_args(const double *acc, size_t n, double dt_s,
                                 double damping, const double *period_s,
                                 size_t n_periods, aq_error *err);

/* opts->peaks one of the three rules; AQ_EVALUE otherwise. */
aq_status aq_spectrum_check_peaks(const aq_spectrum_opts *o, aq_error *err);

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
} aq_sdof;

/* Oscillators run together by the batched kernels (spectrum_batch.c). */
enum { AQ_SPECTRUM_BATCH = 16 };

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
 * bounds (sdof.c's top comment). */
static inline double piece_bound(const aq_sdof *o, double w, double x0, double y0,
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

static inline double acc_at(const double *a, size_t n, size_t k)
{
  return k < n ? a[k] : 0.0;
}

/* The chord bound's slack over every interval at once, from the largest
 * |x| and |y| of the history and |a| of the input (sdof.c's top
 * comment). */
static inline double slack_of(const aq_sdof *o, double xm, double ym, double amax)
{
  double th = o->theta;
  return 0.125 * th * th * (amax + o->kappa * (xm + ym + amax * th));
}

/* PEER's refined samples inside one interval: from the state (x, y) at its
 * first sample, input a0 to a1 (linear), the recursion of s (the
 * oscillator over dt / steps) to each of the steps - 1 points between the
 * two samples.  Returns their largest |x|; xs (NULL, or steps - 1 values)
 * receives x at each. */
static inline double substeps(const aq_sdof *s, size_t steps, double x, double y,
                              double a0, double a1, double *xs)
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

/* ---- sdof.c */

/* The oscillator of period_s (0: the PGA's, x = -a) and damping ratio
 * zeta over one interval dt_s: its transition (p, b) and the pieces an
 * interval is searched in.  AQ_ENUMERIC (field period_s) when GSL's matrix
 * exponential fails. */
aq_status aq_sdof_init(aq_sdof *o, double period_s, double zeta, double dt_s,
                       aq_error *err);

/* The oscillator over PEER's refined step dt / steps of period_s (> 0 or
 * 0): *steps = N (1: no refinement).  Errors: "period_s" below dt / 1000. */
aq_status aq_sdof_peer_init(aq_sdof *s, size_t *steps, double period_s, double zeta,
                            double dt_s, aq_error *err);

/* Response at the samples of one component: x, y for k = 0..nt-1 (the
 * input zero past its n samples).  Returns max |x_k|. */
double aq_sdof_respond(const aq_sdof *o, const double *a, size_t n, size_t nt,
                       double *x, double *y);

/* Raise *best to the largest |x| inside the interval from state (x, y),
 * input a0 to a1 over theta (the ends are the caller's). */
void aq_sdof_search_interval(const aq_sdof *o, double x, double y, double a0,
                             double a1, double *best);

/* The peak of one component's response, between samples included: best is
 * its peak at the samples, amax the input's. */
double aq_sdof_peak_one(const aq_sdof *o, const double *a, size_t n, size_t nt,
                        const double *x, const double *y, double best,
                        double amax);

/* The peak of one component at PEER's refined samples: best is its peak at
 * the samples, amax the input's; s the oscillator over dt / steps.  An
 * interval is refined only if its bound (the largest |x| it can reach
 * between samples) passes the peak found so far. */
double aq_sdof_peak_refined(const aq_sdof *o, const aq_sdof *s, size_t steps, const double *a,
                            size_t n, size_t nt, const double *x, const double *y,
                            double best, double amax);

/* ---- spectrum_batch.c */

/* The nb (<= AQ_SPECTRUM_BATCH) oscillators o at the samples only, in one
 * pass: their peaks into psa[idx[j]].  Returns 0, the batch's new size. */
size_t aq_spectrum_batch_peaks(const aq_sdof *const *o, const size_t *idx, size_t nb,
                               const double *a, size_t n, double *psa);

/* The nr (<= AQ_SPECTRUM_BATCH) oscillators o at PEER's refined samples
 * (s[j] over dt / steps[j], steps[j] >= 2), in two passes: their peaks
 * into psa[idx[j]].  Returns 0, the batch's new size. */
size_t aq_spectrum_batch_refined(const aq_sdof *const *o, const aq_sdof *const *s,
                                 const size_t *steps, const size_t *idx, size_t nr,
                                 const double *a, size_t n, double amax, double *psa);

#endif
