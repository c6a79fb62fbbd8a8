/* outfile.c: write under a temporary name, rename when complete (outfile.h). */
#define _POSIX_C_SOURCE 200809L
#include "outfile.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cleanup.h"

void aq_outfile_temp_name(const char *target, char *buf, size_t n)
{
  snprintf(buf, n, "%s.tmp.%ld", target, (long)getpid());
}

void aq_outfile_release(aq_outfile *o)
{
  if (!o->target) /* zeroed, or released already */
    return;
  aq_cleanup_remove(o->slot);
  free(o->target);
  free(o->tmp);
  memset(o, 0, sizeof *o);
  o->slot = -1;
}

aq_status aq_outfile_reserve(aq_outfile *o, const char *target, aq_error *err)
{
  memset(o, 0, sizeof *o);
  o->slot = -1;
  size_t len = strlen(target) + 32;
  o->target = strdup(target);
  o->tmp = malloc(len);
  if (!o->target || !o->tmp) {
    free(o->target);
    free(o->tmp);
    memset(o, 0, sizeof *o);
    o->slot = -1;
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, NULL, "out of memory");
  }
  aq_outfile_temp_name(target, o->tmp, len);
  /* registered before it exists, so that no signal can slip in between */
  o->slot = aq_cleanup_add(o->tmp);
  return AQ_OK;
}

aq_status aq_outfile_open(aq_outfile *o, const char *target, aq_error *err)
{
  struct stat sb; /* a directory would fail only at the rename, after the work */
  if (stat(target, &sb) == 0 && S_ISDIR(sb.st_mode)) {
    memset(o, 0, sizeof *o);
    o->slot = -1;
    return aq_error_set(err, AQ_EIO, target, -1, -1, NULL,
                        "expected a file name, got a directory");
  }
  aq_status s = aq_outfile_reserve(o, target, err);
  if (s != AQ_OK)
    return s;
  if (!(o->f = fopen(o->tmp, "wx"))) {
    s = aq_error_set(err, AQ_EIO, target, -1, -1, NULL,
                     "cannot create the output (temporary %s): %s", o->tmp, strerror(errno));
    aq_outfile_release(o);
  }
  return s;
}

aq_status aq_outfile_commit(aq_outfile *o, aq_error *err)
{
  if (!o->target) /* zeroed, or released already: nothing to rename */
    return aq_error_set(err, AQ_EINTERNAL, "", -1, -1, NULL, "expected an open output, got none");
  aq_status s = AQ_OK;
  if (o->f) {
    int bad = ferror(o->f); /* a write that failed before the close */
    bad |= fclose(o->f) != 0;
    if (bad)
      s = aq_error_set(err, AQ_EIO, o->target, -1, -1, NULL, "cannot write the output: %s",
                       strerror(errno));
  }
  o->f = NULL;
  if (s == AQ_OK && rename(o->tmp, o->target) != 0)
    s = aq_error_set(err, AQ_EIO, o->target, -1, -1, NULL, "cannot rename %s onto it: %s",
                     o->tmp, strerror(errno));
  if (s != AQ_OK)
    unlink(o->tmp);
  aq_outfile_release(o);
  return s;
}

void aq_outfile_abort(aq_outfile *o)
{
  if (!o->target) /* zeroed, or released already */
    return;
  if (o->f)
    fclose(o->f);
  o->f = NULL;
  if (o->tmp)
    unlink(o->tmp);
  aq_outfile_release(o);
}
