/* capacity_layout.c: the layout of the capacity figure (capacity.c,
 * capacity_fig.h): every text measured before the figure is drawn, the
 * titles split over two lines where one would not hold them, the record
 * names shortened to the labels' share of the width, and the bands placed
 * so that nothing runs off the figure or into another text.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "capacity_fig.h"
#include "plot.h"

/* The fragility IM m's axis title and unit: the six by table, a spectral
 * measure from its name (sa_0.2s_g: Sa(0.2 s); sa_avg_0.1_1s_g: Sa_avg
 * over 0.1 to 1 s; both in g). */
void aq_plot_cap_im_titles(cap *c, int m)
{
  const char *name = c->t->im_name[m];
  double t1, t2;
  if (m < AQ_FRAGILITY_NIM) {
    snprintf(c->im_axis, sizeof c->im_axis, "%s", AX_IM[m]);
    snprintf(c->im_unit, sizeof c->im_unit, "%s", IM_UNIT[m]);
  } else if (sscanf(name, "sa_avg_%lf_%lfs_g", &t1, &t2) == 2) {
    snprintf(c->im_axis, sizeof c->im_axis, "Sa#davg#u over %g–%g s (g)", t1, t2);
    snprintf(c->im_unit, sizeof c->im_unit, "g");
  } else if (sscanf(name, "sa_%lfs_g", &t1) == 1) {
    snprintf(c->im_axis, sizeof c->im_axis, "Sa(%g s) (g)", t1);
    snprintf(c->im_unit, sizeof c->im_unit, "g");
  } else {
    aq_plot_escape(name, c->im_axis, sizeof c->im_axis);
    c->im_unit[0] = '\0';
  }
}

/* Split s at its last ": " that leaves a first part within w mm at
 * character height ht into a[0], a[1] (the part after the colon); *lines 1
 * when s fits whole or cannot be split so. */
static void split_title(const char *s, double w, double ht, char (*a)[400], int *lines)
{
  snprintf(a[0], sizeof a[0], "%s", s);
  a[1][0] = '\0';
  *lines = 1;
  if (aq_plot_cap_width_mm(s, ht) <= w)
    return;
  const char *cut = NULL;
  for (const char *p = strstr(s, ": "); p; p = strstr(p + 1, ": "))
    cut = p;
  if (!cut)
    return;
  snprintf(a[0], sizeof a[0], "%.*s", (int)(cut + 1 - s), s);
  snprintf(a[1], sizeof a[1], "%s", cut + 2);
  *lines = 2;
}

/* The layout (see the sizes above): every text measured before the figure
 * is drawn, its height then known.  -1 when out of memory. */
