/* csv_fields.c: plain CSV rows four at a time (see csv_fields.h).
 *
 * A group is four rows.  Their fields' places follow from the shapes and
 * the signs (a scalar walk that also checks the separators and line ends);
 * then per column two 256-bit registers hold the four fields' 16-byte
 * windows.  Each byte is checked against its place's class (a digit, or
 * the point, exponent letter or exponent sign the shape has there) with
 * compares and one movemask; one byte shuffle puts the mantissa digits
 * right-aligned, maddubs and madd sum them in pairs, fours and eights, and
 * the four mantissas (under 10^15, exact doubles) meet their powers of ten
 * in one vector multiply and one vector divide.  The method (a fixed layout
 * checked and read in vector lanes) follows Lemire's "Number parsing at a
 * gigabyte per second" (Software: Practice and Experience 51(8), 2021), as
 * at2_fields.c does; the code is written here. */
#include "csv_fields.h"

#include <stdint.h>
#include <string.h>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && \
    !defined(AQ_NO_SIMD) && AQ_NUMBER_SHAPES
#define CSV_AVX2 1
#include <immintrin.h>
#else
#define CSV_AVX2 0
#endif

#if CSV_AVX2
#define AVX2 __attribute__((target("avx2")))
#define ROWS 4
/* Bytes a field's reading needs from its start: a sign and the 16-byte
 * window (which holds the byte after the number: len <= 15). */
#define FIELD_ROOM (1 + AQ_NUMBER_SHAPE_WINDOW)
#define MANT_MAX 12 /* mantissa digits the kernel reads: bytes 4-15 */

/* 10^e by index e + 22: sign bit clear, multiply by it; set, divide by its
 * magnitude (aq_number_exact's one operation). */
static const double pow_signed[2 * AQ_NUMBER_EXACT_POW_MAX + 1] = {
    -1e22, -1e21, -1e20, -1e19, -1e18, -1e17, -1e16, -1e15, -1e14, -1e13, -1e12,
    -1e11, -1e10, -1e9,  -1e8,  -1e7,  -1e6,  -1e5,  -1e4,  -1e3,  -1e2,  -1e1,
    1e0,   1e1,   1e2,   1e3,   1e4,   1e5,   1e6,   1e7,   1e8,   1e9,   1e10,
    1e11,  1e12,  1e13,  1e14,  1e15,  1e16,  1e17,  1e18,  1e19,  1e20,  1e21, 1e22};

/* One column's shape as vectors, the same in both 128-bit halves. */
typedef struct {
  __m256i digit, fixed, plus, minus;
  __m256i shuf;       /* window to [0, exponent digits | mantissa digits] */
  __m256i esign;      /* window to its exponent sign's byte 4 times in bytes 0-3 */
  unsigned want2;     /* the shape's bytes in both halves' movemask bits */
  size_t len;
  int e0;             /* the exponent less the field's, plus 22 */
} col_vec;

static inline AVX2 __m256i twice(const unsigned char *b)
{
  return _mm256_broadcastsi128_si256(_mm_loadu_si128((const __m128i *)b));
}

/* Fills *c from the shape; returns 0 when the kernel cannot read it (more
 * than MANT_MAX mantissa digits, or more than three exponent digits). */
static AVX2 int col_setup(col_vec *c, const aq_number_shape *sh)
{
  c->digit = twice(sh->digit);
  c->fixed = twice(sh->fixed);
  c->plus = twice(sh->plus);
  c->minus = twice(sh->minus);
  unsigned char shuf[16], esign[16];
  memset(shuf, 0x80, sizeof shuf);
  memset(esign, 0x80, sizeof esign);
  size_t nd = 0;
  for (size_t j = 0; j < 16; j++)
    nd += sh->mant[j] != 0;
  if (nd > MANT_MAX || (sh->has_exp && sh->exp_digits > 3))
    return 0;
  /* the mantissa digits, in order, to the last bytes; zeros before them */
  for (size_t j = 0, r = 16 - nd; j < 16; j++)
    if (sh->mant[j])
      shuf[r++] = (unsigned char)j;
  /* the exponent digits to bytes 1-3, right-aligned; its sign's byte */
  if (sh->has_exp) {
    for (size_t j = 0; j < sh->exp_digits; j++)
      shuf[4 - sh->exp_digits + j] = (unsigned char)(sh->exp_at + j);
    if (sh->exp_sign_at)
      memset(esign, sh->exp_sign_at, 4);
  }
  c->shuf = twice(shuf);
  c->esign = twice(esign);
  c->want2 = sh->want | sh->want << 16;
  c->len = sh->len;
  c->e0 = AQ_NUMBER_EXACT_POW_MAX - (int)sh->frac;
  return 1;
}

