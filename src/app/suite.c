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
#include "../arch/result.h"
#include "../io/sha256.h"
#include "../report/h5.h"
#include "../report/report.h"
#include "../report/text.h"
#include "../units.h"
#include "../util/pool.h"
#include "app.h"
#include "farm.h"
#include "opt.h"
#include "suite_slot.h"

/* Records in flight per worker thread: at least enough that a worker
 * finishing a short record finds the next one while a long one is still
 * running.  A record whose runs are all done keeps only what writing it
 * needs (slot_shed), a few KB, so the window widens to
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
/* With -o the writer hashes each record file (record_sha256) from the bytes
 * its reader read, kept in the window up to this total (a larger file is
 * read again to hash it): reading it again cost 15 % of the hash. */
#define AQ_SUITE_KEEP_BYTES (64L << 20)
/* The journal (-o) is synced at most this often, s: a sync per record
 * (about 0.1-1 ms on a disk) bounded -o throughput on quiet suites.  A
 * killed suite loses nothing; an operating-system crash, at most the
 * records finished in this interval (they run again with --resume). */
#define AQ_SUITE_JOURNAL_SYNC_S 1.0
/* Progress line refresh period, s. */
#define AQ_SUITE_PROGRESS_PERIOD_S 0.25

static double now_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- per-record work ---------------------------------------------------- */

/* Work is handed out in two kinds of task: preparing a record (read,
 * process, measure, scale and split into steps for every factor: one
 * thread) and running one (arch, scale) of a prepared record (any thread).
 * Runs of the oldest records go first, so the window keeps moving; a new
 * record is prepared when no run is waiting.  A record with many arches or
 * factors thus spreads over every thread. */


typedef struct {
  const aq_suite_cfg *cfg;
  aq_arch **arches;
  int *arch_ok;             /* 0: its stepper cannot be made (reported once) */
  aq_error *arch_err;
  double *lambda0;          /* each arch's, for --scale-to-lambda0 (NAN: none) */
  aq_scale_rule rule;       /* the scaling rule (job/scale.h) */
  const char *model_name;
  size_t nscale;            /* runs per arch per record: factors x polarities */
  size_t npol;              /* polarities per factor (2 with --polarity both) */
  size_t nruns;             /* per record: narch * nscale */
  aq_signal_ws *ws;
  pthread_mutex_t lock;
  pthread_cond_t cond;      /* for the workers: a slot was freed, a record
                             * has runs for any thread, or the end is near */
  pthread_cond_t wcond;     /* for the writer: the next record is done */
  rec_slot *slots;
  size_t window;
  size_t keep_max;          /* a record file's bytes kept up to this size */
  size_t next_claim, next_write;
  int stop;                 /* the writer gave up: workers stop claiming */
  size_t runs_done;         /* for the progress line */
  double read_s, process_s, run_s;
  double wait_s;            /* the workers', waiting for work or room */
  aq_text_layout layout;    /* with cfg->aligned */
  FILE *line;               /* a row is formatted here first (text_row) */
  char *line_buf;
  size_t line_cap;
} suite;

/* Run slot k of an arch: factor k / npol, the record negated (reversed)
 * for the second slot of each factor with --polarity both, or for every
 * slot with --polarity reversed. */
static int slot_reversed(const suite *S, size_t k)
{
  return S->cfg->polarity == AQ_POLARITY_REVERSED ||
         (S->cfg->polarity == AQ_POLARITY_BOTH && k % 2 == 1);
}

static const char *slot_polarity(const suite *S, size_t k)
{
  return slot_reversed(S, k) ? "reversed" : "normal";
}

/* Free what record r's runs needed and writing it does not (the processed
 * samples, unless --store-records writes them, and the step lists): a
 * finished record waiting for the writer holds its metadata, measures and
 * run results only.  Called by the thread that finished its last run. */
static void slot_shed(suite *S, rec_slot *r)
{
  aq_processed *first = &r->subj.proc[0], keep = *first;
  first->acc_mps2 = NULL;
  aq_subject_shed(&r->subj);
  if (S->cfg->store_records)
    *first = keep; /* the writer writes it */
  else
    free(keep.acc_mps2);
  aq_runs_free(&r->plan);
}

static void slot_clear(suite *S, rec_slot *r)
{
  slot_shed(S, r);
  aq_subject_free(&r->subj);
  if (r->runs)
    for (size_t k = 0; k < r->nruns; k++)
      if (r->runs[k].have_res)
        aq_result_free(&r->runs[k].res);
  free(r->runs);
  free(r->scale);
  memset(r, 0, sizeof *r);
}

/* Run i of record r: arch *ai, scale slot *k, azimuth *z. */
static void run_index(const suite *S, const rec_slot *r, size_t i, size_t *ai,
                      size_t *k, size_t *z)
{
  *ai = i / (S->nscale * r->naz);
  *k = i / r->naz % S->nscale;
  *z = i % r->naz;
}

/* The arch azimuth of run slot z of r, deg (NAN for a plain record). */
static double run_azimuth(const suite *S, const rec_slot *r, size_t z)
{
  return r->motion ? S->cfg->azimuths_deg[z] : NAN;
}

/* Record i's motion (or NULL), azimuths per (arch, scale) and runs, set
 * in r (before it is prepared or decoded from the journal). */
static void slot_orient(const suite *S, size_t i, rec_slot *r)
{
  const aq_suite_cfg *c = S->cfg;
  r->motion = c->motions ? c->motions[i] : NULL;
  r->naz = r->motion ? c->nazimuth : 1;
  r->nruns = S->nruns * r->naz;
}

/* The file whose hash identifies record i: the record, or a motion's H1. */
static const char *record_file(const suite *S, size_t i)
{
  const aq_suite_cfg *c = S->cfg;
  return c->motions && c->motions[i] ? c->motions[i]->path[0] : c->records[i];
}

/* Every run of a record that failed before any run: status, NAN values. */
static void fail_runs(suite *S, rec_slot *r)
{
  const aq_suite_cfg *c = S->cfg;
  for (size_t i = 0; i < r->nruns; i++) {
    size_t a, k, z;
    run_index(S, r, i, &a, &k, &z);
    run_slot *u = &r->runs[i];
    double scale = c->scales ? c->scales[k / S->npol] : NAN;
    aq_summary_fill(&u->sum, c->records[r->index], aq_arch_name(S->arches[a]),
                    S->model_name, scale, NAN, r->status, NULL);
    aq_summary_normalise(&u->sum, slot_polarity(S, k), NULL, NULL, NULL);
    u->sum.azimuth_deg = run_azimuth(S, r, z);
  }
}

