/* test_pin.c: the program's outputs pinned to those recorded before the
 * record-to-result path was restructured (tests/data/pin/README.md).
 *
 * tests/pin.sh runs every case of tests/data/pin/cases with the program
 * under test: the main job's TSV (five arches, several scales, both
 * polarities, scaled to a PGA and to K lambda0, every model, the
 * processing options, --components at every azimuth, with and without the
 * vertical), capacity's TSV and --fragility byte for byte; the results
 * files through `archquake compare` and h5diff; -j 1 against -j 2 and 3.
 * The references come from the program itself, on purpose: this test
 * says that nothing changed, not that anything is right (the other tests
 * do that). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "check.h"

AQ_TEST(pin_outputs_unchanged)
{
  char dir[512], log[700], cmd[2048];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(log, sizeof log, "%s/pin.log", dir);
  snprintf(cmd, sizeof cmd, "TMPDIR='%s' AQ_BIN='%s' sh tests/pin.sh >'%s' 2>&1 </dev/null",
           dir, aq_test_bin(), log);
  int rc = system(cmd);
  char *out = aq_test_read_file(log, NULL);
  const char *last = NULL;
  if (out) { /* the last line: "N passed, N failed" */
    size_t n = strlen(out);
    while (n > 0 && out[n - 1] == '\n')
      out[--n] = '\0';
    last = strrchr(out, '\n');
    last = last ? last + 1 : out;
  }
  unsigned passed = 0, failed = 1;
  int parsed = last && sscanf(last, "%u passed, %u failed", &passed, &failed) == 2;
  aq_check(rc != -1 && WIFEXITED(rc) && WEXITSTATUS(rc) == 0 && parsed && failed == 0 &&
               passed >= 30,
           "tests/pin.sh: every pinned output unchanged (exit %d):\n%s",
           rc != -1 && WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, out ? out : "(no output)");
  free(out);
}
