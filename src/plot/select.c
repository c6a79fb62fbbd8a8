/* select.c: a suite's spectra against its target (`plot spectrum` of a
 * file of `archquake select -o`, or of `archquake spectrum -o` with
 * --target): PSA (g) against period (s, log axis): the target and 90 % of
 * it (dashed) over the periods around the range, each record's scaled
 * spectrum (thin), their mean (thick), and the range's ends. */
#include <math.h>
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "plot.h"

static const char *const AX_X = "period T (s)",
                         *const AX_Y = "pseudo-spectral acceleration PSA (g)";

static const int COLOR[] = {AQ_PC_TEAL,  AQ_PC_ORANGE, AQ_PC_PURPLE, AQ_PC_GREEN,
                            AQ_PC_BROWN, AQ_PC_PINK,   AQ_PC_OLIVE,  AQ_PC_GREY};
enum { NCOLOR = sizeof COLOR / sizeof COLOR[0], NTARGET = 200 };
enum { WIDTH_PX = 1000, TOP_PX = 58, PLOT_PX = 470, GAP_PX = 78, ROW_PX = 29, PAD_PX = 24 };

typedef struct {
  const aq_plot_target_set *s;
  double *mean;             /* nper, g */
  double tlo, thi;          /* the periods drawn, s */
  double tt[NTARGET], ta[NTARGET]; /* the target over them, s and g */
  size_t nt;
  double amax;
  aq_plot_key *key; /* the target, 90 % of it, the mean, each record */
  size_t nkey, ncol;
  char band_text[80], mean_text[80];
} fig;

/* the key's ends, fractions of the figure's width */
static const double KEY_X0 = 0.03, KEY_X1 = 0.97;

/* the text's height, mm of the figure (72 points an inch): the axes' and
   title's, the key's; the same however tall the key makes the figure */
static const double TEXT_MM = 5.85, KEY_MM = 4.9;

static int fig_height(size_t nrow)
{
  return TOP_PX + PLOT_PX + GAP_PX + ROW_PX * (int)nrow + PAD_PX;
}

static int draw(void *ctx, aq_error *err)
{
  (void)err;
  const fig *F = ctx;
  const aq_plot_target_set *s = F->s;
  double x0 = log10(F->tlo), x1 = log10(F->thi), y1 = 1.08 * F->amax;
  pladv(0);
  aq_plot_text_height(TEXT_MM);
  double h = (double)fig_height(aq_plot_key_rows(F->nkey, F->ncol));
  double gap = GAP_PX / h, bottom = (h - PLOT_PX - TOP_PX) / h;
  plvpor(0.1, 0.96, bottom, 1 - TOP_PX / h);
  plwind(x0, x1, 0, y1);
  plcol0(AQ_PC_LIGHT);
  plbox("glh", 0, 0, "g", 0, 0);
  PLFLT *x = malloc((s->nper + NTARGET) * sizeof *x), *y = malloc((s->nper + NTARGET) * sizeof *y);
  if (!x || !y) {
    free(x);
    free(y);
    return -1;
  }
  /* the range's ends */
  for (int e = 0; e < 2; e++) {
    PLFLT vx[2], vy[2] = {0, y1};
    vx[0] = vx[1] = log10(s->period_s[e ? s->nper - 1 : 0]);
    plcol0(AQ_PC_GREY);
    pllsty(3);
    plline(2, vx, vy);
  }
  pllsty(1);
  /* each record, scaled */
  for (size_t i = 0; i < s->n; i++) {
    for (size_t k = 0; k < s->nper; k++) {
      x[k] = log10(s->period_s[k]);
      y[k] = s->psa_g[i * s->nper + k];
    }
    plcol0(COLOR[i % NCOLOR]);
    plwidth(1);
    plline((PLINT)s->nper, x, y);
  }
  /* the target and 90 % of it */
  for (size_t k = 0; k < F->nt; k++)
    x[k] = log10(F->tt[k]);
  for (int b = 0; b < 2; b++) {
    for (size_t k = 0; k < F->nt; k++)
      y[k] = (b ? s->band : 1.0) * F->ta[k];
    plcol0(AQ_PC_FG);
    pllsty(b ? 2 : 1);
    plwidth(b ? 1.5 : 2.5);
    plline((PLINT)F->nt, x, y);
  }
  pllsty(1);
  /* the mean */
  for (size_t k = 0; k < s->nper; k++) {
    x[k] = log10(s->period_s[k]);
    y[k] = F->mean[k];
  }
  plcol0(AQ_PC_BLUE);
  plwidth(3);
  plline((PLINT)s->nper, x, y);
  plwidth(1);
  free(x);
  free(y);
  plcol0(AQ_PC_FG);
  plbox("bclnst", 0, 0, "bcnstv", 0, 0);
  char name[600], title[1000];
  aq_plot_shorten_to(s->title_name,
                     0.94 * aq_plot_page_w_mm() - aq_plot_text_mm(s->title_pre) -
                         aq_plot_text_mm(s->title_post),
                     name, sizeof name);
  snprintf(title, sizeof title, "%s%s%s", s->title_pre, name, s->title_post);
  pllab(AX_X, AX_Y, title);
  size_t nrow = aq_plot_key_rows(F->nkey, F->ncol);
  double top = bottom - gap;
  aq_plot_text_height(KEY_MM);
  aq_plot_key_below(F->key, F->nkey, F->ncol, KEY_X0, KEY_X1,
                    top - (double)(ROW_PX * nrow) / h, top);
  return 0;
}

