/* fuzz_smc.c: libFuzzer harness for the USGS SMC parser (aq_smc_parse), run by
 * make fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_smc_parse
#include "fuzz_raw.h"
