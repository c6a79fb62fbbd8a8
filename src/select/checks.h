/* checks.h: the code's conditions on a chosen suite, each with whether it
 * holds and the figures that say so (src/select; docs/select.md):
 *   band         the mean scaled spectrum nowhere below band x target over
 *                the range (EN 1998-1:2004 3.2.3.1.2(4)b; ASCE/SEI 7-22
 *                16.2.3: 90 %)
 *   zero-period  Eurocode 8 only: the mean of the records' zero-period
 *                values (their PGA) at least a_g S (3.2.3.1.2(4)a)
 *   events       at most K records of one event (--max-per-event)
 *   count        at least the code's number of records: EC8 3 (7 for the
 *                mean response, 3.2.3.1.2(3) and 4.3.3.4.3(3)), ASCE 7-22
 *                11 (16.2.2)
 * Nothing prints or allocates. */
#ifndef AQ_SELECT_CHECKS_H
#define AQ_SELECT_CHECKS_H

#include <stddef.h>

#include "misfit.h"
#include "target.h"

#define AQ_SELECT_CHECKS_MAX 4

typedef struct {
  const char *name; /* "band", "zero-period", "events", "count" */
  int holds;
  char detail[240]; /* one sentence with the figures */
} aq_select_check;

/* The fewest records target t's code accepts (1 for a CSV target). */
size_t aq_select_min_count(const aq_target *t);

/* The checks of the suite idx[0..n) of q at the common factor f, the grid
 * periods_s (q->p->nper), event names event_key[i] (NULL: none) for the
 * events check, into out[AQ_SELECT_CHECKS_MAX]; returns how many (the
 * zero-period check only when q has the rule). */
size_t aq_select_checks(const aq_select_prepared *q, const aq_target *t,
                        const double *periods_s, const size_t *idx, size_t n, double f,
                        const char *const *event_key, aq_select_check *out);

/* 1 if every check of out[0..n) holds. */
int aq_select_checks_hold(const aq_select_check *out, size_t n);

#endif