/* --data's rows: the target, the mean, each spectrum (curve, period_s,
 * psa_g). */
static void target_rows(FILE *f, const void *ctx)
{
  const fig *F = ctx;
  const aq_plot_target_set *s = F->s;
  for (size_t k = 0; k < F->nt; k++)
    fprintf(f, "target,%s,%s\n", AQ_TEXT_NUM(F->tt[k]), AQ_TEXT_NUM(F->ta[k]));
  for (size_t k = 0; k < s->nper; k++)
    fprintf(f, "mean,%s,%s\n", AQ_TEXT_NUM(s->period_s[k]), AQ_TEXT_NUM(F->mean[k]));
  for (size_t i = 0; i < s->n; i++)
    for (size_t k = 0; k < s->nper; k++) {
      aq_plot_csv_text(f, s->label[i]);
      fprintf(f, "%s,%s\n", AQ_TEXT_NUM(s->period_s[k]), AQ_TEXT_NUM(s->psa_g[i * s->nper + k]));
    }
}

aq_status aq_plot_target(const aq_plot_target_set *s, const char *target, const char *data,
                         double *draw_s, aq_error *err)
{
  if (s->n == 0 || s->nper < 2)
    return aq_error_set(err, AQ_EVALUE, target, -1, -1, "spectra",
                        "expected spectra at two periods or more, got none");
  if (s->n + 3 > AQ_PLOT_LEGEND_MAX)
    return aq_error_set(err, AQ_EVALUE, target, -1, -1, "spectra",
                        "expected at most %d spectra in one figure, got %zu",
                        AQ_PLOT_LEGEND_MAX - 3, s->n);
  fig F = {.s = s};
  F.mean = calloc(s->nper, sizeof *F.mean);
  if (!F.mean)
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, NULL, "out of memory");
  for (size_t i = 0; i < s->n; i++)
    for (size_t k = 0; k < s->nper; k++) {
      double v = s->psa_g[i * s->nper + k];
      F.mean[k] += v / (double)s->n;
      F.amax = fmax(F.amax, v);
    }
  /* the target from a third of the range's start to three times its end,
   * within the target's own periods (log-spaced) */
  double lo, hi;
  aq_target_periods(s->target, &lo, &hi);
  F.tlo = fmax(s->period_s[0] / 3, lo > 0 ? lo : 0.01);
  F.thi = fmin(s->period_s[s->nper - 1] * 3, hi);
  F.nt = NTARGET;
  for (size_t k = 0; k < F.nt; k++) {
    F.tt[k] = F.tlo * pow(F.thi / F.tlo, (double)k / (double)(F.nt - 1));
    F.ta[k] = aq_target_psa(s->target, F.tt[k]) / AQ_G0_MPS2;
    F.amax = fmax(F.amax, isfinite(F.ta[k]) ? F.ta[k] : 0);
  }
  /* the key: the target, 90 % of it, the mean, each record (a file name
     without its directories; a --components pair whole) */
  F.nkey = s->n + 3;
  F.key = malloc(F.nkey * sizeof *F.key);
  if (!F.key) {
    free(F.mean);
    return aq_error_set(err, AQ_ENOMEM, target, -1, -1, NULL, "out of memory");
  }
  snprintf(F.band_text, sizeof F.band_text, "%g %% of the target", 100 * s->band);
  snprintf(F.mean_text, sizeof F.mean_text, "mean of the %zu scaled spectra", s->n);
  F.key[0] = (aq_plot_key){AQ_PC_FG, 1, 2.5, "target ", s->target_name, ""};
  F.key[1] = (aq_plot_key){AQ_PC_FG, 2, 1.5, F.band_text, NULL, ""};
  F.key[2] = (aq_plot_key){AQ_PC_BLUE, 1, 3, F.mean_text, NULL, ""};
  for (size_t i = 0; i < s->n; i++) {
    const char *b = strrchr(s->label[i], '/');
    F.key[3 + i] = (aq_plot_key){COLOR[i % NCOLOR], 1, 1, "",
                                 b && !strchr(b, ',') ? b + 1 : s->label[i], ""};
  }
  F.ncol = aq_plot_key_columns(F.key, F.nkey, KEY_X0, KEY_X1, WIDTH_PX, KEY_MM);
  aq_status rc = aq_plot_render(target, WIDTH_PX, fig_height(aq_plot_key_rows(F.nkey, F.ncol)),
                                draw, &F, draw_s, err);
  if (rc == AQ_OK && data)
    rc = aq_plot_spectra_csv(data, "curve,period_s,psa_g", target_rows, &F, err);
  free(F.mean);
  free(F.key);
  return rc;
}

