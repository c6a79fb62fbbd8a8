/* csv_rows.c: the data rows of a CSV / plain-text record (csv.c,
 * csv_impl.h): the arrays they are read into, the fast reading of rows of
 * plain decimals (each column by its learnt shape, number.h), the line of
 * a row for messages, and the steps of a time column.
 */
#include <math.h>
#include <stdlib.h>

#include "csv_impl.h"
#include "fixed.h"
#include "number.h"

int aq_csv_rows_grow(csv_rows *r, size_t cap, int with_time)
{
  for (size_t j = 0; j < r->raw->nchan; j++) {
    double *v = realloc(r->raw->chan[j].values, cap * sizeof *v);
    if (!v)
      return 0;
    r->raw->chan[j].values = v;
  }
  if (with_time) {
    double *t = realloc(r->tt, cap * sizeof *t);
    if (!t)
      return 0;
    r->tt = t;
  }
  r->cap = cap;
  return 1;
}

void aq_csv_rows_free_time(csv_rows *r)
{
  free(r->tt);
  r->tt = NULL;
}

/* The line of row idx (0-based), the rows counted as the reading counts
 * them: the lines that are not blank once a '#' comment is cut, from the
 * first row's line (line0, starting at pos) on; -1 if there are fewer.
 * Only for messages: the rows' lines are not kept while reading. */
long aq_csv_row_line(const char *s, size_t n, size_t pos, long line0, size_t idx)
{
  long line = line0 - 1;
  size_t b, e, row = 0;
  while (aq_text_line(s, n, &pos, &b, &e)) {
    line++;
    aq_csv_trim_line(s, &b, &e);
    if (b < e && row++ == idx)
      return line;
  }
  return -1;
}

/* The bytes a shaped read needs from a field's start: a sign and the 16 the
 * shape's load reads (which hold the byte after the number, len <= 15). */
#define CSV_SHAPED_ROOM (1 + AQ_NUMBER_SHAPE_WINDOW)

/* The rows from *pp on that are numbers and separators only: ncols (a
 * constant where inlined) finite plain decimals separated by sep (not ' '),
 * nothing around them, then LF, CRLF, CR (or CRs then LF) or the end of the
 * input, each number read as plain_rows reads it (by its column's shape
 * when it fits, else the general reading, which learns the shape); into
 * the arrays from row k on.  Stops at the first row that is not so
 * (plain_rows reads it the general way) or at cap; returns the new k, with
 * *pp after the last row taken.  A row that stops part way may have
 * written values to row k: the row that fills k later overwrites them. */
static inline size_t bare_rows(const char **pp, const char *end, size_t ncols, char sep,
                               aq_number_shape *shape, double *const *dst, size_t k,
                               size_t cap)
{
  const char *p = *pp;
  while (k < cap) {
    const char *q = p;
    size_t i = 0;
    for (; i < ncols; i++) {
      aq_number_shape *sh = &shape[i];
      double x;
#if AQ_NUMBER_SHAPES
      size_t off = q < end && (*q == '-' || *q == '+');
      if (end - q >= CSV_SHAPED_ROOM && sh->len && aq_number_shape_read_(sh, q, off, &x)) {
        q += off + sh->len;
        if (sh->misses) /* as aq_number_parse_shaped does */
          sh->misses = 0;
      } else
#endif
      {
        size_t used = aq_number_parse_unshaped_(sh, q, (size_t)(end - q), 0, &x);
        if (!used)
          break;
        q += used;
      }
      if (i + 1 < ncols) {
        if (q >= end || *q != sep)
          break;
        q++;
      } else if (q < end && (*q == '\n' || *q == '\r')) {
        q = aq_text_past_eol(q, end);
      } else if (q < end) {
        break;
      }
      if (dst[i])
        dst[i][k] = x;
    }
    if (i < ncols)
      break;
    k++;
    p = q;
    if (p >= end)
      break;
  }
  *pp = p;
  return k;
}

/* The rows from c->pos on that are plain: ncols finite plain decimals, with
 * blanks (and tabs, unless sep is the tab) around them, separated by sep,
 * and a line end (LF, CRLF, CR, CR CR LF, or the end of the input) after
 * the last; into the arrays from row k on, bare rows (bare_rows) first.
 * Returns the new k, with c after the last row taken; any other line
 * (blank, a comment, quotes, a bad or missing field) is left to the
 * general reading, which reads it exactly as before. */
