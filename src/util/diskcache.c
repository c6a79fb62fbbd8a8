/* diskcache.c: keyed entries on disk, checked and written atomically
 * (diskcache.h).  An entry is read through mmap (its pages come from the
 * page cache, populated at once; the value is decoded from the mapping,
 * not copied first). */
#define _GNU_SOURCE /* dl_iterate_phdr */
#include "diskcache.h"

#include "../error.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <link.h>
#include <nettle/sha2.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <xxhash.h>

#include "cleanup.h"

#define MAGIC "AQCACHE2"
#define HEAD (8 + 2 * sizeof(uint64_t)) /* magic, key bytes, value bytes */
#define TAIL sizeof(uint64_t)           /* the checksum */
#define NOTES_MAX 4096                  /* bytes of notes kept; later ones dropped */
/* A read touches an entry's time only when it is older than this, s: the
 * order of use is kept to the minute, and a warm run repeated at once
 * writes no inode. */
#define TOUCH_AFTER_S 60
/* A temporary older than this, s, was left by a writer that was killed
 * (a write takes milliseconds): removed by a scan. */
#define STALE_TMP_S 3600
/* An entry's name: 32 hex digits and ".aqc". */
#define NAME_LEN (32 + 4)
/* The bytes of an entry read to tell its build: the head and the start of
 * its key (the identity's two lines). */
#define PEEK (HEAD + 1024)

struct aq_diskcache {
  char *top;     /* the store's directory */
  char *dir;     /* <top>/<kind> */
  unsigned char *id; /* the identity every key is prefixed with */
  size_t nid;
  char *build;   /* its second line, the build ("build-id HEX\n") */
  pthread_mutex_t evict_lock; /* one scan at a time; guards what follows */
  unsigned long long max; /* the cap of every entry under top, bytes */
  long long used;  /* bytes under top: the last scan's and this store's writes since; -1: no scan yet */
  long long dirty; /* bytes this store wrote since its last scan */
  pthread_mutex_t lock; /* guards what follows */
  int write_failed;     /* 1: a write failed (noted once) */
  unsigned long tmp_seq;
  char notes[NOTES_MAX];
  size_t nnotes;
  aq_diskcache_counts counts;
};

/* The cap of the stores opened next (aq_diskcache_set_default_max). */
static _Atomic unsigned long long default_max = AQ_DISKCACHE_MAX_DEFAULT;

void aq_diskcache_set_default_max(unsigned long long max_bytes)
{
  if (max_bytes > 0)
    atomic_store(&default_max, max_bytes);
}

const char *aq_diskcache_default_dir(char *buf, size_t n)
{
  const char *x = getenv("XDG_CACHE_HOME"), *h = getenv("HOME");
  int len;
  if (x && x[0] == '/')
    len = snprintf(buf, n, "%s/archquake", x);
  else if (h && h[0] == '/')
    len = snprintf(buf, n, "%s/.cache/archquake", h);
  else
    return NULL;
  return len > 0 && (size_t)len < n ? buf : NULL;
}

/* The main program's GNU build-id note (a digest of its code and data,
 * written by the linker), as hex into out[cap]. */
static int build_id_cb(struct dl_phdr_info *info, size_t size, void *data)
{
  (void)size;
  char *out = data; /* first object: the executable */
  for (int i = 0; i < info->dlpi_phnum; i++) {
    const ElfW(Phdr) *ph = &info->dlpi_phdr[i];
    if (ph->p_type != PT_NOTE)
      continue;
    const unsigned char *p = (const unsigned char *)(info->dlpi_addr + ph->p_vaddr);
    const unsigned char *end = p + ph->p_memsz;
    while (p + sizeof(ElfW(Nhdr)) <= end) {
      const ElfW(Nhdr) *nh = (const ElfW(Nhdr) *)p;
      size_t name = (nh->n_namesz + 3) & ~(size_t)3, desc = (nh->n_descsz + 3) & ~(size_t)3;
      const unsigned char *d = p + sizeof *nh + name;
      if (d + nh->n_descsz > end)
        break;
      if (nh->n_type == NT_GNU_BUILD_ID && nh->n_namesz == 4 &&
          memcmp(p + sizeof *nh, "GNU", 4) == 0 && nh->n_descsz <= 64) {
        for (size_t k = 0; k < nh->n_descsz; k++)
          sprintf(out + 2 * k, "%02x", d[k]);
        return 1;
      }
      p += sizeof *nh + name + desc;
    }
  }
  return 1; /* only the first object */
}

