/* suite_slot.h: a record in flight in the suite (suite.c), and its
 * encoding as a journal entry (suite_journal.c) so that --resume can write
 * it again without running it.  Private to src/app. */
#ifndef AQ_APP_SUITE_SLOT_H
#define AQ_APP_SUITE_SLOT_H

#include <stddef.h>

#include "../arch/arch.h"
#include "../arch/result.h"
#include "../error.h"
#include "../io/record.h"
#include "../io/sha256.h"
#include "../job/job.h"
#include "../report/journal.h"
#include "../report/report.h"
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
  int want_sha;       /* 1: sha256 still to be computed (suite.c, record_sha256) */
  double *scale;      /* per run slot: the factor before the arch (job/scale.h) */
  aq_runs plan;       /* the step lists its runs share (job/run.h) */
  const aq_orient_motion *motion; /* NULL: a plain in-plane record */
  size_t naz;         /* azimuths per (arch, scale): 1 for a plain record */
  size_t nruns;       /* narch * nscale * naz */
  run_slot *runs;     /* nruns, arch-major, then scale, then azimuth */
  size_t next_run;    /* next run to hand out (READY) */
  size_t runs_done;
} rec_slot;

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
