/* diskcache.c: keyed entries on disk, checked and written atomically
 * (diskcache.h).  An entry is read through mmap (its pages come from the
 * page cache, populated at once; the value is decoded from the mapping,
 * not copied first). */
#define _GNU_SOURCE /* dl_iterate_phdr */
#include "diskcache.h"

#include "../error.h"

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

#include "diskcache_impl.h"


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


void aq_diskcache_close(aq_diskcache *c)
{
  if (!c)
    return;
  if (c->build && c->dirty > 0) /* the last check of the cap (under no lock: the store's last use) */
    aq_dc_evict(c);
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
  aq_dc_bound(c, (long long)(HEAD + nk + nv + TAIL));
  return 1;
}
