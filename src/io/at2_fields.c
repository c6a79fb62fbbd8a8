/* at2_fields.c: PEER's fixed AT2 fields four at a time (see at2_fields.h).
 *
 * Two fields share one 256-bit register (16 bytes each: the field and the
 * byte after it), two registers a step.  Each byte is checked against its
 * position's class with compares and one movemask; the digits become the
 * mantissa through maddubs and madd (pairs of digits, then of pairs), the
 * exponent's sign and digits an index into a table of exact powers of ten,
 * and the four values come from one vector multiply and one vector divide
 * (IEEE-exact per lane, as mulsd and divsd are), the table's sign choosing
 * which, then the sign bit.  The method (a fixed layout checked and read in
 * vector lanes) follows Lemire's "Number parsing at a gigabyte per second"
 * (Software: Practice and Experience 51(8), 2021); the code is written here. */
#include "at2_fields.h"

#include <math.h>
#include <stdint.h>

#include "number.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && \
    !defined(AQ_NO_SIMD) && AQ_NUMBER_EXACT_OK
#define AT2_AVX2 1
#include <immintrin.h>
#else
#define AT2_AVX2 0
#endif

#if AT2_AVX2
/* The power of ten for a field's exponent, by index 100 * (sign is '+') +
 * its two digits: the value is m * 10^(+-E - 7) for the seven digits m.
 * Sign bit clear: multiply m by the entry; set: divide by its magnitude;
 * NaN: the power is not exact (|+-E - 7| > 22), the field is the caller's. */
#define NAN10 NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN
static const double pow_by_exp[200] = {
    /* E-00..E-15 */
    -1e7, -1e8, -1e9, -1e10, -1e11, -1e12, -1e13, -1e14, -1e15, -1e16,
    -1e17, -1e18, -1e19, -1e20, -1e21, -1e22, NAN, NAN, NAN, NAN, /* E-16..E-19 */
    NAN10, NAN10, NAN10, NAN10, NAN10, NAN10, NAN10, NAN10, /* E-20..E-99 */
    /* E+00..E+29 */
    -1e7, -1e6, -1e5, -1e4, -1e3, -1e2, -1e1, 1e0, 1e1, 1e2,
    1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12,
    1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
    NAN10, NAN10, NAN10, NAN10, NAN10, NAN10, NAN10}; /* E+30..E+99 */

#define AVX2 __attribute__((target("avx2")))

/* Bytes a group of four fields may span from where it is looked for: a
 * line end of at most two bytes before each field, 4 x 15 characters and
 * the last one's next byte. */
#define GROUP_SPAN (4 * (2 + AQ_AT2_FIELD_W) + 1)

/* The next field at q (one line end before it taken, *line counted): LF,
 * CR LF or a CR alone; a line end of other bytes (CR CR LF) leaves q at
 * its second byte, which no field starts with.  q[0..1] are inside the
 * buffer. */
static inline const char *field_at(const char *q, long *line)
{
  if (*q == '\n') {
    (*line)++;
    return q + 1;
  }
  if (*q == '\r') {
    (*line)++;
    return q + 1 + (q[1] == '\n');
  }
  return q;
}

/* Bytes 0..15 of a field and its next byte, the same for both lanes. */
#define LANES(b0, b1, b2, b3, b4, b5, b6, b7, b8, b9, b10, b11, b12, b13, b14, b15)            \
  _mm256_setr_epi8(b0, b1, b2, b3, b4, b5, b6, b7, b8, b9, b10, b11, b12, b13, b14, b15, b0, b1, \
                   b2, b3, b4, b5, b6, b7, b8, b9, b10, b11, b12, b13, b14, b15)

/* The 16 bytes at a and at b in one register. */
static inline AVX2 __m256i load_two(const char *a, const char *b)
{
  return _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128((const __m128i *)a)),
                                 _mm_loadu_si128((const __m128i *)b), 1);
}

/* A field's bytes XOR what they are in "   .0000000E-00" and a blank:
 * the digits' values at the digits, 0 at the other bytes, or one of the
 * differences below for the other bytes allowed there. */
#define FIELD_XOR LANES(' ', ' ', ' ', '.', '0', '0', '0', '0', '0', '0', '0', 'E', '-', '0', '0', ' ')

/* All ones in each byte of t = v ^ FIELD_XOR (two fields) that is in its
 * place: at most 9 at a digit, else 0 or ' ' ^ '-' at the sign, 'E' ^ 'e'
 * at the exponent letter, '-' ^ '+' at its sign, ' ' ^ LF or ' ' ^ CR
 * after the field. */
static inline AVX2 __m256i in_place(__m256i t)
{
  const __m256i most = LANES(0, 0, 0, 0, 9, 9, 9, 9, 9, 9, 9, 0, 0, 9, 9, 0);
  const __m256i alt_a = LANES(0, 0, ' ' ^ '-', 0, 0, 0, 0, 0, 0, 0, 0, 'E' ^ 'e', '-' ^ '+', 0, 0,
                              ' ' ^ '\n');
  const __m256i alt_b = LANES(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, ' ' ^ '\r');
  return _mm256_or_si256(
      _mm256_cmpeq_epi8(_mm256_min_epu8(t, most), t),
      _mm256_or_si256(_mm256_cmpeq_epi8(t, alt_a), _mm256_cmpeq_epi8(t, alt_b)));
}

