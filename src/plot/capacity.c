/* capacity.c: the capacity results of one arch (`archquake capacity`).
 * Top: the verdict of every scale the capacity search ran
 * (capacity/scan_points), as a strip per (record, polarity) along a
 * shared scale axis (scale factor, or the PGA of the scaled record, g):
 * blank below the scale that first moves the arch, shaded by the run's
 * peak rotation (over q_c, or rad) where it survived, red and hatched
 * where it collapsed (the collapse intervals), a tick at every change of
 * verdict; beside each strip its first collapse scale, and R where it
 * survives again above a collapse (a resurrection).  Below, the fitted
 * lognormal fragility Phi(ln(x/median)/beta) in one IM, the band between
 * the CDFs of the median's interval ends, and the data it was fitted to,
 * rebuilt as aq_fragility_fit_records builds them: per record the lowest
 * first collapse of its polarities, at i/n (n records), or censored at
 * its cap (open circles). */
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

static const char *const AX_SCALE = "scale factor on the processed record (1)";
static const char *const AX_PGA = "PGA of the scaled record (g)";
static const char *const AX_QC = "survived: peak rotation / q#dc#u (1)";
static const char *const AX_RAD = "survived: peak rotation (rad)";
static const char *const AX_PROB = "probability of collapse (1)";
/* axis titles of the IMs of aq_fragility_im_names */
static const char *const AX_IM[AQ_FRAGILITY_NIM] = {
    "PGA (g)", "PGV (m/s)", "PGD (m)", "Arias intensity (m/s)", "CAV (m/s)",
    "PGA / (#gl#d0#u g) (1)"};
/* the IMs' units, for the fitted median */
static const char *const IM_UNIT[AQ_FRAGILITY_NIM] = {"g", "m/s", "m", "m/s", "m/s",
                                                      "#gl#d0#u g"};
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
  const aq_plot_capacity_opts *o;
  const char *arch;
  size_t *row;  /* rows of this arch: one line each */
  size_t n;
  double *pga;  /* n: each line's PGA at scale 1 (g; NAN unknown) */
  int *color;   /* n: colour of each line (by record) */
  size_t *rec;  /* n: each line's record (0-based, in the file's order) */
  size_t nrec;
  int have_pol[2]; /* a normal, a reversed line among them */
  frag f;
  int logy;     /* 1: the scale axis log10 */
  double ylo, yhi, xhi; /* scale axis range (in its unit, not log); shade's top */
  double split; /* page fraction of the fragility panel (bottom) */
  double page_px, strips_px; /* page height, the strips' height (px) */
} cap;

enum { D_MOVE = 0, D_FIRST = 1, D_PGA = 2, D_SMAX = 4, I_START = 2, I_COUNT = 3 };

/* Colours of the lines, one per record, cycled. */
static const int LINE_COLOR[] = {AQ_PC_BLUE,   AQ_PC_ORANGE, AQ_PC_GREEN, AQ_PC_RED,
                                 AQ_PC_PURPLE, AQ_PC_TEAL,   AQ_PC_BROWN, AQ_PC_PINK,
                                 AQ_PC_OLIVE,  AQ_PC_NAVY};
enum { NCOLOR = sizeof LINE_COLOR / sizeof LINE_COLOR[0] };
enum { ROW_PX = 26, RECORD_GAP_PX = 8 }; /* a strip, the space between records */

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

static void draw_fragility(const cap *c)
{
  const frag *f = &c->f;
  const aq_h5_fragility_fit *q = f->fit;
  const double *lx = f->cx;
  plvpor(0.1, 0.95, c->split * 0.16, c->split * 0.88);
  plwind(0, f->hi, 0, 1.02);
  int fitted = isfinite(f->cdf[0][0]);
  int band = fitted && !isnan(q->median_lo) && !isnan(q->median_hi);
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
  plmtex("b", 3.0, 0.5, 0.5, AX_IM[f->m]);
  plmtex("l", 4.0, 0.5, 0.5, AX_PROB);
  char title[320];
  if (fitted)
    aq_text_fit(title, sizeof title,
                "fragility of arch %s: median %.3g %s, #gb %.3g (%zu records, %zu censored)",
                c->arch, q->median, IM_UNIT[f->m], q->beta, f->n, f->n - f->ncol);
  else
    aq_text_fit(title, sizeof title, "fragility of arch %s: %s (%zu records, %zu censored)",
                c->arch, q ? "no fit, < 2 collapse values" : "no fit in the file",
                f->n, f->n - f->ncol);
  plmtex("t", 1.2, 0.5, 0.5, title);
  /* a legend entry only for what is drawn */
  const char *all_tx[] = {"lognormal fit", "median's confidence interval",
                          "first collapses (i/n)", "censored at the cap"};
  const int all_col[] = {AQ_PC_BLUE, AQ_PC_LIGHT, AQ_PC_RED, AQ_PC_FG},
            all_st[] = {1, -1, 0, 0};
  const char *all_sym[] = {"", "", "●", "○"};
  const int drawn[] = {fitted, band, f->ncol > 0, f->n > f->ncol};
  const char *tx[4], *sym[4];
  int col[4], st[4], k = 0;
  for (int i = 0; i < 4; i++)
    if (drawn[i]) {
      tx[k] = all_tx[i];
      sym[k] = all_sym[i];
      col[k] = all_col[i];
      st[k++] = all_st[i];
    }
  if (k > 0)
    aq_plot_legend(PL_POSITION_INSIDE | PL_POSITION_TOP | PL_POSITION_LEFT, k, tx, col, st,
                   sym);
}

