/* sha256.h: SHA-256 (FIPS 180-4, section 6.2) of byte strings and files,
 * for the content hashes of a suite's inputs (records and arches) in the
 * results file and the identity keys of `archquake compare`.
 *
 * Streaming: aq_sha256_init, aq_sha256_update (any number of times, any
 * lengths), aq_sha256_final.  The context holds no heap memory.  Nothing
 * prints; aq_sha256_file reports through aq_error.
 */
#ifndef AQ_IO_SHA256_H
#define AQ_IO_SHA256_H

#include <stddef.h>
#include <stdint.h>

#include "../error.h"

#define AQ_SHA256_BYTES 32
#define AQ_SHA256_HEX 65 /* 64 lower-case hex digits and the NUL */

typedef struct {
  uint32_t h[8];         /* hash value H(i) (FIPS 180-4, 6.2.2) */
  uint64_t nbytes;       /* message length so far, bytes */
  unsigned char blk[64]; /* partial block */
  size_t nblk;           /* bytes in blk */
  int accel;             /* 1: the processor's SHA instructions are used */
} aq_sha256_ctx;

void aq_sha256_init(aq_sha256_ctx *c);
void aq_sha256_update(aq_sha256_ctx *c, const void *data, size_t n);
/* Pad, finish and write the 32-byte digest to out. */
void aq_sha256_final(aq_sha256_ctx *c, unsigned char out[AQ_SHA256_BYTES]);

/* on = 1: contexts initialised from now on use the portable code even where
 * the processor has SHA instructions (for tests and benchmarks; not
 * thread-safe: set it before hashing starts). */
void aq_sha256_portable(int on);

/* Digest of data[0..n) as 64 lower-case hex digits into hex. */
void aq_sha256_hex(const void *data, size_t n, char hex[AQ_SHA256_HEX]);

/* Digests of a[0..na) into hexa and b[0..nb) into hexb, as aq_sha256_hex
 * gives them, computed together: with the SHA instructions the two
 * messages' rounds interleave (about 1.6 times the throughput of hashing
 * them one after the other). */
void aq_sha256_hex2(const void *a, size_t na, char hexa[AQ_SHA256_HEX], const void *b,
                    size_t nb, char hexb[AQ_SHA256_HEX]);

/* Digest of the file at path as hex (as sha256sum prints it).  Returns
 * AQ_OK, or AQ_EIO with err naming the file and the system's reason. */
aq_status aq_sha256_file(const char *path, char hex[AQ_SHA256_HEX],
                         aq_error *err);

#endif
