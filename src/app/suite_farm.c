/* suite_farm.c: the main job over other processes (farm.h, archquake-mpi):
 * a task per (record, arch), each process keeping the records it prepared
 * for their other arches; the leader merges a record's arches and writes
 * it, in order (suite_slot.h). */
#define _POSIX_C_SOURCE 200809L
#include "suite_slot.h"

#include <stdlib.h>
#include <string.h>

#include "../job/cache.h"
#include "app.h"
#include "farm.h"

int aq_suite_is_follower(void)
{
  return aq_farm_is_follower();
}

int aq_suite_is_remote(void)
{
  return aq_farm_get() != NULL;
}

/* Records a process keeps prepared beyond those its threads use, for the
 * next tasks of the same record (its other arches). */
#define AQ_SUITE_FARM_KEEP_EXTRA 2
/* Tasks handed out beyond the first not yet written, per running thread. */
#define AQ_SUITE_FARM_AHEAD 8

typedef struct {
  suite *S;
  aq_cache *cache;        /* records prepared here (job/cache.h) */
  rec_slot *kept;         /* its items */
  /* leader */
  aq_h5_writer *h5;
  aq_journal *J;
  aq_suite_stats *stats;
  rec_slot **pend;        /* per record: its arches' results so far, merged */
  size_t *parts;          /* per record: tasks taken */
  size_t next_write;
} farm_ctx;

/* The cache's preparing of record i into slot item (job/cache.h). */
static void farm_prepare(void *ctx, size_t i, void *item)
{
  farm_ctx *X = ctx;
  rec_slot *r = item;
  r->index = i;
  aq_suite_prepare(X->S, r);
  aq_suite_record_sha256(X->S, r, NULL); /* before the slot is shared */
}

static void farm_clear(void *ctx, void *item)
{
  farm_ctx *X = ctx;
  aq_suite_slot_clear(X->S, item);
}

/* Task t: record t / narches with arch t % narches, every factor,
 * polarity and azimuth; its result is the record encoded with that arch's
 * runs only (suite_slot.h). */
static int farm_run(void *ctx, size_t t, unsigned char **msg, size_t *n)
{
  farm_ctx *X = ctx;
  suite *S = X->S;
  size_t na = S->cfg->narches, a = t % na;
  rec_slot *r = aq_cache_acquire(X->cache, t / na);
  size_t per = r->nruns / na; /* runs of one arch */
  aq_stepper **st = calloc(na, sizeof *st);
  int rc = st ? 0 : -1;
  if (rc == 0 && r->runs && !r->failed) {
    aq_error e;
    st[a] = S->arch_ok[a] ? aq_suite_stepper(S, a, &e) : NULL;
    for (size_t k = 0; k < per; k++)
      aq_suite_run_one(S, r, a * per + k, st);
    aq_stepper_free(st[a]);
  }
  free(st);
  rec_slot view = *r;
  view.runs = r->runs ? r->runs + a * per : NULL;
  aq_bytes_out jb = {0};
  aq_suite_slot_encode(&view, per, &jb);
  for (size_t k = 0; r->runs && k < per; k++) /* the results travel; not kept here */
    if (r->runs[a * per + k].have_res) {
      aq_result_free(&r->runs[a * per + k].res);
      r->runs[a * per + k].have_res = 0;
    }
  aq_cache_release(X->cache, r);
  if (jb.oom || rc != 0) {
    free(jb.data);
    return -1;
  }
  *msg = jb.data;
  *n = jb.n;
  return 0;
}

/* Leader: merge task t's result into its record's; write every record
 * whose arches are all in, in record order, and journal it. */
