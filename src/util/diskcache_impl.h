/* diskcache_impl.h: the store's inside, shared by diskcache.c (entries:
 * read, written, named) and diskcache_evict.c (the scan of the directory
 * and the eviction past the cap).  Private to src/util. */
#ifndef AQ_UTIL_DISKCACHE_IMPL_H
#define AQ_UTIL_DISKCACHE_IMPL_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

#include "diskcache.h"

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

/* A scan, and when the directory holds more than the cap, removal of
 * entries until it holds at most 9/10 of it; the bytes left
 * (diskcache_evict.c).  Under evict_lock (or at close). */
long long aq_dc_evict(aq_diskcache *c);
/* After a write of n bytes: the total as known, and a scan (with eviction)
 * when due (diskcache_evict.c). */
void aq_dc_bound(aq_diskcache *c, long long n);

#endif