/* The 16 bytes at a and at b in one register. */
static inline AVX2 __m256i load_two(const char *a, const char *b)
{
  return _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128((const __m128i *)a)),
                                 _mm_loadu_si128((const __m128i *)b), 1);
}

/* All ones in each byte of v (the windows of two fields) that is what the
 * column's shape has there. */
static inline AVX2 __m256i in_shape(__m256i v, __m256i d, const col_vec *c)
{
  const __m256i is_digit = _mm256_cmpeq_epi8(_mm256_min_epu8(d, _mm256_set1_epi8(9)), d);
  const __m256i is_fixed =
      _mm256_or_si256(_mm256_cmpeq_epi8(v, c->plus), _mm256_cmpeq_epi8(v, c->minus));
  return _mm256_or_si256(_mm256_and_si256(is_digit, c->digit),
                         _mm256_and_si256(is_fixed, c->fixed));
}

/* Two fields (v their windows, d = v - '0') as 32-bit lanes per half:
 * [+-E, a, b, c]: E the exponent's digits, a b c the mantissa's in groups
 * of four (the mantissa is a 10^8 + b 10^4 + c). */
static inline AVX2 __m256i fields_two(__m256i v, __m256i d, const col_vec *c)
{
  const __m256i digits = _mm256_shuffle_epi8(d, c->shuf);
  /* bytes [0, e2, e1, e0, m..] times [0, 100, 10, 1, 10, 1, ...] in pairs,
   * then the pairs' sums times [1, 1, 100, 1, 100, 1, 100, 1] in pairs */
  const __m256i w2 = _mm256_setr_epi8(0, 100, 10, 1, 10, 1, 10, 1, 10, 1, 10, 1, 10, 1, 10, 1, 0,
                                      100, 10, 1, 10, 1, 10, 1, 10, 1, 10, 1, 10, 1, 10, 1);
  const __m256i w4 = _mm256_setr_epi16(1, 1, 100, 1, 100, 1, 100, 1, 1, 1, 100, 1, 100, 1, 100, 1);
  const __m256i t = _mm256_madd_epi16(_mm256_maddubs_epi16(digits, w2), w4);
  /* all ones in lane 0 where the exponent's sign is '-': negate E there */
  const __m256i minus =
      _mm256_shuffle_epi8(_mm256_cmpeq_epi8(v, _mm256_set1_epi8('-')), c->esign);
  return _mm256_sub_epi32(_mm256_xor_si256(t, minus), minus);
}

