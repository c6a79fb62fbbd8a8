/* test_io_fields.c: the AT2 reader's fast path for PEER's fixed fields
 * (and the careful reading it falls back to) against an independent reading
 * of the same bytes: the data split at blanks, commas and line ends, the
 * glued values of docs/at2-format.md split off ("-.1E-01-.2E-01": a sign, or
 * a point after an exponent, starts a value), each token read by the C
 * library's strtod (glibc's, another implementation).  Values must agree bit
 * for bit; where strtod does not take a whole token the reader must refuse
 * the file naming that token's line.  The inputs: thousands of random fields
 * of PEER's shape with every sign, exponent (E-99..E+99, e or E) and digit
 * pattern, boundary values written in the same width (2^53, 10^22, 10^23,
 * 19- and 20-digit mantissas, subnormals), every byte of a file replaced in
 * turn by a letter, digit, blank, comma, tab or NUL, and a file cut at every
 * byte.  Each buffer is a heap block of exactly its size, so a read past its
 * end is caught by the address sanitizer. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/record.h"
#include "io/number.h"

#define AT2_HEAD "PEER TEST\nRANDOM FIELDS\nACCELERATION TIME SERIES IN UNITS OF G\n"
#define TOKEN_MAX 64 /* longer tokens: the reference refuses them */

static uint64_t rng(uint64_t *x)
{
  *x ^= *x << 13;
  *x ^= *x >> 7;
  *x ^= *x << 17;
  return *x;
}

/* ---- the reference reading ------------------------------------------- */

static int is_blank(char c)
{
  return c == ' ' || c == '\t' || c == ',' || c == '\f' || c == '\v' || c == '\r' || c == '\n';
}

/* The values of s[pos..n) (line number line at pos, LF or CR LF line ends),
 * at most want of them, into v: returns how many, or -1 when a token is not
 * a finite number (*bad_line its line). */
static long reference_values(const char *s, size_t n, size_t pos, long line, size_t want,
                             double *v, long *bad_line)
{
  size_t k = 0;
  while (k < want) {
    while (pos < n && is_blank(s[pos]))
      line += s[pos++] == '\n';
    if (pos >= n)
      break;
    /* a NUL ends a value like a blank, but is not skipped as one: the
     * next token starts with it, and is no number */
    size_t b = pos;
    while (pos < n && !is_blank(s[pos]) && (pos == b || s[pos] != '\0'))
      pos++;
    char tok[TOKEN_MAX];
    if (pos - b >= sizeof tok || s[b] == '\0') {
      *bad_line = line;
      return -1;
    }
    memcpy(tok, s + b, pos - b);
    tok[pos - b] = '\0';
    const char *t = tok;
    while (*t && k < want) { /* glued values: one token, several values */
      char *e;
      double x = strtod(t, &e);
      int has_exp = memchr(t, 'e', (size_t)(e - t)) || memchr(t, 'E', (size_t)(e - t));
      if (e == t || !isfinite(x) ||
          (*e && !(*e == '-' || *e == '+' || (*e == '.' && has_exp)))) {
        *bad_line = line;
        return -1;
      }
      v[k++] = x;
      t = e;
    }
  }
  return (long)k;
}

/* ---- the reader on a buffer of exactly n bytes ------------------------- */

typedef struct {
  aq_status st;
  long line;     /* of the error */
  char field[96]; /* of the error */
  double *v;     /* the values (malloc'd) on success */
  size_t npts;
  char msg[600];
} reading;

static reading read_at2(const char *text, size_t n)
{
  reading r = {0};
  char *b = malloc(n ? n : 1);
  if (!b) {
    r.st = AQ_ENOMEM;
    return r;
  }
  memcpy(b, text, n);
  aq_raw_file raw;
  aq_error e;
  aq_error_clear(&e);
  r.st = aq_at2_parse((const unsigned char *)b, n, "fields.AT2", NULL, &raw, &e);
  r.line = e.line;
  snprintf(r.field, sizeof r.field, "%s", e.field);
  aq_error_format(&e, r.msg, sizeof r.msg);
  if (r.st == AQ_OK) {
    r.npts = raw.chan[0].npts;
    r.v = malloc(r.npts * sizeof *r.v);
    if (r.v)
      memcpy(r.v, raw.chan[0].values, r.npts * sizeof *r.v);
    aq_raw_file_free(&raw);
  }
  free(b);
  return r;
}

