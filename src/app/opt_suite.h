/* opt_suite.h: --suite FILE of the main job and capacity: the records of a
 * suite file of `archquake select` (select/suite_file.h) become the
 * command's operands, each with its own scale factor.
 *
 * A row whose record is a pair "H1,H2" becomes a --components motion; the
 * others plain RECORDs.  The command runs plain RECORDs first, then the
 * motions, so the factors are put in that order.  Messages: one line each
 * on stderr (app code). */
#ifndef AQ_APP_OPT_SUITE_H
#define AQ_APP_OPT_SUITE_H

#include <stddef.h>

#include "../select/suite_file.h"
#include "opt_orient.h"

typedef struct {
  aq_suite_file file;
  char **argv;      /* the command's argv up to optind, then the plain records */
  double *factors;  /* per record as the command runs them */
  size_t nplain;
} aq_opt_suite;

/* Read the suite file at path for a command whose operands are
 * argv[optind_ .. *argc) and whose --components are in orient: both must be
 * empty (the suite names the records).  On success *argv and *argc are
 * replaced by s->argv and optind_ + s->nplain, the pairs are added to orient
 * and 0 is returned; else one line on stderr, *nerr incremented, -1. */
int aq_opt_suite_take(const char *path, int *argc, char ***argv, int optind_,
                      aq_orient_opts *orient, aq_opt_suite *s, int *nerr);

void aq_opt_suite_free(aq_opt_suite *s);

#endif
