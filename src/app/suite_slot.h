/* suite_slot.h: the main job's parts (suite.h), private to src/app:
 *
 *   suite.c          the scheduler: arches, worker threads, the window of
 *                    records in flight, the order of writing
 *   suite_record.c   a record in flight: prepared and run through job/
 *                    (subject, scale, runs), its rows' summaries
 *   suite_write.c    the ordered writer: diagnostics, TSV rows, results
 *                    file; a journal's records written again (--resume)
 *   suite_journal.c  the journal (--resume): a record as an entry, the
 *                    suite's identity, starting it, appending to it
 *   suite_farm.c     other processes (farm.h): a task per (record, arch)
 *
 * A record in flight is a rec_slot; the suite's state, a suite. */
#ifndef AQ_APP_SUITE_SLOT_H
#define AQ_APP_SUITE_SLOT_H

#include <pthread.h>
#include <stddef.h>
#include <stdio.h>

#include "../arch/arch.h"
#include "../arch/result.h"
#include "../error.h"
#include "../io/record.h"
#include "../io/sha256.h"
#include "../job/job.h"
#include "../report/journal.h"
#include "../report/h5.h"
#include "../report/report.h"
#include "../report/text.h"
#include "../signal/signal.h"
#include "../signal/steps.h"
#include "../util/bytes.h"
#include "suite.h"

typedef struct {
  aq_summary sum;
  aq_result res;
  int have_res;
  aq_error err;  /* when the run failed */
  int failed;
  aq_error check_err; /* when its --check blocks re-run failed (its row: "failed") */
  int check_failed;
  double run_s;
} run_slot;

enum { SLOT_FREE = 0, SLOT_PREPARING, SLOT_READY, SLOT_DONE };

typedef struct {
  int state;
  size_t index;       /* record index */
  aq_subject subj;    /* read and processed (job/subject.h): metadata, measures,
                       * warning; its samples until its runs are done */
  int failed;         /* record-level failure (read or process) */
  aq_error err;
  char status[AQ_SUMMARY_STATUS_MAX];
  char sha256[AQ_SHA256_HEX]; /* of the file (with -o), "" if unreadable */
  int want_sha;       /* 1: sha256 still to be computed (aq_suite_record_sha256) */
  double *scale;      /* per run slot: the factor before the arch (job/scale.h) */
  aq_runs plan;       /* the step lists its runs share (job/run.h) */
  const aq_orient_motion *motion; /* NULL: a plain in-plane record */
  size_t naz;         /* azimuths per (arch, scale): 1 for a plain record */
  size_t nruns;       /* narch * nscale * naz */
  run_slot *runs;     /* nruns, arch-major, then scale, then azimuth */
  size_t next_run;    /* next run to hand out (READY) */
  size_t runs_done;
} rec_slot;

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
  aq_stepper **inline_st;   /* -j 1: no worker thread; the writer works with
                             * these steppers (one per arch), else NULL */
  size_t runs_done;         /* for the progress line */
  size_t total_runs;        /* of every record */
  double read_s, process_s, run_s;
  double wait_s;            /* the workers', waiting for work or room */
  aq_text_layout layout;    /* with cfg->aligned */
  FILE *line;               /* a row is formatted here first (text_row) */
  char *line_buf;
  size_t line_cap;
} suite;

/* The journal (-o) is synced at most this often, s: a sync per record
 * (about 0.1-1 ms on a disk) bounded -o throughput on quiet suites.  A
 * killed suite loses nothing; an operating-system crash, at most the
 * records finished in this interval (they run again with --resume). */
#define AQ_SUITE_JOURNAL_SYNC_S 1.0

/* suite.c */
/* One piece of work with the steppers st, S->lock held (released while
 * it works): a run, or a record prepared.  Returns 1, or 0 if none was
 * there to do. */
int aq_suite_work_one(suite *S, aq_stepper **st);

/* suite_record.c */

/* A monotonic clock, s. */
double aq_suite_now_s(void);
/* 1 if run slot k (of an arch) runs the record reversed. */
int aq_suite_reversed(const suite *S, size_t k);
/* Run i of record r: arch *ai, scale slot *k, azimuth *z. */
void aq_suite_run_index(const suite *S, const rec_slot *r, size_t i, size_t *ai, size_t *k,
                        size_t *z);
