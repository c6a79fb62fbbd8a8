/* diskcache.h: values kept on disk between processes, each under a key
 * (any bytes), for work that a later run would otherwise do again (the
 * processed records of src/job/subject_cache.h).  A store is a directory
 * of entries, one file per key, "<dir>/<kind>/<32 hex digits>.aqc", the
 * digits from the SHA-256 of the key.
 *
 * An entry holds its whole key, its value and a checksum of everything
 * before it (XXH3-64, Debian's libxxhash: about 10 GB/s, where zlib's
 * CRC-32 took a quarter of the time a cached record saves):
 *   "AQCACHE2", u64 key bytes, u64 value bytes, the key, the value,
 *   u64 XXH3-64 (native byte order).  A read compares the whole key, so two keys whose
 * file names collide are never confused: the other key's entry is a miss
 * (and the next write replaces it).  An entry that is short, long, not
 * ours or fails its checksum is corrupt: one note says so, and it is a miss.
 * Every key is prefixed with the store's identity (the program's version
 * and the executable's build: its ELF build-id, else its size and time),
 * so a rebuilt program never reads what another build wrote.
 *
 * Writes are atomic: a temporary "<entry>.tmp.<pid>.<n>" (made with
 * O_EXCL, registered with cleanup.h) renamed onto the entry, so a reader
 * (another thread, another process) sees a whole entry or none, and of
 * two writers of one key the last rename wins with a whole entry.  A
 * write never fails its caller: a directory that cannot be made or
 * written gives one note per store, and the run goes on without storing.
 *
 * The directory is bounded (aq_diskcache_set_max; AQ_DISKCACHE_MAX_DEFAULT):
 * every entry under it, of every kind, counts.  A read of an entry touches
 * its modification time (when older than a minute), the time of its last
 * use.  A store that writes scans the directory when it closes, and also
 * while it runs each time it has written a tenth of the cap or the total
 * it knows (its last scan's and its writes since) passes the cap; a scan
 * that finds more than the cap removes entries until at most 9/10 of it
 * is left: the other builds' entries first (this build can never read
 * them), then the least recently used.  A store that only reads never
 * scans.  A removed entry is a miss for a later read; a reader that has it
 * open keeps its whole contents (an unlinked file lives until unmapped).
 * Temporaries older than an hour (a killed writer's) go too; younger ones
 * are a writer's at work and stay.  So when every writer has closed, the
 * directory holds at most the cap; while several write, it may hold more
 * by what they wrote since their last scans.
 *
 * Nothing here prints: notes are kept (under a lock, the store is shared
 * by threads) for the caller to take (aq_diskcache_notes).  The store owns
 * its notes; a value read is the caller's (aq_diskcache_release). */
#ifndef AQ_UTIL_DISKCACHE_H
#define AQ_UTIL_DISKCACHE_H

#include <stddef.h>

typedef struct aq_diskcache aq_diskcache;

/* The default directory into buf[n]: $XDG_CACHE_HOME/archquake (an absolute
 * $XDG_CACHE_HOME), else $HOME/.cache/archquake.  Returns buf, or NULL when
 * neither is set (then there is no default store). */
const char *aq_diskcache_default_dir(char *buf, size_t n);

/* A store in dir (NULL: the default) for entries of kind (a directory
 * name, e.g. "records"), identified by version (e.g. "0.1.0 (abc123)")
 * and the running executable's build.  Makes nothing on disk until the
 * first write.  NULL when out of memory or when there is no directory. */
aq_diskcache *aq_diskcache_open(const char *dir, const char *kind, const char *version);

/* The default cap of a directory's entries, bytes (docs/cache.md: about
 * 1,600 prepared records of the shared records' mean size). */
#define AQ_DISKCACHE_MAX_DEFAULT (512ull << 20)

/* Bound the directory (every kind under dir) to max_bytes (> 0) from the
 * next write on.  Stores of one directory should share one cap: each
 * evicts down to its own. */
void aq_diskcache_set_max(aq_diskcache *c, unsigned long long max_bytes);

/* The cap of every store opened from now on in this process (> 0; the
 * start: AQ_DISKCACHE_MAX_DEFAULT): a command's --cache-max, so that its
 * stores of every kind share it. */
void aq_diskcache_set_default_max(unsigned long long max_bytes);

/* Free the store, after a last scan if it wrote (see above); NULL is
 * fine. */
void aq_diskcache_close(aq_diskcache *c);

/* The store's directory of entries ("<dir>/<kind>"). */
const char *aq_diskcache_dir(const aq_diskcache *c);

/* A value read: data[0..n), valid until aq_diskcache_release. */
typedef struct {
  const unsigned char *data;
  size_t n;
  void *map_;      /* the entry's mapping */
  size_t mapped_;
} aq_diskcache_value;

/* The entry of key[0..nkey): 1 and *v on a hit (aq_diskcache_release);
 * 0 on a miss (none, another key's, or corrupt: a note), *v empty. */
int aq_diskcache_get(aq_diskcache *c, const void *key, size_t nkey, aq_diskcache_value *v);

/* Release a value read (an empty one is fine). */
void aq_diskcache_release(aq_diskcache_value *v);

/* Store value[0..nvalue) under key[0..nkey).  Returns 1 if stored, 0 if
 * not (a note the first time a write fails). */
int aq_diskcache_put(aq_diskcache *c, const void *key, size_t nkey, const void *value,
                     size_t nvalue);

/* The entry's file name for key into buf[n] (for tests). */
void aq_diskcache_entry_path(const aq_diskcache *c, const void *key, size_t nkey, char *buf,
                             size_t n);

/* The notes so far, one per line ("" when none), moved to the caller
 * (malloc'd, or NULL when none): the store keeps no copy. */
char *aq_diskcache_notes(aq_diskcache *c);

/* Counters: entries read whole (hits), misses, corrupt entries, writes;
 * scans of the directory and entries this store removed to keep its cap. */
typedef struct {
  size_t hits, misses, corrupt, writes;
  size_t scans, evicted;
} aq_diskcache_counts;
aq_diskcache_counts aq_diskcache_count(aq_diskcache *c);

#endif
