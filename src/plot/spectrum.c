/* spectrum.c: the response spectra of a file of `archquake spectrum -o`:
 * pseudo-spectral acceleration (g) against period (s, log axis), one curve
 * per (record, component, damping): a colour per record and component, a
 * line style per damping. */
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

static const char *const AX_X = "period T (s)",
                         *const AX_Y = "pseudo-spectral acceleration PSA (g)";

static const int COLOR[] = {AQ_PC_BLUE,   AQ_PC_RED,  AQ_PC_GREEN, AQ_PC_ORANGE,
                            AQ_PC_PURPLE, AQ_PC_TEAL, AQ_PC_BROWN, AQ_PC_PINK,
                            AQ_PC_OLIVE,  AQ_PC_NAVY};
enum { NCOLOR = sizeof COLOR / sizeof COLOR[0], NSTYLE = 8 };

/* The figure's layout, pixels of a PNG (points of SVG and PDF): the plot
 * PLOT_PX high under TOP_PX of title, then the axis title (GAP_PX), then
 * the key, ROW_PX a row (aq_plot_key_below). */
enum { WIDTH_PX = 1000, TOP_PX = 58, PLOT_PX = 470, GAP_PX = 78, ROW_PX = 29, PAD_PX = 24 };

/* the key's ends, fractions of the figure's width */
static const double KEY_X0 = 0.03, KEY_X1 = 0.97;

/* the text's height, mm of the figure (72 points an inch): the axes' and
   title's, the key's; the same however tall the key makes the figure */
static const double TEXT_MM = 5.85, KEY_MM = 4.9;

static int fig_height(size_t nrow)
{
  return TOP_PX + PLOT_PX + GAP_PX + ROW_PX * (int)nrow + PAD_PX;
}

enum { NAME = 600, POST = 240 };
typedef struct {
  size_t start, n;  /* its rows of the table (periods, in the file's order) */
  int color, style;
  char name[NAME], post[POST]; /* its key: the record whole, then the component and damping */
} curve;

typedef struct {
  const aq_h5_spectra_table *t;
  const char *source;
  curve *c;
  size_t nc;
  double tlo, thi, amax; /* the plotted range: periods (s), PSA (g) */
  aq_plot_key *key;      /* nc */
  size_t ncol;           /* of the key */
} fig;

static const char *base(const char *path)
{
  const char *s = strrchr(path, '/');
  return s ? s + 1 : path;
}

/* A record column as drawn: a RECORD by its file name; a --components
 * pair by its two file names, their common start and end written once
 * ("RSN6_IMPVALL.I_I-ELC{180-hor1,270-hor2}.AT2"); whole, not escaped. */
static void display_name(const char *record, char *out, size_t cap)
{
  const char *comma = strchr(record, ',');
  if (!comma) {
    aq_text_fit(out, cap, "%s", base(record));
    return;
  }
  char first[4096]; /* a path whole (PATH_MAX): its end is the file's name */
  aq_text_fit(first, sizeof first, "%.*s", (int)(comma - record), record);
  const char *a = base(first), *b = base(comma + 1);
  size_t la = strlen(a), lb = strlen(b), p = 0, q = 0;
  while (p < la && p < lb && a[p] == b[p])
    p++;
  while (q < la - p && q < lb - p && a[la - 1 - q] == b[lb - 1 - q])
    q++;
  if (p + q > 0)
    aq_text_fit(out, cap, "%.*s{%.*s,%.*s}%s", (int)p, a, (int)(la - p - q), a + p,
                (int)(lb - p - q), b + p, a + la - q);
  else
    aq_text_fit(out, cap, "%s,%s", a, b);
}

