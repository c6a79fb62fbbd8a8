/* suite.c: records x arches x scales on worker threads, written in order by
 * one writer (see suite.h). */
#define _POSIX_C_SOURCE 200809L
#include "suite.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../arch/arch.h"
#include "../arch/model.h"
#include "../report/h5.h"
#include "../util/pool.h"
#include "app.h"
#include "farm.h"
#include "opt.h"
#include "suite_slot.h"

/* Records in flight per worker thread: at least enough that a worker
 * finishing a short record finds the next one while a long one is still
 * running.  A record whose runs are all done keeps only what writing it
 * needs (aq_suite_slot_shed), a few KB, so the window widens to
 * AQ_SUITE_WINDOW_MAX_PER_THREAD while the finished records it may hold
 * stay within AQ_SUITE_WINDOW_BYTES: with 2 per thread, a worker done with
 * the short records behind a long one (1.6 ms against 0.3-0.6 ms in the
 * quiet bench suite) waited for it, and for the writer, 70 times per 200
 * records at -j 2 (15-35 % of its time).  With --history or --store-records
 * a finished record keeps arrays of unbounded size: the window stays at the
 * minimum. */
#define AQ_SUITE_WINDOW_PER_THREAD 2
#define AQ_SUITE_WINDOW_MAX_PER_THREAD 16
#define AQ_SUITE_WINDOW_BYTES (64L << 20)
/* With -o the writer hashes each record file (aq_suite_record_sha256) from the bytes
 * its reader read, kept in the window up to this total (a larger file is
 * read again to hash it): reading it again cost 15 % of the hash. */
#define AQ_SUITE_KEEP_BYTES (64L << 20)

/* ---- threads ------------------------------------------------------------ */

typedef struct {
  suite *S;
  aq_stepper **st; /* one per arch, this thread's own */
} worker_arg;

/* Record r is done (S->lock held): the writer is woken if r is the one it
 * waits for, the workers only once every record is claimed (then they wait
 * for the last records to finish before they stop). */
static void slot_done(suite *S, rec_slot *r)
{
  r->state = SLOT_DONE;
  if (r->index == S->next_write)
    pthread_cond_signal(&S->wcond);
  if (S->next_claim >= S->cfg->nrecords)
    pthread_cond_broadcast(&S->cond);
}

/* One piece of work with the steppers st (S->lock held, released while it
 * works): a waiting run of the oldest prepared record, else the next record
 * prepared if the window has room.  Returns 1 if it did one, 0 if none
 * was there to do. */
int aq_suite_work_one(suite *S, aq_stepper **st)
{
  const size_t nrec = S->cfg->nrecords;
  /* 1. a waiting run of the oldest prepared record */
  rec_slot *r = NULL;
  for (size_t idx = S->next_write; idx < S->next_claim && !r; idx++) {
    rec_slot *x = &S->slots[idx % S->window];
    if (x->state == SLOT_READY && x->next_run < x->nruns)
      r = x;
  }
  if (r) {
    size_t i = r->next_run++;
    pthread_mutex_unlock(&S->lock);
    aq_suite_run_one(S, r, i, st);
    pthread_mutex_lock(&S->lock);
    S->run_s += r->runs[i].run_s;
    S->runs_done++;
    if (++r->runs_done == r->nruns) { /* the last: nobody else uses r now */
      pthread_mutex_unlock(&S->lock);
      aq_suite_slot_shed(S, r);
      pthread_mutex_lock(&S->lock);
      slot_done(S, r);
    }
    return 1;
  }
  /* 2. prepare the next record, if the window has room */
  if (S->next_claim < nrec && S->next_claim < S->next_write + S->window) {
    size_t idx = S->next_claim++;
    r = &S->slots[idx % S->window];
    r->state = SLOT_PREPARING;
    r->index = idx;
    pthread_mutex_unlock(&S->lock);
    int ok = aq_suite_prepare(S, r);
    pthread_mutex_lock(&S->lock);
    S->read_s += r->subj.read_s;
    S->process_s += r->subj.process_s;
    if (ok && r->nruns > 0) {
      r->state = SLOT_READY;
      if (r->nruns > 1) /* runs for the other threads too */
        pthread_cond_broadcast(&S->cond);
    } else {
      S->runs_done += r->runs ? r->nruns : 0;
      pthread_mutex_unlock(&S->lock);
      aq_suite_slot_shed(S, r);
      pthread_mutex_lock(&S->lock);
      slot_done(S, r);
    }
    return 1;
  }
  return 0;
}

