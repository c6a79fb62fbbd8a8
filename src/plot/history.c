/* history.c: one run's response, three panels sharing the time axis:
 * ground acceleration (g) with +-lambda0 g of both sets, rotation of body 1
 * over the collapse rotation q_c of the hinge set moving (each set's
 * rotation to its own q_c: collapse at +-1 whichever set it is, as the
 * summary's peak_rotation_over_qc), and kinetic energy, potential energy
 * and the work done by the ground (J).  Impacts (returns to q = 0) are
 * marked on the rotation panel, the collapse across all three.  The time
 * axis ends where the run did (its collapse, or the record's end).
 *
 * The work put in is not stored as a history; it is accumulated over the
 * samples from the energy balance of docs/method.md sec. 5: over an
 * interval in which the ground acceleration a_g is constant (zero-order
 * hold of the record's samples, as the run's steps),
 *     dW = -m_T a_g dx,
 * x being the whole arch's centroid displacement.  Its last value is the
 * run's energy_in_j when the run kept one step per sample (tested). */
#include <math.h>
#include <plplot.h>
#include <stdlib.h>
#include <string.h>

#include "../units.h"
#include "plot.h"

/* The rotation and energy axes in a unit that keeps their tick labels
 * short (at most about 5 characters, clear of the axis title): the largest
 * value's unit of 1000s, from the smallest. */
typedef struct {
  double per;        /* SI units per axis unit */
  const char *title; /* axis title */
} axis_unit;

typedef struct {
  const aq_plot_run *run;
  double *w_j;          /* work in at each sample, J */
  double *imp_t_s;      /* impact times, s */
  size_t nimp;
  double *ag_t_s, *ag_g; /* ground: times, s, and g */
  double *qr;           /* rotation / q_c of the set moving, at each sample */
  int qc_sign[2];       /* the side (+1, -1) of each set's collapse line, 0: none */
  double t0_s, t1_s;    /* time axis */
  const axis_unit *e_unit, *q_unit; /* energy and rotation axes */
  int qc_shown;         /* +-q_c on the rotation axis */
} hist;

/* Below this fraction of q_c (a peak of rotation / q_c under it), the
 * rotation axis leaves the collapse lines out (named "off scale" in the
 * legend) so that the response can be seen. */
static const double QC_SHOWN_FRAC = 0.4;
/* the panels are about 620 px wide: a span a pixel keeps every extreme */
static const size_t LINE_BUCKETS = 620;

/* Axis titles (also written to the CSV, so that tests can read them). */
static const char *const AX_TIME = "time in the record (s)", *const AX_GROUND = "ground (g)";

static const axis_unit ROT_UNITS[] = {{1e-6, "rotation / q#dc#u of its set (10⁻⁶)"},
                                      {1e-3, "rotation / q#dc#u of its set (10⁻³)"},
                                      {1, "rotation / q#dc#u of its set (1)"}};
static const axis_unit E_UNITS[] = {
    {1e-3, "energy (mJ)"}, {1, "energy (J)"}, {1e3, "energy (kJ)"}, {1e6, "energy (MJ)"}};

/* The unit of units[n] in which peak (>= 0, SI) reads below `below`:
 * the largest unit that leaves peak at least 1, else the smallest. */
static const axis_unit *unit_for(const axis_unit *units, size_t n, double peak, double below)
{
  size_t k = 0;
  while (k + 1 < n && peak / units[k].per >= below)
    k++;
  return &units[k];
}

/* Ground acceleration held from sample i over [t0 + i dt, t0 + (i+1) dt). */
static double ground_at(const aq_plot_run *r, double t_s)
{
  double k = floor((t_s - r->ag_t0_s) / r->ag_dt_s);
  if (!(k >= 0) || k >= (double)r->na)
    return 0;
  return r->ag_mps2[(size_t)k];
}

