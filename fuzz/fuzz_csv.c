/* fuzz_csv.c: libFuzzer harness for the CSV reader (aq_csv_parse, then aq_record_decide), run by
 * make fuzz; the checks are in fuzz_common.h.  Also: aq_csv_channels agrees with aq_csv_parse
 * (the same error where it refuses; the same channel count where the parse succeeds). */
#include <stdlib.h>
#include <string.h>

#include "io/record.h"

static aq_status parse_and_count(const unsigned char *buf, size_t n, const char *name,
                                 const aq_reader_opts *opts, aq_raw_file *raw, aq_error *err)
{
  size_t nch;
  aq_error ec;
  aq_error_clear(&ec);
  aq_status sc = aq_csv_channels(buf, n, name, opts, &nch, &ec);
  aq_status s = aq_csv_parse(buf, n, name, opts, raw, err);
  if (sc != AQ_OK && (s != sc || ec.line != err->line || strcmp(ec.message, err->message)))
    abort();
  if (s == AQ_OK && (sc != AQ_OK || nch != raw->nchan))
    abort();
  return s;
}

#define AQ_FUZZ_PARSE parse_and_count
#include "fuzz_common.h"