int aq_plot_cap_plan(cap *c)
{
  const aq_h5_capacity_table *t = c->t;
  c->w = 1000 * PT_MM;
  c->label = calloc(c->n ? c->n : 1, sizeof *c->label);
  c->fc = calloc(c->n ? c->n : 1, sizeof *c->fc);
  const char **names = malloc((c->nrec ? c->nrec : 1) * sizeof *names);
  char(*short_names)[1024] = malloc((c->nrec ? c->nrec : 1) * sizeof *short_names);
  if (!c->label || !c->fc || !names || !short_names) {
    free(names);
    free(short_names);
    return -1;
  }
  /* the labels: each record's name, shortened as much as the label share
     needs, the names of one figure kept distinct */
  size_t longest = 1;
  for (size_t k = 0; k < c->n; k++)
    if (k == 0 || c->rec[k] != c->rec[k - 1]) {
      names[c->rec[k]] = aq_plot_cap_base(t->row[c->row[k]].record);
      size_t len = strlen(names[c->rec[k]]);
      longest = len > longest ? len : longest;
    }
  double pol_w = aq_plot_cap_width_mm("  reversed", TXT_MM), room = LABEL_SHARE * c->w - pol_w;
  for (size_t keep = longest + 1; keep-- > 5;) {
    aq_plot_ellipsize_set(names, c->nrec, keep, short_names[0], sizeof short_names[0]);
    double widest = 0;
    for (size_t r = 0; r < c->nrec; r++)
      widest = fmax(widest, aq_plot_cap_width_mm(short_names[r], TXT_MM));
    if (widest <= room)
      break;
  }
  double label_w = 0, fc_w = aq_plot_cap_width_mm("first collapse", TXT_MM);
  for (size_t k = 0; k < c->n; k++) {
    const aq_h5_capacity_row *r = &t->row[c->row[k]];
    int first = k == 0 || c->rec[k] != c->rec[k - 1];
    snprintf(c->label[k], sizeof c->label[k], "%s  %s", first ? short_names[c->rec[k]] : "",
             r->polarity);
    label_w = fmax(label_w, aq_plot_cap_width_mm(c->label[k], TXT_MM));
    double f = r->d[D_FIRST];
    if (strcmp(r->status, "ok") != 0 && strncmp(r->status, "collapse", 8) != 0 && isnan(f) &&
        r->point_count == 0)
      snprintf(c->fc[k], sizeof c->fc[k], "%s", r->status);
    else {
      /* a marked row says so beside its verdict (docs/capacity.md, "Marks") */
      const char *mk = !strcmp(r->status, "slides") || !strcmp(r->status, "beyond") ||
                               !strcmp(r->status, "slides+beyond")
                           ? r->status
                           : "";
      if (isfinite(f))
        snprintf(c->fc[k], sizeof c->fc[k], "%.3g%s%s%s", aq_plot_cap_y_of(c, k, f),
                 r->i[0] > 0 ? "  R" : "", mk[0] ? "  " : "", mk);
      else
        snprintf(c->fc[k], sizeof c->fc[k], "none%s%s", mk[0] ? "  " : "", mk);
    }
    fc_w = fmax(fc_w, aq_plot_cap_width_mm(c->fc[k], TXT_MM));
  }
  free(names);
  free(short_names);
  /* across: labels, strips, first collapses */
  double gap = 0.8 * TXT_MM, w = c->w, y;
  c->sx0 = MARGIN_MM + label_w + gap;
  c->sx1 = w - MARGIN_MM - fc_w - gap;
  /* down: the title, the column's head, the strips, their axis */
  char title[300];
  snprintf(title, sizeof title, "arch %.200s: the verdict of each scanned run", c->arch);
  char lines[2][400];
  split_title(title, w - 2 * MARGIN_MM, TITLE_MM, lines, &c->title_lines);
  for (int i = 0; i < 2; i++)
    snprintf(c->title[i], sizeof c->title[i], "%.299s", lines[i]);
  double lt = aq_plot_cap_pitch_mm(TITLE_MM), lp = aq_plot_cap_pitch_mm(TXT_MM), lk = aq_plot_cap_pitch_mm(KEY_MM);
  y = MARGIN_MM;
  c->title_y = y + lt / 2;
  y += c->title_lines * lt;
  if (!t->have_points) {
    c->note_y = y + lk / 2;
    y += lk;
  }
  c->head_y = y + lp / 2;
  y += lp;
  double nrows = c->n ? aq_plot_cap_row_top(c, c->n - 1) + 1 : 1;
  c->sy0 = y;
  c->sy1 = y += nrows * ROW_PX * PT_MM;
  /* the axis' tick labels and title (3 character heights below it) */
  y += 3.0 * TXT_MM + 0.6 * lp + PAD_MM;
  /* the keys: the shade's bar (16 points), its labels and title (3.2
     character heights below it); the marks, four lines */
  c->key_y = y;
  c->marks_x = w / 2 + 2 * MARGIN_MM;
  double marks_w = SAMPLE_MM + 2 + aq_plot_cap_width_mm("blank: below the scale that moves it", KEY_MM);
  if (c->marks_x + marks_w > w - MARGIN_MM)
    c->marks_x = w - MARGIN_MM - marks_w;
  y += fmax(16 * PT_MM + 3.2 * TXT_MM + 0.6 * lp, 4 * lk) + 2 * PAD_MM;
  /* the fragility: its title, frame, axis and key */
  const frag *f = &c->f;
  const aq_h5_fragility_fit *q = f->fit;
  char ftitle[400], med[48] = "", mk[48] = "";
  if (q && q->marked > 0) /* the fit rests on runs the four-hinge models do not describe */
    snprintf(mk, sizeof mk, ", %lld marked", (long long)q->marked);
  if (q && isfinite(q->median) && q->beta > 0) {
    snprintf(med, sizeof med, "%.3g", q->median);
    snprintf(ftitle, sizeof ftitle,
             "fragility of arch %.100s: median %s %s, #gb %.3g (%zu records, %zu censored%s)",
             c->arch, med, c->im_unit, q->beta, f->n, f->n - f->ncol, mk);
  } else
    snprintf(ftitle, sizeof ftitle, "fragility of arch %.100s: %s (%zu records, %zu censored%s)",
             c->arch, q ? "no fit, < 2 collapse values" : "no fit in the file", f->n,
             f->n - f->ncol, mk);
  split_title(ftitle, w - 2 * MARGIN_MM, TITLE_MM, c->ftitle, &c->ftitle_lines);
  c->ftitle_y = y + lt / 2;
  y += c->ftitle_lines * lt + 0.5 * lp;
  c->fx0 = MARGIN_MM + 4.0 * TXT_MM + 0.6 * lp;
  c->fx1 = w - MARGIN_MM - 2 * TXT_MM; /* room for half of the last tick's label */
  c->fy0 = y;
  c->fy1 = y += FRAG_H_MM;
  y += 3.0 * TXT_MM + 0.6 * lp + PAD_MM;
  const char *tx[4], *sym[4];
  int col[4], st[4], k = aq_plot_cap_frag_keys(c, tx, col, st, sym);
  double entry = 0;
  for (int i = 0; i < k; i++)
    entry = fmax(entry, SAMPLE_MM + 2 + aq_plot_cap_width_mm(tx[i], KEY_MM) + 2 * MARGIN_MM);
  c->leg_cols = k ? k : 1;
  while (c->leg_cols > 1 && c->fx0 + c->leg_cols * entry > w - MARGIN_MM)
    c->leg_cols--;
  c->leg_colw = entry;
  c->leg_y = y;
  y += (k + c->leg_cols - 1) / c->leg_cols * lk + MARGIN_MM;
  c->h = ceil(y / PT_MM) * PT_MM; /* whole points */
  return 0;
}