static int prepare(hist *h, const aq_plot_run *r, aq_error *err)
{
  memset(h, 0, sizeof *h);
  h->run = r;
  size_t n = r->n;
  h->w_j = malloc((n ? n : 1) * sizeof *h->w_j);
  h->imp_t_s = malloc((n ? n : 1) * sizeof *h->imp_t_s);
  h->ag_t_s = malloc((r->na ? r->na : 1) * sizeof *h->ag_t_s);
  h->ag_g = malloc((r->na ? r->na : 1) * sizeof *h->ag_g);
  h->qr = malloc((n ? n : 1) * sizeof *h->qr);
  if (!h->w_j || !h->imp_t_s || !h->ag_t_s || !h->ag_g || !h->qr) {
    aq_error_set(err, AQ_ENOMEM, NULL, -1, -1, "history", "out of memory");
    return -1;
  }
  for (size_t i = 0; i < r->na; i++) {
    h->ag_t_s[i] = r->ag_t0_s + (double)i * r->ag_dt_s;
    h->ag_g[i] = r->ag_mps2[i] / AQ_G0_MPS2;
  }
  double w = 0;
  for (size_t k = 0; k < n; k++) {
    if (k > 0) {
      double tm = 0.5 * (r->t_s[k - 1] + r->t_s[k]);
      w -= r->mass_kg * ground_at(r, tm) * (r->x_m[k] - r->x_m[k - 1]); /* sec. 5 */
      if (!r->na) /* no ground in the file: no work */
        w = NAN;
      double qa = r->q_rad[k - 1], qb = r->q_rad[k];
      if (qa != 0 && (qb == 0 || (qa > 0) != (qb > 0))) /* back through q = 0 */
        h->imp_t_s[h->nimp++] =
            r->t_s[k - 1] + (r->t_s[k] - r->t_s[k - 1]) * qa / (qa - qb);
    }
    h->w_j[k] = w;
  }
  double lo, hi, e_hi = 0;
  aq_plot_range(h->w_j, n, &lo, &hi);
  e_hi = hi;
  aq_plot_range(r->ke_j, n, &lo, &hi);
  e_hi = fmax(e_hi, hi);
  aq_plot_range(r->pe_j, n, &lo, &hi);
  /* J up to 10 kJ (as before), mJ below 0.1 J, MJ above 10 MJ */
  h->e_unit = unit_for(E_UNITS, sizeof E_UNITS / sizeof E_UNITS[0], fmax(e_hi, hi), 1e4);
  if (fmax(e_hi, hi) >= 0.1 && h->e_unit->per < 1)
    h->e_unit = &E_UNITS[1];
  /* the rotation over q_c of the set moving at each sample (its hinge_set;
     a file without them: the set whose side of 0 q is on, else the
     smaller q_c), and the side of each set's collapse line */
  for (int s = 0; s < 2; s++)
    h->qc_sign[s] = r->q_sign[s] > 0 ? 1 : r->q_sign[s] < 0 ? -1 : 0;
  double qc_min = fmin(r->q_c_rad[0], r->q_c_rad[1]);
  for (size_t k = 0; k < n; k++) {
    int s = r->set ? r->set[k] : -1;
    if (s < 0 && r->q_rad[k] != 0)
      for (int j = 0; j < 2; j++)
        if (h->qc_sign[j] != 0 && (r->q_rad[k] > 0) == (h->qc_sign[j] > 0))
          s = j;
    double qc = s == 0 || s == 1 ? r->q_c_rad[s] : qc_min;
    h->qr[k] = qc > 0 ? r->q_rad[k] / qc : 0;
  }
  if (!h->qc_sign[0] && !h->qc_sign[1]) { /* not known: both sides, the smaller q_c */
    h->qc_sign[0] = -1;
    h->qc_sign[1] = 1;
  }
  /* the collapse lines (+-1) on it unless the response would be a flat
     line under them; the unit keeps the tick labels short */
  aq_plot_range(h->qr, n, &lo, &hi);
  double peak = fmax(fabs(lo), fabs(hi));
  h->qc_shown = peak == 0 || peak >= QC_SHOWN_FRAC;
  if (h->qc_shown)
    peak = fmax(peak, 1);
  h->q_unit = unit_for(ROT_UNITS, sizeof ROT_UNITS / sizeof ROT_UNITS[0], peak, 200);
  /* the time axis: the record without its zero pads, and any motion */
  h->t0_s = INFINITY;
  h->t1_s = -INFINITY;
  if (r->n_orig > 0 && r->rec_dt_s > 0) {
    h->t0_s = 0;
    h->t1_s = (double)r->n_orig * r->rec_dt_s;
  }
  for (size_t k = 0; k < n; k++)
    if (r->q_rad[k] != 0 || r->ke_j[k] != 0) {
      h->t0_s = fmin(h->t0_s, r->t_s[k]);
      h->t1_s = fmax(h->t1_s, r->t_s[k]);
    }
  if (r->collapsed == 1 && isfinite(r->collapse_time_s))
    h->t1_s = fmax(h->t1_s, r->collapse_time_s);
  /* the run ends at its last sample (its collapse, or the padded
     record's end): the axis no further, and a fiftieth more */
  if (n && r->t_s[n - 1] < h->t1_s)
    h->t1_s = r->t_s[n - 1];
  if (h->t0_s < h->t1_s)
    h->t1_s += (h->t1_s - h->t0_s) / 50;
  if (!(h->t0_s < h->t1_s)) {
    h->t0_s = n ? r->t_s[0] : 0;
    h->t1_s = n && r->t_s[n - 1] > h->t0_s ? r->t_s[n - 1] : h->t0_s + 1;
  }
  return 0;
}

