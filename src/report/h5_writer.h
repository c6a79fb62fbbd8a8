/* h5_writer.h: the inside of the HDF5 results writer (h5.h), shared by its
 * files and by no one else:
 *   h5.c          the file: open, finish (closed, synced, renamed: never a
 *                 partial file), abort
 *   h5_root.c     the root's attributes and the tables each kind holds
 *   h5_write.c    HDF5 failures as aq_error, attributes, 1-D datasets
 *   h5_sync.c     the background sync of the temporary
 *   h5_rows.c     the buffered, extensible tables (/summary, /records)
 *   h5_records.c  /records and /waveforms
 *   h5_runs.c     /summary and /histories
 *   h5_arches.c   /arches and /geometry
 * Helpers return < 0 on failure (HDF5's convention) unless they say
 * otherwise; the writer and everything it holds is freed by h5.c. */
#ifndef AQ_REPORT_H5_WRITER_H
#define AQ_REPORT_H5_WRITER_H

#include <errno.h>
#include <hdf5.h>
#include <pthread.h>

#include "../util/outfile.h"
#include "h5.h"
#include "h5_table.h"

#define AQ_H5_SUMMARY_CHUNK 256 /* rows per chunk of /summary */
#define AQ_H5_RECORDS_CHUNK 64  /* rows per chunk of /records */
/* Values per chunk of a history or waveform dataset (32 KiB of doubles):
 * what the deflate filter compresses at a time (make bench: bench_h5). */
#define AQ_H5_SERIES_CHUNK 4096
/* Dataset bytes written between two background syncs (see
 * aq_h5w_sync_hint). */
#define AQ_H5_SYNC_BYTES ((size_t)8 << 20)
/* The fixed columns of /records (h5_records.c checks the count). */
#define AQ_H5W_RECORD_COLS 41

/* An extensible 1-D compound dataset filled a chunk of rows at a time, so
 * the writer's memory does not grow with the suite.  A row is filled as its
 * struct (row), then packed as the file stores it, every column's bytes
 * side by side (buf), so that a flush hands HDF5 rows of the file's layout:
 * a /summary row is 4.5 KB as a struct (aq_summary holds the record path)
 * and about 540 bytes packed, which is what the conversion buffers then
 * hold. */
typedef struct {
  hid_t d, ft;        /* dataset, packed type (the rows in buf) */
  const aq_h5_col *cols; /* the columns, over the row struct */
  size_t ncols;
  size_t *at;         /* each column's offset in a packed row */
  unsigned char *row; /* the row being filled (rowsize bytes), if open */
  int open;           /* row holds a row not yet packed */
  unsigned char *buf; /* cap packed rows of psize bytes */
  size_t rowsize, psize, cap, nbuf;
  hsize_t nrows;      /* rows already in the dataset */
  size_t owned[4];    /* offsets in the struct of the row's heap strings
                         (freed at each flush) */
  size_t owned_at[4]; /* theirs in a packed row */
  size_t nowned;
} aq_h5w_table;

struct aq_h5_writer {
  aq_outfile out;   /* the temporary, renamed onto the target by aq_h5_finish */
  char *target;     /* = out.target while it is held */
  char *tmp;        /* = out.tmp */
  hid_t file;
  hid_t g_arches, g_waveforms, g_histories; /* each made when first needed */
  aq_h5w_table runs, records;
  aq_h5_col *run_cols; /* aq_summary_fields then the run's own columns */
  size_t n_run_cols;
  /* /records: the fixed columns then the spectral measures of the root's
   * options (made by aq_h5_write_root, which knows them) */
  aq_h5_col rec_cols[AQ_H5W_RECORD_COLS + AQ_IM_SA_MAX + 1];
  char rec_names[AQ_IM_SA_MAX + 1][64];
  size_t n_rec_cols, n_spectral;
  int store_records;
  int no_runs; /* a kind of file without runs (capacity, spectrum): no /summary */
  int deflate; /* deflate level of the series (histories, waveforms), 0: none */
  /* Reused by every attribute (H5Acreate2 copies them): the scalar
   * dataspace, and a string type whose size is set per attribute. */
  hid_t sp_scalar, t_str;
  /* Background sync (h5_sync.c): a descriptor of the temporary opened
   * before anything was written to it (the final fsync uses it too), the
   * dataset bytes written since the last request, and the syncing thread. */
  int sync_fd;
  size_t sync_pending;
  int sync_thread_on;   /* the thread runs */
  int sync_tried;       /* sync_start was called (once) */
  int sync_request;     /* a sync is asked for (under sync_lock) */
  int sync_quit;        /* the thread is to end (under sync_lock) */
  int sync_errno;       /* first failure of a background sync, 0 if none */
  pthread_t sync_thread;
  pthread_mutex_t sync_lock;
  pthread_cond_t sync_cond;
};

