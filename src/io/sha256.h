/* sha256.h: SHA-256 of byte strings and files by nettle (Debian's
 * nettle-dev), for the content hashes of a suite's inputs (records and
 * arches) in the results file, the identity keys of `archquake compare`, the
 * journal's frames and the FFTW wisdom cache.
 *
 * Streaming: aq_sha256_init, aq_sha256_update (any number of times, any
 * lengths), aq_sha256_final; the context is nettle's and holds no heap
 * memory.  Nothing prints; aq_sha256_file reports through aq_error.
 */
#ifndef AQ_IO_SHA256_H
#define AQ_IO_SHA256_H

#include <errno.h>
#include <nettle/sha2.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "../error.h"

#define AQ_SHA256_BYTES 32 /* = SHA256_DIGEST_SIZE */
#define AQ_SHA256_HEX 65   /* 64 lower-case hex digits and the NUL */

typedef struct sha256_ctx aq_sha256_ctx;

static inline void aq_sha256_init(aq_sha256_ctx *c) { sha256_init(c); }

static inline void aq_sha256_update(aq_sha256_ctx *c, const void *data, size_t n)
{
  sha256_update(c, n, (const uint8_t *)data);
}

/* Write the 32-byte digest to out (the context is reset). */
static inline void aq_sha256_final(aq_sha256_ctx *c, unsigned char out[AQ_SHA256_BYTES])
{
  sha256_digest(c, AQ_SHA256_BYTES, out);
}

/* The digest d as 64 lower-case hex digits into hex. */
static inline void aq_sha256_hexify_(const unsigned char d[AQ_SHA256_BYTES],
                                     char hex[AQ_SHA256_HEX])
{
  static const char digits[] = "0123456789abcdef";
  for (int i = 0; i < AQ_SHA256_BYTES; i++) {
    hex[2 * i] = digits[d[i] >> 4];
    hex[2 * i + 1] = digits[d[i] & 15];
  }
  hex[2 * AQ_SHA256_BYTES] = '\0';
}

/* Digest of data[0..n) as 64 lower-case hex digits into hex. */
static inline void aq_sha256_hex(const void *data, size_t n, char hex[AQ_SHA256_HEX])
{
  aq_sha256_ctx c;
  unsigned char d[AQ_SHA256_BYTES];
  aq_sha256_init(&c);
  aq_sha256_update(&c, data, n);
  aq_sha256_final(&c, d);
  aq_sha256_hexify_(d, hex);
}

/* Digests of a[0..na) into hexa and b[0..nb) into hexb (one after the
 * other). */
static inline void aq_sha256_hex2(const void *a, size_t na, char hexa[AQ_SHA256_HEX],
                                  const void *b, size_t nb, char hexb[AQ_SHA256_HEX])
{
  aq_sha256_hex(a, na, hexa);
  aq_sha256_hex(b, nb, hexb);
}

/* Digest of the file at path as hex (as sha256sum prints it).  Returns
 * AQ_OK, or AQ_EIO with err naming the file and the system's reason. */
static inline aq_status aq_sha256_file(const char *path, char hex[AQ_SHA256_HEX],
                                       aq_error *err)
{
  hex[0] = '\0';
  FILE *f = fopen(path, "rb");
  if (!f)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "cannot open to hash: %s",
                        strerror(errno));
  aq_sha256_ctx c;
  aq_sha256_init(&c);
  unsigned char buf[1 << 16];
  size_t got;
  while ((got = fread(buf, 1, sizeof buf, f)) > 0)
    aq_sha256_update(&c, buf, got);
  int bad = ferror(f), e = errno;
  fclose(f);
  if (bad)
    return aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "cannot read to hash: %s",
                        strerror(e));
  unsigned char d[AQ_SHA256_BYTES];
  aq_sha256_final(&c, d);
  aq_sha256_hexify_(d, hex);
  return AQ_OK;
}

#endif
