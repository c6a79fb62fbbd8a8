/* keys.c: the keys of a figure (see plot.h): the keys laid out below a
 * plot in one or two columns, their names shortened to their room, and
 * PLplot's legends with archquake's colours and padding.
 */
#include <plplot.h>
#include <stdio.h>
#include <stdlib.h>

#include "labels.h"
#include "plot.h"

/* In fractions of a key's width: a column's line, where its text starts,
 * and the room between two columns. */
static const double KEY_LINE0 = 0.01, KEY_LINE1 = 0.07, KEY_LEAD = 0.085, KEY_GAP = 0.03;

/* The widest whole text of each column of a key in nrow rows, in
 * fractions of its width: measured by measure (mm, or em) over unit (the
 * key's width in the same unit). */
static void key_widest(const aq_plot_key *key, size_t n, size_t nrow, double (*measure)(const char *),
                       double unit, double widest[2])
{
  char esc[1024];
  widest[0] = widest[1] = 0;
  for (size_t k = 0; k < n; k++) {
    aq_plot_escape(key[k].name ? key[k].name : "", esc, sizeof esc);
    double w = (measure(key[k].pre ? key[k].pre : "") + measure(esc) +
                measure(key[k].post ? key[k].post : "")) / unit;
    size_t c = k >= nrow;
    widest[c] = w > widest[c] ? w : widest[c];
  }
}

static int key_side_by_side(const double widest[2])
{
  return KEY_LEAD + widest[0] + KEY_GAP + KEY_LEAD + widest[1] <= 1;
}

size_t aq_plot_key_columns(const aq_plot_key *key, size_t n, double x0, double x1, int width_px,
                           double text_mm)
{
  if (n <= AQ_PLOT_KEY_ONE_COLUMN)
    return 1;
  /* the key's width in em of its font (72 points an inch) */
  double widest[2];
  key_widest(key, n, (n + 1) / 2, aq_plot_text_em,
             (x1 - x0) * (double)width_px * 25.4 / 72 / (FONT_PER_HEIGHT * text_mm), widest);
  return key_side_by_side(widest) || n > AQ_PLOT_KEY_ROWS_MAX ? 2 : 1;
}

size_t aq_plot_key_rows(size_t n, size_t ncol)
{
  return ncol > 1 ? (n + 1) / 2 : n;
}

void aq_plot_key_below(const aq_plot_key *key, size_t n, size_t ncol, double x0, double x1,
                       double y0, double y1)
{
  enum { NM = 1024 };
  if (n == 0)
    return;
  ncol = ncol > 1 ? 2 : 1;
  size_t nrow = aq_plot_key_rows(n, ncol);
  char *nm = malloc(n * NM);
  const char **name = malloc(n * sizeof *name);
  double *room = malloc(n * sizeof *room);
  if (!nm || !name || !room) {
    free(nm);
    free(name);
    free(room);
    return;
  }
  double wmm = (x1 - x0) * aq_plot_page_w_mm(), widest[2];
  key_widest(key, n, ncol > 1 ? nrow : n, aq_plot_text_mm, wmm, widest);
  /* where the second column starts: at the middle when both columns fit
     whole beside it, else past the first's widest text; when the two do
     not fit side by side, each a share in proportion to its texts */
  double x2 = 1;
  if (ncol > 1) {
    double need1 = KEY_LEAD + widest[0] + KEY_GAP, need2 = KEY_LEAD + widest[1];
    if (key_side_by_side(widest))
      x2 = need1 <= 0.5 && 0.5 + need2 <= 1 ? 0.5 : need1;
    else
      x2 = need1 / (need1 + need2);
  }
  for (size_t k = 0; k < n; k++) {
    int second = ncol > 1 && k >= nrow;
    double end = ncol > 1 && !second ? x2 - KEY_GAP : 1, start = second ? x2 : 0;
    name[k] = key[k].name ? key[k].name : "";
    room[k] = (end - start - KEY_LEAD) * wmm - aq_plot_text_mm(key[k].pre ? key[k].pre : "") -
              aq_plot_text_mm(key[k].post ? key[k].post : "");
  }
  aq_plot_shorten_set_to(name, n, room, nm, NM);
  plvpor(x0, x1, y0, y1);
  plwind(0, 1, (double)nrow, 0);
  for (size_t k = 0; k < n; k++) {
    double x = ncol > 1 && k >= nrow ? x2 : 0.0, y = (double)(k % nrow) + 0.5;
    PLFLT lx[2] = {x + KEY_LINE0, x + KEY_LINE1}, ly[2] = {y, y};
    plcol0(key[k].color);
    pllsty(key[k].style);
    plwidth(key[k].width);
    plline(2, lx, ly);
    pllsty(1);
    plwidth(1);
    plcol0(AQ_PC_FG);
    char text[3 * NM];
    snprintf(text, sizeof text, "%s%s%s", key[k].pre ? key[k].pre : "", nm + k * NM,
             key[k].post ? key[k].post : "");
    plptex(x + KEY_LEAD, y, 1, 0, 0, text);
  }
  free(nm);
  free(name);
  free(room);
}