/* The record file's identity in the results (compare keys on it), when
 * prepare_record asked for it: hashed by the thread that writes the record
 * (or sends it to the leader), so that with -o the hash overlaps the
 * workers' reading and processing of the next records; from the bytes the
 * reader read when they were kept, else from the file.  next, if not NULL,
 * is the next record, done too when both have their bytes. */
static void record_sha256(const suite *S, rec_slot *r, rec_slot *next)
{
  aq_subject *a = &r->subj, *b = next ? &next->subj : NULL;
  if (b && r->want_sha && a->bytes && next->want_sha && b->bytes) {
    aq_sha256_hex2(a->bytes, a->nbytes, r->sha256, b->bytes, b->nbytes, next->sha256);
    r->want_sha = next->want_sha = 0;
    free(a->bytes);
    free(b->bytes);
    a->bytes = b->bytes = NULL;
    return;
  }
  if (!r->want_sha)
    return;
  r->want_sha = 0;
  aq_error herr;
  char file[4096];
  if (a->bytes)
    aq_sha256_hex(a->bytes, a->nbytes, r->sha256);
  else if (aq_sha256_file(aq_record_file(record_file(S, r->index), file, sizeof file),
                          r->sha256, &herr) != AQ_OK)
    r->sha256[0] = '\0'; /* the reader says why it cannot be read */
  free(a->bytes);
  a->bytes = NULL;
}

/* Read, process and measure record r->index (every component of a motion,
 * job/subject.h), then make the step lists its runs share (job/run.h).
 * Returns 1 if its runs can go ahead, 0 if the record failed (its runs are
 * filled as failed). */
static int prepare_record(suite *S, rec_slot *r)
{
  const aq_suite_cfg *c = S->cfg;
  const char *path = c->records[r->index];
  slot_orient(S, r->index, r);
  r->runs = calloc(r->nruns ? r->nruns : 1, sizeof *r->runs);
  r->scale = calloc(S->nscale, sizeof *r->scale);
  double *slot_sa = calloc(S->nscale, sizeof *slot_sa);
  if (!r->runs || !r->scale || !slot_sa) {
    free(r->runs);
    free(slot_sa);
    r->runs = NULL; /* the writer reports it; no run rows can be made */
    r->failed = 1;
    aq_error_set(&r->err, AQ_ENOMEM, path, -1, -1, NULL, "out of memory");
    aq_summary_status(r->status, sizeof r->status, "read", AQ_ENOMEM);
    return 0;
  }
  const aq_orient_motion *m = r->motion;
  aq_subject_src src = {{m ? m->path[0] : path, m ? m->path[1] : NULL, m ? m->path[2] : NULL},
                        {m ? m->azimuth_deg[0] : NAN, m ? m->azimuth_deg[1] : NAN},
                        path};
  r->want_sha = c->h5_path != NULL; /* hashed by record_sha256 */
  aq_subject_opts so = {&c->read, &c->proc, c->vertical, r->want_sha ? S->keep_max : 0, 0};
  aq_status s = aq_subject_prepare(&r->subj, &src, &so, S->ws, &r->err);
  if (s == AQ_OK)
    s = aq_scale_check_subject(&S->rule, path, r->subj.pga_g, &r->err);
  for (size_t k = 0; s == AQ_OK && k < S->nscale; k++) {
    r->scale[k] = aq_scale_factor(&S->rule, k / S->npol, r->subj.pga_g);
    slot_sa[k] = aq_scale_signed(r->scale[k], slot_reversed(S, k));
  }
  if (s == AQ_OK)
    s = aq_runs_init(&r->plan, &r->subj, r->naz, r->motion ? c->azimuths_deg[0] : 0.0,
                     c->merge_tol_g * AQ_G0_MPS2, slot_sa, S->nscale,
                     aq_scale_per_arch(&S->rule), &r->err);
  free(slot_sa);
  if (s != AQ_OK) {
    r->failed = 1;
    aq_summary_status(r->status, sizeof r->status, r->subj.stage, s);
    fail_runs(S, r);
    return 0;
  }
  snprintf(r->status, sizeof r->status, "ok");
  return 1;
}

/* Run i of prepared record r with this thread's steppers (st[a] NULL when
 * arch a cannot run). */
static void run_one(suite *S, rec_slot *r, size_t i, aq_stepper **st)
{
  const aq_suite_cfg *c = S->cfg;
  size_t ai, k, z;
  run_index(S, r, i, &ai, &k, &z);
  run_slot *u = &r->runs[i];
  double t0 = now_s();
  double scale = aq_scale_for_arch(&S->rule, S->lambda0[ai], r->scale[k]);
  double sa = aq_scale_signed(scale, slot_reversed(S, k)), pga_g = 0;
  int steps_failed = 0, ran = 0;
  aq_status rs = AQ_OK;
  if (aq_scale_per_arch(&S->rule) && !st[ai])
    ; /* the arch's own failure is reported below */
  else if ((rs = aq_scale_check_arch(&S->rule, c->arch_paths[ai], S->lambda0[ai], scale,
                                     &u->err)) != AQ_OK)
    steps_failed = 1;
  else
    rs = aq_runs_run(&r->plan, k, r->motion ? c->azimuths_deg[z] : 0.0, sa, st[ai], &u->res,
                     &pga_g, &steps_failed, &ran, &u->err);
  const char *stage = "run";
  if (steps_failed) {
    stage = "process";
  } else if (!st[ai]) {
    rs = S->arch_err[ai].status != AQ_OK ? S->arch_err[ai].status : AQ_EINTERNAL;
    u->err = S->arch_err[ai];
    stage = "arch";
  }
  u->have_res = ran;
  char status[AQ_SUMMARY_STATUS_MAX];
  aq_summary_status(status, sizeof status, stage, rs);
  u->failed = rs != AQ_OK;
  if (u->failed && u->have_res) {
    aq_result_free(&u->res);
    u->have_res = 0;
  }
  aq_summary_fill(&u->sum, c->records[r->index], aq_arch_name(S->arches[ai]),
                  S->model_name, scale, pga_g, status,
                  u->have_res ? &u->res : NULL);
  aq_summary_normalise(&u->sum, slot_polarity(S, k), u->have_res ? &u->res : NULL,
                       aq_arch_path(S->arches[ai], 0), aq_arch_path(S->arches[ai], 1));
  u->sum.azimuth_deg = run_azimuth(S, r, z);
  u->run_s = now_s() - t0;
}

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

