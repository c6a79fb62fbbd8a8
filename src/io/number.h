/* number.h: the one decimal number parser of the text readers (AT2, CSV,
 * COSMOS, CSMIP, SMC, ESM, K-NET and the fixed-width helpers).  Numbers are
 * read from a byte buffer that is not NUL-terminated, never past its end,
 * with strtod's syntax in the "C" locale less hexadecimal forms, nan and inf:
 *     [+-] digits [. digits] [(e|E) [+-] digits]      (or [+-] . digits ...)
 * and, when asked, Fortran's D exponent (1.0D-02).  The result is the double
 * strtod gives, correctly rounded, whatever the process's locale.
 *
 * Plain decimals of at most 19 significant digits whose value is m * 10^e
 * with m <= 2^53 and |e| <= 22 take a fast path: m and 10^|e| are exact
 * doubles, so one IEEE multiply or divide gives the correctly rounded result
 * (Clinger, "How to read floating point numbers accurately", PLDI 1990).
 * Anything else is copied (at most AQ_NUMBER_TOKEN_MAX - 1 characters) to a
 * NUL-terminated buffer and given to strtod under the "C" numeric locale; a
 * longer number of that kind is read from its first 63 characters only, and
 * the characters left make the readers refuse the token.
 * No allocation; thread-safe. */
#ifndef AQ_IO_NUMBER_H
#define AQ_IO_NUMBER_H

#include <float.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define AQ_NUMBER_TOKEN_MAX 64 /* longest token the strtod path sees, with its NUL */

enum {
  AQ_NUMBER_FORTRAN_D = 1 /* also accept D or d as the exponent letter */
};

/* The writers' counterpart, the one formatter of every double archquake
 * prints (TSV, CSV, HDF5 attributes as text, the report, the suite file):
 * the shortest decimal that strtod reads back to x (%.15g, %.16g or %.17g,
 * whichever is first to), "nan" for any NaN, "inf" and "-inf"; into buf[n]
 * (n >= 32). */
void aq_number_format(char *buf, size_t n, double x);

/* The number starting exactly at s[0] (no blanks skipped) within s[0..n):
 * returns the characters it takes (0 if s does not start with a number, *x
 * untouched) and sets *x.  An exponent letter not followed by digits is not
 * part of the number ("1.5e" takes 3).  Out-of-range values give what
 * strtod gives (+-HUGE_VAL, 0 or a subnormal): callers check isfinite. */
size_t aq_number_parse(const char *s, size_t n, unsigned flags, double *x);

/* aq_number_parse for a finite value: returns 0 also when the number is
 * out of range or otherwise not finite (the readers' common case). */
size_t aq_number_parse_finite(const char *s, size_t n, unsigned flags, double *x);

/* The same as aq_number_parse after skipping blanks (spaces, tabs) at s; the count includes
 * them.  flags 0: no D exponent. */
size_t aq_decimal_parse(const char *s, size_t n, double *x);

/* ---- for the readers' fixed-width fast paths ---- */

/* 1 where m * 10^e below is one IEEE operation on exact doubles: double
 * arithmetic without extended precision (FLT_EVAL_METHOD 0). */
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
#define AQ_NUMBER_EXACT_OK 1
#else
#define AQ_NUMBER_EXACT_OK 0
#endif
#define AQ_NUMBER_EXACT_POW_MAX 22 /* 10^22: the largest exact power of ten */

extern const double aq_number_pow10_exact_[AQ_NUMBER_EXACT_POW_MAX + 1];

/* The decimal m * 10^e (m <= 2^53), correctly rounded, as strtod reads it:
 * m and 10^|e| are exact doubles when |e| <= 22, so one multiply or divide
 * rounds once (Clinger's fast path).  Returns 1 with *x (negated when neg),
 * or 0 when e is out of that range or the arithmetic may round twice (the
 * caller then reads the text with aq_number_parse). */