size_t aq_csv_plain_rows(csv_cur *c, const plain_row *pr, csv_rows *rows, size_t k)
{
  const char *s = c->s, *end = s + c->n;
  const char *p = s + c->pos;
  double *dst[CSV_COLS_MAX]; /* where each column's values go (NULL: nowhere) */
  for (size_t i = 0; i < pr->ncols; i++)
    dst[i] = pr->chof[i] >= 0 ? rows->raw->chan[pr->chof[i]].values
             : (long)i == pr->tcol ? rows->tt
                                   : NULL;
  size_t k0 = k;
  while (p < end && k < rows->cap) {
    if (pr->sep != ' ') { /* the common rows first */
      if (pr->ncols == 2) /* (time, acceleration): its own loop */
        k = bare_rows(&p, end, 2, pr->sep, pr->shape, dst, k, rows->cap);
      else
        k = bare_rows(&p, end, pr->ncols, pr->sep, pr->shape, dst, k, rows->cap);
      if (p >= end || k >= rows->cap)
        break;
    }
    const char *q = p;
    size_t i = 0;
    for (; i < pr->ncols; i++) {
      const char *fb = q;
      while (q < end && (*q == ' ' || (*q == '\t' && pr->sep != '\t')))
        q++;
      if (i > 0 && pr->sep == ' ' && q == fb)
        break; /* blank-separated fields need a blank between */
      double x;
      size_t used = aq_number_parse_shaped(&pr->shape[i], q, (size_t)(end - q), 0, &x);
      if (!used)
        break;
      q += used;
      while (q < end && (*q == ' ' || (*q == '\t' && pr->sep != '\t')))
        q++;
      if (i + 1 < pr->ncols) {
        if (pr->sep != ' ') {
          if (q >= end || *q != pr->sep)
            break;
          q++;
        }
      } else if (q < end && *q != '\n' && *q != '\r') {
        break;
      }
      if (dst[i])
        dst[i][k] = x;
    }
    if (i < pr->ncols)
      break; /* not plain: values written to row k are overwritten later */
    if (q < end) /* at LF or CR: the last field was checked above */
      q = aq_text_past_eol(q, end);
    k++;
    p = q;
  }
  c->line += (long)(k - k0); /* one line per row */
  c->pos = (size_t)(p - s);
  return k;
}

/* The k-th smallest of d[0..n) (Hoare's selection; d is reordered). */
static double select_kth(double *d, size_t n, size_t k)
{
  size_t lo = 0, hi = n - 1;
  while (lo < hi) {
    double pivot = d[lo + (hi - lo) / 2];
    size_t i = lo, j = hi;
    while (i <= j) {
      while (d[i] < pivot)
        i++;
      while (d[j] > pivot)
        j--;
      if (i <= j) {
        double t = d[i];
        d[i] = d[j];
        d[j] = t;
        i++;
        if (j == 0)
          break;
        j--;
      }
    }
    if (k <= j)
      hi = j;
    else if (k >= i)
      lo = i;
    else
      return d[k];
  }
  return d[k];
}

/* The smallest and largest of the n - 1 steps of t, and the first i
 * (0 if none) where |t_i - (t_0 + i est)| > tol, in one pass. */
size_t aq_csv_step_range(const double *t, size_t n, double est, double tol, double *lo,
                         double *hi)
{
  double a = INFINITY, b = -INFINITY;
  size_t off = 0;
  for (size_t i = 1; i < n; i++) {
    double d = t[i] - t[i - 1];
    a = d < a ? d : a;
    b = d > b ? d : b;
    if (fabs(t[i] - (t[0] + (double)i * est)) > tol && !off)
      off = i;
  }
  *lo = a;
  *hi = b;
  return off;
}

/* Median of the n - 1 steps of t (NaN if out of memory): the upper median,
 * element (n - 1) / 2 of the sorted steps. */
double aq_csv_median_step(const double *t, size_t n)
{
  double *d = malloc((n - 1) * sizeof *d);
  if (!d)
    return NAN;
  for (size_t i = 1; i < n; i++)
    d[i - 1] = t[i] - t[i - 1];
  double m = select_kth(d, n - 1, (n - 1) / 2);
  free(d);
  return m;
}
