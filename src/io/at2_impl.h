/* at2_impl.h: the inside of the PEER NGA .AT2 reader, shared by at2.c (the
 * values, the parse) and at2_header.c (the header); internal to src/io.
 * Nothing here allocates; offsets are into the file's bytes.
 */
#ifndef AQ_IO_AT2_IMPL_H
#define AQ_IO_AT2_IMPL_H

#include <stddef.h>

#include "units.h"

#define AT2_MAX_HEADER_LINES 64 /* the NPTS line is looked for in lines 1..64 */

#define AT2_TEXT_LINES 8        /* text lines before it kept for units, event */

typedef struct {
  const char *s;
  size_t n, pos;
  long line; /* 1-based line of pos */
} at2_cur;

/* Where find_header found the header. */
typedef struct {
  size_t line_b, line_e; /* the NPTS line */
  long line;             /* its number */
  size_t data_pos;       /* start of the values */
  long data_line;        /* their first line */
  double npts, dt;
  size_t tail;           /* offset in the NPTS line after DT */
  size_t text_b[AT2_TEXT_LINES], text_e[AT2_TEXT_LINES];
  int ntext;             /* non-blank text lines before it (at most AT2_TEXT_LINES) */
} at2_header;

/* The current line [*b, *e) and move to the next. */
void aq_at2_next_line(at2_cur *c, size_t *b, size_t *e);

const char *aq_at2_find_ci(const char *s, size_t n, const char *needle);

/* 1 if s[0..n) starts with needle, case-insensitive. */
int aq_at2_starts_ci(const char *s, size_t n, const char *needle);

/* Copy s[0..n) into out (NUL-terminated, truncated to cap-1), for messages. */
void aq_at2_quote(const char *s, size_t n, char *out, size_t cap);

int aq_at2_is_digit(char c);

int aq_at2_is_numchar(char c);

/* "UNITS OF X" in the text lines: X as acceleration units.  Returns 1 with
 * *u set, 0 if no units are stated, -1 (word in *what) if X is not
 * acceleration. */
int aq_at2_header_units(const char *s, size_t n, aq_units *u, char *what, size_t cap);

/* Parse an NPTS/DT line s[0..n): NPTS and DT as words in either order, each
 * with its number after it ("NPTS= 4000, DT= .01 SEC", "dt: 0.01 npts 4000")
 * or before it ("4000 NPTS, .01 DT"), or the pair "NPTS, DT" after or before
 * two numbers ("4000 0.0100 NPTS, DT").  Returns 1 (*npts, *dt, *tail the
 * offset after the last thing used), 0 if the line has no NPTS word, -1 if
 * NPTS lacks its number, -2 if DT or its number is missing. */
int aq_at2_npts_line(const char *s, size_t n, double *npts, double *dt, size_t *tail);

/* A line that starts like values: its first non-blank character is a
 * digit, a point or a sign, and it has a digit. */
int aq_at2_data_line(const char *s, size_t n);

/* Find the header: the last line with an NPTS/DT pair that is followed
 * (after blank lines) by a line of values, among the first
 * AT2_MAX_HEADER_LINES (up to an end marker).  Lines before it are free text
 * (they may quote other numbers, even other NPTS lines).  On success fills *h (pos after the NPTS line)
 * and returns 1; returns 0 if none, with *bad_line the last line that had an
 * NPTS word but not its numbers (or -1). */
int aq_at2_find_header(const char *s, size_t n, at2_header *h, long *bad_line,
                       size_t *bad_b, size_t *bad_e, int *bad_kind);

#endif
