/* number.c: the decimal number parser of the text readers (see number.h).
 *
 * Fast path (Clinger, "How to read floating point numbers accurately",
 * PLDI 1990): the significant digits d1..dk (k <= 19) form an exact integer
 * m; the value is m * 10^e.  When m <= 2^53 and |e| <= 22, both m and 10^|e|
 * are exact doubles, so m * 10^e (e >= 0) or m / 10^-e (e < 0) is a single
 * IEEE operation and hence correctly rounded: the double strtod gives.
 * Multiplying by the inexact 1e-k instead would round twice.
 * (Reading eight digits at a time as one 64-bit word measured slower here
 * than this plain loop on the seven- and eight-digit values agencies write.)
 */
#include "number.h"

#include <float.h>
#include <locale.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#define FAST_DIGITS_MAX 19 /* 10^19 - 1 < 2^64 */
#define EXPONENT_CAP 100000 /* beyond any double: strtod decides */
#define FAST_PATH AQ_NUMBER_EXACT_OK

/* Exact powers of ten representable in a double (aq_number_exact). */
const double aq_number_pow10_exact_[AQ_NUMBER_EXACT_POW_MAX + 1] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

#if FAST_PATH
/* A run of digits at *pp: m = m * 10^len + run; *nd += len.  Returns 0 when
 * the digits pass FAST_DIGITS_MAX (m may have wrapped: strtod decides). */
static inline int digit_run(const char **pp, const char *end, uint64_t *m, int *nd)
{
  const char *p = *pp, *b = p;
  uint64_t v = *m;
  while (p < end && (unsigned char)(*p - '0') < 10)
    v = v * 10 + (uint64_t)(*p++ - '0');
  *nd += (int)(p - b);
  *m = v;
  *pp = p;
  return *nd <= FAST_DIGITS_MAX;
}
#endif

static int is_exp_letter(char c, unsigned flags)
{
  return c == 'e' || c == 'E' || ((flags & AQ_NUMBER_FORTRAN_D) && (c == 'd' || c == 'D'));
}

/* ---- the strtod path ------------------------------------------------- */

static locale_t c_numeric;
static pthread_once_t c_numeric_once = PTHREAD_ONCE_INIT;
static void c_numeric_init(void) { c_numeric = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0); }

static size_t parse_strtod(const char *s, size_t n, unsigned flags, double *x, int finite)
{
  char tok[AQ_NUMBER_TOKEN_MAX];
  size_t k = 0;
  while (k < n && k + 1 < sizeof tok) {
    char c = s[k];
    if ((c >= '0' && c <= '9') || c == '.' || c == '+' || c == '-')
      tok[k++] = c;
    else if (is_exp_letter(c, flags))
      tok[k++] = 'e';
    else
      break;
  }
  tok[k] = '\0';
  if (k == 0)
    return 0;
  /* strtod reads the current locale's decimal point: read in "C" */
  pthread_once(&c_numeric_once, c_numeric_init);
  locale_t old = c_numeric ? uselocale(c_numeric) : (locale_t)0;
  char *end;
  double v = strtod(tok, &end);
  if (c_numeric)
    uselocale(old);
  if (end == tok || (finite && !isfinite(v)))
    return 0;
  *x = v;
  return (size_t)(end - tok);
}

/* aq_number_parse; with finite set, a value that is not finite takes 0.
 * The fast path's values are always finite: only strtod's are tested, so
 * the caller's next step does not wait for the division. */
static inline size_t parse(const char *s, size_t n, unsigned flags, double *x, int finite)
{
#if FAST_PATH
  const char *p = s, *end = s + n;
  int neg = 0;
  if (p < end && (*p == '-' || *p == '+'))
    neg = *p++ == '-';
  uint64_t m = 0;
  int nd = 0;
  const char *ib = p;
  if (!digit_run(&p, end, &m, &nd))
    return parse_strtod(s, n, flags, x, finite);
  long frac = 0, digits = p - ib;
  if (p < end && *p == '.') {
    const char *fb = ++p;
    if (!digit_run(&p, end, &m, &nd))
      return parse_strtod(s, n, flags, x, finite);
    frac = p - fb;
    digits += frac;
  }
  if (digits == 0)
    return 0; /* no digit: not a number ("-", ".", "+.e5", "inf") */
  long e = 0;
  if (p < end && is_exp_letter(*p, flags)) {
    const char *q = p + 1;
    int eneg = 0;
    if (q < end && (*q == '-' || *q == '+'))
      eneg = *q++ == '-';
    const char *eb = q;
    while (q < end && *q >= '0' && *q <= '9') {
      if (e < EXPONENT_CAP)
        e = e * 10 + (*q - '0');
      q++;
    }
    if (q > eb) { /* "1.5e" is 1.5 followed by "e" */
      p = q;
      e = eneg ? -e : e;
    } else {
      e = 0;
    }
  }
  e -= frac;
  if (e >= -AQ_NUMBER_EXACT_POW_MAX && e <= AQ_NUMBER_EXACT_POW_MAX &&
      aq_number_exact(m, (int)e, neg, x)) /* m <= 2^53 and one rounding */
    return (size_t)(p - s);
#endif
  return parse_strtod(s, n, flags, x, finite);
}

size_t aq_number_parse(const char *s, size_t n, unsigned flags, double *x)
{
  return parse(s, n, flags, x, 0);
}

size_t aq_number_parse_finite(const char *s, size_t n, unsigned flags, double *x)
{
  return parse(s, n, flags, x, 1);
}

