/* h5.h: the HDF5 results file of a suite (layout: docs/hdf5-layout.md).
 *
 * One writer, used from one thread at a time (the HDF5 library is not
 * entered from anywhere else while it is open).  The file is written under a
 * temporary name beside the target ("<target>.tmp.<pid>") and renamed onto
 * the target only by aq_h5_finish(), after the file is complete, closed
 * (H5Fclose checked) and synced; on any failure, and in aq_h5_abort(), the
 * temporary is removed, so no file is ever left under the target name and an
 * existing target is untouched.  HDF5's automatic error printing is turned
 * off and every HDF5 call is checked; failures are reported through aq_error
 * (input = target path, field = the object being written) with the HDF5
 * library's own description and errno where they say something.
 *
 * Order of calls: aq_h5_open, aq_h5_write_root, aq_h5_write_arch (each arch),
 * then per record aq_h5_write_record followed by its runs (aq_h5_write_run),
 * then aq_h5_finish (or aq_h5_abort at any point).  The writer copies what it
 * needs; callers keep ownership of everything they pass.
 */
#ifndef AQ_REPORT_H5_H
#define AQ_REPORT_H5_H

#include <stddef.h>

#include "../arch/arch.h"
#include "../arch/path.h"
#include "../arch/result.h"
#include "../error.h"
#include "../io/record.h"
#include "../signal/signal.h"
#include "report.h"

#define AQ_H5_FORMAT_VERSION 1 /* root attribute format_version */

typedef struct aq_h5_writer aq_h5_writer;

/* Root: what was run and how. */
typedef struct {
  const char *version;        /* archquake version */
  const char *command_line;   /* argv joined by spaces, shell-quoted where needed */
  const char *created;        /* creation time, ISO-8601 UTC */
  const aq_signal_opts *proc; /* processing options requested */
  double merge_tol_g;         /* --merge-tol, g (0: one step per sample) */
  const char *units;          /* --units as given, or "file" */
  double dt_override_s;       /* --dt, s (0: not given) */
  const char *model;          /* workpath | ode | paper */
  double cor;                 /* --cor, or NAN when each arch's own is used */
  const double *scales;       /* --scale factors (NULL with --scale-to-pga) */
  size_t nscale;              /* their number (1 with --scale-to-pga) */
  double scale_to_pga_g;      /* --scale-to-pga target, g, or NAN */
  int history;                /* 1 with --history */
  long threads;               /* -j */
  const char *polarity;       /* --polarity: normal | reversed | both (NULL: normal) */
} aq_h5_root;

/* One arch as loaded. */
typedef struct {
  const char *name;                /* [arch] name */
  const char *source_file;         /* path as given to --arch */
  const char *config_text;         /* the .cfg exactly as read */
  const aq_arch_dynamics *dyn;     /* [dynamics] */
  const aq_path *set[2];           /* primary, reverse (either may be NULL) */
} aq_h5_arch;

/* One record: what was read, how it was processed and what it measures.
 * rec, proc and im are NULL when the stage did not get that far; rec's
 * sample array is not used (it may have been freed). */
typedef struct {
  const char *source_file;   /* path as given */
  const aq_record *rec;      /* metadata of the record as read, or NULL */
  const aq_processed *proc;  /* processed (unscaled) record, or NULL */
  const aq_im *im;           /* its intensity measures, or NULL */
  const char *status;        /* "ok" or a short code ("read:eformat") */
  const char *error;         /* one-line message, or NULL */
  double timing_read_s;      /* wall time reading, s (timing: not deterministic) */
  double timing_process_s;   /* wall time processing, s */
} aq_h5_record;

/* Open the writer: creates "<target>.tmp.<pid>" (failing clearly if the
 * directory is not writable).  *out is the writer (NULL on failure). */
aq_status aq_h5_open(const char *target, aq_h5_writer **out, aq_error *err);

/* The name aq_h5_open will give the temporary for target (in this process),
 * into buf[n]: a signal handler can know it before the file exists. */
void aq_h5_temp_name(const char *target, char *buf, size_t n);

/* The temporary file's name (for a signal handler that must remove it). */
const char *aq_h5_temp_path(const aq_h5_writer *w);

aq_status aq_h5_write_root(aq_h5_writer *w, const aq_h5_root *r, aq_error *err);

/* Arch number index (0-based, in command-line order). */
aq_status aq_h5_write_arch(aq_h5_writer *w, size_t index, const aq_h5_arch *a,
                           aq_error *err);

/* Record number index (0-based, in command-line order). */
aq_status aq_h5_write_record(aq_h5_writer *w, size_t index,
                             const aq_h5_record *r, aq_error *err);

/* Run (record ri, arch ai, scale si, polarity s->polarity: a reversed run's
 * group name ends in "r"): the summary s as attributes, plus the
 * histories of res if it holds any (res may be NULL for a failed run);
 * error is the run's one-line message or NULL; timing_run_s its wall time. */
aq_status aq_h5_write_run(aq_h5_writer *w, size_t ri, size_t ai, size_t si,
                          const aq_summary *s, const aq_result *res,
                          const char *error, double timing_run_s,
                          aq_error *err);

/* Wall-time shares of the suite, s (root timing_* attributes). */
typedef struct {
  double wall_s, read_s, process_s, run_s, write_s;
} aq_h5_timing;

/* Write the summary table and timings, close, sync and rename onto the
 * target.  Frees w whatever happens; on failure the temporary is removed. */
aq_status aq_h5_finish(aq_h5_writer *w, const aq_h5_timing *t, aq_error *err);

/* Give up: close what is open, remove the temporary, free w (NULL is fine). */
void aq_h5_abort(aq_h5_writer *w);

/* Reading back (compare.c): every run group's summary attributes, in file
 * order.  *out is malloc'd (caller frees), *n its length. */
aq_status aq_h5_read_runs(const char *path, aq_summary **out, size_t *n,
                          aq_error *err);

#endif
