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
 * its cap (open circles).  The fragility panel is drawn in
 * capacity_frag.c, the layout planned in capacity_layout.c. */
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"
#include "capacity_fig.h"

static const char *const AX_SCALE = "scale factor on the processed record (1)";
static const char *const AX_PGA = "PGA of the scaled record (g)";
static const char *const AX_QC = "survived: peak rotation / q#dc#u (1)";
static const char *const AX_RAD = "survived: peak rotation (rad)";

/* Colours of the lines, one per record, cycled. */
static const int LINE_COLOR[] = {AQ_PC_BLUE,   AQ_PC_ORANGE, AQ_PC_GREEN, AQ_PC_RED,
                                 AQ_PC_PURPLE, AQ_PC_TEAL,   AQ_PC_BROWN, AQ_PC_PINK,
                                 AQ_PC_OLIVE,  AQ_PC_NAVY};
enum { NCOLOR = sizeof LINE_COLOR / sizeof LINE_COLOR[0] };

/* Width of s at character height ht_mm, mm. */
double aq_plot_cap_width_mm(const char *s, double ht_mm)
{
  return aq_plot_text_em(s) * aq_plot_font_mm(ht_mm);
}

/* A text line's pitch at character height ht_mm: the font's line and a
 * sixth more. */
double aq_plot_cap_pitch_mm(double ht_mm)
{
  return 1.164 * aq_plot_font_mm(ht_mm) * 7 / 6;
}

const char *aq_plot_cap_base(const char *p)
{
  const char *b = strrchr(p, '/');
  return b ? b + 1 : p;
}

/* The viewport of the figure's rectangle x0..x1, y0..y1 (mm from its top
 * left). */
void aq_plot_cap_vp_mm(const cap *c, double x0, double x1, double y0, double y1)
{
  plvpor(x0 / c->w, x1 / c->w, 1 - y1 / c->h, 1 - y0 / c->h);
}

/* The whole figure as the world, in mm from its top left: where the
 * titles and keys are written with plptex (at their centre line). */
void aq_plot_cap_page_mm(const cap *c)
{
  plvpor(0, 1, 0, 1);
  plwind(0, c->w, c->h, 0);
}

/* A key's entry at (x, y) (mm, its centre line): its sample, a line of
 * style (>= 1), a box of colour (style -1) or a symbol, then its text. */
