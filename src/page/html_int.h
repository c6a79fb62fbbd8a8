/* html_int.h: the inside of the report page (page.h), shared by its files
 * and by no one else:
 *   html.c           the page: style, script, head, contents, the verdict
 *                    map, the sections in order, the file written whole;
 *                    the cells, notes and figures every section uses
 *   html_run.c       the run (command, options, records, arches) and the
 *                    failed records
 *   html_arch.c      per arch: its figures and verdict table
 *   html_capacity.c  a capacity file's section
 *   html_spectrum.c  a spectrum file's section
 * (a select file's section: select.c). */
#ifndef AQ_PAGE_HTML_INT_H
#define AQ_PAGE_HTML_INT_H

#include <stddef.h>

#include "../error.h"
#include "../plot/plot.h"
#include "../report/report.h"
#include "buf.h"
#include "figure.h"
#include "page.h"
#include "read.h"

/* The page being written: its text, inputs, figures' temporary and
 * count, the results file as read, and where failures go. */
typedef struct {
  aq_page_buf *b;
  const aq_page_input *in;
  const char *target;
  char tmp[1100]; /* the figures' temporary */
  int nfig;
  aq_page_results r;
  aq_error *err;
} aq_html_page;

/* The file name of path p, without its directories. */
const char *aq_html_base(const char *p);

/* A number cell: the value to 4 significant digits, data-v the whole. */
void aq_html_num_td(aq_page_buf *b, double v, const char *fmt);

/* A text cell, escaped (mono: in the fixed-width font). */
void aq_html_text_td(aq_page_buf *b, const char *s, int mono);

/* A section's "How to read this." note (html: the page's own markup). */
void aq_html_read_note(aq_page_buf *b, const char *html);

/* A figure of src/plot drawn by draw(ctx) as inline SVG, numbered, with
 * its label (figure.h). */
aq_status aq_html_figure(aq_html_page *p, const char *label, aq_page_draw_fn draw, void *ctx);

/* A run's verdict: failed, collapse or survived. */
const char *aq_html_verdict(const aq_summary *s);

/* The sections (each file's, above); those that read a file return its
 * failure to read (p->err names it). */
void aq_html_section_run(aq_html_page *p);
void aq_html_section_failed(aq_html_page *p);
aq_status aq_html_section_arch(aq_html_page *p, size_t a, size_t *nrows);
aq_status aq_html_section_capacity(aq_html_page *p, const char *path, size_t index);
aq_status aq_html_section_spectrum(aq_html_page *p, const char *path, size_t index);

#endif
