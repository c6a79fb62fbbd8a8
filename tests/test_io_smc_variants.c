/* test_io_smc_variants.c: USGS SMC files beside the corrected and uncorrected
 * accelerograms, against tests/data/records/agency2/PROVENANCE.md: a file
 * converted from another format (data type 0, "UNKNOWN"), read with the
 * units the user gives and refused without; and a type 1 file of unevenly
 * sampled (time, value) pairs, refused in one line that says what it holds. */
#include <string.h>

#include "agency2_fixture.h"

#define SMC_TYPE0 AGENCY2_DIR "0165b-type0-400pts.smc"
#define SMC_UNEVEN AGENCY2_DIR "891018_1.sma-1.0444a.smc"

AQ_TEST(io_smc_type0_unknown)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.accept_vertical = 1;
  aq_record r;
  aq_error err;
  /* the quantity is not stated: no units to take, and the message says why */
  aq_check(aq_record_read(SMC_TYPE0, &ro, &r, &err) == AQ_EUNITS &&
               strstr(err.message, "data type 0 (UNKNOWN)") && strstr(err.message, "--units"),
           "type 0 without --units: %s", err.message);
  /* PROVENANCE: the first 400 values of 0165b_a.smc, 200 samples/s, largest
   * 150.91 cm/s2 = 0.153885 g */
  ro.units = AQ_UNITS_GAL;
  static const aq_test_expect e = {SMC_TYPE0, 400, 0.005, 0.153885, 5e-7, ""};
  if (!aq_test_expect_read(&e, &ro, &r))
    return;
  aq_check(strcmp(r.format, "smc") == 0 && strcmp(r.units_used, "gal") == 0, "%s %s", r.format,
           r.units_used);
  aq_check(strcmp(r.reference, "1987-10-01T14:42:00.000Z") == 0, "start %s", r.reference);
  aq_record_free(&r);
}

AQ_TEST(io_smc_uneven_pairs_refused)
{
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  aq_record r;
  aq_error err;
  char msg[1400];
  aq_status s = aq_record_read(SMC_UNEVEN, &ro, &r, &err);
  aq_error_format(&err, msg, sizeof msg);
  /* PROVENANCE: 20620 pairs from 0 to 29.655 s, steps 0.0007 to 0.037 s */
  aq_check(s == AQ_EUNSUPPORTED && strstr(msg, SMC_UNEVEN ":18:") && strstr(msg, "USGS SMC") &&
               strstr(msg, "20620 (time, value) pairs") && strstr(msg, "0.0007 to 0.037 s") &&
               strstr(msg, "0 to 29.655 s") && strstr(msg, "not supported") &&
               !strchr(msg, '\n'),
           "uneven pairs: %s", msg);
}