/* Record i's motion (or NULL), azimuths and runs, set in r. */
void aq_suite_slot_orient(const suite *S, size_t i, rec_slot *r);
/* The file whose hash identifies record i: the record, or a motion's H1. */
const char *aq_suite_record_file(const suite *S, size_t i);
/* Free what a finished record's writing does not need; free it all. */
void aq_suite_slot_shed(suite *S, rec_slot *r);
void aq_suite_slot_clear(suite *S, rec_slot *r);
/* Record r's sha256 (and next's, if not NULL), when asked for (-o). */
void aq_suite_record_sha256(const suite *S, rec_slot *r, rec_slot *next);
/* Read, process and prepare record r->index; 1 if its runs can go ahead,
 * 0 if it failed (its runs filled as failed). */
int aq_suite_prepare(suite *S, rec_slot *r);
/* Run i of prepared record r with this thread's steppers st[narches]. */
void aq_suite_run_one(suite *S, rec_slot *r, size_t i, aq_stepper **st);
/* A stepper for arch a with the suite's settings, or NULL (err filled). */
aq_stepper *aq_suite_stepper(const suite *S, size_t a, aq_error *err);
/* Load S's arches, every bad one reported, their lambda0 and whether each
 * can run.  Returns AQ_EXIT_OK, AQ_EXIT_USAGE (nothing may run) or
 * AQ_EXIT_FAIL (an arch cannot run: its runs fail). */
int aq_suite_arches(suite *S);
/* The records of cfg (every channel of a multi-channel file a record of its
 * own, FILE#CH, but the vertical ones of a file given whole) into *names
 * (*n, for aq_record_names_free, also on failure), with cfg->motions each
 * one's motion in *mo (free()d); the lines naming the verticals left out
 * in *notes (*nnotes, for aq_record_names_free). */
aq_status aq_suite_names(const aq_suite_cfg *cfg, char ***names, size_t *n,
                         const aq_orient_motion ***mo, char ***notes, size_t *nnotes,
                         aq_error *err);

/* suite_write.c */

/* The progress line (final: clear it). */
void aq_suite_progress(suite *S, double t_start, int final);
/* 1 if writing r prints something on stderr. */
int aq_suite_has_diagnostics(const rec_slot *r);
/* Write one finished record: its diagnostics, rows and results. */
aq_status aq_suite_write_record(suite *S, rec_slot *r, aq_h5_writer *h5, aq_suite_stats *stats,
                                aq_error *err);
/* Open the results file and write the root and the arches. */
aq_status aq_suite_open_h5(suite *S, aq_h5_writer **out, aq_error *err);
/* The text header (and the aligned layout). */
aq_status aq_suite_text_header(suite *S, aq_error *err);
/* Write the records of journal entries e[1..ne) again, in order. */
aq_status aq_suite_journal_replay(suite *S, aq_h5_writer *h5, aq_suite_stats *stats,
                                  const aq_journal_entry *e, size_t ne, aq_error *err);
/* Write records done..nrecords in order as the workers finish them (and
 * journal them, J not NULL).  Returns AQ_OK or the output failure. */
aq_status aq_suite_write_all(suite *S, double t_start, size_t done, aq_h5_writer *h5,
                             aq_journal *J, aq_suite_stats *stats, aq_error *err);

/* suite_journal.c */

/* Start the journal of a suite with -o (see suite_journal.c). */
int aq_suite_journal_start(suite *S, aq_journal **J, aq_journal_entry **e, size_t *ne);
/* Append finished record r to J. */
aq_status aq_suite_journal_append(suite *S, aq_journal *J, const rec_slot *r, aq_error *err);

/* suite_farm.c */

/* Run the suite's tasks through the farm (see suite_farm.c). */
aq_status aq_suite_farm(suite *S, aq_h5_writer *h5, aq_journal *J, size_t done,
                        aq_suite_stats *stats, aq_error *err);

/* Encode the finished record r (nruns runs) as a journal payload into *b
 * (what writing it needs: metadata, intensity measures, status, messages,
 * summaries and counters; not the samples, steps or histories). */
void aq_suite_slot_encode(const rec_slot *r, size_t nruns, aq_bytes_out *b);

/* Decode a payload into r (zeroed first; free with the suite's slot_clear).
 * Returns 0, or -1 if the payload is not a record of nruns runs. */
int aq_suite_slot_decode(const aq_journal_entry *e, size_t nruns, rec_slot *r);

/* The identity of the suite c with its loaded arches, as text lines
 * ("key=value\n": the build, every option that affects the numbers, each
 * arch's path and sha256, each record's path) into *out (malloc'd).
 * Returns 0, or -1 out of memory. */
int aq_suite_identity(const aq_suite_cfg *c, aq_arch *const *arches, char **out);

#endif
