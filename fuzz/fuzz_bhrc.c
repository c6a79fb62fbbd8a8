/* fuzz_bhrc.c: libFuzzer harness for the BHRC VOL1DS parser (aq_bhrc_parse), run by
 * make fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_bhrc_parse
#include "fuzz_raw.h"
