/* html_run.c: the report page's run section (what was run, on what, how)
 * and its failed records (html_int.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "html_int.h"

/* A record's units and where they came from (/records units_source; a file
 * written before that column says only whether --units was given). */
static void units_td(aq_page_buf *b, const aq_page_attrs *root, const aq_page_table *t,
                     size_t i)
{
  static const char *const from[][2] = {{"file", "stated in the file"},
                                        {"response", "StationXML response"},
                                        {"rule", "a --units rule"},
                                        {"option", "--units"}};
  const char *u = aq_page_cell(t, i, "units_orig");
  const char *src = aq_page_cell(t, i, "units_source");
  const char *said = src;
  for (size_t k = 0; k < sizeof from / sizeof from[0]; k++)
    if (strcmp(src, from[k][0]) == 0)
      said = from[k][1];
  if (aq_page_col(t, "units_source") < 0) {
    const char *uo = aq_page_attr(root, "units_override");
    said = !uo || strcmp(uo, "file") == 0 ? "stated in the file" : "--units or the file";
  }
  aq_page_puts(b, "<td>");
  aq_page_esc(b, u[0] ? u : "–");
  if (u[0] && said[0]) {
    aq_page_puts(b, " <small>(");
    aq_page_esc(b, said);
    const char *stated = aq_page_cell(t, i, "units_stated");
    if (stated[0] && strcmp(stated, u) != 0) {
      aq_page_puts(b, "; the file states ");
      aq_page_esc(b, stated);
    }
    aq_page_puts(b, ")</small>");
  }
  aq_page_puts(b, "</td>");
}

/* An arch's shape and voussoirs, as its results file keeps them
 * (/geometry); "–" for a file written before they were kept. */
static void shape_text(aq_page_buf *b, const aq_page_attrs *g)
{
  const char *shape = aq_page_attr(g, "shape");
  double nv = aq_page_attr_num(g, "voussoirs");
  if (!shape) {
    aq_page_puts(b, "–");
    return;
  }
  aq_page_esc(b, shape);
  if (nv > 0)
    aq_page_printf(b, ", %.0f voussoirs", nv);
}

/* Whether the file identifies the record as vertical, and how. */
static void vertical_td(aq_page_buf *b, const aq_page_table *t, size_t i)
{
  double v = aq_page_cell_num(t, i, "vertical");
  const char *by = aq_page_cell(t, i, "vertical_by");
  const char *how = strcmp(by, "stated") == 0 ? "the file says so"
                    : strcmp(by, "dip") == 0  ? "its dip"
                    : strcmp(by, "name") == 0 ? "its channel name"
                                              : by;
  if (!(v >= 0)) { /* no such column, or the record was not read */
    aq_page_puts(b, "<td>–</td>");
    return;
  }
  aq_page_puts(b, v > 0 ? "<td><b>yes</b>" : "<td>no");
  if (v > 0 && how[0]) {
    aq_page_puts(b, " <small>(");
    aq_page_esc(b, how);
    aq_page_puts(b, ")</small>");
  }
  aq_page_puts(b, "</td>");
}

/* Root attributes that are bookkeeping rather than how the suite ran. */
static int is_option(const char *name)
{
  static const char *const not[] = {"archquake_version", "archquake_build", "command_line",
                                    "created", "format_version", "kind", NULL};
  for (int i = 0; not[i]; i++)
    if (strcmp(name, not[i]) == 0)
      return 0;
  return strncmp(name, "timing_", 7) != 0;
}

/* An option's value as the page shows it: a flag's 0 or 1 as no or yes;
 * what a NaN (a value that does not apply) means for that option, in
 * words; every other value as the file holds it. */
