/* search.h: the search for the suite of least misfit (src/select;
 * docs/select.md).
 *
 * Among the suites of N records of the pool that hold at most K records of
 * one event and at most one record of each recording (same.h), the best is the one that meets the conditions (raised by its
 * common factor where needed, misfit.h) with the least misfit; if none can,
 * the one that comes closest (the smallest excess of the scale range), so
 * that the caller can say by how much it falls short.
 *
 *   exhaustive: every combination, C(M, N) of them, each evaluated from
 *     running sums (depth-first, one vector addition per node), split over
 *     threads by the first record: the optimum.
 *   heuristic: greedy, then swaps (Jayaram, Lin & Baker 2011, "A
 *     computationally efficient ground-motion selection algorithm for
 *     matching a target response spectrum mean and variance", Earthquake
 *     Spectra 27(3), 797-815): the suite is built one record at a time,
 *     each the record that makes the best partial suite; then, over and
 *     over, the single exchange of a suite record for a pool record that
 *     improves the suite most is made, until none does.  This ends in a
 *     local optimum that depends on the first record, so it is run from
 *     the best first records in turn (the greedy start, then its
 *     runners-up), at least `starts` of them and then more while the suites
 *     evaluated times the periods stay within a budget, up to every record;
 *     the best end is kept.
 *
 * aq_select_search chooses: exhaustive when C(M, N) <= exhaustive_max,
 * else the heuristic (at least AQ_SELECT_STARTS starts, within
 * AQ_SELECT_HEURISTIC_BUDGET).  Nothing prints; the result's arrays are the
 * caller's (aq_select_result_free). */
#ifndef AQ_SELECT_SEARCH_H
#define AQ_SELECT_SEARCH_H

#include <stddef.h>

#include "../error.h"
#include "misfit.h"

/* Combinations below which aq_select_search is exhaustive by default:
 * C(M, N) <= this (about 1 s on one core at 20 periods). */
#define AQ_SELECT_EXHAUSTIVE_MAX 2000000.0
/* Starts of the heuristic, at least, and its budget: suites evaluated times
 * periods (a logarithm each), more starts while within it (about 0.3 s on
 * one core). */
#define AQ_SELECT_STARTS 4
#define AQ_SELECT_HEURISTIC_BUDGET 5e7

typedef enum { AQ_SEARCH_EXHAUSTIVE = 0, AQ_SEARCH_HEURISTIC } aq_search_kind;

typedef struct {
  aq_search_kind kind;
  size_t *idx;          /* N record indices of the best suite, ascending */
  aq_select_eval eval;  /* what it is */
  double combinations;  /* C(M, N) */
  double evaluated;     /* suites evaluated */
  size_t starts;        /* the heuristic's starts */
  int found;            /* 0: no suite of N records meets the event rule */
} aq_select_result;

/* C(m, n) as a double (inf beyond its range). */
double aq_select_combinations(size_t m, size_t n);

/* Every suite (threads >= 1: the first records spread over them). */
aq_status aq_select_exhaustive(const aq_select_prepared *q, long threads,
                               aq_select_result *r, aq_error *err);

/* Greedy, then swaps, from at least `starts` first records (>= 1), more
 * while the suites evaluated times the periods stay below budget. */
aq_status aq_select_heuristic(const aq_select_prepared *q, size_t starts, double budget,
                              aq_select_result *r, aq_error *err);

/* Exhaustive when C(M, N) <= exhaustive_max, else the heuristic. */
aq_status aq_select_search(const aq_select_prepared *q, double exhaustive_max, long threads,
                           aq_select_result *r, aq_error *err);

void aq_select_result_free(aq_select_result *r);

#endif
