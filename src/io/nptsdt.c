/* nptsdt.c: text whose first line is the two numbers "NPTS DT", as OpenSees
 * examples and many course files write a ground motion (reader.h).
 *
 *     1560 0.02                   NPTS (a whole number >= 2), DT (s, > 0)
 *     0.0063 0.0036 0.0010 ...    then NPTS values, any number to a line,
 * or
 *     0.00 0.0063                 NPTS (time, value) pairs, one to a line,
 *     0.02 0.0036                 the times t0 + k DT (within
 *     ...                         NPTSDT_TIME_TOL_REL of DT)
 * Numbers are separated by blanks, tabs or commas.  Which of the two is
 * decided by the count: NPTS numbers after the first line are values,
 * 2 NPTS on lines of two are pairs (more on lines of two: pairs and rows
 * past the count; more otherwise: values and rows past the count, which
 * are reported for the decision in record.c); fewer are refused, naming
 * both counts.  The file states no units, no channel and no start: record.c asks
 * for --units.  dt is the file's, whatever --dt says (--dt is for files that
 * state none).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fixed.h"
#include "reader.h"

/* Each time must lie within this fraction of DT of t0 + k DT (times are
 * printed to a few decimals; a missing or repeated sample is off by DT). */
#define NPTSDT_TIME_TOL_REL 0.01
#define NPTSDT_TOKEN_MAX 64

static int is_sep(char c)
{
  return c == ' ' || c == '\t' || c == ',';
}

/* The next number of ln after *pos: 1 and *x, 0 at the end of the line, -1
 * when what is there is not a number (*pos at it, *len its length). */
static int next_number(const aq_line *ln, size_t *pos, size_t *len, double *x)
{
  size_t i = *pos;
  while (i < ln->len && is_sep(ln->p[i]))
    i++;
  size_t b = i;
  while (i < ln->len && !is_sep(ln->p[i]))
    i++;
  *pos = b;
  *len = i - b;
  if (b == ln->len)
    return 0;
  if (i - b >= NPTSDT_TOKEN_MAX || !aq_field_double(ln->p + b, i - b, x))
    return -1;
  *pos = i;
  return 1;
}

/* The first non-blank line as "NPTS DT": 1 with both, else 0.  NPTS must be
 * written as a whole number (digits only). */
static int first_line(aq_lines *c, aq_line *ln, double *npts, double *dt)
{
  while (aq_lines_next(c, ln))
    if (!aq_line_blank(ln)) {
      size_t pos = 0, len;
      double x[2], extra;
      for (int i = 0; i < 2; i++)
        if (next_number(ln, &pos, &len, &x[i]) != 1)
          return 0;
      if (next_number(ln, &pos, &len, &extra) != 0)
        return 0;
      size_t b = 0;
      while (is_sep(ln->p[b]))
        b++;
      for (size_t i = b; i < ln->len && !is_sep(ln->p[i]); i++)
        if (ln->p[i] < '0' || ln->p[i] > '9')
          return 0;
      *npts = x[0];
      *dt = x[1];
      return x[0] >= 2 && x[1] > 0 && isfinite(1.0 / x[1]);
    }
  return 0;
}

/* Count the numbers after the first line, and whether every line holds two.
 * 1, or 0 at a token that is not a number. */
static int count_numbers(aq_lines c, size_t *count, int *all_pairs, long *bad_line)
{
  aq_line ln;
  *count = 0;
  *all_pairs = 1;
  while (aq_lines_next(&c, &ln)) {
    size_t pos = 0, len, k = 0;
    double x;
    int r;
    while ((r = next_number(&ln, &pos, &len, &x)) == 1)
      k++;
    if (r < 0) {
      *bad_line = ln.line;
      return 0;
    }
    if (k && k != 2)
      *all_pairs = 0;
    *count += k;
  }
  return 1;
}

int aq_nptsdt_sniff(const unsigned char *buf, size_t n)
{
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line ln;
  double npts, dt;
  size_t count;
  int pairs;
  long bad;
  if (!first_line(&c, &ln, &npts, &dt) || !count_numbers(c, &count, &pairs, &bad))
    return 0;
  return (double)count >= npts;
}