static void worker(void *ctx, size_t k)
{
  worker_arg *w = &((worker_arg *)ctx)[k];
  suite *S = w->S;
  const size_t nrec = S->cfg->nrecords;
  pthread_mutex_lock(&S->lock);
  for (;;) {
    if (S->stop)
      break;
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
      run_one(S, r, i, w->st);
      pthread_mutex_lock(&S->lock);
      S->run_s += r->runs[i].run_s;
      S->runs_done++;
      if (++r->runs_done == r->nruns) { /* the last: nobody else uses r now */
        pthread_mutex_unlock(&S->lock);
        slot_shed(S, r);
        pthread_mutex_lock(&S->lock);
        slot_done(S, r);
      }
      continue;
    }
    /* 2. prepare the next record, if the window has room */
    if (S->next_claim < nrec && S->next_claim < S->next_write + S->window) {
      size_t idx = S->next_claim++;
      r = &S->slots[idx % S->window];
      r->state = SLOT_PREPARING;
      r->index = idx;
      pthread_mutex_unlock(&S->lock);
      int ok = prepare_record(S, r);
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
        slot_shed(S, r);
        pthread_mutex_lock(&S->lock);
        slot_done(S, r);
      }
      continue;
    }
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
    double t0 = now_s();
    pthread_cond_wait(&S->cond, &S->lock);
    S->wait_s += now_s() - t0;
  }
  pthread_mutex_unlock(&S->lock);
}

/* ---- the writer --------------------------------------------------------- */

static void progress(suite *S, double t_start, size_t total, int final)
{
  if (!S->cfg->progress)
    return;
  if (final) {
    fputs("\r\033[K", stderr);
    return;
  }
  size_t done = S->runs_done;
  double el = now_s() - t_start;
  if (done > 0 && done < total)
    fprintf(stderr, "\r\033[Karchquake: %zu/%zu runs, %.1f s elapsed, ~%.0f s left",
            done, total, el, el * (double)(total - done) / (double)done);
  else
    fprintf(stderr, "\r\033[Karchquake: %zu/%zu runs, %.1f s elapsed", done,
            total, el);
  fflush(stderr);
}

/* One row to the text output with one write(2): formatted aside, then put
 * into the (empty) stdio buffer and flushed, so that an interrupted run
 * leaves only whole rows. */
static int text_row(suite *S, const aq_summary *s)
{
  FILE *m = S->line;
  if (fseeko(m, 0, SEEK_SET) != 0 ||
      (S->cfg->aligned ? aq_text_row_aligned(m, &S->layout, s) : aq_text_row(m, s)) != 0 ||
      fflush(m) != 0)
    return -1;
  off_t n = ftello(m);
  if (n < 0)
    return -1;
  return fwrite(S->line_buf, 1, (size_t)n, S->cfg->text) == (size_t)n &&
                 fflush(S->cfg->text) == 0
             ? 0
             : -1;
}

/* 1 if writing r prints something on stderr. */
static int has_diagnostics(const rec_slot *r)
{
  if (r->failed || r->subj.warning[0] || r->subj.rec[0].units_conflict[0])
    return 1;
  for (int k = 0; k < 3; k++)
    if (r->subj.have_rec[k] && (r->subj.rec[k].polarity_note[0] || r->subj.rec[k].vertical_note[0]))
      return 1;
  for (size_t i = 0; r->runs && i < r->nruns; i++)
    if (r->runs[i].failed)
      return 1;
  return 0;
}

/* Write one finished record (report its problems, then its rows).  Returns
 * AQ_OK, or the output failure with *err filled. */
static aq_status write_record(suite *S, rec_slot *r, aq_h5_writer *h5,
                              aq_suite_stats *stats, aq_error *err)
{
  const aq_suite_cfg *c = S->cfg;
  const char *path = c->records[r->index];
  if (r->failed) {
    aq_error_print(&r->err, stderr);
    stats->records_failed++;
  }
  const aq_subject *sj = &r->subj;
  if (sj->warning[0])
    fprintf(stderr, "archquake: %s: warning: %s\n", path, sj->warning);
  if (sj->rec[0].units_conflict[0])
    fprintf(stderr, "archquake: %s: units: %s\n", path, sj->rec[0].units_conflict);
  for (int k = 0; k < 3; k++) { /* each component's polarity and vertical notes */
    if (sj->have_rec[k] && sj->rec[k].polarity_note[0])
      fprintf(stderr, "archquake: %s: polarity: %s\n", sj->rec[k].path, sj->rec[k].polarity_note);
    if (sj->have_rec[k] && sj->rec[k].vertical_note[0])
      fprintf(stderr, "archquake: %s: vertical: %s\n", sj->rec[k].path, sj->rec[k].vertical_note);
  }
  if (!r->runs)
    return AQ_OK;
  for (size_t i = 0; i < r->nruns; i++) {
    run_slot *u = &r->runs[i];
    size_t ai, k, z;
    run_index(S, r, i, &ai, &k, &z);
    if (u->failed && !r->failed && S->arch_ok[ai]) {
      char msg[1200], num[64], az[64] = "";
      aq_error_format(&u->err, msg, sizeof msg);
      aq_text_double(num, sizeof num, u->sum.scale);
      if (r->motion)
        snprintf(az, sizeof az, ", azimuth %g deg", u->sum.azimuth_deg);
      fprintf(stderr, "archquake: %s: arch %s, scale %s%s%s: %s\n", path,
              aq_arch_name(S->arches[ai]), num, slot_reversed(S, k) ? " reversed" : "",
              az, msg);
    }
  }
  if (h5) {
    aq_h5_record hr = {path,
                       sj->have_rec[0] ? &sj->rec[0] : NULL,
                       sj->have_proc[0] ? &sj->proc[0] : NULL,
                       sj->have_im ? &sj->im : NULL,
                       r->status,
                       r->failed ? r->err.message : NULL,
                       r->sha256,
                       sj->read_s,
                       sj->process_s};
    char full[1200];
    if (r->failed) {
      aq_error_format(&r->err, full, sizeof full);
      hr.error = full;
    }
    aq_status s = aq_h5_write_record(h5, r->index, &hr, err);
    if (s != AQ_OK)
      return s;
  }
  const aq_summary **group = malloc(r->naz * sizeof *group);
  if (!group)
    return aq_error_set(err, AQ_ENOMEM, "text output", -1, -1, NULL, "out of memory");
  size_t worst = 0;
  for (size_t i = 0; i < r->nruns; i++) {
    run_slot *u = &r->runs[i];
    size_t ai, k, z;
    run_index(S, r, i, &ai, &k, &z);
    stats->runs++;
    stats->runs_failed += u->failed || r->failed;
    if (z == 0) { /* the worst azimuth of this (arch, scale) */
      for (size_t j = 0; j < r->naz; j++)
        group[j] = &r->runs[i + j].sum;
      worst = aq_summary_worst(group, r->naz);
    }
    int shown = c->all_azimuths || z == worst;
    if (shown && c->text && text_row(S, &u->sum) != 0) {
      free(group);
      return aq_error_set(err, AQ_EIO, "text output", -1, -1, NULL,
                          "cannot write a row: %s", strerror(errno));
    }
    if (h5) {
      char msg[1200];
      const char *em = NULL;
      if (u->failed) {
        aq_error_format(&u->err, msg, sizeof msg);
        em = msg;
      }
      aq_status s = aq_h5_write_run(h5, r->index, ai, k / S->npol, &u->sum,
                                    u->have_res ? &u->res : NULL, em, u->run_s, err);
      if (s != AQ_OK) {
        free(group);
        return s;
      }
    }
  }
  free(group);
  return AQ_OK;
}

