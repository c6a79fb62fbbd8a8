/* misfit.h: the scale rule, the misfit of a suite and the code's checks
 * (src/select; docs/select.md).
 *
 * A pool of records, each with its spectrum PSA_i(T_k) at the periods T_k
 * of the grid (the period range), is matched to a target S(T_k):
 *   - each record's own scale, the one that brings its spectrum closest to
 *     the target in the log over the grid, clipped to [lo, hi]:
 *         s_i = exp(mean_k (ln S(T_k) - ln PSA_i(T_k)));
 *   - a suite's mean scaled spectrum m(T_k) = mean_i s_i PSA_i(T_k), and
 *     its misfit mean_k (ln m(T_k) - ln S(T_k))^2;
 *   - the code's conditions: m(T_k) >= band S(T_k) at every period of the
 *     range (band 0.9: EN 1998-1 3.2.3.1.2(4), ASCE 7-22 16.2.3); for
 *     Eurocode 8 also the mean zero-period value mean_i s_i PGA_i >= a_g S;
 *     at most K records of one event (where the files name it); at most
 *     one record of a group that is one recording (same.h);
 *   - a suite that falls short of them is raised by the one common factor
 *     f >= 1 that makes them hold, if every f s_i stays <= hi: the suite is
 *     then f s_i, and its misfit is that of the raised mean.
 * The suite a search looks for is the one of least misfit after raising
 * among those that meet the conditions (search.h).
 *
 * Units: PSA and PGA in m/s^2, periods in s; factors and misfits are
 * ratios.  The problem's arrays are the caller's.  Nothing allocates but
 * aq_select_prepare (aq_select_prepared_free); nothing prints. */
#ifndef AQ_SELECT_MISFIT_H
#define AQ_SELECT_MISFIT_H

#include <stddef.h>

#include "../error.h"

/* The scale range by default (a factor of four either way). */
#define AQ_SELECT_SCALE_LO_DEFAULT 0.25
#define AQ_SELECT_SCALE_HI_DEFAULT 4.0

/* The band of the 90 % rule. */
#define AQ_SELECT_BAND 0.9

typedef struct {
  size_t nrec, nper;
  const double *psa_mps2;    /* nrec x nper, record-major: PSA_i(T_k), > 0 */
  const double *pga_mps2;    /* nrec: PSA_i(0), for the zero-period rule; NULL without it */
  const int *event;          /* nrec: event index (>= 0), -1 unknown; NULL: none known */
  const double *target_mps2; /* nper: S(T_k), > 0 */
  double target0_mps2;       /* the zero-period rule's bound (EC8: a_g S), 0: no such rule */
  double band;               /* AQ_SELECT_BAND: the mean nowhere below band S */
  double scale_lo, scale_hi; /* the scale range, 0 < lo <= hi */
  size_t count;              /* N: records in a suite (>= 1) */
  size_t max_per_event;      /* K: at most K records of one event; 0: no limit */
  const int *recording;      /* nrec: group of records that are one recording
                                (same.h; >= 0), at most one of each in a suite;
                                -1 alone; NULL: none */
} aq_select_problem;

/* A record's own scale: exp(mean_k (ln target_k - ln psa_k)) clipped to
 * [lo, hi]. */
double aq_select_scale(const double *psa_mps2, const double *target_mps2, size_t nper,
                       double lo, double hi);

/* The misfit of spectrum psa_mps2 at factor f against the target:
 * mean_k (ln (f psa_k) - ln target_k)^2. */
double aq_select_misfit_one(const double *psa_mps2, double f, const double *target_mps2,
                            size_t nper);

/* The pool made ready for a search: each record's scale s_i and its scaled
 * spectrum over the target, y_ik = s_i PSA_ik / S_k, and z_i = s_i PGA_i /
 * target0. */
typedef struct {
  const aq_select_problem *p;
  double *scale; /* nrec */
  double *y;     /* nrec x nper */
  double *z;     /* nrec, or NULL without the zero-period rule */
  double ln_band;
} aq_select_prepared;

aq_status aq_select_prepare(const aq_select_problem *p, aq_select_prepared *q, aq_error *err);
void aq_select_prepared_free(aq_select_prepared *q);

/* What one suite is. */
typedef struct {
  double misfit;      /* of the raised mean, mean_k (ln (f m_k / S_k))^2 */
  double factor;      /* the common factor f >= 1 the conditions need */
  int feasible;       /* 1: f max_i s_i <= hi (the conditions hold once raised) */
  double excess;      /* ln (f max_i s_i / hi) when not feasible (> 0), else 0 */
  double min_ratio;   /* min_k m_k / S_k before raising */
  size_t min_k;       /* where */
  double zero_ratio;  /* mean_i s_i PGA_i / target0 before raising (NAN without the rule) */
  double max_scale;   /* max_i s_i */
} aq_select_eval;

/* Evaluate the suite idx[0..n) (n >= 1; the mean is over n) with sum_y =
 * sum_i y_i (nper values), sum_z = sum_i z_i, max_s = max_i s_i: the
 * search's inner step. */
void aq_select_evaluate_sums(const aq_select_prepared *q, size_t n, const double *sum_y,
                             double sum_z, double max_s, aq_select_eval *e);

/* Evaluate the suite idx[0..n) (n >= 1) from scratch. */
void aq_select_evaluate(const aq_select_prepared *q, const size_t *idx, size_t n,
                        aq_select_eval *e);

/* 1 if suite a is better than suite b: feasible before not; among feasible
 * the lower misfit; among the rest the smaller excess, then the lower
 * misfit. */
int aq_select_better(const aq_select_eval *a, const aq_select_eval *b);

/* 1 if the suite idx[0..n) holds at most K records of each known event
 * and at most one of each recording. */
int aq_select_events_ok(const aq_select_problem *p, const size_t *idx, size_t n);

#endif