static void worker(void *ctx, size_t k)
{
  worker_arg *w = &((worker_arg *)ctx)[k];
  suite *S = w->S;
  const size_t nrec = S->cfg->nrecords;
  pthread_mutex_lock(&S->lock);
  for (;;) {
    if (S->stop)
      break;
    if (aq_suite_work_one(S, w->st))
      continue;
    /* 3. nothing left to hand out, or wait for the writer or a record */
    if (S->next_claim >= nrec) {
      int pending = 0;
      for (size_t idx = S->next_write; idx < S->next_claim; idx++) {
        rec_slot *x = &S->slots[idx % S->window];
        pending |= x->state == SLOT_PREPARING ||
                   (x->state == SLOT_READY && x->next_run < x->nruns);
      }
      if (!pending)
        break;
    }
    double t0 = aq_suite_now_s();
    pthread_cond_wait(&S->cond, &S->lock);
    S->wait_s += aq_suite_now_s() - t0;
  }
  pthread_mutex_unlock(&S->lock);
}

/* The worker threads of S, each with its own steppers.  One worker (-j 1)
 * is no thread: the writer does the work itself, with that worker's
 * steppers (S->inline_st), between the records it writes. */
typedef struct {
  long n;
  size_t started;
  aq_pool *pool;
  worker_arg *wa;
} workers;

/* Start up to W->n workers (W->started of them run; with W->n 1 the
 * writer's steppers made instead). */
static void workers_start(suite *S, workers *W)
{
  const aq_suite_cfg *c = S->cfg;
  W->wa = calloc((size_t)W->n, sizeof *W->wa);
  long n = 0;
  for (; W->wa && n < W->n; n++) {
    worker_arg *a = &W->wa[n];
    a->S = S;
    a->st = calloc(c->narches ? c->narches : 1, sizeof *a->st);
    if (!a->st)
      break;
    for (size_t k = 0; k < c->narches; k++)
      if (S->arch_ok[k]) {
        aq_error e;
        a->st[k] = aq_suite_stepper(S, k, &e);
      }
  }
  if (W->n == 1 && n == 1) { /* -j 1: the writer works (aq_suite_write_all) */
    S->inline_st = W->wa[0].st;
    W->started = 1;
    return;
  }
  W->pool = n > 0 ? aq_pool_start((size_t)n, worker, W->wa, &W->started) : NULL;
}

/* Wait for the workers to finish (told to stop first with stop) and free
 * them; nothing happens if none was started. */
static void workers_join(suite *S, workers *W, int stop)
{
  if (stop && W->started > 0) {
    pthread_mutex_lock(&S->lock);
    S->stop = 1;
    pthread_cond_broadcast(&S->cond);
    pthread_mutex_unlock(&S->lock);
  }
  aq_pool_join(W->pool);
  W->pool = NULL;
  for (long t = 0; W->wa && t < W->n; t++) {
    for (size_t a = 0; W->wa[t].st && a < S->cfg->narches; a++)
      aq_stepper_free(W->wa[t].st[a]);
    free(W->wa[t].st);
  }
  free(W->wa);
  W->wa = NULL;
  W->started = 0;
  S->inline_st = NULL;
}

/* Records in flight for nthreads workers (see AQ_SUITE_WINDOW_PER_THREAD). */
static size_t suite_window(const suite *S, size_t nthreads)
{
  const aq_suite_cfg *c = S->cfg;
  size_t per = AQ_SUITE_WINDOW_PER_THREAD;
  if (c->history || c->store_records)
    return nthreads * per;
  size_t naz = 1; /* a finished record: its slot and its runs */
  for (size_t i = 0; c->motions && i < c->nrecords; i++)
    if (c->motions[i] && c->nazimuth > naz)
      naz = c->nazimuth;
  double bytes = (double)sizeof(rec_slot) + (double)(S->nruns * naz) * sizeof(run_slot);
  while (per < AQ_SUITE_WINDOW_MAX_PER_THREAD &&
         (double)(nthreads * (per + 1)) * bytes <= (double)AQ_SUITE_WINDOW_BYTES)
    per++;
  return nthreads * per;
}

