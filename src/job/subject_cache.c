/* subject_cache.c: prepared subjects on disk (subject_cache.h). */
#define _DEFAULT_SOURCE /* madvise(2)'s MADV_POPULATE_WRITE */
#define _POSIX_C_SOURCE 200809L
#include "subject_cache.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cache_key.h"

#define KEY_FORMAT "archquake prepared subject 1\n"

/* The options go into the key field by field (strings as strings: the
 * bytes after a string's end are not always the same).  A field added to
 * either struct must be added to the key (read_opts_key, proc_opts_key). */
_Static_assert(sizeof(aq_read_opts) == 41336,
               "aq_read_opts changed: add the new field to the cache key "
               "(src/job/subject_cache.c, read_opts_key), then update this size");
_Static_assert(sizeof(aq_signal_opts) == 152,
               "aq_signal_opts changed: add the new field to the cache key "
               "(src/job/subject_cache.c, proc_opts_key), then update this size");
/* A record's metadata is stored as its bytes, its three pointers (path,
 * name, acc_mps2) apart: a pointer field added to aq_record must be
 * stored apart too. */
_Static_assert(sizeof(aq_record) == 2496,
               "aq_record changed: check that subject_cache.c stores every pointer field "
               "apart (path, name, acc_mps2), then update this size");

/* Every reading option but the responses (a keyed subject has none). */
static void read_opts_key(aq_bytes_out *b, const aq_read_opts *r)
{
  aq_bytes_put_i64(b, r->units);
  aq_bytes_put_f64(b, r->dt_s);
  aq_bytes_put_i64(b, (int64_t)r->column);
  aq_bytes_put_i64(b, (int64_t)r->nrules);
  for (size_t i = 0; i < r->nrules && i < AQ_UNITS_RULES_MAX; i++) {
    aq_bytes_put_str(b, r->rules[i].glob, sizeof r->rules[i].glob);
    aq_bytes_put_i64(b, r->rules[i].units);
  }
  aq_bytes_put_i64(b, r->accept_implausible);
  aq_bytes_put_i64(b, r->accept_vertical);
  aq_bytes_put_i64(b, (int64_t)r->ncomponents);
  for (size_t i = 0; i < r->ncomponents && i < AQ_UNITS_RULES_MAX; i++) {
    aq_bytes_put_str(b, r->components[i].glob, sizeof r->components[i].glob);
    aq_bytes_put_str(b, r->components[i].channel, sizeof r->components[i].channel);
  }
}

/* Every processing option but the scale (a subject is at factor 1). */
static void proc_opts_key(aq_bytes_out *b, const aq_signal_opts *p)
{
  aq_bytes_put_i64(b, p->detrend);
  aq_bytes_put_f64(b, p->taper_frac);
  aq_bytes_put_i64(b, p->filter);
  aq_bytes_put_f64(b, p->highpass_hz);
  aq_bytes_put_i64(b, p->highpass_auto);
  aq_bytes_put_i64(b, p->order);
  aq_bytes_put_f64(b, p->lowpass_hz);
  aq_bytes_put_i64(b, (int64_t)p->im_nsa); /* the spectral measures asked for */
  for (size_t i = 0; i < p->im_nsa && i < AQ_IM_SA_MAX; i++)
    aq_bytes_put_f64(b, p->im_period_s[i]);
  aq_bytes_put_f64(b, p->sa_avg_lo_s);
  aq_bytes_put_f64(b, p->sa_avg_hi_s);
  aq_bytes_put_i64(b, p->peaks); /* where their peaks are taken */
}

void aq_subject_key_free(aq_subject_key *k)
{
  free(k->key.data);
  memset(k, 0, sizeof *k);
}

int aq_subject_cache_key(const aq_subject_src *src, const aq_subject_opts *o,
                         aq_subject_key *k)
{
  memset(k, 0, sizeof *k);
  if (o->read->nresponses > 0)
    return 0;
  aq_bytes_out *b = &k->key;
  char fp[256];
  aq_signal_fingerprint(fp, sizeof fp);
  aq_bytes_put_str(b, KEY_FORMAT, 0);
  aq_cache_key_platform(b);
  aq_bytes_put_str(b, fp, 0);
  read_opts_key(b, o->read);
  proc_opts_key(b, o->proc);
  aq_bytes_put_i64(b, o->vertical);
  aq_bytes_put_i64(b, o->any_channel);
  aq_bytes_put_str(b, src->label, 0);
  for (int j = 0; j < 2; j++)
    aq_bytes_put_f64(b, src->azimuth_deg[j]);
  for (int j = 0; j < 3; j++) {
    aq_bytes_put_i64(b, src->path[j] != NULL);
    if (!src->path[j])
      continue;
    aq_bytes_put_str(b, src->path[j], 0);
    char file[4096];
    aq_error e; /* the reader says why */
    if (aq_sha256_file(aq_record_file(src->path[j], file, sizeof file), k->sha256[j], &e) !=
        AQ_OK) {
      aq_subject_key_free(k);
      return 0;
    }
    aq_bytes_put_str(b, k->sha256[j], 0);
  }
  if (b->oom) {
    aq_subject_key_free(k);
    return 0;
  }
  return 1;
}

