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

#define AQ_H5_SUMMARY_CHUNK 256 /* rows per chunk of /summary */
#define AQ_H5_COMPACT_ATTRS 96  /* attributes per group kept compact */
/* Link estimates of the record, arch and run groups (H5Pset_est_link_info):
 * at most 6 datasets each, sized generously so that the header starts
 * large enough for most of the group's attributes (see aq_h5_open). */
#define AQ_H5_EST_LINKS 8
#define AQ_H5_EST_LINK_NAME 150
/* Dataset bytes written between two background syncs (see sync_hint). */
#define AQ_H5_SYNC_BYTES ((size_t)8 << 20)

struct aq_h5_writer {
  char *target;
  char *tmp;
  hid_t file;
  hid_t g_records, g_arches, g_runs;
  /* /summary grows by AQ_H5_SUMMARY_CHUNK rows at a time, so the writer's
   * memory does not grow with the number of runs */
  hid_t d_sum, mt_sum, ft_sum;
  hid_t gcpl; /* record, arch and run groups: attributes kept compact */
  /* Reused by every attribute (H5Acreate2 copies them): the scalar
   * dataspace, and a string type whose size is set per attribute. */
  hid_t sp_scalar, t_str;
  aq_summary buf[AQ_H5_SUMMARY_CHUNK];
  size_t nbuf;   /* rows in buf */
  hsize_t nrows; /* rows already in the dataset */
  /* Background sync (see sync_hint): a descriptor of the temporary opened
   * before anything was written to it (the final fsync uses it too), the
   * dataset bytes written since the last request, and the syncing thread. */
  int sync_fd;
  size_t sync_pending;
  int sync_thread_on;   /* the thread runs */
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

static herr_t attr_write(hid_t loc, const char *name, hid_t type, hid_t space,
                         const void *buf)
{
  hid_t a = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0)
    return -1;
  herr_t rc = H5Awrite(a, type, buf);
  if (H5Aclose(a) < 0)
    rc = -1;
  return rc;
}

/* A scalar string attribute (fixed length strlen + 1, NUL-terminated). */
static herr_t attr_str(aq_h5_writer *w, hid_t loc, const char *name,
                       const char *value)
{
  if (!value)
    value = "";
  if (H5Tset_size(w->t_str, strlen(value) + 1) < 0)
    return -1;
  return attr_write(loc, name, w->t_str, w->sp_scalar, value);
}

static herr_t attr_double(aq_h5_writer *w, hid_t loc, const char *name, double v)
{
  return attr_write(loc, name, H5T_NATIVE_DOUBLE, w->sp_scalar, &v);
}

static herr_t attr_int(aq_h5_writer *w, hid_t loc, const char *name, int64_t v)
{
  return attr_write(loc, name, H5T_NATIVE_INT64, w->sp_scalar, &v);
}

static herr_t attr_doubles(hid_t loc, const char *name, const double *v,
                           size_t n)
{
  hsize_t dim = n;
  hid_t s = H5Screate_simple(1, &dim, NULL);
  if (s < 0)
    return -1;
  herr_t rc = attr_write(loc, name, H5T_NATIVE_DOUBLE, s, v);
  if (H5Sclose(s) < 0)
    rc = -1;
  return rc;
}

/* ---- background sync ------------------------------------------------------
 * The temporary is fdatasync'ed by a thread of the writer's own while the
 * suite runs, every AQ_H5_SYNC_BYTES of datasets, so that the fsync that
 * aq_h5_finish must do before the rename finds almost everything already on
 * disk (for a 36 MB file: 3 ms instead of 30 ms at the end of the suite,
 * when nothing else is left to run).  The thread only syncs a descriptor: it
 * never enters the HDF5 library.  The final fsync is unchanged; a failed
 * background sync fails aq_h5_finish (its error is reported to that
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
 * AQ_H5_SYNC_BYTES have been written since the last request (never waits). */