static int reversed(const aq_h5_capacity_row *r)
{
  return strcmp(r->polarity, "reversed") == 0;
}

/* Line k's y of scale s (scale, or PGA in g), and on the drawn axis. */
static double y_of(const cap *c, size_t k, double s)
{
  return c->o->y_pga ? s * c->pga[k] : s;
}
static double axis_y(const cap *c, double y)
{
  return c->logy ? log10(y) : y;
}

/* The x plotted for a scanned point. */
static double x_of(const cap *c, const aq_capacity_point *p)
{
  return c->o->x_rad ? p->peak_rotation_rad : p->peak_rotation_over_qc;
}

/* y and x ranges over the lines (scanned points, move scale to cap). */
static void ranges(cap *c)
{
  const aq_h5_capacity_table *t = c->t;
  double lo = INFINITY, hi = 0, xhi = c->o->x_rad ? 0 : 1;
  for (size_t k = 0; k < c->n; k++) {
    const aq_h5_capacity_row *r = &t->row[c->row[k]];
    double v[2] = {y_of(c, k, r->d[D_MOVE]), y_of(c, k, r->d[D_SMAX])};
    for (int j = 0; j < 2; j++)
      if (v[j] > 0 && isfinite(v[j])) {
        lo = fmin(lo, v[j]);
        hi = fmax(hi, v[j]);
      }
    for (size_t i = 0; i < r->point_count; i++) {
      const aq_capacity_point *p = &t->point[r->point_start + i];
      double y = y_of(c, k, p->scale), x = x_of(c, p);
      if (y > 0 && isfinite(y)) {
        lo = fmin(lo, y);
        hi = fmax(hi, y);
      }
      if (isfinite(x))
        xhi = fmax(xhi, x);
    }
  }
  if (!(lo < hi)) {
    lo = hi > 0 ? hi / 2 : 0.5;
    hi = lo * 4;
  }
  /* log10 when the range holds two powers of ten (PLplot labels decades) */
  c->logy = ceil(log10(lo / 1.05)) < floor(log10(hi * 1.05));
  c->ylo = c->logy ? lo / 1.05 : 0;
  c->yhi = hi * (c->logy ? 1.05 : 1.03);
  c->xhi = (xhi > 0 ? xhi : 1) * 1.04;
}

/* Strip k's row: its top edge in rows from the top (records apart by a gap). */
static double row_top(const cap *c, size_t k)
{
  return (double)k + (double)c->rec[k] * RECORD_GAP_PX / (double)ROW_PX;
}

static void fill_box(double x0, double x1, double y0, double y1)
{
  PLFLT x[4] = {x0, x1, x1, x0}, y[4] = {y0, y0, y1, y1};
  plfill(4, x, y);
}

/* The shade of a survived run: 0 at rest, 1 at the collapse rotation (or
 * the largest peak rotation in rad). */
static double shade(const cap *c, const aq_capacity_point *p)
{
  double v = c->o->x_rad ? p->peak_rotation_rad / c->xhi : p->peak_rotation_over_qc;
  return isfinite(v) ? fmin(fmax(v, 0), 1) : 0;
}

/* Strip k in rows [y0, y1]: the scanned points' verdicts, each drawn from
 * halfway to the point below to halfway to the point above (on the drawn
 * axis), then the collapse intervals and the ticks at each change. */
