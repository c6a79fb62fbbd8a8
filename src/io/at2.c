/* at2.c: PEER NGA .AT2 reader (see readers.h; format notes in
 * docs/at2-format.md).
 *
 * Layout: three free-text lines (the third says "ACCELERATION TIME SERIES IN
 * UNITS OF G"), a line with NPTS and DT in one of the forms
 *     NPTS=   5372, DT=   .0100 SEC,        (NGA-West2, maybe filter text after)
 *     NPTS=  4000, DT= .01000 SEC           (older PEER)
 *     npts= 4000, dt= 0.01                  (lower case, no SEC)
 *     4000   0.0100   NPTS, DT              (NGA-West1: numbers first)
 * then NPTS values in g, any number per line, separated by blanks (or
 * commas), E-format possibly without a leading zero (-.6403182E-02) and
 * possibly glued to a following negative value or to an "End Data" marker.
 * NPTS is authoritative: reading stops after NPTS values.  Line ends may be
 * LF, CRLF or CR.
 */
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "../units.h"
#include "readers.h"

#define AT2_MAX_HEADER_LINES 6 /* the NPTS line is looked for in lines 1..6 */
#define AT2_TOKEN_MAX 64       /* longest number token accepted, characters */

typedef struct {
  const char *s;
  size_t n, pos;
  long line; /* 1-based line of pos */
} at2_cur;

/* Advance past one line end (LF, CRLF, CR, CR CR LF) at c->pos, if any. */
static int skip_eol(at2_cur *c)
{
  if (c->pos >= c->n)
    return 0;
  if (c->s[c->pos] == '\n') {
    c->pos++;
    c->line++;
    return 1;
  }
  if (c->s[c->pos] == '\r') {
    while (c->pos < c->n && c->s[c->pos] == '\r')
      c->pos++;
    if (c->pos < c->n && c->s[c->pos] == '\n')
      c->pos++;
    c->line++;
    return 1;
  }
  return 0;
}

/* The current line [*b, *e) and move to the next. */
static void next_line(at2_cur *c, size_t *b, size_t *e)
{
  *b = c->pos;
  while (c->pos < c->n && c->s[c->pos] != '\n' && c->s[c->pos] != '\r')
    c->pos++;
  *e = c->pos;
  skip_eol(c);
}

static const char *find_ci(const char *s, size_t n, const char *needle)
{
  size_t m = strlen(needle);
  for (size_t i = 0; i + m <= n; i++)
    if (strncasecmp(s + i, needle, m) == 0)
      return s + i;
  return NULL;
}

/* Copy s[0..n) into out (NUL-terminated, truncated to cap-1), for messages. */
static void quote(const char *s, size_t n, char *out, size_t cap)
{
  size_t k = 0;
  for (size_t i = 0; i < n && k + 1 < cap; i++)
    out[k++] = isprint((unsigned char)s[i]) ? s[i] : '?';
  out[k] = '\0';
}

static int is_digit(char c) { return c >= '0' && c <= '9'; }

static int is_numchar(char c)
{
  return is_digit(c) || c == '.' || c == '+' || c == '-' || c == 'e' || c == 'E';
}

static int is_sep(char c)
{
  return c == ' ' || c == '\t' || c == ',' || c == '\r' || c == '\n' || c == '\f' ||
         c == '\v' || c == '\0';
}

/* Exact powers of ten representable in a double. */
static const double pow10_exact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                       1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
#define AT2_FAST_MANTISSA_MAX 9007199254740992ULL /* 2^53 */

/* Parse a number starting at s[0..n) (blanks skipped first); the input is
 * not NUL-terminated.  Returns the characters consumed (0 if none), with
 * strtod's syntax (hexadecimal forms, nan and inf excluded).
 * Fast path (Clinger 1990): a decimal with at most 19 significant digits,
 * mantissa m <= 2^53 and decimal exponent |e| <= 22 is m * 10^e or m / 10^-e,
 * a single correctly rounded operation on two exact doubles, so the result
 * is the same double strtod gives.  Anything else is copied to a local
 * buffer and given to strtod. */
