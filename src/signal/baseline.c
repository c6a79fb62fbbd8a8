/* baseline.c: baseline correction of an accelerogram (see signal.h):
 * detrend, optional taper, zero pads with cosine junctions, acausal
 * Butterworth filter, scale.
 *
 * Order of operations (docs/processing.md):
 *   1. detrend the original samples: remove the least-squares line (closed
 *      form; the default), or the mean, or nothing;
 *   2. with --taper FRAC > 0 only: Hann (cosine) taper over FRAC of the
 *      record at each end (default 0: the record itself is not tapered);
 *   3. zero pads: total 1.5 n / fc seconds (n = order, fc = high-pass corner;
 *      Converse & Brady 1992, Boore 2005 BSSA 95(2) 745-750), half before and
 *      half after the record, then more zeros after it up to the next FFT
 *      length 2^a or 3 2^a (few lengths, so a suite plans few: see
 *      docs/processing.md); the pads stay in the processed record (pad_front marks the
 *      original first sample) so that velocity and displacement integrated
 *      from it are consistent with the filtered acceleration (Boore 2005);
 *   4. junctions: the pad samples next to the record take a half-cosine
 *      from the record's end value down to 0 over AQ_JUNCTION_S (or 1/fl
 *      with a low-pass; at most the pad), so the padded series has no step
 *      for the filter to ring on, and no sample of the record is weighted
 *      down;
 *   5. acausal Butterworth high-pass (and optional low-pass) as |H| applied
 *      once in the frequency domain (filter.c);
 *   6. multiply by the scale factor.
 * With filter = 0 (--no-filter) steps 2-5 are skipped and there are no pads.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "filter.h"
#include "signal.h"

/* Converse & Brady (1992) / Boore (2005): total pad length = this * n / fc. */
#define AQ_PAD_FACTOR 1.5
/* Junction length, s: the half-cosine that joins each end of the record to
 * its zero pad lasts this long, or one period of the low-pass corner if
 * that is longer (a step would ring at the low-pass corner).  0.1 s changes
 * the PGV of the shipped PEER records by at most 0.3 %; 1/fc (33 s) would
 * add up to 24 % (IELC180 starts at -6.4 mg; docs/processing.md). */
#define AQ_JUNCTION_S 0.1
#define AQ_ORDER_MAX 64 /* beyond this the response is a brick wall anyway */

void aq_signal_opts_default(aq_signal_opts *o)
{
  o->detrend = AQ_DETREND_LINEAR;
  o->taper_frac = 0;
  o->filter = 1;
  o->highpass_hz = AQ_HIGHPASS_DEFAULT_HZ;
  o->highpass_auto = 1;
  o->order = 4;
  o->lowpass_hz = 0;
  o->scale = 1.0;
  static const double im_periods_s[] = {0.2, 0.5, 1.0};
  o->im_nsa = sizeof im_periods_s / sizeof *im_periods_s;
  for (size_t i = 0; i < AQ_IM_SA_MAX; i++)
    o->im_period_s[i] = i < o->im_nsa ? im_periods_s[i] : 0;
  o->sa_avg_lo_s = 0.1;
  o->sa_avg_hi_s = 1.0;
  o->peaks = AQ_SPECTRUM_PEAKS_PEER;
}

void aq_processed_free(aq_processed *p)
{
  if (!p)
    return;
  free(p->acc_mps2);
  memset(p, 0, sizeof *p);
}

size_t aq_signal_fft_size(size_t n)
{
  /* in increasing order: 1, 2, 3, 4, 6, 8, 12, ... (2^a, then 3 2^(a-1)) */
  for (size_t m = 1;; m *= 2) {
    if (m >= n)
      return m;
    if (m >= 2 && m / 2 * 3 >= n)
      return m / 2 * 3;
    if (m > SIZE_MAX / 2)
      return 0;
  }
}