static void put_subject(aq_bytes_out *b, const aq_subject *s)
{
  int64_t flags = s->motion | s->run_v << 1 | s->v_ignored << 2 | s->have_im << 3;
  for (int j = 0; j < 3; j++)
    flags |= (int64_t)s->have_rec[j] << (4 + j) | (int64_t)s->have_proc[j] << (7 + j);
  aq_bytes_put_i64(b, flags);
  aq_bytes_put_f64(b, s->phi_deg[0]);
  aq_bytes_put_f64(b, s->phi_deg[1]);
  aq_bytes_put_f64(b, s->pga_g);
  aq_bytes_put_str(b, s->warning, sizeof s->warning);
  for (int j = 0; j < 3; j++)
    if (s->have_rec[j]) {
      aq_record r = s->rec[j];
      r.path = r.name = NULL;
      r.acc_mps2 = NULL; /* freed once processed */
      aq_bytes_put(b, &r, sizeof r);
      aq_bytes_put_str(b, s->rec[j].path, 0);
      aq_bytes_put_str(b, s->rec[j].name, 0);
    }
  for (int j = 0; j < 3; j++)
    if (s->have_proc[j]) {
      aq_processed p = s->proc[j];
      p.acc_mps2 = NULL;
      aq_bytes_put(b, &p, sizeof p);
      aq_bytes_put(b, s->proc[j].acc_mps2, s->proc[j].n * sizeof(double));
    }
  aq_bytes_put(b, &s->im, sizeof s->im);
}

void aq_subject_cache_put(aq_diskcache *c, const aq_subject_key *k, const aq_subject *s)
{
  for (int j = 0; j < 3; j++)
    if (s->have_rec[j] && s->rec[j].acc_mps2)
      return; /* not as aq_subject_prepare leaves it */
  aq_bytes_out b = {0};
  put_subject(&b, s);
  if (!b.oom)
    aq_diskcache_put(c, k->key.data, k->key.n, b.data, b.n);
  free(b.data);
}

/* Free what a partly decoded subject holds (subject.c's aq_subject_free,
 * which this file does not call: no circle of calls between files). */
static void drop(aq_subject *s)
{
  for (int j = 0; j < 3; j++) {
    aq_record_free(&s->rec[j]);
    aq_processed_free(&s->proc[j]);
  }
  memset(s, 0, sizeof *s);
}

/* Give the fresh array a[0..bytes) its pages at once, before the samples
 * are copied in: one call instead of a page fault for each page the
 * copy would touch first (most of the faults of a warm job's reading).
 * Only the whole pages inside the array; the contents are not changed.  A
 * kernel without MADV_POPULATE_WRITE (before Linux 5.14) refuses it, and
 * the copy faults the pages in as before. */
static void populate(void *a, size_t bytes)
{
  long ps = sysconf(_SC_PAGESIZE);
  if (ps <= 0)
    return;
  const uintptr_t page = (uintptr_t)ps;
  uintptr_t lo = ((uintptr_t)a + page - 1) & ~(page - 1);
  uintptr_t hi = ((uintptr_t)a + bytes) & ~(page - 1);
  if (hi > lo)
    (void)madvise((void *)lo, hi - lo, MADV_POPULATE_WRITE);
}

static int get_subject(aq_bytes_in *r, aq_subject *s)
{
  int64_t flags = aq_bytes_get_int(r, 0, (1 << 10) - 1, "flags");
  s->motion = flags & 1;
  s->run_v = flags >> 1 & 1;
  s->v_ignored = flags >> 2 & 1;
  s->have_im = flags >> 3 & 1;
  s->phi_deg[0] = aq_bytes_get_f64(r, "phi1");
  s->phi_deg[1] = aq_bytes_get_f64(r, "phi2");
  s->pga_g = aq_bytes_get_f64(r, "pga_g");
  aq_bytes_get_str(r, s->warning, sizeof s->warning, NULL, "warning");
  for (int j = 0; j < 3 && !r->bad; j++)
    if (flags >> (4 + j) & 1) {
      aq_record *rec = &s->rec[j];
      if (aq_bytes_get(r, rec, sizeof *rec, "record") != 0) {
        memset(rec, 0, sizeof *rec);
        break;
      }
      rec->path = rec->name = NULL;
      rec->acc_mps2 = NULL;
      s->have_rec[j] = 1;
      aq_bytes_get_str(r, NULL, 0, &rec->path, "path");
      aq_bytes_get_str(r, NULL, 0, &rec->name, "name");
    }
  for (int j = 0; j < 3 && !r->bad; j++)
    if (flags >> (7 + j) & 1) {
      aq_processed *p = &s->proc[j];
      if (aq_bytes_get(r, p, sizeof *p, "processed") != 0) {
        memset(p, 0, sizeof *p);
        break;
      }
      p->acc_mps2 = NULL;
      size_t n = p->n;
      void *a = NULL;
      if (n > (r->n - r->at) / sizeof(double) ||
          posix_memalign(&a, 64, (n ? n : 1) * sizeof(double)) != 0) {
        p->n = 0;
        r->bad = r->bad ? r->bad : "samples";
        break;
      }
      p->acc_mps2 = a;
      s->have_proc[j] = 1;
      populate(a, n * sizeof(double));
      aq_bytes_get(r, p->acc_mps2, n * sizeof(double), "samples");
    }
  aq_bytes_get(r, &s->im, sizeof s->im, "im");
  return r->bad || r->at != r->n ? -1 : 0;
}

int aq_subject_cache_get(aq_diskcache *c, const aq_subject_key *k, aq_subject *s)
{
  memset(s, 0, sizeof *s);
  aq_diskcache_value v;
  if (!aq_diskcache_get(c, k->key.data, k->key.n, &v))
    return 0;
  aq_bytes_in r = {v.data, v.n, 0, NULL, 0};
  int ok = get_subject(&r, s) == 0;
  aq_diskcache_release(&v);
  if (!ok) { /* whole by its checksum, yet not ours: another layout */
    drop(s);
    return 0;
  }
  s->stage = "process";
  return 1;
}