static size_t parse_num(const char *s, size_t n, double *x)
{
  size_t i = 0;
  while (i < n && (s[i] == ' ' || s[i] == '\t'))
    i++;
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
  {
    size_t j = i;
    int neg = 0, nd = 0, anyd = 0, slow = 0;
    long frac = 0;
    uint64_t m = 0;
    if (j < n && (s[j] == '+' || s[j] == '-'))
      neg = s[j++] == '-';
    for (int part = 0; part < 2; part++) {
      while (j < n && is_digit(s[j])) {
        int d = s[j++] - '0';
        anyd = 1;
        if (part)
          frac++;
        if (m == 0 && d == 0)
          continue; /* leading zeros are not significant */
        if (nd >= 19) {
          slow = 1;
          continue;
        }
        m = m * 10 + (uint64_t)d;
        nd++;
      }
      if (part == 0) {
        if (j < n && s[j] == '.')
          j++;
        else
          break;
      }
    }
    if (anyd && !slow) {
      long e = 0;
      if (j < n && (s[j] == 'e' || s[j] == 'E')) {
        size_t k = j + 1;
        int eneg = 0, ed = 0;
        if (k < n && (s[k] == '+' || s[k] == '-'))
          eneg = s[k++] == '-';
        while (k < n && is_digit(s[k]) && ed < 6)
          e = e * 10 + (s[k++] - '0'), ed++;
        if (k < n && is_digit(s[k]))
          slow = 1; /* a huge exponent: strtod decides */
        if (ed) {
          j = k;
          e = eneg ? -e : e;
        } else {
          e = 0; /* "1.5e" is 1.5 followed by "e" */
        }
      }
      e -= frac;
      if (!slow && m <= AT2_FAST_MANTISSA_MAX && e >= -22 && e <= 22) {
        double v = (double)m;
        v = e < 0 ? v / pow10_exact[-e] : v * pow10_exact[e];
        *x = neg ? -v : v;
        return j;
      }
    }
  }
#endif
  char tok[AT2_TOKEN_MAX];
  size_t k = 0;
  while (i + k < n && k + 1 < sizeof tok && is_numchar(s[i + k]))
    tok[k] = s[i + k], k++;
  tok[k] = '\0';
  if (k == 0)
    return 0;
  char *end;
  errno = 0;
  *x = strtod(tok, &end);
  if (end == tok)
    return 0;
  return i + (size_t)(end - tok);
}

/* "UNITS OF X" in the text lines: X as acceleration units.  Returns 1 with
 * *u set, 0 if no units are stated, -1 (word in *what) if X is not
 * acceleration. */