/* The reader and the reference on text[0..n), whose values start at data
 * (line data_line) after an NPTS = npts header: 1 if they agree (the same
 * values bit for bit, or both refuse and at the same line when the
 * reference names a bad token), else a failed check saying how. */
static int agree(const char *what, const char *text, size_t n, size_t data, long data_line,
                 size_t npts)
{
  double *want = malloc(npts * sizeof *want);
  if (!want)
    return aq_check(0, "memory");
  long bad_line = -1;
  long got = reference_values(text, n, data, data_line, npts, want, &bad_line);
  reading r = read_at2(text, n);
  int ok = 1;
  if (got == (long)npts) {
    ok = r.st == AQ_OK && r.npts == npts && r.v;
    for (size_t k = 0; ok && k < npts; k++)
      if (memcmp(&r.v[k], &want[k], sizeof want[k]) != 0) {
        ok = aq_check(0, "%s: value %zu is %.17g, strtod %.17g", what, k + 1, r.v[k], want[k]);
        break;
      }
    if (!ok && r.st != AQ_OK)
      aq_check(0, "%s: refused (%s), strtod reads all %zu values", what, r.msg, npts);
  } else {
    /* a refusal about a value names the bad token's line (the header's
     * checks, e.g. NPTS against the bytes left, may refuse first) */
    ok = r.st != AQ_OK && (got >= 0 || strncmp(r.field, "value", 5) != 0 || r.line == bad_line);
    if (!ok)
      aq_check(0, "%s: %s (line %ld), expected a refusal%s (line %ld)", what,
               r.st == AQ_OK ? "read" : r.msg, r.line, got < 0 ? " naming the bad token" : "",
               bad_line);
  }
  free(r.v);
  free(want);
  return ok;
}

/* ---- writing fields ---------------------------------------------------- */

/* Boundary values and shapes the fast path must leave to strtod, or read
 * exactly at the edge of its range, in the fields' 15 characters (or more,
 * after a blank). */
static const char *const hard_tokens[] = {
    "9007199254740992",     "9007199254740993",     "1e22",
    "1e23",                 ".1234567E-15",         ".1234567E-16",
    ".9999999E+29",         ".9999999E+30",         "1234567890123456789",
    "12345678901234567890", ".4940656E-323",        ".2470328E-323",
    "-.0000000E+00",        ".7273025E-100",        "-.7273025e-06",
    "0.7273025E-06",        "-7.273025E-07",        ".72730250E-06",
    ".727302E-06",          "7273025",              ".7273025E6",
    ".7273025E+6",          "+.7273025E-06",        "-.9999999E+99",
    ".1000000E-99",         "-.2385417E-02-.1E-01", ".2385417E-02.7731905E-03"};

/* One field of PEER's shape, with random sign, digits, exponent letter,
 * sign and value; with hard set, one in eight a token of hard_tokens. */
static void random_field(uint64_t *x, char *f, size_t cap, int hard)
{
  uint64_t r = rng(x);
  if (hard && r % 8 == 0) {
    snprintf(f, cap, " %14s", hard_tokens[(r >> 3) % (sizeof hard_tokens / sizeof *hard_tokens)]);
    return;
  }
  int ex = (r >> 8) % 4 ? (int)((r >> 10) % 16) : (int)((r >> 10) % 100);
  snprintf(f, cap, "  %c.%07uE%c%02d", (r >> 20) & 1 ? '-' : ' ',
           (unsigned)((r >> 21) % 10000000), (r >> 45) % 5 ? '-' : '+', ex);
  if ((r >> 48) % 10 == 0)
    f[11] = 'e';
}

/* An AT2 of npts random fields, five a line (line ends LF or CR LF), into
 * buf; *data and *data_line where the values start.  Returns its length. */
static size_t random_at2(uint64_t *x, size_t npts, int crlf, int hard, char *buf, size_t cap,
                         size_t *data, long *data_line)
{
  size_t n = (size_t)snprintf(buf, cap, AT2_HEAD "NPTS= %zu, DT= .0050 SEC%s", npts,
                              crlf ? "\r\n" : "\n");
  *data = n;
  *data_line = 5;
  for (size_t k = 0; k < npts && n + 40 < cap; k++) {
    char f[40];
    random_field(x, f, sizeof f, hard);
    n += (size_t)snprintf(buf + n, cap - n, "%s%s", f,
                          k % 5 == 4 || k + 1 == npts ? (crlf ? "\r\n" : "\n") : "");
  }
  return n;
}

