/* suite.c: a record x arch map of the verdicts of a results file, for
 * screening at a glance: each cell is the worst run of that record and
 * arch over scales and polarities: a collapse, or the peak rotation over
 * the collapse rotation q_c of its set (0 never moved, 1 collapse), and
 * under it the marks of its runs: "slides" (some run's friction demand
 * passed the given friction), "beyond" (with free hinges, some run's thrust
 * left a joint's section): where the four-hinge verdict stops holding
 * (docs/demand.md). */
#include <math.h>
#include <plplot.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

/* the map's left edge: room for the longest name, within these */
static const double VP_LEFT_MIN = 0.2, VP_LEFT_MAX = 0.45;
/* a cell's label, "collapse", with room either side (aq_plot_chars_fit
   counts a file name's wider characters); the text's scale no smaller */
enum { CELL_CHARS = 7 };
static const double SCALE_MIN = 0.45;
static const char *const AX_KEY = "peak rotation / q#dc#u (1)";

typedef struct {
  const char *source;
  size_t nrec, narch;
  const char **rec, **arch; /* names, first appearance order */
  double *v;                /* nrec x narch: peak/q_c, 1 + collapse, NaN failed or none */
  int *coll;                /* nrec x narch: 1 some run collapsed */
  int *mark;                /* nrec x narch: 1 some run slides, | 2 some run beyond */
} map;

/* a run's marks (docs/tsv.md, status): 1 slides, 2 beyond */
static int run_marks(const aq_summary *s)
{
  if (aq_summary_failed(s->status))
    return 0;
  return (strstr(s->status, "slides") != NULL) | (strstr(s->status, "beyond") != NULL) << 1;
}

static size_t index_of(const char **names, size_t *n, const char *s)
{
  for (size_t i = 0; i < *n; i++)
    if (strcmp(names[i], s) == 0)
      return i;
  names[*n] = s;
  return (*n)++;
}

static const char *base(const char *p)
{
  const char *b = strrchr(p, '/');
  return b ? b + 1 : p;
}