size_t aq_decimal_parse(const char *s, size_t n, double *x)
{
  size_t i = 0;
  while (i < n && (s[i] == ' ' || s[i] == '\t'))
    i++;
  size_t used = aq_number_parse(s + i, n - i, 0, x);
  return used ? i + used : 0;
}

/* ---- shapes (number.h) -------------------------------------------------- */

static const uint64_t pow10_u64[AQ_NUMBER_SHAPE_MAX + 1] = {
    1ULL,          10ULL,          100ULL,          1000ULL,
    10000ULL,      100000ULL,      1000000ULL,      10000000ULL,
    100000000ULL,  1000000000ULL,  10000000000ULL,  100000000000ULL,
    1000000000000ULL, 10000000000000ULL, 100000000000000ULL, 1000000000000000ULL};


/* The layout of the number t[0..len) (its sign left out), read with flags:
 * digits, maybe a point and digits, maybe an exponent letter, sign and one
 * to three digits.  Returns 1 with *sh filled, or 0 (sh->len 0) when the
 * number is longer than a shape covers or laid out otherwise. */
static int shape_learn(aq_number_shape *sh, const char *t, size_t len, unsigned flags)
{
  unsigned misses = sh->misses;
  memset(sh, 0, sizeof *sh);
  sh->misses = misses;
  if (len == 0 || len > AQ_NUMBER_SHAPE_MAX)
    return 0;
  size_t i = 0;
  while (i < len && aq_number_is_digit_(t[i]))
    i++;
  size_t int_digits = i, frac = 0;
  if (i < len && t[i] == '.') {
    sh->has_point = 1;
    while (++i < len && aq_number_is_digit_(t[i]))
      frac++;
  }
  size_t mant_end = i, ndig = int_digits + frac;
  if (ndig == 0)
    return 0;
  if (i < len) { /* the exponent: letter, sign, digits */
    if (!aq_number_is_exp_letter_(t[i], flags))
      return 0;
    sh->has_exp = 1;
    sh->fixed[i] = 0xFF;
    sh->plus[i] = sh->minus[i] = (unsigned char)t[i];
    if (++i < len && (t[i] == '+' || t[i] == '-')) {
      sh->exp_sign_at = (unsigned char)i;
      sh->fixed[i] = 0xFF;
      sh->plus[i] = '+';
      sh->minus[i] = '-';
      i++;
    }
    sh->exp_at = (unsigned char)i;
    sh->exp_digits = (unsigned char)(len - i);
    if (sh->exp_digits < 1 || sh->exp_digits > 3)
      return 0;
    for (; i < len; i++) {
      if (!aq_number_is_digit_(t[i]))
        return 0;
      sh->digit[i] = 0xFF;
    }
  }
  /* The mantissa's digits: place q from ndig - 1 down to 0.  A 4-byte block
   * holds at most four of them (a point may sit between), so within a block
   * a digit's weight is 10^(q - the block's lowest place) <= 1000. */
  size_t q = ndig;
  for (size_t j = 0; j < mant_end; j++) {
    if (t[j] == '.') {
      sh->fixed[j] = 0xFF;
      sh->plus[j] = sh->minus[j] = '.';
      continue;
    }
    q--;
    sh->digit[j] = sh->mant[j] = 0xFF;
    sh->block_scale[j / 4] = pow10_u64[q]; /* the block's last digit sets it */
  }
  q = ndig;
  for (size_t j = 0; j < mant_end; j++)
    if (t[j] != '.') {
      q--;
      uint64_t w = pow10_u64[q] / sh->block_scale[j / 4];
      sh->weight[j] = (short)w;
    }
  sh->frac = (unsigned char)frac;
  sh->flags = (unsigned char)flags;
  sh->want = (1u << len) - 1;
  sh->len = (unsigned char)len;
  return 1;
}

/* After a number that did not fit: learn its shape at the 1st, 2nd, 4th,
 * 8th ... miss in a row, so a column whose layout changes every row costs
 * few relearnings. */
static int learn_now(aq_number_shape *sh)
{
  unsigned k = ++sh->misses;
  return (k & (k - 1)) == 0;
}

size_t aq_number_parse_unshaped_(aq_number_shape *sh, const char *s, size_t n, unsigned flags,
                                 double *x)
{
  size_t used = aq_number_parse_finite(s, n, flags, x);
#if AQ_NUMBER_SHAPES
  if (used && learn_now(sh)) {
    size_t off = s[0] == '-' || s[0] == '+';
    shape_learn(sh, s + off, used - off, flags);
  }
#else
  (void)sh;
  (void)learn_now;
  (void)shape_learn;
#endif
  return used;
}

void aq_number_format(char *buf, size_t n, double x)
{
  if (isnan(x)) {
    snprintf(buf, n, "nan"); /* glibc would print "-nan" for a negative NaN */
    return;
  }
  if (isinf(x)) {
    snprintf(buf, n, "%s", x > 0 ? "inf" : "-inf");
    return;
  }
  /* The fewest significant digits that read back to x.  15 digits always
   * do when any decimal of 15 or fewer does: a double's half spacing is at
   * most 2^-53 |x| (1.1e-16 |x|), less than half the spacing of 15-digit
   * decimals near x (more than 5e-16 |x|), so such a decimal is the one
   * nearest x, which is what %.15g prints (its zeros dropped).  Else 16
   * digits, correctly rounded, read back if any 16-digit decimal does;
   * else 17 always do (IEEE 754-2008, sec. 5.12.2). */
  for (int p = 15; p <= 17; p++) {
    snprintf(buf, n, "%.*g", p, x);
    if (strtod(buf, NULL) == x)
      return;
  }
}