static void draw_strip(const cap *c, size_t k, double y0, double y1)
{
  const aq_h5_capacity_table *t = c->t;
  const aq_h5_capacity_row *r = &t->row[c->row[k]];
  double smax = r->d[D_SMAX], move = r->d[D_MOVE];
  double xa = axis_y(c, c->ylo), xb = axis_y(c, c->yhi);
  double xmove = isfinite(move) && y_of(c, k, move) > c->ylo ? axis_y(c, y_of(c, k, move)) : xa;
  double xcap = isfinite(smax) && y_of(c, k, smax) > 0 ? axis_y(c, y_of(c, k, smax)) : xb;
  PLFLT lx[2] = {xa, xmove}, ly[2] = {0.5 * (y0 + y1), 0.5 * (y0 + y1)};
  plcol0(AQ_PC_GREY); /* at rest: a thin line */
  plline(2, lx, ly);
  double prev = xmove;
  for (size_t i = 0; i < r->point_count; i++) {
    const aq_capacity_point *p = &t->point[r->point_start + i];
    double y = y_of(c, k, p->scale);
    if (!(y > 0) || p->collapsed)
      continue;
    double x = axis_y(c, y), next = xcap;
    for (size_t j = i + 1; j < r->point_count; j++) {
      double yj = y_of(c, k, t->point[r->point_start + j].scale);
      if (yj > 0 && axis_y(c, yj) > x) {
        next = 0.5 * (x + axis_y(c, yj));
        break;
      }
    }
    double from = fmax(prev, xmove);
    if (next > from) {
      plcol1(shade(c, p));
      fill_box(from, fmin(next, xcap), y0, y1);
    }
    prev = next;
  }
  for (int64_t j = 0; j < r->i[I_COUNT]; j++) {
    size_t q = (size_t)(r->i[I_START] + j);
    if (q >= t->ninterval)
      break;
    double a = y_of(c, k, t->interval[2 * q]);
    double b = y_of(c, k, fmin(t->interval[2 * q + 1], smax));
    if (!(a > 0 && b >= a))
      continue;
    double xa_ = axis_y(c, fmax(a, c->ylo)), xb_ = axis_y(c, b);
    plcol0(AQ_PC_RED);
    fill_box(xa_, xb_, y0, y1);
    plcol0(AQ_PC_BG); /* hatched: a collapse does not rest on colour alone */
    plpsty(3);
    fill_box(xa_, xb_, y0, y1);
    plpsty(0);
    plcol0(AQ_PC_FG); /* the changes of verdict */
    plwidth(2);
    PLFLT tx[2] = {xa_, xa_}, ty[2] = {y0 - 0.1, y1 + 0.1};
    plline(2, tx, ty);
    if (t->interval[2 * q + 1] < smax) {
      tx[0] = tx[1] = xb_;
      plline(2, tx, ty);
    }
    plwidth(1);
  }
  plcol0(AQ_PC_FG);
  PLFLT bx[5] = {xmove, xcap, xcap, xmove, xmove}, by[5] = {y0, y0, y1, y1, y0};
  plline(5, bx, by);
}