/* The running build's identity into buf[n]: "build-id HEX", else the
 * executable's size and modification time. */
static void build_identity(char *buf, size_t n)
{
  char id[160] = "";
  dl_iterate_phdr(build_id_cb, id);
  if (id[0]) {
    snprintf(buf, n, "build-id %s", id);
    return;
  }
  struct stat sb;
  if (stat("/proc/self/exe", &sb) == 0)
    snprintf(buf, n, "exe %lld bytes %lld.%09ld ino %llu", (long long)sb.st_size,
             (long long)sb.st_mtim.tv_sec, sb.st_mtim.tv_nsec, (unsigned long long)sb.st_ino);
  else
    snprintf(buf, n, "exe unknown pid %ld", (long)getpid()); /* never shared */
}

aq_diskcache *aq_diskcache_open(const char *dir, const char *kind, const char *version)
{
  char def[PATH_MAX];
  if (!dir && !(dir = aq_diskcache_default_dir(def, sizeof def)))
    return NULL;
  aq_diskcache *c = calloc(1, sizeof *c);
  char build[256];
  build_identity(build, sizeof build);
  size_t nid = strlen(version) + strlen(build) + 64;
  if (!c || !(c->top = strdup(dir)) || !(c->dir = malloc(strlen(dir) + strlen(kind) + 2)) ||
      !(c->id = malloc(nid))) {
    aq_diskcache_close(c);
    return NULL;
  }
  sprintf(c->dir, "%s/%s", dir, kind);
  int len = snprintf((char *)c->id, nid, "archquake %s\n%s\n", version, build);
  c->nid = len > 0 ? (size_t)len : 0;
  if (!(c->build = malloc(strlen(build) + 2))) {
    aq_diskcache_close(c);
    return NULL;
  }
  sprintf(c->build, "%s\n", build);
  c->max = atomic_load(&default_max);
  c->used = -1;
  pthread_mutex_init(&c->lock, NULL);
  pthread_mutex_init(&c->evict_lock, NULL);
  return c;
}

static long long evict(aq_diskcache *c);

void aq_diskcache_close(aq_diskcache *c)
{
  if (!c)
    return;
  if (c->build && c->dirty > 0) /* the last check of the cap (under no lock: the store's last use) */
    evict(c);
  if (c->build) {
    pthread_mutex_destroy(&c->lock);
    pthread_mutex_destroy(&c->evict_lock);
  }
  free(c->top);
  free(c->dir);
  free(c->id);
  free(c->build);
  free(c);
}

void aq_diskcache_set_max(aq_diskcache *c, unsigned long long max_bytes)
{
  if (!c || max_bytes == 0)
    return;
  pthread_mutex_lock(&c->evict_lock);
  c->max = max_bytes;
  pthread_mutex_unlock(&c->evict_lock);
}

const char *aq_diskcache_dir(const aq_diskcache *c)
{
  return c->dir;
}

/* Paths in notes: whole up to this, else "..." and their end, the file's
 * name whole (aq_path_fit). */
#define NOTE_PATH_MAX 512

/* One note line (under the lock); one cut by the room left ends in "...". */
__attribute__((format(printf, 2, 3))) static void note_locked(aq_diskcache *c, const char *fmt, ...)
{
  if (c->nnotes + 2 >= sizeof c->notes)
    return;
  va_list ap;
  va_start(ap, fmt);
  size_t room = sizeof c->notes - c->nnotes - 1;
  int len = vsnprintf(c->notes + c->nnotes, room, fmt, ap);
  va_end(ap);
  if (len < 0)
    return;
  if ((size_t)len >= room && room >= 4) {
    size_t k = c->nnotes + room - 4;
    while (k > c->nnotes && ((unsigned char)c->notes[k] & 0xC0) == 0x80)
      k--;
    memcpy(c->notes + k, "...", 4);
  }
  c->nnotes = strlen(c->notes);
  c->notes[c->nnotes++] = '\n';
  c->notes[c->nnotes] = '\0';
}

char *aq_diskcache_notes(aq_diskcache *c)
{
  if (!c)
    return NULL;
  pthread_mutex_lock(&c->lock);
  char *s = c->nnotes ? strdup(c->notes) : NULL;
  c->nnotes = 0;
  c->notes[0] = '\0';
  pthread_mutex_unlock(&c->lock);
  return s;
}

aq_diskcache_counts aq_diskcache_count(aq_diskcache *c)
{
  aq_diskcache_counts k = {0, 0, 0, 0, 0, 0};
  if (!c)
    return k;
  pthread_mutex_lock(&c->lock);
  k = c->counts;
  pthread_mutex_unlock(&c->lock);
  return k;
}

