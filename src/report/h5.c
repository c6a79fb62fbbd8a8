/* h5.c: the HDF5 results writer (see h5.h and docs/hdf5-layout.md). */
#define _POSIX_C_SOURCE 200809L
#include "h5.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../arch/model.h"
#include "../io/sha256.h"
#include "../util/outfile.h"
#include "h5_table.h"

#define AQ_H5_SUMMARY_CHUNK 256 /* rows per chunk of /summary */
#define AQ_H5_RECORDS_CHUNK 64  /* rows per chunk of /records */
/* Values per chunk of a history or waveform dataset (32 KiB of doubles):
 * what the deflate filter compresses at a time (make bench: bench_h5). */
#define AQ_H5_SERIES_CHUNK 4096
/* Dataset bytes written between two background syncs (see sync_hint). */
#define AQ_H5_SYNC_BYTES ((size_t)8 << 20)

/* ---- the two tables --------------------------------------------------------
 * Column lists (h5_table.h); units "" for strings (each column has its
 * attribute units_<name>). */
typedef aq_h5_col h5_col;

/* A row of /summary: the run's summary (every field of aq_summary_fields, so
 * a field added there is a column here), then what only the file keeps. */
typedef struct {
  aq_summary s;
  int64_t record_index, arch_index, scale_index; /* rows of /records, groups of /arches, --scale */
  int64_t reversals, steps_total, steps_moving, path_evaluations; /* stepper counters */
  double timing_run_s;
  char *error;             /* the run's message, whole (owned: freed at the flush) */
  char *record_text; /* a copy of s.record, the column `record` (a variable-length
                        string; owned: freed at the flush) */
} run_row;

#define RUN_COL(f, kind, units) AQ_H5_COL(run_row, f, kind, units)
static const h5_col run_extra_cols[] = {
    RUN_COL(record_index, AQ_H5_INT, "1"),    RUN_COL(arch_index, AQ_H5_INT, "1"),
    RUN_COL(scale_index, AQ_H5_INT, "1"),     RUN_COL(reversals, AQ_H5_INT, "1"),
    RUN_COL(steps_total, AQ_H5_INT, "1"),     RUN_COL(steps_moving, AQ_H5_INT, "1"),
    RUN_COL(path_evaluations, AQ_H5_INT, "1"), RUN_COL(timing_run_s, AQ_H5_DOUBLE, "s"),
    RUN_COL(error, AQ_H5_VSTR, ""),
};
enum { N_RUN_EXTRA = sizeof run_extra_cols / sizeof run_extra_cols[0] };

/* A row of /records.  A new metadata field of aq_record is one member here,
 * one line in record_cols and one in record_fill. */
typedef struct {
  /* the user's strings, whole (variable-length strings, owned by the row
   * until the flush: see row_strings) */
  char *source_file; /* path as given */
  char *name;        /* file name without directories */
  char sha256[65];   /* of the file's bytes */
  char status[AQ_SUMMARY_STATUS_MAX];
  char *error;
  /* as read */
  char format[16];
  char units_orig[24];
  double to_m_s2;
  char units_stated[24], units_source[12];
  int64_t npts;
  double dt_s, begin_s;
  char reference_time[40];
  char network[16], station[16], location[16], channel[16];
  int64_t vertical; /* 1 vertical, 0 horizontal, -1 not read */
  char vertical_by[8];
  /* processing used */
  char detrend[8];
  int64_t filter;
  double taper_frac, highpass_hz;
  int64_t highpass_order;
  double lowpass_hz;
  int64_t pad_front, pad_back, n_orig;
  /* intensity measures of the processed, unscaled record */
  double pga_g, pgv_m_s, pgd_m, arias_m_s, d5_95_s, cav_m_s, v_end_m_s, d_end_m;
  double pgv_pga_s;
  double sa[AQ_IM_SA_MAX + 1]; /* the spectral measures (aq_im_spectral_value),
                                  columns named by the root's options */
  double timing_read_s, timing_process_s;
  char waveform[40]; /* path of its /waveforms dataset, "" if not stored */
} record_row;

#define REC_COL(f, kind, units) AQ_H5_COL(record_row, f, kind, units)
static const h5_col record_cols[] = {
    REC_COL(source_file, AQ_H5_VSTR, ""), REC_COL(name, AQ_H5_VSTR, ""),
    REC_COL(sha256, AQ_H5_STR, ""),      REC_COL(status, AQ_H5_STR, ""),
    REC_COL(error, AQ_H5_VSTR, ""),       REC_COL(format, AQ_H5_STR, ""),
    REC_COL(units_orig, AQ_H5_STR, ""),  REC_COL(to_m_s2, AQ_H5_DOUBLE, "m/s^2 per file unit"),
    REC_COL(units_stated, AQ_H5_STR, ""), REC_COL(units_source, AQ_H5_STR, ""),
    REC_COL(npts, AQ_H5_INT, "1"),       REC_COL(dt_s, AQ_H5_DOUBLE, "s"),
    REC_COL(begin_s, AQ_H5_DOUBLE, "s"), REC_COL(reference_time, AQ_H5_STR, ""),
    REC_COL(network, AQ_H5_STR, ""),     REC_COL(station, AQ_H5_STR, ""),
    REC_COL(location, AQ_H5_STR, ""),    REC_COL(channel, AQ_H5_STR, ""),
    REC_COL(vertical, AQ_H5_INT, "1"),   REC_COL(vertical_by, AQ_H5_STR, ""),
    REC_COL(detrend, AQ_H5_STR, ""),     REC_COL(filter, AQ_H5_INT, "1"),
    REC_COL(taper_frac, AQ_H5_DOUBLE, "1"), REC_COL(highpass_hz, AQ_H5_DOUBLE, "Hz"),
    REC_COL(highpass_order, AQ_H5_INT, "1"), REC_COL(lowpass_hz, AQ_H5_DOUBLE, "Hz"),
    REC_COL(pad_front, AQ_H5_INT, "1"),  REC_COL(pad_back, AQ_H5_INT, "1"),
    REC_COL(n_orig, AQ_H5_INT, "1"),     REC_COL(pga_g, AQ_H5_DOUBLE, "g"),
    REC_COL(pgv_m_s, AQ_H5_DOUBLE, "m/s"), REC_COL(pgd_m, AQ_H5_DOUBLE, "m"),
    REC_COL(arias_m_s, AQ_H5_DOUBLE, "m/s"), REC_COL(d5_95_s, AQ_H5_DOUBLE, "s"),
    REC_COL(cav_m_s, AQ_H5_DOUBLE, "m/s"), REC_COL(v_end_m_s, AQ_H5_DOUBLE, "m/s"),
    REC_COL(d_end_m, AQ_H5_DOUBLE, "m"), REC_COL(pgv_pga_s, AQ_H5_DOUBLE, "s"),
    REC_COL(timing_read_s, AQ_H5_DOUBLE, "s"),
    REC_COL(timing_process_s, AQ_H5_DOUBLE, "s"), REC_COL(waveform, AQ_H5_STR, ""),
};
enum { N_RECORD_COLS = sizeof record_cols / sizeof record_cols[0] };

/* An extensible 1-D compound dataset filled a chunk of rows at a time, so
 * the writer's memory does not grow with the suite.  A row is filled as its
 * struct (row), then packed as the file stores it, every column's bytes
 * side by side (buf), so that a flush hands HDF5 rows of the file's layout:
 * a /summary row is 4.5 KB as a struct (aq_summary holds the record path)
 * and about 540 bytes packed, which is what the conversion buffers then
 * hold. */
typedef struct {
  hid_t d, ft;        /* dataset, packed type (the rows in buf) */
  const h5_col *cols; /* the columns, over the row struct */
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
} h5_table;

