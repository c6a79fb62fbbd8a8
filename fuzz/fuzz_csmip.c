/* fuzz_csmip.c: libFuzzer harness for the CSMIP V1/V2 parser (aq_csmip_parse), run by
 * make fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_csmip_parse
#include "fuzz_raw.h"