/* aq_csv_rows4, inlined where ncols is a constant. */
static inline __attribute__((always_inline)) AVX2 size_t
rows4(const char **pp, const char *end, size_t ncols, char sep, aq_number_shape *shape,
      double *const *dst, size_t k, size_t cap)
{
  col_vec col[AQ_CSV_FIELDS_COLS_MAX];
  for (size_t i = 0; i < ncols; i++)
    if (!col_setup(&col[i], &shape[i]))
      return k;
  const size_t k0 = k;
  const char *p = *pp;
  const __m256i order = _mm256_setr_epi32(0, 4, 2, 6, 1, 5, 3, 7),
                order_e = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
  const __m256d magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
  /* the bytes a group spans at most: signs, fields, separators, CR LFs */
  size_t span = 0;
  for (size_t i = 0; i < ncols; i++)
    span += 2 + col[i].len;
  span = ROWS * (span + 1) + FIELD_ROOM + sizeof(uint64_t);
  /* where each field's terminator (separator or line end) is in a row
   * without signs: at[i] */
  size_t at[AQ_CSV_FIELDS_COLS_MAX];
  for (size_t i = 0, a = 0; i < ncols; i++)
    at[i] = a += col[i].len + (i > 0);
  const __m256i lane_bit = _mm256_setr_epi64x(1, 2, 4, 8);
  while (cap - k >= ROWS) {
    const int roomy = end - p >= (ptrdiff_t)span; /* no field near the end */
    /* the windows and signs: where the shapes put them */
    const char *w[AQ_CSV_FIELDS_COLS_MAX][ROWS];
    int neg[AQ_CSV_FIELDS_COLS_MAX] = {0}; /* bit r: row r's field is negative */
    const char *q = p;
    if (roomy) {
      /* The same walk with every load at a fixed place from the row's
       * start: the eight bytes from field i's terminator without signs
       * hold it (byte s, the signs before it) and the next field's sign
       * (byte s + 1), so a row waits for one load, not one per field. */
#pragma GCC unroll 4
      for (size_t r = 0; r < ROWS; r++) {
        unsigned c = (unsigned char)q[0], s = 0;
#pragma GCC unroll 4
        for (size_t i = 0; i < ncols; i++) {
          const unsigned off = c == '-' || c == '+';
          neg[i] |= (c == '-') << r;
          w[i][r] = q + at[i] - col[i].len + s + off;
          s += off;
          uint64_t word;
          memcpy(&word, q + at[i], sizeof word);
          word >>= 8 * s;
          const unsigned t = (unsigned char)word;
          c = (unsigned char)(word >> 8);
          if (i + 1 < ncols) {
            if (t != (unsigned char)sep)
              goto out;
          } else if (t == '\n') {
            q += at[i] + s + 1;
          } else if (t == '\r' && c == '\n') {
            q += at[i] + s + 2;
          } else {
            goto out;
          }
        }
      }
    } else
    for (size_t r = 0; r < ROWS; r++)
      for (size_t i = 0; i < ncols; i++) {
        if (end - q < FIELD_ROOM)
          goto out;
        size_t off = *q == '-' || *q == '+';
        neg[i] |= (*q == '-') << r;
        w[i][r] = q + off;
        q += off + col[i].len;
        if (i + 1 < ncols) {
          if (*q != sep)
            goto out;
          q++;
        } else if (*q == '\n') {
          q++;
        } else if (*q == '\r' && end - q >= 2 && q[1] == '\n') {
          q += 2;
        } else {
          goto out;
        }
      }
    /* (a group that stops part way may have stored values at rows
     * k..k+3 below cap: the rows that fill them later overwrite them) */
#pragma GCC unroll 4
    for (size_t i = 0; i < ncols; i++) {
      const col_vec *c = &col[i];
      const __m256i v01 = load_two(w[i][0], w[i][1]), v23 = load_two(w[i][2], w[i][3]);
      const __m256i zero = _mm256_set1_epi8('0');
      const __m256i d01 = _mm256_sub_epi8(v01, zero), d23 = _mm256_sub_epi8(v23, zero);
      const unsigned ok = (unsigned)_mm256_movemask_epi8(
          _mm256_and_si256(in_shape(v01, d01, c), in_shape(v23, d23, c)));
      if ((ok & c->want2) != c->want2)
        goto out;
      const __m256i t01 = fields_two(v01, d01, c), t23 = fields_two(v23, d23, c);
      /* [E0 E1 E2 E3]: the exponents as indices into pow_signed */
      const __m128i e = _mm_add_epi32(
          _mm256_castsi256_si128(
              _mm256_permutevar8x32_epi32(_mm256_unpacklo_epi32(t01, t23), order_e)),
          _mm_set1_epi32(c->e0));
      const __m128i out_of_range =
          _mm_or_si128(_mm_cmpgt_epi32(e, _mm_set1_epi32(2 * AQ_NUMBER_EXACT_POW_MAX)),
                       _mm_cmpgt_epi32(_mm_setzero_si128(), e));
      if (_mm_movemask_epi8(out_of_range))
        goto out; /* 10^e not exact: strtod's */
      /* [a, 10^4 b + c] per field, then [a0 a1 a2 a3 bc0 bc1 bc2 bc3] */
      const __m256i w8 = _mm256_setr_epi16(0, 1, 10000, 1, 0, 0, 0, 0, 0, 1, 10000, 1, 0, 0, 0, 0);
      const __m256i f01 = _mm256_madd_epi16(_mm256_packus_epi32(t01, t01), w8),
                    f23 = _mm256_madd_epi16(_mm256_packus_epi32(t23, t23), w8);
      const __m256i hl = _mm256_permutevar8x32_epi32(_mm256_unpacklo_epi64(f01, f23), order);
      /* at most MANT_MAX = 12 digits: a 10^8 + bc < 10^12, exact */
      const __m256d m =
          _mm256_add_pd(_mm256_mul_pd(_mm256_cvtepi32_pd(_mm256_castsi256_si128(hl)),
                                      _mm256_set1_pd(1e8)),
                        _mm256_cvtepi32_pd(_mm256_extracti128_si256(hl, 1)));
      const __m256d pw = _mm256_i32gather_pd(pow_signed, e, 8);
      const __m256d pa = _mm256_and_pd(pw, magnitude);
      /* the sign bit of lane r where bit r of neg[i] is set */
      const __m256i sel = _mm256_and_si256(_mm256_set1_epi64x(neg[i]), lane_bit);
      const __m256i sign = _mm256_slli_epi64(_mm256_cmpeq_epi64(sel, lane_bit), 63);
      const __m256d x = _mm256_xor_pd(
          _mm256_blendv_pd(_mm256_mul_pd(m, pa), _mm256_div_pd(m, pa), pw),
          _mm256_castsi256_pd(sign));
      if (dst[i])
        _mm256_storeu_pd(dst[i] + k, x);
    }
    k += ROWS;
    p = q;
  }
out:
  if (k > k0)
    for (size_t i = 0; i < ncols; i++)
      if (shape[i].misses) /* as aq_number_parse_shaped does */
        shape[i].misses = 0;
  *pp = p;
  return k;
}
size_t aq_csv_rows4(const char **pp, const char *end, size_t ncols, char sep,
                    aq_number_shape *shape, double *const *dst, size_t k, size_t cap) AVX2;