/* Two checked fields (t = v ^ FIELD_XOR) as 32-bit lanes per 128-bit half:
 * [s, h, b, j]: s 4 for a minus sign (else 0), h the first four digits, b
 * the last three, j the exponent's index into pow_by_exp. */
static inline AVX2 __m256i two_fields(__m256i t)
{
  /* the digits, and 4 at the sign when it is '-' (' ' ^ '-' is 0x0D) and
   * at the exponent's when it is '+' ('-' ^ '+' is 0x06) */
  const __m256i keep = LANES(0, 0, 4, 0, 15, 15, 15, 15, 15, 15, 15, 0, 4, 15, 15, 0);
  /* byte pairs times their weights into 16-bit lanes: [0, s, d4d5, d6d7,
   * d8d9, d10, 100 (exponent '+') + 10 d13, d14] */
  const __m256i w8 = LANES(0, 0, 1, 0, 10, 1, 10, 1, 10, 1, 1, 0, 25, 10, 1, 0);
  /* pairs of those into 32-bit lanes: [s, h = d4..d7, b = d8..d10, j] */
  const __m256i w16 = _mm256_setr_epi16(0, 1, 100, 1, 10, 1, 1, 1, 0, 1, 100, 1, 10, 1, 1, 1);
  return _mm256_madd_epi16(_mm256_maddubs_epi16(_mm256_and_si256(t, keep), w8), w16);
}

size_t aq_at2_fields4(const char **pp, const char *end, long *line, double *acc, size_t k,
                      size_t npts) AVX2;

size_t aq_at2_fields4(const char **pp, const char *end, long *line, double *acc, size_t k,
                      size_t npts)
{
  const char *p = *pp;
  long ln = *line;
  const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7), pat = FIELD_XOR;
  const __m256d magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
  while (npts - k >= 4 && end - p >= GROUP_SPAN) {
    long l = ln;
    const char *q0 = field_at(p, &l);
    const char *q1 = field_at(q0 + AQ_AT2_FIELD_W, &l);
    const char *q2 = field_at(q1 + AQ_AT2_FIELD_W, &l);
    const char *q3 = field_at(q2 + AQ_AT2_FIELD_W, &l);
    const __m256i x01 = _mm256_xor_si256(load_two(q0, q1), pat),
                  x23 = _mm256_xor_si256(load_two(q2, q3), pat);
    if (_mm256_movemask_epi8(_mm256_and_si256(in_place(x01), in_place(x23))) != -1)
      break;
    const __m256i t01 = two_fields(x01), t23 = two_fields(x23);
    /* [s0 s2 h0 h2 | s1 s3 h1 h3] and [b0 b2 j0 j2 | b1 b3 j1 j3], put in
     * field order: [s0 s1 s2 s3 h0 h1 h2 h3] and [b0 b1 b2 b3 j0 j1 j2 j3] */
    const __m256i sh = _mm256_permutevar8x32_epi32(_mm256_unpacklo_epi32(t01, t23), order);
    const __m256i bj = _mm256_permutevar8x32_epi32(_mm256_unpackhi_epi32(t01, t23), order);
    /* the seven digits, 1000 h + b (at most 9 999 999), exact as doubles */
    const __m128i m7 = _mm_add_epi32(
        _mm_mullo_epi32(_mm256_extracti128_si256(sh, 1), _mm_set1_epi32(1000)),
        _mm256_castsi256_si128(bj));
    const __m256d m = _mm256_cvtepi32_pd(m7);
    const __m256d pw = _mm256_i32gather_pd(pow_by_exp, _mm256_extracti128_si256(bj, 1), 8);
    const __m256d pa = _mm256_and_pd(pw, magnitude);
    /* m * 10^e or m / 10^e: one rounding either way (aq_number_exact) */
    __m256d x = _mm256_blendv_pd(_mm256_mul_pd(m, pa), _mm256_div_pd(m, pa), pw);
    if (_mm256_movemask_pd(_mm256_cmp_pd(x, x, _CMP_UNORD_Q)))
      break; /* a power that is not exact: strtod's */
    /* the sign as a bit (4 << 61 is the sign bit) */
    const __m256i sign = _mm256_slli_epi64(_mm256_cvtepi32_epi64(_mm256_castsi256_si128(sh)), 61);
    x = _mm256_xor_pd(x, _mm256_castsi256_pd(sign));
    _mm256_storeu_pd(acc + k, x);
    k += 4;
    p = q3 + AQ_AT2_FIELD_W;
    ln = l;
  }
  *pp = p;
  *line = ln;
  return k;
}
#else
size_t aq_at2_fields4(const char **pp, const char *end, long *line, double *acc, size_t k,
                      size_t npts)
{
  (void)pp, (void)end, (void)line, (void)acc, (void)npts;
  return k;
}
#endif
