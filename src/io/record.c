/* record.c: format detection and dispatch (placeholder: readers land next). */
#include "record.h"

#include <stdlib.h>
#include <string.h>

void aq_record_free(aq_record *rec)
{
  if (!rec)
    return;
  free(rec->path);
  free(rec->name);
  free(rec->acc_mps2);
  memset(rec, 0, sizeof *rec);
}

aq_status aq_record_read(const char *path, const aq_read_opts *opts,
                         aq_record *rec, aq_error *err)
{
  (void)opts;
  memset(rec, 0, sizeof *rec);
  return aq_error_set(err, AQ_EUNSUPPORTED, path, -1, -1, NULL,
                      "no reader in this build");
}