static int draw(void *ctx, aq_error *err)
{
  (void)err;
  const cap *c = ctx;
  const aq_h5_capacity_table *t = c->t;
  const double H = c->page_px;
  /* the strips, from the top: title 50 px, the strips, the axis' labels
     and title 60 px, the key 80 px */
  const double vy1 = 1 - 50 / H, vy0 = vy1 - c->strips_px / H;
  const char *yt = c->o->y_pga ? AX_PGA : AX_SCALE;
  pladv(0);
  plschr(0, 0.85);
  /* the labels' margin: the longest name and its polarity, or as much as fits */
  size_t longest = 1;
  for (size_t k = 0; k < c->n; k++) {
    size_t len = strlen(base(t->row[c->row[k]].record)) + 10;
    longest = len > longest ? len : longest;
  }
  double per_char = 0.8 / (double)aq_plot_chars_fit(0.8);
  double left = fmin(fmax((double)(longest + 2) * per_char, 0.15), 0.42), right = 0.84;
  double nrows = c->n ? row_top(c, c->n - 1) + 1 : 1;
  plvpor(left, right, vy0, vy1);
  plwind(axis_y(c, c->ylo), axis_y(c, c->yhi), nrows, 0);
  PLFLT cpos[4] = {0, 0.1, 0.5, 1}, rr[4] = {1, 1, 0.95, 0.55}; /* as the suite's */
  PLFLT gg[4] = {1, 0.93, 0.6, 0.3}, bb[4] = {1, 0.6, 0.2, 0.1};
  plscmap1l(1, 4, cpos, rr, gg, bb, NULL);
  size_t fit = aq_plot_chars_fit(left - 0.01);
  for (size_t k = 0; k < c->n; k++) {
    const aq_h5_capacity_row *r = &t->row[c->row[k]];
    double y0 = row_top(c, k) + 0.12, y1 = row_top(c, k) + 0.88;
    draw_strip(c, k, y0, y1);
    /* the label: the record's name on its first strip, and the polarity */
    char name[1024], lab[1100];
    int first = k == 0 || c->rec[k] != c->rec[k - 1];
    aq_plot_ellipsize(base(r->record), fit > 12 ? fit - 11 : 1, name, sizeof name);
    aq_text_fit(lab, sizeof lab, "%s  %s", first ? name : "", r->polarity);
    double ymid = 1 - (row_top(c, k) + 0.5) / nrows;
    plcol0(AQ_PC_FG);
    plmtex("lv", 0.8, ymid, 1, lab);
    /* beside it: the first collapse, R for a resurrection */
    char fc[64];
    double f = r->d[D_FIRST];
    if (strcmp(r->status, "ok") != 0 && strncmp(r->status, "collapse", 8) != 0 &&
        isnan(f) && r->point_count == 0)
      snprintf(fc, sizeof fc, "%s", r->status);
    else if (isfinite(f))
      snprintf(fc, sizeof fc, "%.3g%s", y_of(c, k, f), r->i[0] > 0 ? "  R" : "");
    else
      snprintf(fc, sizeof fc, "none");
    plmtex("rv", 0.8, ymid, 0, fc);
  }
  plcol0(AQ_PC_FG);
  plbox(c->logy ? "bnstlf" : "bnst", 0, 0, "", 0, 0);
  plmtex("b", 3.0, 0.5, 0.5, yt);
  plmtex("t", 0.6, 1.02, 0, "first collapse");
  char title[256];
  aq_text_fit(title, sizeof title, "arch %s: the verdict of each scanned run", c->arch);
  plvpor(0.02, 0.98, vy0, vy1); /* the title centred on the page */
  plmtex("t", 2.2, 0.5, 0.5, title);
  if (!t->have_points)
    plmtex("t", 1.0, 0.5, 0.5, "(no scanned points in this file: written before "
                               "capacity/scan_points; the collapse intervals only)");
  /* the key under the axis: the shade, then what the marks mean */
  double ky1 = vy0 - 70 / H, ky0 = ky1 - 16 / H;
  plvpor(0.08, 0.42, ky0, ky1);
  double ktop = c->o->x_rad ? c->xhi : 1; /* the shade's scale: 0 to ktop */
  plwind(0, ktop, 0, 1);
  for (int i = 0; i < 50; i++) {
    plcol1((i + 0.5) / 50);
    fill_box(ktop * i / 50.0, ktop * (i + 1) / 50.0, 0, 1);
  }
  plcol0(AQ_PC_FG);
  plbox("bcnst", 0, 0, "bc", 0, 0);
  plmtex("b", 3.2, 0.5, 0.5, c->o->x_rad ? AX_RAD : AX_QC);
  /* what the marks mean, one a line, right of the shade */
  plvpor(0.5, 0.99, ky1 - 104 / H, ky1);
  plwind(0, 1, 4.2, 0);
  double bw = 0.06; /* a sample's width */
  plcol0(AQ_PC_RED);
  fill_box(0, bw, 0.1, 0.9);
  plcol0(AQ_PC_BG);
  plpsty(3);
  fill_box(0, bw, 0.1, 0.9);
  plpsty(0);
  plcol0(AQ_PC_FG);
  PLFLT tx[2] = {bw / 2, bw / 2}, ty[2] = {1.1, 1.9};
  plwidth(2);
  plline(2, tx, ty);
  plwidth(1);
  plptex(bw / 2, 2.5, 1, 0, 0.5, "R");
  plptex(bw + 0.03, 0.5, 1, 0, 0, "collapse (a collapse interval)");
  plptex(bw + 0.03, 1.5, 1, 0, 0, "a change of verdict");
  plptex(bw + 0.03, 2.5, 1, 0, 0, "survives again above a collapse");
  plptex(bw + 0.03, 3.5, 1, 0, 0, "blank: below the scale that moves it");
  draw_fragility(c);
  return 0;
}