/* ---- h5_write.c ---------------------------------------------------------- */

/* Fill err for a failed HDF5 call: what failed, HDF5's innermost
 * description, and errno if set.  Returns AQ_EIO. */
aq_status aq_h5w_fail(aq_error *err, const char *input, const char *object,
                      const char *what, int errno_);

/* Run an HDF5 call; on a negative result record the failure and goto fail
 * (needs aq_status st, const char *obj, aq_h5_writer *w, aq_error *err). */
#define CK(expr, what)                                                   \
  do {                                                                   \
    errno = 0;                                                           \
    if ((expr) < 0) {                                                    \
      st = aq_h5w_fail(err, w->target, obj, what, errno);                \
      goto fail;                                                         \
    }                                                                    \
  } while (0)

/* A string type of size bytes (NUL-terminated), or < 0. */
hid_t aq_h5w_str_type(size_t size);
/* Scalar attributes of loc: a string (fixed length strlen + 1; NULL as ""),
 * a double, an integer (64-bit). */
herr_t aq_h5w_attr_str(aq_h5_writer *w, hid_t loc, const char *name, const char *value);
herr_t aq_h5w_attr_double(aq_h5_writer *w, hid_t loc, const char *name, double v);
herr_t aq_h5w_attr_int(aq_h5_writer *w, hid_t loc, const char *name, int64_t v);
/* An attribute of n doubles. */
herr_t aq_h5w_attr_doubles(hid_t loc, const char *name, const double *v, size_t n);
/* The group under the root named name, made when first needed. */
hid_t aq_h5w_lazy_group(aq_h5_writer *w, hid_t *g, const char *name);
/* A 1-D dataset of n values of mtype, stored as ftype (series: chunked and
 * compressed at the writer's deflate level), with a units attribute and
 * then the nd double attributes dname[k] = dval[k]. */
herr_t aq_h5w_dataset_1d(aq_h5_writer *w, hid_t loc, const char *name, hid_t ftype,
                         hid_t mtype, const void *v, size_t n, const char *units, size_t nd,
                         const char *const *dname, const double *dval, int series);

/* ---- h5_sync.c ----------------------------------------------------------- */

/* bytes of dataset values were written: ask for a background sync once
 * AQ_H5_SYNC_BYTES have been written since the last request (never waits). */
void aq_h5w_sync_hint(aq_h5_writer *w, size_t bytes);
/* End the syncing thread, if any, after the sync under way if any. */
void aq_h5w_sync_stop(aq_h5_writer *w);

/* ---- h5_rows.c ----------------------------------------------------------- */

/* Create the empty, extensible table name with one units_<column>
 * attribute per column, its rows buffered chunk at a time. */
herr_t aq_h5w_table_open(aq_h5_writer *w, aq_h5w_table *T, const char *name,
                         const aq_h5_col *cols, size_t ncols, size_t rowsize, size_t chunk);
/* The next row to fill (zeroed), the last one packed; or NULL if the
 * flush that made room failed. */
void *aq_h5w_table_row(aq_h5_writer *w, aq_h5w_table *T);
/* A copy of s ("" for NULL) for a row's own string, or NULL. */
char *aq_h5w_row_string(const char *s);
/* Flush and close a table. */
herr_t aq_h5w_table_close(aq_h5_writer *w, aq_h5w_table *T);
/* Drop the buffered rows and close the packed type, ignoring failures;
 * then free the table's memory. */
void aq_h5w_table_close_quietly(aq_h5w_table *T);
void aq_h5w_table_free(aq_h5w_table *T);

/* ---- h5_records.c -------------------------------------------------------- */

/* Set up the /records table's own strings (at aq_h5_open). */
void aq_h5w_records_init(aq_h5_writer *w);
/* /records, with a column per spectral measure of proc (NULL: none). */
herr_t aq_h5w_records_open(aq_h5_writer *w, const aq_signal_opts *proc);
/* The name of a detrending (/records detrend and the root's). */
const char *aq_h5w_detrend_name(aq_detrend d);

/* ---- h5_runs.c ----------------------------------------------------------- */

/* The /summary columns (at aq_h5_open); < 0 out of memory. */
int aq_h5w_runs_init(aq_h5_writer *w);
/* /summary, empty. */
herr_t aq_h5w_runs_open(aq_h5_writer *w);

#endif