static int draw(void *ctx, aq_error *err)
{
  (void)err;
  const map *m = ctx;
  pladv(0);
  /* the names' margin: the longest name, or as much as fits */
  size_t longest = 1;
  for (size_t i = 0; i < m->nrec; i++) {
    size_t len = strlen(base(m->rec[i]));
    longest = len > longest ? len : longest;
  }
  /* text small enough that a cell holds its label ("collapse"): PLplot's
     text grows with the figure's height, which grows with the records,
     while the cells' width is shared by the arches */
  double scale = 0.85, left = VP_LEFT_MIN;
  size_t cell = 0;
  for (int pass = 0; pass < 3; pass++) {
    plschr(0, scale);
    double per_char = 0.8 / (double)aq_plot_chars_fit(0.8); /* page fraction */
    left = fmin(fmax((double)(longest + 3) * per_char, VP_LEFT_MIN), VP_LEFT_MAX);
    cell = aq_plot_chars_fit((0.83 - left) / (double)m->narch);
    if (cell >= CELL_CHARS || scale <= SCALE_MIN)
      break;
    scale = fmax(scale * (double)cell / CELL_CHARS, SCALE_MIN);
  }
  int tight = cell < CELL_CHARS; /* even the smallest text: short labels */
  double text_scale = scale;
  int any_mark = 0;
  for (size_t k = 0; k < m->nrec * m->narch; k++)
    any_mark |= m->mark[k];
  double bottom = any_mark ? 0.2 : 0.14; /* room for the marks' key */
  plvpor(left, 0.83, bottom, 0.9);
  plwind(0, (double)m->narch, (double)m->nrec, 0);
  /* white (never moved) through yellow and orange to brown (about to
   * collapse); collapse itself is red, outside the scale */
  PLFLT cpos[4] = {0, 0.1, 0.5, 1}, rr[4] = {1, 1, 0.95, 0.55};
  PLFLT gg[4] = {1, 0.93, 0.6, 0.3}, bb[4] = {1, 0.6, 0.2, 0.1};
  plscmap1l(1, 4, cpos, rr, gg, bb, NULL);
  for (size_t i = 0; i < m->nrec; i++)
    for (size_t j = 0; j < m->narch; j++) {
      double v = m->v[i * m->narch + j];
      PLFLT x[4] = {j, j + 1, j + 1, j}, y[4] = {i, i, i + 1, i + 1};
      char lab[32];
      if (m->coll[i * m->narch + j]) {
        plcol0(AQ_PC_RED);
        snprintf(lab, sizeof lab, "%s", tight ? "coll." : "collapse");
      } else if (isnan(v)) {
        plcol0(AQ_PC_LIGHT);
        snprintf(lab, sizeof lab, "%s", tight ? "fail" : "failed");
      } else {
        plcol1(fmin(fmax(v, 0), 1));
        snprintf(lab, sizeof lab, tight ? "%.2f" : "%.3f", v);
      }
      plfill(4, x, y);
      plcol0(m->coll[i * m->narch + j] ? AQ_PC_BG : AQ_PC_FG);
      int mk = m->mark[i * m->narch + j];
      plptex(j + 0.5, i + (mk ? 0.42 : 0.5), 1, 0, 0.5, lab);
      if (mk) { /* the marks under the label, smaller */
        static const char *const full[4] = {"", "slides", "beyond", "slides beyond"};
        static const char *const brief[4] = {"", "s", "b", "s b"};
        plschr(0, text_scale * 0.75);
        plptex(j + 0.5, i + 0.8, 1, 0, 0.5, tight || mk == 3 ? brief[mk] : full[mk]);
        plschr(0, text_scale);
      }
    }
  plcol0(AQ_PC_FG);
  plbox("bc", 1, 0, "bc", 1, 0);
  /* a name too long for the margin keeps its start and end (the full
     name is in --data) */
  size_t fit = aq_plot_chars_fit(left - 0.01);
  fit = fit > 2 ? fit - 2 : 1; /* the 0.8 characters between name and map */
  enum { NAME = 1024 };
  size_t nn = m->nrec > m->narch ? m->nrec : m->narch;
  const char **names = malloc((nn ? nn : 1) * sizeof *names);
  char *short_names = malloc((nn ? nn : 1) * NAME);
  if (!names || !short_names) {
    free(names);
    free(short_names);
    return aq_error_set(err, AQ_ENOMEM, m->source, -1, -1, NULL, "out of memory"), -1;
  }
  for (size_t i = 0; i < m->nrec; i++) /* shortened alike, kept distinct */
    names[i] = base(m->rec[i]);
  aq_plot_ellipsize_set(names, m->nrec, fit, short_names, NAME);
  for (size_t i = 0; i < m->nrec; i++)
    plmtex("lv", 0.8, 1 - (i + 0.5) / (double)m->nrec, 1, short_names + i * NAME);
  /* the arches' names over their columns; when one is too long for its
     column, every other name a line higher, each with two columns' room */
  double col = (0.83 - left) / (double)m->narch;
  size_t afit = aq_plot_chars_fit(col);
  int stagger = 0;
  for (size_t j = 0; j < m->narch; j++)
    stagger |= m->narch > 1 && strlen(m->arch[j]) > afit;
  if (stagger)
    afit = aq_plot_chars_fit(2 * col) - 1;
  aq_plot_ellipsize_set(m->arch, m->narch, afit, short_names, NAME);
  for (size_t j = 0; j < m->narch; j++)
    plmtex("t", stagger && j % 2 ? 2.0 : 0.8, (j + 0.5) / (double)m->narch, 0.5,
           short_names + j * NAME);
  free(names);
  free(short_names);
  /* the key's title, beside its labels (outside the map by the key's
     offset and width, 0.045 of the page, and its labels) */
  double key_chars = 0.85 * (double)aq_plot_chars_fit(0.045);
  plmtex("r", key_chars + 4.2, 0.5, 0.5, AX_KEY);
  char t[1100], src[600];
  aq_plot_shorten_to(base(m->source),
                     0.94 * aq_plot_page_w_mm() -
                         aq_plot_text_mm(": records (rows) against arches (columns)"),
                     src, sizeof src);
  snprintf(t, sizeof t, "%s: records (rows) against arches (columns)", src);
  plvpor(0.02, 0.98, bottom, 0.9); /* the caption centred on the page */
  plmtex("b", 1.6, 0.5, 0.5, t);
  plmtex("b", 3.1, 0.5, 0.5, "the worst run over scales and polarities; red: collapse");
  if (any_mark) { /* the marks' key, only when a cell holds one */
    plmtex("b", 4.6, 0.5, 0.5,
           "slides (s): a run's friction demand passed #gm;  beyond (b): its thrust left a "
           "joint's section");
    plmtex("b", 6.1, 0.5, 0.5,
           "the four-hinge verdict holds until then: follow such runs with --model blocks");
  }
  plvpor(left, 0.83, bottom, 0.9);
  /* the colour key */
  PLFLT w, hgt, vals[11];
  for (int k = 0; k <= 10; k++)
    vals[k] = 0.1 * k;
  const PLFLT *vv[1] = {vals};
  PLINT nv[1] = {11}, lopt[1] = {PL_COLORBAR_LABEL_RIGHT}, sub[1] = {0};
  PLFLT ticks[1] = {0.2};
  const char *labels[1] = {""}; /* drawn above, clear of the tick labels */
  const char *axis[1] = {"bcvtm"};
  plcolorbar(&w, &hgt, PL_COLORBAR_SHADE | PL_COLORBAR_SHADE_LABEL,
             PL_POSITION_RIGHT | PL_POSITION_OUTSIDE, 0.02, 0, 0.025, 0.8, AQ_PC_BG,
             AQ_PC_FG, 1, 0, 0, 0, 0, 1, lopt, labels, 1, axis, ticks, sub, nv, vv);
  return 0;
}

