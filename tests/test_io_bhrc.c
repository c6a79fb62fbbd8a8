/* test_io_bhrc.c: the BHRC (Iran) VOL1DS reader against
 * tests/data/records/agency2/PROVENANCE.md (5522-1.V1), read as a user
 * would, and its refusals: another volume named in one line, a DURATION
 * that disagrees with the rate, a block without its end, a cut file. */
#include <math.h>
#include <string.h>

#include "agency2_fixture.h"
#include "raw_fixture.h"

#define BHRC_FILE AGENCY2_DIR "5522-1.V1"

AQ_TEST(io_bhrc_three_blocks_g10)
{
  /* PROVENANCE: 9984 points, 200 samples/s, g/10; peaks +0.159512,
   * +0.0765147, +0.123697 g/10 = 0.01595, 0.007651, 0.01237 g */
  static const aq_test_expect e[3] = {
      {BHRC_FILE "#L1", 9984, 0.005, 0.01595, 5e-6, "g/10"},
      {BHRC_FILE "#V2", 9984, 0.005, 0.007651, 5e-7, "g/10"},
      {BHRC_FILE "#T3", 9984, 0.005, 0.01237, 5e-6, "g/10"}};
  static const double peak_g10[3] = {0.159512, 0.0765147, 0.123697};
  static const double t_peak_s[3] = {15.380, 17.245, 18.590};
  static const double az[3] = {324, NAN, 54};
  for (int i = 0; i < 3; i++) {
    aq_record r;
    if (!aq_test_expect_read(&e[i], NULL, &r))
      continue;
    aq_check(strcmp(r.format, "bhrc") == 0, "format %s", r.format);
    aq_check(strcmp(r.station, "5522") == 0, "station %s", r.station);
    aq_check(r.reference[0] == '\0', "no start time stated, got %s", r.reference);
    /* the peak sample, at the provenance's time, to the stored digits */
    aq_check_rel(fabs(r.acc_mps2[(size_t)(t_peak_s[i] / 0.005 + 0.5)]),
                 peak_g10[i] * 0.1 * AQ_TEST_G0_MPS2, 1e-12, "%s peak sample", e[i].name);
    if (i == 1)
      aq_check(r.vertical == 1 && isnan(r.azimuth_deg), "V2 vertical %d", r.vertical);
    else
      aq_check(r.vertical == 0 && r.azimuth_deg == az[i], "%s azimuth %g", e[i].name,
               r.azimuth_deg);
    aq_record_free(&r);
  }
}

static void expect_bad(aq_status want, const char *from, const char *to, size_t cut,
                       const char *line, const char *word, const char *what)
{
  char msg[1400];
  aq_status s = aq_test_raw_altered(aq_bhrc_parse, BHRC_FILE, cut, from, to, msg, sizeof msg);
  aq_check(s == want && aq_test_msg_names(msg, BHRC_FILE, line) && strstr(msg, word), "%s: %s",
           what, msg);
}

AQ_TEST(io_bhrc_bad_input)
{
  expect_bad(AQ_EUNSUPPORTED, "* VOL1DS FILE", "* VOL2DS FILE", (size_t)-1, ":1:",
             "only VOL1DS", "another volume");
  expect_bad(AQ_EFORMAT, "DURATION =  49.920", "DURATION =  49.820", (size_t)-1, ":11:",
             "49.920 s", "duration against 200 samples/s");
  expect_bad(AQ_EFORMAT, "NO. OF POINTS =   9984", "NO. OF POINTS =   9983", (size_t)-1,
             "integer header #26", "9983", "npts against integer #26");
  expect_bad(AQ_EFORMAT, "UNITS ARE", "UNITS ARE", 133000, "data of channel 1",
             "expected 9984 values", "cut in the data");
  expect_bad(AQ_EFORMAT, "\r\n/&\r\n* VOL1DS", "\r\n   1\r\n* VOL1DS", (size_t)-1, ":1027:",
             "\"/&\"", "no end line");
}
