/* fixed.c: line cursor, fixed-width Fortran fields and dates (see fixed.h). */
#define _DEFAULT_SOURCE /* timegm(3): glibc declares it only with this */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "fixed.h"
#include "number.h"

#define FIELD_MAX 64 /* longest numeric field accepted, characters */

size_t aq_text_line_end(const char *s, size_t i, size_t n)
{
  while (i < n && s[i] != '\n' && s[i] != '\r')
    i++;
  return i;
}

const char *aq_text_past_eol(const char *p, const char *end)
{
  if (*p == '\r') {
    while (p < end && *p == '\r')
      p++;
    if (p < end && *p == '\n')
      p++;
    return p;
  }
  return p + 1;
}

int aq_text_line(const char *s, size_t n, size_t *pos, size_t *b, size_t *e)
{
  size_t p = *pos;
  if (p >= n)
    return 0;
  *b = p;
  p = aq_text_line_end(s, p, n);
  *e = p;
  if (p < n)
    p = (size_t)(aq_text_past_eol(s + p, s + n) - s);
  *pos = p;
  return 1;
}

void aq_lines_init(aq_lines *c, const unsigned char *buf, size_t n)
{
  c->s = (const char *)buf;
  c->n = n;
  c->pos = 0;
  c->line = 1;
}

int aq_lines_at_end(const aq_lines *c)
{
  for (size_t i = c->pos; i < c->n; i++) {
    char ch = c->s[i];
    if (ch != ' ' && ch != '\t' && ch != '\r' && ch != '\n' && ch != 0x1A)
      return 0;
  }
  return 1;
}

int aq_line_blank(const aq_line *ln)
{
  for (size_t i = 0; i < ln->len; i++)
    if (ln->p[i] != ' ' && ln->p[i] != '\t')
      return 0;
  return 1;
}

int aq_lines_next(aq_lines *c, aq_line *out)
{
  size_t b, e;
  if (aq_lines_at_end(c) || !aq_text_line(c->s, c->n, &c->pos, &b, &e))
    return 0;
  out->p = c->s + b;
  out->len = e - b;
  out->line = c->line++;
  return 1;
}

int aq_fortran_fmt_find(const char *s, size_t n, aq_fortran_fmt *f)
{
  const char *open = memchr(s, '(', n);
  if (!open)
    return 0;
  size_t i = (size_t)(open - s) + 1;
  while (i < n && s[i] == ' ')
    i++;
  long per = 0, w = 0;
  int nd = 0;
  while (i < n && isdigit((unsigned char)s[i]) && nd < 4) {
    per = per * 10 + (s[i++] - '0');
    nd++;
  }
  if (nd == 0)
    per = 1;
  if (i >= n)
    return 0;
  char k = (char)toupper((unsigned char)s[i++]);
  if (k != 'I' && k != 'F' && k != 'E')
    return 0;
  nd = 0;
  while (i < n && isdigit((unsigned char)s[i]) && nd < 4) {
    w = w * 10 + (s[i++] - '0');
    nd++;
  }
  if (per < 1 || w < 1 || w > FIELD_MAX)
    return 0;
  f->per_line = (int)per;
  f->width = (int)w;
  f->kind = k;
  return 1;
}

int aq_fortran_descriptor(const char *s, size_t n)
{
  size_t i = 0;
  while (i < n && isdigit((unsigned char)s[i]))
    i++;
  if (i >= n || !strchr("FEIGfeig", s[i]))
    return 0;
  size_t d = ++i;
  while (i < n && isdigit((unsigned char)s[i]))
    i++;
  if (i == d)
    return 0;
  if (i < n && s[i] == '.') {
    d = ++i;
    while (i < n && isdigit((unsigned char)s[i]))
      i++;
    if (i == d)
      return 0;
  }
  return i == n;
}

int aq_field_double(const char *s, size_t n, double *out)
{
  while (n > 0 && (*s == ' ' || *s == '\t')) {
    s++;
    n--;
  }
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t'))
    n--;
  double v;
  if (n == 0 || n >= FIELD_MAX || aq_number_parse_finite(s, n, 0, &v) != n)
    return 0;
  *out = v;
  return 1;
}

int aq_header_int(double v)
{
  return v >= -1e9 && v <= 1e9 ? (int)v : -1;
}

size_t aq_next_word(const char **p, const char *end, const char *stops)
{
  const char *b = *p;
  while (b < end && *b == ' ')
    b++;
  const char *e = b;
  while (e < end && *e != ' ' && !strchr(stops, *e))
    e++;
  *p = b;
  return (size_t)(e - b);
}

void aq_copy_trim(char *out, size_t cap, const char *s, size_t n)
{
  while (n > 0 && isspace((unsigned char)*s)) {
    s++;
    n--;
  }
  while (n > 0 && isspace((unsigned char)s[n - 1]))
    n--;
  if (cap == 0)
    return;
  size_t k = 0;
  for (size_t i = 0; i < n && k + 1 < cap; i++)
    out[k++] = isprint((unsigned char)s[i]) ? s[i] : '?';
  out[k] = '\0';
}

