/* fuzz_csv.c: libFuzzer harness for the CSV reader (aq_csv_parse, then aq_record_decide), run by
 * make fuzz; the checks are in fuzz_common.h. */
#define AQ_FUZZ_PARSE aq_csv_parse
#include "fuzz_common.h"
