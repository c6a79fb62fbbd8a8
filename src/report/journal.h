/* journal.h: an append-only journal of completed work, so that an
 * interrupted suite (SIGINT, SIGTERM, kill -9, a crash, a full disk) can be
 * resumed (`archquake --resume`) without losing what was done.
 *
 * The file ("<target>.journal" beside the results file) is the 8-byte magic
 * "AQJRNL01" followed by entries, each
 *     u64 length (little-endian) | payload (length bytes) | SHA-256 of both
 * written with one write loop and synced (fdatasync) before the call
 * returns, or, with aq_journal_set_sync_period, at most once per period
 * (an entry written is in the journal for any later reader at once, and
 * survives a kill of the process; only an operating-system crash or a power
 * failure can lose the entries written since the last sync, whose work is
 * then done again).  Entry 0 is the identity of the command that wrote it (the
 * caller's bytes; archquake writes text lines); every other entry is one
 * unit of completed work in the caller's own encoding.  A torn or corrupt
 * entry (kill -9 mid-write, a bad sector) fails its length or checksum test:
 * it and everything after it are dropped when the journal is opened again,
 * and the file is truncated to the last whole entry.
 *
 * The payloads are opaque here: a single process, or the leader of several,
 * appends entries and reads them back in order (util/bytes.h builds and
 * parses them).  Nothing prints; failures fill
 * aq_error (input = the journal's path) and return a status.  The journal
 * object owns its descriptor; entries returned by aq_journal_open belong to
 * the caller (aq_journal_entries_free).
 */
#ifndef AQ_REPORT_JOURNAL_H
#define AQ_REPORT_JOURNAL_H

#include <stddef.h>

#include "../error.h"

typedef struct aq_journal aq_journal;

typedef struct {
  unsigned char *data; /* payload (owned by the array) */
  size_t n;            /* its length, bytes */
} aq_journal_entry;

/* The journal's name for a results file target ("<target>.journal") into
 * buf[n]. */
void aq_journal_name(const char *target, char *buf, size_t n);

/* Create (or replace) the journal at path holding only the identity entry,
 * with aq_journal_set_sync_period(sync_period_s): with 0, synced with its
 * directory before the call returns; with a period, both are synced by the
 * first sync (a journal lost to a crash before it is as good as none: the
 * suite starts over).  *out is the journal, open for appending. */
aq_status aq_journal_create(const char *path, const void *identity, size_t n,
                            double sync_period_s, aq_journal **out, aq_error *err);

/* Open an existing journal: every whole entry is returned in *entries
 * (*nentries of them, the identity first); a torn or corrupt tail is cut off
 * (its size in *dropped_bytes) and the journal is left open for appending in
 * *out.  A file that does not exist gives AQ_OK with *out NULL and no
 * entries, and so does one that aq_journal_create left unfinished when it
 * was killed (empty, part of the magic, or the magic and a torn identity
 * entry: nothing was done yet); a file without the magic or with a corrupt
 * identity entry gives AQ_EFORMAT. */
aq_status aq_journal_open(const char *path, aq_journal **out,
                          aq_journal_entry **entries, size_t *nentries,
                          size_t *dropped_bytes, aq_error *err);

/* Append one entry and sync it.  On failure (a full disk...) the journal
 * holds at most a torn entry, which the next open drops. */
aq_status aq_journal_append(aq_journal *j, const void *data, size_t n,
                            aq_error *err);

/* Sync on an append only if period_s (s, > 0) has passed since the last
 * sync (0: every append, the default).  An append that syncs covers every
 * entry before it; aq_journal_close syncs what is left. */
void aq_journal_set_sync_period(aq_journal *j, double period_s);

/* Close, keeping the file (NULL is fine). */
void aq_journal_close(aq_journal *j);

/* Close and delete the file (the work it guarded is safely written). */
aq_status aq_journal_remove(aq_journal *j, aq_error *err);

void aq_journal_entries_free(aq_journal_entry *e, size_t n);

#endif