static void iso_now(char *buf, size_t n)
{
  time_t t = time(NULL);
  struct tm tm;
  if (gmtime_r(&t, &tm))
    strftime(buf, n, "%Y-%m-%dT%H:%M:%SZ", &tm);
  else
    snprintf(buf, n, "unknown");
}

/* Open the results file and write the root and the arches. */
static aq_status open_h5(suite *S, aq_h5_writer **out, aq_error *err)
{
  const aq_suite_cfg *c = S->cfg;
  aq_h5_writer *w;
  aq_status s = aq_h5_open(c->h5_path, &w, err);
  if (s != AQ_OK)
    return s;
  char created[64];
  iso_now(created, sizeof created);
  aq_h5_root root = {AQ_VERSION,
                     c->command_line,
                     created,
                     &c->proc,
                     c->merge_tol_g,
                     c->units_text ? c->units_text : "file",
                     c->read.dt_s,
                     S->model_name,
                     c->cor,
                     c->scales,
                     S->nscale / S->npol,
                     c->scales ? NAN : c->scale_to_pga_g,
                     c->history,
                     c->threads,
                     aq_build_string(),
                     c->store_records,
                     aq_opt_polarity_names[c->polarity],
                     c->scale_to_lambda0 > 0 ? c->scale_to_lambda0 : NAN};
  s = aq_h5_write_root(w, &root, err);
  for (size_t a = 0; s == AQ_OK && a < c->narches; a++) {
    const aq_arch *A = S->arches[a];
    /* the values the runs use: --cor over the file's; none with momentum */
    aq_arch_dynamics used = *aq_arch_dynamics_of(A);
    used.cor = used.impact == AQ_IMPACT_MOMENTUM ? NAN : isnan(c->cor) ? used.cor : c->cor;
    const char *cfg = aq_arch_config_text(A);
    char sha[AQ_SHA256_HEX], joints[2][64], faces[2][8];
    aq_arch_sha256(A, sha); /* the file's bytes, as read, and a joints arch's files' */
    for (int k = 0; k < 2; k++)
      aq_hinge_set_format(aq_arch_hinge_set(A, k), joints[k], sizeof joints[k],
                          faces[k], sizeof faces[k]);
    aq_h5_arch ha = {aq_arch_name(A),
                     c->arch_paths[a],
                     cfg,
                     &used,
                     {aq_arch_path(A, 0), aq_arch_path(A, 1)},
                     sha,
                     aq_arch_searched(A),
                     {joints[0], joints[1]},
                     {faces[0], faces[1]},
                     A};
    s = aq_h5_write_arch(w, a, &ha, err);
  }
  if (s != AQ_OK) {
    aq_h5_abort(w);
    return s;
  }
  *out = w;
  return AQ_OK;
}

/* ---- the journal (--resume) -------------------------------------------- */

/* The first line where identities a (the journal's) and b (this
 * command's) differ, into buf[n] as 'has "..." where this command has
 * "..."'. */
static void first_difference(const char *a, const char *b, char *buf, size_t n)
{
  while (*a && *b) {
    size_t la = strcspn(a, "\n"), lb = strcspn(b, "\n");
    if (la != lb || memcmp(a, b, la) != 0) {
      snprintf(buf, n, "has \"%.*s\" where this command has \"%.*s\"", (int)la, a,
               (int)lb, b);
      return;
    }
    a += la + (a[la] != '\0');
    b += lb + (b[lb] != '\0');
  }
  snprintf(buf, n, "has %s lines than this command's identity", *a ? "more" : "fewer");
}

/* Start the journal of a suite writing to c->h5_path.  With --resume and a
 * journal of the same command, its entries (identity first) are checked and
 * returned in *e (*ne of them) for journal_replay.  Returns AQ_EXIT_OK, or
 * the exit status after printing one line. */