/* The digest of the store's identity and key: the entry's name. */
static void key_digest(const aq_diskcache *c, const void *key, size_t nkey,
                       unsigned char d[SHA256_DIGEST_SIZE])
{
  struct sha256_ctx h;
  sha256_init(&h);
  sha256_update(&h, c->nid, c->id);
  sha256_update(&h, nkey, key);
  sha256_digest(&h, SHA256_DIGEST_SIZE, d);
}

void aq_diskcache_entry_path(const aq_diskcache *c, const void *key, size_t nkey, char *buf,
                             size_t n)
{
  unsigned char d[SHA256_DIGEST_SIZE];
  key_digest(c, key, nkey, d);
  char hex[33];
  for (int k = 0; k < 16; k++)
    sprintf(hex + 2 * k, "%02x", d[k]);
  snprintf(buf, n, "%s/%s.aqc", c->dir, hex);
}

static void count(aq_diskcache *c, size_t *field)
{
  pthread_mutex_lock(&c->lock);
  (*field)++;
  pthread_mutex_unlock(&c->lock);
}

/* A corrupt entry: noted, counted, a miss. */
static int corrupt(aq_diskcache *c, const char *path, const char *why)
{
  pthread_mutex_lock(&c->lock);
  c->counts.corrupt++;
  c->counts.misses++;
  char p[NOTE_PATH_MAX + 1];
  note_locked(c, "cache entry %s is corrupt (%s): not used, computed again",
              aq_path_fit(path, NOTE_PATH_MAX, p, sizeof p), why);
  pthread_mutex_unlock(&c->lock);
  return 0;
}

int aq_diskcache_get(aq_diskcache *c, const void *key, size_t nkey, aq_diskcache_value *v)
{
  memset(v, 0, sizeof *v);
  char path[PATH_MAX];
  aq_diskcache_entry_path(c, key, nkey, path, sizeof path);
  int fd = open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    count(c, &c->counts.misses);
    return 0;
  }
  struct stat sb;
  void *map = MAP_FAILED;
  size_t got = 0;
  int stated = fstat(fd, &sb) == 0;
  if (stated && sb.st_size > 0) {
    got = (size_t)sb.st_size;
    map = mmap(NULL, got, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
  }
  if (stated && sb.st_size == 0) {
    close(fd);
    return corrupt(c, path, "empty");
  }
  if (map == MAP_FAILED) {
    close(fd);
    count(c, &c->counts.misses);
    return 0;
  }
  /* a read is a use: the entry's time for eviction (a store that cannot
   * change it, read-only, keeps the time it has) */
  struct timespec now;
  if (clock_gettime(CLOCK_REALTIME, &now) == 0 && now.tv_sec - sb.st_mtim.tv_sec > TOUCH_AFTER_S)
    (void)futimens(fd, NULL);
  close(fd);
  const unsigned char *buf = map;
  uint64_t nk = 0, nv = 0;
  if (got >= HEAD) {
    memcpy(&nk, buf + 8, sizeof nk);
    memcpy(&nv, buf + 8 + sizeof nk, sizeof nv);
  }
  const char *why = NULL;
  if (got < HEAD + TAIL || memcmp(buf, MAGIC, 8) != 0)
    why = "not an archquake cache entry";
  else if (nk > got || nv > got || HEAD + nk + nv + TAIL != got)
    why = "its length disagrees with its header: truncated or overwritten";
  else {
    uint64_t want;
    memcpy(&want, buf + got - TAIL, sizeof want);
    if (XXH3_64bits(buf, got - TAIL) != want)
      why = "checksum mismatch";
  }
  if (why) {
    munmap(map, got);
    return corrupt(c, path, why);
  }
  const unsigned char *k = buf + HEAD;
  if (nk != c->nid + nkey || memcmp(k, c->id, c->nid) != 0 ||
      memcmp(k + c->nid, key, nkey) != 0) { /* another key of the same name */
    munmap(map, got);
    count(c, &c->counts.misses);
    return 0;
  }
  v->data = buf + HEAD + nk;
  v->n = nv;
  v->map_ = map;
  v->mapped_ = got;
  count(c, &c->counts.hits);
  return 1;
}

void aq_diskcache_release(aq_diskcache_value *v)
{
  if (v->map_)
    munmap(v->map_, v->mapped_);
  memset(v, 0, sizeof *v);
}

