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

AQ_TEST(report_text_aligned_columns)
{
  aq_summary s[3];
  aq_result r;
  memset(&r, 0, sizeof r);
  r.collapsed = 1;
  r.collapse_time_s = 12.3456789;
  r.peak_rotation_rad = -2.2250738585072014e-308;
  r.peak_displacement_m = 0.0216298185;
  r.max_kinetic_energy_j = 98765.4321;
  r.impacts = 123456;
  aq_summary_fill(&s[0], "records/a-very-long-record-name.AT2", "oppenheim", "workpath",
                  1.5, 0.28081234, "ok", &r);
  aq_summary_fill(&s[1], "r.sac", "t", "ode", 0.25, 1e-300, "process:einadmissible",
                  NULL);
  aq_summary_fill(&s[2], "x.csv", "thin", "paper", 2, 0.5, "ok", &r);
  char dir[512], path[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(path, sizeof path, "%s/t.txt", dir);
  FILE *f = fopen(path, "w+");
  if (!aq_check(f != NULL, "open"))
    return;
  aq_text_layout L;
  aq_text_layout_init(&L, strlen("records/a-very-long-record-name.AT2"), strlen("oppenheim"));
  aq_check(aq_text_header_aligned(f, &L) == 0, "header");
  for (int i = 0; i < 3; i++)
    aq_check(aq_text_row_aligned(f, &L, &s[i]) == 0, "row %d", i);
  rewind(f);
  /* every line has the same length, and every column boundary (two spaces
   * before a cell) is at the same offset in every line */
  char line[4][2048];
  size_t len[4];
  for (int i = 0; i < 4; i++) {
    aq_check(fgets(line[i], sizeof line[i], f) != NULL, "line %d", i);
    len[i] = strlen(line[i]);
  }
  fclose(f);
  for (int i = 1; i < 4; i++)
    aq_check(len[i] == len[0], "line %d length %zu = %zu", i, len[i], len[0]);
  /* each column occupies width[i] characters followed by two spaces, in
   * the header and in every row, and no cell is empty */
  for (int i = 0; i < 4; i++) {
    size_t at = 0;
    for (size_t c = 0; c < aq_summary_nfields; c++) {
      size_t w = (size_t)L.width[c];
      int blank = 1;
      for (size_t k = at; k < at + w && k < len[i]; k++)
        blank &= line[i][k] == ' ';
      aq_check(!blank, "line %d column %zu not empty", i, c);
      if (c + 1 < aq_summary_nfields)
        aq_check(line[i][at + w] == ' ' && line[i][at + w + 1] == ' ',
                 "line %d: separator after column %zu at %zu", i, c, at + w);
      at += w + 2;
    }
    aq_check(at - 2 + 1 == len[i], "line %d ends after the last column", i);
  }
  /* numbers: 6 significant digits */
  char *tok, *save = NULL;
  int col = 0;
  for (tok = strtok_r(line[1], " \n", &save); tok; tok = strtok_r(NULL, " \n", &save), col++) {
    if (col == 7)
      aq_check_rel(strtod(tok, NULL), 12.3456789, 5e-6, "collapse time %s", tok);
    if (col == 10)
      aq_check_rel(strtod(tok, NULL), 98765.4321, 5e-6, "KE %s", tok);
    if (col == 11)
      aq_check(strcmp(tok, "123456") == 0, "impacts exact %s", tok);
  }
  aq_check(col == (int)aq_summary_nfields, "%d cells", col);
  aq_check(strstr(line[2], "process:einadmissible") != NULL && strstr(line[2], "nan"),
           "failed row readable");
}