AQ_TEST(io_at2_fields_equal_strtod)
{
  enum { NPTS = 6000, FILES = 4 };
  size_t cap = NPTS * 20 + 200;
  char *buf = malloc(cap);
  if (!aq_check(buf != NULL, "memory"))
    return;
  uint64_t x = 0x5DEECE66D2385ULL;
  int ok = 1;
  for (int f = 0; f < FILES && ok; f++) {
    size_t data;
    long dl;
    size_t n = random_at2(&x, NPTS, f & 1, f >= 2, buf, cap, &data, &dl);
    char what[40];
    snprintf(what, sizeof what, "random file %d", f);
    ok = agree(what, buf, n, data, dl, NPTS);
    reading r = read_at2(buf, n); /* all of them are numbers: read, not refused */
    ok &= aq_check(r.st == AQ_OK, "%s: %s", what, r.msg);
    free(r.v);
  }
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  fields: %d files of %d random fields agree with strtod: %s\n", FILES, NPTS,
           ok ? "yes" : "no");
  free(buf);
}

/* Every byte of the second and third lines of values replaced in turn by
 * each of a set of characters: what the reader makes of it must be what
 * strtod makes of the tokens. */
AQ_TEST(io_at2_fields_each_byte_replaced)
{
  static const char repl[] = {'Z', ':', '/', '0', '7', '9', 'e', 'E', ' ', '\t', ',', '\0'};
  enum { NPTS = 15 };
  char base[2000];
  uint64_t x = 0xA5A5F00D1234ULL;
  size_t data;
  long dl;
  size_t n = random_at2(&x, NPTS, 0, 0, base, sizeof base, &data, &dl);
  size_t from = data + 76, to = n; /* lines 2 and 3 of the values */
  size_t cases = 0, bad = 0;
  char *t = malloc(n);
  if (!aq_check(t != NULL && n - data == 3 * 76, "base file"))
    return;
  for (size_t i = from; i < to; i++) {
    if (base[i] == '\n')
      continue;
    for (size_t c = 0; c < sizeof repl; c++) {
      memcpy(t, base, n);
      t[i] = repl[c];
      char what[64];
      snprintf(what, sizeof what, "byte %zu as 0x%02x", i - data, (unsigned char)repl[c]);
      cases++;
      bad += !agree(what, t, n, data, dl, NPTS);
      if (bad > 5)
        break;
    }
  }
  aq_check(bad == 0, "%zu of %zu single-byte changes differ", bad, cases);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  fields: %zu single-byte changes, %zu differ\n", cases, bad);
  free(t);
}

/* The file cut at every byte of its values: a cut inside the last value
 * reads what is left of it as strtod would, or refuses the file. */
AQ_TEST(io_at2_fields_cut_anywhere)
{
  enum { NPTS = 12 };
  char base[2000];
  uint64_t x = 0x0123456789ULL;
  size_t data, cases = 0, bad = 0;
  long dl;
  for (int crlf = 0; crlf < 2; crlf++) {
    size_t n = random_at2(&x, NPTS, crlf, 1, base, sizeof base, &data, &dl);
    for (size_t m = data + 1; m <= n; m++) {
      char what[40];
      snprintf(what, sizeof what, "cut at byte %zu of %zu", m, n);
      cases++;
      bad += !agree(what, base, m, data, dl, NPTS);
    }
  }
  aq_check(bad == 0, "%zu of %zu cut files differ", bad, cases);
}

/* Random PEER fields (one in eight a hard token), lines of 1 to 5 of them
 * in a random order, LF, CR LF or CR line ends, the values starting at
 * every offset 0..31 from the buffer's start (the header's first line made
 * longer): the fields meet every alignment, line ends between any two of
 * them, and the last bytes of the buffer. */
