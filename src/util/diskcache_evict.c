/* diskcache_evict.c: the scan of a store's directory and the eviction of
 * entries past its cap (diskcache.h): other builds' entries
 * first, then the least recently used. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "diskcache_impl.h"

/* An entry of the directory, as a scan found it. */
typedef struct {
  char name[NAME_LEN + 1]; /* in its kind's directory */
  int kind;                /* the index of its kind's directory in the scan */
  int other;               /* 1: another build's (or not readable as ours) */
  long long size;          /* bytes */
  struct timespec mtime;   /* its last use */
} scanned;

typedef struct {
  scanned *e;
  size_t n, cap;
  char **kinds; /* the kinds' directory names */
  size_t nkinds;
} scan_list;

static void scan_free(scan_list *l)
{
  for (size_t i = 0; i < l->nkinds; i++)
    free(l->kinds[i]);
  free(l->kinds);
  free(l->e);
  memset(l, 0, sizeof *l);
}

/* 1 if name is an entry's: 32 lower-case hex digits and ".aqc". */
static int entry_name(const char *name)
{
  if (strlen(name) != NAME_LEN || strcmp(name + 32, ".aqc") != 0)
    return 0;
  for (int i = 0; i < 32; i++)
    if (!((name[i] >= '0' && name[i] <= '9') || (name[i] >= 'a' && name[i] <= 'f')))
      return 0;
  return 1;
}

/* 1 if the entry open as fd is another build's: its key does not begin
 * with "archquake VERSION\n" and this build's line (any version: the
 * stores of one build may name it differently).  An entry too short to
 * tell, or not ours at all, counts as another's: it can never be read. */
static int other_build(const aq_diskcache *c, int fd)
{
  unsigned char b[PEEK];
  ssize_t got = pread(fd, b, sizeof b, 0);
  if (got < (ssize_t)HEAD || memcmp(b, MAGIC, 8) != 0)
    return 1;
  const unsigned char *k = b + HEAD, *end = b + got;
  static const char arch[] = "archquake ";
  if (end - k < (ptrdiff_t)sizeof arch - 1 || memcmp(k, arch, sizeof arch - 1) != 0)
    return 1;
  const unsigned char *nl = memchr(k, '\n', (size_t)(end - k));
  size_t nb = strlen(c->build);
  return !nl || (size_t)(end - nl - 1) < nb || memcmp(nl + 1, c->build, nb) != 0;
}

/* Every entry under c->top (each directory there is a kind's), its size
 * and time into *l, and the total bytes; stale temporaries are removed on
 * the way. */
static long long scan(const aq_diskcache *c, scan_list *l)
{
  long long total = 0;
  DIR *top = opendir(c->top);
  if (!top)
    return 0;
  struct timespec now;
  clock_gettime(CLOCK_REALTIME, &now);
  for (struct dirent *t; (t = readdir(top));) {
    if (t->d_name[0] == '.')
      continue;
    int kfd = openat(dirfd(top), t->d_name, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (kfd < 0)
      continue; /* not a directory (the FFTW wisdom file), or gone */
    DIR *kd = fdopendir(kfd);
    if (!kd) {
      close(kfd);
      continue;
    }
    int kind = -1;
    char **k = realloc(l->kinds, (l->nkinds + 1) * sizeof *k);
    if (k && (k[l->nkinds] = strdup(t->d_name))) {
      l->kinds = k;
      kind = (int)l->nkinds++;
    } else if (k)
      l->kinds = k;
    for (struct dirent *e; (e = readdir(kd));) {
      struct stat sb;
      int is_entry = entry_name(e->d_name);
      if (!is_entry && !strstr(e->d_name, ".aqc.tmp."))
        continue;
      if (fstatat(kfd, e->d_name, &sb, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(sb.st_mode))
        continue;
      if (!is_entry) { /* a temporary: a writer's at work, or a killed one's */
        if (now.tv_sec - sb.st_mtim.tv_sec > STALE_TMP_S)
          unlinkat(kfd, e->d_name, 0);
        continue;
      }
      total += (long long)sb.st_size;
      if (kind < 0)
        continue; /* out of memory: not a candidate, it stays */
      if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 256;
        scanned *m = realloc(l->e, cap * sizeof *m);
        if (!m)
          continue; /* not a candidate: it stays */
        l->e = m;
        l->cap = cap;
      }
      scanned *s = &l->e[l->n++];
      memcpy(s->name, e->d_name, NAME_LEN + 1);
      s->kind = kind;
      s->size = (long long)sb.st_size;
      s->mtime = sb.st_mtim;
      s->other = 0;
    }
    closedir(kd);
  }
  closedir(top);
  return total;
}

/* The order of eviction: other builds' entries first, then the least
 * recently used; a tie by name, so that every process removes the same. */
static int evict_order(const void *pa, const void *pb)
{
  const scanned *a = pa, *b = pb;
  if (a->other != b->other)
    return b->other - a->other;
  if (a->mtime.tv_sec != b->mtime.tv_sec)
    return a->mtime.tv_sec < b->mtime.tv_sec ? -1 : 1;
  if (a->mtime.tv_nsec != b->mtime.tv_nsec)
    return a->mtime.tv_nsec < b->mtime.tv_nsec ? -1 : 1;
  return strcmp(a->name, b->name);
}

/* A scan, and when the directory holds more than the cap, removal of
 * entries until it holds at most 9/10 of it (so that the next eviction is
 * a tenth of the cap's writes away); returns the bytes left.  Under
 * evict_lock (or at close).  Another process removing the same entry at
 * once is fine: its unlink or ours fails with ENOENT, and both count it
 * gone. */
long long aq_dc_evict(aq_diskcache *c)
{
  scan_list l = {0};
  long long total = scan(c, &l);
  long long target = (long long)(c->max - c->max / 10);
  size_t removed = 0;
  if (total > (long long)c->max) {
    char path[PATH_MAX];
    for (size_t i = 0; i < l.n; i++) { /* whose build: read only when evicting */
      snprintf(path, sizeof path, "%s/%s/%s", c->top, l.kinds[l.e[i].kind], l.e[i].name);
      int fd = open(path, O_RDONLY | O_CLOEXEC);
      l.e[i].other = fd < 0 || other_build(c, fd);
      if (fd >= 0)
        close(fd);
    }
    qsort(l.e, l.n, sizeof *l.e, evict_order);
    for (size_t i = 0; i < l.n && total > target; i++) {
      snprintf(path, sizeof path, "%s/%s/%s", c->top, l.kinds[l.e[i].kind], l.e[i].name);
      if (unlink(path) == 0)
        removed++;
      else if (errno != ENOENT)
        continue; /* it stays: its bytes too */
      total -= l.e[i].size;
    }
  }
  scan_free(&l);
  c->dirty = 0;
  pthread_mutex_lock(&c->lock);
  c->counts.scans++;
  c->counts.evicted += removed;
  pthread_mutex_unlock(&c->lock);
  return total;
}

/* After a write of n bytes: the total as known, and a scan (with eviction
 * if the directory is over the cap) when it passes the cap, or when this
 * store has written a tenth of the cap since its last scan (other
 * processes may have written too). */
void aq_dc_bound(aq_diskcache *c, long long n)
{
  pthread_mutex_lock(&c->evict_lock);
  c->dirty += n;
  if (c->used >= 0)
    c->used += n;
  if (c->used > (long long)c->max || c->dirty > (long long)(c->max / 10))
    c->used = aq_dc_evict(c);
  pthread_mutex_unlock(&c->evict_lock);
}