void aq_plot_cap_key_entry(double x, double y, int color, int style, const char *sym,
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

static int reversed(const aq_h5_capacity_row *r)
{
  return strcmp(r->polarity, "reversed") == 0;
}

/* Line k's y of scale s (scale, or PGA in g), and on the drawn axis. */
double aq_plot_cap_y_of(const cap *c, size_t k, double s)
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
    double v[2] = {aq_plot_cap_y_of(c, k, r->d[D_MOVE]), aq_plot_cap_y_of(c, k, r->d[D_SMAX])};
    for (int j = 0; j < 2; j++)
      if (v[j] > 0 && isfinite(v[j])) {
        lo = fmin(lo, v[j]);
        hi = fmax(hi, v[j]);
      }
    for (size_t i = 0; i < r->point_count; i++) {
      const aq_capacity_point *p = &t->point[r->point_start + i];
      double y = aq_plot_cap_y_of(c, k, p->scale), x = x_of(c, p);
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
double aq_plot_cap_row_top(const cap *c, size_t k)
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
  double xmove = isfinite(move) && aq_plot_cap_y_of(c, k, move) > c->ylo ? axis_y(c, aq_plot_cap_y_of(c, k, move)) : xa;
  double xcap = isfinite(smax) && aq_plot_cap_y_of(c, k, smax) > 0 ? axis_y(c, aq_plot_cap_y_of(c, k, smax)) : xb;
  PLFLT lx[2] = {xa, xmove}, ly[2] = {0.5 * (y0 + y1), 0.5 * (y0 + y1)};
  plcol0(AQ_PC_GREY); /* at rest: a thin line */
  plline(2, lx, ly);
  double prev = xmove;
  for (size_t i = 0; i < r->point_count; i++) {
    const aq_capacity_point *p = &t->point[r->point_start + i];
    double y = aq_plot_cap_y_of(c, k, p->scale);
    if (!(y > 0) || p->collapsed)
      continue;
    double x = axis_y(c, y), next = xcap;
    for (size_t j = i + 1; j < r->point_count; j++) {
      double yj = aq_plot_cap_y_of(c, k, t->point[r->point_start + j].scale);
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
    double a = aq_plot_cap_y_of(c, k, t->interval[2 * q]);
    double b = aq_plot_cap_y_of(c, k, fmin(t->interval[2 * q + 1], smax));
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
  double nrows = c->n ? aq_plot_cap_row_top(c, c->n - 1) + 1 : 1;
  aq_plot_cap_vp_mm(c, c->sx0, c->sx1, c->sy0, c->sy1);
  plwind(axis_y(c, c->ylo), axis_y(c, c->yhi), nrows, 0);
  PLFLT cpos[4] = {0, 0.1, 0.5, 1}, rr[4] = {1, 1, 0.95, 0.55}; /* as the suite's */
  PLFLT gg[4] = {1, 0.93, 0.6, 0.3}, bb[4] = {1, 0.6, 0.2, 0.1};
  plscmap1l(1, 4, cpos, rr, gg, bb, NULL);
  for (size_t k = 0; k < c->n; k++) {
    double y0 = aq_plot_cap_row_top(c, k) + 0.12, y1 = aq_plot_cap_row_top(c, k) + 0.88;
    draw_strip(c, k, y0, y1);
    /* the label (the record's name on its first strip, and the polarity)
       and beside it the first collapse, R for a resurrection */
    double ymid = 1 - (aq_plot_cap_row_top(c, k) + 0.5) / nrows;
    plcol0(AQ_PC_FG);
    plmtex("lv", 0.8, ymid, 1, c->label[k]);
    plmtex("rv", 0.8, ymid, 0, c->fc[k]);
  }
  plcol0(AQ_PC_FG);
  plbox(c->logy ? "bnstlfi" : "bnsti", 0, 0, "", 0, 0); /* ticks out, off the last strip */
  plmtex("b", 3.0, 0.5, 0.5, yt);
  /* the titles and the column's head */
  aq_plot_cap_page_mm(c);
  plptex(c->sx1 + 0.8 * TXT_MM, c->head_y, 1, 0, 0, "first collapse");
  aq_plot_text_height(TITLE_MM);
  for (int i = 0; i < c->title_lines; i++)
    plptex(c->w / 2, c->title_y + i * aq_plot_cap_pitch_mm(TITLE_MM), 1, 0, 0.5, c->title[i]);
  if (!t->have_points) {
    aq_plot_text_height(KEY_MM);
    plptex(c->w / 2, c->note_y, 1, 0, 0.5, "(no scanned points: written before "
                                           "capacity/scan_points; the intervals only)");
  }
  /* the key under the axis: the shade, then what the marks mean */
  aq_plot_text_height(TXT_MM);
  double cx0 = MARGIN_MM + 4 * TXT_MM, cx1 = c->marks_x - 4 * TXT_MM;
  aq_plot_cap_vp_mm(c, cx0, cx1, c->key_y, c->key_y + 16 * PT_MM);
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
  aq_plot_cap_page_mm(c);
  aq_plot_text_height(KEY_MM);
  double lp = aq_plot_cap_pitch_mm(KEY_MM), x = c->marks_x, y = c->key_y + lp / 2;
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
  aq_plot_cap_draw_fragility(c);
  return 0;
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
  if (rc == AQ_OK && aq_plot_cap_frag_build(&c, m) != 0)
    rc = aq_error_set(err, AQ_ENOMEM, source, -1, -1, NULL, "out of memory");
  if (rc == AQ_OK) {
    ranges(&c);
    aq_plot_cap_im_titles(&c, m);
    if (aq_plot_cap_plan(&c) != 0)
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
      aq_plot_cap_frag_csv(f, &c);
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
