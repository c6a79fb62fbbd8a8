/* h5.c: the HDF5 results writer (see h5.h and docs/hdf5-layout.md): the
 * file's life, open under a temporary name, finished (every table flushed,
 * the file closed, synced and renamed onto the target) or abandoned with
 * its temporary removed, so that no partial file is ever left.  What goes
 * into the file is written by h5_root.c, h5_arches.c, h5_records.c and
 * h5_runs.c (h5_writer.h lists the writer's files). */
#define _POSIX_C_SOURCE 200809L
#include "h5.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "h5_writer.h"

static void writer_free(aq_h5_writer *w)
{
  if (!w)
    return;
  aq_h5w_sync_stop(w);
  if (w->sync_fd >= 0)
    close(w->sync_fd);
  H5E_BEGIN_TRY
  {
    aq_h5w_table_close_quietly(&w->runs);
    aq_h5w_table_close_quietly(&w->records);
    if (w->sp_scalar >= 0)
      H5Sclose(w->sp_scalar);
    if (w->t_str >= 0)
      H5Tclose(w->t_str);
  }
  H5E_END_TRY;
  aq_h5w_table_free(&w->runs);
  aq_h5w_table_free(&w->records);
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
    aq_h5w_table_close_quietly(&w->runs);
    aq_h5w_table_close_quietly(&w->records);
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
  aq_h5w_records_init(w);
  w->sp_scalar = w->t_str = -1;
  w->sync_fd = -1;
  w->deflate = AQ_H5_DEFLATE_LEVEL;
  /* named and registered for removal on a signal before it exists */
  if (aq_h5w_runs_init(w) < 0 || aq_outfile_reserve(&w->out, target, err) != AQ_OK) {
    writer_free(w);
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, NULL, "out of memory");
  }
  w->target = w->out.target;
  w->tmp = w->out.tmp;
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
  w->t_str = aq_h5w_str_type(1);
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

aq_status aq_h5_finish(aq_h5_writer *w, const aq_h5_timing *t, aq_error *err)
{
  aq_status st = AQ_OK;
  const char *obj = "/summary";
  if (w->runs.buf) /* a results file's */
    CK(aq_h5w_table_close(w, &w->runs), "rows");
  obj = "/records";
  if (!w->records.buf)
    CK(aq_h5w_records_open(w, NULL), "table");
  CK(aq_h5w_table_close(w, &w->records), "rows");
  obj = "/";
  if (t) {
    CK(aq_h5w_attr_double(w, w->file, "timing_wall_s", t->wall_s), "root attributes");
    CK(aq_h5w_attr_double(w, w->file, "timing_read_s", t->read_s), "root attributes");
    CK(aq_h5w_attr_double(w, w->file, "timing_process_s", t->process_s),
       "root attributes");
    CK(aq_h5w_attr_double(w, w->file, "timing_run_s", t->run_s), "root attributes");
    CK(aq_h5w_attr_double(w, w->file, "timing_write_s", t->write_s), "root attributes");
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
      st = aq_h5w_fail(err, w->target, obj, "H5Fflush (writing the file)", e);
      w->file = -1;
      goto fail;
    }
    hid_t f = w->file;
    w->file = -1;
    errno = 0;
    if (H5Fclose(f) < 0) {
      int e = errno;
      st = aq_h5w_fail(err, w->target, obj, "H5Fclose", e);
      goto fail;
    }
  }
  /* Make the contents durable before the name points at them: on the
   * descriptor opened before the first write (it sees every write-back
   * error since), after the background syncs, any of whose failures
   * counts. */
  aq_h5w_sync_stop(w);
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
