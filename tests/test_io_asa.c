/* test_io_asa.c: the ASA 2.0 reader (Mexican strong-motion database) on both
 * layouts, read as a user would, against tests/data/records/agency2/
 * PROVENANCE.md: CUP50401.012 (UNAM, a copy) and PRUE1004.041 (the CICESE
 * layout, written by written.py there); the first sample's date found from
 * the origin across midnight; and the refusals. */
#include <math.h>
#include <string.h>

#include "agency2_fixture.h"
#include "raw_fixture.h"

#define ASA_UNAM AGENCY2_DIR "CUP50401.012"
#define ASA_CICESE AGENCY2_DIR "PRUE1004.041"

AQ_TEST(io_asa_unam_layout)
{
  /* PROVENANCE: 17500 declared samples (17502 rows), 0.004 s, gal; peaks
   * +0.470, -1.189, +1.216 gal at 0-based rows 10590, 9513, 10051 (the
   * header's "EN LA MUESTRA") = 0.000479, 0.001212, 0.001240 g */
  static const aq_test_expect e[3] = {{ASA_UNAM "#V", 17500, 0.004, 0.000479, 5e-7, "gal"},
                                      {ASA_UNAM "#N90E", 17500, 0.004, 0.001212, 5e-7, "gal"},
                                      {ASA_UNAM "#N00E", 17500, 0.004, 0.001240, 5e-7, "gal"}};
  static const size_t at[3] = {10590, 9513, 10051};
  static const double peak_gal[3] = {0.470, -1.189, 1.216};
  static const double az[3] = {NAN, 90, 0};
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.accept_vertical = 1;
  for (int i = 0; i < 3; i++) {
    aq_record r;
    if (!aq_test_expect_read(&e[i], &ro, &r))
      continue;
    aq_check(strcmp(r.format, "asa") == 0, "format %s", r.format);
    aq_check_abs(r.acc_mps2[at[i]], peak_gal[i] * 0.01, 1e-12, "%s peak at row %zu", e[i].name,
                 at[i]);
    aq_check(strcmp(r.station, "CUP5") == 0, "station %s", r.station);
    /* HORA DE LA PRIMERA MUESTRA 00:00:01, origin 2004/01/01 23:58:02.7: the
     * next day */
    aq_check(strcmp(r.reference, "2004-01-02T00:00:01.000Z") == 0, "start %s", r.reference);
    if (i == 0)
      aq_check(r.vertical == 1, "V is vertical (the first channel)");
    else
      aq_check(!r.vertical && r.azimuth_deg == az[i], "%s azimuth %g", e[i].name,
               r.azimuth_deg);
    aq_record_free(&r);
  }
}

AQ_TEST(io_asa_cicese_layout)
{
  /* PROVENANCE (written.py): 240 samples, 0.01 s, cm/s/s; peaks 111.1262,
   * 44.4981, 89.4062 gal = 0.113317, 0.0453754, 0.091169 g */
  static const aq_test_expect e[3] = {{ASA_CICESE "#N00W", 240, 0.01, 0.113317, 5e-7, "gal"},
                                      {ASA_CICESE "#V", 240, 0.01, 0.0453754, 5e-8, "gal"},
                                      {ASA_CICESE "#N90W", 240, 0.01, 0.091169, 5e-7, "gal"}};
  static const double az[3] = {0, NAN, 270};
  aq_read_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.accept_vertical = 1;
  for (int i = 0; i < 3; i++) {
    aq_record r;
    if (!aq_test_expect_read(&e[i], &ro, &r))
      continue;
    aq_check(strcmp(r.station, "PRUE") == 0, "station %s", r.station);
    aq_check(strcmp(r.reference, "2010-04-05T00:00:07.250Z") == 0, "start %s", r.reference);
    aq_check(i == 1 ? r.vertical == 1 : !r.vertical && r.azimuth_deg == az[i],
             "%s vertical %d azimuth %g", e[i].name, r.vertical, r.azimuth_deg);
    aq_record_free(&r);
  }
}

static void expect_bad(const char *path, const char *from, const char *to, size_t cut,
                       const char *line, const char *word, const char *what)
{
  char msg[1400];
  aq_status s = aq_test_raw_altered(aq_asa_parse, path, cut, from, to, msg, sizeof msg);
  aq_check(s == AQ_EFORMAT && aq_test_msg_names(msg, path, line) && strstr(msg, word), "%s: %s",
           what, msg);
}

AQ_TEST(io_asa_bad_input)
{
  expect_bad(ASA_UNAM, "/17500/17500/17500", "/17600/17600/17600", (size_t)-1,
             "DURACION DEL REGISTRO", "70 s", "npts against the duration");
  expect_bad(ASA_UNAM, "/250/250/250", "/200/250/250", (size_t)-1, "VEL. DE MUESTREO",
             "channel 1", "rate against the interval");
  expect_bad(ASA_UNAM, "/V/N90E/N00E", "/V/N90E", (size_t)-1, ":37:", "a name for each channel",
             "two names for three channels");
  expect_bad(ASA_UNAM, "3F10.3", "3F10.3", 500000, "data", "17500 rows", "cut in the data");
  /* twenty rows past the count that are not copies of the last: the reader
     reports them, the decision refuses them naming both counts
     (test_io_extra_rows.c has the rule for every reader) */
  char dir[512], p[700], msg[1400];
  aq_test_tmpdir(dir, sizeof dir);
  if (aq_test_edited_copy(ASA_CICESE,
                          "2.40/2.40/2.40\r\nNUM. TOTAL DE MUESTRAS, C1-C6: 240/240/240",
                          "2.20/2.20/2.20\r\nNUM. TOTAL DE MUESTRAS, C1-C6: 220/220/220", dir,
                          "twenty.041", p, sizeof p)) {
    aq_read_opts ro;
    memset(&ro, 0, sizeof ro);
    aq_record r;
    aq_error e;
    strcat(p, "#N00W");
    aq_status s = aq_record_read(p, &ro, &r, &e);
    aq_error_format(&e, msg, sizeof msg);
    aq_check(s == AQ_EFORMAT && strstr(msg, "expected 220 values (NUM. TOTAL DE MUESTRAS), "
                                            "got 240: the 20 rows from line"),
             "twenty rows past the count, not copies: %s", msg);
  }
  expect_bad(ASA_CICESE, "DATOS DE ACELERACION:", "DATOS:", (size_t)-1, "header",
             "DATOS DE ACELERACION", "no data section");
}
