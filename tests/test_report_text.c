/* test_report_text.c: the TSV summary writer, read back with the C
 * library's own parser (strtod/strtoll), on high-entropy synthetic runs. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "report/report.h"
#include "report/text.h"

/* Split line (modified in place) at tabs; returns the number of cells. */
static size_t split_tabs(char *line, char **cell, size_t max)
{
  size_t n = 0;
  char *p = line;
  while (n < max) {
    cell[n++] = p;
    char *t = strchr(p, '\t');
    if (!t)
      break;
    *t = '\0';
    p = t + 1;
  }
  char *nl = strchr(cell[n - 1], '\n');
  if (nl)
    *nl = '\0';
  return n;
}

AQ_TEST(report_text_rows_read_back)
{
  aq_summary s[3];
  aq_result r;
  memset(&r, 0, sizeof r);
  r.collapsed = 1;
  r.collapse_time_s = 7.3849201937465521;
  r.peak_rotation_rad = 0.123456789012345678;
  r.peak_displacement_m = 3.0517578125e-05 * 1.7;
  r.max_kinetic_energy_j = 12345.678901234567;
  r.impacts = 17;
  r.energy_in_j = 98765.4321;
  r.energy_dissipated_j = 1.0 / 3.0;
  aq_summary_fill(&s[0], "records/a\tb.AT2", "oppenheim", "workpath", 1.35,
                  0.28081234567891234, "ok", &r);
  r.collapsed = 0;
  r.collapse_time_s = -NAN; /* glibc prints "-nan" for this one */
  r.impacts = 0;
  r.peak_rotation_rad = 2.2250738585072014e-308;
  aq_summary_fill(&s[1], "records/x.sac", "thin arch", "ode", 0.5, 1e-300,
                  "ok", &r);
  aq_summary_fill(&s[2], "bad.AT2", "oppenheim", "workpath", 2.0, NAN,
                  "read:eformat", NULL);

  char dir[512], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/out.tsv", dir);
  FILE *f = fopen(path, "w");
  aq_check(f != NULL, "open %s", path);
  if (!f)
    return;
  aq_check(aq_text_header(f) == 0, "header");
  for (int i = 0; i < 3; i++)
    aq_check(aq_text_row(f, &s[i]) == 0, "row %d", i);
  aq_check(fclose(f) == 0, "close");

  f = fopen(path, "r");
  char line[4096], *cell[64];
  aq_check(fgets(line, sizeof line, f) != NULL, "header line");
  static const char *const want_cols[] = {
      "record", "arch", "model", "scale", "pga_g", "status", "collapsed",
      "collapse_time_s", "peak_rotation_rad", "peak_displacement_m",
      "max_kinetic_energy_j", "impacts"};
  size_t nc = split_tabs(line, cell, 64);
  aq_check(nc >= 12, "at least the 12 issue columns: %zu", nc);
  for (size_t i = 0; i < 12 && i < nc; i++)
    aq_check(strcmp(cell[i], want_cols[i]) == 0, "column %zu: %s", i, cell[i]);

  /* row 0 */
  aq_check(fgets(line, sizeof line, f) != NULL, "row 0");
  nc = split_tabs(line, cell, 64);
  aq_check(nc == aq_summary_nfields, "cells %zu", nc);
  aq_check(strcmp(cell[0], "records/a b.AT2") == 0, "tab in a name: %s", cell[0]);
  aq_check(strtod(cell[3], NULL) == 1.35, "scale exact");
  aq_check(strtod(cell[4], NULL) == 0.28081234567891234, "pga exact");
  aq_check(strcmp(cell[5], "ok") == 0, "status");
  aq_check(strcmp(cell[6], "1") == 0, "collapsed");
  aq_check(strtod(cell[7], NULL) == 7.3849201937465521, "collapse time exact");
  aq_check(strtod(cell[8], NULL) == 0.123456789012345678, "rotation exact");
  aq_check(strtod(cell[9], NULL) == 3.0517578125e-05 * 1.7, "displacement exact");
  aq_check(strtod(cell[10], NULL) == 12345.678901234567, "KE exact");
  aq_check(strtoll(cell[11], NULL, 10) == 17, "impacts");
  aq_check(strtod(cell[13], NULL) == 1.0 / 3.0, "dissipated exact");

  /* row 1: survived: collapse time "nan" whatever the NaN's sign */
  aq_check(fgets(line, sizeof line, f) != NULL, "row 1");
  nc = split_tabs(line, cell, 64);
  aq_check(strcmp(cell[6], "0") == 0, "survived");
  aq_check(strcmp(cell[7], "nan") == 0, "collapse_time_s nan: %s", cell[7]);
  aq_check(strtod(cell[4], NULL) == 1e-300, "tiny pga exact");
  aq_check(strtod(cell[8], NULL) == 2.2250738585072014e-308, "DBL_MIN exact");

  /* row 2: failed record */
  aq_check(fgets(line, sizeof line, f) != NULL, "row 2");
  nc = split_tabs(line, cell, 64);
  aq_check(strcmp(cell[5], "read:eformat") == 0, "status code: %s", cell[5]);
  for (size_t i = 7; i <= 10; i++)
    aq_check(strcmp(cell[i], "nan") == 0, "failed run cell %zu nan: %s", i,
             cell[i]);
  aq_check(fgets(line, sizeof line, f) == NULL, "three rows only");
  fclose(f);
}

AQ_TEST(report_text_status_codes)
{
  char b[64];
  aq_summary_status(b, sizeof b, "read", AQ_EFORMAT);
  aq_check(strcmp(b, "read:eformat") == 0, "%s", b);
  aq_summary_status(b, sizeof b, "run", AQ_ENUMERIC);
  aq_check(strcmp(b, "run:enumeric") == 0, "%s", b);
  aq_summary_status(b, sizeof b, "run", AQ_OK);
  aq_check(strcmp(b, "ok") == 0, "%s", b);
}

AQ_TEST(report_text_write_error_reported)
{
  /* /dev/full: every write fails with ENOSPC once the buffer is flushed */
  FILE *f = fopen("/dev/full", "w");
  if (!aq_check(f != NULL, "open /dev/full"))
    return;
  setvbuf(f, NULL, _IONBF, 0);
  aq_summary s;
  aq_summary_fill(&s, "r", "a", "workpath", 1, 0.5, "ok", NULL);
  aq_check(aq_text_header(f) == -1, "header write fails");
  aq_check(aq_text_row(f, &s) == -1, "row write fails");
  fclose(f);
}
