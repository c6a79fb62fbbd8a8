/* fuzz_nsmn.c: libFuzzer harness for the NSMN/AFAD (Turkey) ASCII parser
 * (aq_nsmn_parse), run by make fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_nsmn_parse
#include "fuzz_raw.h"
