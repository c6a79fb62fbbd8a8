/* test_io_header_ints.c: an integer header word too large for an int (a
 * fuzzed SMC file had hour = 2222222222; fuzz/seeds/fuzz_smc keeps it for
 * the clang sanitizer, which traps the overflowing conversion) is taken as
 * -1, and the start time is then unknown. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/fixed.h"
#include "io/record.h"

#define SMC_FILE "tests/data/records/agency/0165b_a.smc"

AQ_TEST(io_smc_hour_beyond_int)
{
  aq_check(aq_header_int(2222222222.0) == -1 && aq_header_int(-3e9) == -1 &&
               aq_header_int(1e30) == -1 && aq_header_int(1987.0) == 1987,
           "header words beyond an int are -1");
  FILE *f = fopen(SMC_FILE, "rb");
  if (!aq_check(f != NULL, "open %s", SMC_FILE))
    return;
  static char buf[200000];
  size_t n = fread(buf, 1, sizeof buf, f);
  fclose(f);
  aq_raw_file raw;
  aq_error e;
  if (aq_check(aq_raw_parse((unsigned char *)buf, n, SMC_FILE, NULL, &raw, &e) == AQ_OK,
               "%s", e.message)) {
    aq_check(strncmp(raw.chan[0].reference, "1987-10-01T14:42", 16) == 0,
             "as shipped: reference %s (1987, day 274 = Oct 1, 14:42)", raw.chan[0].reference);
    aq_raw_file_free(&raw);
  }
  /* the first integer line: "    -32768      1987       274        14 ..."; the
   * fourth field (hour, columns 31-40) becomes 2222222222 */
  char *hour = strstr(buf, "       274        14");
  if (!aq_check(hour != NULL, "hour field found"))
    return;
  memcpy(hour + 10, "2222222222", 10);
  if (aq_check(aq_raw_parse((unsigned char *)buf, n, SMC_FILE, NULL, &raw, &e) == AQ_OK,
               "%s", e.message)) {
    aq_check(raw.chan[0].reference[0] == '\0', "hour 2222222222: no reference, got %s",
             raw.chan[0].reference);
    aq_raw_file_free(&raw);
  }
}