AQ_TEST(io_at2_fields_alignment_and_lines)
{
  enum { NPTS = 37, SHIFTS = 32 };
  static const char *const eols[] = {"\n", "\r\n", "\r"};
  char buf[4000];
  uint64_t x = 0x9E3779B97F4A7C15ULL;
  size_t cases = 0, bad = 0;
  for (int shift = 0; shift < SHIFTS; shift++)
    for (int e = 0; e < 3; e++)
      for (int layout = 0; layout < 3; layout++) {
        const char *eol = eols[e];
        size_t n = (size_t)snprintf(buf, sizeof buf, "PEER TEST%*s\nRANDOM FIELDS%s", shift, "",
                                    eol);
        n += (size_t)snprintf(buf + n, sizeof buf - n,
                              "ACCELERATION TIME SERIES IN UNITS OF G%sNPTS= %d, DT= .0050 SEC%s",
                              eol, NPTS, eol);
        size_t data = n;
        int on_line = 0, line_len = 1 + (int)(rng(&x) % 5);
        for (int k = 0; k < NPTS; k++) {
          char f[40];
          random_field(&x, f, sizeof f, layout == 2);
          n += (size_t)snprintf(buf + n, sizeof buf - n, "%s", f);
          if (++on_line == line_len || k + 1 == NPTS) {
            n += (size_t)snprintf(buf + n, sizeof buf - n, "%s", eol);
            on_line = 0;
            line_len = layout == 0 ? 5 : 1 + (int)(rng(&x) % 5);
          }
        }
        if (layout == 1 && (shift & 1)) /* no line end after the last value */
          n -= strlen(eol);
        char what[80];
        snprintf(what, sizeof what, "offset %d, line end %d, layout %d", shift, e, layout);
        cases++;
        bad += !agree(what, buf, n, data, 5, NPTS);
        if (e < 2) { /* a bad last value: refused naming its line (the reference counts LFs) */
          size_t last = n - (n > 0 && buf[n - 1] == '\n') - (n > 1 && buf[n - 2] == '\r') - 15;
          char keep = buf[last + 9];
          buf[last + 9] = 'Z';
          snprintf(what, sizeof what, "offset %d, line end %d, layout %d, bad last value", shift,
                   e, layout);
          cases++;
          bad += !agree(what, buf, n, data, 5, NPTS);
          buf[last + 9] = keep;
        }
      }
  aq_check(bad == 0, "%zu of %zu files differ", bad, cases);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  fields: %zu files at every alignment and line length, %zu differ\n", cases, bad);
}

/* Each of the 16 bytes the fast path reads for a field (its 15 and the next
 * one) of fields 2 to 14 (the first stays intact: a first line of values
 * that does not start like one is the header's matter) replaced in turn by a byte of another class
 * or of the same class: neighbours of the digits, signs, points, exponent
 * letters, blanks, a line end, a NUL, and a digit with its high bit set. */
AQ_TEST(io_at2_fields_bad_byte_each_lane)
{
  static const char repl[] = {'/', ':', '0', '5', '9', '+', '-', '.', 'e', 'E', 'D',
                              ' ', '\t', ',', '\n', '\0', (char)0xB5, 'Z'};
  enum { NPTS = 15 };
  char base[2000], t[2000];
  uint64_t x = 0x2385417ABCDEFULL;
  size_t data;
  long dl;
  size_t n = random_at2(&x, NPTS, 0, 0, base, sizeof base, &data, &dl);
  size_t cases = 0, bad = 0;
  if (!aq_check(n - data == 3 * 76, "base file"))
    return;
  for (int f = 1; f < 14 && bad < 6; f++) {
    size_t at = data + (size_t)f * 15 + (size_t)(f / 5); /* a line end after each 5 */
    for (size_t i = 0; i < 16; i++)
      for (size_t c = 0; c < sizeof repl && bad < 6; c++) {
        if (base[at + i] == repl[c])
          continue;
        memcpy(t, base, n);
        t[at + i] = repl[c];
        char what[64];
        snprintf(what, sizeof what, "field %d byte %zu as 0x%02x", f + 1, i,
                 (unsigned char)repl[c]);
        cases++;
        bad += !agree(what, t, n, data, dl, NPTS);
      }
  }
  aq_check(bad == 0, "%zu of %zu changed bytes differ", bad, cases);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  fields: %zu bytes changed in every lane, %zu differ\n", cases, bad);
}

/* ---- column shapes (number.h: aq_number_parse_shaped) ------------------ */

/* strtod's reading of t (NUL-terminated) as aq_number_parse_finite reads:
 * D and d as e when flags ask it, a number that is not finite refused:
 * the characters taken (0: none) and *x. */
static size_t reference_number(const char *t, unsigned flags, double *x)
{
  char c[TOKEN_MAX + 40];
  size_t n = strlen(t);
  if (n >= sizeof c || is_blank(t[0])) /* a number starts at once: no blanks skipped */
    return 0;
  for (size_t i = 0; i <= n; i++)
    c[i] = (flags & AQ_NUMBER_FORTRAN_D) && (t[i] == 'd' || t[i] == 'D') ? 'e' : t[i];
  char *e;
  *x = strtod(c, &e);
  return e == c || !isfinite(*x) ? 0 : (size_t)(e - c);
}

/* One layout of a column: digits before and after the point (the point
 * always there: a shape needs one, or an exponent), exponent letter and
 * digits (0: none), whether the exponent has a sign. */
