/* filter.h (internal to src/signal): the acausal Butterworth filter applied
 * in the frequency domain with cached FFTW plans.  Public entry points are in
 * signal.h; this header is shared by baseline.c and filter.c only. */
#ifndef AQ_SIGNAL_FILTER_H
#define AQ_SIGNAL_FILTER_H

#include <stddef.h>

#include "../error.h"
#include "signal.h"

/* Zero-phase gain at f_hz >= 0 of the filter described by o:
 *   high-pass |H| = 1/sqrt(1 + (fc/f)^(2n)), times, if o->lowpass_hz > 0,
 *   low-pass  |H| = 1/sqrt(1 + (f/fl)^(2n)); 0 at f = 0. */
double aq_filter_gain(double f_hz, const aq_signal_opts *o);

#define AQ_FILTER_ALIGN 64 /* bytes: at least FFTW's SIMD alignment */

/* An array for aq_filter_apply: room for 2 (n/2 + 1) doubles (the in-place
 * transform's spectrum), aligned to AQ_FILTER_ALIGN, from posix_memalign so
 * that free() releases it.  NULL if out of memory. */
double *aq_filter_alloc(size_t n);

/* Filter x in place: n samples at dt_s, x from aq_filter_alloc(n).  In-place
 * r2c transform, bin k multiplied by aq_filter_gain(k / (n dt)) * factor / n,
 * in-place c2r transform.  Plans come from ws (made once per n, under a
 * process-wide lock: FFTW's planner is not thread-safe); the transforms run
 * on x alone through fftw_execute_dft_r2c/c2r, so several threads may share
 * ws.  ws NULL: a workspace of this call's own (the plans stay cached).  Errors:
 * AQ_ENOMEM, AQ_EINTERNAL (FFTW gave no plan), AQ_EVALUE (n outside
 * [2, INT_MAX]); x is then unchanged or garbage (the caller discards it). */
aq_status aq_filter_apply(aq_signal_ws *ws, double *x, size_t n, double dt_s,
                          const aq_signal_opts *o, double factor,
                          const char *input, aq_error *err);

#endif