static void release(hist *h)
{
  free(h->w_j);
  free(h->imp_t_s);
  free(h->ag_t_s);
  free(h->ag_g);
  free(h->qr);
}

static void hline(double t0, double t1, double y, int color, int style)
{
  PLFLT x[2] = {t0, t1}, yy[2] = {y, y};
  plcol0(color);
  pllsty(style);
  plline(2, x, yy);
  pllsty(1);
}

/* One panel: viewport [y0, y1] of the page, box, y title. */
static void panel(const hist *h, double y0, double y1, double lo, double hi,
                  int bottom, const char *ytitle)
{
  double pad = 0.06 * (hi - lo);
  plvpor(0.12, 0.68, y0, y1);
  plwind(h->t0_s, h->t1_s, lo - pad, hi + pad);
  plcol0(AQ_PC_LIGHT);
  plbox("g", 0, 0, "g", 0, 0);
  plcol0(AQ_PC_FG);
  plbox(bottom ? "bcnst" : "bcst", 0, 0, "bcnstv", 0, 0);
  plmtex("l", 5.6, 0.5, 0.5, ytitle);
  if (bottom)
    plmtex("b", 3.2, 0.5, 0.5, AX_TIME);
  if (h->run->collapsed == 1 && isfinite(h->run->collapse_time_s)) {
    PLFLT x[2] = {h->run->collapse_time_s, h->run->collapse_time_s};
    PLFLT y[2] = {lo - pad, hi + pad};
    plcol0(AQ_PC_RED);
    plwidth(2);
    plline(2, x, y);
    plwidth(1);
  }
}

