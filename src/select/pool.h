/* pool.h: what a record (or a pair of components) brings to a selection:
 * its spectrum at the grid of periods and at T = 0, by the rule of the
 * target's code (src/select; docs/select.md).
 *
 * The grid: PEER's 111 periods (spectrum.h) that lie in the range [T1, T2],
 * with T1 and T2 themselves, or the periods of a grid of the user's within
 * the range.
 *
 * A pair's spectrum: Eurocode 8 asks that the mean of the spectra of every
 * horizontal component used meet the elastic spectrum, so a pair brings the
 * mean of its two components' spectra (the mean over the suite is then the
 * mean over every component); ASCE 7-22 16.2.3 asks for the
 * maximum-direction spectrum of each pair, RotD100; a target of the user's
 * (a uniform hazard or conditional mean spectrum from ground-motion models
 * of the NGA-West2 kind) is matched by RotD50.  The zero-period value (the
 * EC8 rule) is the same combination at T = 0.
 *
 * Units: periods s, PSA m/s^2.  The caller owns every array.  Nothing
 * prints; errors fill the aq_error. */
#ifndef AQ_SELECT_POOL_H
#define AQ_SELECT_POOL_H

#include <stddef.h>

#include "../error.h"
#include "../signal/signal.h"
#include "../signal/spectrum.h"
#include "target.h"

typedef enum {
  AQ_PAIR_MEAN = 0, /* the arithmetic mean of the two components' PSA (ec8) */
  AQ_PAIR_ROTD100,  /* RotD100 (asce7) */
  AQ_PAIR_ROTD50    /* RotD50 (a CSV target) */
} aq_pair_rule;

/* The pair rule of target t's code, and its name ("mean of H1 and H2",
 * "RotD100", "RotD50"). */
aq_pair_rule aq_select_pair_rule(const aq_target *t);
const char *aq_select_pair_name(aq_pair_rule r);

/* The grid over [t1_s, t2_s] (0 < t1 < t2): user (n_user > 0) periods in
 * the range, else PEER's in it with t1 and t2; into *periods (malloc'd,
 * ascending, distinct), *n of them.  AQ_OK, AQ_EVALUE (no period of the
 * user's grid in the range: field "--period-grid"), AQ_ENOMEM. */
aq_status aq_select_grid(double t1_s, double t2_s, const double *user, size_t n_user,
                         double **periods, size_t *n, aq_error *err);

/* The spectrum of processed record a (b NULL) or of the pair (a, b) sampled
 * alike, by rule, at damping: psa_mps2[k] at periods[k] (n), and *psa0_mps2
 * at T = 0.  ws: a spectrum workspace (spectrum.h); opts: its options (the
 * peak convention).  Errors as aq_spectrum_psa, field naming the period. */
aq_status aq_select_spectrum(aq_spectrum_ws *ws, const aq_spectrum_opts *opts,
                             const aq_processed *a, const aq_processed *b, aq_pair_rule rule,
                             double damping, const double *periods, size_t n,
                             double *psa_mps2, double *psa0_mps2, aq_error *err);

/* The name of the peak convention of spectra computed with opts ("peer",
 * "exact" or "samples": spectrum.h), for the outputs. */
const char *aq_select_peaks_name(const aq_spectrum_opts *opts);

#endif
