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
  char im_axis[96], im_unit[32]; /* the fragility IM's axis title and unit */
  /* the layout, mm of the figure (72 points an inch) from its top left */
  double w, h;                /* the figure */
  char title[2][300];         /* the strips' title, on one or two lines */
  int title_lines;
  double title_y;             /* its first line's centre */
  double note_y;              /* a file without scan points: the note's centre */
  double head_y;              /* the first collapses' column head */
  double sx0, sx1, sy0, sy1;  /* the strips */
  char (*label)[1100];        /* each strip's label (record name, polarity) */
  char (*fc)[64];             /* each strip's first collapse */
  double key_y;               /* the keys' top */
  double marks_x;             /* the marks' legend: its left edge */
  char ftitle[2][400];        /* the fragility's title */
  int ftitle_lines;
  double ftitle_y;
  double fx0, fx1, fy0, fy1;  /* the fragility's frame */
  double leg_y, leg_colw;     /* its legend: top, a column's width */
  int leg_cols;
} cap;

enum { D_MOVE = 0, D_FIRST = 1, D_PGA = 2, D_SMAX = 4, I_START = 2, I_COUNT = 3 };

/* Colours of the lines, one per record, cycled. */
static const int LINE_COLOR[] = {AQ_PC_BLUE,   AQ_PC_ORANGE, AQ_PC_GREEN, AQ_PC_RED,
                                 AQ_PC_PURPLE, AQ_PC_TEAL,   AQ_PC_BROWN, AQ_PC_PINK,
                                 AQ_PC_OLIVE,  AQ_PC_NAVY};
enum { NCOLOR = sizeof LINE_COLOR / sizeof LINE_COLOR[0] };
enum { ROW_PX = 26, RECORD_GAP_PX = 8 }; /* a strip, the space between records */

/* The layout's sizes (mm of the figure, 72 points an inch): the figure is
 * 1000 points wide, as tall as its strips make it; every text is measured
 * (aq_plot_text_em) and given room, so nothing runs off the figure or into
 * another text. */
static const double PT_MM = 25.4 / 72;
static const double TXT_MM = 3.7;     /* character height: labels, ticks, axes */
static const double TITLE_MM = 3.9;   /* titles */
static const double KEY_MM = 3.4;     /* the keys' texts */
static const double MARGIN_MM = 6;    /* the figure's edge */
static const double PAD_MM = 4;       /* between bands */
static const double FRAG_H_MM = 100;  /* the fragility's frame */
static const double SAMPLE_MM = 9;    /* a key's sample (line, box, symbol) */
static const double LABEL_SHARE = 0.4; /* at most this much of the width for labels */

/* Width of s at character height ht_mm, mm. */
static double width_mm(const char *s, double ht_mm)
{
  return aq_plot_text_em(s) * aq_plot_font_mm(ht_mm);
}

/* A text line's pitch at character height ht_mm: the font's line and a
 * sixth more. */
static double pitch_mm(double ht_mm)
{
  return 1.164 * aq_plot_font_mm(ht_mm) * 7 / 6;
}

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

/* The viewport of the figure's rectangle x0..x1, y0..y1 (mm from its top
 * left). */
static void vp_mm(const cap *c, double x0, double x1, double y0, double y1)
{
  plvpor(x0 / c->w, x1 / c->w, 1 - y1 / c->h, 1 - y0 / c->h);
}

/* The whole figure as the world, in mm from its top left: where the
 * titles and keys are written with plptex (at their centre line). */
static void page_mm(const cap *c)
{
  plvpor(0, 1, 0, 1);
  plwind(0, c->w, c->h, 0);
}

/* A key's entry at (x, y) (mm, its centre line): its sample, a line of
 * style (>= 1), a box of colour (style -1) or a symbol, then its text. */
