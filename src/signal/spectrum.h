/* spectrum.h: elastic response spectra of accelerograms (src/signal).
 *
 * Input: ground acceleration samples (m/s^2) at a constant interval dt_s (s),
 * taken as linear between samples.  Output: pseudo-spectral acceleration
 * PSA(T, zeta) = omega^2 max_t |u(t)| (m/s^2), omega = 2 pi / T, of the
 * linear oscillator u'' + 2 zeta omega u' + omega^2 u = -a(t) at rest at the
 * first sample; for two horizontal components, the peak of every rotated
 * oscillator (angles 0 to 180 degrees), RotD50, RotD100 and the geometric
 * mean.  Spectral displacement is PSA / omega^2 (m).
 *
 * Ownership: the caller owns every array passed in and out.  The workspace
 * (aq_spectrum_ws) holds the response histories of one call; make it once per
 * thread and reuse it (aq_spectrum_ws_free frees it; free accepts NULL).
 * Functions never print: errors fill the aq_error and return a status.
 *
 * Accuracy: the response at the samples is the exact solution for the input
 * linear between samples (Nigam & Jennings 1969), as a transition matrix
 * (sdof.c).  The peak between samples is found wherever it could exceed
 * the peak at the samples (a rigorous bound per interval decides), as the
 * zero of the velocity inside the interval, to rounding: the PSA returned is
 * the true peak of the piecewise-linear input's response within
 * AQ_SPECTRUM_PEAK_REL (relative; the bound is stated in sdof.c).
 * The peak is taken there (aq_spectrum_peaks EXACT), at the samples
 * (SAMPLES), or, by default, at the samples refined as PEER refines them
 * for the NGA-West2 spectra (PEER).
 * docs/spectrum.md explains the method and lists the checks.
 */
#ifndef AQ_SIGNAL_SPECTRUM_H
#define AQ_SIGNAL_SPECTRUM_H

#include <stddef.h>

#include "../error.h"

/* Relative error bound of a returned peak against the exact peak of the
 * response to the piecewise-linear input (rounding of the root search and
 * of the transition matrix; the recurrence's own rounding, about 1e-15 per
 * step, adds to it). */
#define AQ_SPECTRUM_PEAK_REL 1e-12

/* Rotation angles of RotD: n_angles over [0, 180) degrees, step 180/n_angles;
 * the default, 180, is Boore's (2010) 1 degree. */
#define AQ_SPECTRUM_ANGLES_DEFAULT 180

/* PEER's 111 periods of the NGA-West2 flatfile, 0.01 to 20 s (s). */
#define AQ_SPECTRUM_PEER_N 111
extern const double aq_spectrum_peer_periods_s[AQ_SPECTRUM_PEER_N];

/* Where a peak is taken (--peaks; docs/spectrum.md):
 *   PEER (the default): as PEER computes the NGA-West2 database's spectra:
 *     every sample interval cut into N = ceil(10 dt / T) equal steps (N = 1
 *     when dt <= T / 10; a ratio within AQ_SPECTRUM_PEER_RATIO_TOL of a
 *     whole number is that number), the acceleration linear between
 *     samples, the peak at the samples and at those N - 1 points between
 *     them (the exact response there, so the same as the piecewise-linear
 *     recursion at dt / N);
 *   EXACT: the peak over continuous time (within AQ_SPECTRUM_PEAK_REL);
 *   SAMPLES: the peak at the samples only (lower than EXACT by up to
 *     1 - cos(pi dt / T)).
 * All three take the same response; they differ only below T = 10 dt for
 * PEER and SAMPLES, and at every period for EXACT. */
typedef enum {
  AQ_SPECTRUM_PEAKS_PEER = 0,
  AQ_SPECTRUM_PEAKS_EXACT,
  AQ_SPECTRUM_PEAKS_SAMPLES
} aq_spectrum_peaks;

/* Their names, as --peaks takes them and the results file stores them:
 * "peer", "exact", "samples", then NULL. */
extern const char *const aq_spectrum_peaks_names[];

/* The rule of a name among aq_spectrum_peaks_names (and "continuous", the
 * name files written before --peaks gave EXACT), or -1. */
int aq_spectrum_peaks_parse(const char *name);

/* One line saying what a rule does, for the TSV's comment and the report
 * ("peaks at the samples and at N - 1 points between them, N = ceil(10 dt
 * / T) (PEER NGA-West2)"); never NULL. */
const char *aq_spectrum_peaks_text(aq_spectrum_peaks peaks);

/* Relative distance from a whole number within which PEER's ratio 10 dt / T
 * is taken as that number: dt and T are decimal fractions whose binary
 * quotient can miss a whole ratio (10 x 0.007 / 0.01 = 7.000000000000001),
 * and a dt read from a binary float (SAC's DELTA: 0.001 is stored as
 * 0.0010000000474974513, 4.7e-8 above) misses it by the float's rounding,
 * 6e-8; either would add a step.  1e-6 is above both, and below the
 * distance of any ratio of decimals printed to 6 digits from a whole one. */
#define AQ_SPECTRUM_PEER_RATIO_TOL 1e-6

