/* suite_file.h: the suite file of `archquake select`, written by it and
 * read by the main job's and capacity's --suite (docs/select.md).
 *
 * TSV: comment lines "# ..." first (the target, the range, the rule, the
 * search, the checks and whether every condition holds), then the header
 * row and one row per record:
 *     record  channel  scale  misfit  event
 * record: the record as named to select (FILE, FILE#CHANNEL, or a pair of
 * components "H1,H2"), a path as given (relative to the directory select
 * ran in); scale: the factor to run it at (> 0); misfit: the record's own
 * at that scale; event: as the file names it ("-" if it names none).
 * Fields hold no tabs or newlines (the writer turns them into spaces).
 *
 * Nothing prints: the reader fills an aq_error naming the file, the line
 * and the field.  The caller owns what it reads (aq_suite_file_free). */
#ifndef AQ_SELECT_SUITE_FILE_H
#define AQ_SELECT_SUITE_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "../error.h"

typedef struct {
  char *record;     /* malloc'd */
  char channel[32];
  double scale;     /* > 0 */
  double misfit;
  char event[96];
} aq_suite_row;

typedef struct {
  aq_suite_row *row;
  size_t n;
} aq_suite_file;

/* The header row. */
#define AQ_SUITE_FILE_HEADER "record\tchannel\tscale\tmisfit\tevent"

/* Write the comment lines comment[0..ncomment) (each without "# " and
 * without a newline), the header row and the rows to f.  Returns 0, or -1
 * when f reports an error. */
int aq_suite_file_write(FILE *f, const char *const *comment, size_t ncomment,
                        const aq_suite_row *rows, size_t n);

/* Read the suite file at path.  Returns AQ_OK (at least one row), AQ_EIO
 * (it cannot be read), AQ_EFORMAT (err: the line and field: a missing
 * header row, a row of another number of fields, an empty record, a scale
 * that is not a number > 0, the same record twice) or AQ_ENOMEM. */
aq_status aq_suite_file_read(const char *path, aq_suite_file *s, aq_error *err);

void aq_suite_file_free(aq_suite_file *s);

#endif
