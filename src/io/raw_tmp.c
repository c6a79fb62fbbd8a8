/* raw_tmp.c: aq_raw_file_free until record.c provides it (see raw_tmp.h). */
#include <stdlib.h>
#include <string.h>

#include "raw_tmp.h"

void aq_raw_file_free(aq_raw_file *raw)
{
  if (!raw)
    return;
  for (size_t i = 0; i < raw->nchan; i++)
    free(raw->chan[i].values);
  free(raw->chan);
  memset(raw, 0, sizeof *raw);
}
