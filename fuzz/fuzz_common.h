/* fuzz_common.h: the body shared by the reader harnesses.  A harness
 * defines AQ_FUZZ_PARSE (a reader's parse-from-memory function, see
 * io/reader.h) and includes this file.  Each input is parsed from memory
 * under a few reader options and every channel found is decided
 * (aq_record_decide), then the dispatcher that sniffs the format parses it;
 * a record must be consistent when the parse succeeds, and the error must
 * format to one line when it fails.  Anything else aborts. */
#ifndef AQ_FUZZ_COMMON_H
#define AQ_FUZZ_COMMON_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/record.h"

static void aq_fuzz_check(const aq_record *r, aq_status s, const aq_error *e)
{
  if (s == AQ_OK) {
    if (r->npts == 0 || !r->acc_mps2 || !(r->dt_s > 0))
      abort();
    for (size_t k = 0; k < r->npts; k++)
      if (!isfinite(r->acc_mps2[k])) /* NaN or Inf must never get through */
        abort();
  } else {
    char buf[1400];
    aq_error_format(e, buf, sizeof buf);
    if (strchr(buf, '\n') || r->acc_mps2)
      abort();
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  aq_read_opts ro[3];
  memset(ro, 0, sizeof ro);
  ro[1].units = AQ_UNITS_COUNTS;
  ro[1].dt_s = 0.01;
  ro[1].column = 2;
  ro[2].units = AQ_UNITS_G;
  snprintf(ro[2].rules[0].glob, sizeof ro[2].rules[0].glob, "*.x");
  ro[2].rules[0].units = AQ_UNITS_MPS2;
  ro[2].nrules = 1;
  ro[1].accept_implausible = 1;
  for (int i = 0; i < 3; i++) {
    aq_raw_file raw;
    aq_record r;
    aq_error e;
    aq_error_clear(&e);
    aq_reader_opts rop = {ro[i].dt_s, ro[i].column}; /* what a parser is told */
    aq_status s = AQ_FUZZ_PARSE(data, size, "fuzz.x", &rop, &raw, &e);
    if (s != AQ_OK) {
      memset(&r, 0, sizeof r);
      aq_fuzz_check(&r, s, &e);
    }
    for (size_t c = 0; s == AQ_OK && c < raw.nchan; c++) {
      aq_error_clear(&e);
      aq_status sd = aq_record_decide(&raw, c, "fuzz.x", &ro[i], &r, &e);
      aq_fuzz_check(&r, sd, &e);
      aq_record_free(&r);
    }
    aq_raw_file_free(&raw);
  }
  aq_record r;
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_record_parse(data, size, "fuzz", NULL, &r, &e);
  aq_fuzz_check(&r, s, &e);
  aq_record_free(&r);
  return 0;
}

#endif