static const char *option_text(const char *name, const char *value, double num)
{
  static const struct {
    const char *name, *nan;
  } words[] = {
      {"cor", "per arch (each arch's own [dynamics] cor)"},
      {"lowpass_hz", "off"},
      {"highpass_hz", "off (no filter)"},
      {"dt_override_s", "none (each file's own interval)"},
      {"scale_to_pga_g", "none"},
      {"scale_to_lambda0", "none"},
  };
  static const char *const flags[] = {"filter", "history", "store_records"}; /* 0 or 1 */
  for (size_t k = 0; k < sizeof flags / sizeof flags[0]; k++)
    if (strcmp(name, flags[k]) == 0 && (num == 0 || num == 1))
      return num == 1 ? "yes" : "no";
  if (!isnan(num) || strcmp(value, "nan") != 0)
    return value;
  for (size_t k = 0; k < sizeof words / sizeof words[0]; k++)
    if (strcmp(name, words[k].name) == 0)
      return words[k].nan;
  return "– (not applicable)";
}

void aq_html_section_run(aq_html_page *p)
{
  aq_page_buf *b = p->b;
  const aq_page_attrs *root = &p->r.root;
  const char *v;
  aq_page_puts(b, "<h2 id=\"run\">The run</h2>\n");
  aq_html_read_note(b, "What was run, on what, and how: enough to run it again and get the "
               "same numbers.  Each input is identified by the SHA-256 of its bytes, so a "
               "changed file is seen even under the same name: a record's of its file, an "
               "arch's of its .cfg followed by its joints and faces files for a joints "
               "arch (each shown in the arch's section as read).");
  aq_page_puts(b, "<table class=\"wide\"><tbody>\n<tr><th>command line</th><td class=\"mono\">");
  aq_page_esc(b, (v = aq_page_attr(root, "command_line")) ? v : "?");
  aq_page_puts(b, "</td></tr>\n<tr><th>archquake</th><td>");
  aq_page_esc(b, (v = aq_page_attr(root, "archquake_build")) ? v
                 : (v = aq_page_attr(root, "archquake_version")) ? v : "?");
  aq_page_puts(b, "</td></tr>\n<tr><th>date (UTC)</th><td>");
  aq_page_esc(b, (v = aq_page_attr(root, "created")) ? v : "?");
  aq_page_puts(b, p->in->results ? "</td></tr>\n<tr><th>results file</th><td class=\"mono\">"
                                 : "</td></tr>\n<tr><th>file</th><td class=\"mono\">");
  aq_page_esc(b, p->in->results ? p->in->results : p->in->capacity[0]);
  aq_page_puts(b, "</td></tr>\n</tbody></table>\n<h3>Processing and run options</h3>\n"
                  "<table><thead><tr><th>option</th><th>value</th></tr></thead><tbody>\n");
  for (size_t i = 0; i < root->n; i++)
    if (is_option(root->name[i])) {
      aq_page_puts(b, "<tr>");
      aq_html_text_td(b, root->name[i], 1);
      aq_html_text_td(b, option_text(root->name[i], root->value[i], root->num[i]), 0);
      aq_page_puts(b, "</tr>\n");
    }
  aq_page_puts(b, "</tbody></table>\n");

  /* records */
  const aq_page_table *t = &p->r.records;
  aq_page_printf(b, "<h3 id=\"records\">Records (%zu)</h3>\n", t->nrow);
  aq_html_read_note(b, "Each record as read and processed.  <i>Units</i> are those the values "
               "were read in, and where they came from: stated in the file, the "
               "sensitivity of a StationXML response (miniSEED counts), a "
               "<code>--units GLOB=U</code> rule or <code>--units</code> (the options "
               "above).  PGA, PGV, Arias intensity and the significant duration D5–95 "
               "are of the processed record before scaling.  <i>Vertical</i> says "
               "whether the file identifies the channel as vertical, and how (it says "
               "so, its dip, or its channel name: Z, UD, ...); the main job runs a "
               "vertical only with <code>--accept-vertical</code>.  The second table gives each "
               "file's SHA-256 (as <code>sha256sum</code> prints it), to check that a file "
               "at hand is the one that was run.");
  aq_page_puts(b, "<table class=\"wide\"><thead><tr><th>#</th><th>record</th>"
                  "<th>format</th><th>units (from)</th><th>channel</th><th>vertical</th>"
                  "<th>PGA (g)</th><th>PGV (m/s)</th><th>Arias (m/s)</th><th>D5–95 (s)</th>"
                  "<th>status</th></tr></thead><tbody>\n");
  for (size_t i = 0; i < t->nrow; i++) {
    aq_page_printf(b, "<tr><td class=\"n\">%zu</td>", i);
    aq_html_text_td(b, aq_page_cell(t, i, "name"), 1);
    aq_html_text_td(b, aq_page_cell(t, i, "format"), 0);
    units_td(b, root, t, i);
    char ch[160];
    snprintf(ch, sizeof ch, "%s%s%s%s%s", aq_page_cell(t, i, "network"),
             aq_page_cell(t, i, "network")[0] ? "." : "", aq_page_cell(t, i, "station"),
             aq_page_cell(t, i, "station")[0] ? "." : "", aq_page_cell(t, i, "channel"));
    aq_html_text_td(b, ch[0] ? ch : "–", 0);
    vertical_td(b, t, i);
    aq_html_num_td(b, aq_page_cell_num(t, i, "pga_g"), "%.4g");
    aq_html_num_td(b, aq_page_cell_num(t, i, "pgv_m_s"), "%.4g");
    aq_html_num_td(b, aq_page_cell_num(t, i, "arias_m_s"), "%.4g");
    aq_html_num_td(b, aq_page_cell_num(t, i, "d5_95_s"), "%.4g");
    const char *st = aq_page_cell(t, i, "status");
    aq_page_printf(b, "<td class=\"%s\">", strcmp(st, "ok") ? "v-f" : "v-s");
    aq_page_esc(b, strcmp(st, "ok") ? st : "ok");
    aq_page_puts(b, "</td></tr>\n");
  }
  aq_page_puts(b, "</tbody></table>\n");
  /* the files the records came from, with their hashes: a table of its
     own, so that each hash stays on one line */
  aq_page_puts(b, "<h4>Record files and their SHA-256</h4>\n"
                  "<table class=\"wide files\"><thead><tr><th>#</th><th>file as given</th>"
                  "<th>SHA-256 of its bytes</th></tr></thead><tbody>\n");
  for (size_t i = 0; i < t->nrow; i++) {
    aq_page_printf(b, "<tr><td class=\"n\">%zu</td>", i);
    aq_html_text_td(b, aq_page_cell(t, i, "source_file"), 1);
    const char *h = aq_page_cell(t, i, "sha256");
    aq_page_puts(b, h[0] ? "<td class=\"hash\">" : "<td>");
    aq_page_esc(b, h[0] ? h : "– (not read)");
    aq_page_puts(b, "</td></tr>\n");
  }
  aq_page_puts(b, "</tbody></table>\n");

  /* arches (a spectrum file has none) */
  if (p->r.narch == 0)
    return;
  aq_page_printf(b, "<h3 id=\"arches\">Arches (%zu)</h3>\n", p->r.narch);
  aq_html_read_note(b, "Each arch's two hinge sets: the <i>primary</i> set opens when the ground "
               "accelerates one way, the <i>reverse</i> set (the same joints, faces "
               "swapped) the other way.  λ0 is the static collapse multiplier: a constant "
               "ground acceleration of λ0 g starts the mechanism.  q<sub>c</sub> is the "
               "rotation at which it collapses.  Joints are numbered from the springing "
               "on the +x side (the right in the figures), counter-clockwise; e: "
               "extrados, i: intrados.  The shape and voussoirs are those the results "
               "file keeps with the arch's geometry.");
  aq_page_puts(b, "<table class=\"wide\"><thead><tr><th>arch</th><th>shape</th><th>set</th><th>joints</th>"
                  "<th>faces</th><th>λ0</th><th>q<sub>c</sub> (rad)</th><th>admissible</th>"
                  "<th>file, sha256</th></tr></thead><tbody>\n");
  for (size_t a = 0; a < p->r.narch; a++) {
    const aq_page_attrs *A = &p->r.arch[a];
    for (int s = 0; s < 2; s++) {
      char k[64];
      const char *set = s ? "reverse" : "primary";
      aq_page_puts(b, "<tr>");
      if (s == 0) {
        aq_page_puts(b, "<td rowspan=\"2\"><a href=\"#arch-");
        aq_page_printf(b, "%zu\">", a);
        aq_page_esc(b, (v = aq_page_attr(A, "name")) ? v : "?");
        aq_page_puts(b, "</a></td><td rowspan=\"2\">");
        shape_text(b, &p->r.geom[a]);
        aq_page_puts(b, "</td>");
      }
      aq_html_text_td(b, set, 0);
      snprintf(k, sizeof k, "%s_joints", set);
      aq_page_puts(b, "<td class=\"hash\">");
      aq_page_esc(b, (v = aq_page_attr(A, k)) ? v : "–");
      snprintf(k, sizeof k, "%s_faces", set);
      aq_page_puts(b, "</td><td class=\"hash\">");
      aq_page_esc(b, (v = aq_page_attr(A, k)) ? v : "–");
      aq_page_puts(b, "</td>");
      snprintf(k, sizeof k, "%s_lambda0", set);
      aq_html_num_td(b, aq_page_attr_num(A, k), "%.4g");
      snprintf(k, sizeof k, "%s_q_c_rad", set);
      aq_html_num_td(b, aq_page_attr_num(A, k), "%.4g");
      snprintf(k, sizeof k, "%s_admissible", set);
      aq_html_text_td(b, aq_page_attr_num(A, k) == 1 ? "yes" : "no", 0);
      if (s == 0) {
        aq_page_puts(b, "<td rowspan=\"2\" class=\"mono\">");
        aq_page_esc(b, (v = aq_page_attr(A, "source_file")) ? v : "?");
        aq_page_puts(b, "<br>");
        aq_page_esc(b, (v = aq_page_attr(A, "sha256")) ? v : "?");
        aq_page_puts(b, "</td>");
      }
      aq_page_puts(b, "</tr>\n");
    }
  }
  aq_page_puts(b, "</tbody></table>\n");
}