aq_status aq_nptsdt_parse(const unsigned char *buf, size_t n, const char *name,
                          const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts;
  memset(raw, 0, sizeof *raw);
  aq_lines c;
  aq_lines_init(&c, buf, n);
  aq_line ln;
  double npts_d, dt;
  if (!first_line(&c, &ln, &npts_d, &dt))
    return aq_error_set(err, AQ_EFORMAT, name, c.line > 1 ? c.line - 1 : 1, -1, "NPTS DT",
                        "expected a first line of two numbers, NPTS (a whole number >= 2) "
                        "and DT (s, > 0)");
  long head = ln.line;
  size_t count;
  int pairs;
  long bad = 0;
  if (!count_numbers(c, &count, &pairs, &bad)) {
    aq_lines_init(&c, buf, n);
    while (aq_lines_next(&c, &ln) && ln.line < bad)
      ;
    size_t pos = 0, len;
    double x;
    while (next_number(&ln, &pos, &len, &x) == 1)
      ;
    char got[NPTSDT_TOKEN_MAX + 1];
    aq_copy_trim(got, sizeof got, ln.p + pos, len < NPTSDT_TOKEN_MAX ? len : NPTSDT_TOKEN_MAX);
    return aq_error_set(err, AQ_EFORMAT, name, bad, -1, "data",
                        "expected numbers after the \"NPTS DT\" line, got \"%s\"", got);
  }
  if (npts_d > (double)n)
    return aq_error_set(err, AQ_EFORMAT, name, head, -1, "NPTS",
                        "expected at most the %zu bytes of the file, got %.0f", n, npts_d);
  if (!((double)count >= npts_d))
    return aq_error_set(err, AQ_EFORMAT, name, head, -1, "NPTS",
                        "expected %.0f values, or %.0f (time, value) pairs one to a line, "
                        "after \"NPTS DT\"; got %zu numbers%s",
                        npts_d, npts_d, count, pairs ? " on lines of two" : "");
  int is_pairs = (double)count != npts_d && pairs && (double)count >= 2 * npts_d;
  aq_status s = aq_raw_file_alloc(raw, 1, name, err);
  if (s != AQ_OK)
    return s;
  aq_raw_channel *ch = &raw->chan[0];
  ch->npts = (size_t)npts_d;
  ch->dt_s = dt;
  ch->values = malloc(ch->npts * sizeof *ch->values);
  if (!ch->values) {
    aq_raw_file_free(raw);
    return aq_error_set(err, AQ_ENOMEM, name, -1, -1, "data", "out of memory");
  }
  size_t k = 0;
  double t0 = 0;
  aq_extra_rows x_rows; /* rows past NPTS: reported for the decision (record.c) */
  memset(&x_rows, 0, sizeof x_rows);
  while (k < ch->npts && aq_lines_next(&c, &ln)) {
    size_t pos = 0, len;
    double x[2];
    if (!is_pairs) {
      while (k < ch->npts && next_number(&ln, &pos, &len, &x[0]) == 1)
        ch->values[k++] = x[0];
      if (k == ch->npts) {
        aq_line rest = {ln.p + pos, ln.len - pos, ln.line};
        if (!aq_line_blank(&rest)) { /* more on NPTS's last line: no copy of a row */
          x_rows.values = aq_numbers_row(&rest, NULL);
          x_rows.rows = 1;
          x_rows.line = ln.line;
        }
      }
      continue;
    }
    if (next_number(&ln, &pos, &len, &x[0]) != 1)
      continue; /* a blank line */
    next_number(&ln, &pos, &len, &x[1]);
    if (k == 0)
      t0 = x[0];
    double want = t0 + (double)k * dt;
    if (!(fabs(x[0] - want) <= NPTSDT_TIME_TOL_REL * dt)) {
      aq_raw_file_free(raw);
      return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, "time",
                          "expected %.9g s (sample %zu at DT %g s from %.9g s), got %.9g s",
                          want, k + 1, dt, t0, x[0]);
    }
    ch->values[k++] = x[1];
  }
  if (x_rows.rows == 0)
    aq_extra_rows_scan(&c, &ln, NULL, NULL, &x_rows);
  aq_raw_set_extra(ch, &x_rows, is_pairs ? 2 : 1, "NPTS");
  ch->begin_s = t0;
  snprintf(raw->format, sizeof raw->format, "npts-dt");
  return AQ_OK;
}
