/* fuzz_at2.c: libFuzzer harness for the AT2 reader (aq_at2_parse, then aq_record_decide), run by
 * make fuzz; the checks are in fuzz_common.h. */
#define AQ_FUZZ_PARSE aq_at2_parse
#include "fuzz_common.h"
