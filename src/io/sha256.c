/* sha256.c: SHA-256 as specified in FIPS PUB 180-4, Secure Hash Standard
 * (NIST, August 2015), section 6.2; constants from section 4.2.2 and the
 * initial hash value from section 5.3.3.  See sha256.h. */
#define _POSIX_C_SOURCE 200809L
#include "sha256.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

/* K(0..63): the first 32 bits of the fractional parts of the cube roots of
 * the first 64 primes (4.2.2). */
static const uint32_t K[64] = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1,
    0x923f82a4, 0xab1c5ed5, 0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3,
    0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174, 0xe49b69c1, 0xefbe4786,
    0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147,
    0x06ca6351, 0x14292967, 0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13,
    0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85, 0xa2bfe8a1, 0xa81a664b,
    0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a,
    0x5b9cca4f, 0x682e6ff3, 0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208,
    0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

static uint32_t rotr(uint32_t x, unsigned n) { return (x >> n) | (x << (32 - n)); }

/* The six logical functions of 4.1.2. */
#define CH(x, y, z) (((x) & (y)) ^ (~(x) & (z)))
#define MAJ(x, y, z) (((x) & (y)) ^ ((x) & (z)) ^ ((y) & (z)))
#define BSIG0(x) (rotr((x), 2) ^ rotr((x), 13) ^ rotr((x), 22))
#define BSIG1(x) (rotr((x), 6) ^ rotr((x), 11) ^ rotr((x), 25))
#define SSIG0(x) (rotr((x), 7) ^ rotr((x), 18) ^ ((x) >> 3))
#define SSIG1(x) (rotr((x), 17) ^ rotr((x), 19) ^ ((x) >> 10))

/* Process one 512-bit block M(i) (6.2.2, steps 1-4). */
static void block(uint32_t h[8], const unsigned char *m)
{
  uint32_t w[64];
  for (int t = 0; t < 16; t++) /* big-endian words (3.1) */
    w[t] = (uint32_t)m[4 * t] << 24 | (uint32_t)m[4 * t + 1] << 16 |
           (uint32_t)m[4 * t + 2] << 8 | (uint32_t)m[4 * t + 3];
  for (int t = 16; t < 64; t++)
    w[t] = SSIG1(w[t - 2]) + w[t - 7] + SSIG0(w[t - 15]) + w[t - 16];
  uint32_t a = h[0], b = h[1], c = h[2], d = h[3];
  uint32_t e = h[4], f = h[5], g = h[6], hh = h[7];
  for (int t = 0; t < 64; t++) {
    uint32_t t1 = hh + BSIG1(e) + CH(e, f, g) + K[t] + w[t];
    uint32_t t2 = BSIG0(a) + MAJ(a, b, c);
    hh = g;
    g = f;
    f = e;
    e = d + t1;
    d = c;
    c = b;
    b = a;
    a = t1 + t2;
  }
  h[0] += a;
  h[1] += b;
  h[2] += c;
  h[3] += d;
  h[4] += e;
  h[5] += f;
  h[6] += g;
  h[7] += hh;
}

void aq_sha256_init(aq_sha256_ctx *c)
{
  static const uint32_t h0[8] = {0x6a09e667, 0xbb67ae85, 0x3c6ef372,
                                 0xa54ff53a, 0x510e527f, 0x9b05688c,
                                 0x1f83d9ab, 0x5be0cd19}; /* 5.3.3 */
  memcpy(c->h, h0, sizeof h0);
  c->nbytes = 0;
  c->nblk = 0;
}

void aq_sha256_update(aq_sha256_ctx *c, const void *data, size_t n)
{
  const unsigned char *p = data;
  c->nbytes += n;
  if (c->nblk) {
    size_t k = 64 - c->nblk < n ? 64 - c->nblk : n;
    memcpy(c->blk + c->nblk, p, k);
    c->nblk += k;
    p += k;
    n -= k;
    if (c->nblk < 64)
      return;
    block(c->h, c->blk);
    c->nblk = 0;
  }
  for (; n >= 64; p += 64, n -= 64)
    block(c->h, p);
  memcpy(c->blk, p, n);
  c->nblk = n;
}

void aq_sha256_final(aq_sha256_ctx *c, unsigned char out[AQ_SHA256_BYTES])
{
  /* Padding (5.1.1): a 1 bit, zeros to 448 mod 512 bits, then the message
   * length in bits as a 64-bit big-endian integer. */
  uint64_t bits = c->nbytes * 8;
  c->blk[c->nblk++] = 0x80;
  if (c->nblk > 56) {
    memset(c->blk + c->nblk, 0, 64 - c->nblk);
    block(c->h, c->blk);
    c->nblk = 0;
  }
  memset(c->blk + c->nblk, 0, 56 - c->nblk);
  for (int k = 0; k < 8; k++)
    c->blk[56 + k] = (unsigned char)(bits >> (56 - 8 * k));
  block(c->h, c->blk);
  for (int k = 0; k < 8; k++) {
    out[4 * k] = (unsigned char)(c->h[k] >> 24);
    out[4 * k + 1] = (unsigned char)(c->h[k] >> 16);
    out[4 * k + 2] = (unsigned char)(c->h[k] >> 8);
    out[4 * k + 3] = (unsigned char)c->h[k];
  }
}

static void to_hex(const unsigned char d[AQ_SHA256_BYTES], char hex[AQ_SHA256_HEX])
{
  static const char digit[] = "0123456789abcdef";
  for (int k = 0; k < AQ_SHA256_BYTES; k++) {
    hex[2 * k] = digit[d[k] >> 4];
    hex[2 * k + 1] = digit[d[k] & 15];
  }
  hex[2 * AQ_SHA256_BYTES] = '\0';
}

void aq_sha256_hex(const void *data, size_t n, char hex[AQ_SHA256_HEX])
{
  aq_sha256_ctx c;
  unsigned char d[AQ_SHA256_BYTES];
  aq_sha256_init(&c);
  aq_sha256_update(&c, data, n);
  aq_sha256_final(&c, d);
  to_hex(d, hex);
}

aq_status aq_sha256_file(const char *path, char hex[AQ_SHA256_HEX], aq_error *err)
{
  hex[0] = '\0';
  FILE *f = fopen(path, "rb");
  if (!f)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL,
                        "cannot open to hash: %s", strerror(errno));
  aq_sha256_ctx c;
  aq_sha256_init(&c);
  unsigned char buf[1 << 16];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, f)) > 0)
    aq_sha256_update(&c, buf, n);
  int bad = ferror(f);
  int e = errno;
  fclose(f);
  if (bad)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL,
                        "cannot read to hash: %s", strerror(e));
  unsigned char d[AQ_SHA256_BYTES];
  aq_sha256_final(&c, d);
  to_hex(d, hex);
  return AQ_OK;
}