aq_status aq_plot_suite(const aq_h5_run *runs, size_t n, const char *source,
                        const char *target, const char *data, double *draw_s,
                        aq_error *err)
{
  if (n == 0)
    return aq_error_set(err, AQ_EFORMAT, source, -1, -1, "/runs",
                        "expected at least one run, got none");
  map m = {source, 0, 0, NULL, NULL, NULL, NULL, NULL};
  m.rec = malloc(n * sizeof *m.rec);
  m.arch = malloc(n * sizeof *m.arch);
  aq_status rc = AQ_ENOMEM;
  if (m.rec && m.arch)
    for (size_t k = 0; k < n; k++) {
      index_of(m.rec, &m.nrec, runs[k].s.record);
      index_of(m.arch, &m.narch, runs[k].s.arch);
    }
  m.v = malloc((m.nrec * m.narch + 1) * sizeof *m.v);
  m.coll = calloc(m.nrec * m.narch + 1, sizeof *m.coll);
  m.mark = calloc(m.nrec * m.narch + 1, sizeof *m.mark);
  if (!m.rec || !m.arch || !m.v || !m.coll || !m.mark) {
    aq_error_set(err, AQ_ENOMEM, source, -1, -1, NULL, "out of memory");
    goto out;
  }
  for (size_t k = 0; k < m.nrec * m.narch; k++)
    m.v[k] = NAN;
  for (size_t k = 0; k < n; k++) {
    size_t nr = m.nrec, na = m.narch;
    size_t i = index_of(m.rec, &nr, runs[k].s.record), j = index_of(m.arch, &na, runs[k].s.arch);
    size_t c = i * m.narch + j;
    if (runs[k].s.collapsed == 1)
      m.coll[c] = 1;
    m.mark[c] |= run_marks(&runs[k].s);
    if (runs[k].s.collapsed >= 0 && !(m.v[c] >= runs[k].s.peak_rotation_over_qc))
      m.v[c] = runs[k].s.peak_rotation_over_qc;
  }
  /* rows of 0.45 in. at most, at least 5.5 in. high */
  int h = 230 + 48 * (int)m.nrec, w = 1000;
  rc = aq_plot_render(target, w, h < 560 ? 560 : h, draw, &m, draw_s, err);
  if (rc == AQ_OK && data) {
    aq_outfile tmp;
    FILE *f = aq_plot_csv_open(data, &tmp, err);
    if (!f) {
      rc = err->status;
      goto out;
    }
    aq_plot_csv_axes(f, 1, (const char *[]){AX_KEY});
    fprintf(f, "record,arch,collapsed,peak_rotation_over_qc,slides,beyond\n");
    for (size_t i = 0; i < m.nrec; i++)
      for (size_t j = 0; j < m.narch; j++)
      {
        aq_plot_csv_text(f, m.rec[i]);
        aq_plot_csv_text(f, m.arch[j]);
        int mk = m.mark[i * m.narch + j];
        fprintf(f, "%d,%s,%d,%d\n", m.coll[i * m.narch + j], AQ_TEXT_NUM(m.v[i * m.narch + j]),
                mk & 1, mk >> 1);
      }
    rc = aq_plot_csv_close(&tmp, err);
  }
out:
  free(m.rec);
  free(m.arch);
  free(m.v);
  free(m.coll);
  free(m.mark);
  return rc;
}
