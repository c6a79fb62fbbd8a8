/* fuzz_asa.c: libFuzzer harness for the ASA 2.0 parser (aq_asa_parse), run by make
 * fuzz; the checks are in fuzz_raw.h. */
#define AQ_FUZZ_RAW_PARSE aq_asa_parse
#include "fuzz_raw.h"