struct aq_h5_writer {
  aq_outfile out;   /* the temporary, renamed onto the target by aq_h5_finish */
  char *target;     /* = out.target while it is held */
  char *tmp;        /* = out.tmp */
  hid_t file;
  hid_t g_arches, g_waveforms, g_histories; /* each made when first needed */
  h5_table runs, records;
  h5_col *run_cols; /* aq_summary_fields then run_extra_cols */
  size_t n_run_cols;
  /* /records: record_cols then the spectral measures of the root's options
   * (made by aq_h5_write_root, which knows them) */
  h5_col rec_cols[N_RECORD_COLS + AQ_IM_SA_MAX + 1];
  char rec_names[AQ_IM_SA_MAX + 1][64];
  size_t n_rec_cols, n_spectral;
  int store_records;
  int no_runs; /* a kind of file without runs (capacity, spectrum): no /summary */
  int deflate; /* deflate level of the series (histories, waveforms), 0: none */
  /* Reused by every attribute (H5Acreate2 copies them): the scalar
   * dataspace, and a string type whose size is set per attribute. */
  hid_t sp_scalar, t_str;
  /* Background sync (see sync_hint): a descriptor of the temporary opened
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

/* ---- error reporting ---------------------------------------------------- */

static herr_t walk_cb(unsigned n, const H5E_error2_t *e, void *data)
{
  char *buf = data;
  if (n == 0 && e->desc && e->desc[0]) { /* innermost: where it started */
    snprintf(buf, 200, "%s", e->desc);
    char *extra = strstr(buf, ": time = "); /* drop the low-level details */
    if (extra)
      *extra = '\0';
  }
  return 0;
}

/* Fill err for a failed HDF5 call: what failed, HDF5's innermost
 * description, and errno if set. */
static aq_status h5_fail(aq_error *err, const char *input, const char *object,
                         const char *what, int errno_)
{
  char desc[200] = "";
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, walk_cb, desc);
  H5Eclear2(H5E_DEFAULT);
  return aq_error_set(err, AQ_EIO, input, -1, -1, object,
                      "HDF5: %s failed%s%s%s%s", what, desc[0] ? ": " : "",
                      desc, errno_ ? ": " : "", errno_ ? strerror(errno_) : "");
}

/* Run an HDF5 call; on a negative result record the failure and goto fail. */
#define CK(expr, what)                                                   \
  do {                                                                   \
    errno = 0;                                                           \
    if ((expr) < 0) {                                                    \
      st = h5_fail(err, w->target, obj, what, errno);                    \
      goto fail;                                                         \
    }                                                                    \
  } while (0)

/* ---- attribute and dataset helpers (return < 0 on failure) -------------- */

static hid_t str_type(size_t size)
{
  hid_t t = H5Tcopy(H5T_C_S1);
  if (t < 0)
    return t;
  if (H5Tset_size(t, size ? size : 1) < 0 ||
      H5Tset_strpad(t, H5T_STR_NULLTERM) < 0) {
    H5Tclose(t);
    return -1;
  }
  return t;
}

/* A scalar string attribute (fixed length strlen + 1, NUL-terminated). */
static herr_t attr_str(aq_h5_writer *w, hid_t loc, const char *name,
                       const char *value)
{
  if (!value)
    value = "";
  if (H5Tset_size(w->t_str, strlen(value) + 1) < 0)
    return -1;
  return aq_h5_attr_write(loc, name, w->t_str, w->sp_scalar, value);
}

static herr_t attr_double(aq_h5_writer *w, hid_t loc, const char *name, double v)
{
  return aq_h5_attr_write(loc, name, H5T_NATIVE_DOUBLE, w->sp_scalar, &v);
}

static herr_t attr_int(aq_h5_writer *w, hid_t loc, const char *name, int64_t v)
{
  return aq_h5_attr_write(loc, name, H5T_NATIVE_INT64, w->sp_scalar, &v);
}

int aq_h5_attr_text(aq_h5_writer *w, int64_t loc, const char *name, const char *value)
{
  return attr_str(w, (hid_t)loc, name, value) < 0 ? -1 : 0;
}

int aq_h5_attr_int(aq_h5_writer *w, int64_t loc, const char *name, int64_t v)
{
  return attr_int(w, (hid_t)loc, name, v) < 0 ? -1 : 0;
}

int aq_h5_attr_double(aq_h5_writer *w, int64_t loc, const char *name, double v)
{
  return attr_double(w, (hid_t)loc, name, v) < 0 ? -1 : 0;
}

static herr_t attr_doubles(hid_t loc, const char *name, const double *v,
                           size_t n)
{
  hsize_t dim = n;
  hid_t s = H5Screate_simple(1, &dim, NULL);
  if (s < 0)
    return -1;
  herr_t rc = aq_h5_attr_write(loc, name, H5T_NATIVE_DOUBLE, s, v);
  if (H5Sclose(s) < 0)
    rc = -1;
  return rc;
}

