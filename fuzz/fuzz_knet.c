/* fuzz_knet.c: libFuzzer harness for the K-NET/KiK-net reader (aq_knet_parse,
 * then aq_record_decide), run by make fuzz; the checks are in fuzz_common.h. */
#define AQ_FUZZ_PARSE aq_knet_parse
#include "fuzz_common.h"
