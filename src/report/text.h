/* text.h: the TSV summary (one row per run, header row first).  Columns are
 * the fields of aq_summary_fields[] in order.  Numbers are printed as the
 * shortest decimal that reads back to the same double (aq_text_double:
 * 0.8, not 0.80000000000000004), NaN as "nan" and infinities as
 * "inf"/"-inf" whatever the C library would print; tabs and line breaks in
 * names become spaces, so a row is always one line.  Deterministic: the same
 * summary gives the same bytes.  The caller owns the FILE. */
#ifndef AQ_REPORT_TEXT_H
#define AQ_REPORT_TEXT_H

#include <stdint.h>
#include <stdio.h>

#include "report.h"

/* x as every output of archquake prints a double (TSV, CSV, HDF5
 * attributes as text, the report): io/number.h's aq_number_format, the
 * shortest decimal that strtod reads back to the same double (%.15g, %.16g
 * or %.17g, whichever is first to), "nan" for any NaN, "inf" and "-inf";
 * into buf (n >= AQ_TEXT_NUM_MAX). */
enum { AQ_TEXT_NUM_MAX = 32 };
void aq_text_double(char *buf, size_t n, double x);
/* The same into buf[AQ_TEXT_NUM_MAX], returned, for a printf argument:
 * printf("%s,%s\n", AQ_TEXT_NUM(a), AQ_TEXT_NUM(b)) (each its own buffer,
 * alive to the end of the enclosing block). */
char *aq_text_num(char *buf, double x);
#define AQ_TEXT_NUM(x) aq_text_num((char[AQ_TEXT_NUM_MAX]){0}, (x))

/* Format an integer field as the text writer does (AQ_SUMMARY_INT_NONE as
 * "nan") into buf (n >= 32). */
void aq_text_int(char *buf, size_t n, int64_t x);

/* Write the header row.  Returns 0, or -1 if the write failed (errno set). */
int aq_text_header(FILE *f);

/* Write one row.  Returns 0, or -1 if the write failed (errno set). */
int aq_text_row(FILE *f, const aq_summary *s);


/* An aligned table for a terminal (never for files or pipes): the same
 * columns, padded with spaces to fixed widths, numbers with 6 significant
 * digits.  Widths are fixed before the first row (so rows can stream):
 * record_w and arch_w are the longest record path and arch name. */
typedef struct {
  int width[AQ_SUMMARY_FIELDS_MAX]; /* per column of aq_summary_fields[] */
} aq_text_layout;

void aq_text_layout_init(aq_text_layout *L, size_t record_w, size_t arch_w);

/* Header and row in the aligned layout.  Return 0, or -1 on a write error. */
int aq_text_header_aligned(FILE *f, const aq_text_layout *L);
int aq_text_row_aligned(FILE *f, const aq_text_layout *L, const aq_summary *s);

#endif
