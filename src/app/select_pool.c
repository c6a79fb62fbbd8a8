/* select_pool.c: the pool of `archquake select`, read, processed and
 * measured on threads, with the spectra kept on disk (select_pool.h). */
#define _POSIX_C_SOURCE 200809L
#include "select_pool.h"

#include <dirent.h>
#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../job/subject.h"
#include "../job/subject_cache.h"
#include "../util/bytes.h"
#include "../util/pool.h"

#define KEY_FORMAT "archquake select spectra 2\n"

typedef struct {
  aq_select_pool *pool;
  aq_signal_ws *sws;
  aq_signal_opts proc; /* the pool's, without spectral measures */
} ctx;

/* The spectra's key: the prepared subject's, then what the spectra add. */
static int spectra_key(const ctx *C, const aq_subject_src *src, const aq_subject_opts *so,
                       aq_bytes_out *key)
{
  const aq_select_pool *P = C->pool;
  aq_subject_key sk;
  if (!aq_subject_cache_key(src, so, &sk))
    return 0;
  memset(key, 0, sizeof *key);
  aq_bytes_put_str(key, KEY_FORMAT, 0);
  aq_bytes_put(key, sk.key.data, sk.key.n);
  aq_subject_key_free(&sk);
  aq_bytes_put_i64(key, (int64_t)P->nper);
  for (size_t k = 0; k < P->nper; k++)
    aq_bytes_put_f64(key, P->periods_s[k]);
  aq_bytes_put_f64(key, P->damping);
  aq_bytes_put_i64(key, P->pair_rule);
  aq_bytes_put_i64(key, P->sopts.peaks);
  aq_bytes_put_i64(key, (int64_t)P->sopts.n_angles);
  if (key->oom) {
    free(key->data);
    return 0;
  }
  return 1;
}

static void put_member(aq_bytes_out *b, const aq_select_member *m, size_t nper)
{
  aq_bytes_put_f64(b, m->psa0_mps2);
  for (size_t k = 0; k < nper; k++)
    aq_bytes_put_f64(b, m->psa_mps2[k]);
  aq_bytes_put_str(b, m->channel, sizeof m->channel);
  aq_bytes_put_str(b, m->event, sizeof m->event);
  aq_bytes_put_str(b, m->event_key, sizeof m->event_key);
  aq_bytes_put_f64(b, m->dt_s);
  aq_bytes_put_i64(b, (int64_t)m->npts);
  for (size_t c = 0; c < 2; c++) {
    aq_bytes_put_i64(b, (int64_t)m->trace[c].n);
    for (size_t k = 0; k < m->trace[c].n; k++)
      aq_bytes_put_f64(b, m->trace[c].x[k]);
  }
}

/* 1 if the traces read are those a member of this pool has: one for each
 * of its components (two for a pair, one for a record), none beyond, each
 * of finite values, as aq_same_trace_make() makes them.  An entry whose
 * traces are not (whole by its checksum, yet not what this build writes)
 * is not used: the member is computed again, as for a damaged entry
 * (docs/cache.md), and never compared by traces that would hide or invent
 * a duplicate. */
static int traces_whole(const aq_select_member *m)
{
  for (size_t c = 0; c < 2; c++) {
    int want = c == 0 || m->path[1] != NULL;
    if ((m->trace[c].n > 0) != want)
      return 0;
    for (size_t k = 0; k < m->trace[c].n; k++)
      if (!isfinite(m->trace[c].x[k]))
        return 0;
  }
  return 1;
}

static int get_member(aq_bytes_in *r, aq_select_member *m, size_t nper)
{
  m->psa0_mps2 = aq_bytes_get_f64(r, "psa0");
  for (size_t k = 0; k < nper; k++)
    m->psa_mps2[k] = aq_bytes_get_f64(r, "psa");
  aq_bytes_get_str(r, m->channel, sizeof m->channel, NULL, "channel");
  aq_bytes_get_str(r, m->event, sizeof m->event, NULL, "event");
  aq_bytes_get_str(r, m->event_key, sizeof m->event_key, NULL, "event_key");
  m->dt_s = aq_bytes_get_f64(r, "dt");
  m->npts = (size_t)aq_bytes_get_int(r, 0, INT64_MAX, "npts");
  for (size_t c = 0; c < 2 && !r->bad; c++) {
    size_t n = aq_bytes_get_count(r, sizeof(double), "trace");
    if (r->bad || !n)
      continue;
    if (!(m->trace[c].x = malloc(n * sizeof *m->trace[c].x)))
      return 0;
    m->trace[c].n = n;
    for (size_t k = 0; k < n; k++)
      m->trace[c].x[k] = aq_bytes_get_f64(r, "trace");
  }
  return !r->bad && r->at == r->n && traces_whole(m);
}

