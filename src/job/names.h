/* names.h: the records a suite's operands name: every channel of a
 * multi-channel file a record of its own (FILE#CH, io/record.h's
 * aq_record_expand), named on several threads for a long suite.  Nothing
 * here prints. */
#ifndef AQ_JOB_NAMES_H
#define AQ_JOB_NAMES_H

#include <stddef.h>

#include "../error.h"
#include "../io/record.h"

/* aq_record_expand_horizontal of paths[0..n), on up to nthreads threads:
 * the same names in the same order into *out (*nout of them), and the
 * lines saying which vertical channels were left out into *notes (*nnotes;
 * free both with aq_record_names_free).  Returns AQ_OK, or the first
 * operand's failure (err filled, *out and *notes NULL). */
aq_status aq_job_names(char *const *paths, size_t n, const aq_read_opts *opts, long nthreads,
                       char ***out, size_t *nout, char ***notes, size_t *nnotes, aq_error *err);

#endif