static int draw(void *ctx, aq_error *err)
{
  (void)err;
  const hist *h = ctx;
  const aq_plot_run *r = h->run;
  const double gr = r->g_mps2 / AQ_G0_MPS2; /* lambda0 g in units of g0 */
  char title[1100], l0p[64], l0r[64], qcp[64], qcr[64];
  pladv(0);
  plschr(0, 0.85);
  plsyax(7, 0); /* plain numbers, no "(x10^4)" above the axis */
  const char *base = strrchr(r->record, '/');
  base = base ? base + 1 : r->record;
  /* the title on one line, or the record's name on a line of its own (the
     names whole, shortened only beyond the page's width) */
  char rest[500], rec_e[600], arch_e[300];
  double room = 0.94 * aq_plot_page_w_mm();
  aq_plot_escape(base, rec_e, sizeof rec_e);
  aq_plot_escape(r->arch, arch_e, sizeof arch_e);
  snprintf(title, sizeof title, "%s on arch %s: scale %g%s, run %s", rec_e, arch_e, r->scale,
           r->reversed ? " reversed" : "", r->key);
  plvpor(0.02, 0.98, 0.08, 0.93); /* the title centred on the page */
  if (aq_plot_text_mm(title) <= room) {
    plmtex("t", 1.2, 0.5, 0.5, title);
  } else {
    snprintf(rest, sizeof rest, "on arch : scale %g%s, run %s", r->scale,
             r->reversed ? " reversed" : "", r->key);
    aq_plot_shorten_to(r->arch, room - aq_plot_text_mm(rest), arch_e, sizeof arch_e);
    aq_plot_shorten_to(base, room, rec_e, sizeof rec_e);
    snprintf(rest, sizeof rest, "on arch %s: scale %g%s, run %s", arch_e, r->scale,
             r->reversed ? " reversed" : "", r->key);
    plmtex("t", 2.6, 0.5, 0.5, rec_e);
    plmtex("t", 1.2, 0.5, 0.5, rest);
  }
  /* ground */
  double lo, hi;
  aq_plot_range(h->ag_g, r->na, &lo, &hi);
  for (int s = 0; s < 2; s++) {
    lo = fmin(lo, -r->lambda0[s] * gr);
    hi = fmax(hi, r->lambda0[s] * gr);
  }
  panel(h, 0.67, 0.93, lo, hi, 0, AX_GROUND);
  plcol0(AQ_PC_GREY);
  if (r->na)
    aq_plot_line(r->na, h->ag_t_s, h->ag_g, LINE_BUCKETS);
  for (int s = 0; s < 2; s++)
    for (int sg = -1; sg <= 1; sg += 2)
      hline(h->t0_s, h->t1_s, sg * r->lambda0[s] * gr, s ? AQ_PC_ORANGE : AQ_PC_BLUE,
            s ? 3 : 2);
  if (!r->na) { /* in the widest band between the lines, on its own background */
    double pad = 0.06 * (hi - lo), yl[6] = {lo - pad, hi + pad, 0, 0, 0, 0};
    for (int s = 0; s < 2; s++) {
      yl[2 + 2 * s] = r->lambda0[s] * gr;
      yl[3 + 2 * s] = -r->lambda0[s] * gr;
    }
    double best = 0, ym = 0.5 * (lo + hi);
    for (int i = 0; i < 6; i++) { /* the gap above each line to the next */
      double next = INFINITY;
      for (int j = 0; j < 6; j++)
        if (yl[j] > yl[i])
          next = fmin(next, yl[j]);
      if (isfinite(next) && next - yl[i] > best) {
        best = next - yl[i];
        ym = 0.5 * (yl[i] + next);
      }
    }
    aq_plot_note(0.5 * (h->t0_s + h->t1_s), ym, "ground not in this file (written before --history stored it)");
  }
  snprintf(l0p, sizeof l0p, "±#gl#d0#u g, primary (%.3g g)", r->lambda0[0] * gr);
  snprintf(l0r, sizeof l0r, "±#gl#d0#u g, reverse (%.3g g)", r->lambda0[1] * gr);
  {
    const char *t[] = {l0p, l0r, "ground"};
    int c[] = {AQ_PC_BLUE, AQ_PC_ORANGE, AQ_PC_GREY}, st[] = {2, 3, 1};
    aq_plot_legend(PL_POSITION_OUTSIDE | PL_POSITION_RIGHT, r->na ? 3 : 2, t, c, st, NULL);
  }

  /* rotation, in the axis' unit */
  const double qper = h->q_unit->per;
  const int qc_shown = h->qc_shown;
  aq_plot_range(h->qr, r->n, &lo, &hi);
  for (int s = 0; s < 2 && qc_shown; s++) { /* each set's collapse, on its side */
    lo = fmin(lo, h->qc_sign[s] ? h->qc_sign[s] : lo);
    hi = fmax(hi, h->qc_sign[s] ? h->qc_sign[s] : hi);
  }
  panel(h, 0.38, 0.64, lo / qper, hi / qper, 0, h->q_unit->title);
  for (int s = 0; s < 2 && qc_shown; s++)
    if (h->qc_sign[s])
      hline(h->t0_s, h->t1_s, h->qc_sign[s] / qper, s ? AQ_PC_ORANGE : AQ_PC_BLUE, s ? 3 : 2);
  plcol0(AQ_PC_FG);
  PLFLT *qy = malloc((r->n ? r->n : 1) * sizeof *qy);
  if (qy) {
    for (size_t k = 0; k < r->n; k++)
      qy[k] = h->qr[k] / qper;
    aq_plot_line(r->n, r->t_s, qy, LINE_BUCKETS);
    free(qy);
  }
  if (h->nimp) {
    double *zero = calloc(h->nimp, sizeof *zero);
    if (zero) {
      plcol0(AQ_PC_GREEN);
      plschr(0, 0.6);
      plstring((PLINT)h->nimp, h->imp_t_s, zero, "◆");
      plschr(0, 0.85);
      free(zero);
    }
  }
  snprintf(qcp, sizeof qcp, "primary: q#dc#u %.3g rad", r->q_c_rad[0]);
  snprintf(qcr, sizeof qcr, "reverse: q#dc#u %.3g rad", r->q_c_rad[1]);
  {
    char imp[64];
    snprintf(imp, sizeof imp, "impact (%zu)", h->nimp);
    const char *t[] = {"rotation / q#dc#u", qcp, qcr, imp, "collapse"};
    int c[] = {AQ_PC_FG, AQ_PC_BLUE, AQ_PC_ORANGE, AQ_PC_GREEN, AQ_PC_RED};
    int st[] = {1, 2, 3, 0, 1};
    const char *sy[] = {"", "", "", "◆", ""};
    if (!qc_shown) { /* the collapse lines (1) off scale: the legend says so */
      t[1] = "(collapse: 1, off scale)";
      t[2] = qcp;
      snprintf(qcp, sizeof qcp, "q#dc#u %.3g, %.3g rad", r->q_c_rad[0], r->q_c_rad[1]);
      c[1] = c[2] = AQ_PC_FG;
      st[1] = st[2] = 0;
    }
    aq_plot_legend(PL_POSITION_OUTSIDE | PL_POSITION_RIGHT,
                   r->collapsed == 1 ? 5 : 4, t, c, st, sy);
  }

  /* energies */
  aq_plot_range(r->ke_j, r->n, &lo, &hi);
  double a, b;
  aq_plot_range(r->pe_j, r->n, &a, &b);
  lo = fmin(lo, a);
  hi = fmax(hi, b);
  aq_plot_range(h->w_j, r->n, &a, &b);
  lo = fmin(fmin(lo, a), 0);
  hi = fmax(hi, b);
  double unit = h->e_unit->per;
  panel(h, 0.09, 0.35, lo / unit, hi / unit, 1, h->e_unit->title);
  const double *e[3] = {r->pe_j, r->ke_j, h->w_j};
  const int ec[3] = {AQ_PC_BLUE, AQ_PC_RED, AQ_PC_GREEN};
  PLFLT *y = malloc((r->n ? r->n : 1) * sizeof *y);
  for (int j = 0; j < (r->na ? 3 : 2) && y; j++) {
    for (size_t k = 0; k < r->n; k++)
      y[k] = e[j][k] / unit;
    plcol0(ec[j]);
    aq_plot_line(r->n, r->t_s, y, LINE_BUCKETS);
  }
  free(y);
  {
    const char *t[] = {"kinetic", "potential", r->na ? "work in" : "(work in: no ground)"};
    int c[] = {AQ_PC_RED, AQ_PC_BLUE, r->na ? AQ_PC_GREEN : AQ_PC_FG};
    int st[] = {1, 1, r->na ? 1 : 0};
    aq_plot_legend(PL_POSITION_OUTSIDE | PL_POSITION_RIGHT, 3, t, c, st, NULL);
  }
  return 0;
}

