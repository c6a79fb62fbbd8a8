/* capacity_frag.c: the fragility panel of the capacity figure (capacity.c,
 * capacity_fig.h): the data of the fit rebuilt as aq_fragility_fit_records
 * builds it, the lognormal CDF and the band of its median's interval, the
 * panel drawn with its title and key, and its part of --data.
 */
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "capacity_fig.h"
#include "plot.h"

/* Standard normal CDF. */
static double phi(double z)
{
  return 0.5 * erfc(-z / sqrt(2.0));
}

/* Lognormal fragility Phi(ln(x/median)/beta) (median INFINITY: 0). */
static double lognormal_cdf(double x, double median, double beta)
{
  return isinf(median) ? 0 : phi(log(x / median) / beta);
}

static int by_value(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The data of the fit of IM m over the records of c (as
 * aq_fragility_fit_records), the fit, the CDF curves. */
int aq_plot_cap_frag_build(cap *c, int m)
{
  frag *f = &c->f;
  const aq_h5_capacity_table *t = c->t;
  f->m = m;
  f->x = malloc((c->n ? c->n : 1) * sizeof *f->x);
  double *cen = malloc((c->n ? c->n : 1) * sizeof *cen);
  if (!f->x || !cen) {
    free(cen);
    return -1;
  }
  size_t ncen = 0;
  for (size_t k = 0; k < c->n;) {
    const char *rec = t->row[c->row[k]].record;
    double s = INFINITY, top = NAN;
    int bad = 0;
    for (; k < c->n && strcmp(t->row[c->row[k]].record, rec) == 0; k++) {
      const aq_h5_capacity_row *r = &t->row[c->row[k]];
      bad |= isnan(r->im_cap[m]); /* a failed pair: no results */
      if (!isnan(r->im_first[m]))
        s = fmin(s, r->im_first[m]);
      top = r->im_cap[m];
    }
    double x = isfinite(s) ? s : top;
    if (bad || !(x > 0 && isfinite(x)))
      continue;
    if (isfinite(s))
      f->x[f->ncol++] = x;
    else
      cen[ncen++] = x;
  }
  f->n = f->ncol + ncen;
  qsort(f->x, f->ncol, sizeof *f->x, by_value);
  memcpy(f->x + f->ncol, cen, ncen * sizeof *cen);
  free(cen);
  for (size_t i = 0; i < t->nfit; i++)
    if (strcmp(t->fit[i].arch, c->arch) == 0 &&
        strcmp(t->fit[i].im, t->im_name[m]) == 0)
      f->fit = &t->fit[i];
  const aq_h5_fragility_fit *q = f->fit;
  int fitted = q && isfinite(q->median) && q->beta > 0;
  double lo = INFINITY, hi = 0;
  for (size_t i = 0; i < f->n; i++) {
    lo = fmin(lo, f->x[i]);
    hi = fmax(hi, f->x[i]);
  }
  if (fitted) {
    double a = isfinite(q->median_lo) && q->median_lo > 0 ? q->median_lo : q->median;
    double b = isfinite(q->median_hi) ? q->median_hi : q->median;
    lo = fmin(lo, a * exp(-2 * q->beta)); /* the CDF from ~0.02 */
    hi = fmax(hi, b * exp(2 * q->beta));  /* to ~0.98 */
  }
  if (!(lo < hi)) {
    lo = hi > 0 ? hi / 2 : 0.1;
    hi = lo * 4;
  }
  f->lo = lo / 1.1;
  f->hi = hi * 1.1;
  for (int i = 0; i < NCURVE; i++) {
    double x = f->lo * pow(f->hi / f->lo, i / (double)(NCURVE - 1));
    f->cx[i] = x;
    f->cdf[0][i] = fitted ? lognormal_cdf(x, q->median, q->beta) : NAN;
    f->cdf[1][i] = fitted ? lognormal_cdf(x, q->median_lo, q->beta) : NAN;
    f->cdf[2][i] = fitted ? lognormal_cdf(x, q->median_hi, q->beta) : NAN;
  }
  return 0;
}

/* The entries the fragility's key shows: only what is drawn. */
int aq_plot_cap_frag_keys(const cap *c, const char **tx, int *col, int *st, const char **sym)
{
  const frag *f = &c->f;
  const aq_h5_fragility_fit *q = f->fit;
  int fitted = q && isfinite(q->median) && q->beta > 0;
  int band = fitted && !isnan(q->median_lo) && !isnan(q->median_hi);
  static const char *const all_tx[] = {"lognormal fit", "median's confidence interval",
                                       "first collapses (i/n)", "censored at the cap"};
  static const int all_col[] = {AQ_PC_BLUE, AQ_PC_LIGHT, AQ_PC_RED, AQ_PC_FG},
                   all_st[] = {1, -1, 0, 0};
  static const char *const all_sym[] = {"", "", "●", "○"};
  const int drawn[] = {fitted, band, f->ncol > 0, f->n > f->ncol};
  int k = 0;
  for (int i = 0; i < 4; i++)
    if (drawn[i]) {
      tx[k] = all_tx[i];
      sym[k] = all_sym[i];
      col[k] = all_col[i];
      st[k++] = all_st[i];
    }
  return k;
}

void aq_plot_cap_draw_fragility(const cap *c)
{
  const frag *f = &c->f;
  const double *lx = f->cx;
  aq_plot_text_height(TXT_MM);
  aq_plot_cap_vp_mm(c, c->fx0, c->fx1, c->fy0, c->fy1);
  plwind(0, f->hi, 0, 1.02);
  int fitted = isfinite(f->cdf[0][0]);
  int band = fitted && !isnan(f->fit->median_lo) && !isnan(f->fit->median_hi);
  if (band) { /* between the CDFs at median_lo (above) and median_hi, a
                 quadrilateral per step: PLplot fills one polygon of many
                 points wrongly on a PDF page scaled by plsdidev */
    plcol0(AQ_PC_LIGHT);
    for (int i = 0; i + 1 < NCURVE; i++) {
      PLFLT qx[4] = {lx[i], lx[i + 1], lx[i + 1], lx[i]};
      PLFLT qy[4] = {f->cdf[1][i], f->cdf[1][i + 1], f->cdf[2][i + 1], f->cdf[2][i]};
      plfill(4, qx, qy);
    }
  }
  if (fitted) {
    plcol0(AQ_PC_BLUE);
    plwidth(2);
    plline(NCURVE, lx, f->cdf[0]);
    plwidth(1);
  }
  PLFLT ex[2], ey[2];
  for (size_t i = 0; i < f->ncol; i++) { /* empirical steps i/n */
    double x0 = f->x[i], x1 = i + 1 < f->ncol ? f->x[i + 1] : f->hi;
    double y = (i + 1) / (double)f->n;
    plcol0(AQ_PC_RED);
    ex[0] = x0, ex[1] = x1, ey[0] = ey[1] = y;
    plline(2, ex, ey);
    ex[1] = x0, ey[0] = i / (double)f->n;
    plline(2, ex, ey);
    plstring(1, &ex[0], &ey[1], "●");
  }
  for (size_t i = f->ncol; i < f->n; i++) { /* censored at the cap */
    ex[0] = f->x[i];
    ey[0] = f->ncol / (double)f->n;
    plcol0(AQ_PC_FG);
    plstring(1, ex, ey, "○");
  }
  plcol0(AQ_PC_FG);
  plbox("bcnst", 0, 0, "bcnstv", 0.2, 2);
  plmtex("b", 3.0, 0.5, 0.5, c->im_axis);
  plmtex("l", 4.0, 0.5, 0.5, AX_PROB);
  /* the title above, the key below the axis' title: nothing on the data */
  aq_plot_cap_page_mm(c);
  aq_plot_text_height(TITLE_MM);
  for (int i = 0; i < c->ftitle_lines; i++)
    plptex(c->w / 2, c->ftitle_y + i * aq_plot_cap_pitch_mm(TITLE_MM), 1, 0, 0.5, c->ftitle[i]);
  const char *tx[4], *sym[4];
  int col[4], st[4], k = aq_plot_cap_frag_keys(c, tx, col, st, sym);
  aq_plot_text_height(KEY_MM);
  for (int i = 0; i < k; i++)
    aq_plot_cap_key_entry(c->fx0 + (i % c->leg_cols) * c->leg_colw,
              c->leg_y + (i / c->leg_cols + 0.5) * aq_plot_cap_pitch_mm(KEY_MM), col[i], st[i], sym[i], tx[i]);
}

/* The fragility panel's data after the intervals' (a second header). */
void aq_plot_cap_frag_csv(FILE *f, const cap *c)
{
  const frag *g = &c->f;
  const aq_h5_fragility_fit *q = g->fit;
  const char *ax[2] = {c->im_axis, AX_PROB};
  fprintf(f,
          "\n# fragility: arch=%s im=%s median=%s beta=%s median_lo=%s "
          "median_hi=%s records=%zu censored=%zu\n",
          c->arch, c->t->im_name[g->m], AQ_TEXT_NUM(q ? q->median : NAN),
          AQ_TEXT_NUM(q ? q->beta : NAN), AQ_TEXT_NUM(q ? q->median_lo : NAN),
          AQ_TEXT_NUM(q ? q->median_hi : NAN), g->n, g->n - g->ncol);
  aq_plot_csv_axes(f, 2, ax);
  fprintf(f, "series,%s,probability\n", c->t->im_name[g->m]);
  static const char *const name[3] = {"fit", "fit_median_lo", "fit_median_hi"};
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < NCURVE && isfinite(g->cdf[0][0]); i++)
      fprintf(f, "%s,%s,%s\n", name[k], AQ_TEXT_NUM(g->cx[i]), AQ_TEXT_NUM(g->cdf[k][i]));
  for (size_t i = 0; i < g->ncol; i++)
    fprintf(f, "empirical,%s,%s\n", AQ_TEXT_NUM(g->x[i]), AQ_TEXT_NUM((i + 1) / (double)g->n));
  for (size_t i = g->ncol; i < g->n; i++)
    fprintf(f, "censored,%s,%s\n", AQ_TEXT_NUM(g->x[i]), AQ_TEXT_NUM(g->ncol / (double)g->n));
}