static int suite_run(const aq_suite_cfg *c_in, aq_suite_stats *stats_out)
{
  double t_start = aq_suite_now_s();
  aq_app_heap_policy(); /* records' arrays stay in the heap (heap.c) */
  aq_suite_stats stats;
  memset(&stats, 0, sizeof stats);
  aq_suite_cfg cc = *c_in; /* its polarity decided once the arches are loaded */
  const aq_suite_cfg *c = &cc;
  suite S;
  memset(&S, 0, sizeof S);
  pthread_mutex_init(&S.lock, NULL);
  pthread_cond_init(&S.cond, NULL);
  pthread_cond_init(&S.wcond, NULL);
  S.cfg = c;
  S.model_name = aq_model_name(c->model);
  S.rule = (aq_scale_rule){c->scales, c->nscale, c->scale_to_pga_g,
                           c->scale_to_lambda0 > 0 ? c->scale_to_lambda0 : 0};
  workers W = {1, 0, NULL, NULL};
  int rc = AQ_EXIT_OK;
  aq_status ws = AQ_OK;
  aq_journal *J = NULL; /* with -o: the records written so far */
  size_t done = 0;      /* records written from the journal (--resume) */

  /* Arches: loaded once, every bad one reported; nothing runs if any is. */
  S.arches = calloc(c->narches ? c->narches : 1, sizeof *S.arches);
  S.arch_ok = calloc(c->narches ? c->narches : 1, sizeof *S.arch_ok);
  S.arch_err = calloc(c->narches ? c->narches : 1, sizeof *S.arch_err);
  S.lambda0 = calloc(c->narches ? c->narches : 1, sizeof *S.lambda0);
  S.ws = aq_signal_ws_alloc();
  S.line = c->text ? open_memstream(&S.line_buf, &S.line_cap) : NULL;
  if (!S.arches || !S.arch_ok || !S.arch_err || !S.lambda0 || !S.ws || (c->text && !S.line)) {
    fprintf(stderr, "archquake: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto out;
  }
  rc = aq_suite_arches(&S);
  if (rc == AQ_EXIT_USAGE)
    goto out;
  /* both polarities unless every arch answers a record and its negation
   * alike (or the user asked for one) */
  int all_motions = cc.nrecords > 0;
  for (size_t i = 0; i < cc.nrecords; i++)
    all_motions &= cc.motions && cc.motions[i];
  cc.polarity = aq_opt_polarity_resolve(cc.polarity, S.arches, cc.narches, all_motions,
                                        cc.azimuths_deg, cc.nazimuth);
  S.npol = c->polarity == AQ_POLARITY_BOTH ? 2 : 1;
  S.nscale = (c->scales ? c->nscale : 1) * S.npol;
  S.nruns = c->narches * S.nscale; /* per plain record; x azimuths per motion */
  for (size_t i = 0; i < c->nrecords; i++)
    S.total_runs += S.nruns * (c->motions && c->motions[i] ? c->nazimuth : 1);
  long nthreads = c->threads < 1 ? 1 : c->threads;
  if ((size_t)nthreads > c->nrecords)
    nthreads = c->nrecords ? (long)c->nrecords : 1;
  W.n = nthreads;
  S.window = suite_window(&S, (size_t)nthreads);
  S.keep_max = (size_t)AQ_SUITE_KEEP_BYTES / S.window;
  S.slots = calloc(S.window, sizeof *S.slots);
  if (!S.slots) {
    fprintf(stderr, "archquake: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto out;
  }

  if (aq_farm_is_follower()) {
    aq_error ferr;
    if (aq_suite_farm(&S, NULL, NULL, 0, NULL, &ferr) != AQ_OK)
      rc = AQ_EXIT_FAIL;
    goto out;
  }

  /* Without --resume (no records to read back first) and outside a farm,
   * the workers start on the first records while the outputs are opened:
   * with -o that takes 1.5-2 ms (the HDF5 file's root, tables and arches),
   * 2 % of a 200-record quiet suite, when nothing else ran.  An unwritable
   * target still fails before any record is reported or written. */
  int early = !c->resume && !(aq_farm_get() && aq_farm_get()->farm);
  if (early)
    workers_start(&S, &W);
  aq_h5_writer *h5 = NULL;
  aq_error oerr;
  aq_error_clear(&oerr);
  double tw = aq_suite_now_s();
  if (c->h5_path && aq_suite_open_h5(&S, &h5, &oerr) != AQ_OK) {
    aq_error_print(&oerr, stderr);
    rc = AQ_EXIT_OUTPUT;
    goto out;
  }
  aq_journal_entry *jent = NULL;
  size_t njent = 0;
  rc = aq_suite_journal_start(&S, &J, &jent, &njent); /* a refused journal: before any output */
  if (rc != AQ_EXIT_OK) {
    aq_h5_abort(h5);
    goto out;
  }
  if (aq_suite_text_header(&S, &oerr) != AQ_OK)
    goto output_failed;
  ws = aq_suite_journal_replay(&S, h5, &stats, jent, njent, &oerr);
  done = njent ? njent - 1 : 0;
  aq_journal_entries_free(jent, njent);
  if (ws != AQ_OK)
    goto output_failed;
  if (!early) { /* (early: no journal was read back, done = 0) */
    S.next_claim = S.next_write = done;
    for (size_t i = 0; i < done; i++)
      S.runs_done += S.nruns * (c->motions && c->motions[i] ? c->nazimuth : 1);
  }
  stats.write_s += aq_suite_now_s() - tw;

  if (aq_farm_get() && aq_farm_get()->farm) {
    ws = aq_suite_farm(&S, h5, J, done, &stats, &oerr);
    if (ws != AQ_OK)
      goto output_failed;
    goto written;
  }

  if (!early)
    workers_start(&S, &W);
  size_t started = W.started;
  if (started == 0) {
    aq_error_set(&oerr, AQ_ENOMEM, "", -1, -1, NULL, "cannot start a worker thread");
    fprintf(stderr, "archquake: cannot start a worker thread\n");
    rc = AQ_EXIT_FAIL;
  }

  if (started > 0)
    ws = aq_suite_write_all(&S, t_start, done, h5, J, &stats, &oerr);
  workers_join(&S, &W, 0);
  for (size_t k = 0; k < S.window; k++)
    aq_suite_slot_clear(&S, &S.slots[k]);
  if (c->progress)
    aq_suite_progress(&S, t_start, 1);
  if (ws != AQ_OK)
    goto output_failed;
  if (started == 0) {
    aq_h5_abort(h5);
    h5 = NULL;
    goto out;
  }

written:
  stats.read_s = S.read_s;
  stats.process_s = S.process_s;
  stats.run_s = S.run_s;
  stats.wait_s = S.wait_s;
  if (h5) {
    double t0 = aq_suite_now_s();
    aq_h5_timing tm = {aq_suite_now_s() - t_start, S.read_s, S.process_s, S.run_s,
                       stats.write_s};
    aq_status s = aq_h5_finish(h5, &tm, &oerr); /* frees h5 either way */
    h5 = NULL;
    stats.write_s += aq_suite_now_s() - t0;
    if (s != AQ_OK) {
      aq_error_print(&oerr, stderr);
      rc = AQ_EXIT_OUTPUT;
      goto out;
    }
  }
  if (c->text && fflush(c->text) != 0) {
    fprintf(stderr, "archquake: text output: cannot write: %s\n", strerror(errno));
    rc = AQ_EXIT_OUTPUT;
    goto out;
  }
  if (J && aq_journal_remove(J, &oerr) != AQ_OK)
    aq_error_print(&oerr, stderr); /* the results are complete all the same */
  J = NULL;
  if (rc == AQ_EXIT_OK && (stats.runs_failed || stats.records_failed || stats.checks_failed))
    rc = AQ_EXIT_FAIL;
  goto out;

output_failed:
  aq_error_print(&oerr, stderr);
  aq_h5_abort(h5);
  rc = AQ_EXIT_OUTPUT;
out:
  workers_join(&S, &W, 1); /* the outputs failed: stopped before any record */
  for (size_t k = 0; S.slots && k < S.window; k++)
    aq_suite_slot_clear(&S, &S.slots[k]);
  pthread_cond_destroy(&S.cond);
  pthread_cond_destroy(&S.wcond);
  pthread_mutex_destroy(&S.lock);
  aq_journal_close(J); /* kept: --resume continues from it */
  if (S.line)
    fclose(S.line);
  free(S.line_buf);
  stats.wall_s = aq_suite_now_s() - t_start;
  if (S.arches)
    for (size_t a = 0; a < c->narches; a++)
      aq_arch_free(S.arches[a]);
  free(S.arches);
  free(S.arch_ok);
  free(S.arch_err);
  free(S.lambda0);
  free(S.slots);
  aq_signal_ws_free(S.ws);
  if (stats_out)
    *stats_out = stats;
  return rc;
}

/* Every channel of a multi-channel file is a record of its own (FILE#CH). */
int aq_suite_run(const aq_suite_cfg *cfg, aq_suite_stats *stats)
{
  if (aq_farm_get() && aq_farm_get()->farm && (cfg->history || cfg->store_records)) {
    fprintf(stderr, "archquake: %s: expected one rank (mpirun -n 1) with it, got several: "
                    "results travel between ranks without histories or waveforms\n",
            cfg->history ? "--history" : "--store-records");
    return AQ_EXIT_USAGE;
  }
  char **names = NULL;
  size_t n = 0;
  aq_error err;
  const aq_orient_motion **mo = NULL;
  char **notes = NULL;
  size_t nnotes = 0;
  aq_status st = aq_suite_names(cfg, &names, &n, &mo, &notes, &nnotes, &err);
  for (size_t i = 0; st == AQ_OK && !aq_farm_is_follower() && i < nnotes; i++)
    fprintf(stderr, "archquake: %s\n", notes[i]); /* a vertical left out (io/record.h) */
  aq_record_names_free(notes, nnotes);
  if (st != AQ_OK) {
    aq_error_print(&err, stderr);
    aq_record_names_free(names, n);
    free(mo);
    return AQ_EXIT_FAIL;
  }
  aq_suite_cfg c = *cfg;
  c.records = names;
  c.nrecords = n;
  if (cfg->motions)
    c.motions = mo;
  int rc = suite_run(&c, stats);
  aq_record_names_free(names, n);
  free(mo);
  return rc;
}
