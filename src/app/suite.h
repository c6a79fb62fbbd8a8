/* suite.h: the main job's loop, records x arches x scales, on threads.
 *
 * Every record is read and processed once by one worker thread, scaled by
 * each factor and split into steps once per factor; its runs (every arch x
 * every factor) are then handed to whichever threads are free, each with its
 * own steppers (one per arch per thread); the arches are loaded once and
 * shared read-only.  At most `window` (2 to 16 x threads, suite.c) records are in flight
 * (read but not yet written), so memory stays bounded whatever the number
 * of records.
 * One writer (the calling thread) writes text rows, HDF5 groups and
 * diagnostics in (record, arch, scale) order, never in completion order, so
 * the output is the same for every number of threads.
 *
 * Diagnostics (one line each) and the progress line go to stderr; this is
 * app code.  The HDF5 temporary is registered with cleanup.h while it
 * exists, so SIGINT/SIGTERM remove it.  The caller owns everything in
 * aq_suite_cfg.
 *
 * With -o (and neither --history nor --store-records) each record written
 * is also appended to a journal beside the target ("<target>.journal",
 * report/journal.h), removed once the results file is complete.  With
 * cfg.resume an existing journal of the same command (same build, options,
 * arches and records, checked line by line) is read back first: its
 * records are written again, in order, from the journal (rows, results
 * file, diagnostics) and the suite continues with the next one, so the
 * outputs equal an uninterrupted run's.  Text rows are written one row per
 * write(2), so an interrupted run leaves only whole rows.
 */
#ifndef AQ_APP_SUITE_H
#define AQ_APP_SUITE_H

#include <stddef.h>
#include <stdio.h>

#include "../arch/stepper.h"
#include "../error.h"
#include "../io/record.h"
#include "../signal/signal.h"
#include "../util/diskcache.h"
#include "opt_orient.h"

typedef struct {
  char **records;          /* record paths as given, or a motion's label */
  size_t nrecords;
  const aq_orient_motion *const *motions; /* NULL, or per record: NULL (a plain
                              in-plane record) or its --components */
  const double *azimuths_deg; /* the arch azimuths run for each motion, deg */
  size_t nazimuth;         /* their number (>= 1) */
  int all_azimuths;        /* 1: every azimuth's row in the TSV, else the worst */
  int vertical;            /* --vertical: run a motion's vertical component */
  char **arch_paths;       /* --arch files */
  size_t narches;
  aq_read_opts read;       /* reader options */
  aq_signal_opts proc;     /* processing options (proc.scale is ignored) */
  double merge_tol_g;      /* --merge-tol, g (0: one step per sample) */
  const double *record_scales; /* --suite: each record's factor, multiplying each
                            * scale (NULL: 1) */
  const double *scales;    /* --scale factors, or NULL with --scale-to-pga */
  size_t nscale;           /* their number */
  double scale_to_pga_g;   /* --scale-to-pga target, g (used when scales is NULL) */
  double scale_to_lambda0; /* --scale-to-lambda0 K (> 0, scales NULL): each run's
                            * record scaled to a PGA of K lambda0 g of its arch
                            * (lambda0 the smaller of its hinge sets'); else 0 */
  aq_model model;          /* --model */
  double blocks_dt_s;      /* --blocks-dt: the block model's step, s */
  int check_blocks;        /* --check blocks: re-run the marked runs under the block model */
  double cor;              /* --cor, or NAN for each arch's own */
  double friction;         /* --friction, or NAN for each arch's own */
  int polarity;            /* --polarity: AQ_POLARITY_NORMAL, _REVERSED or _BOTH (opt.h) */
  int history;             /* --history: keep and write histories */
  int store_records;       /* --store-records: write processed waveforms (with -o) */
  long threads;            /* -j (>= 1) */
  int progress;            /* 1: progress line on stderr */
  const char *h5_path;     /* -o target, or NULL */
  int resume;              /* --resume: continue from h5_path's journal */
  FILE *text;              /* TSV rows go here (NULL: none) */
  int aligned;             /* 1: an aligned table instead of TSV (a terminal) */
  const char *command_line;/* for the results file */
  const char *units_text;  /* --units as given (for the results file), or NULL */
  aq_diskcache *cache;     /* prepared records on disk (--no-cache: NULL) */
  aq_diskcache *arch_cache; /* built arches on disk (--no-cache: NULL) */
} aq_suite_cfg;

/* Record i's own factor (--suite), 1 without a suite. */
static inline double aq_suite_record_factor(const aq_suite_cfg *c, size_t i)
{
  return c->record_scales ? c->record_scales[i] : 1.0;
}

/* Wall-time figures of a finished suite (s).  read/process/run are summed
 * over worker threads; write is the writer's time in the report writers. */
typedef struct {
  size_t runs;           /* rows written */
  size_t runs_failed;    /* rows whose status is not ok */
  size_t records_failed; /* records that could not be read or processed */
  size_t checks_failed;  /* --check blocks re-runs that failed (row: "failed") */
  double wall_s, read_s, process_s, run_s, write_s;
  double wait_s;         /* worker threads' time waiting for a record to
                          * prepare or run (room in the window, the last
                          * records), summed */
} aq_suite_stats;

/* 1 if this process is a follower (it must create no output). */
int aq_suite_is_follower(void);
/* Under archquake-mpi with several ranks (farm.h), rank 0 hands out a
 * task per (record, arch) to the followers and its own threads, and
 * writes each record, in order, once all its arches are in. */
/* 1 under archquake-mpi (any rank): mpirun's pseudo-terminals are not the
 * user's, so output is TSV and there is no progress line. */
int aq_suite_is_remote(void);

/* Run the suite; returns the exit status (app.h): 0 all ran, 1 some record
 * or run failed, or a --check blocks re-run did (each reported on stderr),
 * 2 an arch could not be loaded (nothing ran), 3 the output could not be
 * written (no partial file).  stats may be NULL. */
int aq_suite_run(const aq_suite_cfg *cfg, aq_suite_stats *stats);

#endif