void aq_html_section_failed(aq_html_page *p)
{
  aq_page_buf *b = p->b;
  const aq_page_table *t = &p->r.records;
  size_t n = 0;
  for (size_t i = 0; i < t->nrow; i++)
    n += strcmp(aq_page_cell(t, i, "status"), "ok") != 0;
  aq_page_printf(b, "<h2 id=\"failed\">Failed records (%zu)</h2>\n", n);
  if (!n) {
    aq_page_puts(b, "<p>Every record was read and processed.</p>\n");
    return;
  }
  aq_html_read_note(b, "Records that could not be read or processed, each with the one-line "
               "reason archquake gave.  They have no verdict; the message says what to "
               "change (a <code>--units</code> rule, the .AT2 beside a .VT2, ...).");
  aq_page_puts(b, "<table class=\"wide\"><thead><tr><th>record</th><th>status</th>"
                  "<th>reason</th></tr></thead><tbody>\n");
  for (size_t i = 0; i < t->nrow; i++)
    if (strcmp(aq_page_cell(t, i, "status"), "ok") != 0) {
      aq_page_puts(b, "<tr>");
      aq_html_text_td(b, aq_page_cell(t, i, "name"), 1);
      aq_page_puts(b, "<td class=\"v-f\">");
      aq_page_esc(b, aq_page_cell(t, i, "status"));
      aq_page_puts(b, "</td>");
      aq_html_text_td(b, aq_page_cell(t, i, "error"), 0);
      aq_page_puts(b, "</tr>\n");
    }
  aq_page_puts(b, "</tbody></table>\n");
}

