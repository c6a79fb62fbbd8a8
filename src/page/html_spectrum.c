/* html_spectrum.c: the report page's section of a spectrum file
 * (html_int.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "html_int.h"

typedef struct {
  const aq_h5_spectra_table *t;
  const char *record, *source; /* record NULL: every record */
} spectrum_fig;
static aq_status draw_spectrum(void *ctx, const char *svg, aq_error *err)
{
  const spectrum_fig *f = ctx;
  return aq_plot_spectrum(f->t, f->record, f->source, svg, NULL, NULL, err);
}

/* The periods a spectrum's table shows beside each curve's peak, those of
 * them the file holds. */
static const double TABLE_T_S[] = {0.1, 0.2, 0.3, 0.5, 1, 2, 3};
enum { NTABLE_T = sizeof TABLE_T_S / sizeof TABLE_T_S[0] };

aq_status aq_html_section_spectrum(aq_html_page *p, const char *path, size_t index)
{
  aq_page_buf *b = p->b;
  aq_h5_spectra_table t;
  aq_status st = aq_h5_spectra_read(path, &t, p->err);
  if (st != AQ_OK)
    return st;
  aq_page_printf(b, "<h2 id=\"spectrum-%zu\">Spectra: ", index);
  aq_page_esc(b, aq_html_base(path));
  aq_page_puts(b, "</h2>\n");
  int rule = t.peaks;
  aq_html_read_note(b, "The response spectra of each record (and of each <code>--components</code> "
               "pair: RotD50, RotD100, GeoMean): the pseudo-spectral acceleration "
               "PSA = ω² max|u| of a damped oscillator against its period, in g.");
  aq_page_puts(b, "<p>Peaks taken by the rule <i>");
  aq_page_esc(b, rule >= 0 ? aq_spectrum_peaks_text((aq_spectrum_peaks)rule)
                           : "not stated (a file written before --peaks: exact)");
  aq_page_puts(b, "</i>.</p>\n");
  /* the curves: runs of rows of one (record, component, damping) */
  size_t ncurve = 0, nrec = 0;
  for (size_t i = 0; i < t.n; i++) {
    int same_rec = i > 0 && !strcmp(t.record[i], t.record[i - 1]);
    ncurve += !(same_rec && !strcmp(t.component[i], t.component[i - 1]) &&
                t.damping[i] == t.damping[i - 1]);
    nrec += !same_rec;
  }
  /* the figures: all curves in one, or a figure per record when a legend
     would not hold them */
  if (ncurve <= AQ_PLOT_LEGEND_MAX) {
    spectrum_fig f = {&t, NULL, path};
    char label[300];
    aq_text_fit(label, sizeof label, "response spectra of %s", aq_html_base(path));
    st = aq_html_figure(p, label, draw_spectrum, &f);
  } else {
    for (size_t i = 0; i < t.n && st == AQ_OK; i++)
      if (i == 0 || strcmp(t.record[i], t.record[i - 1]) != 0) {
        spectrum_fig f = {&t, t.record[i], path};
        char label[600];
        aq_text_fit(label, sizeof label, "response spectra of %s", aq_html_base(t.record[i]));
        st = aq_html_figure(p, label, draw_spectrum, &f);
      }
  }
  /* the table: per curve its peak and its PSA at the periods of
     TABLE_T_S the file holds */
  int have[NTABLE_T] = {0};
  for (size_t i = 0; i < t.n; i++)
    for (int k = 0; k < NTABLE_T; k++)
      have[k] |= fabs(t.period_s[i] - TABLE_T_S[k]) <= 1e-9 * TABLE_T_S[k];
  aq_page_printf(b, "<h3>PSA of %zu curve%s of %zu record%s</h3>\n", ncurve,
                 ncurve == 1 ? "" : "s", nrec, nrec == 1 ? "" : "s");
  aq_page_puts(b, "<table class=\"wide\"><thead><tr><th>record</th><th>component</th>"
                  "<th>damping</th><th>peak PSA (g)</th><th>at T (s)</th>");
  for (int k = 0; k < NTABLE_T; k++)
    if (have[k])
      aq_page_printf(b, "<th>PSA at %g s (g)</th>", TABLE_T_S[k]);
  aq_page_puts(b, "</tr></thead><tbody>\n");
  for (size_t i = 0; i < t.n && st == AQ_OK;) {
    size_t j = i, peak = i;
    double at[NTABLE_T];
    for (int k = 0; k < NTABLE_T; k++)
      at[k] = NAN;
    for (; j < t.n && !strcmp(t.record[j], t.record[i]) &&
           !strcmp(t.component[j], t.component[i]) && t.damping[j] == t.damping[i];
         j++) {
      if (t.psa_g[j] > t.psa_g[peak])
        peak = j;
      for (int k = 0; k < NTABLE_T; k++)
        if (fabs(t.period_s[j] - TABLE_T_S[k]) <= 1e-9 * TABLE_T_S[k])
          at[k] = t.psa_g[j];
    }
    aq_page_puts(b, "<tr><td class=\"mono\" title=\"");
    aq_page_esc(b, t.record[i]);
    aq_page_puts(b, "\">");
    aq_page_esc(b, aq_html_base(t.record[i]));
    aq_page_puts(b, "</td>");
    aq_html_text_td(b, t.component[i], 0);
    aq_html_num_td(b, t.damping[i], "%.3g");
    aq_html_num_td(b, t.psa_g[peak], "%.4g");
    aq_html_num_td(b, t.period_s[peak], "%.4g");
    for (int k = 0; k < NTABLE_T; k++)
      if (have[k])
        aq_html_num_td(b, at[k], "%.4g");
    aq_page_puts(b, "</tr>\n");
    i = j;
  }
  aq_page_puts(b, "</tbody></table>\n");
  /* every value, for those who want them (the TSV of archquake spectrum) */
  aq_page_printf(b, "<details><summary>Every value (%zu rows)</summary>\n<table><thead><tr>"
                    "<th>record</th><th>component</th><th>damping</th><th>T (s)</th>"
                    "<th>PSA (g)</th><th>SD (m)</th><th>PSV (m/s)</th></tr></thead><tbody>\n",
                 t.n);
  for (size_t i = 0; i < t.n; i++) {
    aq_page_puts(b, "<tr>");
    aq_html_text_td(b, aq_html_base(t.record[i]), 1);
    aq_html_text_td(b, t.component[i], 0);
    aq_html_num_td(b, t.damping[i], "%.3g");
    aq_html_num_td(b, t.period_s[i], "%.4g");
    aq_html_num_td(b, t.psa_g[i], "%.4g");
    aq_html_num_td(b, t.sd_m[i], "%.4g");
    aq_html_num_td(b, t.psv_m_s[i], "%.4g");
    aq_page_puts(b, "</tr>\n");
  }
  aq_page_puts(b, "</tbody></table></details>\n");
  aq_h5_spectra_table_free(&t);
  return st;
}

