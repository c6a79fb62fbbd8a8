/* at2.c: PEER NGA .AT2 reader (see reader.h; format notes in
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
 * LF, CRLF or CR.  The header (units, the NPTS/DT line, the sniff) is read
 * in at2_header.c.
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "../units.h"
#include "fixed.h"
#include "number.h"
#include "reader.h"
#include "units.h"
#include "at2_impl.h"

#if defined(__SSE2__) && !defined(AQ_NO_SIMD)
#include <emmintrin.h>
#endif

#define AT2_CHANNEL_MAX 6       /* a component name is short ("180", "UP", "HN1") */
#define AT2_TOKEN_MAX 64       /* longest number token accepted, characters */

/* Advance past one line end (LF, CRLF, CR, CR CR LF) at c->pos, if any. */
static int skip_eol(at2_cur *c)
{
  if (c->pos >= c->n)
    return 0;
  if (c->s[c->pos] != '\n' && c->s[c->pos] != '\r')
    return 0;
  c->pos = (size_t)(aq_text_past_eol(c->s + c->pos, c->s + c->n) - c->s);
  c->line++;
  return 1;
}

/* The current line [*b, *e) and move to the next. */
void aq_at2_next_line(at2_cur *c, size_t *b, size_t *e)
{
  *b = c->pos;
  c->pos = aq_text_line_end(c->s, c->pos, c->n);
  *e = c->pos;
  skip_eol(c);
}

const char *aq_at2_find_ci(const char *s, size_t n, const char *needle)
{
  size_t m = strlen(needle);
  char c0 = (char)(needle[0] | 0x20); /* lower case of a letter (or itself) */
  for (size_t i = 0; i + m <= n; i++)
    if ((char)(s[i] | 0x20) == c0 && strncasecmp(s + i, needle, m) == 0)
      return s + i;
  return NULL;
}

/* 1 if s[0..n) starts with needle, case-insensitive. */
int aq_at2_starts_ci(const char *s, size_t n, const char *needle)
{
  size_t m = strlen(needle);
  return n >= m && strncasecmp(s, needle, m) == 0;
}

/* Copy s[0..n) into out (NUL-terminated, truncated to cap-1), for messages. */
void aq_at2_quote(const char *s, size_t n, char *out, size_t cap)
{
  size_t k = 0;
  for (size_t i = 0; i < n && k + 1 < cap; i++)
    out[k++] = isprint((unsigned char)s[i]) ? s[i] : '?';
  out[k] = '\0';
}

int aq_at2_is_digit(char c) { return c >= '0' && c <= '9'; }

int aq_at2_is_numchar(char c)
{
  return aq_at2_is_digit(c) || c == '.' || c == '+' || c == '-' || c == 'e' || c == 'E';
}

/* Fixed-width fields may touch: after a value with an exponent, a point
 * starts the next value (".2385417E-02.7731905E-03"). */
static int has_exp(const char *t, size_t used)
{
  for (size_t i = 0; i < used; i++)
    if (t[i] == 'e' || t[i] == 'E')
      return 1;
  return 0;
}

static int is_sep(char c)
{
  return c == ' ' || c == '\t' || c == ',' || c == '\r' || c == '\n' || c == '\f' ||
         c == '\v' || c == '\0';
}

/* Bytes between values: 1 a blank or comma, 2 a line end; 0 otherwise. */
static const unsigned char sep_kind[256] = {[' '] = 1, ['\t'] = 1, [','] = 1, ['\f'] = 1,
                                            ['\v'] = 1, ['\n'] = 2, ['\r'] = 2};

/* PEER's fixed fields.  NGA-West2 writes the values five a line in
 * 15-character fields, "   .7273025E-06" or "  -.6521952E-06": two blanks,
 * a blank or a minus, a point, seven digits, E, the exponent's sign and two
 * digits.  Read whole, such a field needs no search for where its number
 * starts or ends, and no loop: the next field starts 15 bytes on whatever
 * the sign was. */
#define PEER_FIELD_W 15 /* characters of one field */

