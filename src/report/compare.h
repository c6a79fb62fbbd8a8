/* compare.h: comparing two suites' results (`archquake compare`).
 *
 * Runs are matched by identity, not by spelling: the record's content
 * (sha256 of its file), the arch's name and configuration (sha256 of its
 * .cfg), and every key field of the summary table other than the record's
 * path and the arch's name (the scale, within the tolerance, so that a
 * --scale-to-pga factor that moved in its last digits still matches; and
 * any key field added to aq_summary_fields, such as a polarity, with no
 * change here).  Runs with equal keys are paired in file order.
 *
 * Before the runs, the configuration of the two files is compared (the
 * settings of aq_h5_suite: processing options, model, cor, version...;
 * and, for records and arches of one name, their content hashes): each
 * difference is an AQ_DIFF_CONFIG.  The version and build, and a setting
 * that only one file states (the other was written before it existed), are
 * shown but do not count.  Then every other summary field of
 * matched runs: numbers agree when
 *     |a - b| <= atol + rtol * max(|a|, |b|)
 * or both are NaN (a surviving arch's collapse time); counts (collapsed,
 * impacts) and strings (model, status) must be equal.
 *
 * Ignoring a name (aq_compare_opts.ignore) drops that setting's row and
 * that summary field; ignoring record_sha256 or arch_sha256 also matches
 * records by file name or arches by name alone.  Nothing prints: each
 * difference is handed to a callback. */
#ifndef AQ_REPORT_COMPARE_H
#define AQ_REPORT_COMPARE_H

#include <stddef.h>

#include "h5.h"
#include "report.h"

typedef enum {
  AQ_DIFF_VALUE = 0, /* a field differs: field, a/b values set */
  AQ_DIFF_ONLY_A,    /* run present only in the first set (a) */
  AQ_DIFF_ONLY_B,    /* run present only in the second set (b) */
  AQ_DIFF_CONFIG     /* a setting or an input's content differs */
} aq_diff_kind;

typedef struct {
  aq_diff_kind kind;
  const aq_summary *a, *b;       /* the runs (NULL for the side that lacks it) */
  const char *record, *arch;     /* display names: record file name, arch name
                                    (config rows: NULL when not about one) */
  const aq_summary_field *field; /* AQ_DIFF_VALUE only */
  double rel;            /* |a - b| / max(|a|, |b|) for numbers; NAN otherwise */
  /* AQ_DIFF_CONFIG: the setting's name and both values as text ("" when
   * that side has none); counts = 0 for a difference shown for information
   * only (the version), which does not make the files differ. */
  const char *name, *va, *vb;
  int counts;
} aq_diff;

typedef void (*aq_diff_fn)(void *ctx, const aq_diff *d);

typedef struct {
  double rtol;                /* relative tolerance */
  double atol;                /* absolute tolerance, in each field's units */
  const char *const *ignore;  /* names of settings and fields to leave out */
  size_t nignore;
} aq_compare_opts;

/* Compare suite a with suite b.  Calls fn (may be NULL) once per
 * difference: configuration rows first, then runs in the order of the
 * sorted keys, then fields.  Returns the number of differences that count
 * (informational rows excluded), or (size_t)-1 when out of memory. */
size_t aq_compare_suites(const aq_h5_suite *a, const aq_h5_suite *b,
                         const aq_compare_opts *o, aq_diff_fn fn, void *ctx);

/* 1 if two numbers agree as above. */
int aq_compare_close(double a, double b, double rtol, double atol);

#endif
