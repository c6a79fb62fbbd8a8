/* fuzz_esm.c: libFuzzer harness for the ESM/ITACA ASCII parser (aq_esm_parse), run by
 * make fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_esm_parse
#include "fuzz_raw.h"
