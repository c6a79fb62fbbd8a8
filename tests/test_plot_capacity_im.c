/* test_plot_capacity_im.c: `plot capacity --im` in every measure the
 * fragility ranks, the spectral ones included (--im sa_avg_0.1_1s_g).
 *
 * The data drawn are the fit's: per record the lower first collapse of its
 * polarities, at the measure's value there.  A spectral measure grows as
 * the scale (Sa(T) and Sa_avg of a scaled record are the scale times the
 * record's), so each point is the record's first collapse scale (from
 * capacity's TSV) times its Sa_avg at scale 1 (from `archquake info`):
 * computed here, against the --data CSV's empirical points; the median in
 * the CSV's fragility line is --fragility's for that measure.  An IM the
 * file does not hold is refused with the file's measures named. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

#define REC "tests/data/records/"
static const char *const RECS[3] = {"RSN77_SFERN_PUL164-hor1.AT2", "IELC180.AT2",
                                    "RSN763_LOMAP_GIL067.AT2"};

/* Column named name of line row (0: the header) of tab-separated text. */
static double tsv_num(const char *tsv, int row, const char *name)
{
  char head[4096];
  const char *e = strchr(tsv, '\n');
  snprintf(head, sizeof head, "%.*s", e ? (int)(e - tsv) : 0, tsv);
  int col = -1, k = 0;
  for (char *t = strtok(head, "\t"); t; t = strtok(NULL, "\t"), k++)
    if (strcmp(t, name) == 0)
      col = k;
  char buf[128];
  return col < 0 ? NAN : strtod(aq_test_tsv_field(tsv, row, col, buf, sizeof buf), NULL);
}

static int cmp(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

AQ_TEST(plot_capacity_im_spectral_measure)
{
  char dir[512], args[4096], err[2048];
  static char cap[1 << 16], info[1 << 16];
  aq_test_tmpdir(dir, sizeof dir);
  snprintf(args, sizeof args,
           "capacity " REC "%s " REC "%s " REC "%s --arch arches/oppenheim.cfg --scale-max 30 "
           "--fragility %s/f.tsv -o %s/c.h5",
           RECS[0], RECS[1], RECS[2], dir, dir);
  int rc = aq_test_run(args, cap, sizeof cap, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", args, rc, err))
    return;
  snprintf(args, sizeof args, "info " REC "%s " REC "%s " REC "%s", RECS[0], RECS[1], RECS[2]);
  rc = aq_test_run(args, info, sizeof info, err, sizeof err);
  if (!aq_check(rc == 0, "info: exit %d %s", rc, err))
    return;
  /* the fit's data: per record, the lower polarity's first collapse scale
     times the record's Sa_avg at scale 1 */
  double want[3];
  for (int r = 0; r < 3; r++) {
    double sa = tsv_num(info, r + 1, "sa_avg_0.1_1s_g");
    double fc = fmin(tsv_num(cap, 2 * r + 1, "first_collapse_scale"),
                     tsv_num(cap, 2 * r + 2, "first_collapse_scale"));
    want[r] = fc * sa;
  }
  qsort(want, 3, sizeof *want, cmp);
  snprintf(args, sizeof args,
           "plot capacity %s/c.h5 --im sa_avg_0.1_1s_g -o %s/c.svg --data %s/c.csv", dir, dir,
           dir);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  if (!aq_check(rc == 0, "%s: exit %d %s", args, rc, err))
    return;
  snprintf(args, sizeof args, "%s/c.csv", dir);
  char *csv = aq_test_read_file(args, NULL);
  double got[3];
  int n = 0;
  for (const char *p = csv ? strstr(csv, "\nempirical,") : NULL; p && n < 3;
       p = strstr(p + 1, "\nempirical,"))
    got[n++] = strtod(p + 11, NULL);
  aq_check(csv && strstr(csv, "\nseries,sa_avg_0.1_1s_g,probability\n") && n == 3,
           "--data: the fragility in sa_avg_0.1_1s_g, 3 records' first collapses (%d)", n);
  for (int i = 0; i < n; i++)
    aq_check_rel(got[i], want[i], 1e-12, "record %d: first collapse's Sa_avg", i);
  /* the median the title and the data give: --fragility's row */
  snprintf(args, sizeof args, "%s/f.tsv", dir);
  char *f = aq_test_read_file(args, NULL);
  double med = NAN;
  for (int row = 1; f && row < 40; row++) {
    char buf[64];
    if (strcmp(aq_test_tsv_field(f, row, 1, buf, sizeof buf), "sa_avg_0.1_1s_g") == 0)
      med = strtod(aq_test_tsv_field(f, row, 4, buf, sizeof buf), NULL);
  }
  const char *line = csv ? strstr(csv, "im=sa_avg_0.1_1s_g median=") : NULL;
  aq_check(line && isfinite(med) && strtod(line + 26, NULL) == med,
           "the fit drawn is --fragility's (median %.17g)", med);
  /* the figure's axis names the measure */
  snprintf(args, sizeof args, "%s/c.svg", dir);
  char *svg = aq_test_read_file(args, NULL);
  aq_check(svg && strstr(svg, "Sa") && strstr(svg, "over 0.1–1 s (g)"),
           "the axis: Sa_avg over 0.1–1 s (g)");
  free(svg);
  free(f);
  free(csv);
  /* a measure the file does not hold: refused, the file's named */
  snprintf(args, sizeof args, "plot capacity %s/c.h5 --im sa_3s_g -o %s/x.png", dir, dir);
  rc = aq_test_run(args, NULL, 0, err, sizeof err);
  aq_check(rc == 2 && strstr(err, "--im: expected one of the file's measures (pga_g") &&
               strstr(err, "sa_avg_0.1_1s_g), got \"sa_3s_g\""),
           "an IM not in the file: exit %d %s", rc, err);
}

/* plot --help says so: the capacity figure's paragraph names the spectral
 * measures among those --im takes, as --im's own line does. */
AQ_TEST(plot_capacity_im_help)
{
  static char out[1 << 16];
  char err[2048];
  int rc = aq_test_run("plot --help", out, sizeof out, err, sizeof err);
  const char *fig = strstr(out, "  capacity CAPACITY.h5");
  const char *end = fig ? strstr(fig, "\n  spectrum SPECTRA.h5") : NULL;
  const char *sa = fig ? strstr(fig, "sa_avg_0.1_1s_g") : NULL;
  const char *opt = strstr(out, "  --im IM");
  aq_check(rc == 0 && end && sa && sa < end && opt && strstr(opt, "sa_avg_0.1_1s_g"),
           "plot --help: the capacity figure and --im both name sa_avg_0.1_1s_g:\n%s", out);
}
