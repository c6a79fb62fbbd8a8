/* fixed.h: what the text readers share below them: lines (a cursor and
 * the line-end rule), Fortran fixed-width fields, and dates (calendar by
 * timegm(3), time zones).
 *
 * The cursor walks buf[0..n) line by line (LF, CRLF, CR CR LF or CR ends;
 * no final newline needed) without copying; lines point into buf and are
 * not NUL-terminated.  Fields are read by column width, never by splitting
 * on blanks, because agencies glue fields (`-94.84213-120.18770`).  Nothing
 * here allocates or prints; failures fill aq_error with the line and field.
 */
#ifndef AQ_IO_FIXED_H
#define AQ_IO_FIXED_H

#include <stddef.h>

#include "../error.h"

typedef struct aq_lines_s {
  const char *s;
  size_t n, pos;
  long line; /* 1-based number of the line that next() returns next */
} aq_lines;

typedef struct aq_line_s {
  const char *p; /* first character (into the buffer) */
  size_t len;    /* without the line end */
  long line;     /* 1-based line number */
} aq_line;

/* The line at *pos of s[0..n) as [*b, *e) without its end (LF, CRLF, CR,
 * CR CR LF); *pos moves past the end.  Returns 0 (nothing set) at the end
 * of the input. */
int aq_text_line(const char *s, size_t n, size_t *pos, size_t *b, size_t *e);

/* The offset of the first LF or CR in s[i..n), or n. */
size_t aq_text_line_end(const char *s, size_t i, size_t n);

/* Past the line end at p < end (*p is LF or CR): LF, CR LF, CR, or CRs
 * then LF, each one line, as every text reader counts them. */
const char *aq_text_past_eol(const char *p, const char *end);

void aq_lines_init(aq_lines *c, const unsigned char *buf, size_t n);

/* The next line in *out; 0 at end of input.  Trailing DOS end-of-file bytes
 * (0x1A) and blank space after the last line count as end of input. */
int aq_lines_next(aq_lines *c, aq_line *out);

/* 1 if the line holds only blanks and tabs. */
int aq_line_blank(const aq_line *ln);

/* 1 if nothing but blanks, line ends and 0x1A remain. */
int aq_lines_at_end(const aq_lines *c);

/* A Fortran edit descriptor "nIw", "nFw.d", "nEw.d" (case-insensitive,
 * e.g. inside "(8F10.5)"): per-line count and field width. */
typedef struct {
  int per_line; /* fields per line, >= 1 */
  int width;    /* characters per field, >= 1 */
  char kind;    /* 'I', 'F' or 'E' */
} aq_fortran_fmt;

/* Find the first "(...)" in s[0..n) and parse the descriptor inside it.
 * Returns 1 on success, 0 if there is none that parses. */
int aq_fortran_fmt_find(const char *s, size_t n, aq_fortran_fmt *f);

/* 1 if s[0..n) is a whole Fortran edit descriptor ("8F10.5", "E15.7",
 * "16I5"), which a header may print where a name is looked for. */
int aq_fortran_descriptor(const char *s, size_t n);

/* Parse the number in s[0..n) (blanks around it allowed).  Returns 1 on
 * success, 0 if blank or not entirely a finite number. */
int aq_field_double(const char *s, size_t n, double *out);

/* An integer header word read as a double, as int; -1 when it does not fit
 * one (a "1e30" in an integer field): then no date or code is taken. */
int aq_header_int(double v);

/* Read count numbers laid out f->per_line to a line, f->width columns each
 * (the last line may hold fewer), from the next lines of c into out[].
 * what names the block for messages ("integer header", "data of channel 2").
 * A short line, a blank or non-numeric field is an AQ_EFORMAT naming the
 * line, the field's 1-based index in the block and what was found. */
aq_status aq_fixed_read(aq_lines *c, size_t count, const aq_fortran_fmt *f,
                        double *out, const char *name, const char *what,
                        aq_error *err);

