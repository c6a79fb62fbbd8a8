/* html.c: the report page (page.h).  One HTML file: the style sheet and a
 * small script inline, the figures inline SVG, nothing fetched.  The
 * script only adds sorting (click a column's head) and a filter by verdict
 * to the verdict tables; every table and figure is there without it. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "../arch/arch.h"
#include "../plot/plot.h"
#include "../report/h5_capacity.h"
#include "../util/cleanup.h"
#include "../util/outfile.h"
#include "buf.h"
#include "figure.h"
#include "page.h"
#include "read.h"
#include "select.h"

/* ---- style and script --------------------------------------------------- */

static const char STYLE[] =
    "body{font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;font-size:10.5pt;"
    "line-height:1.35;color:#111;margin:0 auto;max-width:62em;padding:1em 1.5em}\n"
    "h1{font-size:1.6em;margin:.2em 0}h2{font-size:1.3em;border-bottom:2px solid #333;"
    "margin-top:1.8em}h3{font-size:1.1em;margin-top:1.4em}\n"
    "table{border-collapse:collapse;margin:.4em 0 1em;font-size:.9em}\n"
    "th,td{border:1px solid #999;padding:.15em .4em;text-align:left;vertical-align:top}\n"
    "th{background:#e8e8e8}td.n{text-align:right;font-variant-numeric:tabular-nums}\n"
    "table.wide{width:100%}code,.mono{font-family:'DejaVu Sans Mono',monospace;font-size:.92em;"
    "word-break:break-all}\n"
    "td.hash{font-family:'DejaVu Sans Mono',monospace;font-size:.8em;white-space:nowrap}\n"
    "pre{font-size:.85em;background:#f4f4f4;padding:.4em;white-space:pre-wrap}\n"
    ".read{background:#f3f6fb;border-left:4px solid #1f5bb4;padding:.3em .8em;margin:.6em 0}\n"
    ".v-c{background:#b3001b;color:#fff;font-weight:bold}\n"
    ".v-f{background:#ddd;font-style:italic}\n"
    ".v-s{}\n"
    ".fig{width:100%;height:auto;max-width:46em;display:block;margin:.5em 0}\n"
    ".controls{margin:.3em 0}.controls label{margin-right:1em}\n"
    "th.sort{cursor:pointer}th.sort:after{content:' \\2195';color:#666}\n"
    ".summary td{border:none;padding:0 1em 0 0}\n"
    "@media print{body{max-width:none;padding:0;font-size:9pt}.controls{display:none}"
    "th.sort:after{content:''}h2{page-break-before:always}h2.first{page-break-before:auto}"
    "h2,h3,h4{break-after:avoid;page-break-after:avoid}"
    "tr,.fig,.read{page-break-inside:avoid}thead{display:table-header-group}"
    "a{color:inherit;text-decoration:none}}\n"
    "@page{margin:12mm}\n";

/* Sorting by any column (numbers by data-v, else text) and a filter by
 * verdict on every table.verdicts; the controls are made here, so a page
 * read without the script shows no control that does nothing. */
static const char SCRIPT[] =
    "(function(){\n"
    "function key(td){var v=td.getAttribute('data-v');"
    "return v===null?td.textContent:parseFloat(v);}\n"
    "document.querySelectorAll('table.verdicts').forEach(function(t){\n"
    " var body=t.tBodies[0],heads=t.tHead.rows[0].cells;\n"
    " Array.prototype.forEach.call(heads,function(th,i){th.className+=' sort';\n"
    "  th.title='sort by this column';th.onclick=function(){\n"
    "   var up=th.getAttribute('data-up')!=='1';th.setAttribute('data-up',up?'1':'0');\n"
    "   var rows=Array.prototype.slice.call(body.rows);\n"
    "   rows.sort(function(a,b){var x=key(a.cells[i]),y=key(b.cells[i]);\n"
    "    if(typeof x==='number'&&typeof y==='number'){if(isNaN(x))return 1;if(isNaN(y))return -1;"
    "return up?x-y:y-x;}\n"
    "    return up?String(x).localeCompare(String(y)):String(y).localeCompare(String(x));});\n"
    "   rows.forEach(function(r){body.appendChild(r);});};});\n"
    " var c=document.createElement('div');c.className='controls';c.textContent='Show: ';\n"
    " ['collapse','survived','failed'].forEach(function(v){var l=document.createElement('label');\n"
    "  var b=document.createElement('input');b.type='checkbox';b.checked=true;b.value=v;\n"
    "  b.onchange=function(){Array.prototype.forEach.call(body.rows,function(r){\n"
    "   if(r.getAttribute('data-verdict')===v)r.style.display=b.checked?'':'none';});};\n"
    "  l.appendChild(b);l.appendChild(document.createTextNode(' '+v));c.appendChild(l);});\n"
    " t.parentNode.insertBefore(c,t);});\n"
    "})();\n";

/* ---- helpers -------------------------------------------------------------- */

typedef struct {
  aq_page_buf *b;
  const aq_page_input *in;
  const char *target;
  char tmp[1100]; /* the figures' temporary */
  int nfig;
  aq_page_results r;
  aq_error *err;
} page;

static const char *base(const char *p)
{
  const char *b = strrchr(p, '/');
  return b ? b + 1 : p;
}

