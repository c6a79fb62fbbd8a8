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

/* Filter x (n samples at dt_s, in place): r2c transform, multiply bin k by
 * aq_filter_gain(k / (n dt)) / n, c2r transform.  Plans come from ws (made
 * once per n, under a lock); the transform buffers are fftw_malloc'd per
 * call, so several threads may share ws.  ws NULL: a temporary one.  Errors: AQ_ENOMEM, AQ_EINTERNAL
 * (FFTW gave no plan), AQ_EVALUE (n too large for FFTW). */
aq_status aq_filter_apply(aq_signal_ws *ws, double *x, size_t n, double dt_s,
                          const aq_signal_opts *o, const char *input,
                          aq_error *err);

#endif