/* The most steps per interval the PEER rule is asked for: a period below
 * 10 dt / AQ_SPECTRUM_PEER_STEPS_MAX (dt / 1000) is refused under it (its
 * cost grows as 1/T, and its PSA is the PGA's to rounding long before). */
#define AQ_SPECTRUM_PEER_STEPS_MAX 10000

/* N of the PEER rule for a period_s > 0 and dt_s > 0: ceil(10 dt / T) with
 * the tolerance above, at least 1; 0 if it would pass
 * AQ_SPECTRUM_PEER_STEPS_MAX. */
size_t aq_spectrum_peer_steps(double dt_s, double period_s);

/* Options of a spectrum; aq_spectrum_opts_default() sets the defaults. */
typedef struct {
  size_t n_angles; /* RotD angles over [0, 180) degrees (default 180: 1 degree) */
  aq_spectrum_peaks peaks; /* where a peak is taken (default PEER) */
  int one_at_a_time; /* 0 (the default): one component's periods under
                        SAMPLES and PEER run several at a time, and RotD's
                        two components in one loop; 1:
                        each period and component on its own, as before
                        they did (the same values to the bit; slower: for
                        benches and tests) */
} aq_spectrum_opts;

void aq_spectrum_opts_default(aq_spectrum_opts *o);

typedef struct aq_spectrum_ws aq_spectrum_ws;
aq_spectrum_ws *aq_spectrum_ws_alloc(void);
void aq_spectrum_ws_free(aq_spectrum_ws *ws);

/* PSA of one component.  acc_mps2: n samples (m/s^2, finite) at dt_s (s,
 * > 0); damping: the ratio zeta, 0 < zeta < 1; period_s[i] >= 0 (s): 0
 * gives the limit T -> 0, the peak |a| of the input (PGA).  Fills
 * psa_mps2[i] (m/s^2) for each of the n_periods.  opts NULL: defaults.
 * Returns AQ_OK, AQ_EVALUE (a bad argument, the field names it: "period_s",
 * "damping", "dt", "npts", "samples", "peaks"; under PEER a period > 0
 * below dt / 1000, see AQ_SPECTRUM_PEER_STEPS_MAX) or AQ_ENOMEM; err
 * filled. */
aq_status aq_spectrum_psa(aq_spectrum_ws *ws, const aq_spectrum_opts *opts,
                          const double *acc_mps2, size_t n, double dt_s,
                          double damping, const double *period_s,
                          size_t n_periods, double *psa_mps2, aq_error *err);

/* The response history of one oscillator (period_s > 0) at the n samples:
 * u_m[k] = u(t_k), m, and v_mps[k] = u'(t_k), m/s (both n values, caller's
 * arrays).  Errors as aq_spectrum_psa. */
aq_status aq_spectrum_response(const double *acc_mps2, size_t n, double dt_s,
                               double damping, double period_s, double *u_m,
                               double *v_mps, aq_error *err);

/* Spectra of two horizontal components at one period. */
typedef struct {
  double psa1_mps2;    /* component 1 (the rotation's angle 0), m/s^2 */
  double psa2_mps2;    /* component 2 (angle 90 degrees), m/s^2 */
  double geomean_mps2; /* sqrt(psa1 psa2), m/s^2 */
  double rotd50_mps2;  /* median over the angles of each rotated oscillator's
                          peak (Boore 2010), m/s^2 */
  double rotd100_mps2; /* largest of them, m/s^2 */
} aq_rotd;

/* RotD of two components sampled alike: acc1_mps2 (n1 samples) and
 * acc2_mps2 (n2) at dt_s; the shorter is taken as zero after its end.  The
 * rotated oscillator at angle theta is driven by a1 cos(theta) + a2
 * sin(theta) (its response is the same combination of the two responses,
 * the oscillator being linear), and its peak over time is found as for one
 * component.  RotD50 of an even number of angles is the mean of the two
 * middle peaks.  Fills out[i] for each period; angle_peaks_mps2 (NULL, or
 * n_periods * opts->n_angles values) receives the peak at each angle,
 * period-major.  Errors as aq_spectrum_psa, and "n_angles" (>= 2, even). */
aq_status aq_spectrum_rotd(aq_spectrum_ws *ws, const aq_spectrum_opts *opts,
                           const double *acc1_mps2, size_t n1,
                           const double *acc2_mps2, size_t n2, double dt_s,
                           double damping, const double *period_s,
                           size_t n_periods, aq_rotd *out,
                           double *angle_peaks_mps2, aq_error *err);

/* Sa_avg: the geometric mean of PSA at n_avg periods spaced evenly from
 * t_lo_s to t_hi_s inclusive (Eads et al. 2015), here computed by the
 * caller's spectrum: fills periods_s[0..n_avg) (s).  n_avg >= 2,
 * 0 < t_lo_s < t_hi_s.  Returns AQ_OK or AQ_EVALUE. */
aq_status aq_spectrum_avg_periods(double t_lo_s, double t_hi_s, size_t n_avg,
                                  double *periods_s, aq_error *err);

/* The geometric mean of n values (> 0); 0 if any is 0. */
double aq_spectrum_geomean(const double *v, size_t n);

#endif
