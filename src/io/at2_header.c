/* at2_header.c: the header of a PEER NGA .AT2 record (at2.c, at2_impl.h;
 * docs/at2-format.md): the units its text lines state, the NPTS/DT line in
 * each of its forms, where the values start, and the sniff that tells an
 * AT2 file from its header.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "at2_impl.h"
#include "fixed.h"
#include "number.h"
#include "reader.h"
#include "units.h"

/* "UNITS OF X" in the text lines: X as acceleration units.  Returns 1 with
 * *u set, 0 if no units are stated, -1 (word in *what) if X is not
 * acceleration. */
int aq_at2_header_units(const char *s, size_t n, aq_units *u, char *what, size_t cap)
{
  const char *p = aq_at2_find_ci(s, n, "UNITS OF");
  if (!p)
    return 0;
  p += 8;
  const char *end = s + n;
  while (p < end && *p == ' ')
    p++;
  size_t k = 0;
  char word[32];
  while (p + k < end && k + 1 < sizeof word && p[k] != ' ' && p[k] != ',' &&
         p[k] != '\t')
    word[k] = p[k], k++;
  while (k > 0 && (word[k - 1] == '.' || word[k - 1] == ';'))
    k--;
  word[k] = '\0';
  snprintf(what, cap, "%s", word);
  if (aq_units_parse(word, u) && *u != AQ_UNITS_COUNTS)
    return 1;
  return -1;
}

static int is_alpha(char ch) { return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z'); }

/* Keyword kw as a word (no letter on either side) in s[0..n), case-
 * insensitive: its offset, or -1. */
static long find_word(const char *s, size_t n, const char *kw)
{
  size_t m = strlen(kw);
  if (m > n)
    return -1;
  char k0 = kw[0], k0l = (char)(k0 | 0x20); /* kw's first letter, upper and lower */
  size_t last = n - m;                        /* the last place kw can start */
  /* candidates: the next k0 and the next k0l (memchr: most lines have neither) */
  const char *u = memchr(s, k0, last + 1), *l = memchr(s, k0l, last + 1);
  while (u || l) {
    const char *c = !l || (u && u < l) ? u : l;
    size_t i = (size_t)(c - s);
    if (strncasecmp(s + i, kw, m) == 0 && (i == 0 || !is_alpha(s[i - 1])) &&
        (i + m == n || !is_alpha(s[i + m])))
      return (long)i;
    if (c == u)
      u = i < last ? memchr(s + i + 1, k0, last - i) : NULL;
    else
      l = i < last ? memchr(s + i + 1, k0l, last - i) : NULL;
  }
  return -1;
}

/* A number token starting at s[i] and ending at a separator (blank, comma,
 * ';', end of line): 1 with *x and *end, else 0. */
static int num_at(const char *s, size_t n, size_t i, double *x, size_t *end)
{
  if (i >= n)
    return 0;
  size_t used = aq_decimal_parse(s + i, n - i, x);
  if (!used)
    return 0;
  size_t e = i + used;
  if (e < n && !(s[e] == ' ' || s[e] == '\t' || s[e] == ',' || s[e] == ';'))
    return 0;
  *end = e;
  return 1;
}

/* The number just after keyword end ke (blanks, '=' or ':' between). */
static int num_after(const char *s, size_t n, size_t ke, double *x, size_t *end)
{
  size_t i = ke;
  while (i < n && (s[i] == ' ' || s[i] == '\t' || s[i] == '=' || s[i] == ':'))
    i++;
  return num_at(s, n, i, x, end);
}

/* The number token ending just before offset kb (blanks and commas between). */
static int num_before(const char *s, size_t kb, double *x, size_t *start)
{
  size_t e = kb;
  while (e > 0 && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == ','))
    e--;
  size_t b = e;
  while (b > 0 && aq_at2_is_numchar(s[b - 1]))
    b--;
  size_t end;
  if (b == e || !num_at(s, e, b, x, &end) || end != e)
    return 0;
  *start = b;
  return 1;
}

/* Parse an NPTS/DT line s[0..n): NPTS and DT as words in either order, each
 * with its number after it ("NPTS= 4000, DT= .01 SEC", "dt: 0.01 npts 4000")
 * or before it ("4000 NPTS, .01 DT"), or the pair "NPTS, DT" after or before
 * two numbers ("4000 0.0100 NPTS, DT").  Returns 1 (*npts, *dt, *tail the
 * offset after the last thing used), 0 if the line has no NPTS word, -1 if
 * NPTS lacks its number, -2 if DT or its number is missing. */
