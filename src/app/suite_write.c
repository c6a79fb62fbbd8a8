/* suite_write.c: the main job's ordered writer (suite_slot.h): each
 * finished record's diagnostics, TSV rows and results-file groups, in
 * record order, and the progress line. */
#define _POSIX_C_SOURCE 200809L
#include "suite_slot.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <time.h>

#include "../arch/arch.h"
#include "../arch/model.h"
#include "../report/h5.h"
#include "../report/text.h"
#include "app.h"
#include "opt.h"
#include "opt_record.h"

/* Progress line refresh period, s. */
#define AQ_SUITE_PROGRESS_PERIOD_S 0.25

void aq_suite_progress(suite *S, double t_start, int final)
{
  size_t total = S->total_runs;
  if (!S->cfg->progress)
    return;
  if (final) {
    fputs("\r\033[K", stderr);
    return;
  }
  size_t done = S->runs_done;
  double el = aq_suite_now_s() - t_start;
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
int aq_suite_has_diagnostics(const rec_slot *r)
{
  if (r->failed || r->subj.warning[0] || r->subj.rec[0].units_conflict[0])
    return 1;
  for (int k = 0; k < 3; k++)
    if (r->subj.have_rec[k] && aq_record_note(&r->subj.rec[k], 0, NULL))
      return 1;
  for (size_t i = 0; r->runs && i < r->nruns; i++)
    if (r->runs[i].failed || r->runs[i].check_failed)
      return 1;
  return 0;
}

/* Write one finished record (report its problems, then its rows).  Returns
 * AQ_OK, or the output failure with *err filled. */
aq_status aq_suite_write_record(suite *S, rec_slot *r, aq_h5_writer *h5,
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
  for (int k = 0; k < 3; k++) /* each component's notes */
    if (sj->have_rec[k])
      aq_record_print_notes(&sj->rec[k], stderr);
  if (!r->runs)
    return AQ_OK;
  for (size_t i = 0; i < r->nruns; i++) {
    run_slot *u = &r->runs[i];
    size_t ai, k, z;
    aq_suite_run_index(S, r, i, &ai, &k, &z);
    int run_failed = u->failed && !r->failed && S->arch_ok[ai];
    if (u->check_failed)
      stats->checks_failed++;
    if (run_failed || u->check_failed) {
      char msg[1200], num[64], az[64] = "";
      aq_error_format(run_failed ? &u->err : &u->check_err, msg, sizeof msg);
      aq_text_double(num, sizeof num, u->sum.scale);
      if (r->motion)
        snprintf(az, sizeof az, ", azimuth %g deg", u->sum.azimuth_deg);
      fprintf(stderr, "archquake: %s: arch %s, scale %s%s%s: %s%s\n", path,
              aq_arch_name(S->arches[ai]), num, aq_suite_reversed(S, k) ? " reversed" : "",
              az, run_failed ? "" : "check blocks: ", msg);
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
    aq_suite_run_index(S, r, i, &ai, &k, &z);
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
aq_status aq_suite_open_h5(suite *S, aq_h5_writer **out, aq_error *err)
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
    aq_arch_dynamics used = aq_job_dynamics(A, c->cor); /* the values the runs use */
    s = aq_h5_write_arch_of(w, a, A, c->arch_paths[a], &used, err);
  }
  if (s != AQ_OK) {
    aq_h5_abort(w);
    return s;
  }
  *out = w;
  return AQ_OK;
}

/* The text header (rows follow in an empty stdio buffer), and with
 * cfg->aligned the table's layout. */
aq_status aq_suite_text_header(suite *S, aq_error *err)
{
  const aq_suite_cfg *c = S->cfg;
  if (c->aligned) {
    size_t rw = 6, aw = 4;
    for (size_t i = 0; i < c->nrecords; i++)
      rw = strlen(c->records[i]) > rw ? strlen(c->records[i]) : rw;
    for (size_t a = 0; a < c->narches; a++)
      aw = strlen(aq_arch_name(S->arches[a])) > aw ? strlen(aq_arch_name(S->arches[a])) : aw;
    aq_text_layout_init(&S->layout, rw < AQ_SUMMARY_RECORD_MAX ? rw : AQ_SUMMARY_RECORD_MAX - 1,
                        aw < AQ_SUMMARY_ARCH_MAX ? aw : AQ_SUMMARY_ARCH_MAX - 1);
  }
  if (c->text && ((c->aligned ? aq_text_header_aligned(c->text, &S->layout)
                              : aq_text_header(c->text)) != 0 ||
                  fflush(c->text) != 0)) /* rows start in an empty buffer */
    return aq_error_set(err, AQ_EIO, "text output", -1, -1, NULL, "cannot write: %s",
                        strerror(errno));
  return AQ_OK;
}

/* Write the records of journal entries e[1..ne) again, in order
 * (diagnostics, rows, results file).  Returns AQ_OK or the output failure. */
aq_status aq_suite_journal_replay(suite *S, aq_h5_writer *h5, aq_suite_stats *stats,
                                  const aq_journal_entry *e, size_t ne, aq_error *err)
{
  for (size_t k = 1; k < ne; k++) {
    rec_slot r;
    memset(&r, 0, sizeof r);
    aq_suite_slot_orient(S, k - 1, &r);
    aq_suite_slot_decode(&e[k], r.nruns, &r); /* checked by aq_suite_journal_start */
    aq_suite_slot_orient(S, k - 1, &r);
    aq_status ws = aq_suite_write_record(S, &r, h5, stats, err);
    aq_suite_slot_clear(S, &r);
    if (ws != AQ_OK)
      return ws;
  }
  return AQ_OK;
}

/* Write in record order as records finish: the writer waits for record i
 * (refreshing the progress line), writes it, journals it and frees its
 * slot for the workers. */
aq_status aq_suite_write_all(suite *S, double t_start, size_t done, aq_h5_writer *h5,
                             aq_journal *J, aq_suite_stats *stats, aq_error *err)
{
  const aq_suite_cfg *c = S->cfg;
  aq_status ws = AQ_OK;
  double last_progress = 0;
  for (size_t i = done; i < c->nrecords; i++) {
    rec_slot *r = &S->slots[i % S->window];
    pthread_mutex_lock(&S->lock);
    while (!(r->state == SLOT_DONE && r->index == i)) {
      if (S->inline_st) { /* -j 1: this thread works (suite.c) */
        if (!aq_suite_work_one(S, S->inline_st)) {
          ws = aq_error_set(err, AQ_EINTERNAL, NULL, -1, -1, NULL,
                            "record %zu is neither done nor to be done", i);
          break;
        }
        if (c->progress && aq_suite_now_s() - last_progress >= AQ_SUITE_PROGRESS_PERIOD_S) {
          aq_suite_progress(S, t_start, 0);
          last_progress = aq_suite_now_s();
        }
        continue;
      }
      struct timespec ts;
      clock_gettime(CLOCK_REALTIME, &ts);
      ts.tv_nsec += (long)(AQ_SUITE_PROGRESS_PERIOD_S * 1e9);
      if (ts.tv_nsec >= 1000000000L) {
        ts.tv_sec++;
        ts.tv_nsec -= 1000000000L;
      }
      pthread_cond_timedwait(&S->wcond, &S->lock, &ts);
      if (c->progress && aq_suite_now_s() - last_progress >= AQ_SUITE_PROGRESS_PERIOD_S) {
        aq_suite_progress(S, t_start, 0);
        last_progress = aq_suite_now_s();
      }
    }
    if (ws != AQ_OK) {
      S->stop = 1;
      pthread_mutex_unlock(&S->lock);
      break;
    }
    rec_slot *next = &S->slots[(i + 1) % S->window]; /* the window holds 2 or more */
    if (!(i + 1 < c->nrecords && next->state == SLOT_DONE && next->index == i + 1))
      next = NULL; /* not done yet: no worker touches a record once it is */
    pthread_mutex_unlock(&S->lock);
    double t0 = aq_suite_now_s();
    /* clear the line before diagnostics, and before rows on the terminal */
    if (c->progress && (c->aligned || aq_suite_has_diagnostics(r)))
      aq_suite_progress(S, t_start, 1);
    aq_suite_record_sha256(S, r, next);
    ws = aq_suite_write_record(S, r, h5, stats, err);
    if (ws == AQ_OK && J) /* the record is done: it survives an interruption */
      ws = aq_suite_journal_append(S, J, r, err);
    if (c->progress && c->aligned && c->text)
      fflush(c->text); /* the rows reach the terminal before the next line */
    stats->write_s += aq_suite_now_s() - t0;
    pthread_mutex_lock(&S->lock);
    aq_suite_slot_clear(S, r);
    S->next_write = i + 1;
    if (ws != AQ_OK)
      S->stop = 1;
    pthread_cond_broadcast(&S->cond); /* room in the window */
    pthread_mutex_unlock(&S->lock);
    if (ws != AQ_OK)
      break;
  }
  return ws;
}