const char *aq_find_ci(const char *s, size_t n, const char *needle)
{
  size_t m = strlen(needle);
  for (size_t i = 0; i + m <= n; i++)
    if (strncasecmp(s + i, needle, m) == 0)
      return s + i;
  return NULL;
}

aq_status aq_fixed_read(aq_lines *c, size_t count, const aq_fortran_fmt *f,
                        double *out, const char *name, const char *what,
                        aq_error *err)
{
  aq_line last;
  return aq_fixed_read_last(c, count, f, out, name, what, &last, err);
}

size_t aq_fixed_row(const aq_line *ln, const void *ctx)
{
  const aq_fortran_fmt *f = ctx;
  size_t w = (size_t)f->width, len = ln->len;
  while (len > 0 && (ln->p[len - 1] == ' ' || ln->p[len - 1] == '\t'))
    len--;
  if (w == 0 || len == 0 || len % w != 0 || len / w > (size_t)f->per_line)
    return 0;
  for (size_t b = 0; b < len; b += w) {
    double v;
    if (!aq_field_double(ln->p + b, w, &v))
      return 0;
  }
  return len / w;
}

aq_status aq_fixed_read_last(aq_lines *c, size_t count, const aq_fortran_fmt *f,
                             double *out, const char *name, const char *what,
                             aq_line *last, aq_error *err)
{
  size_t k = 0;
  memset(last, 0, sizeof *last);
  size_t w = (size_t)f->width;
  while (k < count) {
    aq_line ln;
    if (!aq_lines_next(c, &ln))
      return aq_error_set(err, AQ_EFORMAT, name, c->line, -1, what,
                          "expected %zu values, the file ends after %zu", count, k);
    size_t nf = count - k < (size_t)f->per_line ? count - k : (size_t)f->per_line;
    *last = ln;
    for (size_t j = 0; j < nf; j++, k++) {
      size_t b = j * w;
      if (b >= ln.len)
        return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, what,
                            "value %zu: expected %zu values of %zu columns on this "
                            "line, got a line of %zu characters",
                            k + 1, nf, w, ln.len);
      size_t e = b + w < ln.len ? b + w : ln.len;
      if (!aq_field_double(ln.p + b, e - b, &out[k])) {
        char got[FIELD_MAX + 1];
        aq_copy_trim(got, sizeof got, ln.p + b, e - b);
        return aq_error_set(err, AQ_EFORMAT, name, ln.line, -1, what,
                            "value %zu (columns %zu-%zu): expected a number, got \"%s\"",
                            k + 1, b + 1, e, got);
      }
    }
  }
  return AQ_OK;
}

size_t aq_numbers_row(const aq_line *ln, const void *ctx)
{
  (void)ctx;
  size_t n = 0, i = 0;
  while (i < ln->len) {
    while (i < ln->len && (ln->p[i] == ' ' || ln->p[i] == '\t'))
      i++;
    size_t b = i;
    while (i < ln->len && ln->p[i] != ' ' && ln->p[i] != '\t')
      i++;
    double v;
    if (i > b && !aq_field_double(ln->p + b, i - b, &v))
      return 0;
    n += i > b;
  }
  return n;
}

/* s[0..n) without the blanks around it: its start and length. */
static const char *trimmed(const char *s, size_t n, size_t *len)
{
  while (n > 0 && (*s == ' ' || *s == '\t'))
    s++, n--;
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t'))
    n--;
  *len = n;
  return s;
}

void aq_extra_rows_scan(aq_lines *c, const aq_line *last, aq_row_fn *row, const void *ctx,
                        aq_extra_rows *x)
{
  memset(x, 0, sizeof *x);
  x->repeat = 1;
  size_t ll = 0;
  const char *lp = last ? trimmed(last->p, last->len, &ll) : "";
  for (;;) {
    aq_lines at = *c;
    aq_line ln;
    if (!aq_lines_next(&at, &ln))
      break;
    if (!aq_line_blank(&ln)) {
      size_t nv = row ? row(&ln, ctx) : aq_numbers_row(&ln, ctx);
      if (nv == 0)
        break;
      size_t tl;
      const char *tp = trimmed(ln.p, ln.len, &tl);
      if (x->rows++ == 0)
        x->line = ln.line;
      x->values += nv;
      x->repeat &= last && tl == ll && memcmp(tp, lp, tl) == 0;
    }
    *c = at;
  }
  if (x->rows == 0)
    x->repeat = 0;
}

int aq_line_names_accelerogram(const aq_line *ln)
{
  return aq_find_ci(ln->p, ln->len, "accelerogram") != NULL;
}

