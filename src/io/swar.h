/* swar.h: eight text bytes at a time in one 64-bit word ("SIMD within a
 * register"), for the readers' fixed-width fast paths (at2.c, csv.c), and
 * the text readers' line ends (aq_swar_line_end, aq_text_past_eol).
 * Pure functions of their arguments; the caller makes sure the eight bytes
 * it loads lie inside its buffer.
 *
 * A word holds the bytes p[0..8) with p[0] in its lowest byte, whatever
 * the machine's byte order; "byte i" below is p[i].  The digit tricks
 * follow the method described by D. Lemire, "Number parsing at a gigabyte
 * per second", Software: Practice and Experience 51(8), 2021 (section on
 * eight digits at once); the code is written here. */
#ifndef AQ_IO_SWAR_H
#define AQ_IO_SWAR_H

#include <stdint.h>

#define AQ_SWAR_ONES 0x0101010101010101ULL /* 0x01 in every byte */

/* The eight bytes at p, p[0] lowest (compilers make this one load on a
 * little-endian machine, a load and a byte swap on a big-endian one). */
static inline uint64_t aq_swar_load(const char *p)
{
  const unsigned char *u = (const unsigned char *)p;
  return (uint64_t)u[0] | (uint64_t)u[1] << 8 | (uint64_t)u[2] << 16 |
         (uint64_t)u[3] << 24 | (uint64_t)u[4] << 32 | (uint64_t)u[5] << 40 |
         (uint64_t)u[6] << 48 | (uint64_t)u[7] << 56;
}

/* 0x80 in each byte of w that is not an ASCII digit, 0 in the others.
 * x = w ^ '0' maps the digits, and only them, to 0..9.  In each byte,
 * (x & 0x7F) + 0x76 stays below 0x100 (so nothing carries into the next
 * byte) and has its high bit set exactly when x & 0x7F >= 10; or-ing x
 * itself marks the bytes >= 0x80 as well. */
static inline uint64_t aq_swar_nondigits(uint64_t w)
{
  uint64_t x = w ^ (0x30 * AQ_SWAR_ONES);
  return (((x & (0x7F * AQ_SWAR_ONES)) + 0x76 * AQ_SWAR_ONES) | x) & (0x80 * AQ_SWAR_ONES);
}

/* Byte i of w (0..7). */
static inline unsigned aq_swar_byte(uint64_t w, unsigned i)
{
  return (unsigned)(w >> (8 * i)) & 0xFF;
}

/* The number written by the digits in bytes 0..k-1 of w (1 <= k <= 8, all
 * digits; byte 0 the most significant).  Their values (w & 0x0F per byte)
 * are shifted up to fill the top k bytes, with zeros, as leading zeros,
 * below; the bytes after them fall off the top.  Then neighbouring lanes
 * merge three times, the lower (more significant) lane times its width's
 * power of ten plus the upper one: bytes into 2-digit 16-bit lanes (at most
 * 99), those into 4-digit 32-bit lanes (at most 9999), those into the
 * 8-digit value.  Nothing spills into the next lane: 9 * 10 + 9,
 * 99 * 100 + 99 and 9999 * 10^4 + 9999 fit in 8, 16 and 32 bits. */
static inline uint64_t aq_swar_digits(uint64_t w, unsigned k)
{
  uint64_t d = (w & (0x0F * AQ_SWAR_ONES)) << (8 * (8 - k));
  d = (d * 10 + (d >> 8)) & 0x00FF00FF00FF00FFULL;
  d = (d * 100 + (d >> 16)) & 0x0000FFFF0000FFFFULL;
  return (d * 10000 + (d >> 32)) & 0xFFFFFFFFULL;
}

/* The index (0..7) of the lowest byte of mask that has its high bit set;
 * mask != 0. */
static inline unsigned aq_swar_first(uint64_t mask)
{
#if defined(__GNUC__) || defined(__clang__)
  return (unsigned)__builtin_ctzll(mask) / 8;
#else
  unsigned i = 0;
  while (!(mask & (0x80ULL << (8 * i))))
    i++;
  return i;
#endif
}

/* Nonzero if some byte of w is below n (n <= 0x80), and then the lowest
 * byte with its high bit set in the result is the first such byte.
 * w - n in every byte borrows exactly from the bytes below n (and the
 * borrow may spill into higher bytes only above one of them); & ~w drops
 * the bytes whose own high bit was set. */
static inline uint64_t aq_swar_below(uint64_t w, unsigned n)
{
  return (w - n * AQ_SWAR_ONES) & ~w & (0x80 * AQ_SWAR_ONES);
}

/* The offset of the first LF or CR in s[i..n), or n: eight bytes at a time
 * (a byte equal to c is a zero byte of w ^ c, found by aq_swar_below(., 1)),
 * the last few one at a time. */
static inline size_t aq_swar_line_end(const char *s, size_t i, size_t n)
{
  for (; n - i >= 8; i += 8) {
    uint64_t w = aq_swar_load(s + i);
    uint64_t hit = aq_swar_below(w ^ ('\n' * AQ_SWAR_ONES), 1) |
                   aq_swar_below(w ^ ('\r' * AQ_SWAR_ONES), 1);
    if (hit)
      return i + aq_swar_first(hit);
  }
  while (i < n && s[i] != '\n' && s[i] != '\r')
    i++;
  return i;
}

/* Past the line end at p < end (*p is LF or CR): LF, CR LF, CR, or CRs
 * then LF, each one line, as every text reader counts them. */
static inline const char *aq_text_past_eol(const char *p, const char *end)
{
  if (*p == '\r') {
    while (p < end && *p == '\r')
      p++;
    if (p < end && *p == '\n')
      p++;
    return p;
  }
  return p + 1;
}

#endif