static void prepare_member(void *vctx, size_t i)
{
  ctx *C = vctx;
  aq_select_pool *P = C->pool;
  aq_select_member *m = &P->m[i];
  aq_error_clear(&m->err);
  m->psa_mps2 = malloc((P->nper ? P->nper : 1) * sizeof *m->psa_mps2);
  if (!m->psa_mps2) {
    m->st = aq_error_set(&m->err, AQ_ENOMEM, m->name, -1, -1, NULL, "out of memory");
    return;
  }
  aq_subject_src src = {{m->path[0], m->path[1], NULL},
                        {m->azimuth_deg[0], m->azimuth_deg[1]}, m->name};
  aq_subject_opts so = {P->read, &C->proc, 0, 0, 0, NULL};
  aq_bytes_out key = {0};
  int keyed = P->cache && spectra_key(C, &src, &so, &key);
  if (keyed) {
    aq_diskcache_value v;
    if (aq_diskcache_get(P->cache, key.data, key.n, &v)) {
      aq_bytes_in r = {v.data, v.n, 0, NULL, 0};
      int ok = get_member(&r, m, P->nper);
      aq_diskcache_release(&v);
      if (!ok)
        for (size_t c = 0; c < 2; c++)
          aq_same_trace_free(&m->trace[c]);
      if (ok) {
        free(key.data);
        m->cached = 1;
        m->st = AQ_OK;
        return;
      }
    }
  }
  aq_subject s;
  m->st = aq_subject_prepare(&s, &src, &so, C->sws, &m->err);
  if (m->st != AQ_OK) {
    m->vertical = s.have_rec[0] && s.rec[0].vertical;
    if (!m->err.input[0])
      snprintf(m->err.input, sizeof m->err.input, "%s", m->name);
  }
  aq_spectrum_ws *ws = m->st == AQ_OK ? aq_spectrum_ws_alloc() : NULL;
  if (m->st == AQ_OK && !ws)
    m->st = aq_error_set(&m->err, AQ_ENOMEM, m->name, -1, -1, NULL, "out of memory");
  if (m->st == AQ_OK)
    m->st = aq_select_spectrum(ws, &P->sopts, &s.proc[0], m->path[1] ? &s.proc[1] : NULL,
                               P->pair_rule, P->damping, P->periods_s, P->nper, m->psa_mps2,
                               &m->psa0_mps2, &m->err);
  aq_spectrum_ws_free(ws);
  for (size_t k = 0; m->st == AQ_OK && k < P->nper; k++)
    if (!(m->psa_mps2[k] > 0)) {
      m->st = aq_error_set(&m->err, AQ_EVALUE, m->name, -1, -1, "spectrum",
                           "expected PSA > 0 at every period of the range, got %g m/s^2 at "
                           "%g s (a record of zeros?)", m->psa_mps2[k], P->periods_s[k]);
      break;
    }
  if (m->st == AQ_OK) {
    const aq_record *r = &s.rec[0];
    if (m->path[1])
      snprintf(m->channel, sizeof m->channel, "%s", aq_select_pair_name(P->pair_rule));
    else
      snprintf(m->channel, sizeof m->channel, "%s", r->channel[0] ? r->channel : "-");
    snprintf(m->event, sizeof m->event, "%s", r->event);
    snprintf(m->event_key, sizeof m->event_key, "%s", r->event_key);
    if (m->path[1] && strcmp(s.rec[1].event_key, r->event_key) != 0)
      m->event_key[0] = '\0'; /* the two files name different events: none */
    m->dt_s = s.proc[0].dt_s;
    m->npts = r->npts;
    for (size_t c = 0; m->st == AQ_OK && c < (m->path[1] ? 2u : 1u); c++) {
      const aq_processed *pr = &s.proc[c]; /* the record's own span, pads left out */
      m->st = aq_same_trace_make(pr->acc_mps2 + pr->pad_front, pr->n_orig, pr->dt_s,
                                 &m->trace[c], &m->err);
    }
  }
  if (m->st == AQ_OK) {
    if (keyed) {
      aq_bytes_out val = {0};
      put_member(&val, m, P->nper);
      if (!val.oom)
        aq_diskcache_put(P->cache, key.data, key.n, val.data, val.n);
      free(val.data);
    }
  }
  free(key.data);
  aq_subject_free(&s);
}