#if defined(__SSE2__) && !defined(AQ_NO_SIMD) /* every x86-64 CPU */
/* The PEER field at p, with the separator after it (a blank or a line end,
 * not taken): 1 and its value in *x, or 0 if the 16 bytes at p (which the
 * caller has) are anything else, or the value is one strtod must read.
 * One 16-byte vector holds the field and its separator. */
static int peer_field(const char *p, double *x)
{
  /* position by position: where the digits are, and the bytes allowed
   * elsewhere (one of three patterns; their digit places are unused) */
  static const char digit_at[16] = {0, 0, 0, 0, -1, -1, -1, -1, -1, -1, -1, 0, 0, -1, -1, 0};
  static const char pat_a[16] = "   .0000000E-00 ", pat_b[16] = "  -.0000000e+00\n",
                    pat_c[16] = "  -.0000000e+00\r";
  const __m128i v = _mm_loadu_si128((const __m128i *)p);
  const __m128i digits = _mm_loadu_si128((const __m128i *)digit_at);
  /* v - '0' is 0..9, unsigned, exactly at the digits: min(d, 9) == d */
  const __m128i d = _mm_sub_epi8(v, _mm_set1_epi8('0'));
  const __m128i is_digit = _mm_cmpeq_epi8(_mm_min_epu8(d, _mm_set1_epi8(9)), d);
  const __m128i fixed =
      _mm_or_si128(_mm_cmpeq_epi8(v, _mm_loadu_si128((const __m128i *)pat_a)),
                   _mm_or_si128(_mm_cmpeq_epi8(v, _mm_loadu_si128((const __m128i *)pat_b)),
                                _mm_cmpeq_epi8(v, _mm_loadu_si128((const __m128i *)pat_c))));
  const __m128i good = _mm_or_si128(_mm_and_si128(digits, is_digit), _mm_andnot_si128(digits, fixed));
  if (_mm_movemask_epi8(good) != 0xFFFF)
    return 0;
  /* The digit values as 16-bit lanes times their place values, summed in
   * pairs (pmaddwd): bytes 4-7 give 1000 d4 + 100 d5 and 10 d6 + d7,
   * bytes 8-10 give 100 d8 + 10 d9 and d10, bytes 13-14 give 10 d13 and
   * d14; every other byte has weight 0. */
  const __m128i zero = _mm_setzero_si128();
  const __m128i lo = _mm_madd_epi16(_mm_unpacklo_epi8(d, zero),
                                    _mm_setr_epi16(0, 0, 0, 0, 1000, 100, 10, 1));
  const __m128i hi = _mm_madd_epi16(_mm_unpackhi_epi8(d, zero),
                                    _mm_setr_epi16(100, 10, 1, 0, 0, 10, 1, 0));
  /* add each 32-bit lane to the one above it: lo lane 2 = d4..d7, hi lane 0
   * = d8..d10, hi lane 2 = the exponent */
  const __m128i lo2 = _mm_add_epi32(lo, _mm_srli_si128(lo, 4));
  const __m128i hi2 = _mm_add_epi32(hi, _mm_srli_si128(hi, 4));
  uint64_t m = (uint64_t)_mm_cvtsi128_si32(_mm_srli_si128(lo2, 8)) * 1000 +
               (uint64_t)_mm_cvtsi128_si32(hi2);
  int ex = _mm_cvtsi128_si32(_mm_srli_si128(hi2, 8));
  /* value = 0.d4..d10 * 10^ex = d4..d10 * 10^(ex - 7) */
  return aq_number_exact(m, (p[12] == '-' ? -ex : ex) - 7, p[2] == '-', x);
}
#else
/* Without SSE2 (or built with -DAQ_NO_SIMD) the general reading takes every
 * field. */
static int peer_field(const char *p, double *x)
{
  (void)p;
  (void)x;
  return 0;
}
#endif

