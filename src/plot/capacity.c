/* capacity.c: the capacity results of one arch (`archquake capacity`): for
 * each (record, polarity), the scale factors it was scanned over (from the
 * scale below which the arch never moves to the cap), the collapse
 * intervals shaded, so that a resurrection (survival above a first
 * collapse) shows as a gap in the red.  Below, the fitted lognormal
 * fragility Phi(ln(x/median)/beta) in one IM, the band between the CDFs of
 * the median's interval ends, and the data it was fitted to, rebuilt as
 * aq_fragility_fit_records builds them: per record the lowest first
 * collapse of its polarities, at i/n (n records), or censored at its cap
 * (open circles).  Peak rotation against scale is not drawn: capacity does
 * not store it. */
#include <math.h>
#include <plplot.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

static const char *const AX_SCALE = "scale factor on the processed record (1)";

static const char *const AX_PROB = "probability of collapse (1)";
/* axis titles of the IMs of aq_fragility_im_names */
static const char *const AX_IM[AQ_FRAGILITY_NIM] = {
    "PGA (g)", "PGV (m/s)", "PGD (m)", "Arias intensity (m/s)", "CAV (m/s)",
    "PGA / (#gl#d0#u g) (1)"};
enum { NCURVE = 201 }; /* points of each CDF */

/* The fragility panel's data. */
typedef struct {
  int m;                        /* IM number */
  const aq_h5_fragility_fit *fit; /* NULL: the file holds none for the arch */
  size_t n, ncol;               /* records, collapsed among them */
  double *x;                    /* n: sorted first-collapse IMs, then the caps */
  double cx[NCURVE], cdf[3][NCURVE]; /* fit, median_lo, median_hi */
  double lo, hi;                /* x range */
} frag;

typedef struct {
  const aq_h5_capacity_table *t;
  const char *arch;
  size_t *row; /* rows of this arch */
  size_t n;
  frag f;
  double split; /* page fraction of the fragility panel (bottom) */
} cap;

enum { D_MOVE = 0, D_FIRST = 1, D_SMAX = 4, I_START = 2, I_COUNT = 3, I_RES = 0 };

static const char *base(const char *p)
{
  const char *b = strrchr(p, '/');
  return b ? b + 1 : p;
}

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
static int frag_build(cap *c, int m)
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
        strcmp(t->fit[i].im, aq_fragility_im_names[m]) == 0)
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

/* y in the top panel's own [0, 1] to the page. */
static double top_y(const cap *c, double y)
{
  return c->split + y * (1 - c->split);
}

