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
 *
 * Records and runs are rows of two compound tables (/records, /summary),
 * buffered and appended a chunk at a time: no object is made per record or
 * run.  Datasets are made only for what is asked: a record's processed
 * waveform (aq_h5_root.store_records) and a run's histories (a result that
 * holds them).
 */
#ifndef AQ_REPORT_H5_H
#define AQ_REPORT_H5_H

#include <stddef.h>
#include <stdint.h>

#include "../arch/arch.h"
#include "../arch/path.h"
#include "../arch/result.h"
#include "../error.h"
#include "../io/record.h"
#include "../signal/signal.h"
#include "report.h"

#define AQ_H5_FORMAT_VERSION 2 /* root attribute format_version */

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
  const char *build;          /* exact build: version and `git describe` */
  int store_records;          /* 1 with --store-records: processed waveforms */
  const char *polarity;       /* --polarity: normal | reversed | both (NULL: normal) */
  double scale_to_lambda0;    /* --scale-to-lambda0 K (scale_mode lambda0), or NAN */
} aq_h5_root;

/* One arch as loaded. */
typedef struct {
  const char *name;                /* [arch] name */
  const char *source_file;         /* path as given to --arch */
  const char *config_text;         /* the .cfg exactly as read */
  const aq_arch_dynamics *dyn;     /* [dynamics] */
  const aq_path *set[2];           /* primary, reverse (either may be NULL) */
  const char *sha256;              /* hex digest of the .cfg file, or NULL */
  int searched;                    /* 1: the primary set came from the search */
  /* Hinge sets as used: joints "0,6,12,19" and faces "eiei" (NULL: unknown) */
  const char *joints[2], *faces[2];
  /* The arch itself, for its generated geometry in /geometry/NNN (joints,
   * voussoirs' mass properties, outlines, fill, point masses:
   * docs/hdf5-layout.md); NULL: not written. */
  const aq_arch *arch;
  /* A joints arch's joints and faces files, as read (NUL-terminated; NULL
   * where there is none): attributes joints_csv, faces_csv. */
  const char *data_text[2];
} aq_h5_arch;

/* Arch number index as loaded: A's name, .cfg text, its joints and faces
 * files' texts, SHA-256 (aq_arch_sha256), hinge sets as used and geometry,
 * with source_file the path as given and used the [dynamics] values the
 * runs used (NULL: the arch's own).  The one way the commands write an
 * arch (the main job, capacity). */
aq_status aq_h5_write_arch_of(aq_h5_writer *w, size_t index, const aq_arch *A,
                              const char *source_file, const aq_arch_dynamics *used,
                              aq_error *err);

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
  const char *sha256;        /* hex digest of the file, or NULL: the writer
                                hashes the file of a record read */
  double timing_read_s;      /* wall time reading, s (timing: not deterministic) */
  double timing_process_s;   /* wall time processing, s */
} aq_h5_record;

/* Open the writer: creates "<target>.tmp.<pid>" (failing clearly if the
 * directory is not writable), registered for removal on a signal
 * (util/outfile.h) until aq_h5_finish renames it or aq_h5_abort removes
 * it.  *out is the writer (NULL on failure). */
aq_status aq_h5_open(const char *target, aq_h5_writer **out, aq_error *err);

/* The temporary file's name (for a signal handler that must remove it). */
const char *aq_h5_temp_path(const aq_h5_writer *w);

aq_status aq_h5_write_root(aq_h5_writer *w, const aq_h5_root *r, aq_error *err);

/* The root of a file that holds no runs, of the given kind ("spectrum":
 * archquake spectrum -o): the attribute kind, version, build, command line,
 * creation time, processing options, units_override and timing_threads of
 * r, none of the run options (merge_tol_g, model, scales ... polarity). */
aq_status aq_h5_write_root_kind(aq_h5_writer *w, const aq_h5_root *r, const char *kind,
                                aq_error *err);

/* Arch number index (0-based, in command-line order). */
aq_status aq_h5_write_arch(aq_h5_writer *w, size_t index, const aq_h5_arch *a,
                           aq_error *err);

/* Record number index (0-based, in command-line order). */
aq_status aq_h5_write_record(aq_h5_writer *w, size_t index,
                             const aq_h5_record *r, aq_error *err);

/* Run (record ri, arch ai, scale si, polarity s->polarity): the summary s as
 * a row of /summary, with the indices, res's counters, error (the run's
 * one-line message or NULL) and timing_run_s (its wall time); plus the
 * histories of res, if it holds any, as datasets of /histories/RRRRR_AAA_SSS
 * (with "r" appended for a reversed run; res may be NULL for a failed run). */
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

/* Series (histories, waveforms) are stored in chunks, byte-shuffled and
 * deflated at this level (zlib's 1..9; docs/hdf5-layout.md, "Compression";
 * chosen by make bench's bench_h5).  aq_h5_set_deflate sets another for
 * this writer's later series (0: stored as they are), for the bench. */
#define AQ_H5_DEFLATE_LEVEL 1
void aq_h5_set_deflate(aq_h5_writer *w, int level);

/* Give up: close what is open, remove the temporary, free w (NULL is fine). */
void aq_h5_abort(aq_h5_writer *w);

/* Reading back (compare.c). */

/* A run as read back: its summary and what identifies its inputs. */
typedef struct {
  aq_summary s;
  int64_t record_index, arch_index, scale_index;
} aq_h5_run;

/* A record or an arch as read back: its short name (a record's file name
 * without directories, an arch's [arch] name) and content digest. */
typedef struct {
  char name[AQ_SUMMARY_RECORD_MAX];
  char sha256[65];
} aq_h5_input;

/* One configuration value of a file's root (processing options, model, cor,
 * version...), as text (numbers as aq_text_double prints them). */
typedef struct {
  char name[48];
  char value[AQ_SUMMARY_RECORD_MAX]; /* whole: one that does not fit is not read */
} aq_h5_setting;

typedef struct {
  aq_h5_run *runs;
  size_t nruns;
  aq_h5_input *records, *arches;
  size_t nrecords, narches;
  aq_h5_setting *settings;
  size_t nsettings;
} aq_h5_suite;

/* Read the runs, the inputs and the root settings of a results file
 * (format_version 2).  *out is filled (free with aq_h5_suite_free). */
aq_status aq_h5_read_suite(const char *path, aq_h5_suite *out, aq_error *err);

/* Scalar number attribute name of loc into *out, as memory type mtype
 * (both hid_t, an int64_t); 0, or -1 if absent or unreadable.  Prints nothing (HDF5's
 * automatic error printing is off in the readers). */
int aq_h5_attr_num(int64_t loc, const char *name, int64_t mtype, void *out);
void aq_h5_suite_free(aq_h5_suite *s);

/* Attributes of an object (loc: its HDF5 id) of the writer's open file:
 * text (NULL as ""), 64-bit integer, double.  0, or -1 when HDF5 failed. */
int aq_h5_attr_text(aq_h5_writer *w, int64_t loc, const char *name, const char *value);
int aq_h5_attr_int(aq_h5_writer *w, int64_t loc, const char *name, int64_t v);
int aq_h5_attr_double(aq_h5_writer *w, int64_t loc, const char *name, double v);

/* The open file's HDF5 id (between aq_h5_open and aq_h5_finish), for the
 * writers of further groups (h5_capacity.c); an hid_t. */
int64_t aq_h5_file_id(const aq_h5_writer *w);

#endif
