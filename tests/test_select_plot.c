/* test_select_plot.c: the figure of a suite against its target (`plot
 * spectrum` of a select file, or of a spectrum file with --target) and the
 * report's suite section.  The plotted numbers (--data) against what the
 * figure must show: the target from EN 1998-1:2004 eqs. (3.2)-(3.5) (type
 * 1, ground B, Table 3.2) computed here, each record's spectrum at its
 * scale (the suite file's scale times the file's unscaled spectrum), the
 * mean of the plotted spectra; the page holds the section, its checks and
 * its figure; bad input refused in one line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "select_fixture.h"
#include "report/h5_select.h"

#define R "tests/data/records/"
#define EC8B AQ_TEST_EC8B
enum { BIG = 1 << 20 };

static const char *const pool =
    R "RSN6_IMPVALL.I_I-ELC180-hor1.AT2 " R "RSN763_LOMAP_GIL067.AT2 " R "ARL360.at2 "
    R "CHY028-N.AT2 " R "RSN4843_CHUETSU_65006NS.AT2 " R "kocaeli.csv";

AQ_TEST(select_plot_suite_against_target)
{
  char dir[256], args[2048], err[8192], b[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args, "select %s --target " EC8B " --count 4 --scale-range 0.1,10 -o "
           "%s/s.h5 --text %s/s.tsv", pool, dir, dir);
  if (!aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "select: %s", err))
    return;
  for (int k = 0; k < 2; k++) {
    snprintf(args, sizeof args, "plot spectrum %s/s.h5 -o %s/f.%s --data %s/f%d.csv", dir, dir,
             k ? "svg" : "png", dir, k);
    int rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 0, "plot: exit %d: %s", rc, err);
  }
  snprintf(b, sizeof b, "%s/f.png", dir);
  char *png = aq_test_read_file(b, NULL);
  aq_check(png && !memcmp(png, "\x89PNG\r\n\x1a\n", 8), "a PNG");
  free(png);
  snprintf(b, sizeof b, "%s/f.svg", dir);
  char *svg = aq_test_read_file(b, NULL);
  aq_check(svg && strstr(svg, "<svg") && strstr(svg, "period T (s)"), "an SVG, its axis titled");
  free(svg);
  /* the plotted numbers */
  aq_h5_select_file f;
  aq_error e;
  snprintf(b, sizeof b, "%s/s.h5", dir);
  if (!aq_check(aq_h5_select_read(b, &f, &e) == AQ_OK && f.n == 4, "read back: %s", e.message))
    return;
  snprintf(b, sizeof b, "%s/f0.csv", dir);
  FILE *csv = fopen(b, "r");
  char line[1024];
  size_t ntarget = 0, nmean = 0, ncurve = 0;
  double *sum = calloc(f.nper, sizeof *sum), *mean = calloc(f.nper, sizeof *mean);
  while (csv && fgets(line, sizeof line, csv)) {
    if (line[0] == '#' || !strncmp(line, "curve,", 6))
      continue;
    char *c1 = strrchr(line, ','), *c0 = c1;
    *c1 = '\0';
    c0 = strrchr(line, ',');
    double T = strtod(c0 + 1, NULL), a = strtod(c1 + 1, NULL);
    *c0 = '\0';
    const char *name = line[0] == '"' ? line + 1 : line;
    if (!strcmp(name, "target")) {
      aq_check_rel(a, aq_test_ec8_b(T), 1e-12, "the target at %g s", T);
      ntarget++;
      continue;
    }
    size_t k = 0;
    while (k < f.nper && f.period_s[k] != T)
      k++;
    if (!aq_check(k < f.nper, "%s: a period of the grid: %g", name, T))
      continue;
    if (!strcmp(name, "mean")) {
      mean[k] = a;
      nmean++;
      continue;
    }
    size_t j = 0;
    while (j < f.n && strncmp(name, f.record[j], strlen(f.record[j])))
      j++;
    if (!aq_check(j < f.n, "a record of the suite: %s", name))
      continue;
    aq_check_rel(a, f.scale[j] * f.psa_g[j * f.nper + k], 1e-15,
                 "%s at %g s: its spectrum at its scale", f.record[j], T);
    sum[k] += a;
    ncurve++;
  }
  if (csv)
    fclose(csv);
  aq_check(ntarget > 10 && nmean == f.nper && ncurve == f.n * f.nper,
           "target %zu points, mean %zu, curves %zu", ntarget, nmean, ncurve);
  for (size_t k = 0; k < f.nper; k++)
    aq_check_rel(mean[k], sum[k] / (double)f.n, 1e-13, "the mean at %g s", f.period_s[k]);
  free(sum);
  free(mean);
  aq_h5_select_file_free(&f);
  /* the report: the suite's section, its checks and its figure */
  snprintf(args, sizeof args, "--suite %s/s.tsv --arch arches/oppenheim.cfg -o %s/r.h5", dir,
           dir);
  aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "the main job: %s", err);
  snprintf(args, sizeof args, "report %s/r.h5 %s/s.h5 -o %s/r.html", dir, dir, dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "report: exit %d: %s", rc, err);
  snprintf(b, sizeof b, "%s/r.html", dir);
  char *html = aq_test_read_file(b, NULL);
  const char *sec = html ? strstr(html, "<h2 id=\"select-0\">Suite: s.h5") : NULL;
  aq_check(sec && strstr(sec, "EN 1998-1:2004 3.2.2.2") && strstr(sec, "<td>band</td>") &&
               strstr(sec, "<svg") && strstr(sec, "<th>scale</th>") &&
               strstr(html, "href=\"#select-0\""),
           "the page's suite section: target, checks, figure, records");
  free(html);
  /* a select file first: refused, naming it */
  snprintf(args, sizeof args, "report %s/s.h5 -o %s/q.html", dir, dir);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 1 && strstr(err, "s.h5") && strstr(err, "select") &&
               aq_test_count_lines(err) == 1 && aq_test_count_names(dir, "q.html") == 0,
           "a select file first: exit %d: %s", rc, err);
}