static void draw_fragility(const cap *c)
{
  const frag *f = &c->f;
  const aq_h5_fragility_fit *q = f->fit;
  const double *lx = f->cx;
  double poly[2][2 * NCURVE];
  plvpor(0.1, 0.95, c->split * 0.16, c->split * 0.88);
  plwind(0, f->hi, 0, 1.02);
  int fitted = isfinite(f->cdf[0][0]);
  int band = fitted && !isnan(q->median_lo) && !isnan(q->median_hi);
  if (band) { /* between the CDFs at median_lo (above) and median_hi */
    for (int i = 0; i < NCURVE; i++) {
      poly[0][i] = lx[i];
      poly[1][i] = f->cdf[1][i];
      poly[0][2 * NCURVE - 1 - i] = lx[i];
      poly[1][2 * NCURVE - 1 - i] = f->cdf[2][i];
    }
    plcol0(AQ_PC_LIGHT);
    plfill(2 * NCURVE, poly[0], poly[1]);
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
  plmtex("b", 3.0, 0.5, 0.5, AX_IM[f->m]);
  plmtex("l", 4.0, 0.5, 0.5, AX_PROB);
  char title[320];
  if (fitted)
    snprintf(title, sizeof title,
             "fragility of arch %.100s: median %.3g, #gb %.3g (%zu records, %zu censored)",
             c->arch, q->median, q->beta, f->n, f->n - f->ncol);
  else
    snprintf(title, sizeof title, "fragility of arch %.100s: %s (%zu records, %zu censored)",
             c->arch, q ? "not fitted (fewer than two collapse values)" : "no fit in the file",
             f->n, f->n - f->ncol);
  plmtex("t", 1.2, 0.5, 0.5, title);
  const char *tx[] = {"lognormal fit", "median's confidence interval",
                      "first collapses (i/n)", "censored at the cap"};
  int col[] = {AQ_PC_BLUE, AQ_PC_LIGHT, AQ_PC_RED, AQ_PC_FG}, st[] = {1, -1, 0, 0};
  const char *sym[] = {"", "", "●", "○"};
  aq_plot_legend(PL_POSITION_INSIDE | PL_POSITION_TOP | PL_POSITION_LEFT, 4, tx, col, st,
                 sym);
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
  plvpor(0.45, 0.95, top_y(c, 0.22), top_y(c, 0.9));
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
  plvpor(0.45, 0.95, top_y(c, 0.01), top_y(c, 0.1));
  const char *tx[] = {"scanned (arch moves)", "collapse"};
  int col[] = {AQ_PC_GREY, AQ_PC_RED}, st[] = {1, -1};
  aq_plot_legend(PL_POSITION_INSIDE | PL_POSITION_TOP, 2, tx, col, st, NULL);
  draw_fragility(c);
  return 0;
}

/* The fragility panel's data after the intervals' (a second header). */
static void frag_csv(FILE *f, const cap *c)
{
  const frag *g = &c->f;
  const aq_h5_fragility_fit *q = g->fit;
  const char *ax[2] = {AX_IM[g->m], AX_PROB};
  fprintf(f, "\n# fragility: arch=%s im=%s median=%.17g beta=%.17g median_lo=%.17g "
             "median_hi=%.17g records=%zu censored=%zu\n",
          c->arch, aq_fragility_im_names[g->m], q ? q->median : NAN, q ? q->beta : NAN,
          q ? q->median_lo : NAN, q ? q->median_hi : NAN, g->n, g->n - g->ncol);
  aq_plot_csv_axes(f, 2, ax);
  fprintf(f, "series,%s,probability\n", aq_fragility_im_names[g->m]);
  static const char *const name[3] = {"fit", "fit_median_lo", "fit_median_hi"};
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < NCURVE && isfinite(g->cdf[0][0]); i++)
      fprintf(f, "%s,%.17g,%.17g\n", name[k], g->cx[i], g->cdf[k][i]);
  for (size_t i = 0; i < g->ncol; i++)
    fprintf(f, "empirical,%.17g,%.17g\n", g->x[i], (i + 1) / (double)g->n);
  for (size_t i = g->ncol; i < g->n; i++)
    fprintf(f, "censored,%.17g,%.17g\n", g->x[i], g->ncol / (double)g->n);
}

aq_status aq_plot_capacity(const aq_h5_capacity_table *t, const char *arch, const char *im,
                           const char *source, const char *target, const char *data,
                           double *draw_s, aq_error *err)
{
  cap c = {t, arch, NULL, 0, {0}, 0};
  int m = 0;
  if (im) {
    for (m = 0; m < AQ_FRAGILITY_NIM && strcmp(aq_fragility_im_names[m], im) != 0; m++)
      ;
    if (m == AQ_FRAGILITY_NIM)
      return aq_error_set(err, AQ_EOPTION, source, -1, -1, "--im",
                          "expected one of pga_g, pgv_m_s, pgd_m, arias_m_s, cav_m_s, "
                          "pga_lambda0, got \"%s\"", im);
  }
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
  else if (frag_build(&c, m) != 0)
    rc = aq_error_set(err, AQ_ENOMEM, source, -1, -1, NULL, "out of memory");
  else {
    int h = 200 + 40 * (int)c.n, h2 = 500;
    h = h < 500 ? 500 : h;
    c.split = h2 / (double)(h + h2);
    rc = aq_plot_render(target, 1000, h + h2, draw, &c, draw_s, err);
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
      frag_csv(f, &c);
      rc = aq_plot_csv_close(f, tmp, data, 1, err);
    }
  }
  free(c.row);
  free(c.f.x);
  return rc;
}
