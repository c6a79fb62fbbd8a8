/* capacity.c: the capacity results of one arch (`archquake capacity`): for
 * each (record, polarity), the scale factors it was scanned over (from the
 * scale below which the arch never moves to the cap), the collapse
 * intervals shaded, so that a resurrection (survival above a first
 * collapse) shows as a gap in the red.  The fragility fits are not drawn
 * (see docs/plot.md). */
#include <math.h>
#include <plplot.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

static const char *const AX_SCALE = "scale factor on the processed record (1)";

typedef struct {
  const aq_h5_capacity_table *t;
  const char *arch;
  size_t *row; /* rows of this arch */
  size_t n;
} cap;

enum { D_MOVE = 0, D_FIRST = 1, D_SMAX = 4, I_START = 2, I_COUNT = 3, I_RES = 0 };

static const char *base(const char *p)
{
  const char *b = strrchr(p, '/');
  return b ? b + 1 : p;
}

static int draw(void *ctx, aq_error *err)
{
  (void)err;
  const cap *c = ctx;
  const aq_h5_capacity_table *t = c->t;
  double hi = 0;
  for (size_t k = 0; k < c->n; k++)
    hi = fmax(hi, t->row[c->row[k]].d[D_SMAX]);
  if (!(hi > 0))
    hi = 1;
  pladv(0);
  plschr(0, 0.85);
  plvpor(0.38, 0.95, 0.22, 0.9);
  plwind(0, hi * 1.02, (double)c->n, 0);
  for (size_t k = 0; k < c->n; k++) {
    const aq_h5_capacity_row *r = &t->row[c->row[k]];
    double y = k + 0.5, lo = isfinite(r->d[D_MOVE]) ? r->d[D_MOVE] : 0;
    PLFLT x[2] = {fmin(lo, r->d[D_SMAX]), r->d[D_SMAX]}, yy[2] = {y, y};
    plcol0(AQ_PC_GREY);
    plwidth(2);
    plline(2, x, yy);
    plwidth(1);
    for (int64_t j = 0; j < r->i[I_COUNT]; j++) {
      size_t q = (size_t)(r->i[I_START] + j);
      if (q >= t->ninterval)
        break;
      double a = t->interval[2 * q], b = fmin(t->interval[2 * q + 1], r->d[D_SMAX]);
      PLFLT fx[4] = {a, b, b, a}, fy[4] = {y - 0.3, y - 0.3, y + 0.3, y + 0.3};
      plcol0(AQ_PC_RED);
      plfill(4, fx, fy);
    }
    char lab[300];
    snprintf(lab, sizeof lab, "%.28s%s", base(r->record),
             strcmp(r->polarity, "reversed") == 0 ? " (rev.)" : "");
    plcol0(AQ_PC_FG);
    plmtex("lv", 0.8, 1 - y / (double)c->n, 1, lab);
  }
  plcol0(AQ_PC_FG);
  plbox("bcnst", 0, 0, "bc", 0, 0);
  plmtex("b", 3.2, 0.5, 0.5, AX_SCALE);
  char title[256];
  snprintf(title, sizeof title, "collapse capacity of arch %s", c->arch);
  plmtex("t", 1.5, 0.5, 0.5, title);
  plvpor(0.38, 0.95, 0.01, 0.1);
  const char *tx[] = {"scanned (arch moves)", "collapse"};
  int col[] = {AQ_PC_GREY, AQ_PC_RED}, st[] = {1, -1};
  aq_plot_legend(PL_POSITION_INSIDE | PL_POSITION_TOP, 2, tx, col, st, NULL);
  return 0;
}

aq_status aq_plot_capacity(const aq_h5_capacity_table *t, const char *arch,
                           const char *source, const char *target, const char *data,
                           double *draw_s, aq_error *err)
{
  cap c = {t, arch, NULL, 0};
  if (t->n == 0)
    return aq_error_set(err, AQ_EFORMAT, source, -1, -1, "capacity",
                        "expected a capacity results file (archquake capacity -o), got none");
  if (!c.arch)
    c.arch = t->row[0].arch;
  c.row = malloc(t->n * sizeof *c.row);
  if (!c.row)
    return aq_error_set(err, AQ_ENOMEM, source, -1, -1, NULL, "out of memory");
  for (size_t k = 0; k < t->n; k++)
    if (strcmp(t->row[k].arch, c.arch) == 0)
      c.row[c.n++] = k;
  aq_status rc;
  if (c.n == 0)
    rc = aq_error_set(err, AQ_EVALUE, source, -1, -1, "--arch",
                      "expected an arch of the file such as \"%s\", got \"%s\"",
                      t->row[0].arch, c.arch);
  else {
    int h = 200 + 40 * (int)c.n;
    rc = aq_plot_render(target, 1000, h < 500 ? 500 : h, draw, &c, draw_s, err);
  }
  if (rc == AQ_OK && data) {
    char tmp[1024];
    FILE *f = aq_plot_csv_open(data, tmp, sizeof tmp, err);
    if (!f)
      rc = err->status;
    else {
      aq_plot_csv_axes(f, 1, &AX_SCALE);
      fprintf(f, "record,polarity,move_scale,scale_max,collapse_lo,collapse_hi\n");
      for (size_t k = 0; k < c.n; k++) {
        const aq_h5_capacity_row *r = &t->row[c.row[k]];
        int64_t m = r->i[I_COUNT];
        for (int64_t j = 0; j < (m ? m : 1); j++) {
          size_t q = (size_t)(r->i[I_START] + j);
          double a = m && q < t->ninterval ? t->interval[2 * q] : NAN;
          double b = m && q < t->ninterval ? t->interval[2 * q + 1] : NAN;
          fprintf(f, "%s,%s,%.17g,%.17g,%.17g,%.17g\n", r->record, r->polarity,
                  r->d[D_MOVE], r->d[D_SMAX], a, b);
        }
      }
      rc = aq_plot_csv_close(f, tmp, data, 1, err);
    }
  }
  free(c.row);
  return rc;
}
