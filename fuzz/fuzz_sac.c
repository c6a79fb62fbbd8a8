/* fuzz_sac.c: libFuzzer harness for the SAC reader (aq_sac_parse, then aq_record_decide), run by
 * make fuzz; the checks are in fuzz_common.h. */
#define AQ_FUZZ_PARSE aq_sac_parse
#include "fuzz_common.h"
