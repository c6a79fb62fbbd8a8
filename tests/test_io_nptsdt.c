/* test_io_nptsdt.c: text whose first line is "NPTS DT" (OpenSees examples),
 * read as a user would, against tests/data/records/agency2/PROVENANCE.md
 * (two files written by written.py there: values, and (time, value)
 * pairs); the file's DT over --dt; and the refusals. */
#include <string.h>

#include "agency2_fixture.h"
#include "raw_fixture.h"

#define NPTSDT_VALUES AGENCY2_DIR "npts-dt-values.txt"
#define NPTSDT_PAIRS AGENCY2_DIR "npts-dt-pairs.txt"

AQ_TEST(io_nptsdt_values_and_pairs)
{
  /* PROVENANCE (written.py): 403 values at 0.02 s, peak 0.266983 g; 350
   * pairs at 0.005 s, peak 0.0799120 g; neither states units */
  static const aq_test_expect e[2] = {{NPTSDT_VALUES, 403, 0.02, 0.266983, 5e-7, ""},
                                      {NPTSDT_PAIRS, 350, 0.005, 0.0799120, 5e-8, ""}};
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.units = AQ_UNITS_G; /* --units g: the files state none */
  ro.dt_s = 0.01;        /* --dt: for files that state none, not these */
  for (int i = 0; i < 2; i++) {
    aq_record r;
    if (!aq_test_expect_read(&e[i], &ro, &r))
      continue;
    aq_check(strcmp(r.format, "npts-dt") == 0 && strcmp(r.units_used, "g") == 0,
             "%s: format %s units %s", e[i].name, r.format, r.units_used);
    aq_check(r.channel[0] == '\0', "%s: no channel name (got \"%s\")", e[i].name, r.channel);
    aq_record_free(&r);
  }
  /* without --units: refused for want of units, not for its layout */
  aq_record r;
  aq_error err;
  memset(&ro, 0, sizeof ro);
  aq_check(aq_record_read(NPTSDT_VALUES, &ro, &r, &err) == AQ_EUNITS &&
               strstr(err.message, "--units"),
           "no units: %s", err.message);
}

static void expect_bad(const char *path, const char *from, const char *to, const char *line,
                       const char *word, const char *what)
{
  char msg[1400];
  aq_status s = aq_test_raw_altered(aq_nptsdt_parse, path, (size_t)-1, from, to, msg, sizeof msg);
  aq_check(s == AQ_EFORMAT && aq_test_msg_names(msg, path, line) && strstr(msg, word), "%s: %s",
           what, msg);
}

AQ_TEST(io_nptsdt_bad_input)
{
  expect_bad(NPTSDT_VALUES, "403 0.02", "404 0.02", ":1:", "got 403 numbers",
             "one value short");
  expect_bad(NPTSDT_PAIRS, "0.010\t", "0.011\t", ":4:", "expected 0.01 s", "a time off the grid");
  expect_bad(NPTSDT_PAIRS, "350  0.005", "350  0.004", ":3:", "time", "DT against the times");
  expect_bad(NPTSDT_VALUES, "403 0.02", "403 0", ":1:", "NPTS DT", "DT 0");
}