/* The fragility panel's data after the intervals' (a second header). */
static void frag_csv(FILE *f, const cap *c)
{
  const frag *g = &c->f;
  const aq_h5_fragility_fit *q = g->fit;
  const char *ax[2] = {AX_IM[g->m], AX_PROB};
  fprintf(f,
          "\n# fragility: arch=%s im=%s median=%s beta=%s median_lo=%s "
          "median_hi=%s records=%zu censored=%zu\n",
          c->arch, aq_fragility_im_names[g->m], AQ_TEXT_NUM(q ? q->median : NAN),
          AQ_TEXT_NUM(q ? q->beta : NAN), AQ_TEXT_NUM(q ? q->median_lo : NAN),
          AQ_TEXT_NUM(q ? q->median_hi : NAN), g->n, g->n - g->ncol);
  aq_plot_csv_axes(f, 2, ax);
  fprintf(f, "series,%s,probability\n", aq_fragility_im_names[g->m]);
  static const char *const name[3] = {"fit", "fit_median_lo", "fit_median_hi"};
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < NCURVE && isfinite(g->cdf[0][0]); i++)
      fprintf(f, "%s,%s,%s\n", name[k], AQ_TEXT_NUM(g->cx[i]), AQ_TEXT_NUM(g->cdf[k][i]));
  for (size_t i = 0; i < g->ncol; i++)
    fprintf(f, "empirical,%s,%s\n", AQ_TEXT_NUM(g->x[i]), AQ_TEXT_NUM((i + 1) / (double)g->n));
  for (size_t i = g->ncol; i < g->n; i++)
    fprintf(f, "censored,%s,%s\n", AQ_TEXT_NUM(g->x[i]), AQ_TEXT_NUM(g->ncol / (double)g->n));
}

/* The top panel's data: the lines' points, then the shaded intervals. */
static void lines_csv(FILE *f, const cap *c)
{
  const aq_h5_capacity_table *t = c->t;
  const char *ax[2] = {c->o->x_rad ? AX_RAD : AX_QC, c->o->y_pga ? AX_PGA : AX_SCALE};
  aq_plot_csv_axes(f, 2, ax);
  fprintf(f, "record,polarity,legend_no,scale,pga_g,peak_rotation_rad,peak_rotation_over_qc,"
             "collapsed,collapse_time_s\n");
  for (size_t k = 0; k < c->n; k++) {
    const aq_h5_capacity_row *r = &t->row[c->row[k]];
    for (size_t i = 0; i < r->point_count; i++) {
      const aq_capacity_point *p = &t->point[r->point_start + i];
      aq_plot_csv_text(f, r->record);
      fprintf(f, "%s,%zu,%s,%s,%s,%s,%d,%s\n", r->polarity, c->rec[k] + 1, AQ_TEXT_NUM(p->scale),
              AQ_TEXT_NUM(p->scale * c->pga[k]), AQ_TEXT_NUM(p->peak_rotation_rad),
              AQ_TEXT_NUM(p->peak_rotation_over_qc), p->collapsed, AQ_TEXT_NUM(p->collapse_time_s));
    }
  }
  fprintf(f, "\n# collapse intervals (shaded; scale factors; record_pga_g: the record's "
             "PGA at scale 1)\n");
  fprintf(f, "record,polarity,move_scale,scale_max,collapse_lo,collapse_hi,legend_no,"
             "record_pga_g\n");
  for (size_t k = 0; k < c->n; k++) {
    const aq_h5_capacity_row *r = &t->row[c->row[k]];
    int64_t m = r->i[I_COUNT];
    for (int64_t j = 0; j < (m ? m : 1); j++) {
      size_t q = (size_t)(r->i[I_START] + j);
      double a = m && q < t->ninterval ? t->interval[2 * q] : NAN;
      double b = m && q < t->ninterval ? t->interval[2 * q + 1] : NAN;
      aq_plot_csv_text(f, r->record);
      fprintf(f, "%s,%s,%s,%s,%s,%zu,%s\n", r->polarity, AQ_TEXT_NUM(r->d[D_MOVE]),
              AQ_TEXT_NUM(r->d[D_SMAX]), AQ_TEXT_NUM(a), AQ_TEXT_NUM(b), c->rec[k] + 1,
              AQ_TEXT_NUM(c->pga[k]));
    }
  }
}

/* The record's PGA at scale 1 (g) from a row: the IM at the cap over the
 * cap, else the first collapse's PGA over its scale; NAN if neither. */
