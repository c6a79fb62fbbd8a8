/* fuzz_geonet.c: libFuzzer harness for the GeoNet V1A/V2A reader
 * (aq_geonet_parse, then aq_record_decide), run by make fuzz; the checks are
 * in fuzz_common.h. */
#include "io/record.h"
#define AQ_FUZZ_PARSE aq_geonet_parse
#include "fuzz_common.h"
