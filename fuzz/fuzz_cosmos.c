/* fuzz_cosmos.c: libFuzzer harness for the COSMOS V0/V1/V2 parser (aq_cosmos_parse), run by
 * make fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_cosmos_parse
#include "fuzz_raw.h"