/* The group under the root named name, made when first needed. */
static hid_t lazy_group(aq_h5_writer *w, hid_t *g, const char *name)
{
  if (*g < 0)
    *g = H5Gcreate2(w->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  return *g;
}

/* ---- background sync ------------------------------------------------------
 * The temporary is fdatasync'ed by a thread of the writer's own while the
 * suite runs, every AQ_H5_SYNC_BYTES of datasets, so that the fsync that
 * aq_h5_finish must do before the rename finds almost everything already on
 * disk (for a 36 MB file: 3 ms instead of 30 ms at the end of the suite,
 * when nothing else is left to run).  The thread only syncs a descriptor: it
 * never enters the HDF5 library.  It starts at the first request, so a
 * file with less than AQ_H5_SYNC_BYTES of datasets (the main job's file for
 * a few hundred runs) never starts one.  The final fsync is unchanged; a
 * failed background sync fails aq_h5_finish (its error is reported to that
 * descriptor only once). */

static void *sync_main(void *arg)
{
  aq_h5_writer *w = arg;
  pthread_mutex_lock(&w->sync_lock);
  for (;;) {
    while (!w->sync_request && !w->sync_quit)
      pthread_cond_wait(&w->sync_cond, &w->sync_lock);
    if (w->sync_quit)
      break;
    w->sync_request = 0;
    pthread_mutex_unlock(&w->sync_lock);
    int e = fdatasync(w->sync_fd) != 0 ? errno : 0;
    pthread_mutex_lock(&w->sync_lock);
    if (e && !w->sync_errno)
      w->sync_errno = e;
  }
  pthread_mutex_unlock(&w->sync_lock);
  return NULL;
}

/* Start the syncing thread (nothing happens if it cannot be started: the
 * final fsync does all the work then). */
static void sync_start(aq_h5_writer *w)
{
  if (w->sync_fd < 0)
    return;
  if (pthread_mutex_init(&w->sync_lock, NULL) != 0)
    return;
  if (pthread_cond_init(&w->sync_cond, NULL) != 0) {
    pthread_mutex_destroy(&w->sync_lock);
    return;
  }
  if (pthread_create(&w->sync_thread, NULL, sync_main, w) != 0) {
    pthread_cond_destroy(&w->sync_cond);
    pthread_mutex_destroy(&w->sync_lock);
    return;
  }
  w->sync_thread_on = 1;
}

/* End the syncing thread, after the sync under way if any. */
static void sync_stop(aq_h5_writer *w)
{
  if (!w->sync_thread_on)
    return;
  pthread_mutex_lock(&w->sync_lock);
  w->sync_quit = 1;
  pthread_cond_signal(&w->sync_cond);
  pthread_mutex_unlock(&w->sync_lock);
  pthread_join(w->sync_thread, NULL);
  pthread_cond_destroy(&w->sync_cond);
  pthread_mutex_destroy(&w->sync_lock);
  w->sync_thread_on = 0;
}

/* bytes of dataset values were written: ask for a background sync once
 * AQ_H5_SYNC_BYTES have been written since the last request, starting the
 * thread at the first (never waits for a sync). */
static void sync_hint(aq_h5_writer *w, size_t bytes)
{
  w->sync_pending += bytes;
  if (w->sync_pending < AQ_H5_SYNC_BYTES)
    return;
  w->sync_pending = 0;
  if (!w->sync_tried) {
    w->sync_tried = 1;
    sync_start(w);
  }
  if (!w->sync_thread_on)
    return;
  pthread_mutex_lock(&w->sync_lock);
  w->sync_request = 1;
  pthread_cond_signal(&w->sync_cond);
  pthread_mutex_unlock(&w->sync_lock);
}

/* The creation properties of a long series of n values (a history, a
 * waveform): chunks of AQ_H5_SERIES_CHUNK values, each byte-shuffled then
 * deflated at the writer's level (docs/hdf5-layout.md, "Compression"); or
 * H5P_DEFAULT (contiguous) when the level is 0, n is 0 or HDF5 has no
 * deflate filter.  Close it with H5Pclose unless H5P_DEFAULT; < 0 on
 * failure. */
static hid_t series_dcpl(const aq_h5_writer *w, size_t n)
{
  if (w->deflate <= 0 || n == 0 || H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0)
    return H5P_DEFAULT;
  hsize_t chunk = n < AQ_H5_SERIES_CHUNK ? n : AQ_H5_SERIES_CHUNK;
  hid_t p = H5Pcreate(H5P_DATASET_CREATE);
  if (p >= 0 && (H5Pset_chunk(p, 1, &chunk) < 0 || H5Pset_shuffle(p) < 0 ||
                 H5Pset_deflate(p, (unsigned)w->deflate) < 0)) {
    H5Pclose(p);
    return -1;
  }
  return p;
}

void aq_h5_set_deflate(aq_h5_writer *w, int level)
{
  w->deflate = level < 0 ? 0 : level > 9 ? 9 : level;
}

/* A 1-D dataset of n values of mtype, stored as ftype (series: chunked and
 * compressed, series_dcpl), with a units attribute and then the nd double
 * attributes dname[k] = dval[k]. */
static herr_t dataset_1d(aq_h5_writer *w, hid_t loc, const char *name,
                         hid_t ftype, hid_t mtype, const void *v, size_t n,
                         const char *units, size_t nd,
                         const char *const *dname, const double *dval, int series)
{
  hsize_t dim = n;
  hid_t dcpl = series ? series_dcpl(w, n) : H5P_DEFAULT;
  if (dcpl < 0)
    return -1;
  hid_t s = H5Screate_simple(1, &dim, NULL);
  hid_t d = s < 0 ? -1 : H5Dcreate2(loc, name, ftype, s, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (dcpl != H5P_DEFAULT)
    H5Pclose(dcpl);
  if (s < 0)
    return -1;
  herr_t rc = d < 0 ? -1 : 0;
  if (rc == 0 && n > 0)
    rc = H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  if (rc == 0)
    sync_hint(w, n * H5Tget_size(ftype));
  if (rc == 0)
    rc = attr_str(w, d, "units", units);
  for (size_t k = 0; rc == 0 && k < nd; k++)
    rc = attr_double(w, d, dname[k], dval[k]);
  if (d >= 0 && H5Dclose(d) < 0)
    rc = -1;
  if (H5Sclose(s) < 0)
    rc = -1;
  return rc;
}

static herr_t dataset_doubles(aq_h5_writer *w, hid_t loc, const char *name, const double *v,
                              size_t n, const char *units)
{
  return dataset_1d(w, loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, v, n,
                    units, 0, NULL, NULL, 1);
}

/* A history of every voussoir (the block model's): n samples x nv
 * voussoirs, v[i * nv + k], chunked and compressed as the series are, with
 * the columns v0 v1 ... and the same units for each. */
static herr_t dataset_voussoirs(aq_h5_writer *w, hid_t loc, const char *name, const double *v,
                                size_t n, size_t nv, const char *units)
{
  hsize_t dim[2] = {n, nv};
  hsize_t rows = AQ_H5_SERIES_CHUNK / nv ? AQ_H5_SERIES_CHUNK / nv : 1;
  hsize_t chunk[2] = {n < rows ? n : rows, nv};
  hid_t dcpl = H5P_DEFAULT;
  if (w->deflate > 0 && n > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    dcpl = H5Pcreate(H5P_DATASET_CREATE);
    if (dcpl < 0 || H5Pset_chunk(dcpl, 2, chunk) < 0 || H5Pset_shuffle(dcpl) < 0 ||
        H5Pset_deflate(dcpl, (unsigned)w->deflate) < 0) {
      if (dcpl >= 0)
        H5Pclose(dcpl);
      return -1;
    }
  }
  char *names = malloc(nv * 24);
  const char **col = malloc(nv * sizeof *col), **un = malloc(nv * sizeof *un);
  hid_t s = H5Screate_simple(2, dim, NULL);
  hid_t d = s < 0 ? -1 : H5Dcreate2(loc, name, H5T_IEEE_F64LE, s, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  herr_t rc = d < 0 || !names || !col || !un ? -1 : 0;
  for (size_t k = 0; rc == 0 && k < nv; k++) {
    snprintf(names + 24 * k, 24, "v%zu", k);
    col[k] = names + 24 * k;
    un[k] = units;
  }
  if (rc == 0 && n > 0)
    rc = H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  if (rc == 0)
    sync_hint(w, n * nv * sizeof(double));
  if (rc == 0)
    rc = aq_h5_attr_strings(d, "columns", col, nv);
  if (rc == 0)
    rc = aq_h5_attr_strings(d, "units", un, nv);
  if (d >= 0 && H5Dclose(d) < 0)
    rc = -1;
  if (s >= 0 && H5Sclose(s) < 0)
    rc = -1;
  if (s < 0)
    rc = -1;
  if (dcpl != H5P_DEFAULT)
    H5Pclose(dcpl);
  free(names);
  free(col);
  free(un);
  return rc;
}

/* ---- tables ------------------------------------------------------------- */

/* The bytes of column c in a row: its member's (a pointer for a
 * variable-length string). */
static size_t col_bytes(const h5_col *c)
{
  return c->kind == AQ_H5_VSTR ? sizeof(const char *) : c->size;
}

/* Create the empty, extensible table name with one units_<column>
 * attribute per column. */
static herr_t table_open(aq_h5_writer *w, h5_table *T, const char *name,
                         const h5_col *cols, size_t ncols, size_t rowsize,
                         size_t chunk)
{
  T->rowsize = rowsize;
  T->cap = chunk;
  T->cols = cols;
  T->ncols = ncols;
  T->row = calloc(1, rowsize);
  T->at = calloc(ncols, sizeof *T->at);
  if (!T->row || !T->at)
    return -1;
  hid_t mt = aq_h5_table_type(cols, ncols, rowsize, &T->ft);
  if (mt < 0 || H5Tclose(mt) < 0)
    return -1;
  T->psize = H5Tget_size(T->ft);
  for (size_t i = 0; i < ncols; i++) {
    int k = H5Tget_member_index(T->ft, cols[i].name);
    if (k < 0)
      return -1;
    T->at[i] = H5Tget_member_offset(T->ft, (unsigned)k);
    for (size_t j = 0; j < T->nowned; j++)
      if (T->owned[j] == cols[i].offset)
        T->owned_at[j] = T->at[i];
  }
  /* every byte of a packed row is a column's, so row_pack writes it all */
  size_t bytes = 0;
  for (size_t i = 0; i < ncols; i++)
    bytes += col_bytes(&cols[i]);
  T->buf = bytes == T->psize ? malloc(chunk * T->psize) : NULL;
  if (!T->psize || !T->buf)
    return -1;
  hsize_t dim = 0, maxdim = H5S_UNLIMITED, ch = chunk;
  hid_t sp = H5Screate_simple(1, &dim, &maxdim);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  herr_t rc = sp < 0 || dcpl < 0 ? -1 : H5Pset_chunk(dcpl, 1, &ch);
  if (rc >= 0) {
    T->d = H5Dcreate2(w->file, name, T->ft, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    rc = T->d < 0 ? -1 : 0;
  }
  if (rc >= 0)
    rc = aq_h5_table_units(T->d, cols, ncols);
  if (dcpl >= 0 && H5Pclose(dcpl) < 0)
    rc = -1;
  if (sp >= 0 && H5Sclose(sp) < 0)
    rc = -1;
  return rc;
}

/* Free the buffered rows' own strings (after a flush, or when giving up),
 * and with all, the open row's. */
static void row_strings_free(h5_table *T, int all)
{
  for (size_t r = 0; T->buf && r < T->nbuf; r++)
    for (size_t k = 0; k < T->nowned; k++) {
      char *p; /* (a packed row's pointers are not aligned) */
      memcpy(&p, T->buf + r * T->psize + T->owned_at[k], sizeof p);
      free(p);
    }
  for (size_t k = 0; all && T->open && k < T->nowned; k++)
    free(*(char **)(void *)(T->row + T->owned[k]));
  if (all)
    T->open = 0;
}

/* Pack the open row into the buffer (which has room). */
static void row_pack(h5_table *T)
{
  unsigned char *p = T->buf + T->nbuf++ * T->psize;
  for (size_t i = 0; i < T->ncols; i++)
    memcpy(p + T->at[i], T->row + T->cols[i].offset, col_bytes(&T->cols[i]));
  T->open = 0;
}

/* A copy of s ("" for NULL) for a row's own string, or NULL. */
static char *row_string(const char *s)
{
  return strdup(s ? s : "");
}

/* Append the buffered rows to the table.  Returns < 0 on failure. */
static herr_t table_flush(aq_h5_writer *w, h5_table *T)
{
  if (T->nbuf == 0)
    return 0;
  hsize_t start = T->nrows, count = T->nbuf, size = T->nrows + T->nbuf;
  if (H5Dset_extent(T->d, &size) < 0)
    return -1;
  hid_t fs = H5Dget_space(T->d);
  if (fs < 0)
    return -1;
  hid_t ms = H5Screate_simple(1, &count, NULL);
  hid_t xfer = aq_h5_xfer(T->d, T->ft, T->nbuf);
  herr_t rc = -1;
  if (ms >= 0 && xfer >= 0 &&
      H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL) >= 0)
    rc = H5Dwrite(T->d, T->ft, ms, fs, xfer, T->buf);
  if (xfer >= 0 && H5Pclose(xfer) < 0)
    rc = -1;
  if (ms >= 0 && H5Sclose(ms) < 0)
    rc = -1;
  if (H5Sclose(fs) < 0)
    rc = -1;
  if (rc >= 0) {
    sync_hint(w, T->nbuf * T->psize);
    row_strings_free(T, 0); /* (a packed row's every byte is a column's) */
    T->nrows += T->nbuf;
    T->nbuf = 0;
  }
  return rc;
}

/* Pack the open row, if any, after a flush if the buffer is full.
 * Returns < 0 if that flush failed. */
static herr_t row_commit(aq_h5_writer *w, h5_table *T)
{
  if (!T->open)
    return 0;
  if (T->nbuf == T->cap && table_flush(w, T) < 0)
    return -1;
  row_pack(T);
  return 0;
}

/* The next row to fill (zeroed), the last one packed; or NULL if the
 * flush that made room failed. */
static void *table_row(aq_h5_writer *w, h5_table *T)
{
  if (row_commit(w, T) < 0)
    return NULL;
  memset(T->row, 0, T->rowsize);
  T->open = 1;
  return T->row;
}

static void table_close_quietly(h5_table *T)
{
  row_strings_free(T, 1);
  T->nbuf = 0;
  if (T->ft >= 0)
    H5Tclose(T->ft);
  T->ft = -1;
}

static void table_free(h5_table *T)
{
  free(T->buf);
  free(T->row);
  free(T->at);
}

/* ---- lifecycle ---------------------------------------------------------- */

static void writer_free(aq_h5_writer *w)
{
  if (!w)
    return;
  sync_stop(w);
  if (w->sync_fd >= 0)
    close(w->sync_fd);
  H5E_BEGIN_TRY
  {
    table_close_quietly(&w->runs);
    table_close_quietly(&w->records);
    if (w->sp_scalar >= 0)
      H5Sclose(w->sp_scalar);
    if (w->t_str >= 0)
      H5Tclose(w->t_str);
  }
  H5E_END_TRY;
  table_free(&w->runs);
  table_free(&w->records);
  free(w->run_cols);
  aq_outfile_release(&w->out);
  free(w);
}

/* Close every open handle, ignoring failures (used on the failure path).
 * A file that cannot be flushed is abandoned, not closed: HDF5 1.10 leaves a
 * dangling identifier behind a failed H5Fclose, which crashes the library
 * when it terminates (hence also H5dont_atexit in aq_h5_open).  The process
 * is about to report the failure; the temporary is unlinked anyway. */
static void close_quietly(aq_h5_writer *w)
{
  H5E_BEGIN_TRY
  {
    table_close_quietly(&w->runs);
    table_close_quietly(&w->records);
    if (w->file >= 0 && H5Fflush(w->file, H5F_SCOPE_LOCAL) >= 0) {
      /* close every object still open in the file, then the file */
      ssize_t n = H5Fget_obj_count(w->file, H5F_OBJ_ALL & ~H5F_OBJ_FILE);
      if (n > 0) {
        hid_t *ids = malloc((size_t)n * sizeof *ids);
        if (ids) {
          ssize_t m = H5Fget_obj_ids(w->file, H5F_OBJ_ALL & ~H5F_OBJ_FILE,
                                     (size_t)n, ids);
          for (ssize_t i = 0; i < m; i++)
            H5Idec_ref(ids[i]);
          free(ids);
        }
      }
      H5Fclose(w->file);
    }
  }
  H5E_END_TRY;
  w->g_arches = w->g_waveforms = w->g_histories = w->file = -1;
  w->runs.d = w->records.d = -1;
}

aq_status aq_h5_open(const char *target, aq_h5_writer **out, aq_error *err)
{
  *out = NULL;
  /* No library shutdown at exit (see close_quietly); must come before the
   * library initialises, and fails harmlessly if it already has. */
  H5dont_atexit();
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  aq_h5_writer *w = calloc(1, sizeof *w);
  if (!w)
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, NULL, "out of memory");
  w->file = w->g_arches = w->g_waveforms = w->g_histories = -1;
  w->runs.d = w->runs.ft = -1;
  w->records.d = w->records.ft = -1;
  w->runs.owned[w->runs.nowned++] = offsetof(run_row, error);
  w->runs.owned[w->runs.nowned++] = offsetof(run_row, record_text);
  w->records.owned[w->records.nowned++] = offsetof(record_row, source_file);
  w->records.owned[w->records.nowned++] = offsetof(record_row, name);
  w->records.owned[w->records.nowned++] = offsetof(record_row, error);
  w->sp_scalar = w->t_str = -1;
  w->sync_fd = -1;
  w->deflate = AQ_H5_DEFLATE_LEVEL;
  w->n_run_cols = aq_summary_nfields + N_RUN_EXTRA;
  w->run_cols = calloc(w->n_run_cols, sizeof *w->run_cols);
  /* named and registered for removal on a signal before it exists */
  if (!w->run_cols || aq_outfile_reserve(&w->out, target, err) != AQ_OK) {
    writer_free(w);
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, NULL, "out of memory");
  }
  w->target = w->out.target;
  w->tmp = w->out.tmp;
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *f = &aq_summary_fields[i];
    aq_h5_kind kind = f->kind == AQ_SF_STR      ? AQ_H5_STR
                      : f->kind == AQ_SF_DOUBLE ? AQ_H5_DOUBLE
                                                : AQ_H5_INT;
    w->run_cols[i] = (h5_col){f->name, kind, offsetof(run_row, s) + f->offset, f->size,
                              aq_summary_units(f)};
    if (strcmp(f->name, "record") == 0) /* whole, not AQ_SUMMARY_RECORD_MAX bytes a row */
      w->run_cols[i] = (h5_col){f->name, AQ_H5_VSTR, offsetof(run_row, record_text),
                                sizeof(const char *), ""};
  }
  memcpy(w->run_cols + aq_summary_nfields, run_extra_cols, sizeof run_extra_cols);
  struct stat sb;
  if (stat(target, &sb) == 0 && S_ISDIR(sb.st_mode)) {
    aq_error_set(err, AQ_EIO, target, -1, -1, NULL,
                 "expected a file name for the results, got a directory");
    writer_free(w);
    return AQ_EIO;
  }
  /* Create the temporary ourselves first, for a clear errno. */
  int fd = open(w->tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
  if (fd < 0) {
    int e = errno;
    aq_error_set(err, AQ_EIO, target, -1, -1, NULL,
                 "cannot create the output file (temporary %s): %s", w->tmp,
                 strerror(e));
    writer_free(w);
    return AQ_EIO;
  }
  close(fd);
  w->sync_fd = open(w->tmp, O_RDONLY); /* -1: no background sync */
  aq_status st = AQ_OK;
  const char *obj = "/";
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  CK(fapl, "H5Pcreate");
  /* 1.8 object format: attributes larger than 64 KiB (long command lines,
   * arch configurations) go to dense storage instead of failing. */
  CK(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST),
     "H5Pset_libver_bounds");
  /* Waveform and history objects leave the metadata cache when closed
   * (written once, never reopened), so the cache holds only the open
   * tables and groups. */
  CK(H5Pset_evict_on_close(fapl, 1), "H5Pset_evict_on_close");
  w->file = H5Fcreate(w->tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  CK(w->file, "H5Fcreate");
  CK(H5Pclose(fapl), "H5Pclose");
  fapl = -1;
  w->sp_scalar = H5Screate(H5S_SCALAR);
  CK(w->sp_scalar, "H5Screate");
  w->t_str = str_type(1);
  CK(w->t_str, "H5Tcopy");
  *out = w; /* /arches and /summary: by aq_h5_write_root_kind, for the kinds that hold them */
  return AQ_OK;
fail:
  if (fapl >= 0)
    H5Pclose(fapl);
  aq_h5_abort(w);
  return st;
}

const char *aq_h5_temp_path(const aq_h5_writer *w)
{
  return w ? w->tmp : NULL;
}

void aq_h5_abort(aq_h5_writer *w)
{
  if (!w)
    return;
  close_quietly(w);
  aq_outfile_abort(&w->out); /* removes the temporary */
  writer_free(w);
}

static const char *detrend_name(aq_detrend d)
{
  switch (d) {
  case AQ_DETREND_MEAN:
    return "mean";
  case AQ_DETREND_LINEAR:
    return "linear";
  case AQ_DETREND_NONE:
    return "none";
  }
  return "unknown";
}

/* How a record was known to be vertical (/records vertical_by). */
static const char *vertical_by_name(int by)
{
  switch (by) {
  case AQ_VERTICAL_BY_STATED:
    return "stated";
  case AQ_VERTICAL_BY_DIP:
    return "dip";
  case AQ_VERTICAL_BY_NAME:
    return "name";
  }
  return "";
}

/* Processing parameters requested (root attributes). */
static herr_t write_proc(aq_h5_writer *w, hid_t loc, const aq_signal_opts *p)
{
  if (attr_str(w, loc, "detrend", detrend_name(p->detrend)) < 0 ||
      attr_int(w, loc, "filter", p->filter ? 1 : 0) < 0 ||
      attr_double(w, loc, "taper_frac", p->filter ? p->taper_frac : 0.0) < 0 ||
      attr_double(w, loc, "highpass_hz", p->filter ? p->highpass_hz : NAN) < 0 ||
      attr_int(w, loc, "highpass_order", p->filter ? p->order : 0) < 0 ||
      attr_double(w, loc, "lowpass_hz",
                  p->filter && p->lowpass_hz > 0 ? p->lowpass_hz : NAN) < 0 ||
      attr_str(w, loc, "peaks", aq_spectrum_peaks_names[p->peaks]) < 0)
    return -1;
  return 0;
}

/* /records, with a column per spectral measure of proc (NULL: none). */
static herr_t records_open(aq_h5_writer *w, const aq_signal_opts *proc)
{
  memcpy(w->rec_cols, record_cols, sizeof record_cols);
  w->n_spectral = proc ? aq_im_spectral_count(proc) : 0;
  for (size_t k = 0; k < w->n_spectral; k++) {
    aq_im_spectral_name(proc, k, w->rec_names[k], sizeof w->rec_names[k]);
    w->rec_cols[N_RECORD_COLS + k] =
        (h5_col){w->rec_names[k], AQ_H5_DOUBLE, offsetof(record_row, sa) + k * sizeof(double),
                 sizeof(double), "g"};
  }
  w->n_rec_cols = N_RECORD_COLS + w->n_spectral;
  return table_open(w, &w->records, "/records", w->rec_cols, w->n_rec_cols,
                    sizeof(record_row), AQ_H5_RECORDS_CHUNK);
}

aq_status aq_h5_write_root(aq_h5_writer *w, const aq_h5_root *r, aq_error *err)
{
  return aq_h5_write_root_kind(w, r, "results", err);
}

aq_status aq_h5_write_root_kind(aq_h5_writer *w, const aq_h5_root *r, const char *kind,
                                aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/records";
  hid_t f = w->file;
  if (!w->records.buf)
    CK(records_open(w, r->proc), "table");
  obj = "/";
  w->store_records = r->store_records;
  CK(attr_str(w, f, "archquake_version", r->version), "root attributes");
  CK(attr_str(w, f, "archquake_build", r->build ? r->build : r->version),
     "root attributes");
  CK(attr_int(w, f, "format_version", AQ_H5_FORMAT_VERSION), "root attributes");
  CK(attr_str(w, f, "command_line", r->command_line), "root attributes");
  CK(attr_str(w, f, "created", r->created), "root attributes");
  if (r->proc)
    CK(write_proc(w, f, r->proc), "root attributes");
  kind = kind ? kind : "results";
  int results = strcmp(kind, "results") == 0, capacity = strcmp(kind, "capacity") == 0;
  CK(attr_str(w, f, "kind", kind), "root attributes");
  if (results || capacity) { /* the files with arches */
    obj = "/arches";
    CK(lazy_group(w, &w->g_arches, obj), "H5Gcreate");
  }
  w->no_runs = !results;
  if (results && !w->runs.buf) { /* and with runs */
    obj = "/summary";
    CK(table_open(w, &w->runs, obj, w->run_cols, w->n_run_cols, sizeof(run_row),
                  AQ_H5_SUMMARY_CHUNK),
       "table");
  }
  obj = "/";
  if (!results && !capacity) { /* no runs: only what applies */
    CK(attr_str(w, f, "units_override", r->units ? r->units : "file"), "root attributes");
    CK(attr_int(w, f, "timing_threads", r->threads), "root attributes");
    return AQ_OK;
  }
  CK(attr_double(w, f, "merge_tol_g", r->merge_tol_g), "root attributes");
  CK(attr_str(w, f, "units_override", r->units ? r->units : "file"),
     "root attributes");
  CK(attr_double(w, f, "dt_override_s", r->dt_override_s > 0 ? r->dt_override_s : NAN),
     "root attributes");
  CK(attr_str(w, f, "model", r->model), "root attributes");
  CK(attr_double(w, f, "cor", r->cor), "root attributes");
  if (capacity) { /* the scales are the search's (capacity attributes), no histories */
    CK(attr_str(w, f, "polarity", r->polarity ? r->polarity : "normal"), "root attributes");
    CK(attr_int(w, f, "timing_threads", r->threads), "root attributes");
    return AQ_OK;
  }
  if (r->scales) {
    CK(attr_str(w, f, "scale_mode", "list"), "root attributes");
    CK(attr_doubles(f, "scales", r->scales, r->nscale), "root attributes");
  } else {
    CK(attr_str(w, f, "scale_mode", r->scale_to_lambda0 > 0 ? "lambda0" : "pga"),
       "root attributes");
  }
  CK(attr_double(w, f, "scale_to_lambda0", r->scale_to_lambda0 > 0 ? r->scale_to_lambda0 : NAN),
     "root attributes");
  CK(attr_double(w, f, "scale_to_pga_g", r->scale_to_pga_g), "root attributes");
  CK(attr_int(w, f, "history", r->history ? 1 : 0), "root attributes");
  CK(attr_int(w, f, "store_records", r->store_records ? 1 : 0), "root attributes");
  CK(attr_str(w, f, "polarity", r->polarity ? r->polarity : "normal"), "root attributes");
  CK(attr_int(w, f, "timing_threads", r->threads), "root attributes");
  return AQ_OK;
fail:
  return st;
}

static const char *impact_name(aq_impact i)
{
  return i == AQ_IMPACT_MOMENTUM ? "momentum" : "cor";
}

/* A rows x cols table of doubles with its columns' names and units, one
 * string per column (attributes columns and units, as in /capacity). */
static herr_t dataset_2d(aq_h5_writer *w, hid_t loc, const char *name, const double *v,
                         size_t rows, size_t cols, const char *const *units,
                         const char *const *columns)
{
  hsize_t dim[2] = {rows, cols};
  hid_t s = H5Screate_simple(cols > 1 ? 2 : 1, dim, NULL);
  if (s < 0)
    return -1;
  hid_t d = H5Dcreate2(loc, name, H5T_IEEE_F64LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t rc = d < 0 ? -1 : 0;
  if (rc == 0 && rows > 0)
    rc = H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
  if (rc == 0)
    sync_hint(w, rows * cols * sizeof(double));
  if (rc == 0)
    rc = aq_h5_attr_strings(d, "columns", columns, cols);
  if (rc == 0)
    rc = aq_h5_attr_strings(d, "units", units, cols);
  if (d >= 0 && H5Dclose(d) < 0)
    rc = -1;
  if (H5Sclose(s) < 0)
    rc = -1;
  return rc;
}

/* /geometry/NNN: arch NNN's generated geometry (docs/hdf5-layout.md), so
 * that a result can be drawn again without its .cfg. */
static aq_status write_geometry(aq_h5_writer *w, size_t index, const aq_h5_arch *a,
                                aq_error *err)
{
  aq_status st = AQ_OK;
  char obj[64];
  snprintf(obj, sizeof obj, "/geometry/%03zu", index);
  aq_arch_drawing d;
  aq_arch_drawing_of(a->arch, &d);
  size_t n = d.voussoirs;
  /* the point masses as a table: the voussoir an integer, as every index */
  typedef struct {
    int64_t voussoir;
    double x_m, y_m, mass_kg;
  } mass_row;
  static const aq_h5_col mass_cols[] = {
      AQ_H5_COL(mass_row, voussoir, AQ_H5_INT, "1"), AQ_H5_COL(mass_row, x_m, AQ_H5_DOUBLE, "m"),
      AQ_H5_COL(mass_row, y_m, AQ_H5_DOUBLE, "m"),
      AQ_H5_COL(mass_row, mass_kg, AQ_H5_DOUBLE, "kg")};
  mass_row *masses = malloc((d.nmass ? d.nmass : 1) * sizeof *masses);
  hid_t lcpl = H5Pcreate(H5P_LINK_CREATE), g = -1;
  if (!masses) {
    st = aq_error_set(err, AQ_ENOMEM, w->target, -1, -1, obj, "out of memory");
    goto fail;
  }
  for (size_t i = 0; i < d.nmass; i++)
    masses[i] = (mass_row){(int64_t)d.mass[4 * i], d.mass[4 * i + 1], d.mass[4 * i + 2],
                           d.mass[4 * i + 3]};
  CK(lcpl, "H5Pcreate");
  CK(H5Pset_create_intermediate_group(lcpl, 1), "H5Pset_create_intermediate_group");
  g = H5Gcreate2(w->file, obj, lcpl, H5P_DEFAULT, H5P_DEFAULT);
  CK(g, "H5Gcreate");
  CK(attr_str(w, g, "name", a->name), "geometry attributes");
  CK(attr_str(w, g, "shape", d.shape), "geometry attributes");
  CK(attr_int(w, g, "voussoirs", (int64_t)n), "geometry attributes");
  CK(attr_double(w, g, "masonry_kg", d.stone_kg), "geometry attributes");
  CK(attr_double(w, g, "fill_kg", d.fill_kg), "geometry attributes");
  CK(attr_double(w, g, "point_masses_kg", d.point_kg), "geometry attributes");
  static const char *const m4[4] = {"m", "m", "m", "m"}, *const xy[2] = {"x_m", "y_m"},
                           *const jc[4] = {"xi_m", "yi_m", "xe_m", "ye_m"},
                           *const vc[4] = {"mass_kg", "x_m", "y_m", "inertia_kgm2"},
                           *const vu[4] = {"kg", "m", "m", "kg m^2"};
  CK(dataset_2d(w, g, "joints", d.joints, n + 1, 4, m4, jc), "joints");
  CK(dataset_2d(w, g, "voussoirs", d.parts, n, 4, vu, vc), "voussoirs");
  CK(dataset_2d(w, g, "outline", d.outline, d.noutline, 2, m4, xy), "outline");
  CK(dataset_1d(w, g, "outline_start", H5T_STD_I64LE, H5T_NATIVE_INT64, d.outline_start, n + 1,
                "1", 0, NULL, NULL, 0),
     "outline_start");
  CK(dataset_2d(w, g, "fill", d.fill, d.nfill, 2, m4, xy), "fill");
  CK(dataset_1d(w, g, "fill_start", H5T_STD_I64LE, H5T_NATIVE_INT64, d.fill_start, n + 1, "1",
                0, NULL, NULL, 0),
     "fill_start");
  CK(aq_h5_table_write(g, "masses", mass_cols, sizeof mass_cols / sizeof mass_cols[0],
                       sizeof(mass_row), masses, d.nmass, NULL),
     "masses");
fail:
  free(masses);
  if (g >= 0 && H5Gclose(g) < 0 && st == AQ_OK)
    st = h5_fail(err, w->target, obj, "H5Gclose", errno);
  if (lcpl >= 0)
    H5Pclose(lcpl);
  return st;
}

aq_status aq_h5_write_arch(aq_h5_writer *w, size_t index, const aq_h5_arch *a,
                           aq_error *err)
{
  aq_status st = AQ_OK;
  char obj[64];
  hid_t g = -1;
  snprintf(obj, sizeof obj, "/arches/%03zu", index);
  CK(lazy_group(w, &w->g_arches, "/arches"), "H5Gcreate");
  g = H5Gcreate2(w->file, obj, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  CK(g, "H5Gcreate");
  CK(attr_str(w, g, "name", a->name), "arch attributes");
  CK(attr_str(w, g, "source_file", a->source_file), "arch attributes");
  CK(attr_str(w, g, "sha256", a->sha256), "arch attributes");
  CK(attr_str(w, g, "config", a->config_text), "arch attributes");
  static const char *const data_name[2] = {"joints_csv", "faces_csv"};
  for (int k = 0; k < 2; k++) /* a joints arch's files, as read (in sha256) */
    if (a->data_text[k])
      CK(attr_str(w, g, data_name[k], a->data_text[k]), "arch attributes");
  CK(attr_int(w, g, "searched", a->searched ? 1 : 0), "arch attributes");
  if (a->arch) {
    CK(attr_str(w, g, "control", aq_hinge_control_names[aq_arch_control(a->arch)]),
       "arch attributes");
    CK(attr_double(w, g, "friction", aq_arch_friction(a->arch)), "arch attributes");
    size_t jr;
    CK(attr_double(w, g, "mu_rest", aq_arch_mu_rest(a->arch, &jr)), "arch attributes");
    CK(attr_int(w, g, "mu_rest_joint", (int64_t)jr), "arch attributes");
  }
  if (a->dyn) {
    CK(attr_double(w, g, "cor", a->dyn->cor), "arch attributes");
    CK(attr_str(w, g, "impact", impact_name(a->dyn->impact)), "arch attributes");
    CK(attr_double(w, g, "g_mps2", a->dyn->g_mps2), "arch attributes");
  }
  static const char *const set_name[2] = {"primary", "reverse"};
  for (int k = 0; k < 2; k++) {
    const aq_path *p = a->set[k];
    char nm[64];
    snprintf(nm, sizeof nm, "%s_joints", set_name[k]);
    CK(attr_str(w, g, nm, a->joints[k]), "arch attributes");
    snprintf(nm, sizeof nm, "%s_faces", set_name[k]);
    CK(attr_str(w, g, nm, a->faces[k]), "arch attributes");
    snprintf(nm, sizeof nm, "%s_act_sign", set_name[k]);
    CK(attr_int(w, g, nm, p ? p->act_sign : 0), "arch attributes");
    snprintf(nm, sizeof nm, "%s_q_sign", set_name[k]);
    CK(attr_int(w, g, nm, p ? p->q_sign : 0), "arch attributes");
    snprintf(nm, sizeof nm, "%s_admissible", set_name[k]);
    CK(attr_int(w, g, nm, p && p->admissible ? 1 : 0), "arch attributes");
    snprintf(nm, sizeof nm, "%s_lambda0", set_name[k]);
    CK(attr_double(w, g, nm, p ? p->lambda0 : NAN), "arch attributes");
    snprintf(nm, sizeof nm, "%s_q_c_rad", set_name[k]);
    CK(attr_double(w, g, nm, p ? p->s_c_rad : NAN), "arch attributes");
    snprintf(nm, sizeof nm, "%s_mass_kg", set_name[k]);
    CK(attr_double(w, g, nm, p ? p->mass_kg : NAN), "arch attributes");
    if (a->arch && p) { /* its collapse state's friction, and the load with the arch's */
      size_t mj;
      double mu = aq_arch_joint_friction(a->arch, k, NULL, &mj);
      snprintf(nm, sizeof nm, "%s_mu_required", set_name[k]);
      CK(attr_double(w, g, nm, mu), "arch attributes");
      snprintf(nm, sizeof nm, "%s_mu_joint", set_name[k]);
      CK(attr_int(w, g, nm, mj == SIZE_MAX ? -1 : (int64_t)mj), "arch attributes");
      snprintf(nm, sizeof nm, "%s_lambda_friction", set_name[k]);
      CK(attr_double(w, g, nm,
                     aq_arch_lambda_friction(a->arch, p->act_sign, aq_arch_friction(a->arch))),
         "arch attributes");
    }
  }
  CK(H5Gclose(g), "H5Gclose");
  g = -1;
  if (a->arch)
    return write_geometry(w, index, a, err);
  return AQ_OK;
fail:
  if (g >= 0)
    H5E_BEGIN_TRY { H5Gclose(g); } H5E_END_TRY;
  return st;
}

aq_status aq_h5_write_arch_of(aq_h5_writer *w, size_t index, const aq_arch *A,
                              const char *source_file, const aq_arch_dynamics *used,
                              aq_error *err)
{
  char sha[65], joints[2][64], faces[2][8];
  aq_arch_sources src;
  aq_arch_sha256(A, sha); /* the .cfg's bytes as read, and a joints arch's files' */
  aq_arch_sources_of(A, &src);
  for (int k = 0; k < 2; k++)
    aq_hinge_set_format(aq_arch_hinge_set(A, k), joints[k], sizeof joints[k], faces[k],
                        sizeof faces[k]);
  aq_h5_arch ha = {.name = aq_arch_name(A),
                   .source_file = source_file,
                   .config_text = aq_arch_config_text(A),
                   .dyn = used ? used : aq_arch_dynamics_of(A),
                   .set = {aq_arch_path(A, 0), aq_arch_path(A, 1)},
                   .sha256 = sha,
                   .searched = aq_arch_searched(A),
                   .joints = {joints[0], joints[1]},
                   .faces = {faces[0], faces[1]},
                   .arch = A,
                   .data_text = {src.data[0], src.data[1]}};
  return aq_h5_write_arch(w, index, &ha, err);
}

#define COPY(dst, src) snprintf((dst), sizeof(dst), "%s", (src) ? (src) : "")

aq_status aq_h5_write_record(aq_h5_writer *w, size_t index,
                             const aq_h5_record *r, aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/records";
  if (!w->records.buf) /* no root written: the fixed columns */
    CK(records_open(w, NULL), "table");
  record_row *row = table_row(w, &w->records);
  CK(row ? 0 : -1, "rows");
  const char *base = r->source_file ? strrchr(r->source_file, '/') : NULL;
  row->source_file = row_string(r->source_file);
  row->error = row_string(r->error);
  row->name = row_string(r->rec ? r->rec->name : base ? base + 1 : r->source_file);
  CK(row->source_file && row->error && row->name ? 0 : -1, "rows (out of memory)");
  COPY(row->sha256, r->sha256);
  if (!r->sha256 && r->rec && r->source_file) { /* a command that did not hash it
                                                   (capacity, spectrum): its file's */
    char file[4096];
    aq_error herr;
    if (aq_sha256_file(aq_record_file(r->source_file, file, sizeof file), row->sha256,
                       &herr) != AQ_OK)
      row->sha256[0] = '\0';
  }
  COPY(row->status, r->status ? r->status : "ok");
  row->to_m_s2 = row->dt_s = row->begin_s = NAN;
  row->taper_frac = row->highpass_hz = row->lowpass_hz = NAN;
  row->pga_g = row->pgv_m_s = row->pgd_m = row->arias_m_s = NAN;
  row->d5_95_s = row->cav_m_s = row->v_end_m_s = row->d_end_m = NAN;
  row->vertical = -1;
  row->pgv_pga_s = NAN;
  for (size_t k = 0; k < w->n_spectral; k++)
    row->sa[k] = NAN;
  if (r->rec) {
    const aq_record *rec = r->rec;
    COPY(row->format, rec->format);
    COPY(row->units_orig, rec->units_orig);
    row->to_m_s2 = rec->to_mps2;
    row->npts = (int64_t)rec->npts;
    row->dt_s = rec->dt_s;
    row->begin_s = rec->begin_s;
    COPY(row->reference_time, rec->reference);
    COPY(row->network, rec->network);
    COPY(row->station, rec->station);
    COPY(row->location, rec->location);
    COPY(row->channel, rec->channel);
    COPY(row->units_stated, rec->units_stated);
    COPY(row->units_source, rec->units_by);
    row->vertical = rec->vertical ? 1 : 0;
    COPY(row->vertical_by, vertical_by_name(rec->vertical_by));
  }
  if (r->proc) {
    const aq_processed *p = r->proc;
    const aq_signal_opts *u = &p->used;
    COPY(row->detrend, detrend_name(u->detrend));
    row->filter = u->filter ? 1 : 0;
    row->taper_frac = u->filter ? u->taper_frac : 0.0;
    row->highpass_hz = u->filter ? u->highpass_hz : NAN;
    row->highpass_order = u->filter ? u->order : 0;
    row->lowpass_hz = u->filter && u->lowpass_hz > 0 ? u->lowpass_hz : NAN;
    row->pad_front = (int64_t)p->pad_front;
    row->pad_back = (int64_t)p->pad_back;
    row->n_orig = (int64_t)p->n_orig;
    if (w->store_records) {
      char name[32];
      snprintf(name, sizeof name, "/waveforms/%05zu", index);
      static const char *const time_attr[2] = {"dt_s", "t0_s"};
      const double time_val[2] = {p->dt_s, -(double)p->pad_front * p->dt_s};
      obj = "/waveforms";
      CK(lazy_group(w, &w->g_waveforms, obj), "H5Gcreate");
      obj = "acceleration";
      CK(dataset_1d(w, w->file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                    p->acc_mps2, p->n, "m/s^2", 2, time_attr, time_val, 1),
         name);
      snprintf(row->waveform, sizeof row->waveform, "%s", name);
    }
  }
  if (r->im) {
    const aq_im *m = r->im;
    row->pga_g = m->pga_g;
    row->pgv_m_s = m->pgv_mps;
    row->pgd_m = m->pgd_m;
    row->arias_m_s = m->arias_mps;
    row->d5_95_s = m->d5_95_s;
    row->cav_m_s = m->cav_mps;
    row->v_end_m_s = m->v_end_mps;
    row->d_end_m = m->d_end_m;
    row->pgv_pga_s = m->pgv_pga_s;
    for (size_t k = 0; k < w->n_spectral; k++)
      row->sa[k] = aq_im_spectral_value(m, k);
  }
  row->timing_read_s = r->timing_read_s;
  row->timing_process_s = r->timing_process_s;
  return AQ_OK;
fail:
  return st;
}

aq_status aq_h5_write_run(aq_h5_writer *w, size_t ri, size_t ai, size_t si,
                          const aq_summary *s, const aq_result *res,
                          const char *error, double timing_run_s,
                          aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/summary";
  hid_t g = -1;
  if (w->no_runs)
    return aq_error_set(err, AQ_EINTERNAL, w->target, -1, -1, obj,
                        "a run written to a file of another kind than results");
  if (!w->runs.buf) /* no root written: a results file */
    CK(table_open(w, &w->runs, obj, w->run_cols, w->n_run_cols, sizeof(run_row),
                  AQ_H5_SUMMARY_CHUNK),
       "table");
  run_row *row = table_row(w, &w->runs);
  CK(row ? 0 : -1, "rows");
  row->s = *s;
  row->record_index = (int64_t)ri;
  row->arch_index = (int64_t)ai;
  row->scale_index = (int64_t)si;
  row->timing_run_s = timing_run_s;
  row->record_text = row_string(row->s.record);
  row->error = row_string(error);
  CK(row->record_text && row->error ? 0 : -1, "rows (out of memory)");
  if (!res)
    return AQ_OK;
  row->reversals = (int64_t)res->reversals;
  row->steps_total = (int64_t)res->steps_total;
  row->steps_moving = (int64_t)res->steps_moving;
  row->path_evaluations = (int64_t)res->evals;
  const aq_history *h = &res->history;
  if (!h->time_s)
    return AQ_OK;
  char name[128], az[32] = ""; /* runs of one scale at several azimuths */
  if (isfinite(s->azimuth_deg))
    snprintf(az, sizeof az, "_az%.6g", s->azimuth_deg);
  snprintf(name, sizeof name, "/histories/%05zu_%03zu_%03zu%s%s", ri, ai, si,
           strcmp(s->polarity, "reversed") == 0 ? "r" : "", az);
  obj = "/histories";
  CK(lazy_group(w, &w->g_histories, obj), "H5Gcreate");
  obj = name;
  g = H5Gcreate2(w->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  CK(g, "H5Gcreate");
  CK(dataset_doubles(w, g, "time_s", h->time_s, h->n, "s"), "time_s");
  CK(dataset_doubles(w, g, "rotation_rad", h->rotation_rad, h->n, "rad"),
     "rotation_rad");
  CK(dataset_doubles(w, g, "displacement_m", h->displacement_m, h->n, "m"),
     "displacement_m");
  CK(dataset_doubles(w, g, "kinetic_energy_j", h->kinetic_energy_j, h->n, "J"),
     "kinetic_energy_j");
  CK(dataset_doubles(w, g, "potential_energy_j", h->potential_energy_j, h->n, "J"),
     "potential_energy_j");
  if (h->set) /* 64-bit in the file, as every integer */
    CK(dataset_1d(w, g, "hinge_set", H5T_STD_I64LE, H5T_NATIVE_INT, h->set, h->n,
                  "1 (0 primary, 1 reverse, -1 at rest)", 0, NULL, NULL, 1),
       "hinge_set");
  const aq_result_bodies *B = res->bodies;
  if (B && B->hist_x_m && B->nvous > 0) { /* the block model's: every voussoir */
    CK(dataset_voussoirs(w, g, "voussoir_x_m", B->hist_x_m, h->n, B->nvous, "m"),
       "voussoir_x_m");
    CK(dataset_voussoirs(w, g, "voussoir_y_m", B->hist_y_m, h->n, B->nvous, "m"),
       "voussoir_y_m");
    CK(dataset_voussoirs(w, g, "voussoir_rotation_rad", B->hist_rot_rad, h->n, B->nvous,
                         "rad"),
       "voussoir_rotation_rad");
  }
  CK(H5Gclose(g), "H5Gclose");
  return AQ_OK;
fail:
  if (g >= 0)
    H5E_BEGIN_TRY { H5Gclose(g); } H5E_END_TRY;
  return st;
}

/* Flush and close a table. */
static herr_t table_close(aq_h5_writer *w, h5_table *T)
{
  herr_t rc = row_commit(w, T) < 0 ? -1 : table_flush(w, T);
  if (rc >= 0 && H5Dclose(T->d) < 0)
    rc = -1;
  if (rc >= 0)
    T->d = -1;
  if (rc >= 0 && H5Tclose(T->ft) < 0)
    rc = -1;
  if (rc >= 0)
    T->ft = -1;
  return rc;
}

aq_status aq_h5_finish(aq_h5_writer *w, const aq_h5_timing *t, aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/summary";
  if (w->runs.buf) /* a results file's */
    CK(table_close(w, &w->runs), "rows");
  obj = "/records";
  if (!w->records.buf)
    CK(records_open(w, NULL), "table");
  CK(table_close(w, &w->records), "rows");
  obj = "/";
  if (t) {
    CK(attr_double(w, w->file, "timing_wall_s", t->wall_s), "root attributes");
    CK(attr_double(w, w->file, "timing_read_s", t->read_s), "root attributes");
    CK(attr_double(w, w->file, "timing_process_s", t->process_s),
       "root attributes");
    CK(attr_double(w, w->file, "timing_run_s", t->run_s), "root attributes");
    CK(attr_double(w, w->file, "timing_write_s", t->write_s), "root attributes");
  }
  if (w->g_arches >= 0)
    CK(H5Gclose(w->g_arches), "H5Gclose");
  w->g_arches = -1;
  if (w->g_waveforms >= 0)
    CK(H5Gclose(w->g_waveforms), "H5Gclose");
  w->g_waveforms = -1;
  if (w->g_histories >= 0)
    CK(H5Gclose(w->g_histories), "H5Gclose");
  w->g_histories = -1;
  {
    /* Flush first: a file that cannot be flushed is abandoned, never
     * closed (see close_quietly). */
    errno = 0;
    if (H5Fflush(w->file, H5F_SCOPE_LOCAL) < 0) {
      int e = errno;
      st = h5_fail(err, w->target, obj, "H5Fflush (writing the file)", e);
      w->file = -1;
      goto fail;
    }
    hid_t f = w->file;
    w->file = -1;
    errno = 0;
    if (H5Fclose(f) < 0) {
      int e = errno;
      st = h5_fail(err, w->target, obj, "H5Fclose", e);
      goto fail;
    }
  }
  /* Make the contents durable before the name points at them: on the
   * descriptor opened before the first write (it sees every write-back
   * error since), after the background syncs, any of whose failures
   * counts. */
  sync_stop(w);
  int fd = w->sync_fd;
  w->sync_fd = -1;
  if (fd < 0)
    fd = open(w->tmp, O_RDONLY);
  if (fd < 0 || w->sync_errno || fsync(fd) != 0) {
    int e = w->sync_errno ? w->sync_errno : errno;
    if (fd >= 0)
      close(fd);
    st = aq_error_set(err, AQ_EIO, w->target, -1, -1, NULL,
                      "cannot sync %s: %s", w->tmp, strerror(e));
    goto fail;
  }
  close(fd);
  w->target = w->tmp = NULL; /* released by the commit either way */
  if ((st = aq_outfile_commit(&w->out, err)) != AQ_OK) /* renamed, or removed */
    goto fail;
  writer_free(w);
  return AQ_OK;
fail:
  aq_h5_abort(w);
  return st;
}

int64_t aq_h5_file_id(const aq_h5_writer *w)
{
  return (int64_t)w->file;
}