/* A number cell: the value to 4 significant digits, data-v the whole. */
static void num_td(aq_page_buf *b, double v, const char *fmt)
{
  if (isnan(v)) {
    aq_page_puts(b, "<td class=\"n\" data-v=\"NaN\">–</td>");
    return;
  }
  aq_page_printf(b, "<td class=\"n\" data-v=\"%s\">", AQ_TEXT_NUM(v));
  aq_page_printf(b, fmt, v);
  aq_page_puts(b, "</td>");
}

static void text_td(aq_page_buf *b, const char *s, int mono)
{
  aq_page_puts(b, mono ? "<td class=\"mono\">" : "<td>");
  aq_page_esc(b, s);
  aq_page_puts(b, "</td>");
}

static void read_note(aq_page_buf *b, const char *html)
{
  aq_page_puts(b, "<div class=\"read\"><b>How to read this.</b> ");
  aq_page_puts(b, html);
  aq_page_puts(b, "</div>\n");
}

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

/* ---- figures ----------------------------------------------------------- */

/* Whether results file path keeps arch index's geometry (/geometry/NNN). */
static int has_geometry(const char *path, size_t index)
{
  char obj[64];
  snprintf(obj, sizeof obj, "/geometry/%03zu", index);
  int there = 0;
  H5E_BEGIN_TRY
  {
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f >= 0) {
      there = H5Lexists(f, "/geometry", H5P_DEFAULT) > 0 && H5Lexists(f, obj, H5P_DEFAULT) > 0;
      H5Fclose(f);
    }
  }
  H5E_END_TRY;
  return there;
}

typedef struct {
  const aq_arch *arch;
  const char *results, *name; /* arch NULL: drawn from the results file's /geometry */
} arch_fig;
static aq_status draw_arch(void *ctx, const char *svg, aq_error *err)
{
  const arch_fig *a = ctx;
  if (!a->arch)
    return aq_plot_arch_h5(a->results, a->name, 0, svg, NULL, NULL, err);
  return aq_plot_arch(a->arch, 0, svg, NULL, NULL, err);
}

typedef struct {
  const aq_h5_suite *s;
  const char *source;
} suite_fig;
static aq_status draw_suite(void *ctx, const char *svg, aq_error *err)
{
  const suite_fig *f = ctx;
  return aq_plot_suite(f->s->runs, f->s->nruns, f->source, svg, NULL, NULL, err);
}

typedef struct {
  const aq_plot_run *run;
} hist_fig;
static aq_status draw_history(void *ctx, const char *svg, aq_error *err)
{
  const hist_fig *h = ctx;
  return aq_plot_history(h->run, svg, NULL, NULL, err);
}

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

static aq_status figure(page *p, const char *label, aq_page_draw_fn draw, void *ctx)
{
  aq_page_puts(p->b, "<figure>");
  aq_status st = aq_page_figure(p->b, p->tmp, ++p->nfig, label, draw, ctx, p->err);
  aq_page_puts(p->b, "</figure>\n");
  return st;
}

/* ---- the run ------------------------------------------------------------ */

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