static void key_entry(double x, double y, int color, int style, const char *sym,
                      const char *text)
{
  plcol0(color);
  if (style > 0) {
    PLFLT lx[2] = {x, x + SAMPLE_MM}, ly[2] = {y, y};
    pllsty(style);
    plwidth(2);
    plline(2, lx, ly);
    plwidth(1);
    pllsty(1);
  } else if (style < 0) {
    PLFLT bx[4] = {x, x + SAMPLE_MM, x + SAMPLE_MM, x};
    PLFLT by[4] = {y - 1.6, y - 1.6, y + 1.6, y + 1.6};
    plfill(4, bx, by);
  }
  if (sym && sym[0]) {
    PLFLT px = x + SAMPLE_MM / 2, py = y;
    plstring(1, &px, &py, sym);
  }
  plcol0(AQ_PC_FG);
  plptex(x + SAMPLE_MM + 2, y, 1, 0, 0, text);
}

/* The entries the fragility's key shows: only what is drawn. */
static int frag_keys(const cap *c, const char **tx, int *col, int *st, const char **sym)
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

static void draw_fragility(const cap *c)
{
  const frag *f = &c->f;
  const double *lx = f->cx;
  aq_plot_text_height(TXT_MM);
  vp_mm(c, c->fx0, c->fx1, c->fy0, c->fy1);
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
  page_mm(c);
  aq_plot_text_height(TITLE_MM);
  for (int i = 0; i < c->ftitle_lines; i++)
    plptex(c->w / 2, c->ftitle_y + i * pitch_mm(TITLE_MM), 1, 0, 0.5, c->ftitle[i]);
  const char *tx[4], *sym[4];
  int col[4], st[4], k = frag_keys(c, tx, col, st, sym);
  aq_plot_text_height(KEY_MM);
  for (int i = 0; i < k; i++)
    key_entry(c->fx0 + (i % c->leg_cols) * c->leg_colw,
              c->leg_y + (i / c->leg_cols + 0.5) * pitch_mm(KEY_MM), col[i], st[i], sym[i], tx[i]);
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
  const char *yt = c->o->y_pga ? AX_PGA : AX_SCALE;
  pladv(0);
  aq_plot_text_height(TXT_MM);
  double nrows = c->n ? row_top(c, c->n - 1) + 1 : 1;
  vp_mm(c, c->sx0, c->sx1, c->sy0, c->sy1);
  plwind(axis_y(c, c->ylo), axis_y(c, c->yhi), nrows, 0);
  PLFLT cpos[4] = {0, 0.1, 0.5, 1}, rr[4] = {1, 1, 0.95, 0.55}; /* as the suite's */
  PLFLT gg[4] = {1, 0.93, 0.6, 0.3}, bb[4] = {1, 0.6, 0.2, 0.1};
  plscmap1l(1, 4, cpos, rr, gg, bb, NULL);
  for (size_t k = 0; k < c->n; k++) {
    double y0 = row_top(c, k) + 0.12, y1 = row_top(c, k) + 0.88;
    draw_strip(c, k, y0, y1);
    /* the label (the record's name on its first strip, and the polarity)
       and beside it the first collapse, R for a resurrection */
    double ymid = 1 - (row_top(c, k) + 0.5) / nrows;
    plcol0(AQ_PC_FG);
    plmtex("lv", 0.8, ymid, 1, c->label[k]);
    plmtex("rv", 0.8, ymid, 0, c->fc[k]);
  }
  plcol0(AQ_PC_FG);
  plbox(c->logy ? "bnstlfi" : "bnsti", 0, 0, "", 0, 0); /* ticks out, off the last strip */
  plmtex("b", 3.0, 0.5, 0.5, yt);
  /* the titles and the column's head */
  page_mm(c);
  plptex(c->sx1 + 0.8 * TXT_MM, c->head_y, 1, 0, 0, "first collapse");
  aq_plot_text_height(TITLE_MM);
  for (int i = 0; i < c->title_lines; i++)
    plptex(c->w / 2, c->title_y + i * pitch_mm(TITLE_MM), 1, 0, 0.5, c->title[i]);
  if (!t->have_points) {
    aq_plot_text_height(KEY_MM);
    plptex(c->w / 2, c->note_y, 1, 0, 0.5, "(no scanned points: written before "
                                           "capacity/scan_points; the intervals only)");
  }
  /* the key under the axis: the shade, then what the marks mean */
  aq_plot_text_height(TXT_MM);
  double cx0 = MARGIN_MM + 4 * TXT_MM, cx1 = c->marks_x - 4 * TXT_MM;
  vp_mm(c, cx0, cx1, c->key_y, c->key_y + 16 * PT_MM);
  double ktop = c->o->x_rad ? c->xhi : 1; /* the shade's scale: 0 to ktop */
  plwind(0, ktop, 0, 1);
  for (int i = 0; i < 50; i++) {
    plcol1((i + 0.5) / 50);
    fill_box(ktop * i / 50.0, ktop * (i + 1) / 50.0, 0, 1);
  }
  plcol0(AQ_PC_FG);
  plbox("bcnst", 0, 0, "bc", 0, 0);
  plmtex("b", 3.2, 0.5, 0.5, c->o->x_rad ? AX_RAD : AX_QC);
  /* what the marks mean, one a line */
  page_mm(c);
  aq_plot_text_height(KEY_MM);
  double lp = pitch_mm(KEY_MM), x = c->marks_x, y = c->key_y + lp / 2;
  plcol0(AQ_PC_RED);
  fill_box(x, x + SAMPLE_MM, y - 1.8, y + 1.8);
  plcol0(AQ_PC_BG);
  plpsty(3);
  fill_box(x, x + SAMPLE_MM, y - 1.8, y + 1.8);
  plpsty(0);
  plcol0(AQ_PC_FG);
  PLFLT tx[2] = {x + SAMPLE_MM / 2, x + SAMPLE_MM / 2}, ty[2] = {y + lp - 1.8, y + lp + 1.8};
  plwidth(2);
  plline(2, tx, ty);
  plwidth(1);
  plptex(x + SAMPLE_MM / 2, y + 2 * lp, 1, 0, 0.5, "R");
  static const char *const marks[4] = {"collapse (a collapse interval)", "a change of verdict",
                                       "survives again above a collapse",
                                       "blank: below the scale that moves it"};
  for (int i = 0; i < 4; i++)
    plptex(x + SAMPLE_MM + 2, y + i * lp, 1, 0, 0, marks[i]);
  draw_fragility(c);
  return 0;
}

