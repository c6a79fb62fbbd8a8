/* fuzz_mseed.c: libFuzzer harness for the miniSEED parser (aq_mseed_parse), run by
 * make fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_mseed_parse
#include "fuzz_raw.h"
