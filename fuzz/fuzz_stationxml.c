/* fuzz_stationxml.c: libFuzzer harness for the StationXML reader
 * (aq_stationxml_parse, libxml2), run by make fuzz.  A parse that succeeds
 * must hold at least one epoch with NUL-terminated codes; a failure must
 * format to one line and leave the response empty.  Then the response is
 * applied to a one-channel counts record. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "io/record.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  aq_response resp;
  aq_error e;
  aq_error_clear(&e);
  aq_status s = aq_stationxml_parse(data, size, "fuzz.xml", &resp, &e);
  if (s != AQ_OK) {
    char buf[1400];
    aq_error_format(&e, buf, sizeof buf);
    if (strchr(buf, '\n') || resp.n || resp.epoch)
      abort();
    return 0;
  }
  if (resp.n == 0)
    abort();
  double v = 1.0;
  aq_raw_channel ch = {.channel = "HNE", .network = "CE", .station = "58360",
                       .units = "counts", .reference = "2019-10-15T05:33:21.000Z",
                       .npts = 1, .dt_s = 0.01, .values = &v, .azimuth_deg = NAN,
                       .dip_deg = NAN, .vertical = -1};
  aq_raw_file raw = {.nchan = 1, .chan = &ch};
  s = aq_stationxml_apply(&resp, "fuzz.xml", &raw, "fuzz", &e);
  if (s == AQ_OK && !(isfinite(ch.counts_per_mps2) && ch.counts_per_mps2 != 0))
    abort();
  aq_response_free(&resp);
  return 0;
}