static int draw(void *ctx, aq_error *err)
{
  (void)err;
  const fig *F = ctx;
  const aq_h5_spectra_table *t = F->t;
  double x0 = log10(F->tlo), x1 = log10(F->thi);
  if (x1 - x0 < 0.5) { /* at least half a decade */
    x0 -= 0.25;
    x1 += 0.25;
  }
  double y1 = F->amax > 0 ? 1.08 * F->amax : 1;
  pladv(0);
  aq_plot_text_height(TEXT_MM);
  /* the plot above (PLOT_PX high), the legend below it */
  double h = (double)fig_height(aq_plot_key_rows(F->nc, F->ncol));
  double gap = GAP_PX / h, bottom = (h - PLOT_PX - TOP_PX) / h;
  plvpor(0.1, 0.96, bottom, 1 - TOP_PX / h);
  plwind(x0, x1, 0, y1);
  plcol0(AQ_PC_LIGHT);
  plbox("glh", 0, 0, "g", 0, 0); /* a grid at every decade's ticks */
  char title[1100], name[600], whole[600];
  display_name(F->source, whole, sizeof whole);
  aq_plot_shorten_to(whole, 0.94 * aq_plot_page_w_mm() -
                                aq_plot_text_mm("response spectra of  (peaks: not stated)"),
                     name, sizeof name);
  snprintf(title, sizeof title, "response spectra of %s (peaks: %s)", name,
           t->peaks >= 0 ? aq_spectrum_peaks_names[t->peaks] : "not stated");
  size_t most = 0;
  for (size_t k = 0; k < F->nc; k++)
    most = F->c[k].n > most ? F->c[k].n : most;
  PLFLT *x = malloc((most ? most : 1) * sizeof *x), *y = malloc((most ? most : 1) * sizeof *y);
  for (size_t k = 0; x && y && k < F->nc; k++) {
    const curve *c = &F->c[k];
    for (size_t i = 0; i < c->n; i++) {
      x[i] = log10(t->period_s[c->start + i]);
      y[i] = t->psa_g[c->start + i];
    }
    plcol0(c->color);
    pllsty(c->style);
    plwidth(1.5);
    plline((PLINT)c->n, x, y);
  }
  free(x);
  free(y);
  pllsty(1);
  plwidth(1);
  plcol0(AQ_PC_FG);
  plbox("bclnst", 0, 0, "bcnstv", 0, 0);
  pllab(AX_X, AX_Y, title);
  /* the key below, drawn here (a line and its text per curve, no box):
   * PLplot's own legend box is measured narrower than cairo draws its
   * text on a PDF page scaled to the paper */
  size_t nrow = aq_plot_key_rows(F->nc, F->ncol);
  double top = bottom - gap;
  aq_plot_text_height(KEY_MM);
  aq_plot_key_below(F->key, F->nc, F->ncol, KEY_X0, KEY_X1, top - (double)(ROW_PX * nrow) / h,
                    top);
  return 0;
}

/* 1 if row i belongs to the record asked (NULL: every record). */
static int wanted(const aq_h5_spectra_table *t, size_t i, const char *record)
{
  return !record || strcmp(t->record[i], record) == 0 ||
         strcmp(base(t->record[i]), record) == 0;
}

aq_status aq_plot_spectra_csv(const char *data, const char *header,
                              void (*rows)(FILE *f, const void *ctx), const void *ctx,
                              aq_error *err)
{
  aq_outfile tmp;
  FILE *f = aq_plot_csv_open(data, &tmp, err);
  if (!f)
    return err->status;
  aq_plot_csv_axes(f, 2, (const char *[]){AX_X, AX_Y});
  fprintf(f, "%s\n", header);
  rows(f, ctx);
  return aq_plot_csv_close(&tmp, err);
}

/* --data's rows: each curve's (record, component, damping, period_s, psa_g). */
static void curve_rows(FILE *f, const void *ctx)
{
  const fig *F = ctx;
  const aq_h5_spectra_table *t = F->t;
  for (size_t k = 0; k < F->nc; k++)
    for (size_t i = F->c[k].start; i < F->c[k].start + F->c[k].n; i++) {
      aq_plot_csv_text(f, t->record[i]);
      aq_plot_csv_text(f, t->component[i]);
      fprintf(f, "%s,%s,%s\n", AQ_TEXT_NUM(t->damping[i]), AQ_TEXT_NUM(t->period_s[i]),
              AQ_TEXT_NUM(t->psa_g[i]));
    }
}

