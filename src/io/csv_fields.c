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

/* 10^e by index e + 22: sign bit clear, multiply by it; set, divide by its
 * magnitude (aq_number_exact's one operation). */
static const double pow_signed[2 * AQ_NUMBER_EXACT_POW_MAX + 1] = {
    -1e22, -1e21, -1e20, -1e19, -1e18, -1e17, -1e16, -1e15, -1e14, -1e13, -1e12,
    -1e11, -1e10, -1e9,  -1e8,  -1e7,  -1e6,  -1e5,  -1e4,  -1e3,  -1e2,  -1e1,
    1e0,   1e1,   1e2,   1e3,   1e4,   1e5,   1e6,   1e7,   1e8,   1e9,   1e10,
    1e11,  1e12,  1e13,  1e14,  1e15,  1e16,  1e17,  1e18,  1e19,  1e20,  1e21, 1e22};

/* One column's shape as vectors, the same in both 128-bit halves. */
typedef struct {
  __m256i digit, fixed, plus, minus, shuf;
  unsigned want2;     /* the shape's bytes in both halves' movemask bits */
  size_t len;
} col_vec;

static inline AVX2 __m256i twice(const unsigned char *b)
{
  return _mm256_broadcastsi128_si256(_mm_loadu_si128((const __m128i *)b));
}

static AVX2 void col_setup(col_vec *c, const aq_number_shape *sh)
{
  c->digit = twice(sh->digit);
  c->fixed = twice(sh->fixed);
  c->plus = twice(sh->plus);
  c->minus = twice(sh->minus);
  /* the mantissa digits, in order, to the last bytes; zeros before them */
  unsigned char shuf[16];
  size_t nd = 0;
  for (size_t j = 0; j < 16; j++)
    nd += sh->mant[j] != 0;
  memset(shuf, 0x80, sizeof shuf);
  for (size_t j = 0, r = 16 - nd; j < 16; j++)
    if (sh->mant[j])
      shuf[r++] = (unsigned char)j;
  c->shuf = twice(shuf);
  c->want2 = sh->want | sh->want << 16;
  c->len = sh->len;
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

/* The mantissas of two fields (d = window - '0'), per half as 32-bit lanes
 * [h, l, h, l]: h its digits but the last eight, l those eight. */
static inline AVX2 __m256i mantissa_two(__m256i d, const col_vec *c)
{
  const __m256i digits = _mm256_shuffle_epi8(d, c->shuf);
  const __m256i w2 = _mm256_set1_epi16(0x010A);           /* bytes 10, 1 */
  const __m256i w4 = _mm256_set1_epi32(0x00010064);       /* 100, 1 */
  const __m256i w8 = _mm256_set1_epi32(0x00012710);       /* 10000, 1 */
  __m256i t = _mm256_madd_epi16(_mm256_maddubs_epi16(digits, w2), w4);
  t = _mm256_packus_epi32(t, t);
  return _mm256_madd_epi16(t, w8);
}

/* The exponent of the field whose window is at w: the shape's, with the
 * field's exponent digits and sign; as an index into pow_signed, or -1 when
 * 10^e is not exact. */
static inline int exp_index(const aq_number_shape *sh, const char *w)
{
  int e = -(int)sh->frac;
  if (sh->has_exp) {
    int ex = 0;
    for (unsigned j = 0; j < sh->exp_digits; j++)
      ex = ex * 10 + (w[sh->exp_at + j] - '0');
    e += sh->exp_sign_at && w[sh->exp_sign_at] == '-' ? -ex : ex;
  }
  e += AQ_NUMBER_EXACT_POW_MAX;
  return (unsigned)e <= 2 * AQ_NUMBER_EXACT_POW_MAX ? e : -1;
}

size_t aq_csv_rows4(const char **pp, const char *end, size_t ncols, char sep,
                    aq_number_shape *shape, double *const *dst, size_t k, size_t cap) AVX2;

size_t aq_csv_rows4(const char **pp, const char *end, size_t ncols, char sep,
                    aq_number_shape *shape, double *const *dst, size_t k, size_t cap)
{
  col_vec col[AQ_CSV_FIELDS_COLS_MAX];
  for (size_t i = 0; i < ncols; i++)
    col_setup(&col[i], &shape[i]);
  const size_t k0 = k;
  const char *p = *pp;
  const __m256i order = _mm256_setr_epi32(0, 4, 2, 6, 1, 5, 3, 7);
  const __m256d magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
  while (cap - k >= ROWS) {
    /* the windows and signs: where the shapes put them */
    const char *w[AQ_CSV_FIELDS_COLS_MAX][ROWS];
    uint64_t sign[AQ_CSV_FIELDS_COLS_MAX][ROWS];
    const char *q = p;
    for (size_t r = 0; r < ROWS; r++)
      for (size_t i = 0; i < ncols; i++) {
        if (end - q < FIELD_ROOM)
          goto out;
        size_t off = *q == '-' || *q == '+';
        sign[i][r] = (uint64_t)(*q == '-') << 63;
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
    __m256d x[AQ_CSV_FIELDS_COLS_MAX];
    for (size_t i = 0; i < ncols; i++) {
      const col_vec *c = &col[i];
      const __m256i v01 = load_two(w[i][0], w[i][1]), v23 = load_two(w[i][2], w[i][3]);
      const __m256i zero = _mm256_set1_epi8('0');
      const __m256i d01 = _mm256_sub_epi8(v01, zero), d23 = _mm256_sub_epi8(v23, zero);
      const unsigned ok = (unsigned)_mm256_movemask_epi8(
          _mm256_and_si256(in_shape(v01, d01, c), in_shape(v23, d23, c)));
      if ((ok & c->want2) != c->want2)
        goto out;
      int e[ROWS];
      for (size_t r = 0; r < ROWS; r++)
        if ((e[r] = exp_index(&shape[i], w[i][r])) < 0)
          goto out;
      /* [h0 l0 h2 l2 | h1 l1 h3 l3] to [h0 h1 h2 h3 l0 l1 l2 l3] */
      const __m256i hl = _mm256_permutevar8x32_epi32(
          _mm256_unpacklo_epi64(mantissa_two(d01, c), mantissa_two(d23, c)), order);
      /* h < 10^7 (at most 15 digits): h 10^8 + l < 10^15, exact */
      const __m256d m =
          _mm256_add_pd(_mm256_mul_pd(_mm256_cvtepi32_pd(_mm256_castsi256_si128(hl)),
                                      _mm256_set1_pd(1e8)),
                        _mm256_cvtepi32_pd(_mm256_extracti128_si256(hl, 1)));
      const __m256d pw = _mm256_setr_pd(pow_signed[e[0]], pow_signed[e[1]], pow_signed[e[2]],
                                        pow_signed[e[3]]);
      const __m256d pa = _mm256_and_pd(pw, magnitude);
      /* m * 10^e or m / 10^-e: one rounding either way (aq_number_exact) */
      x[i] = _mm256_xor_pd(_mm256_blendv_pd(_mm256_mul_pd(m, pa), _mm256_div_pd(m, pa), pw),
                           _mm256_castsi256_pd(_mm256_loadu_si256((const __m256i *)sign[i])));
    }
    for (size_t i = 0; i < ncols; i++)
      if (dst[i])
        _mm256_storeu_pd(dst[i] + k, x[i]);
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
#else
size_t aq_csv_rows4(const char **pp, const char *end, size_t ncols, char sep,
                    aq_number_shape *shape, double *const *dst, size_t k, size_t cap)
{
  (void)pp, (void)end, (void)ncols, (void)sep, (void)shape, (void)dst, (void)cap;
  return k;
}
#endif
