/* fuzz_nptsdt.c: libFuzzer harness for the "NPTS DT" text parser (aq_nptsdt_parse), run
 * by make fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_nptsdt_parse
#include "fuzz_raw.h"