static inline int aq_number_exact(uint64_t m, int e, int neg, double *x)
{
  if (!AQ_NUMBER_EXACT_OK || m > (1ULL << 53) || e < -AQ_NUMBER_EXACT_POW_MAX ||
      e > AQ_NUMBER_EXACT_POW_MAX)
    return 0;
  double v = (double)m;
  v = e < 0 ? v / aq_number_pow10_exact_[-e] : v * aq_number_pow10_exact_[e];
  /* the sign as a bit, not a branch: signs of successive values are
   * random, a branch on them would be mispredicted half the time */
  uint64_t bits;
  memcpy(&bits, &v, sizeof bits);
  bits ^= (uint64_t)(neg != 0) << 63;
  memcpy(x, &bits, sizeof bits);
  return 1;
}

/* ---- a column's shape ---------------------------------------------------
 * Machine-written columns repeat one layout: "%.3f" gives "12.345" row after
 * row, "%.7E" "-6.5219520E-07": the same number of digits before and after
 * the point, the same exponent letter and width; only the digits and the
 * signs change.  A shape learned from one number lets the next ones be
 * checked and read from one 16-byte load, with no search for where they end
 * (SSE2, which every x86-64 CPU has; elsewhere no shape is ever learned and
 * every number takes the general reading).  Zero-initialise one per column;
 * no allocation. */
#define AQ_NUMBER_SHAPE_MAX 15 /* characters after the sign a shape covers */

typedef struct {
  unsigned char len;         /* characters after the sign; 0: none learned */
  unsigned char frac;        /* digits after the point */
  unsigned char has_point, has_exp, exp_sign_at, exp_at, exp_digits, flags;
  unsigned misses;           /* numbers in a row that did not fit */
  unsigned want;             /* bits 0..len-1 */
  unsigned char digit[16];   /* 0xFF where a digit (mantissa or exponent) is */
  unsigned char mant[16];    /* 0xFF where a mantissa digit is */
  unsigned char fixed[16];   /* 0xFF where the point, letter or exponent sign is */
  unsigned char plus[16];    /* those bytes, the exponent's sign as '+' */
  unsigned char minus[16];   /* and as '-' */
  short weight[16];          /* a mantissa digit's place value in its 4-byte block */
  uint64_t block_scale[4];   /* the place value of each block's last digit */
} aq_number_shape;

#if defined(__SSE2__) && !defined(AQ_NO_SIMD) && AQ_NUMBER_EXACT_OK
#define AQ_NUMBER_SHAPES 1
#include <emmintrin.h>
#else
#define AQ_NUMBER_SHAPES 0
#endif
#define AQ_NUMBER_SHAPE_WINDOW 16 /* bytes one load reads after the sign */

/* The general reading of aq_number_parse_shaped, which learns the shape. */
size_t aq_number_parse_unshaped_(aq_number_shape *shape, const char *s, size_t n,
                                 unsigned flags, double *x);

static inline int aq_number_is_digit_(char c) { return (unsigned char)(c - '0') < 10; }

static inline int aq_number_is_exp_letter_(char c, unsigned flags)
{
  return c == 'e' || c == 'E' || ((flags & AQ_NUMBER_FORTRAN_D) && (c == 'd' || c == 'D'));
}

#if AQ_NUMBER_SHAPES
static inline __m128i aq_number_load16_(const void *p) { return _mm_loadu_si128((const __m128i *)p); }

/* The number at s (sign of off characters, 0 or 1) read with shape *sh from
 * the 16 bytes at s + off, which the caller has: 1 with *x, or 0 if it does
 * not fit the shape (or must go to strtod).  (A yes or no, not the length:
 * the caller's next position then depends on the shape alone, not on the
 * checks, and the processor need not wait for them to go on.) */