int aq_zone_offset(const char *s, size_t n, int *hours_east)
{
  static const struct {
    const char *word;
    int east_h;
  } zones[] = {{"UTC", 0},  {"GMT", 0},  {"UT", 0},  {"PDT", -7}, {"PST", -8},
               {"MDT", -6}, {"MST", -7}, {"CDT", -5}, {"CST", -6}, {"EDT", -4},
               {"EST", -5}, {"JST", 9}};
  for (size_t i = 0; i < sizeof zones / sizeof zones[0]; i++)
    if (strlen(zones[i].word) == n && strncasecmp(s, zones[i].word, n) == 0) {
      *hours_east = zones[i].east_h;
      return 1;
    }
  return 0;
}

/* ---- calendar: timegm(3) and gmtime_r(3) -------------------------------- */

/* Seconds since 1970-01-01T00:00:00Z of midnight (UTC) of year-month-day,
 * where day may run past the month (a day of the year as the day of
 * January): timegm normalises it.  Returns 1, or 0 if timegm fails. */
static int utc_midnight_s(int year, int month, int day, long long *t)
{
  struct tm tm;
  memset(&tm, 0, sizeof tm);
  tm.tm_year = year - 1900;
  tm.tm_mon = month - 1;
  tm.tm_mday = day;
  time_t s = timegm(&tm);
  if (s == (time_t)-1) /* midnight is never the second before 1970 */
    return 0;
  *t = (long long)s;
  return 1;
}

int aq_month_day(int year, int jday, int *month, int *day)
{
  long long t;
  if (year < 1800 || year > 2200 || jday < 1 || jday > 366 || !utc_midnight_s(year, 1, jday, &t))
    return 0;
  time_t s = (time_t)t;
  struct tm tm;
  if (!gmtime_r(&s, &tm) || tm.tm_year + 1900 != year)
    return 0;
  *month = tm.tm_mon + 1;
  *day = tm.tm_mday;
  return 1;
}

/* ISO-8601 of a date and a time of day in ms that may fall outside the day
 * (negative: days before; beyond 24 h: days after). */
static int iso_from_day_ms(char *out, size_t cap, int year, int month, int day, long tod_ms)
{
  long long t;
  return utc_midnight_s(year, month, day, &t) && aq_iso_from_ms(out, cap, t * 1000 + tod_ms);
}

static int date_ok(int year, int month, int day, int minute, double sec)
{
  return year >= 1800 && year <= 2200 && month >= 1 && month <= 12 && day >= 1 &&
         day <= 31 && minute >= 0 && minute <= 59 && sec >= 0 && sec < 61;
}

int aq_iso_time(char *out, size_t cap, int year, int month, int day, int hour,
                int minute, double sec)
{
  if (!date_ok(year, month, day, minute, sec) || hour < 0 || hour > 48)
    return 0;
  return iso_from_day_ms(out, cap, year, month, day,
                         ((long)hour * 60 + minute) * 60000L + lround(sec * 1000.0));
}

int aq_iso_time_local(char *out, size_t cap, int year, int month, int day, int hour,
                      int minute, double sec, int east_h)
{
  if (!date_ok(year, month, day, minute, sec) || hour < 0 || hour > 24 || east_h < -14 ||
      east_h > 14)
    return 0;
  return iso_from_day_ms(out, cap, year, month, day,
                         ((long)(hour - east_h) * 60 + minute) * 60000L + lround(sec * 1000.0));
}

int aq_iso_parse(const char *s, double *epoch_s)
{
  int y, mo, d, h = 0, mi = 0, used = 0;
  double sec = 0;
  if (sscanf(s, "%4d-%2d-%2d%n", &y, &mo, &d, &used) != 3)
    return 0;
  const char *t = s + used;
  if (*t == 'T' || *t == ' ') {
    if (sscanf(t + 1, "%2d:%2d:%lf", &h, &mi, &sec) < 2)
      return 0;
  }
  if (y < 1 || y > 9999 || mo < 1 || mo > 12 || d < 1 || d > 31 || h < 0 || h > 24 ||
      mi < 0 || mi > 59 || !(sec >= 0 && sec < 61))
    return 0;
  long long day_s;
  if (!utc_midnight_s(y, mo, d, &day_s))
    return 0;
  *epoch_s = (double)day_s + h * 3600.0 + mi * 60.0 + sec;
  return 1;
}

int aq_iso_from_ms(char *out, size_t cap, long long ms)
{
  long long days = ms >= 0 ? ms / 86400000LL : -((-ms + 86399999LL) / 86400000LL);
  long long tod = ms - days * 86400000LL; /* 0 .. 86399999 */
  if (days < -100000 || days > 3000000)
    return 0;
  time_t s = (time_t)(days * 86400LL);
  struct tm tm;
  if (!gmtime_r(&s, &tm))
    return 0;
  snprintf(out, cap, "%04d-%02d-%02dT%02lld:%02lld:%02lld.%03lldZ", tm.tm_year + 1900,
           tm.tm_mon + 1, tm.tm_mday, tod / 3600000LL, (tod / 60000LL) % 60,
           (tod / 1000LL) % 60, tod % 1000LL);
  return 1;
}