/* write(2) all of p[0..n), through EINTR. */
static int write_all(int fd, const void *p, size_t n)
{
  const unsigned char *q = p;
  while (n > 0) {
    ssize_t w = write(fd, q, n);
    if (w < 0 && errno == EINTR)
      continue;
    if (w <= 0)
      return -1;
    q += w;
    n -= (size_t)w;
  }
  return 0;
}

/* mkdir, an existing directory being fine. */
static int make_dir(const char *d)
{
  return mkdir(d, 0700) == 0 || errno == EEXIST ? 0 : -1;
}

/* The store's directories: every missing one above the top one (the XDG
 * base-directory rule: a missing $XDG_CACHE_HOME is made, 0700), the top
 * one, the kind's.  A --cache-dir the user names is checked before the run
 * (src/app/opt_table.c), so only the default directory grows parents here. */
static int make_dirs(const aq_diskcache *c)
{
  char parent[PATH_MAX];
  snprintf(parent, sizeof parent, "%s", c->top);
  for (char *p = parent + 1; (p = strchr(p, '/')) != NULL; p++) {
    *p = '\0';
    make_dir(parent); /* a failure shows at the top one below */
    *p = '/';
  }
  return make_dir(c->top) == 0 && make_dir(c->dir) == 0 ? 0 : -1;
}

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
static long long evict(aq_diskcache *c)
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
static void bound(aq_diskcache *c, long long n)
{
  pthread_mutex_lock(&c->evict_lock);
  c->dirty += n;
  if (c->used >= 0)
    c->used += n;
  if (c->used > (long long)c->max || c->dirty > (long long)(c->max / 10))
    c->used = evict(c);
  pthread_mutex_unlock(&c->evict_lock);
}

static int write_failed(aq_diskcache *c, const char *what, int e)
{
  pthread_mutex_lock(&c->lock);
  char p[NOTE_PATH_MAX + 1];
  if (!c->write_failed)
    note_locked(c, "cannot write the cache in %s (%s: %s): the run goes on without storing",
                aq_path_fit(c->dir, NOTE_PATH_MAX, p, sizeof p), what, strerror(e));
  c->write_failed = 1;
  pthread_mutex_unlock(&c->lock);
  return 0;
}

int aq_diskcache_put(aq_diskcache *c, const void *key, size_t nkey, const void *value,
                     size_t nvalue)
{
  pthread_mutex_lock(&c->lock);
  int failed = c->write_failed;
  unsigned long seq = c->tmp_seq++;
  pthread_mutex_unlock(&c->lock);
  if (failed)
    return 0;
  if (make_dirs(c) != 0)
    return write_failed(c, "mkdir", errno);
  char path[PATH_MAX], tmp[PATH_MAX + 64];
  aq_diskcache_entry_path(c, key, nkey, path, sizeof path);
  snprintf(tmp, sizeof tmp, "%s.tmp.%ld.%lu", path, (long)getpid(), seq);
  int slot = aq_cleanup_add(tmp);
  int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    int e = errno;
    aq_cleanup_remove(slot);
    return write_failed(c, "create", e);
  }
  unsigned char head[HEAD];
  uint64_t nk = c->nid + nkey, nv = nvalue;
  memcpy(head, MAGIC, 8);
  memcpy(head + 8, &nk, sizeof nk);
  memcpy(head + 8 + sizeof nk, &nv, sizeof nv);
  XXH3_state_t *h = XXH3_createState();
  uint64_t sum = 0;
  if (h && XXH3_64bits_reset(h) == XXH_OK && XXH3_64bits_update(h, head, HEAD) == XXH_OK &&
      XXH3_64bits_update(h, c->id, c->nid) == XXH_OK &&
      XXH3_64bits_update(h, key, nkey) == XXH_OK &&
      XXH3_64bits_update(h, value, nvalue) == XXH_OK)
    sum = XXH3_64bits_digest(h);
  else
    errno = ENOMEM;
  int bad = !h || sum == 0 || write_all(fd, head, HEAD) || write_all(fd, c->id, c->nid) ||
            write_all(fd, key, nkey) || write_all(fd, value, nvalue) ||
            write_all(fd, &sum, sizeof sum);
  XXH3_freeState(h);
  int e = errno;
  if (close(fd) != 0 && !bad) {
    bad = 1;
    e = errno;
  }
  if (!bad && rename(tmp, path) != 0) {
    bad = 1;
    e = errno;
  }
  if (bad)
    unlink(tmp);
  aq_cleanup_remove(slot);
  if (bad)
    return write_failed(c, "write", e);
  count(c, &c->counts.writes);
  bound(c, (long long)(HEAD + nk + nv + TAIL));
  return 1;
}
