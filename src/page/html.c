/* html.c: the report page (page.h).  One HTML file: the style sheet and a
 * small script inline, the figures inline SVG, nothing fetched.  The
 * script only adds sorting (click a column's head) and a filter by verdict
 * to the verdict tables; every table and figure is there without it.
 * Here: the style and script, the page's head, contents and verdict map,
 * the sections in order and the file written whole; the sections
 * themselves are html_run.c, html_arch.c, html_capacity.c,
 * html_spectrum.c and select.c (html_int.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "../plot/plot.h"
#include "../util/cleanup.h"
#include "../util/outfile.h"
#include "buf.h"
#include "figure.h"
#include "html_int.h"
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

/* ---- cells, notes and figures (html_int.h) ------------------------------- */

const char *aq_html_base(const char *p)
{
  const char *b = strrchr(p, '/');
  return b ? b + 1 : p;
}

/* A number cell: the value to 4 significant digits, data-v the whole. */
void aq_html_num_td(aq_page_buf *b, double v, const char *fmt)
{
  if (isnan(v)) {
    aq_page_puts(b, "<td class=\"n\" data-v=\"NaN\">–</td>");
    return;
  }
  aq_page_printf(b, "<td class=\"n\" data-v=\"%s\">", AQ_TEXT_NUM(v));
  aq_page_printf(b, fmt, v);
  aq_page_puts(b, "</td>");
}

void aq_html_text_td(aq_page_buf *b, const char *s, int mono)
{
  aq_page_puts(b, mono ? "<td class=\"mono\">" : "<td>");
  aq_page_esc(b, s);
  aq_page_puts(b, "</td>");
}

void aq_html_read_note(aq_page_buf *b, const char *html)
{
  aq_page_puts(b, "<div class=\"read\"><b>How to read this.</b> ");
  aq_page_puts(b, html);
  aq_page_puts(b, "</div>\n");
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

aq_status aq_html_figure(aq_html_page *p, const char *label, aq_page_draw_fn draw,
                         void *ctx)
{
  aq_page_puts(p->b, "<figure>");
  aq_status st = aq_page_figure(p->b, p->tmp, ++p->nfig, label, draw, ctx, p->err);
  aq_page_puts(p->b, "</figure>\n");
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
static aq_page_kind other_kind(const aq_html_page *p, size_t c)
{
  aq_page_kind kind = AQ_PAGE_CAPACITY;
  aq_error e;
  aq_page_file_kind(p->in->capacity[c], &kind, &e); /* checked before the aq_html_page */
  return kind;
}

static aq_status build(aq_html_page *p, aq_page_stats *stats)
{
  aq_page_buf *b = p->b;
  const aq_h5_suite *S = &p->r.suite;
  const char *first = p->in->results ? p->in->results : p->in->capacity[0];
  size_t ncol = 0, nfail = 0, nkind[4] = {0, 0, 0, 0};
  for (size_t k = 0; k < S->nruns; k++) {
    ncol += strcmp(aq_html_verdict(&S->runs[k].s), "collapse") == 0;
    nfail += strcmp(aq_html_verdict(&S->runs[k].s), "failed") == 0;
  }
  for (size_t c = 0; c < p->in->ncapacity; c++)
    nkind[other_kind(p, c)]++;
  aq_page_puts(b, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
                  "<meta name=\"viewport\" content=\"width=device-width\">\n<title>archquake "
                  "report: ");
  aq_page_esc(b, aq_html_base(first));
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
    aq_html_read_note(b, "Each record against each arch: the worst run over the scales and "
                 "polarities.  A red cell collapsed; otherwise the number is the largest peak "
                 "rotation as a fraction of the collapse rotation q<sub>c</sub> (0: the arch "
                 "never moved; near 1: close to collapse).  Grey cells failed: see "
                 "<a href=\"#failed\">Failed records</a>.");
    suite_fig sf = {S, p->in->results};
    st = S->nruns ? aq_html_figure(p, "verdict map: records against arches", draw_suite, &sf)
                  : AQ_OK;
    for (size_t a = 0; a < p->r.narch && st == AQ_OK; a++)
      st = aq_html_section_arch(p, a, &nrows);
  }
  for (size_t c = 0; c < p->in->ncapacity && st == AQ_OK; c++) {
    aq_page_kind kind = other_kind(p, c);
    st = kind == AQ_PAGE_SELECT
             ? aq_page_select_section(b, p->in->capacity[c], c, p->tmp, &p->nfig, p->err)
         : kind == AQ_PAGE_SPECTRUM ? aq_html_section_spectrum(p, p->in->capacity[c], c)
                                    : aq_html_section_capacity(p, p->in->capacity[c], c);
  }
  if (st != AQ_OK)
    return st;
  aq_html_section_failed(p);
  aq_html_section_run(p);
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
  aq_html_page p;
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