static void sync_hint(aq_h5_writer *w, size_t bytes)
{
  w->sync_pending += bytes;
  if (!w->sync_thread_on || w->sync_pending < AQ_H5_SYNC_BYTES)
    return;
  w->sync_pending = 0;
  pthread_mutex_lock(&w->sync_lock);
  w->sync_request = 1;
  pthread_cond_signal(&w->sync_cond);
  pthread_mutex_unlock(&w->sync_lock);
}

/* A 1-D dataset of n values of mtype, stored as ftype, with a units
 * attribute and then the nd double attributes dname[k] = dval[k]. */
static herr_t dataset_1d(aq_h5_writer *w, hid_t loc, const char *name,
                         hid_t ftype, hid_t mtype, const void *v, size_t n,
                         const char *units, size_t nd,
                         const char *const *dname, const double *dval)
{
  hsize_t dim = n;
  hid_t s = H5Screate_simple(1, &dim, NULL);
  if (s < 0)
    return -1;
  hid_t d = H5Dcreate2(loc, name, ftype, s, H5P_DEFAULT, H5P_DEFAULT,
                       H5P_DEFAULT);
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
                    units, 0, NULL, NULL);
}

/* ---- lifecycle ---------------------------------------------------------- */

static hid_t summary_type(hid_t *file);
static herr_t summary_flush(aq_h5_writer *w);

