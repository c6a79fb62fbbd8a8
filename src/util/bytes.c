/* bytes.c: values as bytes and back (bytes.h). */
#include "bytes.h"

#include <stdlib.h>
#include <string.h>

void aq_bytes_put(aq_bytes_out *b, const void *p, size_t n)
{
  if (b->oom || n == 0)
    return;
  if (b->cap - b->n < n) {
    size_t nc = b->cap ? b->cap : 1024;
    while (nc - b->n < n)
      nc *= 2;
    unsigned char *d = realloc(b->data, nc);
    if (!d) {
      b->oom = 1;
      return;
    }
    b->data = d;
    b->cap = nc;
  }
  memcpy(b->data + b->n, p, n);
  b->n += n;
}

void aq_bytes_put_i64(aq_bytes_out *b, int64_t v)
{
  aq_bytes_put(b, &v, sizeof v);
}

void aq_bytes_put_f64(aq_bytes_out *b, double v)
{
  aq_bytes_put(b, &v, sizeof v);
}

void aq_bytes_put_str(aq_bytes_out *b, const char *s, size_t cap)
{
  uint64_t n = !s ? 0 : cap ? strnlen(s, cap - 1) : strlen(s);
  aq_bytes_put(b, &n, sizeof n);
  aq_bytes_put(b, s, (size_t)n);
}

static int fail(aq_bytes_in *r, const char *what, size_t at)
{
  if (!r->bad) {
    r->bad = what ? what : "";
    r->bad_at = at;
  }
  return -1;
}

int aq_bytes_get(aq_bytes_in *r, void *p, size_t n, const char *what)
{
  if (r->bad)
    return -1;
  if (r->n - r->at < n)
    return fail(r, what, r->at);
  if (n)
    memcpy(p, r->data + r->at, n);
  r->at += n;
  return 0;
}

int64_t aq_bytes_get_i64(aq_bytes_in *r, const char *what)
{
  int64_t v = 0;
  return aq_bytes_get(r, &v, sizeof v, what) == 0 ? v : 0;
}

double aq_bytes_get_f64(aq_bytes_in *r, const char *what)
{
  double v = 0;
  return aq_bytes_get(r, &v, sizeof v, what) == 0 ? v : 0;
}

int64_t aq_bytes_get_int(aq_bytes_in *r, int64_t lo, int64_t hi, const char *what)
{
  int64_t v = aq_bytes_get_i64(r, what);
  if (!r->bad && (v < lo || v > hi))
    fail(r, what, r->at - sizeof v);
  return r->bad ? 0 : v;
}

size_t aq_bytes_get_count(aq_bytes_in *r, size_t item_bytes, const char *what)
{
  uint64_t v = 0;
  if (aq_bytes_get(r, &v, sizeof v, what) != 0)
    return 0;
  if (v > (r->n - r->at) / (item_bytes ? item_bytes : 1)) {
    fail(r, what, r->at - sizeof v);
    return 0;
  }
  return (size_t)v;
}

int aq_bytes_get_str(aq_bytes_in *r, char *s, size_t cap, char **dup, const char *what)
{
  if (s && cap)
    s[0] = '\0';
  size_t start = r->at, k = aq_bytes_get_count(r, 1, what);
  if (r->bad)
    return -1;
  if (s && k >= cap)
    return fail(r, what, start);
  char *d = s;
  if (!s && !(d = *dup = malloc(k + 1)))
    return fail(r, what, start);
  memcpy(d, r->data + r->at, k);
  d[k] = '\0';
  r->at += k;
  return 0;
}