/* Long format: series,time_s,value (the series name carries the unit). */
static aq_status write_data(const hist *h, const char *data, aq_error *err)
{
  aq_outfile tmp;
  FILE *f = aq_plot_csv_open(data, &tmp, err);
  if (!f)
    return err->status;
  const aq_plot_run *r = h->run;
  aq_plot_csv_axes(f, 4, (const char *[]){AX_TIME, AX_GROUND, h->q_unit->title,
                                          h->e_unit->title});
  fprintf(f, "series,time_s,value\n");
  for (size_t i = 0; i < r->na; i++)
    fprintf(f, "ground_accel_g,%s,%s\n", AQ_TEXT_NUM(h->ag_t_s[i]), AQ_TEXT_NUM(h->ag_g[i]));
  for (int s = 0; s < 2; s++) {
    fprintf(f, "%s_lambda0_g,nan,%s\n", s ? "reverse" : "primary",
            AQ_TEXT_NUM(r->lambda0[s] * r->g_mps2 / AQ_G0_MPS2));
    fprintf(f, "%s_q_c_rad,nan,%s\n", s ? "reverse" : "primary", AQ_TEXT_NUM(r->q_c_rad[s]));
  }
  static const char *names[] = {"rotation_rad", "rotation_over_qc", "kinetic_energy_j",
                                "potential_energy_j", "work_in_j"};
  const double *v[] = {r->q_rad, h->qr, r->ke_j, r->pe_j, h->w_j};
  for (size_t j = 0; j < (r->na ? 5 : 4); j++)
    for (size_t i = 0; i < r->n; i++)
      fprintf(f, "%s,%s,%s\n", names[j], AQ_TEXT_NUM(r->t_s[i]), AQ_TEXT_NUM(v[j][i]));
  for (size_t i = 0; i < h->nimp; i++)
    fprintf(f, "impact,%s,0\n", AQ_TEXT_NUM(h->imp_t_s[i]));
  if (r->collapsed == 1)
    fprintf(f, "collapse,%s,1\n", AQ_TEXT_NUM(r->collapse_time_s));
  return aq_plot_csv_close(&tmp, err);
}

aq_status aq_plot_history(const aq_plot_run *run, const char *target,
                          const char *data, double *draw_s, aq_error *err)
{
  hist h;
  aq_status rc = AQ_ENOMEM;
  if (prepare(&h, run, err) == 0) {
    rc = aq_plot_render(target, 1100, 850, draw, &h, draw_s, err);
    if (rc == AQ_OK && data)
      rc = write_data(&h, data, err);
  }
  release(&h);
  return rc;
}
