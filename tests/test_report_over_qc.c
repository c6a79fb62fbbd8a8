/* test_report_over_qc.c: peak_rotation_over_qc is the largest |q| / q_c
 * over both hinge sets: exactly 1 for a run that collapsed, whatever the
 * other set reached first.  San Fernando (RSN77) on oppenheim at scale 5,
 * normal polarity, swings further on the reverse set (q_c 0.3057 rad) than
 * the primary's q_c (0.2286 rad), then collapses on the primary: 1, not the
 * reverse peak over the reverse q_c.  Every other run of scales 1 to 5 lies
 * between peak_rotation_rad over the larger and over the smaller q_c, which
 * `archquake mechanism` prints (the bounds of a maximum over two sets). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arch/result.h"
#include "check.h"

/* Column name of the TSV text's header: its index, or -1. */
static int column(const char *text, const char *name)
{
  int col = 0;
  size_t len = strlen(name);
  for (const char *p = text; *p && *p != '\n'; col++) {
    size_t w = strcspn(p, "\t\n");
    if (w == len && strncmp(p, name, len) == 0)
      return col;
    p += w;
    if (*p == '\t')
      p++;
  }
  return -1;
}

/* Cell (row, col) of the TSV text (row 0 the header) into buf. */
static const char *cell(const char *text, int row, int col, char *buf, size_t cap)
{
  const char *p = text;
  for (int r = 0; r < row && p; r++)
    if ((p = strchr(p, '\n')))
      p++;
  for (int c = 0; c < col && p; c++)
    if ((p = strpbrk(p, "\t\n")) && *p == '\t')
      p++;
    else
      p = NULL;
  size_t w = p ? strcspn(p, "\t\n") : 0;
  snprintf(buf, cap, "%.*s", (int)(w < cap ? w : cap - 1), p ? p : "");
  return buf;
}

AQ_TEST(report_over_qc_collapse_is_one)
{
  static char out[65536];
  char err[4096], b[64];
  /* q_c of both sets, from the mechanism table */
  int rc = aq_test_run("mechanism --arch arches/oppenheim.cfg", out, sizeof out, err, sizeof err);
  int cq = column(out, "q_c_rad");
  if (!aq_check(rc == 0 && cq >= 0, "mechanism: %d %s", rc, err))
    return;
  double qcp = strtod(cell(out, 1, cq, b, sizeof b), NULL);
  double qcr = strtod(cell(out, 2, cq, b, sizeof b), NULL);
  aq_check(qcp > 0.2 && qcr > 0.3,
           "q_c %g %g", qcp, qcr);
  rc = aq_test_run("tests/data/records/RSN77_SFERN_PUL164-hor1.AT2 --arch arches/oppenheim.cfg "
                   "--scale 1,2,3,4,5 --polarity both",
                   out, sizeof out, err, sizeof err);
  int cs = column(out, "scale"), cp = column(out, "polarity"), cc = column(out, "collapsed"),
      cr = column(out, "peak_rotation_rad"), co = column(out, "peak_rotation_over_qc");
  if (!aq_check(rc == 0 && aq_test_count_lines(out) == 11 && cs >= 0 && co >= 0, "run: %d %s",
                rc, err))
    return;
  int seen_key = 0;
  for (int row = 1; row <= 10; row++) {
    double scale = strtod(cell(out, row, cs, b, sizeof b), NULL);
    int normal = strcmp(cell(out, row, cp, b, sizeof b), "normal") == 0;
    int collapsed = atoi(cell(out, row, cc, b, sizeof b));
    double peak = strtod(cell(out, row, cr, b, sizeof b), NULL);
    double over = strtod(cell(out, row, co, b, sizeof b), NULL);
    if (collapsed) {
      aq_check(over == 1.0, "scale %g %s: collapsed, over q_c %.17g", scale,
               normal ? "normal" : "reversed", over);
    } else {
      double lo = peak / fmax(qcp, qcr), hi = peak / fmin(qcp, qcr);
      aq_check(over >= lo * (1 - 1e-9) && over <= hi * (1 + 1e-9) && over < 1,
               "scale %g: %.17g outside [%g, %g]", scale, over, lo, hi);
    }
    if (scale == 5 && normal) {
      seen_key = 1;
      /* the case the definition is about: a reverse peak above the
       * primary's q_c, then collapse on the primary */
      aq_check(collapsed && peak > qcp * 1.05 && peak < qcr, "RSN77 x5: collapsed %d peak %g",
               collapsed, peak);
    }
  }
  aq_check(seen_key, "RSN77 at scale 5, normal, in the rows");
}

/* The function itself on a made-up result: paths with q_c 0.25 and 0.5. */
AQ_TEST(report_over_qc_largest_over_both_sets)
{
  aq_path p = {.s_c_rad = 0.25, .admissible = 1}, r = {.s_c_rad = 0.5, .admissible = 1};
  aq_result res;
  memset(&res, 0, sizeof res);
  res.peak_rotation_set_rad[0] = 0.2;
  res.peak_rotation_set_rad[1] = 0.3; /* the larger |q|, the smaller ratio (0.6) */
  aq_check_rel(aq_result_peak_over_qc(&res, &p, &r), 0.8, 1e-15, "0.2/0.25");
  res.peak_rotation_set_rad[0] = 0;
  aq_check_rel(aq_result_peak_over_qc(&res, &p, &r), 0.6, 1e-15, "0.3/0.5");
  aq_check(isnan(aq_result_peak_over_qc(&res, &p, NULL)), "moved on a set with no path");
  res.peak_rotation_set_rad[1] = 0;
  aq_check(aq_result_peak_over_qc(&res, &p, NULL) == 0, "never moved");
}
