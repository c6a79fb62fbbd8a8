/* select.c: the report's section of a suite of `archquake select`
 * (select.h). */
#include "select.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../plot/plot.h"
#include "../report/h5_select.h"
#include "figure.h"

static const char *base(const char *p)
{
  const char *b = strrchr(p, '/');
  return b ? b + 1 : p;
}

typedef struct {
  const aq_h5_select_file *f;
  const char *path;
} select_fig;

static aq_status draw(void *ctx, const char *svg, aq_error *err)
{
  const select_fig *s = ctx;
  return aq_plot_select(s->f, NULL, s->path, svg, NULL, NULL, err);
}

aq_status aq_page_select_section(aq_page_buf *b, const char *path, size_t index,
                                 const char *tmp, int *nfig, aq_error *err)
{
  aq_h5_select_file f;
  aq_status st = aq_h5_select_read(path, &f, err);
  if (st != AQ_OK)
    return st;
  aq_page_printf(b, "<h2 id=\"select-%zu\">Suite: ", index);
  aq_page_esc(b, base(path));
  aq_page_puts(b, "</h2>\n<div class=\"read\">The records were chosen and scaled by "
                  "<code>archquake select</code> to match the target spectrum below: each "
                  "record scaled to bring its spectrum closest to the target in the log over "
                  "the period range, the suite whose mean spectrum has the least misfit "
                  "(the mean of the squared log ratios) among those that meet the code's "
                  "conditions.  The main job ran each record at the scale listed "
                  "(<code>--suite</code>).</div>\n");
  aq_page_puts(b, "<p><b>Target:</b> ");
  aq_page_esc(b, f.description);
  aq_page_printf(b, " (<code>");
  aq_page_esc(b, f.target);
  aq_page_printf(b, "</code>).  Range %g to %g s, %zu periods; spectra at damping %g, peaks ",
                 f.period_s[0], f.period_s[f.nper - 1], f.nper, f.damping);
  aq_page_esc(b, f.peaks);
  aq_page_printf(b, "; common factor %.6g; misfit %.6g.</p>\n", f.factor, f.misfit);
  aq_page_printf(b, "<p><b>Conditions:</b> %s</p>\n",
                 f.conditions_hold ? "every condition holds"
                                   : "<span class=\"v-c\">NOT every condition holds</span> "
                                     "(written with --best-effort)");
  aq_page_puts(b, "<table class=\"wide\"><thead><tr><th>check</th><th>holds</th>"
                  "<th>figures</th></tr></thead><tbody>\n");
  for (size_t i = 0; i < f.nchecks; i++) {
    aq_page_puts(b, "<tr><td>");
    aq_page_esc(b, f.check_name[i]);
    aq_page_printf(b, "</td><td class=\"%s\">%s</td><td>", f.check_holds[i] ? "v-s" : "v-c",
                   f.check_holds[i] ? "yes" : "NO");
    aq_page_esc(b, f.check_detail[i]);
    aq_page_puts(b, "</td></tr>\n");
  }
  aq_page_puts(b, "</tbody></table>\n<figure>");
  select_fig sf = {&f, path};
  st = aq_page_figure(b, tmp, ++*nfig, "the suite's scaled spectra, their mean and the target",
                      draw, &sf, err);
  aq_page_puts(b, "</figure>\n<table class=\"wide\"><thead><tr><th>record</th>"
                  "<th>channel</th><th>scale</th><th>misfit</th><th>event</th></tr></thead>"
                  "<tbody>\n");
  for (size_t j = 0; j < f.n; j++) {
    aq_page_puts(b, "<tr><td class=\"mono\">");
    aq_page_esc(b, f.record[j]);
    aq_page_puts(b, "</td><td>");
    aq_page_esc(b, f.channel[j]);
    aq_page_printf(b, "</td><td class=\"n\">%.6g</td><td class=\"n\">%.4g</td><td>",
                   f.scale[j], f.misfit_one[j]);
    aq_page_esc(b, f.event[j]);
    aq_page_puts(b, "</td></tr>\n");
  }
  aq_page_puts(b, "</tbody></table>\n<details><summary>How the suite was found (the suite "
                  "file's header)</summary><pre>");
  aq_page_esc(b, f.comments ? f.comments : "");
  aq_page_puts(b, "</pre></details>\n");
  aq_h5_select_file_free(&f);
  return st;
}