void aq_plot_legend(int position, size_t n, const char *const *text,
                    const int *color, const int *style, const char *const *sym)
{
  aq_plot_legend_at(position, 0.01, 0.02, 1, n, text, color, style, sym);
}

void aq_plot_legend_at(int position, double x, double y, int ncolumn, size_t n,
                       const char *const *text, const int *color, const int *style,
                       const char *const *sym)
{
  enum { MAX_ENTRIES = AQ_PLOT_LEGEND_MAX };
  PLINT opt[MAX_ENTRIES], col[MAX_ENTRIES], sty[MAX_ENTRIES], box[MAX_ENTRIES] = {0};
  PLINT pat[MAX_ENTRIES] = {0}, tcol[MAX_ENTRIES], symn[MAX_ENTRIES];
  PLFLT w[MAX_ENTRIES], bs[MAX_ENTRIES] = {0}, blw[MAX_ENTRIES] = {0},
        ss[MAX_ENTRIES];
  const char *sy[MAX_ENTRIES], *ptext[MAX_ENTRIES];
  char padded[MAX_ENTRIES][160];
  if (n > MAX_ENTRIES)
    n = MAX_ENTRIES;
  for (size_t i = 0; i < n; i++) {
    opt[i] = 0;
    if (style[i] > 0)
      opt[i] |= PL_LEGEND_LINE;
    if (sym && sym[i] && sym[i][0])
      opt[i] |= PL_LEGEND_SYMBOL;
    if (style[i] < 0)
      opt[i] = PL_LEGEND_COLOR_BOX;
    col[i] = color[i];
    tcol[i] = AQ_PC_FG;
    sty[i] = style[i] > 0 ? style[i] : 1;
    w[i] = 1.5;
    ss[i] = 1.0;
    symn[i] = 1;
    sy[i] = sym && sym[i] ? sym[i] : "";
    /* a space's room after each text: on a PDF page scaled onto the paper
       PLplot measures the text a little narrower than cairo draws it */
    snprintf(padded[i], sizeof padded[i], "%s\u2002", text[i]); /* an en space */
    ptext[i] = padded[i];
    box[i] = color[i];
    bs[i] = 0.8;
  }
  PLFLT lw, lh;
  PLINT ncol = ncolumn > 1 ? ncolumn : 1, nrow = ((PLINT)n + ncol - 1) / ncol;
  pllegend(&lw, &lh, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX |
                         (ncol > 1 ? PL_LEGEND_ROW_MAJOR : 0),
           position, x, y, 0.06, AQ_PC_BG, AQ_PC_FG, 1, nrow, ncol, (PLINT)n, opt, 0.6, 0.7,
           2.0, 0.0, tcol, ptext, box, pat, bs,
           blw, col, sty, w, col, ss, symn, sy);
}