size_t aq_csv_rows4(const char **pp, const char *end, size_t ncols, char sep,
                    aq_number_shape *shape, double *const *dst, size_t k, size_t cap)
{
  if (ncols == 2) /* (time, acceleration): its own loop */
    return rows4(pp, end, 2, sep, shape, dst, k, cap);
  return rows4(pp, end, ncols, sep, shape, dst, k, cap);
}
size_t aq_csv_steps4(const double *t, size_t n, size_t i0, double est, double tol, double *lo,
                     double *hi, size_t *off) AVX2;

size_t aq_csv_steps4(const double *t, size_t n, size_t i0, double est, double tol, double *lo,
                     double *hi, size_t *off)
{
  __m256d a = _mm256_set1_pd(*lo), b = _mm256_set1_pd(*hi);
  const __m256d t0 = _mm256_set1_pd(t[0]), e = _mm256_set1_pd(est), tl = _mm256_set1_pd(tol);
  const __m256d magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
  __m256d idx = _mm256_setr_pd((double)i0, (double)i0 + 1, (double)i0 + 2, (double)i0 + 3);
  size_t i = i0;
  for (; n - i >= 4; i += 4) {
    const __m256d ti = _mm256_loadu_pd(t + i);
    const __m256d d = _mm256_sub_pd(ti, _mm256_loadu_pd(t + i - 1));
    a = _mm256_min_pd(d, a); /* d < a ? d : a */
    b = _mm256_max_pd(d, b); /* d > b ? d : b */
    const __m256d dev =
        _mm256_and_pd(_mm256_sub_pd(ti, _mm256_add_pd(t0, _mm256_mul_pd(idx, e))), magnitude);
    const int far = _mm256_movemask_pd(_mm256_cmp_pd(dev, tl, _CMP_GT_OQ));
    if (far && !*off)
      *off = i + (size_t)__builtin_ctz((unsigned)far);
    idx = _mm256_add_pd(idx, _mm256_set1_pd(4));
  }
  double la[4], hb[4];
  _mm256_storeu_pd(la, a);
  _mm256_storeu_pd(hb, b);
  for (int j = 0; j < 4; j++) {
    *lo = la[j] < *lo ? la[j] : *lo;
    *hi = hb[j] > *hi ? hb[j] : *hi;
  }
  return i;
}
#else
size_t aq_csv_rows4(const char **pp, const char *end, size_t ncols, char sep,
                    aq_number_shape *shape, double *const *dst, size_t k, size_t cap)
{
  (void)pp, (void)end, (void)ncols, (void)sep, (void)shape, (void)dst, (void)cap;
  return k;
}
size_t aq_csv_steps4(const double *t, size_t n, size_t i0, double est, double tol, double *lo,
                     double *hi, size_t *off)
{
  (void)t, (void)n, (void)est, (void)tol, (void)lo, (void)hi, (void)off;
  return i0;
}
#endif