/* A spectrum file's spectra against a target; bad --target refused. */
AQ_TEST(select_plot_spectrum_file_target)
{
  char dir[256], args[2048], err[8192], b[600];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args, "spectrum " R "ARL360.at2 " R "CHY028-N.AT2 --periods "
           "0.1,0.2,0.3,0.5,0.8,1 -o %s/sp.h5", dir);
  if (!aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "spectrum: %s", err))
    return;
  snprintf(args, sizeof args, "plot spectrum %s/sp.h5 --target " EC8B " -o %s/f.png --data "
           "%s/f.csv", dir, dir, dir);
  int rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 0, "exit %d: %s", rc, err);
  snprintf(b, sizeof b, "%s/f.csv", dir);
  char *csv = aq_test_read_file(b, NULL);
  aq_check(csv && strstr(csv, "\nmean,") && strstr(csv, "\ntarget,") &&
               strstr(csv, "ARL360.at2"), "target, mean and the records plotted");
  free(csv);
  static const struct {
    const char *opts, *says;
  } bad[] = {
      {"--target ec8:type=1,ground=Q,ag=0.2", "ground"},
      {"--target asce7:sds=1", "sd1"},
  };
  for (size_t i = 0; i < 2; i++) {
    snprintf(args, sizeof args, "plot spectrum %s/sp.h5 %s -o %s/g.png", dir, bad[i].opts, dir);
    rc = aq_test_run(args, NULL, 0, err, sizeof err);
    aq_check(rc == 2 && strstr(err, bad[i].says) && aq_test_count_lines(err) == 1 &&
                 aq_test_count_names(dir, "g.png") == 0,
             "%s: exit %d: %s", bad[i].opts, rc, err);
  }
  snprintf(args, sizeof args, "select %s --target " EC8B " --count 3 --scale-range 0.1,10 -o "
           "%s/s.h5", pool, dir);
  aq_check(aq_test_run(args, NULL, 0, err, sizeof err) == 0, "select: %s", err);
  snprintf(args, sizeof args, "plot spectrum %s/s.h5 --record x -o %s/g.png", dir, dir);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--record") && aq_test_count_lines(err) == 1 &&
               aq_test_count_names(dir, "g.png") == 0,
           "--record with a select file: exit %d: %s", rc, err);
}
