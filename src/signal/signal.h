/* src/signal: a record made ready for the arch: baseline and filter,
 * intensity measures, spectra and constant-acceleration steps.
 *
 * signal.h: baseline correction, intensity measures and constant-acceleration
 * steps (src/signal).  Input: aq_record (m/s^2, s).  Output: aq_processed
 * (corrected, padded acceleration, m/s^2), aq_im (intensity measures, SI
 * except pga_g) and aq_steps (see steps.h).
 *
 * Ownership: aq_processed owns its array (aq_processed_free).  The filter
 * workspace (aq_signal_ws) is a handle on the process's FFTW plans, made
 * once per transform size and kept until exit (shared read-only between
 * threads once made); aq_signal_ws_free frees the handle and saves the
 * planner's wisdom (filter.c).
 */
#ifndef AQ_SIGNAL_H
#define AQ_SIGNAL_H

#include <stddef.h>

#include "../error.h"
#include "../io/record.h"
#include "spectrum.h"
#include "steps.h"

typedef enum { AQ_DETREND_MEAN = 0, AQ_DETREND_LINEAR, AQ_DETREND_NONE } aq_detrend;

/* Processing options; aq_signal_opts_default() gives the documented defaults. */
typedef struct {
  aq_detrend detrend; /* --detrend (default linear) */
  double taper_frac;  /* --taper: Hann taper length at each end / record length (default 0: none) */
  int filter;         /* 0 with --no-filter (skips taper, pads and filter) */
  double highpass_hz; /* --highpass corner (default AQ_HIGHPASS_DEFAULT_HZ) */
  int highpass_auto;  /* 1 (default, cleared by --highpass): a record shorter
                         than 1/highpass_hz gets the corner 1/duration instead
                         of being refused */
  int order;          /* --order of the Butterworth high-pass (default 4) */
  double lowpass_hz;  /* --lowpass corner, 0 = off (default off) */
  double scale;       /* multiply the processed record by this (default 1) */
  /* The spectral intensity measures aq_im_compute adds (5 % damping):
   * Sa(T) at im_period_s[0..im_nsa) (--im-periods; default 0.2, 0.5, 1 s)
   * and Sa_avg over [sa_avg_lo_s, sa_avg_hi_s] (--sa-avg; default 0.1 to
   * 1 s; lo = 0: none).  All zero: no spectral measure. */
  size_t im_nsa;
#define AQ_IM_SA_MAX 8
  double im_period_s[AQ_IM_SA_MAX];
  double sa_avg_lo_s, sa_avg_hi_s;
  aq_spectrum_peaks peaks; /* --peaks: where their peaks are taken (default
                              PEER's refined samples; spectrum.h) */
} aq_signal_opts;

/* The default high-pass corner, Hz: low enough to keep the long-period
 * content that agencies keep (PEER's corners on the shipped records are
 * 0.03-0.2 Hz; docs/processing.md). */
#define AQ_HIGHPASS_DEFAULT_HZ 0.03

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
  int residual_warn;   /* AQ_IM_WARN_* bits: residuals above PRISM's limits;
                          the caller warns (aq_im_residual_warning), it is not an error */
  double pgv_pga_s;    /* PGV / PGA (m/s over m/s^2), s; NAN for a record of zeros */
  /* Spectral measures, from the options the record was processed with
   * (p->used): PSA at AQ_IM_DAMPING, the peak taken as used.peaks says. */
  size_t n_sa;                       /* = used.im_nsa */
  double sa_period_s[AQ_IM_SA_MAX];  /* s */
  double sa_g[AQ_IM_SA_MAX];         /* Sa(T), g */
  double sa_avg_lo_s, sa_avg_hi_s;   /* the range of Sa_avg, s (0: none) */
  double sa_avg_g; /* Sa_avg: the geometric mean of Sa at AQ_IM_SA_AVG_N
                      periods evenly spaced over the range (Eads et al.
                      2015), g; NAN when there is no range */
} aq_im;

#define AQ_IM_DAMPING 0.05 /* of the spectral measures */
#define AQ_IM_SA_AVG_N 10  /* periods of Sa_avg (Eads et al. 2015: ten) */