/* aq_fixed_read, the last line read in *last (for aq_extra_rows_scan). */
aq_status aq_fixed_read_last(aq_lines *c, size_t count, const aq_fortran_fmt *f,
                             double *out, const char *name, const char *what,
                             aq_line *last, aq_error *err);

/* The values of a line of f's layout: per_line fields of width columns (a
 * shorter line, whole fields), each a number; 0 if it is not such a line.
 * An aq_row_fn with ctx the aq_fortran_fmt. */
size_t aq_fixed_row(const aq_line *ln, const void *ctx);

/* Rows past a data block of a stated count, what a reader reports in
 * aq_raw_channel's extra_* fields: from c on, every line that row()
 * accepts (it returns the values the line holds; 0: not a row of the
 * block; NULL: a line of blank-separated numbers, each one value), blank
 * lines skipped, up to the first it does not accept or the end of the
 * input, where c is left.  last is the block's last row: each extra row is
 * compared with it (text, blanks around trimmed). */
typedef struct aq_extra_rows_s {
  size_t rows, values; /* 0: none */
  long line;           /* the first one's line */
  int repeat;          /* 1: every one is a copy of last */
} aq_extra_rows;
typedef size_t aq_row_fn(const aq_line *ln, const void *ctx);
/* The default row: a line of blank-separated numbers, each one value (0 if
 * a word is not a number, or the line is blank). */
size_t aq_numbers_row(const aq_line *ln, const void *ctx);
void aq_extra_rows_scan(aq_lines *c, const aq_line *last, aq_row_fn *row, const void *ctx,
                        aq_extra_rows *x);

/* The word at *p (before end) after blanks: *p moves to its start, the
 * length returned ends at a blank, at end or at a character of stops. */
size_t aq_next_word(const char **p, const char *end, const char *stops);

/* 1 if the line names an ACCELEROGRAM (any case): the start of a channel's
 * text header in CSMIP and RENADIC files. */
int aq_line_names_accelerogram(const aq_line *ln);

/* Copy s[0..n) trimmed of blanks into out (NUL-terminated, truncated). */
void aq_copy_trim(char *out, size_t cap, const char *s, size_t n);

/* Case-insensitive search for needle in s[0..n); NULL if absent. */
const char *aq_find_ci(const char *s, size_t n, const char *needle);

/* Whole hours east of UTC of a zone word s[0..n) ("UTC", "GMT", "PDT",
 * "PST", "JST", ...): 1 and *hours_east if known, else 0. */
int aq_zone_offset(const char *s, size_t n, int *hours_east);

/* ISO-8601 "YYYY-MM-DDThh:mm:ss.sssZ" from a calendar date and time of day
 * in UTC (sec may carry a fraction; hour may exceed 23, which rolls the day
 * over).  Returns 1, or 0 if a value is out of range. */
int aq_iso_time(char *out, size_t cap, int year, int month, int day, int hour,
                int minute, double sec);

/* The same from a local time in a zone east_h whole hours east of UTC
 * (JST 9, PDT -7): UTC is local minus east_h, rolling the day back or over.
 * Returns 1, or 0 if a value is out of range (|east_h| <= 14). */
int aq_iso_time_local(char *out, size_t cap, int year, int month, int day, int hour,
                      int minute, double sec, int east_h);

/* Seconds since 1970-01-01T00:00:00 UTC of "YYYY-MM-DD[Thh:mm[:ss.sss]][Z]"
 * (the zone suffix is ignored: StationXML and miniSEED times are UTC).
 * Returns 1, or 0 if s does not start with such a time. */
int aq_iso_parse(const char *s, double *epoch_s);

/* ISO-8601 UTC of ms milliseconds since 1970-01-01T00:00:00Z; 1, or 0 if
 * out of range. */
int aq_iso_from_ms(char *out, size_t cap, long long ms);

/* Month and day of day-of-year jday in year: 1, or 0 if out of range. */
int aq_month_day(int year, int jday, int *month, int *day);

#endif
