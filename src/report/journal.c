/* journal.c: the append-only journal of completed work (see journal.h). */
#define _POSIX_C_SOURCE 200809L
#include "journal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "../io/sha256.h"

#define AQ_JOURNAL_MAGIC "AQJRNL01"
#define AQ_JOURNAL_MAGIC_BYTES 8
#define AQ_JOURNAL_LEN_BYTES 8 /* u64 little-endian payload length */

struct aq_journal {
  int fd;
  char *path;
  double sync_period_s; /* 0: every append is synced */
  double last_sync_s;   /* CLOCK_MONOTONIC time of the last sync */
  int unsynced;         /* entries written since the last sync */
  int dir_unsynced;     /* the directory is to be synced with the next sync */
};

static double monotonic_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void aq_journal_name(const char *target, char *buf, size_t n)
{
  snprintf(buf, n, "%s.journal", target);
}

static void put_u64le(unsigned char *p, uint64_t v)
{
  for (int i = 0; i < 8; i++)
    p[i] = (unsigned char)(v >> (8 * i));
}

static uint64_t get_u64le(const unsigned char *p)
{
  uint64_t v = 0;
  for (int i = 7; i >= 0; i--)
    v = v << 8 | p[i];
  return v;
}

/* write(2) until all n bytes are out (retrying EINTR and short writes). */
static int write_all(int fd, const void *p, size_t n)
{
  const unsigned char *b = p;
  while (n > 0) {
    ssize_t k = write(fd, b, n);
    if (k < 0 && errno == EINTR)
      continue;
    if (k <= 0) {
      if (k == 0)
        errno = EIO;
      return -1;
    }
    b += k;
    n -= (size_t)k;
  }
  return 0;
}

static aq_status sys_fail(aq_error *err, const char *path, const char *what)
{
  return aq_error_set(err, AQ_EIO, path, -1, -1, NULL, "cannot %s the journal: %s",
                      what, strerror(errno));
}

/* Sync the directory holding path, so that a new name survives a crash. */
static void sync_dir(const char *path)
{
  char *dir = strdup(path);
  if (!dir)
    return;
  char *slash = strrchr(dir, '/');
  const char *d = slash ? (slash == dir ? "/" : (*slash = '\0', dir)) : ".";
  int fd = open(d, O_RDONLY);
  if (fd >= 0) {
    fsync(fd);
    close(fd);
  }
  free(dir);
}

static aq_journal *journal_new(int fd, const char *path)
{
  aq_journal *j = malloc(sizeof *j);
  char *p = strdup(path);
  if (!j || !p) {
    free(j);
    free(p);
    return NULL;
  }
  j->fd = fd;
  j->path = p;
  j->sync_period_s = 0;
  j->last_sync_s = monotonic_s();
  j->unsynced = 0;
  j->dir_unsynced = 0;
  return j;
}

/* Sync the entries written (and the directory, once, after a deferred
 * create). */
static aq_status journal_sync(aq_journal *j, aq_error *err)
{
  if (fdatasync(j->fd) != 0)
    return sys_fail(err, j->path, "sync");
  if (j->dir_unsynced)
    sync_dir(j->path);
  j->dir_unsynced = 0;
  j->unsynced = 0;
  j->last_sync_s = monotonic_s();
  return AQ_OK;
}

