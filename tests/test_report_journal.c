/* test_report_journal.c: the journal (src/report/journal.c) read back
 * entry by entry; its frame layout (8-byte magic, u64 little-endian length,
 * payload, SHA-256 of length and payload) checked byte for byte, the
 * digest computed independently (Python's hashlib); a torn tail at every
 * possible cut is dropped and appends continue after the last whole entry. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "report/journal.h"

/* The test's own payloads (high-entropy lengths). */
static const char *const payload[3] = {"identity: suite 7 x 3", "abc",
                                        "record 0: rows 0.31882870091777438"};

static void write_journal(const char *path)
{
  aq_journal *j = NULL;
  aq_error err;
  aq_check(aq_journal_create(path, payload[0], strlen(payload[0]), 0.0, &j, &err) == AQ_OK,
           "created");
  for (int k = 1; j && k < 3; k++)
    aq_check(aq_journal_append(j, payload[k], strlen(payload[k]), &err) == AQ_OK,
             "appended %d", k);
  aq_journal_close(j);
}

AQ_TEST(report_journal_frames_and_torn_tails)
{
  char dir[512], path[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/r.h5.journal", dir);
  char name[700];
  aq_journal_name(path, name, sizeof name);
  aq_check(strstr(name, "r.h5.journal.journal") != NULL, "name: target + .journal");

  /* absent: no journal, no error */
  aq_journal *j = NULL;
  aq_journal_entry *e = NULL;
  size_t ne = 9, dropped = 9;
  aq_error err;
  aq_check(aq_journal_open(path, &j, &e, &ne, &dropped, &err) == AQ_OK && !j && ne == 0,
           "absent journal: AQ_OK, nothing");

  write_journal(path);
  size_t n = 0;
  unsigned char *bytes = (unsigned char *)aq_test_read_file(path, &n);
  size_t want = 8;
  for (int k = 0; k < 3; k++)
    want += 8 + strlen(payload[k]) + 32;
  aq_check(bytes && n == want, "size %zu = magic + 3 frames (%zu)", n, want);
  aq_check(bytes && memcmp(bytes, "AQJRNL01", 8) == 0, "magic");
  /* frame 1 holds "abc": its length word, then the payload, then the
   * SHA-256 of the 11 bytes 03 00 00 00 00 00 00 00 'a' 'b' 'c' */
  size_t off = 8 + 8 + strlen(payload[0]) + 32;
  static const unsigned char len3[8] = {3, 0, 0, 0, 0, 0, 0, 0};
  aq_check(bytes && memcmp(bytes + off, len3, 8) == 0 && memcmp(bytes + off + 8, "abc", 3) == 0,
           "frame 1: little-endian length and payload");
  /* digest of those 11 bytes, from Python's hashlib.sha256 */
  static const unsigned char sum[32] = {
      0xce, 0x91, 0xdc, 0x5e, 0xec, 0x01, 0x39, 0xad, 0xf0, 0x91, 0x90, 0x0d, 0x22, 0x59, 0x71, 0xd6,
      0xad, 0x24, 0x6a, 0x84, 0x5b, 0xad, 0x79, 0x1b, 0x56, 0x93, 0xa9, 0xd0, 0xd5, 0x5d, 0xd3, 0x91};
  aq_check(bytes && memcmp(bytes + off + 11, sum, 32) == 0, "frame 1: its SHA-256");

  aq_check(aq_journal_open(path, &j, &e, &ne, &dropped, &err) == AQ_OK && j && ne == 3 &&
               dropped == 0,
           "three whole entries, nothing dropped (%zu, %zu)", ne, dropped);
  for (size_t k = 0; k < ne && k < 3; k++)
    aq_check(e[k].n == strlen(payload[k]) && memcmp(e[k].data, payload[k], e[k].n) == 0,
             "entry %zu read back", k);
  aq_journal_entries_free(e, ne);
  aq_journal_close(j);

  /* every cut inside the last frame: it is dropped, the two before kept,
   * and an append after the cut reads back */
  size_t last = n - (8 + strlen(payload[2]) + 32);
  int bad = 0;
  for (size_t cut = last + 1; cut < n && bytes; cut++) {
    FILE *f = fopen(path, "wb");
    fwrite(bytes, 1, cut, f);
    fclose(f);
    if (aq_journal_open(path, &j, &e, &ne, &dropped, &err) != AQ_OK || ne != 2 ||
        dropped != cut - last) {
      bad++;
      aq_journal_entries_free(e, ne);
      aq_journal_close(j);
      continue;
    }
    aq_journal_entries_free(e, ne);
    aq_journal_append(j, "xyz", 3, &err);
    aq_journal_close(j);
    aq_journal_open(path, &j, &e, &ne, &dropped, &err);
    bad += !(ne == 3 && e[2].n == 3 && memcmp(e[2].data, "xyz", 3) == 0 && dropped == 0);
    aq_journal_entries_free(e, ne);
    aq_journal_close(j);
  }
  aq_check(bad == 0, "torn tail dropped at every cut (%d failed of %zu)", bad, n - last - 1);

  /* one flipped payload byte in the middle frame: it and all after it go */
  write_journal(path);
  FILE *f = fopen(path, "r+b");
  fseek(f, (long)(off + 9), SEEK_SET);
  fputc('B', f);
  fclose(f);
  aq_check(aq_journal_open(path, &j, &e, &ne, &dropped, &err) == AQ_OK && ne == 1 &&
               dropped == n - off,
           "corrupt frame and the rest dropped (%zu entries, %zu bytes)", ne, dropped);
  aq_journal_entries_free(e, ne);
  aq_check(aq_journal_remove(j, &err) == AQ_OK && access(path, F_OK) != 0, "removed");

  /* what a creation killed half-way leaves (empty, part of the magic, the
   * magic and a torn identity): nothing was done, as if there were no
   * journal */
  static const char *const unfinished[] = {"", "AQJR", "AQJRNL01\x05", "AQJRNL01"};
  for (size_t k = 0; k < sizeof unfinished / sizeof *unfinished; k++) {
    f = fopen(path, "wb");
    fputs(unfinished[k], f);
    fclose(f);
    j = NULL;
    aq_check(aq_journal_open(path, &j, &e, &ne, &dropped, &err) == AQ_OK && !j && ne == 0,
             "unfinished creation \"%s\": no journal", unfinished[k]);
  }
  /* a first record cut at every byte of the identity entry: the same */
  int bad_cut = 0;
  for (size_t cut = 0; cut < 8 + 8 + strlen(payload[0]) + 32; cut++) {
    f = fopen(path, "wb");
    fwrite(bytes, 1, cut, f);
    fclose(f);
    j = NULL;
    bad_cut += aq_journal_open(path, &j, &e, &ne, &dropped, &err) != AQ_OK || j;
    aq_journal_close(j);
  }
  aq_check(bad_cut == 0, "identity cut at every byte: no journal (%d failed)", bad_cut);

  /* no magic, or a whole identity entry that is corrupt: AQ_EFORMAT naming
   * the file */
  static const char *const refused[] = {"AQJRNL02", "AQJRX", "not a journal"};
  for (size_t k = 0; k < sizeof refused / sizeof *refused; k++) {
    f = fopen(path, "wb");
    fputs(refused[k], f);
    fclose(f);
    aq_check(aq_journal_open(path, &j, &e, &ne, &dropped, &err) == AQ_EFORMAT && !j &&
                 strstr(err.input, "r.h5.journal"),
             "no magic (\"%s\"): AQ_EFORMAT", refused[k]);
  }
  f = fopen(path, "wb");
  bytes[8 + 8] ^= 1; /* the identity's first payload byte */
  fwrite(bytes, 1, 8 + 8 + strlen(payload[0]) + 32, f);
  bytes[8 + 8] ^= 1;
  fclose(f);
  aq_check(aq_journal_open(path, &j, &e, &ne, &dropped, &err) == AQ_EFORMAT && !j &&
               strstr(err.input, "r.h5.journal"),
           "corrupt identity: AQ_EFORMAT");
  free(bytes);
}

/* With a sync period, the creation and appends that do not sync still reach
 * the file at once (a killed suite keeps them): each is read back whole by a
 * second open of the journal while the first is still open, before any
 * close. */
AQ_TEST(report_journal_sync_period_keeps_every_entry)
{
  char dir[512], path[700];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/p.h5.journal", dir);
  aq_journal *j = NULL;
  aq_error err;
  aq_check(aq_journal_create(path, payload[0], strlen(payload[0]), 3600.0, &j, &err) == AQ_OK,
           "created");
  if (!j)
    return;
  /* no append within the test syncs, nor the creation */
  for (int k = 1; k < 3; k++) {
    aq_check(aq_journal_append(j, payload[k], strlen(payload[k]), &err) == AQ_OK,
             "appended %d", k);
    aq_journal *r = NULL;
    aq_journal_entry *e = NULL;
    size_t ne = 0, dropped = 9;
    aq_check(aq_journal_open(path, &r, &e, &ne, &dropped, &err) == AQ_OK,
             "opened beside the writer");
    aq_check(ne == (size_t)k + 1 && dropped == 0, "entries %zu (want %d), dropped %zu", ne,
             k + 1, dropped);
    for (size_t i = 0; i < ne && i <= (size_t)k; i++)
      aq_check(e[i].n == strlen(payload[i]) && memcmp(e[i].data, payload[i], e[i].n) == 0,
               "entry %zu read back", i);
    aq_journal_entries_free(e, ne);
    aq_journal_close(r);
  }
  aq_journal_close(j);
  unlink(path);
}
