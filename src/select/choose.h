/* choose.h: a selection from start to end: the target at the grid, each
 * record's scale, the search (search.h), the common factor, the checks
 * (checks.h), and, when no suite meets the conditions, by how much the
 * best falls short and where (src/select; docs/select.md).
 *
 * Units: periods s, PSA m/s^2.  The input's arrays are the caller's; the
 * selection owns its own (aq_selection_free).  Nothing prints. */
#ifndef AQ_SELECT_CHOOSE_H
#define AQ_SELECT_CHOOSE_H

#include <stddef.h>

#include "../error.h"
#include "checks.h"
#include "misfit.h"
#include "search.h"
#include "target.h"

typedef struct {
  const aq_target *target;
  const double *periods_s;   /* the grid, nper, ascending */
  size_t nper;
  size_t nrec;               /* the usable pool */
  const double *psa_mps2;    /* nrec x nper */
  const double *psa0_mps2;   /* nrec: at T = 0 */
  const char *const *event_key; /* nrec: "" when the file names no event */
  size_t count;              /* N */
  double scale_lo, scale_hi;
  size_t max_per_event;      /* 0: no limit */
  const int *recording;      /* nrec: group of records that are one recording
                                (same.h), -1 alone; NULL: none */
  double exhaustive_max;     /* AQ_SELECT_EXHAUSTIVE_MAX */
  long threads;
} aq_select_input;

typedef struct {
  aq_select_problem problem;
  aq_select_prepared prep;
  aq_select_result search; /* idx: the chosen records (indices into the pool) */
  double *target_mps2;     /* nper: the target at the grid */
  int *event;              /* nrec: event index, -1 none */
  size_t nevents;
  double *scale;           /* count: each chosen record's scale, common factor included */
  double *misfit_one;      /* count: each one's own misfit at that scale */
  aq_select_check checks[AQ_SELECT_CHECKS_MAX];
  size_t nchecks;
  int all_hold;            /* every check holds */
  int raised;              /* 1: the common factor is above 1 */
} aq_selection;

/* Choose.  Returns AQ_OK with *s filled (whether or not the conditions
 * hold: s->all_hold), or AQ_ENOMEM. */
aq_status aq_select_choose(const aq_select_input *in, aq_selection *s, aq_error *err);

void aq_selection_free(aq_selection *s);

/* One sentence on why the chosen suite does not meet the conditions and by
 * how much (the lowest ratio to the target and its period at the largest
 * common factor the scale range allows, the zero-period value, the count),
 * into buf[n]. */
void aq_selection_shortfall(const aq_selection *s, const aq_select_input *in, char *buf,
                            size_t n);

/* What the suite file's header says beyond the selection itself. */
typedef struct {
  const char *build;      /* the program's version and build */
  const char *range_from; /* how the range was chosen ("--periods", ...) */
  const char *peaks;      /* the spectra's peak rule (spectrum.h's name) */
  const char *pair_rule;  /* a pair's spectrum (pool.h's name) */
  const char *processing; /* the pool's processing in words */
  size_t nusable;         /* usable records of the pool */
  const char *same;       /* which records are one recording (one sentence), or NULL */
} aq_selection_context;

/* The lines of the suite file's header (target, range, spectra, rule,
 * search, the records that are one recording, common factor, misfit, each
 * check, whether all hold; no "# "
 * and no newline), at most AQ_SELECTION_LINES_MAX of AQ_SELECTION_LINE_MAX
 * bytes into lines; returns their number. */
#define AQ_SELECTION_LINES_MAX (10 + AQ_SELECT_CHECKS_MAX)
#define AQ_SELECTION_LINE_MAX 1024
size_t aq_selection_describe(const aq_selection *s, const aq_select_input *in,
                             const aq_selection_context *c,
                             char lines[][AQ_SELECTION_LINE_MAX]);

/* One sentence on the common factor: "none (the least-misfit suite meets
 * the conditions)" or "1.043: the least-misfit suite fell below 90 % of the
 * target at 0.45 s", into buf[n]. */
void aq_selection_factor_note(const aq_selection *s, const aq_select_input *in, char *buf,
                              size_t n);

#endif