aq_status aq_plot_select(const aq_h5_select_file *f, const aq_target *override,
                         const char *source, const char *target, const char *data,
                         double *draw_s, aq_error *err)
{
  aq_target own;
  aq_status st = AQ_OK;
  if (!override && (st = aq_target_parse(f->target, &own, err)) != AQ_OK)
    return st;
  double *psa = malloc((f->n * f->nper > 0 ? f->n * f->nper : 1) * sizeof *psa);
  if (!psa) {
    if (!override)
      aq_target_free(&own);
    return aq_error_set(err, AQ_ENOMEM, source, -1, -1, NULL, "out of memory");
  }
  for (size_t i = 0; i < f->n; i++) /* each record at its scale */
    for (size_t k = 0; k < f->nper; k++)
      psa[i * f->nper + k] = f->scale[i] * f->psa_g[i * f->nper + k];
  const aq_target *tg = override ? override : &own;
  char post[200];
  const char *b = strrchr(source, '/');
  snprintf(post, sizeof post, ": %zu records, misfit %.3g", f->n, f->misfit);
  aq_plot_target_set s = {f->n, f->nper, f->period_s, psa, (const char *const *)f->record,
                          tg, tg->spec, f->band > 0 ? f->band : 0.9, "the suite of ",
                          b ? b + 1 : source, post};
  st = aq_plot_target(&s, target, data, draw_s, err);
  free(psa);
  if (!override)
    aq_target_free(&own);
  return st;
}

aq_status aq_plot_spectra_target(const aq_h5_spectra_table *t, const char *record,
                                 const aq_target *tg, const char *source, const char *target,
                                 const char *data, double *draw_s, aq_error *err)
{
  /* the curves: runs of rows of one (record, component, damping), all at
   * the periods of the first and the target's damping */
  size_t nper = 0, n = 0;
  for (size_t i = 0; i < t->n; i++) {
    int keep = !record || !strcmp(t->record[i], record);
    if (keep && n == 0 && (nper == 0 || (!strcmp(t->record[i], t->record[i - 1]) &&
                                         !strcmp(t->component[i], t->component[i - 1]))))
      nper++;
    else if (keep && nper && n == 0)
      n = 1;
  }
  double *period = malloc((nper ? nper : 1) * sizeof *period);
  double *psa = malloc((t->n ? t->n : 1) * sizeof *psa);
  const char **label = malloc((t->n ? t->n : 1) * sizeof *label);
  char (*names)[200] = malloc((t->n ? t->n : 1) * sizeof *names);
  aq_status st = AQ_OK;
  if (!period || !psa || !label || !names)
    st = aq_error_set(err, AQ_ENOMEM, source, -1, -1, NULL, "out of memory");
  size_t nc = 0, k = 0;
  for (size_t i = 0; st == AQ_OK && i < t->n; i++) {
    if (record && strcmp(t->record[i], record) != 0)
      continue;
    if (k == 0) {
      snprintf(names[nc], sizeof names[nc], "%s %s", t->record[i], t->component[i]);
      label[nc] = names[nc];
    }
    if (nc == 0)
      period[k] = t->period_s[i];
    if (k >= nper || t->period_s[i] != period[k] || fabs(t->damping[i] - tg->damping) > 1e-12)
      st = aq_error_set(err, AQ_EVALUE, source, -1, -1, "--target",
                        "expected every spectrum of the file at the same periods and at the "
                        "target's damping %g, got %s %s at %g s, damping %g", tg->damping,
                        t->record[i], t->component[i], t->period_s[i], t->damping[i]);
    psa[nc * nper + k] = t->psa_g[i];
    if (++k == nper) {
      k = 0;
      nc++;
    }
  }
  if (st == AQ_OK && (nc == 0 || k != 0))
    st = aq_error_set(err, AQ_EVALUE, source, -1, -1, "--record",
                      record ? "expected a record of the file, got \"%s\""
                             : "expected spectra in the file, got none%s", record ? record : "");
  if (st == AQ_OK) {
    const char *b = strrchr(source, '/');
    aq_plot_target_set s = {nc, nper, period, psa, label, tg, tg->spec, 0.9, "the spectra of ",
                            b ? b + 1 : source, " against the target"};
    st = aq_plot_target(&s, target, data, draw_s, err);
  }
  free(period);
  free(psa);
  free(label);
  free(names);
  return st;
}
