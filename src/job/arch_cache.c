/* arch_cache.c: built arches on disk (arch_cache.h). */
#include "arch_cache.h"

#include <stdint.h>
#include <stdlib.h>

#include "../io/sha256.h"
#include "cache_key.h"

#define KEY_FORMAT "archquake arch 2\n"

void aq_arch_cache_key(const aq_arch_sources *src, aq_bytes_out *key)
{
  aq_bytes_put_str(key, KEY_FORMAT, 0);
  aq_cache_key_platform(key);
  const char *part[3] = {src->text, src->data[0], src->data[1]};
  size_t n[3] = {src->ntext, src->ndata[0], src->ndata[1]};
  for (int k = 0; k < 3; k++) { /* each part apart: no two sets of files alike */
    char hex[AQ_SHA256_HEX] = "";
    aq_bytes_put_i64(key, part[k] != NULL);
    aq_bytes_put_i64(key, part[k] ? (int64_t)n[k] : 0);
    if (part[k])
      aq_sha256_hex(part[k], n[k], hex);
    aq_bytes_put_str(key, hex, 0);
  }
  aq_bytes_put_f64(key, src->friction); /* a command's --friction: another build */
  aq_bytes_put_i64(key, src->friction_table);
}

/* aq_arch_store over an aq_diskcache. */
static int get(void *ctx, const aq_arch_sources *src, const unsigned char **bytes, size_t *n,
               void **handle)
{
  aq_bytes_out key = {0};
  aq_arch_cache_key(src, &key);
  aq_diskcache_value *v = malloc(sizeof *v);
  int hit = !key.oom && v && aq_diskcache_get(ctx, key.data, key.n, v);
  free(key.data);
  if (!hit) {
    free(v);
    return 0;
  }
  *bytes = v->data;
  *n = v->n;
  *handle = v;
  return 1;
}

static void release(void *ctx, void *handle)
{
  (void)ctx;
  aq_diskcache_release(handle);
  free(handle);
}

static void put(void *ctx, const aq_arch_sources *src, const unsigned char *bytes, size_t n)
{
  aq_bytes_out key = {0};
  aq_arch_cache_key(src, &key);
  if (!key.oom)
    aq_diskcache_put(ctx, key.data, key.n, bytes, n);
  free(key.data);
}

aq_status aq_arch_cache_load(aq_diskcache *c, const char *path, const aq_arch_options *opt,
                             int *hit, aq_arch **out, aq_error *err)
{
  aq_arch_store s = {c, get, release, put};
  return aq_arch_load_stored_opts(path, opt, c ? &s : NULL, hit, out, err);
}