static int journal_start(suite *S, aq_journal **J, aq_journal_entry **e, size_t *ne)
{
  const aq_suite_cfg *c = S->cfg;
  *J = NULL;
  *e = NULL;
  *ne = 0;
  if (!c->h5_path || c->history || c->store_records)
    return AQ_EXIT_OK; /* datasets a journal does not hold */
  char *id = NULL, *path = malloc(strlen(c->h5_path) + 16);
  size_t dropped = 0;
  aq_error err;
  aq_error_clear(&err);
  int rc = AQ_EXIT_OK;
  if (!path || aq_suite_identity(c, S->arches, &id) != 0) {
    fprintf(stderr, "archquake: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto out;
  }
  aq_journal_name(c->h5_path, path, strlen(c->h5_path) + 16);
  if (c->resume && aq_journal_open(path, J, e, ne, &dropped, &err) != AQ_OK) {
    char msg[1200];
    aq_error_format(&err, msg, sizeof msg);
    fprintf(stderr, "archquake: %s (--resume: run without it to start over)\n", msg);
    rc = AQ_EXIT_USAGE;
    goto out;
  }
  if (!*J) {
    if (aq_journal_create(path, id, strlen(id) + 1, AQ_SUITE_JOURNAL_SYNC_S, J, &err) != AQ_OK) {
      aq_error_print(&err, stderr);
      rc = AQ_EXIT_OUTPUT;
    }
    goto out;
  }
  char why[1200] = "";
  if ((*e)[0].n != strlen(id) + 1 || memcmp((*e)[0].data, id, (*e)[0].n) != 0) {
    char diff[1000];
    first_difference((const char *)(*e)[0].data, id, diff, sizeof diff);
    snprintf(why, sizeof why, "the journal is another command's: it %s", diff);
  }
  /* Check every entry before writing anything: the order, and that each
   * record's file is still the one that was run. */
  for (size_t k = 1; !why[0] && k < *ne; k++) {
    rec_slot r;
    memset(&r, 0, sizeof r);
    char sha[AQ_SHA256_HEX] = "", file[4096];
    if (k - 1 < c->nrecords)
      slot_orient(S, k - 1, &r);
    if (k - 1 >= c->nrecords || aq_suite_slot_decode(&(*e)[k], r.nruns, &r) != 0 ||
        r.index != k - 1)
      snprintf(why, sizeof why, "entry %zu: expected record %zu of this suite, got "
                                "something else", k, k - 1);
    else if (r.sha256[0] &&
             (aq_sha256_file(aq_record_file(record_file(S, k - 1), file, sizeof file), sha,
                             &err) != AQ_OK ||
              strcmp(sha, r.sha256) != 0))
      snprintf(why, sizeof why, "the record %s changed since the journal was written "
                                "(sha256 %s, journal %s)", c->records[k - 1],
               sha[0] ? sha : "unreadable", r.sha256);
    slot_clear(S, &r);
  }
  if (why[0]) {
    fprintf(stderr, "archquake: %s: --resume: %s; run without --resume to start over\n",
            path, why);
    aq_journal_close(*J);
    *J = NULL;
    rc = AQ_EXIT_USAGE;
    goto out;
  }
  if (dropped)
    fprintf(stderr, "archquake: %s: dropped a torn last entry (%zu bytes): its record "
                    "runs again\n", path, dropped);
  fprintf(stderr, "archquake: %s: %zu of %zu records done before, continuing\n", path,
          *ne - 1, c->nrecords);
out:
  if (*J)
    aq_journal_set_sync_period(*J, AQ_SUITE_JOURNAL_SYNC_S);
  if (rc != AQ_EXIT_OK) {
    aq_journal_entries_free(*e, *ne);
    *e = NULL;
    *ne = 0;
  }
  free(id);
  free(path);
  return rc;
}

/* Write the records of journal entries e[1..ne) again, in order
 * (diagnostics, rows, results file).  Returns AQ_OK or the output failure. */
static aq_status journal_replay(suite *S, aq_h5_writer *h5, aq_suite_stats *stats,
                                const aq_journal_entry *e, size_t ne, aq_error *err)
{
  for (size_t k = 1; k < ne; k++) {
    rec_slot r;
    memset(&r, 0, sizeof r);
    slot_orient(S, k - 1, &r);
    aq_suite_slot_decode(&e[k], r.nruns, &r); /* checked by journal_start */
    slot_orient(S, k - 1, &r);
    aq_status ws = write_record(S, &r, h5, stats, err);
    slot_clear(S, &r);
    if (ws != AQ_OK)
      return ws;
  }
  return AQ_OK;
}

/* A stepper for arch a with the suite's settings, or NULL (err filled). */
static aq_stepper *make_stepper(const suite *S, size_t a, aq_error *err)
{
  const aq_suite_cfg *c = S->cfg;
  return aq_job_stepper(S->arches[a], c->model, c->cor, c->history, err);
}

/* ---- other processes (farm.h): a task per (record, arch) ---------------- */

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
  pthread_mutex_t lock;   /* guards the cache */
  pthread_cond_t cond;
  rec_slot *cache;        /* records prepared here (state SLOT_PREPARING or SLOT_READY) */
  size_t *users, *used;   /* per cache slot: tasks using it, tick of its last use */
  size_t ncache, tick;
  /* leader */
  aq_h5_writer *h5;
  aq_journal *J;
  aq_suite_stats *stats;
  rec_slot **pend;        /* per record: its arches' results so far, merged */
  size_t *parts;          /* per record: tasks taken */
  size_t next_write;
} farm_ctx;

/* Record i prepared in the cache (with a use counted). */
static rec_slot *farm_acquire(farm_ctx *X, size_t i)
{
  pthread_mutex_lock(&X->lock);
  for (;;) {
    size_t hit = X->ncache, lru = X->ncache;
    for (size_t k = 0; k < X->ncache; k++) {
      rec_slot *x = &X->cache[k];
      if (x->state != SLOT_FREE && x->index == i)
        hit = k;
      else if (X->users[k] == 0 && x->state != SLOT_PREPARING &&
               (lru == X->ncache || X->used[k] < X->used[lru]))
        lru = k;
    }
    if (hit < X->ncache && X->cache[hit].state == SLOT_READY) {
      X->users[hit]++;
      pthread_mutex_unlock(&X->lock);
      return &X->cache[hit];
    }
    if (hit == X->ncache && lru < X->ncache) { /* prepare it here */
      rec_slot *r = &X->cache[lru];
      slot_clear(X->S, r);
      r->state = SLOT_PREPARING;
      r->index = i;
      X->users[lru] = 1;
      pthread_mutex_unlock(&X->lock);
      prepare_record(X->S, r);
      record_sha256(X->S, r, NULL); /* before the slot is shared */
      pthread_mutex_lock(&X->lock);
      r->state = SLOT_READY;
      pthread_cond_broadcast(&X->cond);
      pthread_mutex_unlock(&X->lock);
      return r;
    }
    pthread_cond_wait(&X->cond, &X->lock); /* being prepared, or every slot in use */
  }
}

static void farm_release(farm_ctx *X, rec_slot *r)
{
  pthread_mutex_lock(&X->lock);
  size_t k = (size_t)(r - X->cache);
  X->users[k]--;
  X->used[k] = ++X->tick;
  pthread_cond_broadcast(&X->cond);
  pthread_mutex_unlock(&X->lock);
}

/* Task t: record t / narches with arch t % narches, every factor,
 * polarity and azimuth; its result is the record encoded with that arch's
 * runs only (suite_slot.h). */
