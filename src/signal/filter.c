/* filter.c: acausal (zero-phase) Butterworth filtering in the frequency
 * domain with FFTW, and the plan cache behind aq_signal_ws.
 *
 * The filter multiplies the spectrum once by the real magnitude response
 * |H(f)| of a Butterworth filter of order n (no phase: acausal), as Boore
 * (2005, BSSA 95(2) 745-750) and PEER's processing do with time-domain
 * forward+backward passes, except that |H| is applied exactly here, not |H|^2.
 *
 * Threads: FFTW's planner is not thread-safe, so every planner call (create
 * and destroy) holds one process-wide mutex.  Plans are made with
 * FFTW_ESTIMATE (no timing measurements: the same plan, hence bit-identical
 * results, on every run) and executed with fftw_execute_dft_r2c/c2r on
 * buffers from fftw_malloc, which is the thread-safe part of FFTW's API.
 */
#include "filter.h"

#include <fftw3.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

/* FFTW's planner is global to the process: one lock for every workspace. */
static pthread_mutex_t aq_fftw_planner_lock = PTHREAD_MUTEX_INITIALIZER;

typedef struct {
  size_t n;       /* transform length */
  fftw_plan r2c;  /* n reals -> n/2+1 complex */
  fftw_plan c2r;  /* n/2+1 complex -> n reals (destroys its input) */
} plan_pair;

struct aq_signal_ws {
  plan_pair *plans; /* cache, guarded by aq_fftw_planner_lock */
  size_t nplans, cap;
};

aq_signal_ws *aq_signal_ws_alloc(void)
{
  return calloc(1, sizeof(aq_signal_ws));
}

void aq_signal_ws_free(aq_signal_ws *ws)
{
  if (!ws)
    return;
  pthread_mutex_lock(&aq_fftw_planner_lock);
  for (size_t i = 0; i < ws->nplans; i++) {
    fftw_destroy_plan(ws->plans[i].r2c);
    fftw_destroy_plan(ws->plans[i].c2r);
  }
  pthread_mutex_unlock(&aq_fftw_planner_lock);
  free(ws->plans);
  free(ws);
}

/* Find or make the plans for length n.  Caller holds the planner lock. */
static const plan_pair *plans_for(aq_signal_ws *ws, size_t n)
{
  for (size_t i = 0; i < ws->nplans; i++)
    if (ws->plans[i].n == n)
      return &ws->plans[i];
  if (ws->nplans == ws->cap) {
    size_t cap = ws->cap ? 2 * ws->cap : 8;
    plan_pair *p = realloc(ws->plans, cap * sizeof *p);
    if (!p)
      return NULL;
    ws->plans = p;
    ws->cap = cap;
  }
  /* plan on scratch arrays of the alignment fftw_malloc gives, which is the
   * alignment of every buffer later passed to the new-array execute calls */
  double *x = fftw_malloc(n * sizeof *x);
  fftw_complex *X = fftw_malloc((n / 2 + 1) * sizeof *X);
  fftw_plan r2c = NULL, c2r = NULL;
  if (x && X) {
    r2c = fftw_plan_dft_r2c_1d((int)n, x, X, FFTW_ESTIMATE);
    c2r = fftw_plan_dft_c2r_1d((int)n, X, x, FFTW_ESTIMATE);
  }
  fftw_free(x);
  fftw_free(X);
  if (!r2c || !c2r) {
    if (r2c)
      fftw_destroy_plan(r2c);
    if (c2r)
      fftw_destroy_plan(c2r);
    return NULL;
  }
  plan_pair *pp = &ws->plans[ws->nplans++];
  pp->n = n;
  pp->r2c = r2c;
  pp->c2r = c2r;
  return pp;
}

/* x^k for integer k >= 1 by repeated squaring (cheaper than pow per bin). */
static double ipow(double x, int k)
{
  double r = 1.0;
  while (k > 0) {
    if (k & 1)
      r *= x;
    x *= x;
    k >>= 1;
  }
  return r;
}

double aq_filter_gain(double f_hz, const aq_signal_opts *o)
{
  if (!(f_hz > 0))
    return 0.0;
  double r = o->highpass_hz / f_hz;
  double g = 1.0 / sqrt(1.0 + ipow(r * r, o->order));
  if (o->lowpass_hz > 0) {
    double q = f_hz / o->lowpass_hz;
    g /= sqrt(1.0 + ipow(q * q, o->order));
  }
  return g;
}

aq_status aq_filter_apply(aq_signal_ws *ws, double *x, size_t n, double dt_s,
                          const aq_signal_opts *o, const char *input,
                          aq_error *err)
{
  if (n < 2 || n > (size_t)INT_MAX)
    return aq_error_set(err, AQ_EVALUE, input, -1, -1, "--highpass",
                        "expected a padded length in [2, %d] samples for the "
                        "FFT, got %zu",
                        INT_MAX, n);
  aq_signal_ws *own = NULL;
  if (!ws && !(ws = own = aq_signal_ws_alloc()))
    return aq_error_set(err, AQ_ENOMEM, input, -1, -1, "fft",
                        "cannot allocate the FFT workspace");
  pthread_mutex_lock(&aq_fftw_planner_lock);
  const plan_pair *pp = plans_for(ws, n);
  fftw_plan r2c = pp ? pp->r2c : NULL, c2r = pp ? pp->c2r : NULL;
  pthread_mutex_unlock(&aq_fftw_planner_lock);
  if (!pp) {
    aq_signal_ws_free(own);
    return aq_error_set(err, AQ_EINTERNAL, input, -1, -1, "fft",
                        "cannot make FFTW plans for %zu points", n);
  }

  size_t nc = n / 2 + 1;
  double *buf = fftw_malloc(n * sizeof *buf);
  fftw_complex *spec = fftw_malloc(nc * sizeof *spec);
  if (!buf || !spec) {
    fftw_free(buf);
    fftw_free(spec);
    aq_signal_ws_free(own);
    return aq_error_set(err, AQ_ENOMEM, input, -1, -1, "fft",
                        "cannot allocate FFT buffers of %zu points", n);
  }
  for (size_t i = 0; i < n; i++)
    buf[i] = x[i];
  fftw_execute_dft_r2c(r2c, buf, spec);
  /* bin k is frequency k / (n dt); 1/n undoes FFTW's unnormalised pair */
  double df_hz = 1.0 / ((double)n * dt_s), inv_n = 1.0 / (double)n;
  for (size_t k = 0; k < nc; k++) {
    double g = aq_filter_gain((double)k * df_hz, o) * inv_n;
    spec[k][0] *= g;
    spec[k][1] *= g;
  }
  fftw_execute_dft_c2r(c2r, spec, buf);
  for (size_t i = 0; i < n; i++)
    x[i] = buf[i];
  fftw_free(buf);
  fftw_free(spec);
  aq_signal_ws_free(own);
  return AQ_OK;
}
