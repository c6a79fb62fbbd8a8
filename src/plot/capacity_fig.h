/* capacity_fig.h: the capacity figure's state and layout (capacity.c),
 * shared with its fragility panel (capacity_frag.c) and its layout
 * (capacity_layout.c); internal to src/plot.  Lengths in mm of the figure
 * from its top left (72 points an inch).  The figure borrows the capacity
 * table; frag.x and the strips' arrays are freed by aq_plot_capacity.
 */
#ifndef AQ_PLOT_CAPACITY_FIG_H
#define AQ_PLOT_CAPACITY_FIG_H

#include <stddef.h>
#include <stdio.h>

#include "plot.h"

static const char *const AX_PROB = "probability of collapse (1)";

/* axis titles of the IMs of aq_fragility_im_names */
static const char *const AX_IM[AQ_FRAGILITY_NIM] = {
    "PGA (g)", "PGV (m/s)", "PGD (m)", "Arias intensity (m/s)", "CAV (m/s)",
    "PGA / (#gl#d0#u g) (1)"};

/* the IMs' units, for the fitted median */
static const char *const IM_UNIT[AQ_FRAGILITY_NIM] = {"g", "m/s", "m", "m/s", "m/s",
                                                      "#gl#d0#u g"};

enum { NCURVE = 201 }; /* points of each CDF */

/* The fragility panel's data. */
typedef struct {
  int m;                        /* IM number */
  const aq_h5_fragility_fit *fit; /* NULL: the file holds none for the arch */
  size_t n, ncol;               /* records, collapsed among them */
  double *x;                    /* n: sorted first-collapse IMs, then the caps */
  double cx[NCURVE], cdf[3][NCURVE]; /* fit, median_lo, median_hi */
  double lo, hi;                /* x range */
} frag;

typedef struct {
  const aq_h5_capacity_table *t;
  const aq_plot_capacity_opts *o;
  const char *arch;
  size_t *row;  /* rows of this arch: one line each */
  size_t n;
  double *pga;  /* n: each line's PGA at scale 1 (g; NAN unknown) */
  int *color;   /* n: colour of each line (by record) */
  size_t *rec;  /* n: each line's record (0-based, in the file's order) */
  size_t nrec;
  int have_pol[2]; /* a normal, a reversed line among them */
  frag f;
  int logy;     /* 1: the scale axis log10 */
  double ylo, yhi, xhi; /* scale axis range (in its unit, not log); shade's top */
  char im_axis[96], im_unit[32]; /* the fragility IM's axis title and unit */
  /* the layout, mm of the figure (72 points an inch) from its top left */
  double w, h;                /* the figure */
  char title[2][300];         /* the strips' title, on one or two lines */
  int title_lines;
  double title_y;             /* its first line's centre */
  double note_y;              /* a file without scan points: the note's centre */
  double head_y;              /* the first collapses' column head */
  double sx0, sx1, sy0, sy1;  /* the strips */
  char (*label)[1100];        /* each strip's label (record name, polarity) */
  char (*fc)[64];             /* each strip's first collapse */
  double key_y;               /* the keys' top */
  double marks_x;             /* the marks' legend: its left edge */
  char ftitle[2][400];        /* the fragility's title */
  int ftitle_lines;
  double ftitle_y;
  double fx0, fx1, fy0, fy1;  /* the fragility's frame */
  double leg_y, leg_colw;     /* its legend: top, a column's width */
  int leg_cols;
} cap;

enum { D_MOVE = 0, D_FIRST = 1, D_PGA = 2, D_SMAX = 4, I_START = 2, I_COUNT = 3 };

enum { ROW_PX = 26, RECORD_GAP_PX = 8 }; /* a strip, the space between records */

/* The layout's sizes (mm of the figure, 72 points an inch): the figure is
 * 1000 points wide, as tall as its strips make it; every text is measured
 * (aq_plot_text_em) and given room, so nothing runs off the figure or into
 * another text. */
static const double PT_MM = 25.4 / 72;

static const double TXT_MM = 3.7;     /* character height: labels, ticks, axes */

static const double TITLE_MM = 3.9;   /* titles */

static const double KEY_MM = 3.4;     /* the keys' texts */

static const double MARGIN_MM = 6;    /* the figure's edge */

static const double PAD_MM = 4;       /* between bands */

static const double FRAG_H_MM = 100;  /* the fragility's frame */

static const double SAMPLE_MM = 9;    /* a key's sample (line, box, symbol) */

static const double LABEL_SHARE = 0.4; /* at most this much of the width for labels */

/* Width of s at character height ht_mm, mm. */
double aq_plot_cap_width_mm(const char *s, double ht_mm);

/* A text line's pitch at character height ht_mm: the font's line and a
 * sixth more. */
double aq_plot_cap_pitch_mm(double ht_mm);

const char *aq_plot_cap_base(const char *p);

/* The viewport of the figure's rectangle x0..x1, y0..y1 (mm from its top
 * left). */
void aq_plot_cap_vp_mm(const cap *c, double x0, double x1, double y0, double y1);

/* The whole figure as the world, in mm from its top left: where the
 * titles and keys are written with plptex (at their centre line). */
void aq_plot_cap_page_mm(const cap *c);

/* A key's entry at (x, y) (mm, its centre line): its sample, a line of
 * style (>= 1), a box of colour (style -1) or a symbol, then its text. */
void aq_plot_cap_key_entry(double x, double y, int color, int style, const char *sym,
                           const char *text);

/* Line k's y of scale s (scale, or PGA in g), and on the drawn axis. */
double aq_plot_cap_y_of(const cap *c, size_t k, double s);

/* Strip k's row: its top edge in rows from the top (records apart by a gap). */
double aq_plot_cap_row_top(const cap *c, size_t k);

/* The data of the fit of IM m over the records of c (as
 * aq_fragility_fit_records), the fit, the CDF curves. */
int aq_plot_cap_frag_build(cap *c, int m);

/* The entries the fragility's key shows: only what is drawn. */
int aq_plot_cap_frag_keys(const cap *c, const char **tx, int *col, int *st, const char **sym);

void aq_plot_cap_draw_fragility(const cap *c);

/* The fragility panel's data after the intervals' (a second header). */
void aq_plot_cap_frag_csv(FILE *f, const cap *c);

/* ---- capacity_layout.c */

/* The fragility IM m's axis title and unit: the six by table, a spectral
 * measure from its name (sa_0.2s_g: Sa(0.2 s); sa_avg_0.1_1s_g: Sa_avg
 * over 0.1 to 1 s; both in g). */
void aq_plot_cap_im_titles(cap *c, int m);

/* The layout (see the sizes above): every text measured before the figure
 * is drawn, its height then known.  -1 when out of memory. */
int aq_plot_cap_plan(cap *c);

#endif