static void section_run(page *p)
{
  aq_page_buf *b = p->b;
  const aq_page_attrs *root = &p->r.root;
  const char *v;
  aq_page_puts(b, "<h2 id=\"run\">The run</h2>\n");
  read_note(b, "What was run, on what, and how: enough to run it again and get the "
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
      text_td(b, root->name[i], 1);
      text_td(b, option_text(root->name[i], root->value[i], root->num[i]), 0);
      aq_page_puts(b, "</tr>\n");
    }
  aq_page_puts(b, "</tbody></table>\n");

  /* records */
  const aq_page_table *t = &p->r.records;
  aq_page_printf(b, "<h3 id=\"records\">Records (%zu)</h3>\n", t->nrow);
  read_note(b, "Each record as read and processed.  <i>Units</i> are those the values "
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
    text_td(b, aq_page_cell(t, i, "name"), 1);
    text_td(b, aq_page_cell(t, i, "format"), 0);
    units_td(b, root, t, i);
    char ch[160];
    snprintf(ch, sizeof ch, "%s%s%s%s%s", aq_page_cell(t, i, "network"),
             aq_page_cell(t, i, "network")[0] ? "." : "", aq_page_cell(t, i, "station"),
             aq_page_cell(t, i, "station")[0] ? "." : "", aq_page_cell(t, i, "channel"));
    text_td(b, ch[0] ? ch : "–", 0);
    vertical_td(b, t, i);
    num_td(b, aq_page_cell_num(t, i, "pga_g"), "%.4g");
    num_td(b, aq_page_cell_num(t, i, "pgv_m_s"), "%.4g");
    num_td(b, aq_page_cell_num(t, i, "arias_m_s"), "%.4g");
    num_td(b, aq_page_cell_num(t, i, "d5_95_s"), "%.4g");
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
    text_td(b, aq_page_cell(t, i, "source_file"), 1);
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
  read_note(b, "Each arch's two hinge sets: the <i>primary</i> set opens when the ground "
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
      text_td(b, set, 0);
      snprintf(k, sizeof k, "%s_joints", set);
      aq_page_puts(b, "<td class=\"hash\">");
      aq_page_esc(b, (v = aq_page_attr(A, k)) ? v : "–");
      snprintf(k, sizeof k, "%s_faces", set);
      aq_page_puts(b, "</td><td class=\"hash\">");
      aq_page_esc(b, (v = aq_page_attr(A, k)) ? v : "–");
      aq_page_puts(b, "</td>");
      snprintf(k, sizeof k, "%s_lambda0", set);
      num_td(b, aq_page_attr_num(A, k), "%.4g");
      snprintf(k, sizeof k, "%s_q_c_rad", set);
      num_td(b, aq_page_attr_num(A, k), "%.4g");
      snprintf(k, sizeof k, "%s_admissible", set);
      text_td(b, aq_page_attr_num(A, k) == 1 ? "yes" : "no", 0);
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

/* ---- per arch ------------------------------------------------------------ */

static const char *verdict(const aq_summary *s)
{
  return aq_summary_failed(s->status) ? "failed" : s->collapsed == 1 ? "collapse" : "survived";
}

/* The marks of a run that ran (docs/demand.md): 0 none, 1 slides, 2
 * beyond, 3 both. */
static int marks(const aq_summary *s)
{
  return (strstr(s->status, "slides") != NULL) | (strstr(s->status, "beyond") != NULL) << 1;
}

/* The history key of a run (as h5.c names /histories groups). */
static void history_key(const aq_h5_run *r, char *key, size_t cap)
{
  char az[32] = "";
  if (!isnan(r->s.azimuth_deg))
    snprintf(az, sizeof az, "_az%.6g", r->s.azimuth_deg);
  snprintf(key, cap, "%05lld_%03lld_%03lld%s%s", (long long)r->record_index,
           (long long)r->arch_index, (long long)r->scale_index,
           strcmp(r->s.polarity, "reversed") == 0 ? "r" : "", az);
}

static aq_status history_figure(page *p, const aq_h5_run *r, const char *why)
{
  char key[96];
  history_key(r, key, sizeof key);
  aq_plot_run run;
  aq_error e;
  aq_page_buf *b = p->b;
  aq_page_puts(b, "<h4>");
  aq_page_esc(b, base(r->s.record));
  aq_page_printf(b, " at scale %.4g, %s (%s)</h4>\n", r->s.scale, r->s.polarity, why);
  if (aq_plot_run_read(p->in->results, key, &run, &e) != AQ_OK) {
    aq_page_puts(b, "<p><i>History not stored: ");
    aq_page_esc(b, e.message);
    aq_page_puts(b, "</i></p>\n");
    return AQ_OK;
  }
  hist_fig h = {&run};
  char label[512];
  aq_text_fit(label, sizeof label, "history of %s on %s at scale %g", base(r->s.record),
              r->s.arch, r->s.scale);
  aq_status st = figure(p, label, draw_history, &h);
  aq_plot_run_free(&run);
  return st;
}

/* A run's place among its arch's: its record, scale and azimuth, whose
 * polarities (both, unless the arch is its own mirror image) make one group
 * in which the worse run governs. */
typedef struct {
  int64_t rec, scale;
  double az;
  size_t k;
} run_key;

static int run_key_cmp(const void *pa, const void *pb)
{
  const run_key *x = pa, *y = pb;
  if (x->rec != y->rec)
    return x->rec < y->rec ? -1 : 1;
  if (x->scale != y->scale)
    return x->scale < y->scale ? -1 : 1;
  int nx = isnan(x->az), ny = isnan(y->az);
  if (nx || ny)
    return nx - ny;
  if (x->az != y->az)
    return x->az < y->az ? -1 : 1;
  return x->k < y->k ? -1 : x->k > y->k;
}

/* The governing run of each group of arch a's runs (the worse polarity,
 * aq_summary_worst), in a new array of *ng; NULL when out of memory. */
static const aq_h5_run **governing_runs(const aq_h5_suite *S, size_t a, size_t *ng)
{
  size_t n = 0;
  for (size_t k = 0; k < S->nruns; k++)
    n += S->runs[k].arch_index == (int64_t)a;
  run_key *key = malloc((n ? n : 1) * sizeof *key);
  const aq_summary **row = malloc((n ? n : 1) * sizeof *row);
  const aq_h5_run **gov = malloc((n ? n : 1) * sizeof *gov);
  if (!key || !row || !gov) {
    free(key);
    free(row);
    free(gov);
    return NULL;
  }
  n = 0;
  for (size_t k = 0; k < S->nruns; k++) {
    const aq_h5_run *r = &S->runs[k];
    if (r->arch_index == (int64_t)a)
      key[n++] = (run_key){r->record_index, r->scale_index, r->s.azimuth_deg, k};
  }
  qsort(key, n, sizeof *key, run_key_cmp);
  *ng = 0;
  for (size_t i = 0; i < n;) {
    size_t j = i;
    for (; j < n && key[j].rec == key[i].rec && key[j].scale == key[i].scale &&
           (key[j].az == key[i].az || (isnan(key[j].az) && isnan(key[i].az)));
         j++)
      row[j - i] = &S->runs[key[j].k].s;
    gov[(*ng)++] = &S->runs[key[i + aq_summary_worst(row, j - i)].k];
    i = j;
  }
  free(key);
  free(row);
  return gov;
}

static aq_status section_arch(page *p, size_t a, size_t *nrows)
{
  aq_page_buf *b = p->b;
  const aq_page_attrs *A = &p->r.arch[a];
  const char *name = aq_page_attr(A, "name");
  name = name ? name : "?";
  const aq_h5_suite *S = &p->r.suite;
  size_t ncol = 0, nsurv = 0, nfail = 0, any_az = 0, any_rev = 0, nslide = 0, nbeyond = 0;
  const aq_h5_run *strongest = NULL;
  for (size_t k = 0; k < S->nruns; k++) {
    const aq_h5_run *r = &S->runs[k];
    if (r->arch_index != (int64_t)a)
      continue;
    const char *v = verdict(&r->s);
    ncol += v[0] == 'c';
    nsurv += v[0] == 's';
    nfail += v[0] == 'f';
    nslide += marks(&r->s) & 1;
    nbeyond += (marks(&r->s) & 2) >> 1;
    any_az += !isnan(r->s.azimuth_deg);
    any_rev += strcmp(r->s.polarity, "reversed") == 0;
  }
  /* the worse polarity of each record and scale governs */
  size_t ng = 0, gcol = 0, gsurv = 0;
  const aq_h5_run **gov = governing_runs(S, a, &ng);
  if (!gov)
    return aq_error_set(p->err, AQ_ENOMEM, p->target, -1, -1, NULL, "out of memory");
  for (size_t g = 0; g < ng; g++) {
    const char *v = verdict(&gov[g]->s);
    gcol += v[0] == 'c';
    gsurv += v[0] == 's';
    if (v[0] == 's' && (!strongest || gov[g]->s.pga_g > strongest->s.pga_g))
      strongest = gov[g];
  }
  free(gov);
  aq_page_printf(b, "<h2 id=\"arch-%zu\">Arch ", a);
  aq_page_esc(b, name);
  aq_page_puts(b, "</h2>\n");
  aq_page_printf(b, "<p><b>%zu collapse%s</b>, %zu survived, %zu failed, of %zu runs.  "
                    "λ0 %.4g (primary), %.4g (reverse); q<sub>c</sub> %.4g rad, %.4g rad.</p>\n",
                 ncol, ncol == 1 ? "" : "s", nsurv, nfail, ncol + nsurv + nfail,
                 aq_page_attr_num(A, "primary_lambda0"), aq_page_attr_num(A, "reverse_lambda0"),
                 aq_page_attr_num(A, "primary_q_c_rad"), aq_page_attr_num(A, "reverse_q_c_rad"));
  if (any_rev)
    aq_page_printf(b, "<p>Each record and scale ran both ways (the polarity column), and the "
                      "worse governs: <b>%zu collapse%s</b>, %zu survived, %zu failed, of %zu."
                      "</p>\n",
                   gcol, gcol == 1 ? "" : "s", gsurv, ng - gcol - gsurv, ng);
  const char *control = aq_page_attr(A, "control");
  double mu = aq_page_attr_num(A, "friction");
  if (control && !strcmp(control, "free"))
    aq_page_puts(b, "<p>Hinges <b>free</b>: any joint may open, so each direction of ground "
                    "acceleration drives its own minimum mechanism (primary: along −x, "
                    "reverse: along +x).");
  else
    aq_page_printf(b, "<p>Hinges <b>fixed</b>%s: the hinge-controlled arch, whose mechanical "
                      "joints are the primary set's (the reverse set swaps their faces); every "
                      "other joint is taken to carry what the thrust demands, and every verdict "
                      "below assumes so.",
                   control ? "" : " (a file written before the control was recorded)");
  if (mu > 0)
    aq_page_printf(b, "  Joint friction μ = %.4g.", mu);
  else
    aq_page_puts(b, "  No joint friction given: sliding is not checked.");
  /* the friction the collapse states need (the figure's lower panel) */
  double need[2] = {aq_page_attr_num(A, "primary_mu_required"),
                    aq_page_attr_num(A, "reverse_mu_required")};
  double lf[2] = {aq_page_attr_num(A, "primary_lambda_friction"),
                  aq_page_attr_num(A, "reverse_lambda_friction")};
  static const char *const set_word[2] = {"primary", "reverse"};
  for (int k = 0; k < 2; k++) {
    if (isnan(need[k]))
      continue;
    aq_page_printf(b, "  At its λ0 the %s set needs μ = %.3g (joint %.0f)", set_word[k], need[k],
                   aq_page_attr_num(A, k ? "reverse_mu_joint" : "primary_mu_joint"));
    if (mu > 0 && need[k] > mu)
      aq_page_printf(b, ": <b>more than the arch's %.3g</b>, so a line of thrust stands only "
                        "up to λ = %.4g in that direction", mu, lf[k]);
    aq_page_puts(b, ".");
  }
  aq_page_puts(b, "</p>\n");
  if (nslide || nbeyond) {
    aq_page_puts(b, "<p><b>Beyond the four-hinge model:</b> ");
    if (nslide)
      aq_page_printf(b, "%zu run%s <b>slide%s</b> (the friction demand passed μ); ", nslide,
                     nslide == 1 ? "" : "s", nslide == 1 ? "s" : "");
    if (nbeyond)
      aq_page_printf(b, "in %zu run%s the thrust left a joint's section with free hinges "
                        "(<b>beyond</b>); ",
                     nbeyond, nbeyond == 1 ? "" : "s");
    aq_page_puts(b, "their verdicts are the four-hinge model's, which stops describing the "
                    "arch at the time given; follow them with <code>--model blocks</code>.</p>\n");
  }
  /* the arch */
  const char *cfg = aq_page_attr(A, "config");
  aq_arch *arch = NULL;
  aq_error e;
  /* from its .cfg as read; an arch the .cfg alone does not make (a joints
   * arch's files) from the geometry the results file keeps */
  /* the friction the runs used (--friction over the file's); the page reads no table */
  aq_arch_options ao = {.friction = mu};
  int loaded =
      cfg && aq_arch_load_string_opts(cfg, strlen(cfg), name, &ao, &arch, &e) == AQ_OK;
  if (loaded || has_geometry(p->in->results, a)) {
    arch_fig f = {arch, p->in->results, name};
    char label[200];
    snprintf(label, sizeof label, "arch %s to scale with its hinge sets", name);
    aq_status st = figure(p, label, draw_arch, &f);
    aq_arch_free(arch);
    if (st != AQ_OK)
      return st;
    read_note(b, "The arch to scale.  Filled circles are hinges at the extrados (outer "
                 "face), open circles at the intrados; blue the primary set, orange the "
                 "reverse set.  Below it, the friction each joint needs at the set's λ0 "
                 "(|T|/N of the force across it, from the hinge reactions), each set in its "
                 "colour, the arch's friction coefficient dashed: where a set's curve passes "
                 "it, that joint would slide before the set's hinges can turn.");
  } else {
    aq_page_puts(b, "<p><i>The arch's configuration could not be loaded: ");
    aq_page_esc(b, cfg ? e.message : "no config attribute");
    aq_page_puts(b, "</i></p>\n");
  }
  if (cfg) {
    aq_page_puts(b, "<details><summary>The arch file as read</summary><pre>");
    aq_page_esc(b, cfg);
    aq_page_puts(b, "</pre></details>\n");
  }
  /* a joints arch's files, as read: with the .cfg, what its SHA-256 covers */
  static const char *const data_attr[2][2] = {{"joints_csv", "Its joints file as read"},
                                              {"faces_csv", "Its faces file as read"}};
  for (int k = 0; k < 2; k++) {
    const char *text = aq_page_attr(A, data_attr[k][0]);
    if (!text)
      continue;
    aq_page_printf(b, "<details><summary>%s</summary><pre>", data_attr[k][1]);
    aq_page_esc(b, text);
    aq_page_puts(b, "</pre></details>\n");
  }
  /* the verdict table */
  aq_page_printf(b, "<h3 id=\"verdicts-%zu\">Verdicts</h3>\n", a);
  read_note(b, "One row per run: a record, scaled, against this arch.  <b>COLLAPSE</b> "
               "rows are marked in words and bold as well as colour; <i>failed</i> runs "
               "have no verdict (their reason is in <a href=\"#failed\">Failed "
               "records</a> or the status).  The margin is in the last columns: the peak "
               "rotation as a fraction of q<sub>c</sub> (1 is collapse) and the PGA over "
               "λ0 g (below 1 the arch never moves).  The friction demand is the largest "
               "|T|/N at any joint over the run (∞: a joint pulled apart), the thrust the "
               "largest eccentricity of the line of thrust at a joint that is not a hinge "
               "(beyond 1 it leaves the section).  <b>slides</b>: a friction μ was given and "
               "the demand passed it; <b>beyond</b>: with free hinges the thrust left a "
               "section; each with the time, from which the four-hinge model of the verdict "
               "no longer describes the arch: follow such a run with <code>--model "
               "blocks</code>.  Click a column's head to sort; the boxes above the table "
               "hide a verdict.");
  aq_page_puts(b, "<table class=\"verdicts wide\"><thead><tr><th>record</th><th>scale</th>");
  if (any_rev)
    aq_page_puts(b, "<th>polarity</th>");
  if (any_az)
    aq_page_puts(b, "<th>azimuth (°)</th>");
  aq_page_puts(b, "<th>PGA (g)</th><th>verdict</th><th>collapse at (s)</th>"
                  "<th>peak rotation / q<sub>c</sub></th><th>peak rotation (rad)</th>"
                  "<th>PGA / λ0 g</th><th>impacts</th><th>friction demand</th>"
                  "<th>thrust eccentricity</th></tr></thead><tbody>\n");
  for (size_t k = 0; k < S->nruns; k++) {
    const aq_h5_run *r = &S->runs[k];
    if (r->arch_index != (int64_t)a)
      continue;
    const char *v = verdict(&r->s);
    aq_page_printf(b, "<tr data-verdict=\"%s\">", v);
    aq_page_puts(b, "<td class=\"mono\" title=\"");
    aq_page_esc(b, r->s.record);
    aq_page_puts(b, "\">");
    aq_page_esc(b, base(r->s.record));
    aq_page_puts(b, "</td>");
    num_td(b, r->s.scale, "%.4g");
    if (any_rev)
      text_td(b, r->s.polarity, 0);
    if (any_az)
      num_td(b, r->s.azimuth_deg, "%.4g");
    num_td(b, r->s.pga_g, "%.4g");
    if (v[0] == 'f') {
      aq_page_puts(b, "<td class=\"v-f\">⚠ failed: ");
      aq_page_esc(b, r->s.status);
    } else {
      /* the marks follow the verdict in its cell (a failed run has none) */
      aq_page_puts(b, v[0] == 'c' ? "<td class=\"v-c\">✖ COLLAPSE"
                                  : "<td class=\"v-s\">survived");
      int mk = marks(&r->s);
      if (mk & 1)
        aq_page_printf(b, "; slides at %.3f s", r->s.slide_time_s);
      if (mk & 2)
        aq_page_printf(b, "; beyond at %.3f s", r->s.thrust_ecc_time_s);
    }
    aq_page_puts(b, "</td>");
    num_td(b, r->s.collapse_time_s, "%.3f");
    num_td(b, r->s.peak_rotation_over_qc, "%.3f");
    num_td(b, r->s.peak_rotation_rad, "%.3g");
    num_td(b, r->s.pga_over_lambda0, "%.3g");
    num_td(b, r->s.impacts < 0 ? NAN : (double)r->s.impacts, "%.0f");
    num_td(b, r->s.mu_demand, "%.3g");
    num_td(b, r->s.thrust_ecc_max, "%.3g");
    aq_page_puts(b, "</tr>\n");
    (*nrows)++;
  }
  aq_page_puts(b, "</tbody></table>\n");
  /* histories */
  aq_page_puts(b, "<h3>Responses</h3>\n");
  if (!p->r.have_histories) {
    aq_page_puts(b, "<p><i>No histories in this results file (the suite was run without "
                    "<code>--history</code>): the responses of the collapsed runs and of "
                    "the strongest surviving one are not drawn.</i></p>\n");
    return AQ_OK;
  }
  read_note(b, "The response of each collapsed run and of the surviving run with the "
               "largest PGA: the ground acceleration with ±λ0 g (where the arch starts to "
               "move), the rotation with ±q<sub>c</sub>, and the energies; impacts green, "
               "the collapse red.");
  for (size_t k = 0; k < S->nruns; k++) {
    const aq_h5_run *r = &S->runs[k];
    if (r->arch_index == (int64_t)a && strcmp(verdict(&r->s), "collapse") == 0) {
      aq_status st = history_figure(p, r, "collapse");
      if (st != AQ_OK)
        return st;
    }
  }
  if (strongest)
    return history_figure(p, strongest, "the strongest surviving run");
  return AQ_OK;
}

/* ---- capacity ------------------------------------------------------------ */

static aq_status section_capacity(page *p, const char *path, size_t index)
{
  aq_page_buf *b = p->b; /* path's kind: capacity, checked before the page */
  aq_h5_capacity_table t;
  int present = 0;
  aq_status st = aq_h5_capacity_read(path, &t, &present, p->err);
  if (st != AQ_OK)
    return st;
  aq_page_printf(b, "<h2 id=\"capacity-%zu\">Capacity: ", index);
  aq_page_esc(b, base(path));
  aq_page_puts(b, "</h2>\n");
  read_note(b, "For each record and polarity, every scale factor at which the verdict "
               "changes, from the scale at which the arch first moves to the cap.  The "
               "<i>first collapse</i> is the smallest scale that collapses the arch; a "
               "rocking arch can survive again at a larger scale (a <b>resurrection</b>, "
               "marked R), so the collapse intervals are listed whole.  The fragility curve "
               "is the lognormal probability of collapse against an intensity measure "
               "(IM), fitted to the records' first collapses, with the band of its median's "
               "90 % confidence interval; records that never collapse count as censored "
               "at their cap.");
  aq_page_puts(b, "<table class=\"wide\"><thead><tr><th>record</th><th>arch</th>"
                  "<th>polarity</th><th>status</th><th>moves from scale</th>"
                  "<th>first collapse scale</th><th>its PGA (g)</th>"
                  "<th>collapse intervals (scale)</th><th>resurrection</th></tr></thead>"
                  "<tbody>\n");
  for (size_t k = 0; k < t.n; k++) {
    const aq_h5_capacity_row *r = &t.row[k];
    aq_page_puts(b, "<tr>");
    text_td(b, base(r->record), 1);
    text_td(b, r->arch, 0);
    text_td(b, r->polarity, 0);
    aq_page_printf(b, "<td class=\"%s\">", strcmp(r->status, "ok") == 0 ? "v-s" : "v-f");
    aq_page_esc(b, r->status);
    aq_page_puts(b, "</td>");
    num_td(b, r->d[0], "%.4g");
    num_td(b, r->d[1], "%.4g");
    num_td(b, r->d[2], "%.4g");
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
    st = figure(p, label, draw_capacity, &c);
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
                      "<th>censored</th></tr></thead><tbody>\n");
      for (size_t i = 0; i < n; i++) {
        const aq_h5_fragility_fit *f = &t.fit[order[i]];
        if (f->rank > 0) /* the file's rank */
          aq_page_printf(b, "<tr><td class=\"n\">%lld</td>", (long long)f->rank);
        else
          aq_page_puts(b, "<tr><td class=\"n\">–</td>");
        text_td(b, f->im, 1);
        num_td(b, f->median, "%.4g");
        num_td(b, f->beta, "%.3f");
        num_td(b, f->beta_per_power, "%.3f");
        aq_page_printf(b, "<td class=\"n\">%.4g – %.4g</td>", f->median_lo, f->median_hi);
        num_td(b, (double)f->records, "%.0f");
        num_td(b, (double)f->censored, "%.0f");
        aq_page_puts(b, "</tr>\n");
      }
      aq_page_puts(b, "</tbody></table>\n");
    }
  }
  aq_h5_capacity_table_free(&t);
  return st;
}

/* ---- failed records ------------------------------------------------------- */

static void section_failed(page *p)
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
  read_note(b, "Records that could not be read or processed, each with the one-line "
               "reason archquake gave.  They have no verdict; the message says what to "
               "change (a <code>--units</code> rule, the .AT2 beside a .VT2, ...).");
  aq_page_puts(b, "<table class=\"wide\"><thead><tr><th>record</th><th>status</th>"
                  "<th>reason</th></tr></thead><tbody>\n");
  for (size_t i = 0; i < t->nrow; i++)
    if (strcmp(aq_page_cell(t, i, "status"), "ok") != 0) {
      aq_page_puts(b, "<tr>");
      text_td(b, aq_page_cell(t, i, "name"), 1);
      aq_page_puts(b, "<td class=\"v-f\">");
      aq_page_esc(b, aq_page_cell(t, i, "status"));
      aq_page_puts(b, "</td>");
      text_td(b, aq_page_cell(t, i, "error"), 0);
      aq_page_puts(b, "</tr>\n");
    }
  aq_page_puts(b, "</tbody></table>\n");
}