/* PRISM's residual limits: warn when |v_end| > 1 cm/s or |d_end| > 1 cm. */
#define AQ_IM_VEND_LIMIT_MPS 0.01
#define AQ_IM_DEND_LIMIT_M 0.01
enum { AQ_IM_WARN_VEND = 1, AQ_IM_WARN_DEND = 2 };

void aq_processed_free(aq_processed *p);

/* Workspace: a handle on the FFTW plans cached per transform size for the
 * whole process (made under a lock, then reused; safe to share between
 * threads).  Free accepts NULL. */
typedef struct aq_signal_ws aq_signal_ws;
aq_signal_ws *aq_signal_ws_alloc(void);
void aq_signal_ws_free(aq_signal_ws *ws);

/* Baseline-correct rec with options o (detrend, taper, pad, filter, scale).
 * Fills *out (caller frees with aq_processed_free).  Errors name rec->path
 * and the option at fault (e.g. "--highpass"). */
aq_status aq_signal_process(const aq_record *rec, const aq_signal_opts *o,
                            aq_signal_ws *ws, aq_processed *out,
                            aq_error *err);

/* Intensity measures of a processed record (all n samples, pads included):
 * PGA (g), PGV (m/s), PGD (m) with trapezoidal integration from rest at the
 * first sample, Arias intensity pi/(2g) int a^2 dt (m/s), D5-95 (s) from the
 * normalised Arias curve with linear interpolation, CAV int |a| dt (m/s),
 * residual end velocity and displacement, residual_warn, PGV/PGA; and the
 * spectral measures p->used asks for (spectrum.h's aq_spectrum_psa, which
 * allocates its workspace here: the only allocation).  Returns AQ_EVALUE
 * (err filled) for an empty record, dt <= 0 or a bad period (field
 * "--im-periods" or "--sa-avg"), AQ_ENOMEM. */
aq_status aq_im_compute(const aq_processed *p, aq_im *im, aq_error *err);

/* The spectral measures of options u, in the order of every table: Sa(T)
 * at each of u->im_period_s, then Sa_avg when u has a range.  Their count;
 * the name of measure k < count ("sa_0.2s_g", "sa_avg_0.1_1s_g"); and its
 * value in im (computed with u), g. */
size_t aq_im_spectral_count(const aq_signal_opts *u);
void aq_im_spectral_name(const aq_signal_opts *u, size_t k, char *buf, size_t n);
double aq_im_spectral_value(const aq_im *im, size_t k);

/* Trapezoidal integration from rest: v[0] = 0, v[k+1] = v[k] + dt (a[k] +
 * a[k+1]) / 2 (m/s from m/s^2), and likewise d from v (m).  v and d hold n
 * values each; d may be NULL.  Any consistent units work (cm/s^2 -> cm/s). */
void aq_signal_integrate(const double *a_mps2, size_t n, double dt_s,
                         double *v_mps, double *d_m);

/* If im->residual_warn is set, write one sentence into buf (no newline, e.g.
 * "residual velocity 0.0231 m/s exceeds 0.01 m/s") and return 1; else
 * return 0 and leave buf empty.  The caller prints it as a warning. */
int aq_im_residual_warning(const aq_im *im, char *buf, size_t n);

/* Constant-acceleration steps of a processed record, pads included: sample i
 * holds over [(i - pad_front) dt, (i - pad_front + 1) dt) s, so the original
 * record starts at t = 0 and the front pad has negative times (zero-order
 * hold).  merge_tol_mps2 as in aq_steps_from_samples (--merge-tol G is
 * G * AQ_G0_MPS2).  Fills *out (caller frees with aq_steps_free). */
aq_status aq_steps_from_processed(const aq_processed *p, double merge_tol_mps2,
                                  aq_steps *out, aq_error *err);

/* The smallest FFT length of the form 2^a or 3 2^a that is >= n (two per
 * octave: a suite's records share few lengths, so few FFTW plans are made;
 * docs/processing.md); 0 if none fits size_t. */
size_t aq_signal_fft_size(size_t n);

/* What the processed samples depend on beyond the record and the options,
 * into buf[n] (one line, for a cache key: src/job/subject_cache.h): FFTW's
 * version, the CPU's SIMD sets among which FFTW's plans choose their
 * codelets (SSE2, AVX, AVX2, FMA, AVX-512), and whether the built-in
 * wisdom is used. */
void aq_signal_fingerprint(char *buf, size_t n);

#endif
