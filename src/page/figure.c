/* figure.c: a figure of the plot stage as inline SVG (figure.h).  The
 * figure is drawn to a temporary .svg (PLplot's svg device: text as
 * text), read back, and put into the page without its XML prolog and
 * DOCTYPE, scaled to the page's width by its viewBox, its ids made unique
 * in the page. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../plot/plot.h"
#include "figure.h"

void aq_page_figure_temp(const char *target, char *buf, size_t cap)
{
  snprintf(buf, cap, "%s.fig.%ld.svg", target, (long)getpid());
}

/* The whole file at path, NUL-terminated (malloc'd), or NULL. */
static char *read_all(const char *path)
{
  FILE *f = fopen(path, "rb");
  if (!f)
    return NULL;
  char *s = NULL;
  long n = -1;
  if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0)
    s = malloc((size_t)n + 1);
  if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
    free(s);
    s = NULL;
  }
  if (s)
    s[n] = '\0';
  fclose(f);
  return s;
}

/* Append svg (a whole file of the svg device) to out as an element of the
 * page: from "<svg", width and height replaced by the page's, every id and
 * reference to one prefixed by "f<id>-". */
static int inline_svg(aq_page_buf *out, const char *svg, int id, const char *label)
{
  const char *p = strstr(svg, "<svg");
  if (!p)
    return -1;
  const char *open_end = strchr(p, '>');
  if (!open_end)
    return -1;
  /* the opening tag, its size left to the page */
  aq_page_printf(out, "<svg class=\"fig\" role=\"img\" aria-label=\"");
  aq_page_esc(out, label);
  aq_page_puts(out, "\"");
  const char *vb = strstr(p, "viewBox=\"");
  if (vb && vb < open_end) {
    const char *e = strchr(vb + 9, '"');
    aq_page_put(out, " ", 1);
    aq_page_put(out, vb, (size_t)(e - vb + 1));
  }
  aq_page_puts(out, " xmlns=\"http://www.w3.org/2000/svg\">");
  char prefix[32];
  snprintf(prefix, sizeof prefix, "f%d-", id);
  for (const char *q = open_end + 1; *q;) {
    const char *a = strstr(q, "id=\""), *b = strstr(q, "url(#");
    const char *next = a && (!b || a < b) ? a : b;
    if (!next) {
      aq_page_puts(out, q);
      break;
    }
    size_t skip = next == a ? 4 : 5;
    aq_page_put(out, q, (size_t)(next - q) + skip);
    aq_page_puts(out, prefix);
    q = next + skip;
  }
  return 0;
}

aq_status aq_page_figure(aq_page_buf *out, const char *tmp, int id, const char *label,
                         aq_page_draw_fn draw, void *ctx, aq_error *err)
{
  aq_status st = draw(ctx, tmp, err);
  if (st != AQ_OK) {
    remove(tmp);
    return st;
  }
  char *svg = read_all(tmp);
  remove(tmp);
  if (!svg)
    return aq_error_set(err, AQ_EIO, tmp, -1, -1, NULL, "cannot read the figure back");
  int rc = inline_svg(out, svg, id, label);
  free(svg);
  if (rc != 0)
    return aq_error_set(err, AQ_EFORMAT, tmp, -1, -1, NULL, "expected an SVG figure");
  return AQ_OK;
}
