/* html_capacity.c: the report page's section of a capacity file
 * (html_int.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../report/h5_capacity.h"
#include "html_int.h"

typedef struct {
  const aq_h5_capacity_table *t;
  const char *arch, *source;
} cap_fig;
static aq_status draw_capacity(void *ctx, const char *svg, aq_error *err)
{
  const cap_fig *c = ctx;
  aq_plot_capacity_opts o = {c->arch, NULL, 0, 0};
  return aq_plot_capacity(c->t, &o, c->source, svg, NULL, NULL, err);
}

aq_status aq_html_section_capacity(aq_html_page *p, const char *path, size_t index)
{
  aq_page_buf *b = p->b; /* path's kind: capacity, checked before the aq_html_page */
  aq_h5_capacity_table t;
  int present = 0;
  aq_status st = aq_h5_capacity_read(path, &t, &present, p->err);
  if (st != AQ_OK)
    return st;
  aq_page_printf(b, "<h2 id=\"capacity-%zu\">Capacity: ", index);
  aq_page_esc(b, aq_html_base(path));
  aq_page_puts(b, "</h2>\n");
  aq_html_read_note(b, "For each record and polarity, every scale factor at which the verdict "
               "changes, from the scale at which the arch first moves to the cap.  The "
               "<i>first collapse</i> is the smallest scale that collapses the arch; a "
               "rocking arch can survive again at a larger scale (a <b>resurrection</b>, "
               "marked R), so the collapse intervals are listed whole.  The fragility curve "
               "is the lognormal probability of collapse against an intensity measure "
               "(IM), fitted to the records' first collapses, with the band of its median's "
               "90 % confidence interval; records that never collapse count as censored "
               "at their cap.  A status <b>slides</b> or <b>beyond</b>: a run up to the "
               "first collapse asked more friction of a joint than it has, or (free "
               "hinges) put the thrust outside a joint; the verdict is then the four-hinge "
               "model's, which the arch has left (<i>marked from</i> gives the lowest such "
               "scale; --model blocks follows those runs).");
  aq_page_puts(b, "<table class=\"wide\"><thead><tr><th>record</th><th>arch</th>"
                  "<th>polarity</th><th>status</th><th>moves from scale</th>"
                  "<th>first collapse scale</th><th>its PGA (g)</th>"
                  "<th>collapse intervals (scale)</th><th>resurrection</th>"
                  "<th>marked from scale</th></tr></thead>"
                  "<tbody>\n");
  for (size_t k = 0; k < t.n; k++) {
    const aq_h5_capacity_row *r = &t.row[k];
    aq_page_puts(b, "<tr>");
    aq_html_text_td(b, aq_html_base(r->record), 1);
    aq_html_text_td(b, r->arch, 0);
    aq_html_text_td(b, r->polarity, 0);
    aq_page_printf(b, "<td class=\"%s\">", strcmp(r->status, "ok") == 0 ? "v-s" : "v-f");
    aq_page_esc(b, r->status);
    aq_page_puts(b, "</td>");
    aq_html_num_td(b, r->d[0], "%.4g");
    aq_html_num_td(b, r->d[1], "%.4g");
    aq_html_num_td(b, r->d[2], "%.4g");
    aq_page_puts(b, "<td>");
    for (int64_t j = 0; j < r->i[3]; j++) {
      size_t q = (size_t)(r->i[2] + j);
      if (q >= t.ninterval)
        break;
      aq_page_printf(b, "%s[%.4g, %.4g%s", j ? ", " : "", t.interval[2 * q],
                     t.interval[2 * q + 1], isinf(t.interval[2 * q + 1]) ? ")" : "]");
    }
    aq_page_puts(b, r->i[3] ? "</td>" : "none up to the cap</td>");
    aq_page_puts(b, r->i[0] > 0 ? "<td class=\"v-c\">R: yes</td>" : "<td>no</td>");
    aq_html_num_td(b, r->d[6], "%.4g"); /* first_mark_scale */
    aq_page_puts(b, "</tr>\n");
  }
  aq_page_puts(b, "</tbody></table>\n");
  /* per arch: the figure and the ranking of the measures */
  for (size_t k = 0; k < t.n && st == AQ_OK; k++) {
    int seen = 0;
    for (size_t j = 0; j < k; j++)
      seen |= strcmp(t.row[j].arch, t.row[k].arch) == 0;
    if (seen)
      continue;
    const char *arch = t.row[k].arch;
    aq_page_puts(b, "<h3>Arch ");
    aq_page_esc(b, arch);
    aq_page_puts(b, "</h3>\n");
    cap_fig c = {&t, arch, path};
    char label[300];
    aq_text_fit(label, sizeof label, "capacity of arch %s: verdict strips and fragility", arch);
    st = aq_html_figure(p, label, draw_capacity, &c);
    /* the measures in the order of their rank: by what the rank orders,
       the dispersion per power of the scale (beta_per_power), NaN last */
    size_t order[64], n = 0;
    for (size_t i = 0; i < t.nfit && n < 64; i++)
      if (strcmp(t.fit[i].arch, arch) == 0)
        order[n++] = i;
    for (size_t i = 1; i < n; i++)
      for (size_t j = i; j > 0; j--) {
        double x = t.fit[order[j - 1]].beta_per_power, y = t.fit[order[j]].beta_per_power;
        if (!(isnan(x) ? 0 : isnan(y) ? 1 : x > y))
          break;
        size_t s = order[j];
        order[j] = order[j - 1];
        order[j - 1] = s;
      }
    if (n) {
      aq_page_puts(b, "<p>The intensity measures ranked by the dispersion of their "
                      "fragility fit per power of the scale the measure grows with: β, "
                      "halved for Arias intensity, which grows as the square of the scale "
                      "and so spreads twice as much while ordering the records alike (the "
                      "column <i>ranked by</i>).  The smaller, the better the measure "
                      "predicts this arch's collapse.");
      int spectral = 0;
      for (size_t i = 0; i < n; i++)
        spectral |= strncmp(t.fit[order[i]].im, "sa_", 3) == 0;
      if (spectral) {
        int r = aq_spectrum_peaks_parse(t.peaks);
        aq_page_puts(b, "  Sa(T) and Sa_avg are pseudo-spectral accelerations at 5 % "
                        "damping, their peaks taken by the rule <i>");
        aq_page_esc(b, r >= 0 ? aq_spectrum_peaks_text((aq_spectrum_peaks)r)
                              : "not stated (a file written before --peaks: exact)");
        aq_page_puts(b, "</i>.");
      }
      aq_page_puts(b, "</p>\n<table><thead><tr><th>rank</th><th>measure</th>"
                      "<th>median</th><th>β</th><th>ranked by: β per power of the scale</th>"
                      "<th>median 90 % interval</th><th>records</th>"
                      "<th>censored</th><th>marked</th></tr></thead><tbody>\n");
      for (size_t i = 0; i < n; i++) {
        const aq_h5_fragility_fit *f = &t.fit[order[i]];
        if (f->rank > 0) /* the file's rank */
          aq_page_printf(b, "<tr><td class=\"n\">%lld</td>", (long long)f->rank);
        else
          aq_page_puts(b, "<tr><td class=\"n\">–</td>");
        aq_html_text_td(b, f->im, 1);
        aq_html_num_td(b, f->median, "%.4g");
        aq_html_num_td(b, f->beta, "%.3f");
        aq_html_num_td(b, f->beta_per_power, "%.3f");
        aq_page_printf(b, "<td class=\"n\">%.4g – %.4g</td>", f->median_lo, f->median_hi);
        aq_html_num_td(b, (double)f->records, "%.0f");
        aq_html_num_td(b, (double)f->censored, "%.0f");
        aq_html_num_td(b, f->marked >= 0 ? (double)f->marked : NAN, "%.0f");
        aq_page_puts(b, "</tr>\n");
      }
      aq_page_puts(b, "</tbody></table>\n");
    }
  }
  aq_h5_capacity_table_free(&t);
  return st;
}