aq_status aq_journal_append(aq_journal *j, const void *data, size_t n, aq_error *err)
{
  size_t total = AQ_JOURNAL_LEN_BYTES + n + AQ_SHA256_BYTES;
  unsigned char *frame = malloc(total);
  if (!frame)
    return aq_error_set(err, AQ_ENOMEM, j->path, -1, -1, NULL, "out of memory");
  put_u64le(frame, (uint64_t)n);
  if (n)
    memcpy(frame + AQ_JOURNAL_LEN_BYTES, data, n);
  aq_sha256_ctx c;
  aq_sha256_init(&c);
  aq_sha256_update(&c, frame, AQ_JOURNAL_LEN_BYTES + n);
  aq_sha256_final(&c, frame + AQ_JOURNAL_LEN_BYTES + n);
  /* one frame, one write loop: a kill between writes leaves a torn frame
   * that the checksum rejects */
  int rc = write_all(j->fd, frame, total);
  free(frame);
  if (rc != 0)
    return sys_fail(err, j->path, "append to");
  if (j->sync_period_s > 0 && monotonic_s() - j->last_sync_s < j->sync_period_s) {
    j->unsynced = 1; /* in the page cache: it survives a kill, not a crash */
    return AQ_OK;
  }
  return journal_sync(j, err);
}

void aq_journal_set_sync_period(aq_journal *j, double period_s)
{
  j->sync_period_s = period_s > 0 ? period_s : 0;
}

aq_status aq_journal_create(const char *path, const void *identity, size_t n,
                            double sync_period_s, aq_journal **out, aq_error *err)
{
  *out = NULL;
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
    return sys_fail(err, path, "create");
  aq_journal *j = journal_new(fd, path);
  if (!j) {
    close(fd);
    unlink(path);
    return aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
  }
  aq_journal_set_sync_period(j, sync_period_s);
  j->dir_unsynced = 1;
  aq_status s = AQ_OK;
  if (write_all(fd, AQ_JOURNAL_MAGIC, AQ_JOURNAL_MAGIC_BYTES) != 0)
    s = sys_fail(err, path, "write");
  if (s == AQ_OK)
    s = aq_journal_append(j, identity, n, err);
  if (s != AQ_OK) {
    aq_journal_remove(j, NULL);
    return s;
  }
  *out = j;
  return AQ_OK;
}

/* Read the whole file into *buf (*n bytes). */
static int slurp(int fd, unsigned char **buf, size_t *n)
{
  struct stat sb;
  *buf = NULL;
  *n = 0;
  if (fstat(fd, &sb) != 0)
    return -1;
  size_t size = (size_t)sb.st_size;
  unsigned char *b = malloc(size ? size : 1);
  if (!b) {
    errno = ENOMEM;
    return -1;
  }
  size_t got = 0;
  while (got < size) {
    ssize_t k = read(fd, b + got, size - got);
    if (k < 0 && errno == EINTR)
      continue;
    if (k <= 0)
      break; /* shorter than stat said: take what is there */
    got += (size_t)k;
  }
  *buf = b;
  *n = got;
  return 0;
}

void aq_journal_entries_free(aq_journal_entry *e, size_t n)
{
  for (size_t i = 0; e && i < n; i++)
    free(e[i].data);
  free(e);
}