aq_status aq_plot_spectrum(const aq_h5_spectra_table *t, const char *record,
                           const char *source, const char *target, const char *data,
                           double *draw_s, aq_error *err)
{
  fig F = {t, source, NULL, 0, INFINITY, 0, 0, NULL, 1};
  F.c = calloc(AQ_PLOT_LEGEND_MAX + 1, sizeof *F.c);
  if (!F.c)
    return aq_error_set(err, AQ_ENOMEM, source, -1, -1, "spectra", "out of memory");
  /* the curves: runs of rows of one (record, component, damping) */
  size_t ncurve = 0, colors = 0;
  for (size_t i = 0; i < t->n; i++) {
    if (!wanted(t, i, record))
      continue;
    int same = i > 0 && wanted(t, i - 1, record) && !strcmp(t->record[i], t->record[i - 1]) &&
               !strcmp(t->component[i], t->component[i - 1]);
    if (!(same && t->damping[i] == t->damping[i - 1])) {
      if (ncurve < AQ_PLOT_LEGEND_MAX) {
        curve *c = &F.c[ncurve];
        c->start = i;
        if (!same) /* a new record and component: the next colour */
          colors++;
        c->color = COLOR[(colors - 1) % NCOLOR];
        size_t d = 0; /* the damping's index among this component's */
        for (size_t k = ncurve; k > 0 && F.c[k - 1].color == c->color &&
                                !strcmp(t->record[F.c[k - 1].start], t->record[i]) &&
                                !strcmp(t->component[F.c[k - 1].start], t->component[i]);
             k--)
          d++;
        c->style = 1 + (int)(d % NSTYLE);
      }
      ncurve++;
    }
    if (ncurve <= AQ_PLOT_LEGEND_MAX) {
      F.c[ncurve - 1].n++;
      F.tlo = fmin(F.tlo, t->period_s[i]);
      F.thi = fmax(F.thi, t->period_s[i]);
      F.amax = fmax(F.amax, t->psa_g[i]);
    }
  }
  aq_status rc = AQ_OK;
  if (ncurve == 0)
    rc = aq_error_set(err, AQ_EVALUE, source, -1, -1, "--record",
                      record ? "expected a record of the file, got \"%s\""
                             : "expected spectra in the file, got none%s",
                      record ? record : "");
  else if (ncurve > AQ_PLOT_LEGEND_MAX)
    rc = aq_error_set(err, AQ_EVALUE, source, -1, -1, "--record",
                      "expected at most %d curves in one figure, got %zu: choose a "
                      "record with --record", AQ_PLOT_LEGEND_MAX, ncurve);
  if (rc != AQ_OK) {
    free(F.c);
    return rc;
  }
  F.nc = ncurve;
  F.key = malloc(F.nc * sizeof *F.key);
  if (!F.key) {
    free(F.c);
    return aq_error_set(err, AQ_ENOMEM, source, -1, -1, "spectra", "out of memory");
  }
  for (size_t k = 0; k < F.nc; k++) {
    curve *c = &F.c[k];
    display_name(t->record[c->start], c->name, sizeof c->name);
    char comp[200];
    aq_plot_escape(t->component[c->start], comp, sizeof comp);
    snprintf(c->post, sizeof c->post, "  %s, #gz = %g %%", comp, 100 * t->damping[c->start]);
    F.key[k] = (aq_plot_key){c->color, c->style, 1.5, "", c->name, c->post};
  }
  F.ncol = aq_plot_key_columns(F.key, F.nc, KEY_X0, KEY_X1, WIDTH_PX, KEY_MM);
  rc = aq_plot_render(target, WIDTH_PX, fig_height(aq_plot_key_rows(F.nc, F.ncol)), draw, &F,
                      draw_s, err);
  if (rc == AQ_OK && data)
    rc = aq_plot_spectra_csv(data, "record,component,damping,period_s,psa_g", curve_rows, &F,
                             err);
  free(F.key);
  free(F.c);
  return rc;
}
