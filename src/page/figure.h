/* figure.h: a figure of src/plot inline in the page (src/page/figure.c).
 * draw(ctx, path, err) renders the figure as SVG to path (an aq_plot_*
 * call); the file is read back into the page and removed. */
#ifndef AQ_PAGE_FIGURE_H
#define AQ_PAGE_FIGURE_H

#include <stddef.h>

#include "../error.h"
#include "buf.h"

typedef aq_status (*aq_page_draw_fn)(void *ctx, const char *svg_path, aq_error *err);

/* The temporary a figure of the page for target is drawn to, into
 * buf[cap] (one at a time; a signal handler can remove it). */
void aq_page_figure_temp(const char *target, char *buf, size_t cap);

/* Append the figure drawn by draw(ctx) at tmp to out as an <svg> element
 * (aria-label: label; ids prefixed "f<id>-").  The file is removed. */
aq_status aq_page_figure(aq_page_buf *out, const char *tmp, int id, const char *label,
                         aq_page_draw_fn draw, void *ctx, aq_error *err);

#endif