/* ---- spectra ------------------------------------------------------------- */

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

static aq_status section_spectrum(page *p, const char *path, size_t index)
{
  aq_page_buf *b = p->b;
  aq_h5_spectra_table t;
  aq_status st = aq_h5_spectra_read(path, &t, p->err);
  if (st != AQ_OK)
    return st;
  aq_page_printf(b, "<h2 id=\"spectrum-%zu\">Spectra: ", index);
  aq_page_esc(b, base(path));
  aq_page_puts(b, "</h2>\n");
  int rule = t.peaks;
  read_note(b, "The response spectra of each record (and of each <code>--components</code> "
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
    aq_text_fit(label, sizeof label, "response spectra of %s", base(path));
    st = figure(p, label, draw_spectrum, &f);
  } else {
    for (size_t i = 0; i < t.n && st == AQ_OK; i++)
      if (i == 0 || strcmp(t.record[i], t.record[i - 1]) != 0) {
        spectrum_fig f = {&t, t.record[i], path};
        char label[600];
        aq_text_fit(label, sizeof label, "response spectra of %s", base(t.record[i]));
        st = figure(p, label, draw_spectrum, &f);
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
    aq_page_esc(b, base(t.record[i]));
    aq_page_puts(b, "</td>");
    text_td(b, t.component[i], 0);
    num_td(b, t.damping[i], "%.3g");
    num_td(b, t.psa_g[peak], "%.4g");
    num_td(b, t.period_s[peak], "%.4g");
    for (int k = 0; k < NTABLE_T; k++)
      if (have[k])
        num_td(b, at[k], "%.4g");
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
    text_td(b, base(t.record[i]), 1);
    text_td(b, t.component[i], 0);
    num_td(b, t.damping[i], "%.3g");
    num_td(b, t.period_s[i], "%.4g");
    num_td(b, t.psa_g[i], "%.4g");
    num_td(b, t.sd_m[i], "%.4g");
    num_td(b, t.psv_m_s[i], "%.4g");
    aq_page_puts(b, "</tr>\n");
  }
  aq_page_puts(b, "</tbody></table></details>\n");
  aq_h5_spectra_table_free(&t);
  return st;
}

/* ---- the page -------------------------------------------------------------- */

static double now_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* The file a section of kind `kind` reports, other files: capacity,
 * select, spectrum. */
static aq_page_kind other_kind(const page *p, size_t c)
{
  aq_page_kind kind = AQ_PAGE_CAPACITY;
  aq_error e;
  aq_page_file_kind(p->in->capacity[c], &kind, &e); /* checked before the page */
  return kind;
}

static aq_status build(page *p, aq_page_stats *stats)
{
  aq_page_buf *b = p->b;
  const aq_h5_suite *S = &p->r.suite;
  const char *first = p->in->results ? p->in->results : p->in->capacity[0];
  size_t ncol = 0, nfail = 0, nkind[4] = {0, 0, 0, 0};
  for (size_t k = 0; k < S->nruns; k++) {
    ncol += strcmp(verdict(&S->runs[k].s), "collapse") == 0;
    nfail += strcmp(verdict(&S->runs[k].s), "failed") == 0;
  }
  for (size_t c = 0; c < p->in->ncapacity; c++)
    nkind[other_kind(p, c)]++;
  aq_page_puts(b, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
                  "<meta name=\"viewport\" content=\"width=device-width\">\n<title>archquake "
                  "report: ");
  aq_page_esc(b, base(first));
  aq_page_printf(b, "</title>\n<style>\n%s</style>\n</head><body>\n", STYLE);
  aq_page_puts(b, "<h1>archquake report</h1>\n<p class=\"mono\">");
  aq_page_esc(b, p->in->results ? p->in->results : first);
  for (size_t c = p->in->results ? 0 : 1; c < p->in->ncapacity; c++) {
    aq_page_puts(b, "<br>");
    aq_page_esc(b, p->in->capacity[c]);
  }
  aq_page_puts(b, "</p>\n<table class=\"summary\"><tr>");
  aq_page_printf(b, "<td><b>%zu</b> records</td>", p->r.records.nrow);
  if (p->in->results)
    aq_page_printf(b, "<td><b>%zu</b> arches</td><td><b>%zu</b> runs</td><td><b>%zu</b> "
                      "collapses</td><td><b>%zu</b> failed runs</td>",
                   p->r.narch, S->nruns, ncol, nfail);
  else if (p->r.narch)
    aq_page_printf(b, "<td><b>%zu</b> arches</td>", p->r.narch);
  if (nkind[AQ_PAGE_CAPACITY])
    aq_page_printf(b, "<td><b>%zu</b> capacity file%s</td>", nkind[AQ_PAGE_CAPACITY],
                   nkind[AQ_PAGE_CAPACITY] == 1 ? "" : "s");
  if (nkind[AQ_PAGE_SELECT])
    aq_page_printf(b, "<td><b>%zu</b> selected suite%s</td>", nkind[AQ_PAGE_SELECT],
                   nkind[AQ_PAGE_SELECT] == 1 ? "" : "s");
  if (nkind[AQ_PAGE_SPECTRUM])
    aq_page_printf(b, "<td><b>%zu</b> spectrum file%s</td>", nkind[AQ_PAGE_SPECTRUM],
                   nkind[AQ_PAGE_SPECTRUM] == 1 ? "" : "s");
  aq_page_puts(b, "</tr></table>\n<p>Contents: ");
  if (p->in->results) {
    aq_page_puts(b, "<a href=\"#overview\">overview</a>");
    for (size_t a = 0; a < p->r.narch; a++) {
      const char *nm = aq_page_attr(&p->r.arch[a], "name");
      aq_page_printf(b, " · <a href=\"#arch-%zu\">arch ", a);
      aq_page_esc(b, nm ? nm : "?");
      aq_page_puts(b, "</a>");
    }
    aq_page_puts(b, " · ");
  }
  for (size_t c = 0; c < p->in->ncapacity; c++) {
    aq_page_kind kind = other_kind(p, c);
    static const char *const id[] = {"", "capacity", "select", "spectrum"},
                             *const what[] = {"", "capacity", "suite", "spectra"};
    aq_page_printf(b, "<a href=\"#%s-%zu\">%s %zu</a> · ", id[kind], c, what[kind], c + 1);
  }
  aq_page_puts(b, "<a href=\"#failed\">failed records</a> · <a href=\"#run\">the run</a>"
                  "</p>\n");
  aq_status st = AQ_OK;
  size_t nrows = 0;
  if (p->in->results) {
    /* overview: the verdict map */
    aq_page_puts(b, "<h2 id=\"overview\" class=\"first\">Overview</h2>\n");
    read_note(b, "Each record against each arch: the worst run over the scales and "
                 "polarities.  A red cell collapsed; otherwise the number is the largest peak "
                 "rotation as a fraction of the collapse rotation q<sub>c</sub> (0: the arch "
                 "never moved; near 1: close to collapse).  Grey cells failed: see "
                 "<a href=\"#failed\">Failed records</a>.");
    suite_fig sf = {S, p->in->results};
    st = S->nruns ? figure(p, "verdict map: records against arches", draw_suite, &sf) : AQ_OK;
    for (size_t a = 0; a < p->r.narch && st == AQ_OK; a++)
      st = section_arch(p, a, &nrows);
  }
  for (size_t c = 0; c < p->in->ncapacity && st == AQ_OK; c++) {
    aq_page_kind kind = other_kind(p, c);
    st = kind == AQ_PAGE_SELECT
             ? aq_page_select_section(b, p->in->capacity[c], c, p->tmp, &p->nfig, p->err)
         : kind == AQ_PAGE_SPECTRUM ? section_spectrum(p, p->in->capacity[c], c)
                                    : section_capacity(p, p->in->capacity[c], c);
  }
  if (st != AQ_OK)
    return st;
  section_failed(p);
  section_run(p);
  aq_page_puts(b, "<hr><p><small>Written by ");
  aq_page_esc(b, p->in->build ? p->in->build : "archquake");
  aq_page_puts(b, ": <span class=\"mono\">");
  aq_page_esc(b, p->in->command_line ? p->in->command_line : "");
  aq_page_printf(b, "</span></small></p>\n<script>\n%s</script>\n</body></html>\n", SCRIPT);
  if (stats) {
    stats->figures = (size_t)p->nfig;
    stats->runs = nrows;
  }
  return b->failed ? aq_error_set(p->err, AQ_ENOMEM, p->target, -1, -1, NULL, "out of memory")
                   : AQ_OK;
}

aq_status aq_page_write(const aq_page_input *in, const char *target, aq_page_stats *stats,
                        aq_error *err)
{
  double t0 = now_s();
  aq_page_buf b = {0};
  page p;
  memset(&p, 0, sizeof p);
  p.b = &b;
  p.in = in;
  p.target = target;
  p.err = err;
  aq_page_figure_temp(target, p.tmp, sizeof p.tmp);
  int fig_slot = aq_cleanup_add(p.tmp); /* a signal while drawing removes it */
  /* every input checked before anything is drawn: the results file (or
     the first other file: the run's section) read, every other one's kind */
  aq_status st = AQ_OK;
  if (!in->results && in->ncapacity == 0)
    st = aq_error_set(err, AQ_EVALUE, target, -1, -1, NULL,
                      "expected a results, capacity, select or spectrum file, got none");
  if (st == AQ_OK)
    st = aq_page_results_read(in->results ? in->results : in->capacity[0], &p.r, err);
  for (size_t c = 0; c < in->ncapacity && st == AQ_OK; c++) {
    aq_page_kind kind;
    st = aq_page_file_kind(in->capacity[c], &kind, err);
    if (st == AQ_OK && kind == AQ_PAGE_RESULTS)
      st = aq_error_set(err, AQ_EFORMAT, in->capacity[c], -1, -1, NULL,
                        "expected at most one results file of the main job, got a second "
                        "(report each suite on a page of its own)");
  }
  if (st == AQ_OK)
    st = build(&p, stats);
  aq_page_results_free(&p.r);
  aq_cleanup_remove(fig_slot);
  aq_outfile o;
  if (st == AQ_OK && (st = aq_outfile_open(&o, target, err)) == AQ_OK) {
    fwrite(b.s, 1, b.n, o.f); /* a short write fails the commit (ferror) */
    st = aq_outfile_commit(&o, err);
  }
  if (stats) {
    stats->bytes = b.n;
    stats->build_s = now_s() - t0;
  }
  aq_page_buf_free(&b);
  return st;
}