/* The fragility panel's data after the intervals' (a second header). */
static void frag_csv(FILE *f, const cap *c)
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

/* The fragility IM m's axis title and unit: the six by table, a spectral
 * measure from its name (sa_0.2s_g: Sa(0.2 s); sa_avg_0.1_1s_g: Sa_avg
 * over 0.1 to 1 s; both in g). */
static void im_titles(cap *c, int m)
{
  const char *name = c->t->im_name[m];
  double t1, t2;
  if (m < AQ_FRAGILITY_NIM) {
    snprintf(c->im_axis, sizeof c->im_axis, "%s", AX_IM[m]);
    snprintf(c->im_unit, sizeof c->im_unit, "%s", IM_UNIT[m]);
  } else if (sscanf(name, "sa_avg_%lf_%lfs_g", &t1, &t2) == 2) {
    snprintf(c->im_axis, sizeof c->im_axis, "Sa#davg#u over %g–%g s (g)", t1, t2);
    snprintf(c->im_unit, sizeof c->im_unit, "g");
  } else if (sscanf(name, "sa_%lfs_g", &t1) == 1) {
    snprintf(c->im_axis, sizeof c->im_axis, "Sa(%g s) (g)", t1);
    snprintf(c->im_unit, sizeof c->im_unit, "g");
  } else {
    aq_plot_escape(name, c->im_axis, sizeof c->im_axis);
    c->im_unit[0] = '\0';
  }
}

/* Split s at its last ": " that leaves a first part within w mm at
 * character height ht into a[0], a[1] (the part after the colon); *lines 1
 * when s fits whole or cannot be split so. */
static void split_title(const char *s, double w, double ht, char (*a)[400], int *lines)
{
  snprintf(a[0], sizeof a[0], "%s", s);
  a[1][0] = '\0';
  *lines = 1;
  if (width_mm(s, ht) <= w)
    return;
  const char *cut = NULL;
  for (const char *p = strstr(s, ": "); p; p = strstr(p + 1, ": "))
    cut = p;
  if (!cut)
    return;
  snprintf(a[0], sizeof a[0], "%.*s", (int)(cut + 1 - s), s);
  snprintf(a[1], sizeof a[1], "%s", cut + 2);
  *lines = 2;
}

