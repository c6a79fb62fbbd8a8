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

#endif