static void writer_free(aq_h5_writer *w)
{
  if (!w)
    return;
  sync_stop(w);
  if (w->sync_fd >= 0)
    close(w->sync_fd);
  H5E_BEGIN_TRY
  {
    if (w->gcpl >= 0)
      H5Pclose(w->gcpl);
    if (w->sp_scalar >= 0)
      H5Sclose(w->sp_scalar);
    if (w->t_str >= 0)
      H5Tclose(w->t_str);
  }
  H5E_END_TRY;
  free(w->target);
  free(w->tmp);
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
    if (w->mt_sum >= 0)
      H5Tclose(w->mt_sum);
    if (w->ft_sum >= 0)
      H5Tclose(w->ft_sum);
    if (w->file >= 0 && H5Fflush(w->file, H5F_SCOPE_LOCAL) >= 0) {
      if (w->d_sum >= 0)
        H5Dclose(w->d_sum);
      if (w->g_runs >= 0)
        H5Gclose(w->g_runs);
      if (w->g_arches >= 0)
        H5Gclose(w->g_arches);
      if (w->g_records >= 0)
        H5Gclose(w->g_records);
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
  w->g_runs = w->g_arches = w->g_records = w->file = -1;
  w->d_sum = w->mt_sum = w->ft_sum = -1;
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
  w->file = w->g_records = w->g_arches = w->g_runs = -1;
  w->d_sum = w->mt_sum = w->ft_sum = w->gcpl = -1;
  w->sp_scalar = w->t_str = -1;
  w->sync_fd = -1;
  size_t len = strlen(target) + 40;
  w->target = strdup(target);
  w->tmp = malloc(len);
  if (!w->target || !w->tmp) {
    writer_free(w);
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, NULL, "out of memory");
  }
  aq_h5_temp_name(target, w->tmp, len);
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
  sync_start(w);
  aq_status st = AQ_OK;
  const char *obj = "/";
  hid_t sp = -1, dcpl = -1;
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  CK(fapl, "H5Pcreate");
  /* 1.8 object format: attributes larger than 64 KiB (long command lines,
   * arch configurations) go to dense storage instead of failing. */
  CK(H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST),
     "H5Pset_libver_bounds");
  /* Every record, arch and run object leaves the metadata cache when it is
   * closed (written once, never reopened): the cache then holds only the
   * open top-level groups and /summary, instead of growing by ~30 KiB per
   * record and run until HDF5 starts evicting.  This halves the writer's
   * time per object (no heap growth, no page faults on it, no cache
   * bookkeeping for thousands of entries) and its memory. */
  CK(H5Pset_evict_on_close(fapl, 1), "H5Pset_evict_on_close");
  w->file = H5Fcreate(w->tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  CK(w->file, "H5Fcreate");
  CK(H5Pclose(fapl), "H5Pclose");
  fapl = -1;
  /* Up to AQ_H5_COMPACT_ATTRS attributes stay in the object header (the
   * 1.8 format otherwise moves more than 8 to a heap and a B-tree, which
   * costs the writer several times more per attribute). */
  w->sp_scalar = H5Screate(H5S_SCALAR);
  CK(w->sp_scalar, "H5Screate");
  w->t_str = str_type(1);
  CK(w->t_str, "H5Tcopy");
  w->gcpl = H5Pcreate(H5P_GROUP_CREATE);
  CK(w->gcpl, "H5Pcreate");
  CK(H5Pset_attr_phase_change(w->gcpl, AQ_H5_COMPACT_ATTRS, AQ_H5_COMPACT_ATTRS - 8),
     "H5Pset_attr_phase_change");
  /* The object header of a new group is sized from these estimates; the
   * space the links do not take holds the first attributes, which would
   * otherwise grow the header step by step (a third of the time spent per
   * attribute).  The file stays the same size to within a few KiB. */
  CK(H5Pset_est_link_info(w->gcpl, AQ_H5_EST_LINKS, AQ_H5_EST_LINK_NAME),
     "H5Pset_est_link_info");
  obj = "/records";
  w->g_records = H5Gcreate2(w->file, obj, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  CK(w->g_records, "H5Gcreate");
  obj = "/arches";
  w->g_arches = H5Gcreate2(w->file, obj, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  CK(w->g_arches, "H5Gcreate");
  obj = "/runs";
  w->g_runs = H5Gcreate2(w->file, obj, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  CK(w->g_runs, "H5Gcreate");
  obj = "/summary";
  w->mt_sum = summary_type(&w->ft_sum);
  CK(w->mt_sum, "summary type");
  {
    hsize_t dim = 0, maxdim = H5S_UNLIMITED, chunk = AQ_H5_SUMMARY_CHUNK;
    sp = H5Screate_simple(1, &dim, &maxdim);
    CK(sp, "H5Screate");
    dcpl = H5Pcreate(H5P_DATASET_CREATE);
    CK(dcpl, "H5Pcreate");
    CK(H5Pset_chunk(dcpl, 1, &chunk), "H5Pset_chunk");
    w->d_sum = H5Dcreate2(w->file, obj, w->ft_sum, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    CK(w->d_sum, "H5Dcreate");
    CK(H5Pclose(dcpl), "H5Pclose");
    dcpl = -1;
    CK(H5Sclose(sp), "H5Sclose");
    sp = -1;
    CK(attr_str(w, w->d_sum, "units",
                "per member: scale 1, pga_g g, *_s s, *_rad rad, *_m m, *_j J, "
                "collapsed and impacts counts (-1: failed run), lambda0_first g/g, "
                "peak_rotation_over_qc 1, pga_over_lambda0_g 1"),
       "summary attributes");
  }
  *out = w;
  return AQ_OK;
fail:
  if (fapl >= 0)
    H5Pclose(fapl);
  if (dcpl >= 0)
    H5Pclose(dcpl);
  if (sp >= 0)
    H5Sclose(sp);
  aq_h5_abort(w);
  return st;
}

void aq_h5_temp_name(const char *target, char *buf, size_t n)
{
  snprintf(buf, n, "%s.tmp.%ld", target, (long)getpid());
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
  if (w->tmp)
    unlink(w->tmp);
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

/* Processing parameters (requested at the root, used per record). */
static herr_t write_proc(aq_h5_writer *w, hid_t loc, const aq_signal_opts *p)
{
  if (attr_str(w, loc, "detrend", detrend_name(p->detrend)) < 0 ||
      attr_int(w, loc, "filter", p->filter ? 1 : 0) < 0 ||
      attr_double(w, loc, "taper_frac", p->filter ? p->taper_frac : 0.0) < 0 ||
      attr_double(w, loc, "highpass_hz", p->filter ? p->highpass_hz : NAN) < 0 ||
      attr_int(w, loc, "highpass_order", p->filter ? p->order : 0) < 0 ||
      attr_double(w, loc, "lowpass_hz",
                  p->filter && p->lowpass_hz > 0 ? p->lowpass_hz : NAN) < 0)
    return -1;
  return 0;
}

aq_status aq_h5_write_root(aq_h5_writer *w, const aq_h5_root *r, aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/";
  hid_t f = w->file;
  CK(attr_str(w, f, "archquake_version", r->version), "root attributes");
  CK(attr_int(w, f, "format_version", AQ_H5_FORMAT_VERSION), "root attributes");
  CK(attr_str(w, f, "command_line", r->command_line), "root attributes");
  CK(attr_str(w, f, "created", r->created), "root attributes");
  if (r->proc)
    CK(write_proc(w, f, r->proc), "root attributes");
  CK(attr_double(w, f, "merge_tol_g", r->merge_tol_g), "root attributes");
  CK(attr_str(w, f, "units_override", r->units ? r->units : "file"),
     "root attributes");
  CK(attr_double(w, f, "dt_override_s", r->dt_override_s > 0 ? r->dt_override_s : NAN),
     "root attributes");
  CK(attr_str(w, f, "model", r->model), "root attributes");
  CK(attr_double(w, f, "cor", r->cor), "root attributes");
  if (r->scales) {
    CK(attr_str(w, f, "scale_mode", "list"), "root attributes");
    CK(attr_doubles(f, "scales", r->scales, r->nscale), "root attributes");
  } else {
    CK(attr_str(w, f, "scale_mode", "pga"), "root attributes");
  }
  CK(attr_double(w, f, "scale_to_pga_g", r->scale_to_pga_g), "root attributes");
  CK(attr_int(w, f, "history", r->history ? 1 : 0), "root attributes");
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

aq_status aq_h5_write_arch(aq_h5_writer *w, size_t index, const aq_h5_arch *a,
                           aq_error *err)
{
  aq_status st = AQ_OK;
  char obj[64];
  snprintf(obj, sizeof obj, "/arches/%03zu", index);
  hid_t g = H5Gcreate2(w->file, obj, H5P_DEFAULT, w->gcpl, H5P_DEFAULT);
  CK(g, "H5Gcreate");
  CK(attr_str(w, g, "name", a->name), "arch attributes");
  CK(attr_str(w, g, "source_file", a->source_file), "arch attributes");
  CK(attr_str(w, g, "config", a->config_text), "arch attributes");
  if (a->dyn) {
    CK(attr_double(w, g, "cor", a->dyn->cor), "arch attributes");
    CK(attr_str(w, g, "impact", impact_name(a->dyn->impact)), "arch attributes");
    CK(attr_double(w, g, "g_m_s2", a->dyn->g_mps2), "arch attributes");
  }
  static const char *const set_name[2] = {"primary", "reverse"};
  for (int k = 0; k < 2; k++) {
    const aq_path *p = a->set[k];
    char nm[64];
    snprintf(nm, sizeof nm, "%s_admissible", set_name[k]);
    CK(attr_int(w, g, nm, p && p->admissible ? 1 : 0), "arch attributes");
    snprintf(nm, sizeof nm, "%s_lambda0", set_name[k]);
    CK(attr_double(w, g, nm, p ? p->lambda0 : NAN), "arch attributes");
    snprintf(nm, sizeof nm, "%s_q_c_rad", set_name[k]);
    CK(attr_double(w, g, nm, p ? p->s_c_rad : NAN), "arch attributes");
    snprintf(nm, sizeof nm, "%s_mass_kg", set_name[k]);
    CK(attr_double(w, g, nm, p ? p->mass_kg : NAN), "arch attributes");
  }
  CK(H5Gclose(g), "H5Gclose");
  return AQ_OK;
fail:
  if (g >= 0)
    H5E_BEGIN_TRY { H5Gclose(g); } H5E_END_TRY;
  return st;
}

aq_status aq_h5_write_record(aq_h5_writer *w, size_t index,
                             const aq_h5_record *r, aq_error *err)
{
  aq_status st = AQ_OK;
  char obj[64];
  snprintf(obj, sizeof obj, "/records/%05zu", index);
  hid_t g = H5Gcreate2(w->file, obj, H5P_DEFAULT, w->gcpl, H5P_DEFAULT);
  CK(g, "H5Gcreate");
  CK(attr_str(w, g, "source_file", r->source_file), "record attributes");
  CK(attr_str(w, g, "status", r->status ? r->status : "ok"), "record attributes");
  if (r->error)
    CK(attr_str(w, g, "error", r->error), "record attributes");
  if (r->rec) {
    const aq_record *rec = r->rec;
    CK(attr_str(w, g, "name", rec->name), "record attributes");
    CK(attr_str(w, g, "format", rec->format), "record attributes");
    CK(attr_str(w, g, "units_orig", rec->units_orig), "record attributes");
    CK(attr_double(w, g, "to_m_s2", rec->to_mps2), "record attributes");
    CK(attr_int(w, g, "npts", (int64_t)rec->npts), "record attributes");
    CK(attr_double(w, g, "dt_s", rec->dt_s), "record attributes");
    CK(attr_double(w, g, "begin_s", rec->begin_s), "record attributes");
    CK(attr_str(w, g, "reference_time", rec->reference), "record attributes");
    CK(attr_str(w, g, "network", rec->network), "record attributes");
    CK(attr_str(w, g, "station", rec->station), "record attributes");
    CK(attr_str(w, g, "location", rec->location), "record attributes");
    CK(attr_str(w, g, "channel", rec->channel), "record attributes");
  }
  if (r->proc) {
    const aq_processed *p = r->proc;
    CK(write_proc(w, g, &p->used), "record attributes");
    CK(attr_int(w, g, "pad_front", (int64_t)p->pad_front), "record attributes");
    CK(attr_int(w, g, "pad_back", (int64_t)p->pad_back), "record attributes");
    CK(attr_int(w, g, "n_orig", (int64_t)p->n_orig), "record attributes");
    static const char *const time_attr[2] = {"dt_s", "t0_s"};
    const double time_val[2] = {p->dt_s, -(double)p->pad_front * p->dt_s};
    CK(dataset_1d(w, g, "acceleration_m_s2", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                  p->acc_mps2, p->n, "m/s^2", 2, time_attr, time_val),
       "acceleration_m_s2");
  }
  if (r->im) {
    const aq_im *m = r->im;
    CK(attr_double(w, g, "pga_g", m->pga_g), "record attributes");
    CK(attr_double(w, g, "pgv_m_s", m->pgv_mps), "record attributes");
    CK(attr_double(w, g, "pgd_m", m->pgd_m), "record attributes");
    CK(attr_double(w, g, "arias_m_s", m->arias_mps), "record attributes");
    CK(attr_double(w, g, "d5_95_s", m->d5_95_s), "record attributes");
    CK(attr_double(w, g, "cav_m_s", m->cav_mps), "record attributes");
    CK(attr_double(w, g, "v_end_m_s", m->v_end_mps), "record attributes");
    CK(attr_double(w, g, "d_end_m", m->d_end_m), "record attributes");
  }
  CK(attr_double(w, g, "timing_read_s", r->timing_read_s), "record attributes");
  CK(attr_double(w, g, "timing_process_s", r->timing_process_s),
     "record attributes");
  CK(H5Gclose(g), "H5Gclose");
  return AQ_OK;
fail:
  if (g >= 0)
    H5E_BEGIN_TRY { H5Gclose(g); } H5E_END_TRY;
  return st;
}

static herr_t write_summary_attrs(aq_h5_writer *w, hid_t g, const aq_summary *s)
{
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *f = &aq_summary_fields[i];
    herr_t rc = 0;
    switch (f->kind) {
    case AQ_SF_STR:
      rc = attr_str(w, g, f->name, aq_summary_get_str(s, f));
      break;
    case AQ_SF_DOUBLE:
      rc = attr_double(w, g, f->name, aq_summary_get_double(s, f));
      break;
    case AQ_SF_INT:
      rc = attr_int(w, g, f->name, aq_summary_get_int(s, f));
      break;
    }
    if (rc < 0)
      return -1;
  }
  return 0;
}

aq_status aq_h5_write_run(aq_h5_writer *w, size_t ri, size_t ai, size_t si,
                          const aq_summary *s, const aq_result *res,
                          const char *error, double timing_run_s,
                          aq_error *err)
{
  aq_status st = AQ_OK;
  char obj[96], link[64];
  char az[32] = ""; /* runs of one scale at several azimuths */
  if (isfinite(s->azimuth_deg))
    snprintf(az, sizeof az, "_az%.6g", s->azimuth_deg);
  snprintf(obj, sizeof obj, "/runs/%05zu_%03zu_%03zu%s%s", ri, ai, si,
           strcmp(s->polarity, "reversed") == 0 ? "r" : "", az);
  hid_t g = -1;
  g = H5Gcreate2(w->file, obj, H5P_DEFAULT, w->gcpl, H5P_DEFAULT);
  CK(g, "H5Gcreate");
  CK(write_summary_attrs(w, g, s), "run attributes");
  CK(attr_int(w, g, "record_index", (int64_t)ri), "run attributes");
  CK(attr_int(w, g, "arch_index", (int64_t)ai), "run attributes");
  CK(attr_int(w, g, "scale_index", (int64_t)si), "run attributes");
  snprintf(link, sizeof link, "/records/%05zu", ri);
  CK(attr_str(w, g, "record_group", link), "run attributes");
  snprintf(link, sizeof link, "/arches/%03zu", ai);
  CK(attr_str(w, g, "arch_group", link), "run attributes");
  if (error)
    CK(attr_str(w, g, "error", error), "run attributes");
  if (res) {
    CK(attr_int(w, g, "reversals", (int64_t)res->reversals), "run attributes");
    CK(attr_int(w, g, "steps_total", (int64_t)res->steps_total), "run attributes");
    CK(attr_int(w, g, "steps_moving", (int64_t)res->steps_moving),
       "run attributes");
    CK(attr_int(w, g, "path_evaluations", (int64_t)res->evals), "run attributes");
    const aq_history *h = &res->history;
    if (h->time_s) {
      CK(dataset_doubles(w, g, "time_s", h->time_s, h->n, "s"), "time_s");
      CK(dataset_doubles(w, g, "rotation_rad", h->rotation_rad, h->n, "rad"),
         "rotation_rad");
      CK(dataset_doubles(w, g, "displacement_m", h->displacement_m, h->n, "m"),
         "displacement_m");
      CK(dataset_doubles(w, g, "kinetic_energy_j", h->kinetic_energy_j, h->n, "J"),
         "kinetic_energy_j");
      CK(dataset_doubles(w, g, "potential_energy_j", h->potential_energy_j, h->n,
                         "J"),
         "potential_energy_j");
      if (h->set)
        CK(dataset_1d(w, g, "hinge_set", H5T_STD_I32LE, H5T_NATIVE_INT, h->set,
                      h->n, "1 (0 primary, 1 reverse, -1 at rest)", 0, NULL,
                      NULL),
           "hinge_set");
    }
  }
  CK(attr_double(w, g, "timing_run_s", timing_run_s), "run attributes");
  CK(H5Gclose(g), "H5Gclose");
  g = -1;
  w->buf[w->nbuf++] = *s;
  if (w->nbuf == AQ_H5_SUMMARY_CHUNK)
    CK(summary_flush(w), "/summary rows");
  return AQ_OK;
fail:
  if (g >= 0)
    H5E_BEGIN_TRY { H5Gclose(g); } H5E_END_TRY;
  return st;
}

/* The compound type of aq_summary (memory layout); *file gets the packed
 * copy for the file.  Returns the memory type or < 0. */
static hid_t summary_type(hid_t *file)
{
  hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(aq_summary));
  if (t < 0)
    return -1;
  for (size_t i = 0; i < aq_summary_nfields; i++) {
    const aq_summary_field *f = &aq_summary_fields[i];
    hid_t m = -1;
    herr_t rc = -1;
    switch (f->kind) {
    case AQ_SF_STR:
      m = str_type(f->size);
      if (m >= 0) {
        rc = H5Tinsert(t, f->name, f->offset, m);
        if (H5Tclose(m) < 0)
          rc = -1;
      }
      break;
    case AQ_SF_DOUBLE:
      rc = H5Tinsert(t, f->name, f->offset, H5T_NATIVE_DOUBLE);
      break;
    case AQ_SF_INT:
      rc = H5Tinsert(t, f->name, f->offset, H5T_NATIVE_INT64);
      break;
    }
    if (rc < 0) {
      H5Tclose(t);
      return -1;
    }
  }
  *file = H5Tcopy(t);
  if (*file < 0 || H5Tpack(*file) < 0) {
    if (*file >= 0)
      H5Tclose(*file);
    H5Tclose(t);
    return -1;
  }
  return t;
}

/* Append the buffered rows to /summary.  Returns < 0 on failure. */
static herr_t summary_flush(aq_h5_writer *w)
{
  if (w->nbuf == 0)
    return 0;
  hsize_t start = w->nrows, count = w->nbuf, size = w->nrows + w->nbuf;
  if (H5Dset_extent(w->d_sum, &size) < 0)
    return -1;
  hid_t fs = H5Dget_space(w->d_sum);
  if (fs < 0)
    return -1;
  hid_t ms = H5Screate_simple(1, &count, NULL);
  herr_t rc = -1;
  if (ms >= 0 &&
      H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL) >= 0)
    rc = H5Dwrite(w->d_sum, w->mt_sum, ms, fs, H5P_DEFAULT, w->buf);
  if (ms >= 0 && H5Sclose(ms) < 0)
    rc = -1;
  if (H5Sclose(fs) < 0)
    rc = -1;
  if (rc >= 0) {
    w->nrows += w->nbuf;
    w->nbuf = 0;
  }
  return rc;
}

aq_status aq_h5_finish(aq_h5_writer *w, const aq_h5_timing *t, aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/summary";
  CK(summary_flush(w), "/summary rows");
  CK(H5Dclose(w->d_sum), "H5Dclose");
  w->d_sum = -1;
  CK(H5Tclose(w->mt_sum), "H5Tclose");
  w->mt_sum = -1;
  CK(H5Tclose(w->ft_sum), "H5Tclose");
  w->ft_sum = -1;
  obj = "/";
  if (t) {
    CK(attr_double(w, w->file, "timing_wall_s", t->wall_s), "root attributes");
    CK(attr_double(w, w->file, "timing_read_s", t->read_s), "root attributes");
    CK(attr_double(w, w->file, "timing_process_s", t->process_s),
       "root attributes");
    CK(attr_double(w, w->file, "timing_run_s", t->run_s), "root attributes");
    CK(attr_double(w, w->file, "timing_write_s", t->write_s), "root attributes");
  }
  CK(H5Gclose(w->g_runs), "H5Gclose");
  w->g_runs = -1;
  CK(H5Gclose(w->g_arches), "H5Gclose");
  w->g_arches = -1;
  CK(H5Gclose(w->g_records), "H5Gclose");
  w->g_records = -1;
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
  if (rename(w->tmp, w->target) != 0) {
    int e = errno;
    st = aq_error_set(err, AQ_EIO, w->target, -1, -1, NULL,
                      "cannot rename %s onto it: %s", w->tmp, strerror(e));
    goto fail;
  }
  writer_free(w);
  return AQ_OK;
fail:
  aq_h5_abort(w);
  return st;
}
