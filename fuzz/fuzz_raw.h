/* fuzz_raw.h: the body shared by the harnesses of the agency-format parsers
 * (io/reader.h), which report what a file states (aq_raw_file).  A harness
 * defines AQ_FUZZ_RAW_PARSE and includes this file.  Each input is parsed
 * from memory; on success every channel must be consistent (npts > 0,
 * finite dt > 0, finite values), on failure the error must format to one
 * line and raw must be empty.  Anything else aborts.  Parse only: no units
 * decision, so that a minute gives well over 1e5 executions. */
#ifndef AQ_FUZZ_RAW_H
#define AQ_FUZZ_RAW_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "io/record.h"

static void aq_fuzz_raw_check(const aq_raw_file *r, aq_status s, const aq_error *e)
{
  if (s == AQ_OK) {
    if (r->nchan == 0 || !r->chan)
      abort();
    for (size_t i = 0; i < r->nchan; i++) {
      const aq_raw_channel *c = &r->chan[i];
      if (c->npts == 0 || !c->values || !(c->dt_s > 0) || !isfinite(c->dt_s) ||
          !memchr(c->channel, '\0', sizeof c->channel) || !memchr(c->units, '\0', sizeof c->units))
        abort();
      for (size_t k = 0; k < c->npts; k++)
        if (!isfinite(c->values[k]))
          abort();
    }
  } else {
    char buf[1400];
    aq_error_format(e, buf, sizeof buf);
    if (strchr(buf, '\n') || r->nchan || r->chan)
      abort();
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  aq_raw_file r;
  aq_error e;
  aq_error_clear(&e);
  aq_status s = AQ_FUZZ_RAW_PARSE(data, size, "fuzz", NULL, &r, &e);
  aq_fuzz_raw_check(&r, s, &e);
  if (s == AQ_OK)
    aq_raw_file_free(&r);
  return 0;
}

#endif
