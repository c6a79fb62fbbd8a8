/* csv_impl.h: the inside of the CSV / plain-text reader, shared by csv.c
 * (lines, fields, the parse), csv_rows.c (the data rows, the time steps)
 * and csv_names.c (units, times and keys in the words); internal to
 * src/io.  Nothing here allocates but aq_csv_rows_grow (the caller frees
 * the rows' arrays: the channels' with the raw file, tt with
 * aq_csv_rows_free_time) and aq_csv_median_step (its own scratch).
 */
#ifndef AQ_IO_CSV_IMPL_H
#define AQ_IO_CSV_IMPL_H

#include <stddef.h>

#include "number.h"
#include "reader.h"
#include "units.h"

#define CSV_FIELD_MAX 128 /* characters kept of one field */
#define CSV_NAME_MAX 64   /* characters kept of a column name */
#define CSV_COLS_MAX 64   /* columns a file may have */

typedef struct {
  const char *s;
  size_t n, pos;
  long line; /* line number of the line last returned */
} csv_cur;

/* The rows' arrays: each channel's values (in raw) and the times (when
 * there is a time column), cap rows each. */
typedef struct {
  aq_raw_file *raw;
  double *tt;
  size_t cap;
} csv_rows;

/* What a plain row is: ncols numbers separated by sep (' ': runs of blanks
 * and tabs), column tcol the time (or -1), chof[i] the channel of column i
 * (or -1). */
typedef struct {
  size_t ncols;
  char sep;
  long tcol;
  const int *chof;
  aq_number_shape *shape; /* each column's (number.h) */
} plain_row;

/* ---- csv.c */

/* isspace() of the C locale, without the library call. */
int aq_csv_is_space(char c);

/* Strip a '#' comment and surrounding blanks. */
void aq_csv_trim_line(const char *s, size_t *b, size_t *e);

/* ---- csv_rows.c */

/* Grow every channel's array (and the times', with_time) to cap rows; 0
 * when out of memory (the arrays kept as they were). */
int aq_csv_rows_grow(csv_rows *r, size_t cap, int with_time);

/* Free the times' array. */
void aq_csv_rows_free_time(csv_rows *r);

/* The line of row idx (0-based), the rows counted as the reading counts
 * them: the lines that are not blank once a '#' comment is cut, from the
 * first row's line (line0, starting at pos) on; -1 if there are fewer.
 * Only for messages: the rows' lines are not kept while reading. */
long aq_csv_row_line(const char *s, size_t n, size_t pos, long line0, size_t idx);

/* The rows from c->pos on that are plain: ncols finite plain decimals, with
 * blanks (and tabs, unless sep is the tab) around them, separated by sep,
 * and a line end (LF, CRLF, CR, CR CR LF, or the end of the input) after
 * the last; into the arrays from row k on, bare rows (bare_rows) first.
 * Returns the new k, with c after the last row taken; any other line
 * (blank, a comment, quotes, a bad or missing field) is left to the
 * general reading, which reads it exactly as before. */
size_t aq_csv_plain_rows(csv_cur *c, const plain_row *pr, csv_rows *rows, size_t k);

/* The smallest and largest of the n - 1 steps of t, and the first i
 * (0 if none) where |t_i - (t_0 + i est)| > tol, in one pass. */
size_t aq_csv_step_range(const double *t, size_t n, double est, double tol, double *lo,
                         double *hi);

/* Median of the n - 1 steps of t (NaN if out of memory): the upper median,
 * element (n - 1) / 2 of the sorted steps. */
double aq_csv_median_step(const double *t, size_t n);

/* ---- csv_names.c */

/* Units named in a piece of text: 1 acceleration (*u set), -1 units that are
 * not acceleration (velocity, displacement, time), 0 none recognised. */
int aq_csv_units_in(const char *text, aq_units *u);

/* The quantity the units in text measure ("vel (cm/s)", "disp_cm",
 * "cm/s"): the word in () or [], after the last '_' or blank, or the whole
 * text (aq_units_quantity). */
aq_quantity aq_csv_quantity_in(const char *text);

/* 1 if a column name names the time (t, time, sec, seconds, zeit, tiempo,
 * temps, with units or a suffix after it). */
int aq_csv_is_time_name(const char *name);

/* JMA: "INITIAL TIME = YYYY MM DD hh mm ss" (JST) in [v, e). */
int aq_csv_jma_start(const char *v, const char *e, char *out, size_t cap);

/* CWB: "#StartTime(GMT+08): YYYY/MM/DD-hh:mm:ss.sss" in s[b..e) (after '#'). */
int aq_csv_cwb_start(const char *s, size_t b, size_t e, char *out, size_t cap);

/* "KEY = value" or "KEY: value" in a preamble line: returns the value's
 * start (in s) if the line's key starts with key (case-insensitive). */
const char *aq_csv_kv(const char *s, size_t b, size_t e, const char *key);

/* A column's name as the channel's: as written when it fits; else without
 * its units in parentheses or brackets ("Acceleration (g)" ->
 * "Acceleration"); else none, never a cut phrase. */
void aq_csv_channel_name(const char *col, char *out, size_t cap);

#endif