static double row_pga(const aq_h5_capacity_row *r)
{
  double p = r->im_cap[0] / r->d[D_SMAX]; /* im 0: pga_g */
  if (!(p > 0 && isfinite(p)))
    p = r->d[D_PGA] / r->d[D_FIRST];
  return p > 0 && isfinite(p) ? p : NAN;
}

/* The lines of c->arch: rows, colours (one per record), PGAs. */
static aq_status lines_build(cap *c, const char *source, aq_error *err)
{
  const aq_h5_capacity_table *t = c->t;
  c->row = malloc(t->n * sizeof *c->row);
  c->pga = malloc(t->n * sizeof *c->pga);
  c->color = malloc(t->n * sizeof *c->color);
  c->rec = malloc(t->n * sizeof *c->rec);
  if (!c->row || !c->pga || !c->color || !c->rec)
    return aq_error_set(err, AQ_ENOMEM, source, -1, -1, NULL, "out of memory");
  size_t nrec = 0;
  for (size_t k = 0; k < t->n; k++) {
    const aq_h5_capacity_row *r = &t->row[k];
    if (strcmp(r->arch, c->arch) != 0)
      continue;
    if (c->n && strcmp(t->row[c->row[c->n - 1]].record, r->record) != 0)
      nrec++;
    c->pga[c->n] = row_pga(r);
    c->color[c->n] = LINE_COLOR[nrec % NCOLOR];
    c->rec[c->n] = nrec;
    c->have_pol[reversed(r)] = 1;
    c->row[c->n++] = k;
    if (c->o->y_pga && r->point_count && isnan(c->pga[c->n - 1]))
      return aq_error_set(err, AQ_EVALUE, source, -1, -1, "--y",
                          "expected the PGA of record %s (capacity/im_cap), got none "
                          "(plot the scale: --y scale)", r->record);
  }
  c->nrec = c->n ? nrec + 1 : 0;
  if (c->n == 0)
    return aq_error_set(err, AQ_EVALUE, source, -1, -1, "--arch",
                        "expected an arch of the file such as \"%s\", got \"%s\"",
                        t->row[0].arch, c->arch);
  return AQ_OK;
}

aq_status aq_plot_capacity(const aq_h5_capacity_table *t, const aq_plot_capacity_opts *o,
                           const char *source, const char *target, const char *data,
                           double *draw_s, aq_error *err)
{
  cap c;
  memset(&c, 0, sizeof c);
  c.t = t;
  c.o = o;
  c.arch = o->arch;
  int m = 0;
  if (o->im) {
    for (m = 0; m < AQ_FRAGILITY_NIM && strcmp(aq_fragility_im_names[m], o->im) != 0; m++)
      ;
    if (m == AQ_FRAGILITY_NIM)
      return aq_error_set(err, AQ_EOPTION, source, -1, -1, "--im",
                          "expected one of pga_g, pgv_m_s, pgd_m, arias_m_s, cav_m_s, "
                          "pga_lambda0, got \"%s\"", o->im);
  }
  if (t->n == 0)
    return aq_error_set(err, AQ_EFORMAT, source, -1, -1, "capacity",
                        "expected a capacity results file (archquake capacity -o), got none");
  if (!c.arch)
    c.arch = t->row[0].arch;
  aq_status rc = lines_build(&c, source, err);
  if (rc == AQ_OK && frag_build(&c, m) != 0)
    rc = aq_error_set(err, AQ_ENOMEM, source, -1, -1, NULL, "out of memory");
  if (rc == AQ_OK) {
    ranges(&c);
    double nrows = c.n ? (double)c.n + (double)c.rec[c.n - 1] * RECORD_GAP_PX / ROW_PX : 1;
    const double frame_px = 50 + 70 + 104 + 50, frag_px = 500; /* around the strips; below */
    c.strips_px = ROW_PX * nrows;
    c.page_px = frame_px + c.strips_px + frag_px;
    c.split = frag_px / c.page_px;
    rc = aq_plot_render(target, 1000, (int)c.page_px, draw, &c, draw_s, err);
  }
  if (rc == AQ_OK && data) {
    aq_outfile tmp;
    FILE *f = aq_plot_csv_open(data, &tmp, err);
    if (!f)
      rc = err->status;
    else {
      lines_csv(f, &c);
      frag_csv(f, &c);
      rc = aq_plot_csv_close(&tmp, err);
    }
  }
  free(c.row);
  free(c.pga);
  free(c.color);
  free(c.rec);
  free(c.f.x);
  return rc;
}