static inline int aq_number_shape_read_(const aq_number_shape *sh, const char *s, size_t off,
                                        double *x)
{
  const char *p = s + off;
  const __m128i v = aq_number_load16_(p);
  /* v - '0' is 0..9 (unsigned) exactly at the digits: min(d, 9) == d */
  const __m128i d = _mm_sub_epi8(v, _mm_set1_epi8('0'));
  const __m128i is_digit = _mm_cmpeq_epi8(_mm_min_epu8(d, _mm_set1_epi8(9)), d);
  const __m128i fixed_ok = _mm_or_si128(_mm_cmpeq_epi8(v, aq_number_load16_(sh->plus)),
                                        _mm_cmpeq_epi8(v, aq_number_load16_(sh->minus)));
  const __m128i ok = _mm_or_si128(_mm_and_si128(is_digit, aq_number_load16_(sh->digit)),
                                  _mm_and_si128(fixed_ok, aq_number_load16_(sh->fixed)));
  if (((unsigned)_mm_movemask_epi8(ok) & sh->want) != sh->want)
    return 0;
  /* the byte after must end the number as the general reading would */
  char c = p[sh->len];
  if (aq_number_is_digit_(c) || (!sh->has_point && c == '.') ||
      (!sh->has_exp && aq_number_is_exp_letter_(c, sh->flags)))
    return 0;
  /* The mantissa digits as 16-bit lanes times their weights, summed in
   * pairs (pmaddwd), then pairs of pairs: one sum per 4-byte block, each
   * times the place value of its block. */
  const __m128i md = _mm_and_si128(d, aq_number_load16_(sh->mant)), zero = _mm_setzero_si128();
  __m128i lo = _mm_madd_epi16(_mm_unpacklo_epi8(md, zero), aq_number_load16_(sh->weight));
  __m128i hi = _mm_madd_epi16(_mm_unpackhi_epi8(md, zero), aq_number_load16_(sh->weight + 8));
  lo = _mm_add_epi32(lo, _mm_srli_si128(lo, 4)); /* lanes 0, 2: blocks 0, 1 */
  hi = _mm_add_epi32(hi, _mm_srli_si128(hi, 4)); /* lanes 0, 2: blocks 2, 3 */
  uint64_t m = (uint64_t)_mm_cvtsi128_si32(lo) * sh->block_scale[0] +
               (uint64_t)_mm_cvtsi128_si32(_mm_srli_si128(lo, 8)) * sh->block_scale[1] +
               (uint64_t)_mm_cvtsi128_si32(hi) * sh->block_scale[2] +
               (uint64_t)_mm_cvtsi128_si32(_mm_srli_si128(hi, 8)) * sh->block_scale[3];
  int e = -(int)sh->frac;
  if (sh->has_exp) {
    int ex = 0;
    for (unsigned j = 0; j < sh->exp_digits; j++)
      ex = ex * 10 + (p[sh->exp_at + j] - '0');
    e += sh->exp_sign_at && p[sh->exp_sign_at] == '-' ? -ex : ex;
  }
  return aq_number_exact(m, e, off && s[0] == '-', x);
}
#endif

/* aq_number_parse_finite(s, n, flags, x), the same characters taken and the
 * same value, reading s with *shape when it fits and learning *shape from
 * the number otherwise. */
static inline size_t aq_number_parse_shaped(aq_number_shape *shape, const char *s, size_t n,
                                            unsigned flags, double *x)
{
#if AQ_NUMBER_SHAPES
  if (shape->len && n > AQ_NUMBER_SHAPE_WINDOW && flags == shape->flags) {
    size_t off = s[0] == '-' || s[0] == '+';
    if (n - off >= AQ_NUMBER_SHAPE_WINDOW && aq_number_shape_read_(shape, s, off, x)) {
      if (shape->misses) /* (a store only when it changes) */
        shape->misses = 0;
      return off + shape->len;
    }
  }
#endif
  return aq_number_parse_unshaped_(shape, s, n, flags, x);
}

#endif