aq_status aq_select_pool_prepare(aq_select_pool *pool, long threads, aq_error *err)
{
  ctx C = {pool, aq_signal_ws_alloc(), *pool->proc};
  if (!C.sws)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "select", "out of memory");
  C.proc.im_nsa = 0; /* no spectral intensity measures: the spectra are ours */
  C.proc.sa_avg_lo_s = C.proc.sa_avg_hi_s = 0;
  aq_status st = aq_pool_for(pool->n, threads, prepare_member, &C, err);
  aq_signal_ws_free(C.sws);
  return st;
}

void aq_select_pool_free(aq_select_pool *pool)
{
  for (size_t i = 0; pool->m && i < pool->n; i++) {
    free(pool->m[i].psa_mps2);
    aq_same_trace_free(&pool->m[i].trace[0]);
    aq_same_trace_free(&pool->m[i].trace[1]);
  }
  free(pool->m);
  pool->m = NULL;
  pool->n = 0;
}

/* A growing list of names. */
typedef struct {
  char **v;
  size_t n, cap;
} names;

static int push(names *s, const char *x)
{
  if (s->n == s->cap) {
    size_t c = s->cap ? 2 * s->cap : 64;
    char **v = realloc(s->v, c * sizeof *v);
    if (!v)
      return -1;
    s->v = v;
    s->cap = c;
  }
  if (!(s->v[s->n] = strdup(x)))
    return -1;
  s->n++;
  return 0;
}

static int cmp_name(const void *a, const void *b)
{
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The regular files of directory dir, in name order, onto out. */
static aq_status add_directory(const char *dir, names *out, aq_error *err)
{
  DIR *d = opendir(dir);
  if (!d)
    return aq_error_set(err, AQ_EIO, dir, -1, -1, NULL, "cannot read the directory");
  names files = {0};
  struct dirent *e;
  int bad = 0;
  size_t dl = strlen(dir);
  while (!bad && (e = readdir(d))) {
    if (e->d_name[0] == '.')
      continue;
    size_t len = dl + strlen(e->d_name) + 2;
    char *path = malloc(len);
    struct stat sb;
    if (!path) {
      bad = 1;
      break;
    }
    snprintf(path, len, "%s%s%s", dir, dl && dir[dl - 1] == '/' ? "" : "/", e->d_name);
    if (stat(path, &sb) == 0 && S_ISREG(sb.st_mode))
      bad = push(&files, path) != 0;
    free(path);
  }
  closedir(d);
  if (files.n)
    qsort(files.v, files.n, sizeof *files.v, cmp_name);
  for (size_t k = 0; !bad && k < files.n; k++)
    bad = push(out, files.v[k]) != 0;
  aq_record_names_free(files.v, files.n);
  return bad ? aq_error_set(err, AQ_ENOMEM, dir, -1, -1, NULL, "out of memory") : AQ_OK;
}

aq_status aq_select_pool_files(char *const *ops, size_t n, char ***files, size_t *nfiles,
                               aq_error *err)
{
  names out = {0};
  aq_status st = AQ_OK;
  for (size_t i = 0; st == AQ_OK && i < n; i++) {
    struct stat sb;
    if (stat(ops[i], &sb) == 0 && S_ISDIR(sb.st_mode)) {
      st = add_directory(ops[i], &out, err);
    } else if (access(ops[i], F_OK) != 0 && strpbrk(ops[i], "*?[")) {
      glob_t g;
      int r = glob(ops[i], 0, NULL, &g);
      if (r != 0)
        st = aq_error_set(err, AQ_EIO, ops[i], -1, -1, NULL,
                          "expected a record, a directory or a glob matching files, got a "
                          "glob matching none");
      for (size_t k = 0; r == 0 && st == AQ_OK && k < g.gl_pathc; k++)
        if (push(&out, g.gl_pathv[k]) != 0)
          st = aq_error_set(err, AQ_ENOMEM, ops[i], -1, -1, NULL, "out of memory");
      if (r == 0 || r == GLOB_NOSPACE)
        globfree(&g);
    } else if (push(&out, ops[i]) != 0) {
      st = aq_error_set(err, AQ_ENOMEM, ops[i], -1, -1, NULL, "out of memory");
    }
  }
  if (st != AQ_OK) {
    aq_record_names_free(out.v, out.n);
    return st;
  }
  *files = out.v;
  *nfiles = out.n;
  return AQ_OK;
}