/* The layout (see the sizes above): every text measured before the figure
 * is drawn, its height then known.  -1 when out of memory. */
static int plan(cap *c)
{
  const aq_h5_capacity_table *t = c->t;
  c->w = 1000 * PT_MM;
  c->label = calloc(c->n ? c->n : 1, sizeof *c->label);
  c->fc = calloc(c->n ? c->n : 1, sizeof *c->fc);
  const char **names = malloc((c->nrec ? c->nrec : 1) * sizeof *names);
  char(*short_names)[1024] = malloc((c->nrec ? c->nrec : 1) * sizeof *short_names);
  if (!c->label || !c->fc || !names || !short_names) {
    free(names);
    free(short_names);
    return -1;
  }
  /* the labels: each record's name, shortened as much as the label share
     needs, the names of one figure kept distinct */
  size_t longest = 1;
  for (size_t k = 0; k < c->n; k++)
    if (k == 0 || c->rec[k] != c->rec[k - 1]) {
      names[c->rec[k]] = base(t->row[c->row[k]].record);
      size_t len = strlen(names[c->rec[k]]);
      longest = len > longest ? len : longest;
    }
  double pol_w = width_mm("  reversed", TXT_MM), room = LABEL_SHARE * c->w - pol_w;
  for (size_t keep = longest + 1; keep-- > 5;) {
    aq_plot_ellipsize_set(names, c->nrec, keep, short_names[0], sizeof short_names[0]);
    double widest = 0;
    for (size_t r = 0; r < c->nrec; r++)
      widest = fmax(widest, width_mm(short_names[r], TXT_MM));
    if (widest <= room)
      break;
  }
  double label_w = 0, fc_w = width_mm("first collapse", TXT_MM);
  for (size_t k = 0; k < c->n; k++) {
    const aq_h5_capacity_row *r = &t->row[c->row[k]];
    int first = k == 0 || c->rec[k] != c->rec[k - 1];
    snprintf(c->label[k], sizeof c->label[k], "%s  %s", first ? short_names[c->rec[k]] : "",
             r->polarity);
    label_w = fmax(label_w, width_mm(c->label[k], TXT_MM));
    double f = r->d[D_FIRST];
    if (strcmp(r->status, "ok") != 0 && strncmp(r->status, "collapse", 8) != 0 && isnan(f) &&
        r->point_count == 0)
      snprintf(c->fc[k], sizeof c->fc[k], "%s", r->status);
    else if (isfinite(f))
      snprintf(c->fc[k], sizeof c->fc[k], "%.3g%s", y_of(c, k, f), r->i[0] > 0 ? "  R" : "");
    else
      snprintf(c->fc[k], sizeof c->fc[k], "none");
    fc_w = fmax(fc_w, width_mm(c->fc[k], TXT_MM));
  }
  free(names);
  free(short_names);
  /* across: labels, strips, first collapses */
  double gap = 0.8 * TXT_MM, w = c->w, y;
  c->sx0 = MARGIN_MM + label_w + gap;
  c->sx1 = w - MARGIN_MM - fc_w - gap;
  /* down: the title, the column's head, the strips, their axis */
  char title[300];
  snprintf(title, sizeof title, "arch %.200s: the verdict of each scanned run", c->arch);
  char lines[2][400];
  split_title(title, w - 2 * MARGIN_MM, TITLE_MM, lines, &c->title_lines);
  for (int i = 0; i < 2; i++)
    snprintf(c->title[i], sizeof c->title[i], "%.299s", lines[i]);
  double lt = pitch_mm(TITLE_MM), lp = pitch_mm(TXT_MM), lk = pitch_mm(KEY_MM);
  y = MARGIN_MM;
  c->title_y = y + lt / 2;
  y += c->title_lines * lt;
  if (!t->have_points) {
    c->note_y = y + lk / 2;
    y += lk;
  }
  c->head_y = y + lp / 2;
  y += lp;
  double nrows = c->n ? row_top(c, c->n - 1) + 1 : 1;
  c->sy0 = y;
  c->sy1 = y += nrows * ROW_PX * PT_MM;
  /* the axis' tick labels and title (3 character heights below it) */
  y += 3.0 * TXT_MM + 0.6 * lp + PAD_MM;
  /* the keys: the shade's bar (16 points), its labels and title (3.2
     character heights below it); the marks, four lines */
  c->key_y = y;
  c->marks_x = w / 2 + 2 * MARGIN_MM;
  double marks_w = SAMPLE_MM + 2 + width_mm("blank: below the scale that moves it", KEY_MM);
  if (c->marks_x + marks_w > w - MARGIN_MM)
    c->marks_x = w - MARGIN_MM - marks_w;
  y += fmax(16 * PT_MM + 3.2 * TXT_MM + 0.6 * lp, 4 * lk) + 2 * PAD_MM;
  /* the fragility: its title, frame, axis and key */
  const frag *f = &c->f;
  const aq_h5_fragility_fit *q = f->fit;
  char ftitle[400], med[48] = "";
  if (q && isfinite(q->median) && q->beta > 0) {
    snprintf(med, sizeof med, "%.3g", q->median);
    snprintf(ftitle, sizeof ftitle,
             "fragility of arch %.100s: median %s %s, #gb %.3g (%zu records, %zu censored)",
             c->arch, med, c->im_unit, q->beta, f->n, f->n - f->ncol);
  } else
    snprintf(ftitle, sizeof ftitle, "fragility of arch %.100s: %s (%zu records, %zu censored)",
             c->arch, q ? "no fit, < 2 collapse values" : "no fit in the file", f->n,
             f->n - f->ncol);
  split_title(ftitle, w - 2 * MARGIN_MM, TITLE_MM, c->ftitle, &c->ftitle_lines);
  c->ftitle_y = y + lt / 2;
  y += c->ftitle_lines * lt + 0.5 * lp;
  c->fx0 = MARGIN_MM + 4.0 * TXT_MM + 0.6 * lp;
  c->fx1 = w - MARGIN_MM - 2 * TXT_MM; /* room for half of the last tick's label */
  c->fy0 = y;
  c->fy1 = y += FRAG_H_MM;
  y += 3.0 * TXT_MM + 0.6 * lp + PAD_MM;
  const char *tx[4], *sym[4];
  int col[4], st[4], k = frag_keys(c, tx, col, st, sym);
  double entry = 0;
  for (int i = 0; i < k; i++)
    entry = fmax(entry, SAMPLE_MM + 2 + width_mm(tx[i], KEY_MM) + 2 * MARGIN_MM);
  c->leg_cols = k ? k : 1;
  while (c->leg_cols > 1 && c->fx0 + c->leg_cols * entry > w - MARGIN_MM)
    c->leg_cols--;
  c->leg_colw = entry;
  c->leg_y = y;
  y += (k + c->leg_cols - 1) / c->leg_cols * lk + MARGIN_MM;
  c->h = ceil(y / PT_MM) * PT_MM; /* whole points */
  return 0;
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
  int m = 0; /* the IMs the file holds: the six, then its spectral measures */
  size_t nim = t->nim ? t->nim : AQ_FRAGILITY_NIM;
  if (o->im) {
    for (m = 0; m < (int)nim && strcmp(t->im_name[m], o->im) != 0; m++)
      ;
    if (m == (int)nim) {
      char list[600] = "";
      for (size_t j = 0, n = 0; j < nim && n < sizeof list; j++)
        n += (size_t)snprintf(list + n, sizeof list - n, "%s%s", j ? ", " : "", t->im_name[j]);
      return aq_error_set(err, AQ_EOPTION, source, -1, -1, "--im",
                          "expected one of the file's measures (%s), got \"%s\"", list, o->im);
    }
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
    im_titles(&c, m);
    if (plan(&c) != 0)
      rc = aq_error_set(err, AQ_ENOMEM, source, -1, -1, NULL, "out of memory");
  }
  if (rc == AQ_OK) /* 1000 points wide, as tall as the plan */
    rc = aq_plot_render(target, 1000, (int)ceil(c.h / PT_MM), draw, &c, draw_s, err);
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
  free(c.label);
  free(c.fc);
  return rc;
}