static int header_units(const char *s, size_t n, aq_units *u, char *what, size_t cap)
{
  const char *p = find_ci(s, n, "UNITS OF");
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

aq_status aq_at2_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_read_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts; /* an AT2 file states everything it can */
  memset(raw, 0, sizeof *raw);
  at2_cur c = {(const char *)buf, n, 0, 1};
  size_t lb[AT2_MAX_HEADER_LINES], le[AT2_MAX_HEADER_LINES];
  long npts_line = -1;
  int nlines = 0;
  while (nlines < AT2_MAX_HEADER_LINES && c.pos < c.n) {
    long this_line = c.line;
    next_line(&c, &lb[nlines], &le[nlines]);
    nlines++;
    if (find_ci(c.s + lb[nlines - 1], le[nlines - 1] - lb[nlines - 1], "NPTS")) {
      npts_line = this_line;
      break;
    }
  }
  if (npts_line < 0)
    return aq_error_set(err, AQ_EFORMAT, name, -1, -1, "NPTS",
                        "expected a line with NPTS and DT among the first %d "
                        "lines, found none",
                        AT2_MAX_HEADER_LINES);
  const char *hl = c.s + lb[nlines - 1];
  size_t hn = le[nlines - 1] - lb[nlines - 1];
  char got[80];
  quote(hl, hn, got, sizeof got);

  /* NPTS and DT. */
  double npts_d = -1, dt = -1;
  const char *pn = find_ci(hl, hn, "NPTS");
  const char *q = pn + 4;
  while (q < hl + hn && (*q == ' ' || *q == '\t'))
    q++;
  if (q < hl + hn && (*q == '=' || *q == ':')) {
    size_t used = parse_num(q + 1, (size_t)(hl + hn - q - 1), &npts_d);
    const char *after = q + 1 + used;
    if (!used || (after < hl + hn && (isalnum((unsigned char)*after) || *after == '.')))
      return aq_error_set(err, AQ_EFORMAT, name, npts_line, -1, "NPTS",
                          "expected NPTS= a positive integer, got \"%s\"", got);
    const char *pd = NULL;
    for (const char *r = q + 1 + used; r + 2 <= hl + hn; r++)
      if ((r[0] == 'D' || r[0] == 'd') && (r[1] == 'T' || r[1] == 't')) {
        const char *t = r + 2;
        while (t < hl + hn && (*t == ' ' || *t == '\t'))
          t++;
        if (t < hl + hn && (*t == '=' || *t == ':')) {
          pd = t + 1;
          break;
        }
      }
    if (!pd || !parse_num(pd, (size_t)(hl + hn - pd), &dt))
      return aq_error_set(err, AQ_EFORMAT, name, npts_line, -1, "DT",
                          "expected DT= the sample interval in s, got \"%s\"", got);
  } else { /* NGA-West1: "4000   0.0100   NPTS, DT" */
    size_t used = parse_num(hl, (size_t)(pn - hl), &npts_d);
    size_t used2 = used ? parse_num(hl + used, (size_t)(pn - hl) - used, &dt) : 0;
    if (!used || !used2)
      return aq_error_set(err, AQ_EFORMAT, name, npts_line, -1, "NPTS",
                          "expected \"NPTS= N, DT= S\" or \"N S NPTS, DT\", got \"%s\"",
                          got);
  }
  if (!(npts_d >= 1) || npts_d != floor(npts_d) || npts_d > 1e12)
    return aq_error_set(err, AQ_EFORMAT, name, npts_line, -1, "NPTS",
                        "expected a positive integer, got \"%s\"", got);
  if (!isfinite(dt) || !(dt > 0))
    return aq_error_set(err, AQ_EFORMAT, name, npts_line, -1, "DT",
                        "expected a sample interval > 0 s, got \"%s\"", got);
  size_t npts = (size_t)npts_d;

  /* Units: the text lines say "UNITS OF G"; an AT2 file is in g by its
   * definition when they say nothing. */
  char ustated[24] = "g", usaid[64] = "";
  long uline = -1;
  for (int k = 0; k + 1 < nlines; k++) {
    aq_units hu;
    char uword[32] = "";
    int r = header_units(c.s + lb[k], le[k] - lb[k], &hu, uword, sizeof uword);
    if (r == 1) {
      snprintf(ustated, sizeof ustated, "%s", aq_units_name(hu));
      uline = k + 1;
      break;
    }
    if (r < 0) {
      ustated[0] = '\0';
      snprintf(usaid, sizeof usaid, "line %d: UNITS OF %s", k + 1, uword);
      uline = k + 1;
      break;
    }
  }

  /* Each value takes at least one character and one separator. */
  size_t room = (c.n - c.pos + 1) / 2;
  if (npts > room)
    return aq_error_set(err, AQ_EFORMAT, name, npts_line, -1, "NPTS",
                        "expected at most %zu values in the %zu bytes that "
                        "follow, got NPTS = %zu",
                        room, c.n - c.pos, npts);
  double *acc = malloc(npts * sizeof *acc);
  if (!acc)
    return aq_error_set(err, AQ_ENOMEM, name, -1, -1, NULL,
                        "out of memory for %zu samples", npts);

  size_t k = 0;
  char field[40], tokq[AT2_TOKEN_MAX + 8];
  while (k < npts) {
    /* separators */
    while (c.pos < c.n) {
      char ch = c.s[c.pos];
      if (ch == ' ' || ch == '\t' || ch == ',' || ch == '\f' || ch == '\v')
        c.pos++;
      else if (!skip_eol(&c))
        break;
    }
    if (c.pos >= c.n)
      break;
    const char *t = c.s + c.pos;
    size_t avail = c.n - c.pos, tl = 0;
    while (tl < avail && !is_sep(t[tl]))
      tl++;
    if (tl == 0)
      tl = 1; /* a NUL byte */
    if ((t[0] == 'e' || t[0] == 'E') && tl >= 3 && strncasecmp(t, "end", 3) == 0)
      break; /* "End Data" marker */
    double x;
    size_t used = parse_num(t, tl, &x);
    int bad = !used || !isfinite(x);
    if (!bad && used < tl) {
      char nx = t[used];
      bad = !(nx == '-' || nx == '+' ||
              (tl - used >= 3 && strncasecmp(t + used, "end", 3) == 0));
    }
    if (bad) { /* the message's parts, only on the error path */
      snprintf(field, sizeof field, "value %zu", k + 1);
      quote(t, tl < AT2_TOKEN_MAX ? tl : AT2_TOKEN_MAX, tokq, sizeof tokq);
    }
    if (!used) {
      free(acc);
      if ((tl >= 3 && (strncasecmp(t, "nan", 3) == 0 || strncasecmp(t, "inf", 3) == 0)) ||
          (tl >= 4 && (strncasecmp(t + 1, "nan", 3) == 0 || strncasecmp(t + 1, "inf", 3) == 0)))
        return aq_error_set(err, AQ_EVALUE, name, c.line, -1, field,
                            "expected a finite number, got \"%s\"", tokq);
      return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, field,
                          "expected a number, got \"%s\"", tokq);
    }
    if (used < tl) {
      char nx = t[used];
      int glued_value = nx == '-' || nx == '+';
      int glued_end = tl - used >= 3 && strncasecmp(t + used, "end", 3) == 0;
      if (!glued_value && !glued_end) {
        free(acc);
        if (c.pos + tl == c.n) /* cut off in the middle of a value */
          return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "NPTS",
                              "expected %zu values (NPTS, line %ld), got %zu and "
                              "a cut-off \"%s\" at the end: file truncated",
                              npts, npts_line, k, tokq);
        return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, field,
                            "expected a number, got \"%s\"", tokq);
      }
    }
    if (!isfinite(x)) {
      free(acc);
      return aq_error_set(err, AQ_EVALUE, name, c.line, -1, field,
                          "expected a finite number, got \"%s\"", tokq);
    }
    acc[k] = x;
    k++;
    c.pos += used;
  }
  if (k < npts) {
    free(acc);
    return aq_error_set(err, AQ_EFORMAT, name, c.line, -1, "NPTS",
                        "expected %zu values (NPTS, line %ld), got %zu: file "
                        "truncated or NPTS too large",
                        npts, npts_line, k);
  }
  aq_status s = aq_raw_file_alloc(raw, 1, name, err);
  if (s != AQ_OK) {
    free(acc);
    return s;
  }
  snprintf(raw->format, sizeof raw->format, "at2");
  aq_raw_channel *ch = &raw->chan[0];
  ch->npts = npts;
  ch->dt_s = dt;
  ch->begin_s = 0.0;
  snprintf(ch->units, sizeof ch->units, "%s", ustated);
  snprintf(ch->units_said, sizeof ch->units_said, "%s", usaid);
  ch->units_line = uline;
  ch->values = acc;
  return AQ_OK;
}
