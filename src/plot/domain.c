/* domain.c: the half-cycle collapse domain (Oppenheim 1992; the paper's
 * section 4.1): the amplitude ratio a/(lambda0 g) of a rectangular pulse
 * against its duration, the shortest collapsing duration of each ratio
 * (computed by aq_domain_min_duration) drawn as the boundary and the
 * collapse region (longer pulses) shaded. */
#include <math.h>
#include <plplot.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

static const char *const AX_X = "pulse duration (s)",
                         *const AX_Y = "amplitude ratio a / (#gl#d0#u g) (1)";

typedef struct {
  const char *arch;
  double lambda0, tmax_s;
  const double *ratio, *dur_s;
  size_t n;
  size_t *order; /* finite durations, by ratio */
  size_t nf;
} dom;

static int draw(void *ctx, aq_error *err)
{
  (void)err;
  const dom *d = ctx;
  double dlo = INFINITY, dhi = 0, rlo = INFINITY, rhi = 0;
  for (size_t i = 0; i < d->n; i++) {
    rlo = fmin(rlo, d->ratio[i]);
    rhi = fmax(rhi, d->ratio[i]);
    if (isfinite(d->dur_s[i])) {
      dlo = fmin(dlo, d->dur_s[i]);
      dhi = fmax(dhi, d->dur_s[i]);
    }
  }
  if (!(dlo <= dhi))
    dlo = 0.01, dhi = d->tmax_s;
  double x0 = floor(log10(dlo) - 0.05), x1 = ceil(log10(dhi) + 0.05);
  double y1 = rhi * 1.08, y0 = 1 - 0.04 * (y1 - 1); /* room for the points near 1 */
  pladv(0);
  plschr(0, 0.95);
  plvpor(0.11, 0.95, 0.2, 0.9); /* below: the axis' title, then the key */
  plwind(x0, x1, y0, y1);
  char title[600], name[300];
  aq_plot_shorten_to(d->arch,
                     0.94 * aq_plot_page_w_mm() -
                         aq_plot_text_mm("half-cycle collapse domain of arch  (#gl#d0#u = "
                                         "0.0001234)"),
                     name, sizeof name);
  snprintf(title, sizeof title, "half-cycle collapse domain of arch %s (#gl#d0#u = %.4g)", name,
           d->lambda0);
  /* the collapse region: right of the boundary, up to the top of the frame */
  if (d->nf) {
    PLFLT *x = malloc((d->nf + 3) * sizeof *x), *y = malloc((d->nf + 3) * sizeof *y);
    if (x && y) {
      size_t m = 0;
      for (size_t k = 0; k < d->nf; k++) {
        x[m] = log10(d->dur_s[d->order[k]]);
        y[m++] = d->ratio[d->order[k]];
      }
      x[m] = x[m - 1];
      y[m++] = y1;
      x[m] = x1;
      y[m++] = y1;
      x[m] = x1;
      y[m++] = y[0];
      plcol0(AQ_PC_SHADE);
      plfill((PLINT)m, x, y);
      for (size_t k = 0; k < d->nf; k++) {
        x[k] = log10(d->dur_s[d->order[k]]);
        y[k] = d->ratio[d->order[k]];
      }
      plcol0(AQ_PC_RED);
      plwidth(2);
      plline((PLINT)d->nf, x, y);
      plwidth(1);
      plstring((PLINT)d->nf, x, y, "●");
    }
    free(x);
    free(y);
  }
  plcol0(AQ_PC_FG);
  plbox("bclnst", 0, 0, "bcnstv", 0, 0);
  pllab(AX_X, AX_Y, title);
  plcol0(AQ_PC_FG);
  plptex(x1 - 0.05 * (x1 - x0), y1 - 0.1 * (y1 - y0), 1, 0, 1, "collapse");
  /* low and left, where the boundary is furthest right (the ratio near 1
     takes the longest pulse) */
  plptex(x0 + 0.03 * (x1 - x0), 1 + 0.06 * (y1 - 1), 1, 0, 0, "no collapse");
  const char *t[] = {"shortest collapsing pulse", "collapse region"};
  int c[] = {AQ_PC_RED, AQ_PC_SHADE}, st[] = {1, -1};
  const char *sy[] = {"●", ""};
  /* the key outside the frame, under the axis' title: on no data */
  aq_plot_legend_at(PL_POSITION_OUTSIDE | PL_POSITION_BOTTOM, 0, 0.16, 2, 2, t, c, st, sy);
  return 0;
}

aq_status aq_plot_domain(const char *arch_name, double lambda0, const double *ratio,
                         const double *dur_s, size_t n, double tmax_s,
                         const char *target, const char *data, double *draw_s,
                         aq_error *err)
{
  dom d = {arch_name, lambda0, tmax_s, ratio, dur_s, n, NULL, 0};
  d.order = malloc((n ? n : 1) * sizeof *d.order);
  if (!d.order)
    return aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "domain", "out of memory");
  for (size_t i = 0; i < n; i++) /* insertion by ratio (a few ratios) */
    if (isfinite(dur_s[i])) {
      size_t k = d.nf++;
      while (k > 0 && ratio[d.order[k - 1]] > ratio[i]) {
        d.order[k] = d.order[k - 1];
        k--;
      }
      d.order[k] = i;
    }
  aq_status rc = aq_plot_render(target, 1000, 720, draw, &d, draw_s, err);
  if (rc == AQ_OK && data) {
    aq_outfile tmp;
    FILE *f = aq_plot_csv_open(data, &tmp, err);
    if (!f)
      rc = err->status;
    else {
      aq_plot_csv_axes(f, 2, (const char *[]){AX_X, AX_Y});
      fprintf(f, "ratio,min_duration_s\n");
      for (size_t i = 0; i < n; i++)
        fprintf(f, "%s,%s\n", AQ_TEXT_NUM(ratio[i]), AQ_TEXT_NUM(dur_s[i]));
      rc = aq_plot_csv_close(&tmp, err);
    }
  }
  free(d.order);
  return rc;
}
