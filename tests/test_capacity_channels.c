/* capacity on a file of several channels, as the main job: each horizontal
 * channel a record of its own (FILE#CH), the vertical the user did not
 * name left out with one note and exit 0; naming the vertical is still
 * refused.  The rows are checked against capacity run on the horizontal
 * channels named by hand, and the note against the main job's. */
#include <stdio.h>
#include <string.h>

#include "check.h"

/* CWB text: time, U, N, E (PROVENANCE.md: the vertical first) */
#define ECU "tests/data/records/2-ECU.dat"
#define ARCH "arches/oppenheim.cfg"
#define OPTS " --arch " ARCH " --resolution 0.05 -j 2"

AQ_TEST(capacity_multichannel_file_skips_its_vertical)
{
  static char out[8192], err[2048], out2[8192], err2[2048], merr[2048];
  int rc = aq_test_run("capacity " ECU OPTS, out, sizeof out, err, sizeof err);
  aq_check(rc == 0, "exit %d (want 0): %s", rc, err);
  aq_check(aq_test_count_lines(err) == 1 && strstr(err, ECU "#U") && strstr(err, "vertical"),
           "one note naming " ECU "#U as vertical: %s", err);
  /* rows: N and E, each both polarities, as when named by hand */
  char f[256];
  aq_check(aq_test_count_lines(out) == 5, "header + 4 rows, got %zu lines",
           aq_test_count_lines(out));
  const char *want[] = {ECU "#N", ECU "#N", ECU "#E", ECU "#E"};
  for (int k = 0; k < 4; k++)
    aq_check(strcmp(aq_test_tsv_field(out, k + 1, 0, f, sizeof f), want[k]) == 0,
             "row %d: record %s, want %s", k + 1, f, want[k]);
  int rc2 = aq_test_run("capacity " ECU "#N " ECU "#E" OPTS, out2, sizeof out2, err2,
                        sizeof err2);
  aq_check(rc2 == 0 && err2[0] == '\0' && strcmp(out, out2) == 0,
           "the same rows as the channels named by hand (exit %d): %s", rc2, err2);
  /* the main job says the same about the vertical */
  rc = aq_test_run(ECU " --arch " ARCH, NULL, 0, merr, sizeof merr);
  aq_check(rc == 0 && strcmp(err, merr) == 0, "the main job's note (exit %d): %s", rc, merr);
  /* naming the vertical is still refused, in one line */
  rc = aq_test_run("capacity " ECU "#U" OPTS, out2, sizeof out2, err2, sizeof err2);
  aq_check(rc == 1 && aq_test_count_lines(err2) == 1 && strstr(err2, "vertical"),
           "naming #U: exit %d (want 1): %s", rc, err2);
}
