/* outfile.h: an output written under a temporary name beside its target,
 * "<target>.tmp.<pid>", and renamed onto the target only when complete, so
 * that no partial file ever carries the target's name and an existing one
 * stays untouched after a failure.  While it exists the temporary is
 * registered with cleanup.h: SIGINT, SIGTERM, SIGHUP and SIGPIPE remove it
 * (after aq_cleanup_install), and aq_cleanup_stale recognises it once its
 * process has died.
 *
 * aq_outfile_open makes the temporary as a stdio stream (opened "wx": a
 * file of that name is never overwritten); aq_outfile_reserve only names
 * and registers it, for writers that create the file themselves (HDF5,
 * PLplot).  Then exactly one of aq_outfile_commit (close, rename) and
 * aq_outfile_abort (close, remove).  Errors name the target, and the
 * temporary where it matters; nothing prints. */
#ifndef AQ_UTIL_OUTFILE_H
#define AQ_UTIL_OUTFILE_H

#include <stdio.h>

#include "../error.h"

typedef struct {
  char *target;  /* copy of the target's name */
  char *tmp;     /* the temporary's name */
  FILE *f;       /* with aq_outfile_open: the stream to write, else NULL */
  int slot;      /* its cleanup slot, or -1 */
} aq_outfile;

/* The temporary's name for target into buf[n]: "<target>.tmp.<pid>". */
void aq_outfile_temp_name(const char *target, char *buf, size_t n);

/* Name and register the temporary of target in *o (no file is made).
 * AQ_ENOMEM (err) when out of memory. */
aq_status aq_outfile_reserve(aq_outfile *o, const char *target, aq_error *err);

/* As aq_outfile_reserve, then create the temporary for writing (o->f).
 * AQ_EIO (err: the target, the temporary and the reason) when target is a
 * directory or the temporary cannot be created; nothing is left registered
 * then. */
aq_status aq_outfile_open(aq_outfile *o, const char *target, aq_error *err);

/* Close o->f (if open; a failed close, or a write error the stream holds,
 * is a failed write) and rename the
 * temporary onto the target.  On failure the temporary is removed and err
 * says why.  Either way o is released. */
aq_status aq_outfile_commit(aq_outfile *o, aq_error *err);

/* Close o->f (if open), remove the temporary, release o.  A zeroed o, or
 * one already released, is fine. */
void aq_outfile_abort(aq_outfile *o);

/* Release o without touching any file: for a writer that could not create
 * the temporary (a file of that name is not its own).  A zeroed o, or one
 * already released, is fine. */
void aq_outfile_release(aq_outfile *o);

#endif