static int farm_run(void *ctx, size_t t, unsigned char **msg, size_t *n)
{
  farm_ctx *X = ctx;
  suite *S = X->S;
  size_t na = S->cfg->narches, a = t % na;
  rec_slot *r = farm_acquire(X, t / na);
  size_t per = r->nruns / na; /* runs of one arch */
  aq_stepper **st = calloc(na, sizeof *st);
  int rc = st ? 0 : -1;
  if (rc == 0 && r->runs && !r->failed) {
    aq_error e;
    st[a] = S->arch_ok[a] ? make_stepper(S, a, &e) : NULL;
    for (size_t k = 0; k < per; k++)
      run_one(S, r, a * per + k, st);
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
  farm_release(X, r);
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
  slot_orient(S, i, &part);
  size_t nruns = part.nruns, per = nruns / na;
  aq_journal_entry e = {(unsigned char *)msg, n};
  if (aq_suite_slot_decode(&e, per, &part) != 0 || part.index != i) {
    slot_clear(S, &part);
    return aq_error_set(err, AQ_EFORMAT, c->records[i], -1, -1, NULL,
                        "expected the results of record %zu, arch %zu from a follower, "
                        "got a malformed message of %zu bytes", i, a, n), -1;
  }
  slot_orient(S, i, &part); /* decoding cleared it */
  rec_slot *m = X->pend[i];
  int first = m == NULL;
  if (first) { /* the first arch in: the record itself, with room for every run */
    m = X->pend[i] = malloc(sizeof *m);
    run_slot *runs = part.runs ? calloc(nruns ? nruns : 1, sizeof *runs) : NULL;
    if (!m || (part.runs && !runs)) {
      free(m);
      free(runs);
      X->pend[i] = NULL;
      slot_clear(S, &part);
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
    slot_clear(S, &part); /* a copy of what m holds */
  X->parts[i]++;
  aq_status ws = AQ_OK;
  for (; ws == AQ_OK && X->next_write < c->nrecords && X->parts[X->next_write] == na;
       X->next_write++) {
    rec_slot *r = X->pend[X->next_write];
    ws = write_record(S, r, X->h5, X->stats, err);
    if (ws == AQ_OK && X->J) {
      aq_bytes_out jb = {0};
      aq_suite_slot_encode(r, r->nruns, &jb);
      ws = jb.oom ? aq_error_set(err, AQ_ENOMEM, c->h5_path, -1, -1, NULL, "out of memory")
                  : aq_journal_append(X->J, jb.data, jb.n, err);
      free(jb.data);
    }
    slot_clear(S, r);
    free(r);
    X->pend[X->next_write] = NULL;
  }
  return ws == AQ_OK ? 0 : -1;
}

/* Run the suite's tasks through the farm: a follower runs what it is
 * handed; the leader (h5, J, stats for writing) records done..nrecords.
 * Returns AQ_OK, or the failure (err filled). */
static aq_status farm_suite(suite *S, aq_h5_writer *h5, aq_journal *J, size_t done,
                            aq_suite_stats *stats, aq_error *err)
{
  const aq_suite_cfg *c = S->cfg;
  const aq_farm *f = aq_farm_get();
  size_t threads = c->threads > 0 ? (size_t)c->threads : 1, na = c->narches;
  size_t ntask = c->nrecords * na, ntodo = f->follower ? 0 : ntask - done * na;
  farm_ctx X = {.S = S, .h5 = h5, .J = J, .stats = stats, .next_write = done,
                .ncache = threads + AQ_SUITE_FARM_KEEP_EXTRA};
  pthread_mutex_init(&X.lock, NULL);
  pthread_cond_init(&X.cond, NULL);
  X.cache = calloc(X.ncache, sizeof *X.cache);
  X.users = calloc(X.ncache, sizeof *X.users);
  X.used = calloc(X.ncache, sizeof *X.used);
  size_t *todo = calloc(ntodo ? ntodo : 1, sizeof *todo);
  if (!f->follower) {
    X.pend = calloc(c->nrecords ? c->nrecords : 1, sizeof *X.pend);
    X.parts = calloc(c->nrecords ? c->nrecords : 1, sizeof *X.parts);
  }
  aq_status ws = AQ_OK;
  if (!X.cache || !X.users || !X.used || !todo || (!f->follower && (!X.pend || !X.parts)))
    ws = aq_error_set(err, AQ_ENOMEM, "", -1, -1, NULL, "out of memory");
  for (size_t k = 0; k < ntodo; k++)
    todo[k] = done * na + k;
  aq_farm_tasks T = {ntask, (long)threads, na, AQ_SUITE_FARM_AHEAD, farm_run, farm_take,
                     &X};
  if (ws == AQ_OK && na > 0 && f->farm(f->ctx, &T, todo, ntodo, err) != 0)
    ws = err->status != AQ_OK ? err->status : AQ_EIO;
  for (size_t i = 0; X.pend && i < c->nrecords; i++)
    if (X.pend[i]) {
      slot_clear(S, X.pend[i]);
      free(X.pend[i]);
    }
  for (size_t k = 0; X.cache && k < X.ncache; k++)
    slot_clear(S, &X.cache[k]);
  free(X.cache);
  free(X.users);
  free(X.used);
  free(X.pend);
  free(X.parts);
  free(todo);
  pthread_cond_destroy(&X.cond);
  pthread_mutex_destroy(&X.lock);
  return ws;
}

/* The worker threads of S, each with its own steppers. */
typedef struct {
  long n;
  size_t started;
  aq_pool *pool;
  worker_arg *wa;
} workers;

/* Start up to W->n workers (W->started of them run). */
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
        a->st[k] = make_stepper(S, k, &e);
      }
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

static int suite_run(const aq_suite_cfg *c, aq_suite_stats *stats_out)
{
  double t_start = now_s();
  aq_app_heap_policy(); /* records' arrays stay in the heap (heap.c) */
  aq_suite_stats stats;
  memset(&stats, 0, sizeof stats);
  suite S;
  memset(&S, 0, sizeof S);
  pthread_mutex_init(&S.lock, NULL);
  pthread_cond_init(&S.cond, NULL);
  pthread_cond_init(&S.wcond, NULL);
  S.cfg = c;
  S.model_name = aq_model_name(c->model);
  S.npol = c->polarity == AQ_POLARITY_BOTH ? 2 : 1;
  S.nscale = (c->scales ? c->nscale : 1) * S.npol;
  S.nruns = c->narches * S.nscale; /* per plain record; x azimuths per motion */
  S.rule = (aq_scale_rule){c->scales, c->nscale, c->scale_to_pga_g,
                           c->scale_to_lambda0 > 0 ? c->scale_to_lambda0 : 0};
  long nthreads = c->threads < 1 ? 1 : c->threads;
  if ((size_t)nthreads > c->nrecords)
    nthreads = c->nrecords ? (long)c->nrecords : 1;
  S.window = suite_window(&S, (size_t)nthreads);
  workers W = {nthreads, 0, NULL, NULL};
  S.keep_max = (size_t)AQ_SUITE_KEEP_BYTES / S.window;
  int rc = AQ_EXIT_OK;
  aq_status ws = AQ_OK;
  aq_journal *J = NULL; /* with -o: the records written so far */
  size_t done = 0;      /* records written from the journal (--resume) */

  /* Arches: loaded once, every bad one reported; nothing runs if any is. */
  S.arches = calloc(c->narches ? c->narches : 1, sizeof *S.arches);
  S.arch_ok = calloc(c->narches ? c->narches : 1, sizeof *S.arch_ok);
  S.arch_err = calloc(c->narches ? c->narches : 1, sizeof *S.arch_err);
  S.lambda0 = calloc(c->narches ? c->narches : 1, sizeof *S.lambda0);
  S.slots = calloc(S.window, sizeof *S.slots);
  S.ws = aq_signal_ws_alloc();
  S.line = c->text ? open_memstream(&S.line_buf, &S.line_cap) : NULL;
  if (!S.arches || !S.arch_ok || !S.arch_err || !S.lambda0 || !S.slots || !S.ws || (c->text && !S.line)) {
    fprintf(stderr, "archquake: out of memory\n");
    rc = AQ_EXIT_FAIL;
    goto out;
  }
  int bad_arch = 0;
  for (size_t a = 0; a < c->narches; a++) {
    aq_error e;
    aq_error_clear(&e);
    if (aq_arch_load(c->arch_paths[a], &S.arches[a], &e) != AQ_OK) {
      aq_error_print(&e, stderr);
      bad_arch = 1;
    }
  }
  /* One name, one arch: rows are labelled and compared by name.  An option
   * that cannot act on an arch is refused, not ignored. */
  for (size_t a = 0; !bad_arch && a < c->narches; a++) {
    for (size_t b = 0; b < a; b++)
      if (strcmp(aq_arch_name(S.arches[a]), aq_arch_name(S.arches[b])) == 0) {
        fprintf(stderr, "archquake: %s: name: expected a name unlike the other arches', "
                        "got \"%s\", the name of %s too\n",
                c->arch_paths[a], aq_arch_name(S.arches[a]), c->arch_paths[b]);
        bad_arch = 1;
        break;
      }
    aq_mechanism_warn_minimum(c->arch_paths[a], S.arches[a]);
    bad_arch |= aq_opt_cor_momentum(c->arch_paths[a], !isnan(c->cor),
                                    aq_arch_dynamics_of(S.arches[a])->impact ==
                                        AQ_IMPACT_MOMENTUM);
  }
  if (bad_arch) {
    rc = AQ_EXIT_USAGE;
    goto out;
  }
  for (size_t a = 0; a < c->narches; a++)
    S.lambda0[a] = aq_lambda0(S.arches[a]);
  /* An arch whose stepper cannot be made (no admissible mechanism...) is
   * reported once; its runs fail. */
  for (size_t a = 0; a < c->narches; a++) {
    aq_error_clear(&S.arch_err[a]);
    aq_stepper *st = make_stepper(&S, a, &S.arch_err[a]);
    S.arch_ok[a] = st != NULL;
    if (!st) {
      char msg[1200];
      aq_error_format(&S.arch_err[a], msg, sizeof msg);
      fprintf(stderr, "archquake: %s: arch %s cannot run: %s\n", c->arch_paths[a],
              aq_arch_name(S.arches[a]), msg);
      rc = AQ_EXIT_FAIL;
    }
    aq_stepper_free(st);
  }

  if (aq_farm_is_follower()) {
    aq_error ferr;
    if (farm_suite(&S, NULL, NULL, 0, NULL, &ferr) != AQ_OK)
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
  double tw = now_s();
  if (c->h5_path && open_h5(&S, &h5, &oerr) != AQ_OK) {
    aq_error_print(&oerr, stderr);
    rc = AQ_EXIT_OUTPUT;
    goto out;
  }
  aq_journal_entry *jent = NULL;
  size_t njent = 0;
  rc = journal_start(&S, &J, &jent, &njent); /* a refused journal: before any output */
  if (rc != AQ_EXIT_OK) {
    aq_h5_abort(h5);
    goto out;
  }
  if (c->aligned) {
    size_t rw = 6, aw = 4;
    for (size_t i = 0; i < c->nrecords; i++)
      rw = strlen(c->records[i]) > rw ? strlen(c->records[i]) : rw;
    for (size_t a = 0; a < c->narches; a++)
      aw = strlen(aq_arch_name(S.arches[a])) > aw ? strlen(aq_arch_name(S.arches[a])) : aw;
    aq_text_layout_init(&S.layout, rw < AQ_SUMMARY_RECORD_MAX ? rw : AQ_SUMMARY_RECORD_MAX - 1,
                        aw < AQ_SUMMARY_ARCH_MAX ? aw : AQ_SUMMARY_ARCH_MAX - 1);
  }
  if (c->text && (c->aligned ? aq_text_header_aligned(c->text, &S.layout)
                             : aq_text_header(c->text)) != 0) {
    aq_error_set(&oerr, AQ_EIO, "text output", -1, -1, NULL,
                 "cannot write: %s", strerror(errno));
    goto output_failed;
  }
  if (c->text && fflush(c->text) != 0) { /* rows start in an empty buffer */
    aq_error_set(&oerr, AQ_EIO, "text output", -1, -1, NULL,
                 "cannot write: %s", strerror(errno));
    goto output_failed;
  }
  ws = journal_replay(&S, h5, &stats, jent, njent, &oerr);
  done = njent ? njent - 1 : 0;
  aq_journal_entries_free(jent, njent);
  if (ws != AQ_OK)
    goto output_failed;
  if (!early) { /* (early: no journal was read back, done = 0) */
    S.next_claim = S.next_write = done;
    for (size_t i = 0; i < done; i++)
      S.runs_done += S.nruns * (c->motions && c->motions[i] ? c->nazimuth : 1);
  }
  stats.write_s += now_s() - tw;

  if (aq_farm_get() && aq_farm_get()->farm) {
    ws = farm_suite(&S, h5, J, done, &stats, &oerr);
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

  /* Write in record order as records finish. */
  size_t total = 0;
  for (size_t i = 0; i < c->nrecords; i++)
    total += S.nruns * (c->motions && c->motions[i] ? c->nazimuth : 1);
  double last_progress = 0;
  for (size_t i = done; started > 0 && i < c->nrecords; i++) {
    rec_slot *r = &S.slots[i % S.window];
    pthread_mutex_lock(&S.lock);
    while (!(r->state == SLOT_DONE && r->index == i)) {
      struct timespec ts;
      clock_gettime(CLOCK_REALTIME, &ts);
      ts.tv_nsec += (long)(AQ_SUITE_PROGRESS_PERIOD_S * 1e9);
      if (ts.tv_nsec >= 1000000000L) {
        ts.tv_sec++;
        ts.tv_nsec -= 1000000000L;
      }
      pthread_cond_timedwait(&S.wcond, &S.lock, &ts);
      if (c->progress && now_s() - last_progress >= AQ_SUITE_PROGRESS_PERIOD_S) {
        progress(&S, t_start, total, 0);
        last_progress = now_s();
      }
    }
    rec_slot *next = &S.slots[(i + 1) % S.window]; /* the window holds 2 or more */
    if (!(i + 1 < c->nrecords && next->state == SLOT_DONE && next->index == i + 1))
      next = NULL; /* not done yet: no worker touches a record once it is */
    pthread_mutex_unlock(&S.lock);
    double t0 = now_s();
    /* clear the line before diagnostics, and before rows on the terminal */
    if (c->progress && (c->aligned || has_diagnostics(r)))
      progress(&S, t_start, total, 1);
    record_sha256(&S, r, next);
    ws = write_record(&S, r, h5, &stats, &oerr);
    if (ws == AQ_OK && J) { /* the record is done: it survives an interruption */
      aq_bytes_out jb = {0};
      aq_suite_slot_encode(r, r->nruns, &jb);
      ws = jb.oom ? aq_error_set(&oerr, AQ_ENOMEM, c->h5_path, -1, -1, NULL, "out of memory")
                  : aq_journal_append(J, jb.data, jb.n, &oerr);
      free(jb.data);
    }
    if (c->progress && c->aligned && c->text)
      fflush(c->text); /* the rows reach the terminal before the next line */
    stats.write_s += now_s() - t0;
    pthread_mutex_lock(&S.lock);
    slot_clear(&S, r);
    S.next_write = i + 1;
    if (ws != AQ_OK)
      S.stop = 1;
    pthread_cond_broadcast(&S.cond); /* room in the window */
    pthread_mutex_unlock(&S.lock);
    if (ws != AQ_OK)
      break;
  }
  workers_join(&S, &W, 0);
  for (size_t k = 0; k < S.window; k++)
    slot_clear(&S, &S.slots[k]);
  if (c->progress)
    progress(&S, t_start, total, 1);
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
    double t0 = now_s();
    aq_h5_timing tm = {now_s() - t_start, S.read_s, S.process_s, S.run_s,
                       stats.write_s};
    aq_status s = aq_h5_finish(h5, &tm, &oerr); /* frees h5 either way */
    h5 = NULL;
    stats.write_s += now_s() - t0;
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
  if (rc == AQ_EXIT_OK && (stats.runs_failed || stats.records_failed))
    rc = AQ_EXIT_FAIL;
  goto out;

output_failed:
  aq_error_print(&oerr, stderr);
  aq_h5_abort(h5);
  rc = AQ_EXIT_OUTPUT;
out:
  workers_join(&S, &W, 1); /* the outputs failed: stopped before any record */
  for (size_t k = 0; S.slots && k < S.window; k++)
    slot_clear(&S, &S.slots[k]);
  pthread_cond_destroy(&S.cond);
  pthread_cond_destroy(&S.wcond);
  pthread_mutex_destroy(&S.lock);
  aq_journal_close(J); /* kept: --resume continues from it */
  if (S.line)
    fclose(S.line);
  free(S.line_buf);
  stats.wall_s = now_s() - t_start;
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

/* Naming the records reads every file of the suite (and parses those that
 * may hold several channels): 6 ms for the 200 files of the quiet bench
 * suite, before any record ran.  With several threads, each names a
 * contiguous part of at least this many operands. */
#define AQ_SUITE_EXPAND_MIN_PER_THREAD 8

typedef struct {
  char *const *paths;
  size_t n;
  const aq_read_opts *opts;
  char **names;
  size_t nnames;
  aq_status st;
  aq_error err;
} expand_part;

static void expand_part_run(void *ctx, size_t k)
{
  expand_part *p = &((expand_part *)ctx)[k];
  p->st = aq_record_expand(p->paths, p->n, p->opts, &p->names, &p->nnames, &p->err);
}

/* aq_record_expand of paths[0..n), on up to nthreads threads: the same
 * names in the same order. */
static aq_status expand_records(char *const *paths, size_t n, const aq_read_opts *opts,
                                long nthreads, char ***out, size_t *nout, aq_error *err)
{
  size_t T = nthreads > 1 ? (size_t)nthreads : 1;
  if (T > n / AQ_SUITE_EXPAND_MIN_PER_THREAD)
    T = n / AQ_SUITE_EXPAND_MIN_PER_THREAD;
  expand_part *p = T > 1 ? calloc(T, sizeof *p) : NULL;
  if (!p)
    return aq_record_expand(paths, n, opts, out, nout, err);
  for (size_t k = 0; k < T; k++)
    p[k] = (expand_part){paths + n * k / T, n * (k + 1) / T - n * k / T, opts, NULL, 0,
                         AQ_OK, {0}};
  aq_status st = aq_pool_for(T, (long)T, expand_part_run, p, err);
  size_t total = 0;
  for (size_t k = 0; st == AQ_OK && k < T; k++) {
    if (p[k].st != AQ_OK) {
      st = p[k].st;
      *err = p[k].err;
    }
  }
  for (size_t k = 0; k < T; k++)
    total += p[k].nnames;
  char **names = st == AQ_OK ? malloc((total ? total : 1) * sizeof *names) : NULL;
  if (st == AQ_OK && !names)
    st = aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
  size_t m = 0;
  for (size_t k = 0; k < T; k++) {
    if (names) { /* the names move; their array goes */
      memcpy(names + m, p[k].names, p[k].nnames * sizeof *names);
      free(p[k].names);
    } else {
      aq_record_names_free(p[k].names, p[k].nnames);
    }
    m += p[k].nnames;
  }
  free(p);
  *out = names;
  *nout = names ? total : 0;
  return st;
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
  aq_status st = AQ_OK;
  if (!cfg->motions) {
    st = expand_records(cfg->records, cfg->nrecords, &cfg->read, cfg->threads, &names, &n,
                        &err);
  } else { /* plain records expanded one by one, motions kept beside them */
    for (size_t i = 0; st == AQ_OK && i < cfg->nrecords; i++) {
      char **one = NULL;
      size_t k = 1;
      if (cfg->motions[i]) {
        one = malloc(sizeof *one);
        if (one && !(one[0] = strdup(cfg->records[i]))) {
          free(one);
          one = NULL;
        }
        st = one ? AQ_OK : aq_error_set(&err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
      } else {
        st = aq_record_expand(cfg->records + i, 1, &cfg->read, &one, &k, &err);
      }
      char **nn = st == AQ_OK ? realloc(names, (n + k) * sizeof *nn) : NULL;
      const aq_orient_motion **nm = nn ? realloc(mo, (n + k) * sizeof *nm) : NULL;
      if (nn)
        names = nn;
      if (nm)
        mo = nm;
      if (st == AQ_OK && (!nn || !nm)) {
        aq_record_names_free(one, k);
        st = aq_error_set(&err, AQ_ENOMEM, NULL, -1, -1, NULL, "out of memory");
        break;
      }
      for (size_t j = 0; st == AQ_OK && j < k; j++) {
        names[n + j] = one[j];
        mo[n + j] = cfg->motions[i];
      }
      if (st == AQ_OK) {
        free(one);
        n += k;
      }
    }
  }
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