aq_status aq_journal_open(const char *path, aq_journal **out,
                          aq_journal_entry **entries, size_t *nentries,
                          size_t *dropped_bytes, aq_error *err)
{
  *out = NULL;
  *entries = NULL;
  *nentries = 0;
  *dropped_bytes = 0;
  int fd = open(path, O_RDWR | O_CLOEXEC);
  if (fd < 0)
    return errno == ENOENT ? AQ_OK : sys_fail(err, path, "open");
  unsigned char *buf;
  size_t size;
  if (slurp(fd, &buf, &size) != 0) {
    aq_status s = sys_fail(err, path, "read");
    close(fd);
    return s;
  }
  aq_status s = AQ_OK;
  aq_journal_entry *e = NULL;
  size_t ne = 0, cap = 0, off = AQ_JOURNAL_MAGIC_BYTES;
  if (size < AQ_JOURNAL_MAGIC_BYTES && memcmp(buf, AQ_JOURNAL_MAGIC, size) == 0) {
    free(buf); /* empty or part of the magic: see the torn identity below */
    close(fd);
    return AQ_OK;
  }
  if (size < AQ_JOURNAL_MAGIC_BYTES ||
      memcmp(buf, AQ_JOURNAL_MAGIC, AQ_JOURNAL_MAGIC_BYTES) != 0) {
    s = aq_error_set(err, AQ_EFORMAT, path, -1, 0, "magic",
                     "expected an archquake journal (\"%s\"), got other bytes",
                     AQ_JOURNAL_MAGIC);
    goto done;
  }
  while (size - off >= AQ_JOURNAL_LEN_BYTES + AQ_SHA256_BYTES) {
    uint64_t len = get_u64le(buf + off);
    if (len > size - off - AQ_JOURNAL_LEN_BYTES - AQ_SHA256_BYTES)
      break; /* torn: the frame runs past the end */
    unsigned char sum[AQ_SHA256_BYTES];
    aq_sha256_ctx c;
    aq_sha256_init(&c);
    aq_sha256_update(&c, buf + off, AQ_JOURNAL_LEN_BYTES + (size_t)len);
    aq_sha256_final(&c, sum);
    if (memcmp(sum, buf + off + AQ_JOURNAL_LEN_BYTES + len, AQ_SHA256_BYTES) != 0)
      break; /* corrupt: this entry and all after it are dropped */
    if (ne == cap) {
      size_t nc = cap ? 2 * cap : 64;
      aq_journal_entry *ee = realloc(e, nc * sizeof *e);
      if (!ee) {
        s = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
        goto done;
      }
      e = ee;
      cap = nc;
    }
    e[ne].n = (size_t)len;
    e[ne].data = malloc(len ? (size_t)len : 1);
    if (!e[ne].data) {
      s = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
      goto done;
    }
    if (len)
      memcpy(e[ne].data, buf + off + AQ_JOURNAL_LEN_BYTES, (size_t)len);
    ne++;
    off += AQ_JOURNAL_LEN_BYTES + (size_t)len + AQ_SHA256_BYTES;
  }
  if (ne == 0 && (size - off < AQ_JOURNAL_LEN_BYTES + AQ_SHA256_BYTES ||
                  get_u64le(buf + off) > size - off - AQ_JOURNAL_LEN_BYTES - AQ_SHA256_BYTES)) {
    /* the magic and a torn identity: its creator was killed before the
     * journal held anything, as if there were none */
    free(buf);
    close(fd);
    return AQ_OK;
  }
  if (ne == 0) {
    s = aq_error_set(err, AQ_EFORMAT, path, -1, (long)off, "identity",
                     "expected a whole identity entry, got a torn or corrupt one");
    goto done;
  }
  if (off < size) { /* cut the torn tail so that appends follow whole entries */
    if (ftruncate(fd, (off_t)off) != 0 || fdatasync(fd) != 0) {
      s = sys_fail(err, path, "truncate");
      goto done;
    }
    *dropped_bytes = size - off;
  }
  if (lseek(fd, 0, SEEK_END) < 0) {
    s = sys_fail(err, path, "seek in");
    goto done;
  }
  if (!(*out = journal_new(fd, path)))
    s = aq_error_set(err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
done:
  free(buf);
  if (s != AQ_OK) {
    aq_journal_entries_free(e, ne);
    close(fd);
    return s;
  }
  *entries = e;
  *nentries = ne;
  return AQ_OK;
}

void aq_journal_close(aq_journal *j)
{
  if (!j)
    return;
  if (j->unsynced)
    journal_sync(j, NULL); /* kept for --resume: best effort, as after a crash */
  close(j->fd);
  free(j->path);
  free(j);
}

aq_status aq_journal_remove(aq_journal *j, aq_error *err)
{
  if (!j)
    return AQ_OK;
  aq_status s = AQ_OK;
  if (unlink(j->path) != 0 && errno != ENOENT)
    s = sys_fail(err, j->path, "remove");
  j->unsynced = 0; /* nothing left to keep */
  aq_journal_close(j);
  return s;
}