/* Check the options against the record (dt, length). */
static aq_status check_opts(const aq_record *rec, const aq_signal_opts *o,
                            aq_error *err)
{
  const char *in = rec->path;
  if (o->detrend != AQ_DETREND_MEAN && o->detrend != AQ_DETREND_LINEAR &&
      o->detrend != AQ_DETREND_NONE)
    return aq_error_set(err, AQ_EVALUE, in, -1, -1, "--detrend",
                        "expected mean, linear or none, got code %d",
                        (int)o->detrend);
  if (!isfinite(o->scale))
    return aq_error_set(err, AQ_EVALUE, in, -1, -1, "scale",
                        "expected a finite factor, got %g", o->scale);
  if (!(rec->dt_s > 0) || !isfinite(rec->dt_s))
    return aq_error_set(err, AQ_EVALUE, in, -1, -1, "dt",
                        "expected a finite sample interval > 0 s, got %g",
                        rec->dt_s);
  if (rec->npts < 1 || !rec->acc_mps2)
    return aq_error_set(err, AQ_EVALUE, in, -1, -1, "npts",
                        "expected at least 1 sample, got %zu", rec->npts);
  if (!o->filter)
    return AQ_OK;
  double nyq_hz = 0.5 / rec->dt_s;
  if (!(o->taper_frac >= 0 && o->taper_frac <= 0.5))
    return aq_error_set(err, AQ_EVALUE, in, -1, -1, "--taper",
                        "expected a fraction of the record in [0, 0.5] at "
                        "each end, got %g",
                        o->taper_frac);
  if (o->order < 1 || o->order > AQ_ORDER_MAX)
    return aq_error_set(err, AQ_EVALUE, in, -1, -1, "--order",
                        "expected a filter order in [1, %d], got %d",
                        AQ_ORDER_MAX, o->order);
  if (!(o->highpass_hz > 0) || !(o->highpass_hz < nyq_hz))
    return aq_error_set(err, AQ_EVALUE, in, -1, -1, "--highpass",
                        "expected a corner > 0 Hz and below the Nyquist "
                        "frequency %g Hz (dt = %g s), got %g Hz",
                        nyq_hz, rec->dt_s, o->highpass_hz);
  if (o->lowpass_hz != 0) {
    if (!(o->lowpass_hz > o->highpass_hz))
      return aq_error_set(err, AQ_EVALUE, in, -1, -1, "--lowpass",
                          "expected a corner above the high-pass corner %g "
                          "Hz, got %g Hz",
                          o->highpass_hz, o->lowpass_hz);
    if (!(o->lowpass_hz < nyq_hz))
      return aq_error_set(err, AQ_EVALUE, in, -1, -1, "--lowpass",
                          "expected a corner below the Nyquist frequency %g "
                          "Hz (dt = %g s), got %g Hz",
                          nyq_hz, rec->dt_s, o->lowpass_hz);
  }
  /* a high-pass corner whose period exceeds the record cannot be resolved */
  double dur_s = (double)rec->npts * rec->dt_s, need_s = 1.0 / o->highpass_hz;
  if (dur_s < need_s)
    return aq_error_set(err, AQ_EVALUE, in, -1, -1, "--highpass",
                        "expected a record of at least %g s (1/fc for a %g Hz "
                        "corner), got %g s (%zu samples at %g s); raise "
                        "--highpass or use --no-filter",
                        need_s, o->highpass_hz, dur_s, rec->npts, rec->dt_s);
  return AQ_OK;
}

/* Remove the mean, or the least-squares line a + b i against the sample
 * index (times scale out), or nothing.  The line in closed form, two passes,
 * no allocation: with c = (n - 1)/2 (the mean index), b = sum (i - c) y_i /
 * S with S = sum (i - c)^2 = n (n^2 - 1) / 12, and a + b i = mean + b (i - c). */
static aq_status detrend(double *y, size_t n, aq_detrend how, const char *in,
                         aq_error *err)
{
  if (how == AQ_DETREND_NONE)
    return AQ_OK;
  double mean = 0;
  for (size_t i = 0; i < n; i++)
    mean += y[i];
  mean /= (double)n;
  double b = 0, c = 0.5 * ((double)n - 1.0);
  if (how == AQ_DETREND_LINEAR && n >= 2) {
    double dn = (double)n, sxy = 0;
    for (size_t i = 0; i < n; i++)
      sxy += ((double)i - c) * (y[i] - mean);
    b = sxy / (dn * (dn * dn - 1.0) / 12.0);
    if (!isfinite(b))
      return aq_error_set(err, AQ_ENUMERIC, in, -1, -1, "--detrend",
                          "expected a finite least-squares slope, got %g", b);
  }
  for (size_t i = 0; i < n; i++)
    y[i] -= mean + b * ((double)i - c);
  return AQ_OK;
}

/* Hann taper over m = round(frac n) samples at each end: the weight rises
 * from 0 at the end sample as (1 - cos(pi k / m)) / 2, k = 0..m-1. */
static void taper(double *y, size_t n, double frac)
{
  size_t m = (size_t)floor(frac * (double)n + 0.5);
  if (m > n / 2)
    m = n / 2;
  for (size_t k = 0; k < m; k++) {
    double w = 0.5 * (1.0 - cos(AQ_PI * (double)k / (double)m));
    y[k] *= w;
    y[n - 1 - k] *= w;
  }
}

/* Half-cosine junctions in the pads: the m pad samples before y[0] rise
 * from 0 to y[0] as (1 - cos(pi k / m)) / 2 (k = 1..m counted from the far
 * end), likewise after y[n-1]; the record's own samples are untouched. */