/* The values from c->pos on that are plain finite numbers, each ended by a
 * separator (is_sep) or the end of the input, into acc[k..npts): returns the
 * new k.  Stops with c at the first token that is anything else (a glued
 * value, an end marker, a bad token: the careful loop takes it) or at the
 * end of the input.  The common case, in one pass over the bytes. */
static size_t plain_values(at2_cur *c, double *acc, size_t k, size_t npts)
{
  const char *s = c->s, *p = s + c->pos, *end = s + c->n;
  long line = c->line;
  while (k < npts) {
    if (end - p > PEER_FIELD_W && peer_field(p, &acc[k])) {
      k++;
      p += PEER_FIELD_W;
      continue;
    }
    if (p < end && sep_kind[(unsigned char)*p] == 2) { /* a field may follow */
      p = aq_text_past_eol(p, end);
      line++;
      continue;
    }
    for (;;) { /* separators, as the careful loop skips them */
      while (p < end && sep_kind[(unsigned char)*p] == 1)
        p++;
      if (p >= end || sep_kind[(unsigned char)*p] != 2)
        break;
      p = aq_text_past_eol(p, end);
      line++;
    }
    if (p >= end)
      break;
    double x;
    size_t used = aq_number_parse_finite(p, (size_t)(end - p), 0, &x);
    if (!used || (p + used < end && !is_sep(p[used])))
      break;
    acc[k++] = x;
    p += used;
  }
  c->pos = (size_t)(p - s);
  c->line = line;
  return k;
}

/* Copy s[b..e) trimmed of blanks into out. */
static void trimmed(const char *s, size_t b, size_t e, char *out, size_t cap)
{
  while (b < e && (s[b] == ' ' || s[b] == '\t' || s[b] == ','))
    b++;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == ','))
    e--;
  aq_at2_quote(s + b, e - b, out, cap);
}

