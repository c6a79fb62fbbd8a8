/* fuzz_renadic.c: libFuzzer harness for the RENADIC V1 parser (aq_renadic_parse), run by
 * make fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_renadic_parse
#include "fuzz_raw.h"
