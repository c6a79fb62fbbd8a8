/* test_io_nsmn.c: the NSMN/AFAD (Turkey) ASCII reader, read as a user would,
 * against tests/data/records/agency2/PROVENANCE.md (TK9999-20110305.txt,
 * written by written.py there from the format's description, with
 * ISO-8859-9 bytes in its header), and its refusals. */
#include <math.h>
#include <string.h>

#include "agency2_fixture.h"
#include "raw_fixture.h"

#define NSMN_FILE AGENCY2_DIR "TK9999-20110305.txt"

AQ_TEST(io_nsmn_three_columns)
{
  /* PROVENANCE (written.py): 300 rows, SAMPLING INTERVAL (sec) 0.01, gal;
   * peaks 164.214523, 136.259538, 58.487743 gal = 0.1674522, 0.1389461,
   * 0.0596409 g */
  static const aq_test_expect e[3] = {{NSMN_FILE "#N-S", 300, 0.01, 0.1674522, 5e-8, "gal"},
                                      {NSMN_FILE "#E-W", 300, 0.01, 0.1389461, 5e-8, "gal"},
                                      {NSMN_FILE "#U-D", 300, 0.01, 0.0596409, 5e-8, "gal"}};
  static const double az[3] = {0, 90, NAN};
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.accept_vertical = 1;
  ro.dt_s = 0.02; /* a --dt for files that state none: not this one */
  for (int i = 0; i < 3; i++) {
    aq_record r;
    if (!aq_test_expect_read(&e[i], &ro, &r))
      continue;
    aq_check(strcmp(r.format, "nsmn") == 0, "format %s", r.format);
    aq_check(strcmp(r.station, "9999") == 0 && strcmp(r.network, "TK") == 0, "station %s.%s",
             r.network, r.station);
    aq_check(strcmp(r.reference, "2011-03-05T12:34:56.500Z") == 0, "start %s", r.reference);
    aq_check(i == 2 ? r.vertical == 1 : !r.vertical && r.azimuth_deg == az[i],
             "%s vertical %d azimuth %g", e[i].name, r.vertical, r.azimuth_deg);
    aq_record_free(&r);
  }
}

static void expect_bad(const char *from, const char *to, size_t cut, const char *line,
                       const char *word, const char *what)
{
  char msg[1400];
  aq_status s = aq_test_raw_altered(aq_nsmn_parse, NSMN_FILE, cut, from, to, msg, sizeof msg);
  aq_check(s == AQ_EFORMAT && aq_test_msg_names(msg, NSMN_FILE, line) && strstr(msg, word),
           "%s: %s", what, msg);
}

AQ_TEST(io_nsmn_bad_input)
{
  expect_bad(": 300\r\n", ": 301\r\n", (size_t)-1, "data", "the file ends after 300",
             "one row short");
  /* one row over the count, not a copy of the last: refused by the decision
     (test_io_extra_rows.c) naming both counts */
  {
    char dir[512], p[700], msg[1400];
    aq_test_tmpdir(dir, sizeof dir);
    if (aq_test_edited_copy(NSMN_FILE, ": 300\r\n", ": 299\r\n", dir, "over.txt", p, sizeof p)) {
      aq_read_opts ro;
      memset(&ro, 0, sizeof ro);
      aq_record r;
      aq_error e;
      strcat(p, "#N-S");
      aq_status s = aq_record_read(p, &ro, &r, &e);
      aq_error_format(&e, msg, sizeof msg);
      aq_check(s == AQ_EFORMAT && strstr(msg, "expected 299 values (NUMBER OF DATA), got 300"),
               "one row over: %s", msg);
    }
  }
  expect_bad("(sec)        : 0.01", "(sec)        : 0", (size_t)-1, ":14:",
             "SAMPLING INTERVAL", "dt 0");
  expect_bad("NUMBER OF DATA", "NUMBER OF ROWS", (size_t)-1, "NUMBER OF DATA", "count",
             "no count");
}