aq_status aq_at2_parse(const unsigned char *buf, size_t n, const char *name,
                       const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  (void)opts; /* an AT2 file states everything it can */
  memset(raw, 0, sizeof *raw);
  const char *s = (const char *)buf;
  at2_header h;
  long bad_line;
  size_t bad_b = 0, bad_e = 0;
  int bad_kind = -1;
  char got[80];
  if (!aq_at2_find_header(s, n, &h, &bad_line, &bad_b, &bad_e, &bad_kind)) {
    if (bad_line > 0) {
      aq_at2_quote(s + bad_b, bad_e - bad_b, got, sizeof got);
      if (bad_kind == -2)
        return aq_error_set(err, AQ_EFORMAT, name, bad_line, -1, "DT",
                            "expected DT= the sample interval in s, got \"%s\"", got);
      return aq_error_set(err, AQ_EFORMAT, name, bad_line, -1, "NPTS",
                          "expected NPTS= a positive integer (\"NPTS= N, DT= S\" or "
                          "\"N S NPTS, DT\"), got \"%s\"",
                          got);
    }
    return aq_error_set(err, AQ_EFORMAT, name, -1, -1, "NPTS",
                        "expected a line with NPTS and DT followed by the values "
                        "among the first %d lines, found none",
                        AT2_MAX_HEADER_LINES);
  }
  long npts_line = h.line;
  aq_at2_quote(s + h.line_b, h.line_e - h.line_b, got, sizeof got);
  double npts_d = h.npts, dt = h.dt;
  if (!(npts_d >= 1) || npts_d != floor(npts_d) || npts_d > 1e12)
    return aq_error_set(err, AQ_EFORMAT, name, npts_line, -1, "NPTS",
                        "expected a positive integer, got \"%s\"", got);
  if (!isfinite(dt) || !(dt > 0))
    return aq_error_set(err, AQ_EFORMAT, name, npts_line, -1, "DT",
                        "expected a sample interval > 0 s, got \"%s\"", got);
  size_t npts = (size_t)npts_d;
  at2_cur c = {s, n, h.data_pos, h.data_line};

  /* Units: the text lines say "UNITS OF G"; an AT2 file is in g by its
   * definition when they say nothing. */
  char ustated[24] = "g", usaid[64] = "", ufrom[64] = "a PEER AT2 file: g";
  int qty = AQ_QUANTITY_UNSTATED;
  for (int k = 0; k < h.ntext; k++) {
    aq_units hu;
    char uword[32] = "";
    int r = aq_at2_header_units(s + h.text_b[k], h.text_e[k] - h.text_b[k], &hu, uword,
                         sizeof uword);
    if (r == 1) {
      snprintf(ustated, sizeof ustated, "%s", aq_units_name(hu));
      snprintf(ufrom, sizeof ufrom, "header line %d: UNITS OF %.24s", k + 1, uword);
      qty = AQ_QUANTITY_ACCELERATION;
      break;
    }
    if (r < 0) {
      ustated[0] = '\0';
      snprintf(usaid, sizeof usaid, "UNITS OF %s", uword);
      qty = aq_units_quantity(uword);
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
    k = plain_values(&c, acc, k, npts);
    if (k >= npts)
      break;
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
    double x;
    size_t used;
    if (t[0] != 'e' && t[0] != 'E' && t[0] != '*') { /* the common case first */
      used = aq_decimal_parse(t, avail, &x);
      if (used && (used == avail || is_sep(t[used])) && isfinite(x)) {
        acc[k++] = x;
        c.pos += used;
        continue;
      }
    }
    while (tl < avail && !is_sep(t[tl]))
      tl++;
    if (tl == 0)
      tl = 1; /* a NUL byte */
    if (((t[0] == 'e' || t[0] == 'E') && tl >= 3 && strncasecmp(t, "end", 3) == 0) ||
        t[0] == '*')
      break; /* "End Data" or "*** End Data ***" marker */
    used = aq_decimal_parse(t, tl, &x);
    int bad = !used || !isfinite(x);
    if (!bad && used < tl) {
      char nx = t[used];
      bad = !(nx == '-' || nx == '+' || nx == '*' || (nx == '.' && has_exp(t, used)) ||
              (tl - used >= 3 && strncasecmp(t + used, "end", 3) == 0));
    }
    if (bad) { /* the message's parts, only on the error path */
      snprintf(field, sizeof field, "value %zu", k + 1);
      aq_at2_quote(t, tl < AT2_TOKEN_MAX ? tl : AT2_TOKEN_MAX, tokq, sizeof tokq);
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
      int glued_value = nx == '-' || nx == '+' || (nx == '.' && has_exp(t, used));
      int glued_end = nx == '*' || (tl - used >= 3 && strncasecmp(t + used, "end", 3) == 0);
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
  /* values past NPTS, reported for the decision (record.c): numbers left
   * on the last value's line (never a copy of a row), else rows of numbers
   * after it up to anything else (an "End Data" marker ends the data) */
  aq_extra_rows x;
  memset(&x, 0, sizeof x);
  size_t lb = c.pos, lend = aq_text_line_end(c.s, c.pos, c.n);
  while (lb > 0 && c.s[lb - 1] != '\n' && c.s[lb - 1] != '\r')
    lb--;
  aq_line last = {c.s + lb, lend - lb, c.line}, rest = {c.s + c.pos, lend - c.pos, c.line};
  if (!aq_line_blank(&rest)) {
    x.values = aq_numbers_row(&rest, NULL);
    x.rows = x.values > 0;
    x.line = c.line;
  } else {
    aq_lines after = {c.s, c.n, lend, c.line};
    aq_extra_rows_scan(&after, &last, NULL, NULL, &x);
  }
  aq_status st = aq_raw_file_alloc(raw, 1, name, err);
  if (st != AQ_OK) {
    free(acc);
    return st;
  }
  snprintf(raw->format, sizeof raw->format, "at2");
  aq_raw_channel *ch = &raw->chan[0];
  ch->npts = npts;
  ch->dt_s = dt;
  ch->begin_s = 0.0;
  snprintf(ch->units, sizeof ch->units, "%s", ustated);
  snprintf(ch->units_said, sizeof ch->units_said, "%s", usaid);
  snprintf(ch->units_from, sizeof ch->units_from, "%s", ufrom);
  ch->quantity = qty;
  aq_raw_set_extra(ch, &x, 1, "NPTS");
  if (qty != AQ_QUANTITY_UNSTATED)
    snprintf(ch->quantity_said, sizeof ch->quantity_said, "%s",
             qty == AQ_QUANTITY_ACCELERATION ? ufrom : usaid);
  ch->values = acc;
  /* What the text states: the event line (PEER: "Event, date, station,
   * component"), the component (PEER's three text lines: the second line's
   * last field's first word, "180", "N", "UP"; else a "Component:" in any
   * text line), the processing (filter corners on the NPTS or units line). */
  if (h.ntext >= 2)
    trimmed(s, h.text_b[1], h.text_e[1], raw->event, sizeof raw->event);
  if (h.ntext >= 2) { /* the event alone: the line without its last two fields,
                         the station and the component ("Imperial Valley-02,
                         5/19/1940" of "..., El Centro Array #9, 180") */
    size_t b = h.text_b[1], e = h.text_e[1], commas = 0;
    while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == ','))
      e--;
    while (e > b && commas < 2)
      commas += s[--e] == ',';
    if (commas == 2)
      trimmed(s, b, e, raw->event_name, sizeof raw->event_name);
  }
  size_t cb = 0, ce = 0, le = 0; /* le: the end of the component's line */
  int last_field = 0;             /* PEER's last field: the component alone */
  if (h.ntext == 3) {
    size_t b = h.text_b[1], e = h.text_e[1], commas = 0;
    for (size_t i = b; i < e; i++)
      if (s[i] == ',')
        commas++, cb = i + 1;
    if (commas < 2)
      cb = 0;
    le = e;
    last_field = cb != 0;
  }
  for (int k = 0; k < h.ntext && !cb; k++) {
    const char *f = aq_at2_find_ci(s + h.text_b[k], h.text_e[k] - h.text_b[k], "Component:");
    if (f)
      cb = (size_t)(f - s) + 10, le = h.text_e[k];
  }
  if (cb) {
    while (cb < n && (s[cb] == ' ' || s[cb] == '\t'))
      cb++;
    ce = cb;
    while (ce < n && (isalnum((unsigned char)s[ce]) || s[ce] == '-' || s[ce] == '.'))
      ce++;
    /* PEER's last field holds the component and at most a remark in
     * parentheses ("180", "N (CWB)"); other words there ("8 values per
     * line") are not a component, nor is a Fortran format ("8F10.5") */
    size_t r = ce;
    while (r < le && (s[r] == ' ' || s[r] == '\t'))
      r++;
    int alone = !last_field || r >= le || s[r] == '(';
    if (ce > cb && ce - cb <= AT2_CHANNEL_MAX && alone &&
        !aq_fortran_descriptor(s + cb, ce - cb)) {
      trimmed(s, cb, ce, ch->channel, sizeof ch->channel);
      char *endp;
      double az = strtod(ch->channel, &endp);
      if (ch->channel[0] && !*endp && az >= 0 && az <= 360)
        ch->azimuth_deg = az;
    }
  }
  size_t tb = h.line_b + h.tail, te = h.line_e;
  while (tb < te && (s[tb] == ' ' || s[tb] == ',' || s[tb] == '\t'))
    tb++;
  if (te - tb >= 3 && strncasecmp(s + tb, "SEC", 3) == 0)
    tb += 3;
  char tailtxt[120];
  trimmed(s, tb, te, tailtxt, sizeof tailtxt);
  for (int k = 0; k < h.ntext && !raw->processing[0]; k++) {
    const char *f = aq_at2_find_ci(s + h.text_b[k], h.text_e[k] - h.text_b[k], "FILTER");
    if (f)
      trimmed(s, (size_t)(f - s), h.text_e[k], raw->processing, sizeof raw->processing);
  }
  if (!raw->processing[0] && tailtxt[0])
    snprintf(raw->processing, sizeof raw->processing, "%s", tailtxt);
  return AQ_OK;
}