int aq_at2_npts_line(const char *s, size_t n, double *npts, double *dt, size_t *tail)
{
  long kn = find_word(s, n, "NPTS");
  if (kn < 0)
    return 0;
  long kd = find_word(s, n, "DT");
  if (kd < 0)
    return -2;
  size_t k1 = (size_t)(kn < kd ? kn : kd), k2 = (size_t)(kn < kd ? kd : kn);
  size_t e1 = k1 + (kn < kd ? 4 : 2), e2 = k2 + (kn < kd ? 2 : 4);
  double v[2];
  size_t end = 0;
  int ok = 0;
  /* adjacent keywords ("NPTS, DT"): the pair of numbers after or before */
  size_t i = e1;
  while (i < k2 && (s[i] == ' ' || s[i] == '\t' || s[i] == ',' || s[i] == '/' ||
                    s[i] == '&'))
    i++;
  if (i == k2) {
    size_t e, j;
    if (num_after(s, n, e2, &v[0], &e)) {
      j = e;
      while (j < n && (s[j] == ' ' || s[j] == '\t' || s[j] == ','))
        j++;
      ok = num_at(s, n, j, &v[1], &end);
    }
    size_t b1, b0;
    if (!ok && num_before(s, k1, &v[1], &b1) && num_before(s, b1, &v[0], &b0)) {
      ok = 1;
      end = e2;
    }
  } else {
    size_t e, b;
    int g1 = num_after(s, k2, e1, &v[0], &e) || num_before(s, k1, &v[0], &b);
    int g2 = num_after(s, n, e2, &v[1], &end);
    if (!g2 && num_before(s, k2, &v[1], &b)) {
      g2 = 1;
      end = e2;
    }
    ok = g1 && g2;
    if (!ok) /* which keyword lacks its number */
      return (kn < kd ? !g1 : !g2) ? -1 : -2;
  }
  if (!ok)
    return -1;
  *npts = kn < kd ? v[0] : v[1];
  *dt = kn < kd ? v[1] : v[0];
  *tail = end;
  return 1;
}

/* A line that starts like values: its first non-blank character is a
 * digit, a point or a sign, and it has a digit. */
int aq_at2_data_line(const char *s, size_t n)
{
  size_t i = 0;
  while (i < n && (s[i] == ' ' || s[i] == '\t'))
    i++;
  if (i >= n || !(aq_at2_is_digit(s[i]) || s[i] == '.' || s[i] == '-' || s[i] == '+'))
    return 0;
  for (; i < n; i++)
    if (aq_at2_is_digit(s[i]))
      return 1;
  return 0;
}

int aq_at2_find_header(const char *s, size_t n, at2_header *h, long *bad_line,
                       size_t *bad_b, size_t *bad_e, int *bad_kind)
{
  at2_cur c = {s, n, 0, 1};
  if (n >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0)
    c.pos = 3;
  *bad_line = -1;
  h->ntext = 0;
  int found = 0, ntext = 0;
  for (int k = 0; k < AT2_MAX_HEADER_LINES && c.pos < c.n; k++) {
    long ln = c.line;
    size_t b, e;
    aq_at2_next_line(&c, &b, &e);
    double np = 0, dt = 0;
    size_t tail = 0;
    size_t fb = b;
    while (fb < e && (s[fb] == ' ' || s[fb] == '\t'))
      fb++;
    /* a commented line ('#', '%', '!') of another format is never the header */
    int r = fb < e && (s[fb] == '#' || s[fb] == '%' || s[fb] == '!')
                ? 0
                : aq_at2_npts_line(s + b, e - b, &np, &dt, &tail);
    if (r != 0) {
      at2_cur d = c; /* the next non-blank line */
      size_t db = d.pos, de = d.pos;
      long dl = d.line;
      while (d.pos < d.n) {
        dl = d.line;
        aq_at2_next_line(&d, &db, &de);
        size_t i = db;
        while (i < de && (s[i] == ' ' || s[i] == '\t'))
          i++;
        if (i < de)
          break;
      }
      if (aq_at2_data_line(s + db, de - db)) {
        /* the last such line is the header (earlier ones are quoted) */
        found = r > 0;
        if (r > 0) {
          h->line_b = b, h->line_e = e, h->line = ln;
          h->data_pos = db, h->data_line = dl;
          h->npts = np, h->dt = dt, h->tail = tail;
          h->ntext = ntext;
          *bad_line = -1;
        } else { /* the header by its place, but malformed */
          *bad_line = ln, *bad_b = b, *bad_e = e, *bad_kind = r;
        }
      }
    } else if ((found || *bad_line > 0) && fb < e &&
               (s[fb] == '*' || ((s[fb] | 0x20) == 'e' && (aq_at2_starts_ci(s + fb, e - fb, "end data") ||
                                                            aq_at2_starts_ci(s + fb, e - fb, "end of data"))))) {
      break; /* an end marker: the data is over */
    }
    if (fb < e && ntext < AT2_TEXT_LINES) {
      h->text_b[ntext] = b, h->text_e[ntext] = e;
      ntext++;
    }
  }
  return found;
}

int aq_at2_sniff(const unsigned char *buf, size_t n, size_t *text_lines_b,
                 size_t *text_lines_e, int *ntext, int max_text)
{
  at2_header h;
  long bl;
  size_t bb, be;
  int bk;
  if (!aq_at2_find_header((const char *)buf, n, &h, &bl, &bb, &be, &bk)) {
    *ntext = 0;
    return bl > 0; /* a malformed header is still AT2: the parser says why */
  }
  int m = h.ntext < max_text ? h.ntext : max_text;
  for (int i = 0; i < m; i++)
    text_lines_b[i] = h.text_b[i], text_lines_e[i] = h.text_e[i];
  *ntext = m;
  return 1;
}
