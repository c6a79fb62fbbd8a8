/* bytes.h: values as bytes and back: archquake-mpi's messages (a task's
 * results) and the journal's entries (a record written).  Native byte
 * order and layout: the ranks of one job share a machine type, and a
 * journal is read back only by the build that wrote it.
 *
 * aq_bytes_out grows as values are put; running out of memory sets oom and
 * ignores later puts (free data with free()).  aq_bytes_in reads in order;
 * a read past the end, or a value out of the range asked, sets bad (the
 * name of what was read, or "" when none was given) and bad_at (its byte
 * offset), and every later read fails too (giving 0 or "").  Nothing here
 * prints. */
#ifndef AQ_UTIL_BYTES_H
#define AQ_UTIL_BYTES_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
  unsigned char *data;
  size_t n, cap;
  int oom;
} aq_bytes_out;

void aq_bytes_put(aq_bytes_out *b, const void *p, size_t n);
void aq_bytes_put_i64(aq_bytes_out *b, int64_t v);
void aq_bytes_put_f64(aq_bytes_out *b, double v);
/* A string as a u64 length and its bytes (NULL as ""); at most cap - 1
 * bytes of it when cap > 0 (what a char[cap] holds). */
void aq_bytes_put_str(aq_bytes_out *b, const char *s, size_t cap);

typedef struct {
  const unsigned char *data;
  size_t n, at;
  const char *bad;  /* NULL while every read fitted */
  size_t bad_at;
} aq_bytes_in;

/* Each returns 0, or -1 once the reader is bad. */
int aq_bytes_get(aq_bytes_in *r, void *p, size_t n, const char *what);
int64_t aq_bytes_get_i64(aq_bytes_in *r, const char *what);
double aq_bytes_get_f64(aq_bytes_in *r, const char *what);
/* An integer in [lo, hi]. */
int64_t aq_bytes_get_int(aq_bytes_in *r, int64_t lo, int64_t hi, const char *what);
/* A count of items of item_bytes each that the rest of the input can hold. */
size_t aq_bytes_get_count(aq_bytes_in *r, size_t item_bytes, const char *what);
/* A string put by aq_bytes_put_str into s[cap] (NUL-terminated; longer than
 * cap - 1 bytes is bad), or with s NULL a malloc'd copy in *dup. */
int aq_bytes_get_str(aq_bytes_in *r, char *s, size_t cap, char **dup, const char *what);

#endif
