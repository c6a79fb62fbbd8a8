/* same.h: which members of a pool are one recording (src/select;
 * docs/select.md, "One recording twice").
 *
 * The same accelerogram reaches a pool in several processings (an agency's
 * older and newer corrections, a textbook's digitisation, one file in two
 * formats).  Their spectra differ (other filters, other trims) and their
 * files may spell the event, the station and the channel differently, but
 * the accelerations are one signal: the peak over lags of their normalised
 * cross-correlation is near 1, where two components of one station or two
 * stations of one event stay far below (measured in docs/select.md).
 *
 * A member's trace: its processed acceleration over the record's own span
 * (pads left out) as the mean over consecutive windows of AQ_SAME_STEP_S,
 * from the running integral interpolated linearly (a box filter and a
 * common sampling for records of any step).  Two traces x, y compare by
 *     rho = max over lags tau of |sum_t x(t) y(t + tau)| / sqrt(sum x^2 sum y^2),
 * (the absolute value: a component written with the opposite sign, 180 and
 * 000, is the same recording), computed by FFT (GSL's radix-2 real
 * transforms, no shared state).  Members are the same recording when some
 * trace of one and some trace of the other (a pair brings two) reach
 * AQ_SAME_RHO_MIN; the relation is closed over chains (a group).
 *
 * Units: s, m/s^2; rho is a ratio.  Nothing prints. */
#ifndef AQ_SELECT_SAME_H
#define AQ_SELECT_SAME_H

#include <stddef.h>

#include "../error.h"

/* The traces' common step, s (a box mean: content above about 20 Hz is
 * averaged away, below it kept). */
#define AQ_SAME_STEP_S 0.02
/* The peak normalised cross-correlation from which two traces are one
 * recording (docs/select.md, measured on the shared records: one recording
 * in two processings 0.959, two components of one station at most 0.45,
 * two stations of one event at most 0.21, records of other events at most
 * 0.48). */
#define AQ_SAME_RHO_MIN 0.8

typedef struct {
  double *x; /* n samples at AQ_SAME_STEP_S */
  size_t n;
} aq_same_trace;

/* The trace of acc[0..n) at dt_s (n >= 1, dt_s > 0) into *t (t->x malloc'd;
 * aq_same_trace_free).  AQ_OK or AQ_ENOMEM. */
aq_status aq_same_trace_make(const double *acc_mps2, size_t n, double dt_s, aq_same_trace *t,
                             aq_error *err);
void aq_same_trace_free(aq_same_trace *t);

/* rho of traces a and b (0 when either is all zeros or empty); *lag_s (if
 * not NULL) the lag of the peak, s (b later than a: > 0).  Returns -1 when
 * out of memory. */
double aq_same_rho(const aq_same_trace *a, const aq_same_trace *b, double *lag_s);

/* The first pass: the traces' means over AQ_SAME_COARSE_STEPS windows (0.1
 * s), whose rho (25 times cheaper) must reach AQ_SAME_RHO_COARSE for the
 * traces to be compared at their own step (docs/select.md: one recording in
 * two processings 0.903 at 0.1 s, records of other events at most 0.51). */
#define AQ_SAME_COARSE_STEPS 5
#define AQ_SAME_RHO_COARSE 0.6

/* The cheap test before the correlation: two members are compared only
 * when their spectra at the grid and at T = 0 (pool.h) are within this
 * factor of each other at every period (docs/select.md: one recording in
 * two processings within 1.23 on the shared records). */
#define AQ_SAME_SPECTRUM_RATIO_MAX 2.0

/* Two members taken as one recording, and by how much. */
typedef struct {
  size_t i, j; /* i < j, members */
  double rho;  /* the largest rho between their traces */
} aq_same_pair;

/* The members 0..m-1, member i with its traces tr[2 i] and tr[2 i + 1]
 * (n 0: none), its spectrum psa_mps2[i nper .. i nper + nper) and
 * psa0_mps2[i] (NULL: every two compared), compared two by two (on threads)
 * where their spectra are within AQ_SAME_SPECTRUM_RATIO_MAX of each other
 * (*compared: how many two by two were correlated): group[i] (m) the group of
 * members that are one recording, numbered 0.. in order of their first
 * member, -1 for a member alone; *pairs (malloc'd, *npairs, in order of i
 * then j) every two members whose rho reaches rho_min; *ngroups.  AQ_OK or
 * AQ_ENOMEM. */
aq_status aq_same_groups(const aq_same_trace *tr, size_t m, const double *psa_mps2,
                         size_t nper, const double *psa0_mps2, double rho_min, long threads,
                         int *group, size_t *ngroups, aq_same_pair **pairs, size_t *npairs,
                         size_t *compared, aq_error *err);

#endif