static int farm_take(void *ctx, size_t t, const unsigned char *msg, size_t n, aq_error *err)
{
  farm_ctx *X = ctx;
  suite *S = X->S;
  const aq_suite_cfg *c = S->cfg;
  size_t na = c->narches, i = t / na, a = t % na;
  rec_slot part;
  memset(&part, 0, sizeof part);
  aq_suite_slot_orient(S, i, &part);
  size_t nruns = part.nruns, per = nruns / na;
  aq_journal_entry e = {(unsigned char *)msg, n};
  if (aq_suite_slot_decode(&e, per, &part) != 0 || part.index != i) {
    aq_suite_slot_clear(S, &part);
    return aq_error_set(err, AQ_EFORMAT, c->records[i], -1, -1, NULL,
                        "expected the results of record %zu, arch %zu from a follower, "
                        "got a malformed message of %zu bytes", i, a, n), -1;
  }
  aq_suite_slot_orient(S, i, &part); /* decoding cleared it */
  rec_slot *m = X->pend[i];
  int first = m == NULL;
  if (first) { /* the first arch in: the record itself, with room for every run */
    m = X->pend[i] = malloc(sizeof *m);
    run_slot *runs = part.runs ? calloc(nruns ? nruns : 1, sizeof *runs) : NULL;
    if (!m || (part.runs && !runs)) {
      free(m);
      free(runs);
      X->pend[i] = NULL;
      aq_suite_slot_clear(S, &part);
      return aq_error_set(err, AQ_ENOMEM, c->records[i], -1, -1, NULL, "out of memory"), -1;
    }
    *m = part; /* m owns the record's metadata now */
    m->runs = runs;
    S->read_s += part.subj.read_s;
    S->process_s += part.subj.process_s;
  }
  for (size_t k = 0; m->runs && part.runs && k < per; k++) { /* moved into m */
    m->runs[a * per + k] = part.runs[k];
    S->run_s += part.runs[k].run_s;
  }
  free(part.runs);
  part.runs = NULL;
  if (!first)
    aq_suite_slot_clear(S, &part); /* a copy of what m holds */
  X->parts[i]++;
  aq_status ws = AQ_OK;
  for (; ws == AQ_OK && X->next_write < c->nrecords && X->parts[X->next_write] == na;
       X->next_write++) {
    rec_slot *r = X->pend[X->next_write];
    ws = aq_suite_write_record(S, r, X->h5, X->stats, err);
    if (ws == AQ_OK && X->J)
      ws = aq_suite_journal_append(S, X->J, r, err);
    aq_suite_slot_clear(S, r);
    free(r);
    X->pend[X->next_write] = NULL;
  }
  return ws == AQ_OK ? 0 : -1;
}

/* Run the suite's tasks through the farm: a follower runs what it is
 * handed; the leader (h5, J, stats for writing) records done..nrecords.
 * Returns AQ_OK, or the failure (err filled). */
aq_status aq_suite_farm(suite *S, aq_h5_writer *h5, aq_journal *J, size_t done,
                            aq_suite_stats *stats, aq_error *err)
{
  const aq_suite_cfg *c = S->cfg;
  const aq_farm *f = aq_farm_get();
  size_t threads = c->threads > 0 ? (size_t)c->threads : 1, na = c->narches;
  size_t ntask = c->nrecords * na, ntodo = f->follower ? 0 : ntask - done * na;
  size_t nkeep = threads + AQ_SUITE_FARM_KEEP_EXTRA;
  farm_ctx X = {.S = S, .h5 = h5, .J = J, .stats = stats, .next_write = done};
  X.kept = calloc(nkeep, sizeof *X.kept);
  aq_cache_cfg cc = {c->nrecords, nkeep, X.kept, sizeof *X.kept, farm_prepare, farm_clear, &X};
  X.cache = X.kept ? aq_cache_alloc(&cc) : NULL;
  size_t *todo = calloc(ntodo ? ntodo : 1, sizeof *todo);
  if (!f->follower) {
    X.pend = calloc(c->nrecords ? c->nrecords : 1, sizeof *X.pend);
    X.parts = calloc(c->nrecords ? c->nrecords : 1, sizeof *X.parts);
  }
  aq_status ws = AQ_OK;
  if (!X.cache || !todo || (!f->follower && (!X.pend || !X.parts)))
    ws = aq_error_set(err, AQ_ENOMEM, "", -1, -1, NULL, "out of memory");
  for (size_t k = 0; k < ntodo; k++)
    todo[k] = done * na + k;
  aq_farm_tasks T = {ntask, (long)threads, na, AQ_SUITE_FARM_AHEAD, farm_run, farm_take,
                     &X};
  if (ws == AQ_OK && na > 0 && f->farm(f->ctx, &T, todo, ntodo, err) != 0)
    ws = err->status != AQ_OK ? err->status : AQ_EIO;
  for (size_t i = 0; X.pend && i < c->nrecords; i++)
    if (X.pend[i]) {
      aq_suite_slot_clear(S, X.pend[i]);
      free(X.pend[i]);
    }
  aq_cache_free(X.cache);
  for (size_t k = 0; X.kept && k < nkeep; k++)
    aq_suite_slot_clear(S, &X.kept[k]);
  free(X.kept);
  free(X.pend);
  free(X.parts);
  free(todo);
  return ws;
}
