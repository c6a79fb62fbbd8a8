/* signal.h: baseline correction, intensity measures and constant-acceleration
 * steps (src/signal).  Input: aq_record (m/s^2, s).  Output: aq_processed
 * (corrected, padded acceleration, m/s^2), aq_im (intensity measures, SI
 * except pga_g) and aq_steps (see steps.h).
 *
 * Ownership: aq_processed owns its array (aq_processed_free).  The filter
 * workspace (aq_signal_ws) holds FFTW plans made once per transform size and
 * is shared read-only between threads once made; aq_signal_ws_free frees it.
 */
#ifndef AQ_SIGNAL_H
#define AQ_SIGNAL_H

#include <stddef.h>

#include "../error.h"
#include "../io/record.h"

typedef enum { AQ_DETREND_MEAN = 0, AQ_DETREND_LINEAR, AQ_DETREND_NONE } aq_detrend;

/* Processing options; aq_signal_opts_default() gives the documented defaults. */
typedef struct {
  aq_detrend detrend; /* --detrend (default mean) */
  double taper_frac;  /* --taper: Hann taper length at each end / record length (default 0.05) */
  int filter;         /* 0 with --no-filter (skips taper and filter) */
  double highpass_hz; /* --highpass corner (default 0.05 Hz) */
  int order;          /* --order of the Butterworth high-pass (default 4) */
  double lowpass_hz;  /* --lowpass corner, 0 = off (default off) */
  double scale;       /* multiply the processed record by this (default 1) */
} aq_signal_opts;

void aq_signal_opts_default(aq_signal_opts *o);

/* A processed record: the corrected acceleration with its pads. */
typedef struct {
  size_t n;             /* samples, pads included */
  double dt_s;          /* sample interval, s */
  size_t pad_front;     /* zero-pad samples before the original record */
  size_t pad_back;      /* zero-pad samples after it */
  size_t n_orig;        /* samples of the original record (= n - pads) */
  double *acc_mps2;     /* n samples, m/s^2; sample pad_front is the record's first sample (t = 0) */
  aq_signal_opts used;  /* the options actually applied */
} aq_processed;

/* Intensity measures of a processed record (pads included: they are at rest). */
typedef struct {
  double pga_g;        /* max |a|, g */
  double pgv_mps;      /* max |v|, m/s, trapezoidal integration */
  double pgd_m;        /* max |d|, m */
  double arias_mps;    /* pi/(2g) * int a^2 dt, m/s */
  double d5_95_s;      /* significant duration, s */
  double cav_mps;      /* int |a| dt, m/s */
  double v_end_mps;    /* residual velocity at the end, m/s */
  double d_end_m;      /* residual displacement at the end, m */
} aq_im;

void aq_processed_free(aq_processed *p);

/* Workspace: FFTW plans cached per transform size (made under a lock, then
 * reused; safe to share between threads).  Free accepts NULL. */
typedef struct aq_signal_ws aq_signal_ws;
aq_signal_ws *aq_signal_ws_alloc(void);
void aq_signal_ws_free(aq_signal_ws *ws);

/* Baseline-correct rec with options o (detrend, taper, pad, filter, scale).
 * Fills *out (caller frees with aq_processed_free).  Errors name rec->path
 * and the option at fault (e.g. "--highpass"). */
aq_status aq_signal_process(const aq_record *rec, const aq_signal_opts *o,
                            aq_signal_ws *ws, aq_processed *out,
                            aq_error *err);

/* Intensity measures of a processed record. */
aq_status aq_im_compute(const aq_processed *p, aq_im *im, aq_error *err);

#endif