typedef struct {
  int int_digits, frac_digits, exp_digits, exp_sign;
  char letter;
} layout;

static layout random_layout(uint64_t *x)
{
  uint64_t r = rng(x);
  layout l;
  l.int_digits = (int)(r % 8);                     /* 0..7 */
  l.frac_digits = (int)((r >> 3) % 9);              /* 0..8 */
  if (l.int_digits + l.frac_digits == 0)
    l.frac_digits = 1;
  l.exp_digits = (r >> 7) % 3 ? (int)((r >> 9) % 4) : 0; /* 0..3 */
  l.exp_sign = (int)((r >> 11) % 4 != 0);
  l.letter = "eEdD"[(r >> 13) % 4];
  if ((r >> 15) % 16 == 0) /* now and then longer than a shape covers */
    l.frac_digits = 12 + (int)((r >> 19) % 8);
  return l;
}

/* A number of layout l: random digits, sign and exponent sign. */
static void layout_number(uint64_t *x, const layout *l, char *t, size_t cap)
{
  uint64_t r = rng(x), y = rng(x);
  size_t p = 0;
  if (r % 3 == 0)
    t[p++] = r % 2 ? '-' : '+';
  for (int i = 0; i < l->int_digits + l->frac_digits + 1 && p + 8 < cap; i++) {
    if (i == l->int_digits) {
      t[p++] = '.';
      continue;
    }
    t[p++] = (char)('0' + y % 10);
    y = y / 10 ? y / 10 : rng(x);
  }
  if (l->exp_digits) {
    t[p++] = l->letter;
    if (l->exp_sign)
      t[p++] = (r >> 5) % 2 ? '-' : '+';
    for (int i = 0; i < l->exp_digits; i++)
      t[p++] = (char)('0' + (r >> (8 + 4 * i)) % 10);
  }
  t[p] = '\0';
}

/* A column of numbers of a few layouts, each number followed by a random
 * tail (what comes after a number in a file: separators, line ends, the
 * next number, letters, points, exponent letters), read one after another
 * with one shape; each number also with one character replaced by a letter,
 * point, sign or blank, and cut by the end of its buffer.  Every reading
 * must take the characters strtod takes and give its double bit for bit. */
AQ_TEST(io_number_shapes_equal_strtod)
{
  static const char tails[] = "0123456789.,; \t\n\reEdD+-Z";
  static const char repl[] = "Z.+- e,5";
  uint64_t x = 0xC0FFEE2385417ULL;
  size_t cases = 0, bad = 0;
  for (int col = 0; col < 400 && bad < 8; col++) {
    aq_number_shape sh = {0};
    unsigned flags = col % 3 == 0 ? AQ_NUMBER_FORTRAN_D : 0;
    layout l = random_layout(&x), other = random_layout(&x);
    for (int row = 0; row < 200 && bad < 8; row++) {
      char t[TOKEN_MAX + 40];
      uint64_t r = rng(&x);
      layout_number(&x, r % 10 ? &l : &other, t, TOKEN_MAX);
      size_t len = strlen(t);
      if (r % 7 == 0 && len > 0) /* one character replaced */
        t[(r >> 8) % len] = repl[(r >> 16) % (sizeof repl - 1)];
      size_t tail = (r >> 24) % 5 == 0 ? (r >> 28) % 4 : 17 + (r >> 28) % 8; /* cut, or room */
      for (size_t i = 0; i < tail; i++)
        t[len + i] = tails[rng(&x) % (sizeof tails - 1)];
      t[len + tail] = '\0';
      size_t n = len + tail;
      char *b = malloc(n ? n : 1); /* exactly the bytes: a read past them is caught */
      if (!b)
        return;
      memcpy(b, t, n);
      double got = -2.385, want = 0;
      size_t used = aq_number_parse_shaped(&sh, b, n, flags, &got);
      size_t want_used = reference_number(t, flags, &want);
      cases++;
      if (used != want_used || (used && memcmp(&got, &want, sizeof got) != 0)) {
        bad++;
        aq_check(0, "\"%s\" (%zu bytes, flags %u): %.17g taking %zu, strtod %.17g taking %zu", t, n,
                 flags, got, used, want, want_used);
      }
      free(b);
    }
  }
  aq_check(bad == 0, "%zu of %zu numbers read through a shape differ from strtod", bad, cases);
  if (getenv("AQ_TEST_VERBOSE"))
    printf("  shapes: %zu numbers read through column shapes, %zu differ\n", cases, bad);
}