static void junctions(double *y, size_t n, size_t m_front, size_t m_back)
{
  for (size_t k = 1; k <= m_front; k++)
    y[-(ptrdiff_t)k] =
        y[0] * 0.5 * (1.0 + cos(AQ_PI * (double)k / (double)(m_front + 1)));
  for (size_t k = 1; k <= m_back; k++)
    y[n - 1 + k] =
        y[n - 1] * 0.5 * (1.0 + cos(AQ_PI * (double)k / (double)(m_back + 1)));
}

aq_status aq_signal_process(const aq_record *rec, const aq_signal_opts *opts,
                            aq_signal_ws *ws, aq_processed *out,
                            aq_error *err)
{
  memset(out, 0, sizeof *out);
  /* the default corner rises to 1/duration on a record shorter than its
   * period (an explicit --highpass is checked as given) */
  aq_signal_opts use = *opts;
  const aq_signal_opts *o = &use;
  double dur_s = (double)rec->npts * rec->dt_s;
  if (use.filter && use.highpass_auto && dur_s > 0 && isfinite(dur_s) &&
      use.highpass_hz > 0 && dur_s < 1.0 / use.highpass_hz) {
    use.highpass_hz = 1.0 / dur_s;
    while (dur_s < 1.0 / use.highpass_hz) /* at most a few ulps */
      use.highpass_hz = nextafter(use.highpass_hz, INFINITY);
  }
  aq_status st = check_opts(rec, o, err);
  if (st != AQ_OK)
    return st;
  const char *in = rec->path;
  size_t n = rec->npts;

  size_t front = 0, ntot = n;
  if (o->filter) {
    double pad_s = AQ_PAD_FACTOR * (double)o->order / o->highpass_hz;
    double pad_n = ceil(pad_s / rec->dt_s);
    if (!(pad_n < 1e9)) /* > 1e9 pad samples: far beyond any record */
      return aq_error_set(err, AQ_EVALUE, in, -1, -1, "--highpass",
                          "expected pads of at most 1e9 samples, got %g "
                          "(1.5 n / fc = %g s at dt = %g s)",
                          pad_n, pad_s, rec->dt_s);
    front = ((size_t)pad_n + 1) / 2;
    ntot = aq_signal_fft_size(n + 2 * front);
    if (ntot == 0)
      return aq_error_set(err, AQ_EVALUE, in, -1, -1, "npts",
                          "expected a record that fits an FFT, got %zu "
                          "samples", n);
  }
  /* filtered: the array is also the in-place FFT buffer (aligned, room for
   * the spectrum); free() releases either kind */
  double *a = o->filter ? aq_filter_alloc(ntot) : malloc(ntot * sizeof *a);
  if (!a)
    return aq_error_set(err, AQ_ENOMEM, in, -1, -1, "npts",
                        "cannot allocate %zu samples", ntot);
  double *y = a + front;
  for (size_t i = 0; i < n; i++) {
    y[i] = rec->acc_mps2[i];
    if (!isfinite(y[i])) {
      aq_error_set(err, AQ_EVALUE, in, -1, -1, "sample",
                   "sample %zu: expected a finite acceleration, got %g", i,
                   y[i]);
      free(a);
      return AQ_EVALUE;
    }
  }
  if (front)
    memset(a, 0, front * sizeof *a);
  if (ntot > front + n)
    memset(y + n, 0, (ntot - front - n) * sizeof *a);
  st = detrend(y, n, o->detrend, in, err);
  if (st == AQ_OK && o->filter) {
    taper(y, n, o->taper_frac);
    double junction_s = AQ_JUNCTION_S;
    if (o->lowpass_hz > 0 && 1.0 / o->lowpass_hz > junction_s)
      junction_s = 1.0 / o->lowpass_hz;
    size_t m = (size_t)ceil(junction_s / rec->dt_s);
    size_t back = ntot - front - n;
    junctions(y, n, m < front ? m : front, m < back ? m : back);
    st = aq_filter_apply(ws, a, ntot, rec->dt_s, o, o->scale, in, err);
  } else if (st == AQ_OK && o->scale != 1.0) {
    for (size_t i = 0; i < ntot; i++)
      a[i] *= o->scale;
  }
  if (st != AQ_OK) {
    free(a);
    return st;
  }
  out->n = ntot;
  out->dt_s = rec->dt_s;
  out->pad_front = front;
  out->pad_back = ntot - n - front;
  out->n_orig = n;
  out->acc_mps2 = a;
  out->used = *o;
  return AQ_OK;
}

aq_status aq_steps_from_processed(const aq_processed *p, double merge_tol_mps2,
                                  aq_steps *out, aq_error *err)
{
  memset(out, 0, sizeof *out);
  if (!p || !p->acc_mps2 || p->n == 0)
    return aq_error_set(err, AQ_EVALUE, NULL, -1, -1, "npts",
                        "expected a processed record with samples, got none");
  return aq_steps_from_samples(p->acc_mps2, p->n, p->dt_s,
                               -(double)p->pad_front * p->dt_s, merge_tol_mps2,
                               out, err);
}
