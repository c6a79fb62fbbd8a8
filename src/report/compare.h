/* compare.h: comparing two suites' run summaries (`archquake compare`).
 *
 * Runs are matched by their key fields (record, arch, scale: the scale
 * within the tolerance, so that a --scale-to-pga factor that moved in its
 * last digits still matches); runs with equal keys are paired in file order.
 * Every other summary field is compared: numbers agree when
 *     |a - b| <= atol + rtol * max(|a|, |b|)
 * or both are NaN (a surviving arch's collapse time); counts (collapsed,
 * impacts) and strings (model, status) must be equal.  Nothing allocates
 * beyond the sorted index it frees; nothing prints: each difference is
 * handed to a callback. */
#ifndef AQ_REPORT_COMPARE_H
#define AQ_REPORT_COMPARE_H

#include <stddef.h>

#include "report.h"

typedef enum {
  AQ_DIFF_VALUE = 0, /* a field differs: field, a/b values set */
  AQ_DIFF_ONLY_A,    /* run present only in the first set (a) */
  AQ_DIFF_ONLY_B     /* run present only in the second set (b) */
} aq_diff_kind;

typedef struct {
  aq_diff_kind kind;
  const aq_summary *a, *b; /* the runs (NULL for the side that lacks it) */
  const aq_summary_field *field; /* AQ_DIFF_VALUE only */
  double rel;            /* |a - b| / max(|a|, |b|) for numbers; NAN otherwise */
} aq_diff;

typedef void (*aq_diff_fn)(void *ctx, const aq_diff *d);

/* Compare runs a[0..na) with b[0..nb) within rtol (relative) and atol
 * (absolute, in each field's units).  Calls fn (may be NULL) once per
 * difference, in the order of the sorted keys, then fields.  Returns the
 * number of differences, or (size_t)-1 when out of memory. */
size_t aq_compare_runs(const aq_summary *a, size_t na, const aq_summary *b,
                       size_t nb, double rtol, double atol, aq_diff_fn fn,
                       void *ctx);

/* 1 if two numbers agree as above. */
int aq_compare_close(double a, double b, double rtol, double atol);

#endif
