/* fuzz_stationxml.c: libFuzzer harness for the StationXML reader
 * (aq_stationxml_parse, libxml2), run by make fuzz.  A parse that succeeds
 * must hold at least one epoch with NUL-terminated codes; a failure must
 * format to one line and leave the response empty.  Then a channel's
 * epochs are looked up and every epoch applied to a counts channel. */
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
  const aq_response_epoch *hit;
  size_t nsame = 0;
  char spans[256] = "";
  size_t nhit = aq_response_find(&resp, ch.network, ch.station, ch.location, ch.channel,
                                 1571117601.0, &hit, &nsame, spans, sizeof spans);
  if ((nhit > 0) != (hit != NULL) || nhit > nsame || strlen(spans) >= sizeof spans)
    abort();
  for (size_t k = 0; k < resp.n; k++) { /* every epoch applied */
    aq_raw_channel c = ch;
    s = aq_response_apply(&resp.epoch[k], "fuzz.xml", &c, &e);
    if (s == AQ_OK && c.quantity == AQ_QUANTITY_ACCELERATION &&
        !(isfinite(c.counts_per_mps2) && c.counts_per_mps2 != 0))
      abort();
  }
  aq_response_free(&resp);
  return 0;
}
